//! Axis ranges: padded data ranges for time histories, and equal-scale ranges
//! for the trajectory projections (one metre is as long on both axes).

use std::ops::Range;

/// Fraction of the data span added on each side.
const PAD: f64 = 0.05;

/// Smallest half-span of an axis, in the data's unit: a constant signal
/// (or a single row) still gets a usable axis.
const MIN_HALF_SPAN: f64 = 1.0e-3;

/// Smallest and largest of `values`, or `None` when there are none.
pub(crate) fn bounds<'a>(values: impl IntoIterator<Item = &'a f64>) -> Option<(f64, f64)> {
    values.into_iter().fold(None, |acc, &v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// `lo..hi` widened by 5 % of the span on each side; a (nearly) zero span is
/// widened to ±5 % of the value, at least ±1e-3.
pub(crate) fn padded(lo: f64, hi: f64) -> Range<f64> {
    let mid = 0.5 * (lo + hi);
    let half = (0.5 * (hi - lo) * (1.0 + 2.0 * PAD))
        .max(PAD * mid.abs())
        .max(MIN_HALF_SPAN);
    (mid - half)..(mid + half)
}

/// The time axis: `t0..t_end` exactly, or one second around `t0` for a
/// single-row run.
pub(crate) fn time_axis(t: &[f64]) -> Range<f64> {
    match (t.first(), t.last()) {
        (Some(&t0), Some(&t1)) if t1 > t0 => t0..t1,
        (Some(&t0), _) => (t0 - 0.5)..(t0 + 0.5),
        _ => 0.0..1.0,
    }
}

/// Ranges for a plotting area of `pixels = (width, height)` such that one
/// unit has the same length in pixels on both axes, the data box
/// `x`×`y` is centred and padded, and it fills the area in the tighter
/// direction.
pub(crate) fn equal_scale(
    x: (f64, f64),
    y: (f64, f64),
    pixels: (u32, u32),
) -> (Range<f64>, Range<f64>) {
    let (w, h) = (f64::from(pixels.0.max(1)), f64::from(pixels.1.max(1)));
    let x_pad = padded(x.0, x.1);
    let y_pad = padded(y.0, y.1);
    // Units per pixel: the larger of the two needed ratios.
    let scale = ((x_pad.end - x_pad.start) / w).max((y_pad.end - y_pad.start) / h);
    let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
    (
        (cx - 0.5 * scale * w)..(cx + 0.5 * scale * w),
        (cy - 0.5 * scale * h)..(cy + 0.5 * scale * h),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span(r: &Range<f64>) -> f64 {
        r.end - r.start
    }

    #[test]
    fn equal_scale_gives_the_same_units_per_pixel_on_both_axes() {
        // A 4 m × 0.2 m side view in a 900 × 450 px area: x decides.
        let (xr, yr) = equal_scale((-2.0, 2.0), (0.1, 0.3), (900, 450));
        assert!((span(&xr) / 900.0 - span(&yr) / 450.0).abs() < 1e-12);
        assert!((span(&xr) - 4.4).abs() < 1e-12);
        assert!(((yr.start + yr.end) / 2.0 - 0.2).abs() < 1e-12);
        // A tall data box in a wide area: y decides.
        let (xr, yr) = equal_scale((0.0, 1.0), (0.0, 10.0), (800, 400));
        assert!((span(&xr) / 800.0 - span(&yr) / 400.0).abs() < 1e-12);
        assert!((span(&yr) - 11.0).abs() < 1e-12);
        assert!(xr.start < 0.0 && xr.end > 1.0);
    }

    #[test]
    fn a_single_point_still_has_finite_nonzero_ranges() {
        let (xr, yr) = equal_scale((1.0, 1.0), (2.0, 2.0), (100, 100));
        assert!(span(&xr) > 0.0 && span(&yr) > 0.0);
        assert!(xr.start < 1.0 && xr.end > 1.0);
        assert_eq!(padded(0.0, 0.0), -1.0e-3..1.0e-3);
        let r = padded(10.0, 10.0);
        assert!((r.start - 9.5).abs() < 1e-12 && (r.end - 10.5).abs() < 1e-12);
    }

    #[test]
    fn time_axis_and_bounds() {
        assert_eq!(time_axis(&[0.0, 0.1, 2.0]), 0.0..2.0);
        assert_eq!(time_axis(&[3.0]), 2.5..3.5);
        assert_eq!(bounds(&[3.0, -1.0, 2.0]), Some((-1.0, 3.0)));
        assert_eq!(bounds(&[]), None);
    }
}
