//! The rover body, and the extra masses a suspension carries.

use serde::{Deserialize, Serialize};

use super::Inertia;

/// The rover body (sprung mass), its centre of mass G is the body-frame origin.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyDesc {
    /// Mass m_B \[kg\], > 0.
    pub mass: f64,
    /// Inertia J_B about G [kg·m²].
    pub inertia: Inertia,
}

/// A mass carried by a suspension that is not a wheel (an arm with mass, a
/// hub): either at a named point of the suspension (`point`), or on one of
/// its members (`member`) at a given rest position (`position`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MassDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Mass \[kg\], ≥ 0.
    pub mass: f64,
    /// Inertia about its centre [kg·m²], in the member's frame at rest.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<Inertia>,
    /// The member it moves with (e.g. `arm`, `rocker`, `bogie_left`, `upright`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub member: Option<String>,
    /// Its centre at rest, body components \[m\] (with `member`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// A named point of the suspension (instead of `member` + `position`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point: Option<String>,
}
