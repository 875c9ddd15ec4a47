use rover_derive::Rover;

// No wheel gives a radius and the defaults give none: one error, at the
// defaults, not one per wheel.
#[derive(Rover)]
#[rover(
    name = "ui",
    gravity = 1.62,
    body = { mass = 10.0, inertia = [0.2, 0.3, 0.4] },
    wheel_defaults = { mass = 0.5, stiffness = 3000.0, damping = 100.0, mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 40.0, max_torque = 1.0 },
    suspension = [
        { name = "left", kind = "longitudinal_swing_arm", pivot = [0.1, 0.2, 0.0], length = 0.15,
          coordinate = { rest_deg = -20.0, min_deg = -40.0, max_deg = 0.0, stiffness = 4.0 }, fit = { method = "taylor", terms = 4 } },
        { name = "right", kind = "longitudinal_swing_arm", pivot = [0.1, -0.2, 0.0], length = 0.15,
          coordinate = { rest_deg = -20.0, min_deg = -40.0, max_deg = 0.0, stiffness = 4.0 }, fit = { method = "taylor", terms = 4 } },
    ],
    wheel = [{ name = "left", suspension = "left" }, { name = "right", suspension = "right" }],
)]
struct Inline;

include!("../uses/use_all.rs");

fn main() {
    use_all!(Inline, InlinePlant, 8, 2);
}
