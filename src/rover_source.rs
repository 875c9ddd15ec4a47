//! Where a rover comes from: a built-in name or a description file.

use std::path::Path;

use rover_spec::{Spec, SpecError};

/// Load a rover by built-in name (`exomars`, `swing4`, `mer`, `lrv`) or by
/// path. Relative paths are taken from `base` (the scenario's directory when
/// the rover is named in a scenario) and then from the working directory.
pub fn load_rover(name_or_path: &str, base: Option<&Path>) -> Result<Spec, SpecError> {
    if let Some(text) = rover_models::builtin(name_or_path) {
        let origin = rover_models::builtin_path(name_or_path).unwrap_or(name_or_path);
        return rover_spec::load_str(text, origin);
    }
    let direct = Path::new(name_or_path);
    let path = match base {
        Some(b) if direct.is_relative() && !direct.exists() => b.join(direct),
        _ => direct.to_path_buf(),
    };
    rover_spec::load_file(&path)
}

/// The names of the built-in rovers, for messages.
pub fn builtin_names() -> String {
    rover_models::NAMES.join(", ")
}
