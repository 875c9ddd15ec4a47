//! The height-field interface the terrains implement, for the modules of
//! this crate (it is defined, and named by users, in `rover-dynamics`:
//! no_std, so that generated code can name it), and the finiteness check
//! of the unbounded terrains.

pub(crate) use rover_dynamics::height_field::{Bounds, HeightField, OffMap, Plane};

/// Checks that a query point is finite, for the unbounded analytic terrains.
#[inline]
pub(crate) fn finite_point(x: f64, y: f64) -> Result<(), OffMap> {
    if x.is_finite() && y.is_finite() {
        Ok(())
    } else {
        Err(OffMap {
            x,
            y,
            bounds: Bounds::UNBOUNDED,
        })
    }
}
