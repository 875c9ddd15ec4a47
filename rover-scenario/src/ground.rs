//! A scenario's `[terrain]`: the ground's shape (any terrain kind,
//! docs/TERRAIN.md) and, optionally, the soil it is made of
//! (docs/SOIL.md): rigid ground without one.
//!
//! ```toml
//! [terrain]
//! kind = "slope"
//! angle_deg = 10.0
//! soil = "lunar_nominal"      # a built-in soil, or a file with a [soil] table
//! ruts = true                 # on a soil: the wheels leave ruts (default)
//! rut_cell = 0.02             # the ruts' cell [m] (default 0.02)
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
    /// `ruts`: whether the wheels leave ruts on the soil (default: yes).
    pub ruts: Option<bool>,
    /// `rut_cell`: the side of the ruts' cells \[m\] (default
    /// [`DEFAULT_RUT_CELL`]).
    pub rut_cell: Option<f64>,
}

/// The ruts' cell unless `rut_cell` says otherwise \[m\]: a fifth to a
/// tenth of a rover wheel's width.
pub const DEFAULT_RUT_CELL: f64 = 0.02;

impl From<TerrainConfig> for GroundConfig {
    fn from(shape: TerrainConfig) -> Self {
        Self {
            shape,
            ..Self::default()
        }
    }
}

impl GroundConfig {
    /// The terrain, its files relative to `base_dir`.
    pub fn build(&self, base_dir: &Path) -> Result<Terrain, TerrainError> {
        self.shape.build(base_dir)
    }

    /// The ruts' cell \[m\] when the wheels leave ruts (a soil, and
    /// `ruts` not false), `None` when they do not; a `rut_cell` that is
    /// not a positive length, or ruts asked of rigid ground, is refused.
    pub fn rut_cell(&self) -> Result<Option<f64>, SoilError> {
        if let Some(cell) = self.rut_cell
            && !(cell.is_finite() && cell > 0.0 && cell <= 1.0)
        {
            return Err(SoilError::Source(format!(
                "terrain.rut_cell = {cell}: the side of the ruts' cells must be a length in (0, 1] m; 0.02 (the default) resolves a rover wheel's rut, a tenth of a wheel's width is enough"
            )));
        }
        if self.soil.is_none() {
            if self.ruts == Some(true) || self.rut_cell.is_some() {
                return Err(SoilError::Source(
                    "terrain.ruts: ruts need a soil, and this terrain is rigid; give [terrain] a soil (soil = \"dry_sand\", docs/SOIL.md), or leave out ruts and rut_cell".into(),
                ));
            }
            return Ok(None);
        }
        Ok((self.ruts != Some(false)).then_some(self.rut_cell.unwrap_or(DEFAULT_RUT_CELL)))
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
        let ruts = match table.remove("ruts") {
            None => None,
            Some(toml::Value::Boolean(b)) => Some(b),
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "terrain.ruts = {other}: give true (the wheels leave ruts on the soil, the default) or false (the soil springs back under every wheel)"
                )));
            }
        };
        let rut_cell = match table.remove("rut_cell") {
            None => None,
            Some(toml::Value::Float(x)) => Some(x),
            Some(toml::Value::Integer(i)) => Some(i as f64),
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "terrain.rut_cell = {other}: give the ruts' cell in metres, e.g. 0.02"
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
        Ok(Self {
            shape,
            soil,
            ruts,
            rut_cell,
        })
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
        if let toml::Value::Table(table) = &mut value {
            if let Some(ruts) = self.ruts {
                table.insert("ruts".into(), toml::Value::Boolean(ruts));
            }
            if let Some(cell) = self.rut_cell {
                table.insert("rut_cell".into(), toml::Value::Float(cell));
            }
        }
        value.serialize(s)
    }
}
