//! Every step's row, for the clients that take them all (the Foxglove
//! channels: docs/VIEW.md): while any such client is connected
//! ([`super::live::Shared::row_readers`]) the loop copies each step's row
//! into a ring of [`ROW_FEED_CAPACITY`] rows, sized
//! once, and each client reads the rows it has not yet had. A client that
//! falls behind by more than the ring misses the oldest ones (it is told
//! how many), and the loop never waits for it.

/// Rows the ring holds: half a second at the default 1 kHz.
pub const ROW_FEED_CAPACITY: usize = 512;

/// The last [`ROW_FEED_CAPACITY`] rows, with a count of every row ever
/// pushed.
#[derive(Debug)]
pub struct RowFeed {
    columns: usize,
    rows: Vec<f64>,
    pushed: u64,
    /// The count at the last reset: rows before it are not read.
    start: u64,
}

/// What a reader got: the rows it had not had, and how many it missed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Read {
    /// Rows copied out.
    pub rows: usize,
    /// Rows that were overwritten before this reader read them.
    pub missed: u64,
}

impl RowFeed {
    /// A ring for rows of `columns` values.
    pub fn new(columns: usize) -> Self {
        RowFeed {
            columns,
            rows: vec![0.0; columns * ROW_FEED_CAPACITY],
            pushed: 0,
            start: 0,
        }
    }

    /// Values a row.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// The count of rows pushed so far: where a new reader starts.
    pub fn pushed(&self) -> u64 {
        self.pushed
    }

    /// Copy in one row (its first `columns` values). Allocates nothing.
    pub fn push(&mut self, row: &[f64]) {
        let k = (self.pushed % ROW_FEED_CAPACITY as u64) as usize * self.columns;
        self.rows[k..k + self.columns].copy_from_slice(&row[..self.columns]);
        self.pushed += 1;
    }

    /// Forget every row (a reset: the rows before it are another run's).
    pub fn clear(&mut self) {
        self.start = self.pushed;
    }

    /// The rows pushed after the first `*seen` (and since the last
    /// [`RowFeed::clear`]), appended to `out` in order, at most
    /// [`ROW_FEED_CAPACITY`]; `*seen` moves past them.
    pub fn read(&self, seen: &mut u64, out: &mut Vec<f64>) -> Read {
        let seen_from = (*seen).max(self.start);
        let oldest = self.pushed.saturating_sub(ROW_FEED_CAPACITY as u64);
        let missed = oldest.saturating_sub(seen_from);
        let from = seen_from.max(oldest);
        for i in from..self.pushed {
            let k = (i % ROW_FEED_CAPACITY as u64) as usize * self.columns;
            out.extend_from_slice(&self.rows[k..k + self.columns]);
        }
        let rows = (self.pushed - from) as usize;
        *seen = self.pushed;
        Read { rows, missed }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reader_gets_every_row_once_in_order_and_counts_what_it_missed() {
        let mut feed = RowFeed::new(2);
        let mut seen = feed.pushed();
        for i in 0..10 {
            feed.push(&[i as f64, -(i as f64)]);
        }
        let mut out = Vec::new();
        assert_eq!(
            feed.read(&mut seen, &mut out),
            Read {
                rows: 10,
                missed: 0
            }
        );
        assert_eq!(out[..4], [0.0, -0.0, 1.0, -1.0]);
        out.clear();
        assert_eq!(feed.read(&mut seen, &mut out), Read { rows: 0, missed: 0 });
        // Behind by more than the ring: the oldest are gone, and counted.
        let n = ROW_FEED_CAPACITY as u64 + 30;
        for i in 0..n {
            feed.push(&[(10 + i) as f64, 0.0]);
        }
        let got = feed.read(&mut seen, &mut out);
        assert_eq!(
            got,
            Read {
                rows: ROW_FEED_CAPACITY,
                missed: 30
            }
        );
        assert_eq!(out[0], 40.0);
        assert_eq!(out[out.len() - 2], (10 + n - 1) as f64);
        // After a reset the reader gets the rows since, not those before.
        feed.push(&[5.0, 5.0]);
        feed.clear();
        feed.push(&[7.0, 7.0]);
        out.clear();
        assert_eq!(feed.read(&mut seen, &mut out), Read { rows: 1, missed: 0 });
        assert_eq!(out, [7.0, 7.0]);
    }
}
