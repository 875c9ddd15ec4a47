//! Swing arms, longitudinal and transversal (MODEL.md §3, paper eq. 33).

use crate::linkage::{Linkage, Member, MemberShare, PointDef};
use crate::real::{Real, rotate};

/// A swing arm on a pivot with a principal axis:
/// ```text
/// longitudinal (axis e_y): u = A + Ry(y)·[0, 0, −l] = A + [−l·sin y, 0, −l·cos y]
/// transversal  (axis e_x): u = A + Rx(y)·[0, 0, −l],  camber γ = y − y_ref
/// ```
/// Member angle `y − y_c` about the axis.
#[derive(Clone, Debug, PartialEq)]
pub struct SwingArm {
    /// Pivot A \[m\].
    pub pivot: [f64; 3],
    /// Arm length l \[m\].
    pub length: f64,
    /// 1 for longitudinal (e_y), 0 for transversal (e_x).
    pub axis: usize,
    /// Rest angle y_c \[rad\].
    pub rest: f64,
    /// Camber at rest, `y_c − y_ref` (transversal), else 0 \[rad\].
    pub camber_rest: f64,
}

impl Linkage for SwingArm {
    fn members(&self) -> Vec<Member> {
        vec![Member {
            name: "arm",
            pivot: self.pivot,
            shares: vec![MemberShare {
                coord: 0,
                axis: Some(self.axis),
            }],
            camber_rest: self.camber_rest,
        }]
    }

    fn points(&self) -> Vec<PointDef> {
        let d = rotate(self.axis, self.rest, [0.0, 0.0, -self.length]);
        vec![PointDef {
            name: "wheel".into(),
            member: 0,
            rest: [
                self.pivot[0] + d[0],
                self.pivot[1] + d[1],
                self.pivot[2] + d[2],
            ],
            wheel: true,
        }]
    }

    fn motion<R: Real>(&self, _member: usize, _coord: usize, y: R) -> Option<([R; 3], R)> {
        Some(([R::cst(0.0); 3], y - R::cst(self.rest)))
    }
}
