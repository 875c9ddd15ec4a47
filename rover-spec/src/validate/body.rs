//! Masses and inertia tensors.

use crate::checks::{Ctx, num, symmetric_eigenvalues};
use crate::description::Inertia;

/// Relative tolerance of the symmetry and triangle-inequality checks.
const REL_TOL: f64 = 1e-9;

/// Check an inertia tensor: symmetric, positive definite, and its
/// principal moments obey the triangle inequality (J_1 + J_2 ≥ J_3 for
/// every ordering), which every real mass distribution does.
pub fn check_inertia(ctx: &mut Ctx, path: &str, inertia: &Inertia) -> Option<[[f64; 3]; 3]> {
    let m = inertia.matrix();
    if m.iter().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    let scale = m
        .iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (m[i][j] - m[j][i]).abs() > REL_TOL * scale {
            ctx.error(
                path,
                format!(
                    "inertia is not symmetric: row {}, column {} is {} but row {}, column {} is {}",
                    i + 1,
                    j + 1,
                    num(m[i][j]),
                    j + 1,
                    i + 1,
                    num(m[j][i])
                ),
                "an inertia tensor is symmetric: make the off-diagonal entries equal in pairs",
            );
            return None;
        }
    }
    let e = symmetric_eigenvalues(m);
    let diagonal = matches!(inertia, Inertia::Diagonal(_));
    if e[0] <= 0.0 {
        let message = if diagonal {
            format!(
                "inertia is not positive definite: J_xx = {}, J_yy = {}, J_zz = {} kg·m² must all be > 0",
                num(m[0][0]),
                num(m[1][1]),
                num(m[2][2])
            )
        } else {
            format!(
                "inertia is not positive definite: its principal moments are {}, {}, {} kg·m²",
                num(e[0]),
                num(e[1]),
                num(e[2])
            )
        };
        ctx.error(
            path,
            message,
            "moments of inertia are positive, in kg·m²; check the signs (off-diagonal entries are −∫xy dm)",
        );
        return None;
    }
    if e[0] + e[1] < e[2] * (1.0 - REL_TOL) {
        let message = if diagonal {
            let (names, vals) = largest_first(m);
            format!(
                "inertia breaks the triangle inequality: {} + {} = {} < {} = {} kg·m²",
                names[1],
                names[2],
                num(vals[1] + vals[2]),
                names[0],
                num(vals[0])
            )
        } else {
            format!(
                "inertia breaks the triangle inequality: principal moments {} + {} = {} < {} kg·m²",
                num(e[0]),
                num(e[1]),
                num(e[0] + e[1]),
                num(e[2])
            )
        };
        ctx.error(
            path,
            message,
            "no mass distribution has one moment larger than the sum of the other two \
             (J_xx + J_yy ≥ J_zz and its permutations): check the values and their axes",
        );
        return None;
    }
    Some(m)
}

/// Diagonal moments, the largest first, with their names.
fn largest_first(m: [[f64; 3]; 3]) -> ([&'static str; 3], [f64; 3]) {
    let mut items = [("J_xx", m[0][0]), ("J_yy", m[1][1]), ("J_zz", m[2][2])];
    items.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut names = [items[0].0, items[1].0, items[2].0];
    // Keep the two smaller ones in axis order for the message.
    if names[1] > names[2] {
        names.swap(1, 2);
        return (names, [items[0].1, items[2].1, items[1].1]);
    }
    (names, [items[0].1, items[1].1, items[2].1])
}
