//! The contract between the suspension library and the fit: a suspension
//! kind gives its exact kinematics as members that turn and move with its
//! coordinates ([`Linkage`]); [`crate::fit`] turns the motion of each point
//! into the polynomials of the numeric model (MODEL.md §3).
//!
//! Every kind of the library moves a member with each coordinate
//! separately, so the motion of a point is a sum of one-coordinate shares:
//! ```text
//! u(y) = p + Σ_i [ t_i(y_i) + (Rot(a_i, θ_i(y_i)) − I)·(p − P) ]
//! ```
//! p the point at rest, P the member's pivot at rest, t_i the pivot's
//! displacement and θ_i the member's angle about the principal axis a_i,
//! both zero at the rest value. At most one coordinate turns a member
//! (the bogie of a rocker-bogie moves with the rocker but turns only with
//! its own angle), which keeps this sum exact.

use rover_dynamics::model::MemberRotation;
use rover_dynamics::poly::{PolyVec, ScalarPoly};

use crate::real::Real;

/// The range of one suspension coordinate: where the fit must hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoordRange {
    /// Rest value y_c: the expansion centre, and the Taylor point.
    pub rest: f64,
    /// Lower travel limit.
    pub min: f64,
    /// Upper travel limit.
    pub max: f64,
}

/// How exact kinematics become polynomials.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FitMethod {
    /// Taylor series about the rest value (the paper's eq. 33), computed
    /// exactly by evaluating the kinematics on truncated power series.
    Taylor,
    /// Least squares over the travel range on Chebyshev-spaced samples,
    /// through the rest point (better over a wide range).
    LeastSquares,
}

/// Fit options of one suspension (the description's `fit` table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Taylor or least squares.
    pub method: FitMethod,
    /// Number of terms k per coordinate (powers ξ⁰ … ξ^(k−1)); default 5.
    pub terms: usize,
    /// Largest accepted position error over the range \[m\].
    pub tolerance: f64,
    /// Largest accepted angle error over the range \[rad\].
    pub angle_tolerance: f64,
}

impl Default for FitOptions {
    /// Least squares, k = 5 (the paper's choice: enough terms for good
    /// velocities and accelerations), 1 mm, 1 mrad.
    fn default() -> Self {
        FitOptions {
            method: FitMethod::LeastSquares,
            terms: 5,
            tolerance: 1e-3,
            angle_tolerance: 1e-3,
        }
    }
}

/// How a member moves with one of its suspension's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MemberShare {
    /// The coordinate, local to the suspension.
    pub coord: usize,
    /// The principal axis it turns about (0 = e_x, 1 = e_y, 2 = e_z), if it
    /// turns with this coordinate (it may only move).
    pub axis: Option<usize>,
}

/// A member (arm, rocker, bogie, upright) of a suspension.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// Its name (`arm`, `rocker_left`, `upright`, …).
    pub name: &'static str,
    /// Its pivot at rest, body components \[m\].
    pub pivot: [f64; 3],
    /// Its shares, at most one with an axis.
    pub shares: Vec<MemberShare>,
    /// Camber of a wheel on it at rest \[rad\].
    pub camber_rest: f64,
}

/// A named point of a suspension.
#[derive(Clone, Debug, PartialEq)]
pub struct PointDef {
    /// Its name (wheels refer to it).
    pub name: String,
    /// The member carrying it.
    pub member: usize,
    /// Its position at rest, body components \[m\].
    pub rest: [f64; 3],
    /// Whether a wheel may sit on it.
    pub wheel: bool,
}

/// The exact kinematics of a suspension kind.
pub trait Linkage {
    /// The members.
    fn members(&self) -> Vec<Member>;
    /// The named points.
    fn points(&self) -> Vec<PointDef>;
    /// Displacement of the member's pivot and member angle, both zero at
    /// the rest value, due to local coordinate `coord` at `y`; `None` where
    /// the linkage cannot assemble.
    fn motion<R: Real>(&self, member: usize, coord: usize, y: R) -> Option<([R; 3], R)>;

    /// The drawing of the linkage: its links as pairs of joints, each
    /// joint a point of a member at rest (the pivots, the ball joints, the
    /// points). By default, a link from each member's pivot to each of
    /// its points.
    fn sketch(&self) -> Vec<[LinkEnd; 2]> {
        let members = self.members();
        self.points()
            .iter()
            .map(|p| {
                [
                    LinkEnd {
                        member: p.member,
                        rest: members[p.member].pivot,
                    },
                    LinkEnd {
                        member: p.member,
                        rest: p.rest,
                    },
                ]
            })
            .collect()
    }
}

/// One end of a drawn link: a point of a member, by its position at rest;
/// it moves with the member ([`point_share`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkEnd {
    /// The member (index into [`Linkage::members`]).
    pub member: usize,
    /// The point at rest, body components \[m\].
    pub rest: [f64; 3],
}

/// The share of one coordinate in the motion of a point on a member:
/// `[Δu_x, Δu_y, Δu_z, θ]`, all zero at the rest value.
pub fn point_share<L: Linkage, R: Real>(
    linkage: &L,
    member: &Member,
    member_index: usize,
    share: &MemberShare,
    rest: [f64; 3],
    y: R,
) -> Option<[R; 4]> {
    let (t, angle) = linkage.motion(member_index, share.coord, y)?;
    let rel = [
        R::cst(rest[0] - member.pivot[0]),
        R::cst(rest[1] - member.pivot[1]),
        R::cst(rest[2] - member.pivot[2]),
    ];
    let turned = match share.axis {
        Some(axis) => crate::real::rotate(axis, angle, rel),
        None => rel,
    };
    Some([
        t[0] + turned[0] - rel[0],
        t[1] + turned[1] - rel[1],
        t[2] + turned[2] - rel[2],
        angle,
    ])
}

/// Largest error of one coordinate's share over its range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShareError {
    /// The coordinate (global index).
    pub coord: usize,
    /// Largest |u_fit − u_exact| \[m\].
    pub position: f64,
    /// Where it occurs.
    pub position_at: f64,
    /// Largest |θ_fit − θ_exact| \[rad\].
    pub angle: f64,
    /// Where it occurs.
    pub angle_at: f64,
}

/// A body carried by a suspension, as fitted polynomials in the global
/// coordinates, with the fit's maximum errors over the declared range.
#[derive(Clone, Debug, PartialEq)]
pub struct FittedPoint {
    /// u_j(y), body components \[m\].
    pub position: PolyVec,
    /// The member's rotations (one per coordinate it turns with).
    pub member: Vec<MemberRotation>,
    /// Camber γ(y) \[rad\] (zero for the longitudinal kinds).
    pub camber: ScalarPoly,
    /// Suspension-induced steer ε(y) \[rad\].
    pub toe: ScalarPoly,
    /// Bound on |u_fit − u_exact| anywhere in the travel box: the sum of
    /// the shares' maxima \[m\].
    pub max_position_error: f64,
    /// Same for the member, camber and steer angles \[rad\].
    pub max_angle_error: f64,
    /// Per coordinate.
    pub shares: Vec<ShareError>,
}
