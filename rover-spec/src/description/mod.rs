//! The rover description: loose, serde-friendly types that mirror the TOML
//! file one to one (docs/DESCRIPTION.md). Nothing here is checked; see
//! [`crate::validate`].

mod body;
mod coordinate;
mod fit;
mod inertia;
mod rover;
mod suspension;
mod wheel;

pub use body::{BodyDesc, MassDesc};
pub use coordinate::{CoordinateDesc, SpringTableDesc};
pub use fit::{FitDesc, FitMethodDesc};
pub use inertia::Inertia;
pub use rover::Description;
pub use suspension::{
    ArmDesc, DoubleWishboneDesc, MemberDesc, PolyPointDesc, PolyTermDesc, PolynomialDesc,
    RockerBogieDesc, RockerDesc, ScalarPolyDesc, ScalarTermDesc, SuspensionDesc, SwingArmDesc,
    TransversalSwingArmDesc,
};
pub use wheel::{MotorMountDesc, WheelDesc, WheelFields};
