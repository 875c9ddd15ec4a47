//! A point of a library suspension as polynomials in the global
//! coordinates: every share of its member fitted (MODEL.md §3, eq. 32–34).

use rover_dynamics::model::MemberRotation;
use rover_dynamics::poly::{PolyVec, ScalarPoly, Term};

use crate::fit::{FitFailure, fit_share};
use crate::jet::Jet;
use crate::linkage::{CoordRange, FitOptions, FittedPoint, Linkage, ShareError, point_share};

/// Fit the point that sits at `rest` on member `member` of `linkage`.
/// `ranges` and `global` are indexed by the suspension's local coordinate.
/// On failure, gives the local coordinate that failed.
pub fn fit_point<L: Linkage>(
    linkage: &L,
    member: usize,
    rest: [f64; 3],
    ranges: &[CoordRange],
    global: &[usize],
    options: &FitOptions,
) -> Result<FittedPoint, (usize, FitFailure)> {
    let members = linkage.members();
    let m = &members[member];
    let mut position = PolyVec::constant(rest);
    let mut rotations = Vec::new();
    let mut camber = ScalarPoly::constant(m.camber_rest);
    let mut toe = ScalarPoly::constant(0.0);
    let mut shares = Vec::new();
    for share in &m.shares {
        let range = ranges[share.coord];
        let exact = |y: f64| point_share(linkage, m, member, share, rest, y);
        let series = |y: Jet| point_share(linkage, m, member, share, rest, y);
        let fit = fit_share(&exact, &series, range, options).map_err(|e| (share.coord, e))?;
        let coord = global[share.coord];
        position.terms.push(Term {
            coord,
            center: range.rest,
            coeffs: fit.coeffs.iter().map(|c| [c[0], c[1], c[2]]).collect(),
        });
        let angle_term = || Term {
            coord,
            center: range.rest,
            coeffs: fit.coeffs.iter().map(|c| c[3]).collect(),
        };
        let mut angle_error = 0.0;
        if let Some(axis) = share.axis {
            let mut a = [0.0; 3];
            a[axis] = 1.0;
            rotations.push(MemberRotation {
                coord,
                axis: a,
                angle: ScalarPoly {
                    constant: 0.0,
                    terms: vec![angle_term()],
                },
            });
            match axis {
                0 => camber.terms.push(angle_term()),
                2 => toe.terms.push(angle_term()),
                _ => {}
            }
            angle_error = fit.angle_error;
        }
        shares.push(ShareError {
            coord,
            position: fit.position_error,
            position_at: fit.position_error_at,
            angle: angle_error,
            angle_at: fit.angle_error_at,
        });
    }
    Ok(FittedPoint {
        position,
        member: rotations,
        camber,
        toe,
        max_position_error: shares.iter().map(|s| s.position).sum(),
        max_angle_error: shares.iter().map(|s| s.angle).sum(),
        shares,
    })
}
