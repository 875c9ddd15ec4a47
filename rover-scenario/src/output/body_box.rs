//! The box a viewer draws for the rover's body: the description gives
//! masses and inertias, not a shape, so the box is sized from the wheel
//! layout. `rover drive`'s page and the Foxglove scene draw the same one.

/// Length (body x), width (body y) and height of the body's box \[m\],
/// from the wheels' rest centres (body axes, from G) and radii: 0.8 of
/// the wheelbase (at least a wheel's diameter) long, the track less a
/// wheel's diameter (at least a radius) wide, a radius high.
pub fn body_box(rest: &[[f64; 3]], radius: &[f64]) -> [f64; 3] {
    let span = |k: usize| {
        let (lo, hi) = rest
            .iter()
            .map(|p| p[k])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        hi - lo
    };
    let r_max = radius.iter().cloned().fold(0.0, f64::max);
    [
        0.8 * span(0).max(2.0 * r_max),
        (span(1) - 2.0 * r_max).max(r_max),
        r_max,
    ]
}
