//! Any kind of the library, behind one [`Linkage`].

use crate::linkage::{LinkEnd, Linkage, Member, PointDef};
use crate::real::Real;

use super::{DoubleWishbone, Rocker, RockerBogie, SwingArm};

/// The exact kinematics of a library suspension.
#[derive(Clone, Debug, PartialEq)]
pub enum Kinematics {
    /// Longitudinal or transversal swing arm.
    SwingArm(SwingArm),
    /// Longitudinal or transversal rocker.
    Rocker(Rocker),
    /// Rocker-bogie with differential.
    RockerBogie(RockerBogie),
    /// Double wishbone.
    DoubleWishbone(DoubleWishbone),
}

impl Linkage for Kinematics {
    fn members(&self) -> Vec<Member> {
        match self {
            Kinematics::SwingArm(k) => k.members(),
            Kinematics::Rocker(k) => k.members(),
            Kinematics::RockerBogie(k) => k.members(),
            Kinematics::DoubleWishbone(k) => k.members(),
        }
    }
    fn points(&self) -> Vec<PointDef> {
        match self {
            Kinematics::SwingArm(k) => k.points(),
            Kinematics::Rocker(k) => k.points(),
            Kinematics::RockerBogie(k) => k.points(),
            Kinematics::DoubleWishbone(k) => k.points(),
        }
    }
    fn motion<R: Real>(&self, member: usize, coord: usize, y: R) -> Option<([R; 3], R)> {
        match self {
            Kinematics::SwingArm(k) => k.motion(member, coord, y),
            Kinematics::Rocker(k) => k.motion(member, coord, y),
            Kinematics::RockerBogie(k) => k.motion(member, coord, y),
            Kinematics::DoubleWishbone(k) => k.motion(member, coord, y),
        }
    }
    fn sketch(&self) -> Vec<[LinkEnd; 2]> {
        match self {
            Kinematics::SwingArm(k) => k.sketch(),
            Kinematics::Rocker(k) => k.sketch(),
            Kinematics::RockerBogie(k) => k.sketch(),
            Kinematics::DoubleWishbone(k) => k.sketch(),
        }
    }
}
