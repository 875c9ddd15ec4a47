//! A scenario packed into one folder (an FMU's `resources/`, the C
//! library's scenario folder): `scenario.toml`, every file it names copied
//! beside it under a flat name (the rover's description, terrain maps,
//! soil and command files), and `export.toml`, the export's settings. The
//! exported library reads nothing else, so the folder can travel.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rover_scenario::prepare::Prepared;

use crate::error::ExportError;
use crate::variables::Inputs;

/// The packed scenario's file name.
pub const SCENARIO_FILE: &str = "scenario.toml";
/// The export's settings' file name.
pub const SETTINGS_FILE: &str = "export.toml";

/// What the exported library needs besides the scenario.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExportSettings {
    /// The inputs the plant takes.
    pub inputs: Inputs,
    /// The FMU's instantiation token (FMI 2's GUID): an importer that
    /// gives another one instantiates another FMU's description.
    pub token: String,
}

impl ExportSettings {
    /// The settings as `export.toml` holds them.
    pub fn to_toml(&self) -> String {
        let inputs = match self.inputs {
            Inputs::None => "none",
            Inputs::Torques => "torques",
        };
        format!(
            "# Written by `rover export`: what the plant library reads besides scenario.toml.\ninputs = \"{inputs}\"\ntoken = \"{}\"\n",
            self.token
        )
    }

    /// Read `dir`'s `export.toml`.
    pub fn read(dir: &Path) -> Result<Self, String> {
        let path = dir.join(SETTINGS_FILE);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("{}: cannot read the export's settings: {e}", path.display()))?;
        let table: toml::Table = text
            .parse()
            .map_err(|e| format!("{}: not the export's settings: {e}", path.display()))?;
        let inputs = match table.get("inputs").and_then(|v| v.as_str()) {
            Some("none") => Inputs::None,
            Some("torques") => Inputs::Torques,
            other => {
                return Err(format!(
                    "{}: inputs = {other:?}: expected \"none\" or \"torques\"",
                    path.display()
                ));
            }
        };
        let token = table
            .get("token")
            .and_then(|v| v.as_str())
            .unwrap_or_default()
            .to_string();
        Ok(ExportSettings { inputs, token })
    }
}

/// A scenario packed by [`pack`].
#[derive(Debug)]
pub struct Packed {
    /// The scenario as read from its own place (checked: it runs).
    pub prepared: Prepared,
    /// The settings written.
    pub settings: ExportSettings,
    /// The files written into the folder, by name.
    pub files: Vec<String>,
}

/// Pack the scenario file `scenario` (its rover overridden by `rover`, a
/// built-in name or a description file) into `dir`, which is created. A
/// built-in rover stays a name (the library holds its generated plant);
/// a description file is copied as `rover.toml`. Every string of the
/// scenario that names an existing file relative to the scenario's folder
/// is copied and renamed.
pub fn pack(
    rover: Option<&str>,
    scenario: &Path,
    dir: &Path,
    inputs: Inputs,
) -> Result<Packed, ExportError> {
    let prepared =
        Prepared::from_file(rover, scenario).map_err(|e| ExportError::Prepare(Box::new(e)))?;
    // It must run: a scenario that cannot start fails here, not in the
    // importer.
    prepared
        .stepper(false)
        .map_err(|e| ExportError::Prepare(Box::new(e)))?;
    let mut table: toml::Table = prepared
        .text
        .parse()
        .map_err(|e| ExportError::Usage(format!("{}: {e}", scenario.display())))?;
    std::fs::create_dir_all(dir).map_err(|e| ExportError::io(dir, "create the folder", e))?;
    let mut copies: BTreeMap<String, PathBuf> = BTreeMap::new();
    let base = prepared.base.clone();
    // The rover: a built-in name, or a file relative to the working
    // directory (named on the command line) or to the scenario.
    let rover_value = if rover_models::builtin(&prepared.rover).is_some() {
        prepared.rover.clone()
    } else {
        let direct = PathBuf::from(&prepared.rover);
        let path = if rover.is_some() || direct.is_absolute() || direct.exists() {
            direct
        } else {
            base.join(direct)
        };
        copies.insert("rover.toml".into(), path);
        "rover.toml".into()
    };
    table.remove("rover");
    rewrite_files(&mut table, &base, &mut copies);
    table.insert("rover".into(), toml::Value::String(rover_value));
    let mut files = Vec::new();
    for (name, source) in &copies {
        let to = dir.join(name);
        std::fs::copy(source, &to)
            .map_err(|e| ExportError::io(source, "copy into the export", e))?;
        files.push(name.clone());
    }
    let text = format!(
        "# Packed by `rover export` from {}: the files it names copied beside it.\n{}",
        scenario.display(),
        toml::to_string(&table).map_err(|e| ExportError::Usage(e.to_string()))?
    );
    let settings = ExportSettings {
        inputs,
        token: token_of(&text, inputs),
    };
    write(&dir.join(SCENARIO_FILE), text.as_bytes())?;
    write(&dir.join(SETTINGS_FILE), settings.to_toml().as_bytes())?;
    files.push(SCENARIO_FILE.into());
    files.push(SETTINGS_FILE.into());
    // The packed folder must give the same run.
    Prepared::from_file(None, &dir.join(SCENARIO_FILE))
        .and_then(|p| p.stepper(false).map(|_| ()))
        .map_err(|e| ExportError::Prepare(Box::new(e)))?;
    Ok(Packed {
        prepared,
        settings,
        files,
    })
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    std::fs::write(path, bytes).map_err(|e| ExportError::io(path, "write", e))
}

/// Each string of `table` naming a file relative to `base` (or absolute)
/// is replaced by a flat name, recorded in `copies`.
fn rewrite_files(table: &mut toml::Table, base: &Path, copies: &mut BTreeMap<String, PathBuf>) {
    for (_, value) in table.iter_mut() {
        rewrite_value(value, base, copies);
    }
}

fn rewrite_value(value: &mut toml::Value, base: &Path, copies: &mut BTreeMap<String, PathBuf>) {
    match value {
        toml::Value::String(s) => {
            let path = base.join(&*s);
            if s.is_empty() || !path.is_file() {
                return;
            }
            if let Some((name, _)) = copies.iter().find(|(_, p)| **p == path) {
                *s = name.clone();
                return;
            }
            let file = path
                .file_name()
                .map(|f| f.to_string_lossy().into_owned())
                .unwrap_or_else(|| "file".into());
            let mut name = file.clone();
            let mut k = 2;
            while copies.contains_key(&name) || name == SCENARIO_FILE || name == SETTINGS_FILE {
                name = format!("{k}_{file}");
                k += 1;
            }
            copies.insert(name.clone(), path);
            *s = name;
        }
        toml::Value::Array(items) => {
            for v in items {
                rewrite_value(v, base, copies);
            }
        }
        toml::Value::Table(t) => rewrite_files(t, base, copies),
        _ => {}
    }
}

/// A token that changes with the packed scenario and the inputs, in FMI's
/// GUID shape.
fn token_of(text: &str, inputs: Inputs) -> String {
    let mut h = crc32fast::Hasher::new();
    h.update(text.as_bytes());
    let a = h.clone().finalize();
    h.update(format!("{inputs:?}").as_bytes());
    let b = h.clone().finalize();
    h.update(b"rover-export");
    let c = h.finalize();
    format!(
        "{{{a:08x}-{:04x}-{:04x}-{:04x}-{c:08x}{:04x}}}",
        b >> 16,
        b & 0xffff,
        c >> 16,
        a & 0xffff
    )
}
