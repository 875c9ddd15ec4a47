//! The MER-type rocker-bogie with a differential (MODEL.md §3).

use crate::linkage::{LinkEnd, Linkage, Member, MemberShare, PointDef};
use crate::real::{Real, rotate};

/// Rocker-bogie, both sides. Local coordinates: 0 = rocker angle y_r (left
/// side; the differential turns the right rocker by −y_r), 1 = left bogie
/// angle, 2 = right bogie angle, both relative to the body:
/// ```text
/// front = A + Ry(±(y_r − y_rc))·(F − A)
/// P     = A + Ry(±(y_r − y_rc))·(P_c − A)           bogie pivot
/// mid   = P + Ry(y_b − y_bc)·(M − P_c),  rear likewise
/// ```
/// Choosing the bogie's angle relative to the body keeps each u_j a sum of
/// one-coordinate terms; 6 wheels, 3 coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct RockerBogie {
    /// Left rocker pivot A \[m\].
    pub pivot: [f64; 3],
    /// Left front wheel at rest \[m\].
    pub front: [f64; 3],
    /// Left bogie pivot at rest \[m\].
    pub bogie_pivot: [f64; 3],
    /// Left middle wheel at rest \[m\].
    pub middle: [f64; 3],
    /// Left rear wheel at rest \[m\].
    pub rear: [f64; 3],
    /// Rest values of y_r, left bogie, right bogie \[rad\].
    pub rest: [f64; 3],
}

/// Mirror a left-side point to the right side.
fn mirror(p: [f64; 3]) -> [f64; 3] {
    [p[0], -p[1], p[2]]
}

impl Linkage for RockerBogie {
    fn members(&self) -> Vec<Member> {
        let turn = |c| MemberShare {
            coord: c,
            axis: Some(1),
        };
        vec![
            Member {
                name: "rocker_left",
                pivot: self.pivot,
                shares: vec![turn(0)],
                camber_rest: 0.0,
            },
            Member {
                name: "rocker_right",
                pivot: mirror(self.pivot),
                shares: vec![turn(0)],
                camber_rest: 0.0,
            },
            Member {
                name: "bogie_left",
                pivot: self.bogie_pivot,
                shares: vec![
                    MemberShare {
                        coord: 0,
                        axis: None,
                    },
                    turn(1),
                ],
                camber_rest: 0.0,
            },
            Member {
                name: "bogie_right",
                pivot: mirror(self.bogie_pivot),
                shares: vec![
                    MemberShare {
                        coord: 0,
                        axis: None,
                    },
                    turn(2),
                ],
                camber_rest: 0.0,
            },
        ]
    }

    fn points(&self) -> Vec<PointDef> {
        let p = |name: &str, member, rest| PointDef {
            name: name.into(),
            member,
            rest,
            wheel: true,
        };
        vec![
            p("front_left", 0, self.front),
            p("middle_left", 2, self.middle),
            p("rear_left", 2, self.rear),
            p("front_right", 1, mirror(self.front)),
            p("middle_right", 3, mirror(self.middle)),
            p("rear_right", 3, mirror(self.rear)),
        ]
    }

    fn motion<R: Real>(&self, member: usize, coord: usize, y: R) -> Option<([R; 3], R)> {
        let zero = [R::cst(0.0); 3];
        let rocker = y - R::cst(self.rest[0]);
        Some(match (member, coord) {
            (0, _) => (zero, rocker),
            (1, _) => (zero, -rocker),
            (2 | 3, 0) => {
                let (angle, a, p) = if member == 2 {
                    (rocker, self.pivot, self.bogie_pivot)
                } else {
                    (-rocker, mirror(self.pivot), mirror(self.bogie_pivot))
                };
                let rel = [
                    R::cst(p[0] - a[0]),
                    R::cst(p[1] - a[1]),
                    R::cst(p[2] - a[2]),
                ];
                let moved = rotate(1, angle, rel);
                (
                    [moved[0] - rel[0], moved[1] - rel[1], moved[2] - rel[2]],
                    R::cst(0.0),
                )
            }
            (_, c) => (zero, y - R::cst(self.rest[c.min(2)])),
        })
    }

    /// Each rocker from its pivot to its front wheel and to its bogie's
    /// pivot; each bogie from its pivot to its middle and rear wheels.
    fn sketch(&self) -> Vec<[LinkEnd; 2]> {
        let end = |member, rest| LinkEnd { member, rest };
        let mut links = Vec::new();
        for (side, (rocker, bogie)) in [(0, 2), (1, 3)].into_iter().enumerate() {
            let m = |p: [f64; 3]| if side == 0 { p } else { mirror(p) };
            let (a, p) = (m(self.pivot), m(self.bogie_pivot));
            links.push([end(rocker, a), end(rocker, m(self.front))]);
            links.push([end(rocker, a), end(rocker, p)]);
            links.push([end(bogie, p), end(bogie, m(self.middle))]);
            links.push([end(bogie, p), end(bogie, m(self.rear))]);
        }
        links
    }
}
