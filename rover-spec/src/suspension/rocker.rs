//! Free rockers, longitudinal and transversal (MODEL.md §3).

use crate::linkage::{Linkage, Member, MemberShare, PointDef};
use crate::real::{Real, rotate};

/// A rocker on a pivot with a principal axis, carrying one point per arm:
/// ```text
/// wheel k: u = A + R(y + β_k)·[0, 0, −l_k]     (R = Ry longitudinal, Rx transversal)
/// ```
/// y = 0 at rest by default; member angle `y − y_c`; the transversal
/// rocker's wheels camber with it (γ = y).
#[derive(Clone, Debug, PartialEq)]
pub struct Rocker {
    /// Pivot A \[m\].
    pub pivot: [f64; 3],
    /// Arms: point name, length l_k \[m\], angle β_k \[rad\].
    pub arms: Vec<(String, f64, f64)>,
    /// 1 for longitudinal (e_y), 0 for transversal (e_x).
    pub axis: usize,
    /// Rest angle y_c \[rad\].
    pub rest: f64,
}

impl Linkage for Rocker {
    fn members(&self) -> Vec<Member> {
        vec![Member {
            name: "rocker",
            pivot: self.pivot,
            shares: vec![MemberShare {
                coord: 0,
                axis: Some(self.axis),
            }],
            camber_rest: if self.axis == 0 { self.rest } else { 0.0 },
        }]
    }

    fn points(&self) -> Vec<PointDef> {
        self.arms
            .iter()
            .map(|(name, l, beta)| {
                let d = rotate(self.axis, self.rest + beta, [0.0, 0.0, -l]);
                PointDef {
                    name: name.clone(),
                    member: 0,
                    rest: [
                        self.pivot[0] + d[0],
                        self.pivot[1] + d[1],
                        self.pivot[2] + d[2],
                    ],
                    wheel: true,
                }
            })
            .collect()
    }

    fn motion<R: Real>(&self, _member: usize, _coord: usize, y: R) -> Option<([R; 3], R)> {
        Some(([R::cst(0.0); 3], y - R::cst(self.rest)))
    }
}
