//! Contact geometry between a wheel and the terrain (MODEL.md §6, paper §4.1).

mod bounded;
mod math;
mod meridional;
mod patch;
mod tracked;

pub use bounded::{BoundedContact, CROSSING_TOLERANCE, NEGLIGIBLE, SearchMemory};
pub use meridional::{MeridionalContact, RimSampling};
pub use patch::{Contact, MAX_PATCHES, Patch};
pub use tracked::TrackedContact;
