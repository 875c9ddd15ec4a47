//! The whole description.

use serde::{Deserialize, Serialize};

use super::{BodyDesc, SuspensionDesc, WheelDesc, WheelFields};

/// A rover description, as read from TOML (or built in Rust).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Description {
    /// The rover's name.
    pub name: String,
    /// Gravitational acceleration g [m/s²], > 0.
    pub gravity: f64,
    /// The body.
    pub body: BodyDesc,
    /// Values every wheel takes unless it sets its own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wheel_defaults: Option<WheelFields>,
    /// Suspensions, in order: their coordinates are y_1 … y_m in this order.
    #[serde(rename = "suspension", default, skip_serializing_if = "Vec::is_empty")]
    pub suspensions: Vec<SuspensionDesc>,
    /// Wheels, in order (CSV columns follow it).
    #[serde(rename = "wheel", default, skip_serializing_if = "Vec::is_empty")]
    pub wheels: Vec<WheelDesc>,
}

impl Description {
    /// The description as TOML text; reading it back gives an equal value.
    pub fn to_toml_string(&self) -> Result<String, toml::ser::Error> {
        toml::to_string(self)
    }
}
