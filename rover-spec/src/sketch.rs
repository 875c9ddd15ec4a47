//! A drawing of a rover's suspensions: the joints of its linkages (pivots,
//! ball joints, wheel centres) and the members between them, each joint's
//! position a polynomial in the suspension coordinates like the carried
//! bodies' `u_j(y)`, so that a viewer draws the members at any state from
//! the coordinates alone.

use rover_dynamics::poly::PolyVec;

/// The joints and links of every library suspension of a rover.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sketch {
    /// The joints.
    pub joints: Vec<SketchJoint>,
    /// The links (members, or the arms of a member) between joints.
    pub links: Vec<SketchLink>,
}

/// One joint: a point of a member.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchJoint {
    /// Its position from G in body components, `c + Σ_i Σ_p Z_ip·ξ_i^p`,
    /// ξ_i = y_i − y_ic \[m\]: fitted like the carried bodies (the
    /// suspension's `fit` options) from the exact kinematics, or, for a
    /// wheel centre, the wheel's own `u_j(y)`.
    pub position: PolyVec,
    /// The wheel (index in the description's order) whose centre it is.
    pub wheel: Option<usize>,
}

/// A straight link between two joints.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchLink {
    /// The suspension's name.
    pub suspension: String,
    /// The member's name (`arm`, `rocker`, `rocker_left`, `bogie_left`,
    /// `lower_arm`, `upright`, …).
    pub member: String,
    /// The joints it joins (indices into [`Sketch::joints`]).
    pub joints: [usize; 2],
}

impl Sketch {
    /// Every joint's position in body components at coordinates `y` \[m\].
    pub fn positions(&self, y: &[f64]) -> Vec<[f64; 3]> {
        self.joints.iter().map(|j| j.position.value(y)).collect()
    }
}
