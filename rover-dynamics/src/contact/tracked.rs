//! Contact by tracking the contact centre from step to step (MODEL.md §6,
//! our form of the paper's eq. 35, whose extracted text is garbled).
//!
//! From the previous rim angle β* of H, a few secant steps on dh/dβ = 0 (the
//! slope from the terrain's gradient) reach the deepest rim point; A and B
//! are then found by marching outwards from it and refining with the
//! meridional crossing search. One patch per wheel; the meridional search is
//! the fallback when there is no previous contact or the iteration fails,
//! and the search itself on a plane (flat ground, a slope), where it cuts
//! the rim in closed form.

use crate::height_field::{HeightField, OffMap};

#[cfg(test)]
use super::math;
use super::meridional::{MeridionalContact, clearance, clearance_slope, crossing};
use super::patch::{Contact, RimAngle, RimFrame};

/// March step of the crossing search \[rad\] (2°).
const MARCH: f64 = 2.0 * core::f64::consts::PI / 180.0;
/// Secant iterations on dh/dβ = 0.
const NEWTON_STEPS: usize = 8;

/// The tracking search; holds the previous contact angle of one wheel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TrackedContact {
    /// The fallback search (and its sampling).
    pub fallback: MeridionalContact,
    previous: Option<f64>,
}

impl TrackedContact {
    /// A tracker with no previous contact.
    pub fn new(fallback: MeridionalContact) -> Self {
        Self {
            fallback,
            previous: None,
        }
    }

    /// The patch of one wheel (see [`MeridionalContact::find`]).
    pub fn find<H: HeightField + ?Sized>(
        &mut self,
        terrain: &H,
        centre: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    ) -> Result<Contact, OffMap> {
        let mut contact = Contact::default();
        self.find_into(terrain, centre, axis, radius, &mut contact)?;
        Ok(contact)
    }

    /// [`TrackedContact::find`] written into `out`, for a caller that keeps
    /// its contacts (no copies of the patches on the way back: they were a
    /// quarter of the tracked right-hand side on flat ground, callgrind).
    /// On `Err`, `out` holds what was found before the failure and the
    /// previous contact angle is kept.
    pub fn find_into<H: HeightField + ?Sized>(
        &mut self,
        terrain: &H,
        centre: [f64; 3],
        axis: [f64; 3],
        radius: f64,
        out: &mut Contact,
    ) -> Result<(), OffMap> {
        // On a plane the rim's run below the ground is one arc that the
        // meridional search cuts in closed form, exactly and at a third of
        // the cost of tracking it: nothing to track.
        let on_plane = terrain.plane().is_some();
        let tracked = match (self.previous, RimFrame::new(centre, axis, radius)) {
            (Some(b0), Some(frame)) if !on_plane => self.track(terrain, &frame, b0, out)?,
            _ => false,
        };
        if !tracked {
            self.fallback
                .find_into(terrain, centre, axis, radius, out)?;
            // Keep the deepest patch only: tracking follows one patch.
            if out.count > 1 {
                let deepest = out
                    .patches()
                    .iter()
                    .max_by(|a, b| a.deflection.total_cmp(&b.deflection))
                    .copied();
                if let Some(p) = deepest {
                    out.patches[0] = p;
                }
                out.count = 1;
            }
        }
        self.previous = (out.count > 0).then(|| out.patches[0].angle);
        Ok(())
    }

    /// Tracks from `b0`; writes the one patch into `out` and returns true,
    /// or returns false (and leaves `out` alone) when the iteration does
    /// not reach a point below the ground.
    fn track<H: HeightField + ?Sized>(
        &self,
        terrain: &H,
        frame: &RimFrame,
        b0: f64,
        out: &mut Contact,
    ) -> Result<bool, OffMap> {
        let half = core::f64::consts::FRAC_PI_2;
        let tol = self.fallback.sampling.tolerance;
        let slope = |b: f64| clearance_slope(terrain, frame, RimAngle::new(b)).map(|(_, g)| g);
        // Secant on g(β) = dh/dβ.
        let (mut b_prev, mut b) = (b0 - 0.01, b0);
        let (mut g_prev, mut g) = (slope(b_prev)?, slope(b)?);
        for _ in 0..NEWTON_STEPS {
            if g.abs() < 1e-10 || g == g_prev {
                break;
            }
            let next = (b - g * (b - b_prev) / (g - g_prev)).clamp(-half, half);
            b_prev = b;
            g_prev = g;
            b = next;
            g = slope(b)?;
        }
        let h_min = clearance(terrain, frame, b)?;
        if h_min.is_nan() || h_min >= 0.0 || g.abs() > 1e-3 || !b.is_finite() {
            return Ok(false);
        }
        let mut deep = false;
        let mut edge = |dir: f64| -> Result<RimAngle, OffMap> {
            let (mut inner, mut h_in) = (b, h_min);
            loop {
                // (Not `clamp`: in the closure its bounds are not constants, and its
                // check of them would be a path to a panic.)
                let outer = (inner + dir * MARCH).max(-half).min(half);
                let h_out = clearance(terrain, frame, outer)?;
                if h_out >= 0.0 {
                    return crossing(terrain, frame, inner, h_in, outer, h_out, tol);
                }
                if outer.abs() >= half {
                    deep = true;
                    return Ok(RimAngle::new(outer));
                }
                inner = outer;
                h_in = h_out;
            }
        };
        let a = edge(-1.0)?;
        let e = edge(1.0)?;
        *out = Contact {
            deep,
            ..Contact::default()
        };
        out.push(frame.patch(a, e));
        Ok(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Z = a·sin(2π·X/λx)·cos(2π·Y/λy)`, a wavy field for the test.
    struct Waves;

    impl HeightField for Waves {
        fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
            Ok(self.height_gradient(x, y)?.0)
        }

        fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
            let (a, kx, ky) = (
                0.03,
                core::f64::consts::TAU / 0.45,
                core::f64::consts::TAU / 0.7,
            );
            let (sx, cx) = math::sin_cos(kx * x);
            let (sy, cy) = math::sin_cos(ky * y);
            Ok((a * sx * cy, [a * kx * cx * cy, -a * ky * sx * sy]))
        }
    }

    #[test]
    fn the_clearance_slope_is_the_derivative_of_the_clearance() {
        // A wavy field, the wheel tilted and its axis skewed, so that every
        // term of the slope counts.
        let terrain = Waves;
        let axis = {
            let a: [f64; 3] = [0.2, 0.95, 0.15];
            let n = math::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
            a.map(|v| v / n)
        };
        let frame = RimFrame::new([0.31, -0.12, 0.08], axis, 0.1).unwrap();
        for k in 0..=40 {
            let b = -1.5 + 3.0 * k as f64 / 40.0;
            let e = 1e-5;
            let fd = (clearance(&terrain, &frame, b + e).unwrap()
                - clearance(&terrain, &frame, b - e).unwrap())
                / (2.0 * e);
            let (h, exact) = clearance_slope(&terrain, &frame, RimAngle::new(b)).unwrap();
            assert_eq!(h, clearance(&terrain, &frame, b).unwrap());
            assert!((exact - fd).abs() < 1e-7, "β = {b}: {exact} vs {fd}");
        }
    }
}
