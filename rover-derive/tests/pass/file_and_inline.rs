use rover_derive::Rover;
use rover_dynamics::nalgebra::SVector;
use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad};

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml")]
struct FromFile;

#[derive(Rover)]
#[rover(
    name = "ui",
    gravity = 1.62,
    body = { mass = 10.0, inertia = [0.2, 0.3, 0.4] },
    wheel_defaults = { mass = 0.5, radius = 0.1, stiffness = 3000.0, damping = 100.0, mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 40.0, max_torque = 1.0 },
    suspension = [{ name = "left", kind = "longitudinal_swing_arm", pivot = [0.1, 0.2, 0.0], length = 0.15,
        coordinate = { rest_deg = -20.0, min_deg = -40.0, max_deg = 0.0, stiffness = 4.0 }, fit = { method = "taylor", terms = 4 } }],
    wheel = [{ name = "left", suspension = "left" }],
    jacobian = true,
)]
pub struct Inline;

include!("../uses/use_all.rs");

fn main() {
    // The items the error stub mirrors exist on a real plant.
    use_all!(Inline, InlinePlant, 7, 1);
    let (mut a, mut b) = (FromFile::plant(), Inline::plant());
    assert_eq!(FromFilePlant::DOF, 7);
    assert_eq!(a.dof(), b.dof());
    let mut x = [0.0; 7];
    x[3] = 0.1;
    x[6] = -0.3;
    let w = [0.1; 7];
    let loads = [WheelLoad { force: [1.0, 2.0, 30.0], ..Default::default() }];
    let (mut xa, mut wa, mut xb, mut wb) = ([0.0; 7], [0.0; 7], [0.0; 7], [0.0; 7]);
    a.derivatives(&x, &w, &loads, &mut xa, &mut wa).unwrap();
    b.derivatives(&x, &w, &loads, &mut xb, &mut wb).unwrap();
    assert_eq!(wa, wb);
    assert!(wa[2] != 0.0);
    let jac = b.jacobian_array(&x, &w, &loads);
    // ∂Ẋ/∂v_x = R[0][0] = 1 at θ = ψ = 0.
    assert_eq!(jac[0][7], 1.0);
    // The same plant on nalgebra's fixed-size types.
    let (xs, ws) = (SVector::<f64, 7>::from(x), SVector::<f64, 7>::from(w));
    let (mut xd, mut wd) = (SVector::<f64, 7>::zeros(), SVector::<f64, 7>::zeros());
    b.derivatives_fixed(&xs, &ws, &loads, &mut xd, &mut wd).unwrap();
    assert_eq!(wd.as_slice(), &wb[..]);
    assert_eq!(b.jacobian_fixed(&xs, &ws, &loads)[(0, 7)], 1.0);
    let m = b.mass_matrix_fixed(&xs);
    assert_eq!(m, m.transpose());
}
