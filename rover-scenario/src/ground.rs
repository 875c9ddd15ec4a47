//! A scenario's `[terrain]`: the ground's shape (any terrain kind,
//! docs/TERRAIN.md) and, optionally, the soil it is made of
//! (docs/SOIL.md): rigid ground without one.
//!
//! ```toml
//! [terrain]
//! kind = "slope"
//! angle_deg = 10.0
//! soil = "lunar_nominal"      # a built-in soil, or a file with a [soil] table
//!
//! [terrain.soil]              # or the soil's own numbers
//! n = 1.0
//! k_c = 1400.0
//! # …
//! ```

use std::path::Path;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use rover_dynamics::soil::Soil;
use rover_runtime::soil::{SoilConfig, SoilError};
use rover_terrain::{Terrain, TerrainConfig, TerrainError};

/// Where a scenario's soil comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum SoilSpec {
    /// A built-in soil's name, or a TOML file with a `[soil]` table
    /// (relative to the scenario file).
    Named(String),
    /// The soil's numbers, as a `[terrain.soil]` table.
    Table(SoilConfig),
}

/// The `[terrain]` table: the shape, and the soil if the ground is soft.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroundConfig {
    /// The terrain's shape (every key of `[terrain]` but `soil`).
    pub shape: TerrainConfig,
    /// The soil (`soil`), or `None` for rigid ground.
    pub soil: Option<SoilSpec>,
}

impl From<TerrainConfig> for GroundConfig {
    fn from(shape: TerrainConfig) -> Self {
        Self { shape, soil: None }
    }
}

impl GroundConfig {
    /// The terrain, its files relative to `base_dir`.
    pub fn build(&self, base_dir: &Path) -> Result<Terrain, TerrainError> {
        self.shape.build(base_dir)
    }

    /// The soil, checked, its file relative to `base_dir`; `None` for
    /// rigid ground.
    pub fn soil(&self, base_dir: &Path) -> Result<Option<Soil>, SoilError> {
        let config = match &self.soil {
            None => return Ok(None),
            Some(SoilSpec::Table(c)) => *c,
            Some(SoilSpec::Named(name)) => match SoilConfig::builtin(name) {
                Some(c) => c,
                None => {
                    let path = base_dir.join(name);
                    if !path.exists() {
                        return Err(SoilError::Source(format!(
                            "soil = \"{name}\": no built-in soil of that name ({}) and no file {}; give a built-in soil's name, or a TOML file with a [soil] table (relative to the scenario)",
                            rover_runtime::soil::SOIL_NAMES.join(", "),
                            path.display()
                        )));
                    }
                    SoilConfig::named_or_file(&path.to_string_lossy()).map_err(|e| match e {
                        SoilError::Source(m) => {
                            SoilError::Source(format!("soil = \"{name}\": {m}"))
                        }
                        e => e,
                    })?
                }
            },
        };
        config.soil().map(Some)
    }
}

impl<'de> Deserialize<'de> for GroundConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(d)?;
        let soil = match table.remove("soil") {
            None => None,
            Some(toml::Value::String(name)) => Some(SoilSpec::Named(name)),
            Some(v @ toml::Value::Table(_)) => {
                Some(SoilSpec::Table(v.try_into().map_err(|e| {
                    D::Error::custom(format!("terrain.soil: {e}"))
                })?))
            }
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "terrain.soil = {other}: give a built-in soil's name ({}), a TOML file with a [soil] table, or a [terrain.soil] table",
                    rover_runtime::soil::SOIL_NAMES.join(", ")
                )));
            }
        };
        let shape = if table.is_empty() {
            TerrainConfig::default()
        } else {
            toml::Value::Table(table)
                .try_into()
                .map_err(|e| D::Error::custom(format!("terrain: {e}")))?
        };
        Ok(Self { shape, soil })
    }
}

impl Serialize for GroundConfig {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::Error as _;
        let mut value = toml::Value::try_from(&self.shape).map_err(S::Error::custom)?;
        if let (Some(soil), toml::Value::Table(table)) = (&self.soil, &mut value) {
            let soil = match soil {
                SoilSpec::Named(name) => toml::Value::String(name.clone()),
                SoilSpec::Table(c) => toml::Value::try_from(c).map_err(S::Error::custom)?,
            };
            table.insert("soil".into(), soil);
        }
        value.serialize(s)
    }
}
