//! The equations of motion assembled (MODEL.md §5, paper eq. 24–31):
//! ```text
//! M·ẇ = −Ṁ·w − f1 + f2 + Q,    ẋ = B·w
//! ```

use crate::attitude::Attitude;
use crate::bias::add_bias;
use crate::forces::{Load, add_gravity, add_suspension, add_wheel_loads};
use crate::kinematics::{body_kinematics, position_rates};
use crate::mass::mass_matrix;
use crate::model::Model;
use crate::scalar::Scalar;
use crate::solve::ldlt_solve;
use crate::workspace::Workspace;

/// `ẋ` and `ẇ` at state (x, w) under wheel loads `loads` and spring
/// neutrals `neutral`. `ws.mass` holds the LDLᵀ factors afterwards (its
/// diagonal the pivots D, for the caller's positive-definiteness check).
pub fn derivatives<S: Scalar>(
    model: &Model,
    ws: &mut Workspace<S>,
    neutral: &[S],
    x: &[S],
    w: &[S],
    loads: &[Load<S>],
    xdot: &mut [S],
    wdot: &mut [S],
) {
    let n = ws.dof;
    let y = &x[6..];
    body_kinematics(model, y, ws);
    mass_matrix(model, ws);
    let att = Attitude::new(x[3], x[4], x[5]);
    let mut rhs = core::mem::take(&mut ws.rhs);
    for v in rhs.iter_mut() {
        *v = S::zero();
    }
    add_bias(model, ws, w, &mut rhs);
    add_gravity(model, ws, &att, &mut rhs);
    add_suspension(model, neutral, y, &w[6..], &mut rhs);
    add_wheel_loads(model, ws, &att, loads, &mut rhs);
    ldlt_solve(&mut ws.mass, &mut rhs, n);
    wdot.copy_from_slice(&rhs);
    ws.rhs = rhs;
    position_rates(x, w, xdot);
}
