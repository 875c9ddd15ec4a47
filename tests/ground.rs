//! The ground in a whole run: a rover holds on a slope below the friction
//! angle and slides above it.

/// Largest horizontal distance of G from its start over the run.
fn max_drift(r: &crate::support::run::Run) -> f64 {
    let (x, y) = (r.col("X"), r.col("Y"));
    x.iter()
        .zip(&y)
        .map(|(a, b)| ((a - x[0]).powi(2) + (b - y[0]).powi(2)).sqrt())
        .fold(0.0, f64::max)
}

fn on_slope(angle_deg: f64) -> crate::support::run::Run {
    crate::support::run::run(
        "swing4",
        &format!(
            "duration = 20.0\noutput_rate = 20.0\n[terrain]\nkind = \"slope\"\nangle_deg = {angle_deg}\n\
             [initial]\nattitude_deg = [0.0, {}, 0.0]\n\
             [control.speed]\nspeed = 0.0\nkp = 30.0\nki = 100.0\n\
             [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\n",
            -angle_deg
        ),
    )
}

#[test]
fn rover_holds_on_a_slope_below_the_friction_angle_and_slides_above() {
    // atan(μx_max) = atan(0.5) = 26.6°.
    let held = on_slope(15.0);
    assert!(held.summary.complete, "{:?}", held.summary.error);
    let d = max_drift(&held);
    assert!(d < 0.01, "on 15° the rover moved {d} m (limit 1 cm)");
    let slid = on_slope(32.0);
    let d = max_drift(&slid);
    assert!(
        d > 0.2,
        "on 32° the rover moved only {d} m: it should slide"
    );
    let x = slid.col("X");
    assert!(x[x.len() - 1] < x[0], "it slides downhill (towards −X)");
}
