//! The built-in rovers, as TOML descriptions (read them with
//! `rover_spec::load_str(text, path)`):
//!
//! - `exomars`: the paper's Example 1 (6 wheels, two longitudinal rockers and
//!   a transversal rocker, 9 DOF);
//! - `swing4`: the paper's Example 2 (4 wheels on longitudinal swing arms,
//!   10 DOF);
//! - `mer`: a MER-type rocker-bogie 6-wheeler (9 DOF);
//! - `lrv`: an LRV-type rover on four double wishbones (10 DOF).
//!
//! Each also has a generated plant (straight-line code written by
//! `rover-codegen` from the same file, `no_std`, no heap): [`Exomars`],
//! [`Swing4`], [`Mer`], [`Lrv`]. [`plant`] gives one by name.
#![warn(missing_docs)]

mod generated;

pub use generated::exomars::Exomars;
pub use generated::lrv::Lrv;
pub use generated::mer::Mer;
pub use generated::swing4::Swing4;
/// Example 2 at fidelity level 3 (MODEL.md §9), frozen at its loaded equilibrium.
pub use generated::swing4_linearized::Swing4Linearized;
/// Example 2 at fidelity level 2 (MODEL.md §9), frozen at its loaded equilibrium.
pub use generated::swing4_simplified::Swing4Simplified;

/// The names of the built-in rovers.
pub const NAMES: &[&str] = &["exomars", "swing4", "mer", "lrv"];

/// The TOML text of a built-in rover.
pub fn builtin(name: &str) -> Option<&'static str> {
    match name {
        "exomars" => Some(include_str!("../exomars.toml")),
        "swing4" => Some(include_str!("../swing4.toml")),
        "mer" => Some(include_str!("../mer.toml")),
        "lrv" => Some(include_str!("../lrv.toml")),
        _ => None,
    }
}

/// The generated plant of a built-in rover, by name (`None` for other
/// names): what the CLI runs for built-in rovers.
pub fn plant(name: &str) -> Option<BuiltinPlant> {
    match name {
        "exomars" => Some(BuiltinPlant::Exomars(Exomars::new())),
        "swing4" => Some(BuiltinPlant::Swing4(Swing4::new())),
        "mer" => Some(BuiltinPlant::Mer(Mer::new())),
        "lrv" => Some(BuiltinPlant::Lrv(Lrv::new())),
        _ => None,
    }
}

/// The generated plant of a built-in rover at a reduced fidelity level
/// (`"simplified"` or `"linearized"`, MODEL.md §9), where one is generated
/// (Example 2); `None` otherwise.
pub fn plant_at(name: &str, level: &str) -> Option<BuiltinPlant> {
    match (name, level) {
        ("swing4", "simplified") => Some(BuiltinPlant::Swing4Simplified(Swing4Simplified::new())),
        ("swing4", "linearized") => Some(BuiltinPlant::Swing4Linearized(Swing4Linearized::new())),
        _ => None,
    }
}

/// One of the generated plants, chosen at run time; each call dispatches
/// with a `match` (no allocation, no virtual call).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BuiltinPlant {
    /// The paper's Example 1.
    Exomars(Exomars),
    /// The paper's Example 2.
    Swing4(Swing4),
    /// The MER-type rocker-bogie.
    Mer(Mer),
    /// The LRV-type rover.
    Lrv(Lrv),
    /// Example 2, fidelity level 2.
    Swing4Simplified(Swing4Simplified),
    /// Example 2, fidelity level 3.
    Swing4Linearized(Swing4Linearized),
}

impl BuiltinPlant {
    /// The generated type's path, for summaries and messages.
    pub fn name(&self) -> &'static str {
        match self {
            BuiltinPlant::Exomars(_) => "rover_models::Exomars",
            BuiltinPlant::Swing4(_) => "rover_models::Swing4",
            BuiltinPlant::Mer(_) => "rover_models::Mer",
            BuiltinPlant::Lrv(_) => "rover_models::Lrv",
            BuiltinPlant::Swing4Simplified(_) => "rover_models::Swing4Simplified",
            BuiltinPlant::Swing4Linearized(_) => "rover_models::Swing4Linearized",
        }
    }
}

rover_dynamics::forward_plant!(BuiltinPlant {
    Exomars,
    Swing4,
    Mer,
    Lrv,
    Swing4Simplified,
    Swing4Linearized,
});

/// The path of a built-in rover's file, relative to the workspace root
/// (for messages).
pub fn builtin_path(name: &str) -> Option<&'static str> {
    match name {
        "exomars" => Some("models/exomars.toml"),
        "swing4" => Some("models/swing4.toml"),
        "mer" => Some("models/mer.toml"),
        "lrv" => Some("models/lrv.toml"),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_has_text_and_path() {
        for name in NAMES {
            let text = builtin(name).expect("text");
            assert!(text.contains(&format!("name = \"{name}\"")));
            let path = builtin_path(name).expect("path");
            let on_disk = std::fs::read_to_string(
                std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("..")
                    .join(path),
            )
            .expect("file");
            assert_eq!(on_disk, text);
        }
        assert_eq!(builtin("nope"), None);
        assert_eq!(builtin_path("nope"), None);
    }
}
