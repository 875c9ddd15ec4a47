//! The double wishbone: a four-bar linkage in the y–z plane (MODEL.md §3).

use crate::linkage::{LinkEnd, Linkage, Member, MemberShare, PointDef};
use crate::real::Real;

/// Double wishbone in the plane x = `x`. With s = +1 on the left (lower
/// pivot at y > 0) and −1 on the right, and y the lower arm's angle about
/// e_x (right-hand rule, 0 = horizontal):
/// ```text
/// B(y) = L + s·l_L·[cos y, sin y]                 lower ball joint (y, z)
/// C(y): |C − U| = l_U, |C − B| = h                upper ball joint, the branch
///                                                 with C above B at rest
/// φ(y) = atan2(C_z − B_z, C_y − B_y)              upright angle
/// W(y) = B + along·e_u + across·s·[e_u,z, −e_u,y] wheel centre, e_u = (C − B)/h
/// ```
/// The upright turns about e_x by φ(y) − φ(y_c): that is the member angle
/// and the camber change (camber 0 at rest). Solved exactly, fitted by
/// least squares over the travel (or Taylor on request).
#[derive(Clone, Debug, PartialEq)]
pub struct DoubleWishbone {
    /// Plane position x \[m\].
    pub x: f64,
    /// Lower inner pivot L (y, z) \[m\].
    pub lower_pivot: [f64; 2],
    /// Lower arm length l_L \[m\].
    pub lower_length: f64,
    /// Upper inner pivot U (y, z) \[m\].
    pub upper_pivot: [f64; 2],
    /// Upper arm length l_U \[m\].
    pub upper_length: f64,
    /// Upright length h \[m\].
    pub upright_length: f64,
    /// Wheel centre (along, across) the upright \[m\].
    pub wheel_offset: [f64; 2],
    /// Rest angle y_c \[rad\].
    pub rest: f64,
    /// Assembly branch ±1, chosen at rest.
    pub branch: f64,
}

/// The linkage's joints at one value of y (plane coordinates y, z).
struct Pose<R> {
    lower: [R; 2],
    upper: [R; 2],
}

impl DoubleWishbone {
    /// Side s: +1 left, −1 right.
    pub fn side(&self) -> f64 {
        if self.lower_pivot[0] >= 0.0 {
            1.0
        } else {
            -1.0
        }
    }

    /// Pick the assembly branch with the upper ball joint above the lower
    /// at rest (`branch` is ignored); `None` if the linkage does not
    /// assemble at rest, or only upside down.
    pub fn assembled(mut self) -> Option<Self> {
        self.branch = 1.0;
        let up = self.pose(self.rest)?;
        self.branch = -1.0;
        let down = self.pose(self.rest)?;
        self.branch = if up.upper[1] >= down.upper[1] {
            1.0
        } else {
            -1.0
        };
        let chosen = self.pose(self.rest)?;
        (chosen.upper[1] > chosen.lower[1]).then_some(self)
    }

    /// Solve the four-bar at y (exact circle intersection).
    fn pose<R: Real>(&self, y: R) -> Option<Pose<R>> {
        let s = self.side();
        let b = [
            R::cst(self.lower_pivot[0]) + R::cst(s * self.lower_length) * y.cos(),
            R::cst(self.lower_pivot[1]) + R::cst(s * self.lower_length) * y.sin(),
        ];
        let u = [R::cst(self.upper_pivot[0]), R::cst(self.upper_pivot[1])];
        let d = [u[0] - b[0], u[1] - b[1]];
        let dist2 = d[0] * d[0] + d[1] * d[1];
        let dist = dist2.sqrt();
        let h = self.upright_length;
        let lu = self.upper_length;
        // Distance from B along BU to the chord, and half-chord.
        let a = (dist2 + R::cst(h * h - lu * lu)) / (R::cst(2.0) * dist);
        let half2 = R::cst(h * h) - a * a;
        if !is_positive(dist.value()) || !is_positive(half2.value()) {
            return None;
        }
        let half = half2.sqrt();
        let e = [d[0] / dist, d[1] / dist];
        let perp = [-e[1], e[0]];
        let k = R::cst(-s * self.branch);
        let c = [
            b[0] + a * e[0] + k * half * perp[0],
            b[1] + a * e[1] + k * half * perp[1],
        ];
        Some(Pose { lower: b, upper: c })
    }

    /// Upright angle φ and upper-arm angle ψ about e_x.
    fn angles<R: Real>(&self, p: &Pose<R>) -> (R, R) {
        let phi = (p.upper[1] - p.lower[1]).atan2(p.upper[0] - p.lower[0]);
        let psi = (p.upper[1] - R::cst(self.upper_pivot[1]))
            .atan2(p.upper[0] - R::cst(self.upper_pivot[0]));
        (phi, psi)
    }

    /// The rest pose in f64 (exists by construction).
    fn rest_pose(&self) -> ([f64; 2], [f64; 2]) {
        match self.pose(self.rest) {
            Some(p) => (p.lower, p.upper),
            None => ([f64::NAN; 2], [f64::NAN; 2]),
        }
    }
}

impl Linkage for DoubleWishbone {
    fn members(&self) -> Vec<Member> {
        let (b, _) = self.rest_pose();
        let turn = vec![MemberShare {
            coord: 0,
            axis: Some(0),
        }];
        vec![
            Member {
                name: "lower_arm",
                pivot: [self.x, self.lower_pivot[0], self.lower_pivot[1]],
                shares: turn.clone(),
                camber_rest: 0.0,
            },
            Member {
                name: "upper_arm",
                pivot: [self.x, self.upper_pivot[0], self.upper_pivot[1]],
                shares: turn.clone(),
                camber_rest: 0.0,
            },
            Member {
                name: "upright",
                pivot: [self.x, b[0], b[1]],
                shares: turn,
                camber_rest: 0.0,
            },
        ]
    }

    fn points(&self) -> Vec<PointDef> {
        let (b, c) = self.rest_pose();
        let h = self.upright_length;
        let e = [(c[0] - b[0]) / h, (c[1] - b[1]) / h];
        let n = [self.side() * e[1], -self.side() * e[0]];
        let [along, across] = self.wheel_offset;
        vec![PointDef {
            name: "wheel".into(),
            member: 2,
            rest: [
                self.x,
                b[0] + along * e[0] + across * n[0],
                b[1] + along * e[1] + across * n[1],
            ],
            wheel: true,
        }]
    }

    fn motion<R: Real>(&self, member: usize, _coord: usize, y: R) -> Option<([R; 3], R)> {
        let zero = R::cst(0.0);
        if member == 0 {
            return Some(([zero; 3], y - R::cst(self.rest)));
        }
        let now = self.pose(y)?;
        let rest = self.pose(R::cst(self.rest))?;
        let (phi, psi) = self.angles(&now);
        let (phi_c, psi_c) = self.angles(&rest);
        if member == 1 {
            return Some(([zero; 3], psi - psi_c));
        }
        let t = [
            zero,
            now.lower[0] - rest.lower[0],
            now.lower[1] - rest.lower[1],
        ];
        Some((t, phi - phi_c))
    }

    /// The lower arm from its inner pivot to the lower ball joint, the
    /// upper arm likewise, the upright between the ball joints, and its
    /// stub axle (from the upright's axis at the wheel's `along` offset out
    /// to the wheel centre).
    fn sketch(&self) -> Vec<[LinkEnd; 2]> {
        let (b, c) = self.rest_pose();
        let at = |p: [f64; 2]| [self.x, p[0], p[1]];
        let h = self.upright_length;
        let along = self.wheel_offset[0];
        let axle = [
            b[0] + along * (c[0] - b[0]) / h,
            b[1] + along * (c[1] - b[1]) / h,
        ];
        let end = |member, rest| LinkEnd { member, rest };
        let wheel = self.points()[0].rest;
        vec![
            [end(0, at(self.lower_pivot)), end(0, at(b))],
            [end(1, at(self.upper_pivot)), end(1, at(c))],
            [end(2, at(b)), end(2, at(c))],
            [end(2, at(axle)), end(2, wheel)],
        ]
    }
}

/// `v > 0` (false for NaN).
fn is_positive(v: f64) -> bool {
    v > 0.0
}
