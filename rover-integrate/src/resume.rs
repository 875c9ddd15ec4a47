//! Whether an `advance` call continues where the previous one stopped.

/// The time and state an adaptive integrator left behind. Its history (FSAL derivative,
/// BDF differences) is reused only if the next call starts from exactly these values and
/// no [`restart`](super::Integrator::restart) came in between.
#[derive(Debug, Clone)]
pub(crate) struct Resume {
    t: f64,
    y: Vec<f64>,
    valid: bool,
}

impl Resume {
    /// Room for a state of dimension `dim`; nothing recorded yet.
    pub(crate) fn new(dim: usize) -> Self {
        Self {
            t: f64::NAN,
            y: vec![0.0; dim],
            valid: false,
        }
    }

    /// True if `(t, y)` is bit for bit what was recorded last, and nothing invalidated it.
    pub(crate) fn matches(&self, t: f64, y: &[f64]) -> bool {
        self.valid
            && t.to_bits() == self.t.to_bits()
            && self
                .y
                .iter()
                .zip(y)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// Records where this call stopped.
    pub(crate) fn record(&mut self, t: f64, y: &[f64]) {
        self.t = t;
        self.y.copy_from_slice(y);
        self.valid = true;
    }

    /// Forgets the record: the next call starts afresh.
    pub(crate) fn invalidate(&mut self) {
        self.valid = false;
    }
}
