//! A scenario's `[terrain]`: the ground's shape (any terrain kind,
//! docs/TERRAIN.md) and, optionally, the soils it is made of
//! (docs/SOIL.md): rigid ground without any.
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
//!
//! [terrain.soil_map]          # soils by region: a raster of classes …
//! path = "classes.png"
//! origin = [-5.0, -5.0]
//! spacing = [0.5, 0.5]
//! [terrain.soil_map.classes]
//! 0 = "lunar_nominal"
//! 1 = "dry_sand"
//!
//! [[terrain.soil_patches]]    # … and patches over it, in order
//! shape = "circle"
//! center = [4.0, 0.0]
//! radius = 1.5
//! soil = "dry_sand"
//! edge = 0.2
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use rover_dynamics::soil::Soil;
use rover_runtime::soil::{SOIL_NAMES, SoilConfig, SoilError};
use rover_terrain::{
    Georeference, PatchShape, SoilMap, SoilPatch, Terrain, TerrainConfig, TerrainError,
    read_class_raster,
};

/// Where a soil comes from: the background `soil`, a soil map's class, a
/// patch's `soil`.
#[derive(Clone, Debug, PartialEq)]
pub enum SoilSpec {
    /// A built-in soil's name, or a TOML file with a `[soil]` table
    /// (relative to the scenario file).
    Named(String),
    /// The soil's numbers, as a table (`[terrain.soil]`, or inline).
    Table(SoilConfig),
}

/// `[terrain.soil_map]`: a raster of soil classes, and the soil of each.
#[derive(Clone, Debug, PartialEq)]
pub struct SoilMapConfig {
    /// The raster: a `.csv` matrix or a grayscale `.png` of classes,
    /// relative to the scenario file.
    pub path: PathBuf,
    /// South-west node `[X, Y]` \[m\], for PNG and header-less CSV.
    pub origin: Option<[f64; 2]>,
    /// Node spacing `[dx, dy]` \[m\], with `origin`.
    pub spacing: Option<[f64; 2]>,
    /// `[terrain.soil_map.classes]`: class → soil.
    pub classes: BTreeMap<u16, SoilSpec>,
}

/// One `[[terrain.soil_patches]]`: a soil over a shape.
#[derive(Clone, Debug, PartialEq)]
pub struct SoilPatchConfig {
    /// `shape` and its keys.
    pub shape: PatchShape,
    /// The patch's soil.
    pub soil: SoilSpec,
    /// Width \[m\] of the band, centred on the outline, over which the
    /// patch fades into what lies under it (default 0.1; 0: sharp).
    pub edge: f64,
}

/// A patch's `edge` when it gives none \[m\].
pub const DEFAULT_PATCH_EDGE: f64 = 0.1;

/// The `[terrain]` table: the shape, and the soils if the ground is soft.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroundConfig {
    /// The terrain's shape (every key of `[terrain]` but the soils').
    pub shape: TerrainConfig,
    /// The background soil (`soil`), or `None`.
    pub soil: Option<SoilSpec>,
    /// `ruts`: whether the wheels leave ruts on the soil (default: yes).
    pub ruts: Option<bool>,
    /// `rut_cell`: the side of the ruts' cells \[m\] (default
    /// [`DEFAULT_RUT_CELL`]).
    pub rut_cell: Option<f64>,
    /// A raster of soil classes over the background (`[terrain.soil_map]`).
    pub soil_map: Option<SoilMapConfig>,
    /// Patches over both, bottom to top (`[[terrain.soil_patches]]`).
    pub soil_patches: Vec<SoilPatchConfig>,
}

/// The soils a scenario's ground is made of: each soil with a label for
/// messages and outputs (its name, "class 2", "patch 1"), and the map of
/// where each lies (class = index into `soils`).
#[derive(Clone, Debug)]
pub struct SoilLayout {
    /// The soils, each once (identical soils share a class).
    pub soils: Vec<(String, Soil)>,
    /// Where each lies.
    pub map: SoilMap,
}

/// A soil map or patch that cannot be built; each names the `[terrain]`
/// key at fault, what is wrong and how to fix it.
#[derive(Debug, thiserror::Error)]
pub enum SoilMapError {
    /// A soil (of a class, a patch, the background) that cannot be found or
    /// is outside physics.
    #[error("{}", soil_message(key, source))]
    Soil {
        /// The key that gives it, below `terrain.`: `soil_patches[1].soil`.
        key: String,
        /// What is wrong with it.
        source: SoilError,
    },
    /// The raster file, or a patch's shape (its message names the key).
    #[error("{0}")]
    Terrain(TerrainError),
    /// The layers do not make a ground: a class without a soil, a map
    /// that does not cover the terrain.
    #[error("terrain.{key}: {problem}\n  = help: {help}")]
    Layout {
        /// The key, below `terrain.`.
        key: String,
        /// What is wrong.
        problem: String,
        /// How to fix it.
        help: String,
    },
}

fn soil_message(key: &str, source: &SoilError) -> String {
    match source {
        SoilError::Source(m) => format!("terrain.{key} = {m}"),
        e => format!("terrain.{key}: {e}"),
    }
}

impl SoilMapError {
    /// The scenario key the error is about, as a dotted path.
    pub fn field_path(&self) -> String {
        match self {
            SoilMapError::Soil { key, .. } | SoilMapError::Layout { key, .. } => {
                format!("terrain.{key}")
            }
            SoilMapError::Terrain(TerrainError::Parameter { name, .. }) => {
                format!("terrain.{name}")
            }
            SoilMapError::Terrain(_) => "terrain.soil_map.path".into(),
        }
    }

    fn layout(key: &str, problem: String, help: impl Into<String>) -> Self {
        SoilMapError::Layout {
            key: key.into(),
            problem,
            help: help.into(),
        }
    }
}

/// A terrain error of the soil map or of a patch, its parameter named
/// below `prefix` (`soil_patches[0].`).
fn under(prefix: &str, e: TerrainError) -> SoilMapError {
    SoilMapError::Terrain(match e {
        TerrainError::Parameter {
            name,
            problem,
            help,
        } => TerrainError::Parameter {
            name: if name.starts_with(prefix) {
                name
            } else {
                format!("{prefix}{name}")
            },
            problem,
            help,
        },
        e => e,
    })
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

impl SoilSpec {
    /// The soil, checked, its file relative to `base_dir`. A
    /// [`SoilError::Source`] message starts with the name in quotes, for
    /// the caller to put its key before it.
    pub fn resolve(&self, base_dir: &Path) -> Result<Soil, SoilError> {
        let config = match self {
            SoilSpec::Table(c) => *c,
            SoilSpec::Named(name) => match SoilConfig::builtin(name) {
                Some(c) => c,
                None => {
                    let path = base_dir.join(name);
                    if !path.exists() {
                        return Err(SoilError::Source(format!(
                            "\"{name}\": no built-in soil of that name ({}) and no file {}; give a built-in soil's name, or a TOML file with a [soil] table (relative to the scenario)",
                            SOIL_NAMES.join(", "),
                            path.display()
                        )));
                    }
                    SoilConfig::named_or_file(&path.to_string_lossy()).map_err(|e| match e {
                        SoilError::Source(m) => SoilError::Source(format!("\"{name}\": {m}")),
                        e => e,
                    })?
                }
            },
        };
        config.soil()
    }

    /// The label of the soil in messages and outputs: its name, else
    /// `otherwise`.
    fn label(&self, otherwise: impl FnOnce() -> String) -> String {
        match self {
            SoilSpec::Named(name) => name.clone(),
            SoilSpec::Table(_) => otherwise(),
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
        if !self.is_soft() {
            if self.ruts == Some(true) || self.rut_cell.is_some() {
                return Err(SoilError::Source(
                    "terrain.ruts: ruts need a soil, and this terrain is rigid; give [terrain] a soil (soil = \"dry_sand\", docs/SOIL.md), or leave out ruts and rut_cell".into(),
                ));
            }
            return Ok(None);
        }
        Ok((self.ruts != Some(false)).then_some(self.rut_cell.unwrap_or(DEFAULT_RUT_CELL)))
    }

    /// Whether the ground is soft: a soil, a soil map or soil patches.
    pub fn is_soft(&self) -> bool {
        self.soil.is_some() || self.soil_map.is_some() || !self.soil_patches.is_empty()
    }

    /// The soil, checked, its file relative to `base_dir`; `None` for
    /// rigid ground. A ground of several soils gives its background soil;
    /// without one, an error: such a ground is [`soil_layout`](Self::soil_layout)'s.
    pub fn soil(&self, base_dir: &Path) -> Result<Option<Soil>, SoilError> {
        match &self.soil {
            Some(spec) => spec.resolve(base_dir).map(Some).map_err(|e| match e {
                SoilError::Source(m) => SoilError::Source(format!("soil = {m}")),
                e => e,
            }),
            None if self.is_soft() => Err(SoilError::Source(
                "soil: this ground's soils lie by region (terrain.soil_map, terrain.soil_patches) \
                 over no background soil, and this use of the scenario takes a single soil \
                 (a program reads the regions with GroundConfig::soil_layout)\n  = help: give \
                 [terrain] a background `soil`"
                    .into(),
            )),
            None => Ok(None),
        }
    }

    /// The soils of the ground and where each lies, files relative to
    /// `base_dir`, checked against `terrain`'s extent (a map without a
    /// background soil must cover it); `None` for rigid ground. A single
    /// `soil` is one soil over [`SoilMap::uniform`]`(0)`; the background
    /// soil, when given, is soil 0.
    pub fn soil_layout(
        &self,
        base_dir: &Path,
        terrain: &Terrain,
    ) -> Result<Option<SoilLayout>, SoilMapError> {
        if !self.is_soft() {
            return Ok(None);
        }
        let mut soils: Vec<(String, Soil)> = Vec::new();
        let mut class_of = |label: String, soil: Soil, key: &str| {
            if let Some(k) = soils.iter().position(|(_, s)| *s == soil) {
                return Ok(k as u16);
            }
            let k = u16::try_from(soils.len()).map_err(|_| {
                SoilMapError::layout(
                    key,
                    "the ground has more than 65536 different soils".into(),
                    "use fewer soils",
                )
            })?;
            soils.push((label, soil));
            Ok(k)
        };
        let resolve = |spec: &SoilSpec, key: &str| {
            spec.resolve(base_dir).map_err(|source| SoilMapError::Soil {
                key: key.into(),
                source,
            })
        };

        let background = match &self.soil {
            Some(spec) => {
                let soil = resolve(spec, "soil")?;
                Some(class_of(spec.label(|| "background".into()), soil, "soil")?)
            }
            None => None,
        };
        if background.is_none() && self.soil_map.is_none() {
            return Err(SoilMapError::layout(
                "soil_patches",
                "the soil patches lie over no soil: [terrain] has neither a `soil` nor a \
                 [terrain.soil_map]"
                    .into(),
                "give the ground under the patches a soil: `soil = \"lunar_nominal\"` (a \
                 built-in name, a soil file or a [terrain.soil] table) in [terrain]",
            ));
        }

        let raster = match &self.soil_map {
            None => None,
            Some(m) => {
                let georeference = match (m.origin, m.spacing) {
                    (Some(origin), Some(spacing)) => Some(Georeference { origin, spacing }),
                    (None, None) => None,
                    (Some(_), None) | (None, Some(_)) => {
                        let (key, given) = if m.origin.is_some() {
                            ("soil_map.spacing", "origin")
                        } else {
                            ("soil_map.origin", "spacing")
                        };
                        return Err(SoilMapError::layout(
                            key,
                            format!("{given} is given alone"),
                            "give both origin = [x, y] and spacing = [dx, dy] in \
                             [terrain.soil_map], or neither (a CSV map with an x0,y0,dx,dy \
                             header)",
                        ));
                    }
                };
                let file = read_class_raster(&base_dir.join(&m.path), georeference)
                    .map_err(|e| under("soil_map.", e))?;
                let present = file.raster.classes();
                if let Some(&c) = present.iter().find(|c| !m.classes.contains_key(c)) {
                    let place = file.first_place(c).unwrap_or_default();
                    return Err(SoilMapError::layout(
                        "soil_map.classes",
                        format!(
                            "class {c} of the soil map has no soil; it first appears at {place}"
                        ),
                        format!(
                            "add `{c} = \"dry_sand\"` (a built-in soil's name, a soil file or a \
                             table of the soil's keys) to [terrain.soil_map.classes]"
                        ),
                    ));
                }
                // Every listed class is checked; those the raster holds
                // become soils.
                let mut index = BTreeMap::new();
                for (&c, spec) in &m.classes {
                    let key = format!("soil_map.classes.{c}");
                    let soil = resolve(spec, &key)?;
                    if present.binary_search(&c).is_ok() {
                        index.insert(
                            c,
                            class_of(spec.label(|| format!("class {c}")), soil, &key)?,
                        );
                    }
                }
                if background.is_none() {
                    covers(&file.raster.footprint(), terrain)?;
                }
                Some(
                    file.raster
                        .map_classes(|c| index.get(&c).copied().unwrap_or_default()),
                )
            }
        };

        let mut patches = Vec::with_capacity(self.soil_patches.len());
        for (i, p) in self.soil_patches.iter().enumerate() {
            let key = format!("soil_patches[{i}].soil");
            let soil = resolve(&p.soil, &key)?;
            let class = class_of(p.soil.label(|| format!("patch {i}")), soil, &key)?;
            patches.push(
                SoilPatch::new(p.shape.clone(), class, p.edge)
                    .map_err(|e| under(&format!("soil_patches[{i}]."), e))?,
            );
        }
        let map = match (background, &raster, patches.is_empty()) {
            (Some(b), None, true) => SoilMap::uniform(b),
            _ => SoilMap::new(background, raster, patches).map_err(SoilMapError::Terrain)?,
        };
        Ok(Some(SoilLayout { soils, map }))
    }
}

/// Checks that a soil map's `footprint` covers `terrain` (there is no
/// background soil around it).
fn covers(
    footprint: &rover_dynamics::height_field::Bounds,
    terrain: &Terrain,
) -> Result<(), SoilMapError> {
    let t = terrain.bounds();
    let f = footprint;
    let help = "give [terrain] a background `soil` for the ground off the map, or a soil map \
                that covers the terrain";
    let extent = |b: &rover_dynamics::height_field::Bounds| {
        format!(
            "X [{}, {}], Y [{}, {}] m",
            b.x_min, b.x_max, b.y_min, b.y_max
        )
    };
    if ![t.x_min, t.x_max, t.y_min, t.y_max]
        .iter()
        .all(|v| v.is_finite())
    {
        return Err(SoilMapError::layout(
            "soil",
            format!(
                "the terrain is unbounded and the soil map covers only {}: a background soil \
                 is needed for the ground off the map",
                extent(f)
            ),
            help,
        ));
    }
    if t.x_min < f.x_min || t.x_max > f.x_max || t.y_min < f.y_min || t.y_max > f.y_max {
        return Err(SoilMapError::layout(
            "soil_map",
            format!(
                "the soil map covers {} (its pixels, half a spacing beyond the outer nodes) \
                 and the terrain spans {}, beyond it, with no background soil",
                extent(f),
                extent(&t)
            ),
            help,
        ));
    }
    Ok(())
}

/// A soil reference's value at `key` (below `terrain.`).
fn soil_spec(value: toml::Value, key: &str) -> Result<SoilSpec, String> {
    match value {
        toml::Value::String(name) => Ok(SoilSpec::Named(name)),
        v @ toml::Value::Table(_) => v
            .try_into()
            .map(SoilSpec::Table)
            .map_err(|e| format!("terrain.{key}: {e}")),
        other => {
            let table = if key == "soil" {
                "a [terrain.soil] table".to_string()
            } else {
                "a table of the soil's keys (docs/SOIL.md)".to_string()
            };
            Err(format!(
                "terrain.{key} = {other}: give a built-in soil's name ({}), a TOML file with a [soil] table, or {table}",
                SOIL_NAMES.join(", ")
            ))
        }
    }
}

/// `[terrain.soil_map]`.
fn soil_map(value: toml::Value) -> Result<SoilMapConfig, String> {
    let toml::Value::Table(mut table) = value else {
        return Err(format!(
            "terrain.soil_map = {value}: give a [terrain.soil_map] table with path, origin and \
             spacing (PNG, header-less CSV) and [terrain.soil_map.classes]"
        ));
    };
    let classes = match table.remove("classes") {
        Some(toml::Value::Table(t)) => t,
        Some(other) => {
            return Err(format!(
                "terrain.soil_map.classes = {other}: give a [terrain.soil_map.classes] table, \
                 one `class = soil` line per class of the map (0 = \"lunar_nominal\")"
            ));
        }
        None => {
            return Err(
                "terrain.soil_map has no classes: give each class of the map its soil \
                 in a [terrain.soil_map.classes] table (0 = \"lunar_nominal\", 1 = \"dry_sand\")"
                    .into(),
            );
        }
    };
    let mut by_class = BTreeMap::new();
    for (k, v) in classes {
        let Ok(c) = k.parse::<u16>() else {
            return Err(format!(
                "terrain.soil_map.classes.{k}: `{k}` is not a soil class: the keys are the map's \
                 class numbers, whole numbers 0 … 65535"
            ));
        };
        by_class.insert(c, soil_spec(v, &format!("soil_map.classes.{k}"))?);
    }
    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Keys {
        path: PathBuf,
        #[serde(default)]
        origin: Option<[f64; 2]>,
        #[serde(default)]
        spacing: Option<[f64; 2]>,
    }
    let keys: Keys = toml::Value::Table(table)
        .try_into()
        .map_err(|e| format!("terrain.soil_map: {e}"))?;
    Ok(SoilMapConfig {
        path: keys.path,
        origin: keys.origin,
        spacing: keys.spacing,
        classes: by_class,
    })
}

/// `[[terrain.soil_patches]]`'s `i`-th table.
fn soil_patch(i: usize, value: toml::Value) -> Result<SoilPatchConfig, String> {
    let toml::Value::Table(mut table) = value else {
        return Err(format!(
            "terrain.soil_patches[{i}] = {value}: each patch is a table: \
             [[terrain.soil_patches]] with shape, its keys and soil"
        ));
    };
    let soil = match table.remove("soil") {
        Some(v) => soil_spec(v, &format!("soil_patches[{i}].soil"))?,
        None => {
            return Err(format!(
                "terrain.soil_patches[{i}] has no soil: give the patch's `soil` (a built-in \
                 soil's name, a soil file or a table of the soil's keys)"
            ));
        }
    };
    let edge = match table.remove("edge") {
        None => DEFAULT_PATCH_EDGE,
        Some(toml::Value::Float(e)) => e,
        Some(toml::Value::Integer(e)) => e as f64,
        Some(other) => {
            return Err(format!(
                "terrain.soil_patches[{i}].edge = {other}: give the width of the patch's \
                 blend band in metres, ≥ 0"
            ));
        }
    };
    let shape: PatchShape = toml::Value::Table(table).try_into().map_err(|e| {
        format!(
            "terrain.soil_patches[{i}]: {}\n  = help: a patch is shape = \"circle\" (center, \
             radius), \"rectangle\" (x = [min, max], y = [min, max]) or \"polygon\" (points), \
             with soil and edge",
            e.to_string().trim_end()
        )
    })?;
    // The numbers are checked here, so that a scenario is refused when read.
    SoilPatch::new(shape.clone(), 0, edge).map_err(|e| match e {
        TerrainError::Parameter {
            name,
            problem,
            help,
        } => format!("terrain.soil_patches[{i}].{name}: {problem}\n  = help: {help}"),
        e => e.to_string(),
    })?;
    Ok(SoilPatchConfig { shape, soil, edge })
}

impl<'de> Deserialize<'de> for GroundConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(d)?;
        let soil = table
            .remove("soil")
            .map(|v| soil_spec(v, "soil"))
            .transpose()
            .map_err(D::Error::custom)?;
        let soil_map = table
            .remove("soil_map")
            .map(soil_map)
            .transpose()
            .map_err(D::Error::custom)?;
        let soil_patches = match table.remove("soil_patches") {
            None => Vec::new(),
            Some(toml::Value::Array(items)) => items
                .into_iter()
                .enumerate()
                .map(|(i, v)| soil_patch(i, v))
                .collect::<Result<_, _>>()
                .map_err(D::Error::custom)?,
            Some(other) => {
                return Err(D::Error::custom(format!(
                    "terrain.soil_patches = {other}: give each patch as a [[terrain.soil_patches]] \
                     table"
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
            soil_map,
            soil_patches,
        })
    }
}

fn spec_value(spec: &SoilSpec) -> Result<toml::Value, toml::ser::Error> {
    Ok(match spec {
        SoilSpec::Named(name) => toml::Value::String(name.clone()),
        SoilSpec::Table(c) => toml::Value::try_from(c)?,
    })
}

impl Serialize for GroundConfig {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::Error as _;
        let mut value = toml::Value::try_from(&self.shape).map_err(S::Error::custom)?;
        if let toml::Value::Table(table) = &mut value {
            if let Some(soil) = &self.soil {
                table.insert("soil".into(), spec_value(soil).map_err(S::Error::custom)?);
            }
            if let Some(m) = &self.soil_map {
                let mut map = toml::Table::new();
                map.insert(
                    "path".into(),
                    toml::Value::String(m.path.to_string_lossy().into_owned()),
                );
                for (key, pair) in [("origin", m.origin), ("spacing", m.spacing)] {
                    if let Some(v) = pair {
                        map.insert(
                            key.into(),
                            toml::Value::try_from(v).map_err(S::Error::custom)?,
                        );
                    }
                }
                let mut classes = toml::Table::new();
                for (c, spec) in &m.classes {
                    classes.insert(c.to_string(), spec_value(spec).map_err(S::Error::custom)?);
                }
                map.insert("classes".into(), toml::Value::Table(classes));
                table.insert("soil_map".into(), toml::Value::Table(map));
            }
            if !self.soil_patches.is_empty() {
                let mut patches = Vec::with_capacity(self.soil_patches.len());
                for p in &self.soil_patches {
                    let mut patch = toml::Value::try_from(&p.shape).map_err(S::Error::custom)?;
                    if let toml::Value::Table(t) = &mut patch {
                        t.insert(
                            "soil".into(),
                            spec_value(&p.soil).map_err(S::Error::custom)?,
                        );
                        t.insert("edge".into(), toml::Value::Float(p.edge));
                    }
                    patches.push(patch);
                }
                table.insert("soil_patches".into(), toml::Value::Array(patches));
            }
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
