//! The scenario's `[terrain]` table, and building a [`Terrain`] from it.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::bump::Bump;
use super::ditch::Ditch;
use super::error::TerrainError;
use super::file_format::{FileFormat, LoadOptions, load_grid};
use super::flat::Flat;
use super::georeference::Georeference;
use super::grid::{EdgePolicy, Interpolation};
use super::height_field::Bounds;
use super::profile::Footprint;
use super::random_field::RandomField;
use super::sinusoid::Sinusoid;
use super::slope::Slope;
use super::step::Step;
use super::terrain::Terrain;

/// The `[terrain]` table of a scenario, chosen by `kind`. Lengths in metres,
/// angles in degrees (`*_deg`), directions as azimuths from +X towards +Y.
///
/// ```toml
/// [terrain]
/// kind = "random"     # flat | slope | bump | ditch | step | sinusoid | random | file
/// z_r = 0.2
/// seed = 1
/// ```
/// Unknown keys are errors. The default is flat ground at Z = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum TerrainConfig {
    /// Horizontal ground.
    Flat(FlatConfig),
    /// An inclined plane.
    Slope(SlopeConfig),
    /// A raised-cosine bump.
    Bump(BumpConfig),
    /// A trench with cosine walls.
    Ditch(DitchConfig),
    /// A straight step.
    Step(StepConfig),
    /// Sinusoidal corrugations.
    Sinusoid(SinusoidConfig),
    /// The seeded random field of MODEL.md §11.
    Random(RandomConfig),
    /// A height map from a file.
    File(FileConfig),
}

impl Default for TerrainConfig {
    fn default() -> TerrainConfig {
        TerrainConfig::Flat(FlatConfig::default())
    }
}

/// `kind = "flat"`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlatConfig {
    /// Ground height \[m\] (default 0).
    #[serde(default)]
    pub height: f64,
}

/// `kind = "slope"`: see [`Slope`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlopeConfig {
    /// Inclination [°], |angle| < 90.
    pub angle_deg: f64,
    /// Direction of ascent [°] (default 0: rising towards +X).
    #[serde(default)]
    pub direction_deg: f64,
    /// A point of the plane \[m\] (default the origin) ...
    #[serde(default)]
    pub origin: [f64; 2],
    /// ... and its height \[m\] (default 0).
    #[serde(default)]
    pub height: f64,
}

/// `kind = "bump"`: see [`Bump`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BumpConfig {
    /// Height \[m\].
    pub height: f64,
    /// Full width at the base \[m\].
    pub width: f64,
    /// Flat top \[m\] (default 0).
    #[serde(default)]
    pub top_width: f64,
    /// Centre \[m\].
    pub center: [f64; 2],
    /// Direction across the ridge [°] (default 0).
    #[serde(default)]
    pub direction_deg: f64,
    /// `"ridge"` (default) or `"round"`.
    #[serde(default)]
    pub footprint: Footprint,
}

/// `kind = "ditch"`: see [`Ditch`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DitchConfig {
    /// Depth \[m\], > 0.
    pub depth: f64,
    /// Width at ground level \[m\].
    pub width: f64,
    /// Flat floor \[m\] (default 0).
    #[serde(default)]
    pub bottom_width: f64,
    /// Centre \[m\].
    pub center: [f64; 2],
    /// Direction across the trench [°] (default 0).
    #[serde(default)]
    pub direction_deg: f64,
    /// `"ridge"` (default: a straight trench) or `"round"` (a pit).
    #[serde(default)]
    pub footprint: Footprint,
}

/// `kind = "step"`: see [`Step`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepConfig {
    /// Rise \[m\] (negative: a step down).
    pub height: f64,
    /// A point of the step line \[m\].
    pub position: [f64; 2],
    /// Direction in which the ground rises [°] (default 0).
    #[serde(default)]
    pub direction_deg: f64,
    /// Width of the cosine ramp \[m\] (default 0.01; 0 keeps the step sharp).
    #[serde(default = "default_ramp_width")]
    pub ramp_width: f64,
}

fn default_ramp_width() -> f64 {
    0.01
}

/// `kind = "sinusoid"`: see [`Sinusoid`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SinusoidConfig {
    /// Amplitude \[m\].
    pub amplitude: f64,
    /// Wavelength \[m\].
    pub wavelength: f64,
    /// Direction the waves run along [°] (default 0).
    #[serde(default)]
    pub direction_deg: f64,
    /// Phase at the origin [°] (default 0).
    #[serde(default)]
    pub phase_deg: f64,
}

/// `kind = "random"`: see [`RandomField`]; every field but `z_r` has
/// MODEL.md §11's default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RandomConfig {
    /// Roughness scale Z_R (0 … 1 in the paper).
    pub z_r: f64,
    /// Seed (default 1).
    #[serde(default = "default_seed")]
    pub seed: u64,
    /// Random node spacing L \[m\] (default 0.5).
    #[serde(default = "default_node_spacing")]
    pub node_spacing: f64,
    /// Node values uniform in [−a, a] \[m\] (default a = 0.5).
    #[serde(default = "default_node_amplitude")]
    pub node_amplitude: f64,
    /// Terrain grid spacing \[m\] (default 0.05).
    #[serde(default = "default_grid_spacing")]
    pub grid_spacing: f64,
    /// Centre of the flat start patch \[m\] (default the origin).
    #[serde(default)]
    pub patch_center: [f64; 2],
    /// Radius of the flat start patch \[m\] (default 0.3).
    #[serde(default = "default_patch_radius")]
    pub patch_radius: f64,
    /// Blend ring width \[m\] (default 0.5).
    #[serde(default = "default_patch_blend")]
    pub patch_blend: f64,
    /// `[x_min, x_max, y_min, y_max]` \[m\] (default [−20, 20, −20, 20]).
    #[serde(default = "default_extent")]
    pub extent: [f64; 4],
    /// `"bicubic"` (default) or `"bilinear"`.
    #[serde(default)]
    pub interpolation: Interpolation,
    /// `"error"` (default) or `"clamp"`.
    #[serde(default)]
    pub edge: EdgePolicy,
}

fn default_seed() -> u64 {
    RandomField::default().seed
}
fn default_node_spacing() -> f64 {
    RandomField::default().node_spacing
}
fn default_node_amplitude() -> f64 {
    RandomField::default().node_amplitude
}
fn default_grid_spacing() -> f64 {
    RandomField::default().grid_spacing
}
fn default_patch_radius() -> f64 {
    RandomField::default().patch_radius
}
fn default_patch_blend() -> f64 {
    RandomField::default().patch_blend
}
fn default_extent() -> [f64; 4] {
    let e = RandomField::default().extent;
    [e.x_min, e.x_max, e.y_min, e.y_max]
}

impl RandomConfig {
    /// The random field of roughness `z_r` (0 … 1 in the paper) with every
    /// other setting at MODEL.md §11's default, as `kind = "random"` with
    /// only `z_r` reads.
    pub fn new(z_r: f64) -> Self {
        RandomConfig {
            z_r,
            seed: default_seed(),
            node_spacing: default_node_spacing(),
            node_amplitude: default_node_amplitude(),
            grid_spacing: default_grid_spacing(),
            patch_center: [0.0; 2],
            patch_radius: default_patch_radius(),
            patch_blend: default_patch_blend(),
            extent: default_extent(),
            interpolation: Interpolation::default(),
            edge: EdgePolicy::default(),
        }
    }

    /// The same field with another seed.
    pub fn seed(self, seed: u64) -> Self {
        RandomConfig { seed, ..self }
    }

    /// The random field these settings describe.
    pub fn field(&self) -> RandomField {
        let [x_min, x_max, y_min, y_max] = self.extent;
        RandomField {
            z_r: self.z_r,
            seed: self.seed,
            node_spacing: self.node_spacing,
            node_amplitude: self.node_amplitude,
            grid_spacing: self.grid_spacing,
            patch_center: self.patch_center,
            patch_radius: self.patch_radius,
            patch_blend: self.patch_blend,
            extent: Bounds {
                x_min,
                x_max,
                y_min,
                y_max,
            },
            interpolation: self.interpolation,
            edge: self.edge,
        }
    }
}

/// `kind = "file"`: a height map (see the format modules for each layout).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileConfig {
    /// The file; relative to the scenario file's directory.
    pub path: PathBuf,
    /// `"asc"`, `"csv"`, `"png"` or `"geotiff"` (default: from the extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<FileFormat>,
    /// Heights are `offset + scale·value` \[m\]; required for PNG (m per count),
    /// default 1 otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// See `scale` \[m\] (default 0).
    #[serde(default)]
    pub offset: f64,
    /// South-west node `[X, Y]` \[m\], for PNG and header-less CSV.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f64; 2]>,
    /// Node spacing `[dx, dy]` \[m\], with `origin`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<[f64; 2]>,
    /// `"bicubic"` (default) or `"bilinear"`.
    #[serde(default)]
    pub interpolation: Interpolation,
    /// `"error"` (default) or `"clamp"`.
    #[serde(default)]
    pub edge: EdgePolicy,
}

impl TerrainConfig {
    /// MODEL.md §11's random field of roughness `z_r` (0 … 1 in the paper),
    /// every other setting at its default ([`RandomConfig::new`]).
    pub fn random(z_r: f64) -> Self {
        TerrainConfig::Random(RandomConfig::new(z_r))
    }

    /// Builds the terrain; file paths are resolved against `base_dir` (the
    /// scenario file's directory). Every parameter is checked.
    pub fn build(&self, base_dir: &Path) -> Result<Terrain, TerrainError> {
        Ok(match self {
            TerrainConfig::Flat(c) => Terrain::Flat(Flat::new(c.height)?),
            TerrainConfig::Slope(c) => Terrain::Slope(Slope::new(
                c.angle_deg,
                c.direction_deg,
                c.origin,
                c.height,
            )?),
            TerrainConfig::Bump(c) => Terrain::Bump(Bump::new(
                c.height,
                c.width,
                c.top_width,
                c.center,
                c.direction_deg,
                c.footprint,
            )?),
            TerrainConfig::Ditch(c) => Terrain::Ditch(Ditch::new(
                c.depth,
                c.width,
                c.bottom_width,
                c.center,
                c.direction_deg,
                c.footprint,
            )?),
            TerrainConfig::Step(c) => Terrain::Step(Step::new(
                c.height,
                c.position,
                c.direction_deg,
                c.ramp_width,
            )?),
            TerrainConfig::Sinusoid(c) => Terrain::Sinusoid(Sinusoid::new(
                c.amplitude,
                c.wavelength,
                c.direction_deg,
                c.phase_deg,
            )?),
            TerrainConfig::Random(c) => Terrain::Grid(c.field().grid()?),
            TerrainConfig::File(c) => Terrain::Grid(c.load(base_dir)?),
        })
    }
}

/// Largest height a terrain file may hold \[m\], after scale and offset.
pub const MAX_HEIGHT: f64 = 1e6;

impl FileConfig {
    /// Loads the grid, with this table's interpolation and edge policy.
    pub fn load(&self, base_dir: &Path) -> Result<super::grid::Grid, TerrainError> {
        let path = base_dir.join(&self.path);
        if path.is_dir() {
            return Err(TerrainError::parameter(
                "path",
                format!("`{}` is a directory, not a terrain file", path.display()),
                "give the path of a .asc, .csv, .png or .tif file (relative to the scenario file)",
            ));
        }
        if let Some(scale) = self.scale
            && !(scale.is_finite() && scale != 0.0)
        {
            return Err(TerrainError::parameter(
                "scale",
                format!(
                    "scale must be a finite number other than 0, got {scale}: heights are offset + scale·value"
                ),
                "give the metres per unit of the file's values (1 for metres, 0.001 for millimetres)",
            ));
        }
        let format = match self.format {
            Some(format) => format,
            None => FileFormat::from_path(&path)?,
        };
        let georeference = match (self.origin, self.spacing) {
            (Some(origin), Some(spacing)) => Some(Georeference { origin, spacing }),
            (None, None) => None,
            (Some(_), None) => {
                return Err(TerrainError::parameter(
                    "spacing",
                    "origin is given without spacing",
                    "give both origin = [x, y] and spacing = [dx, dy], or neither",
                ));
            }
            (None, Some(_)) => {
                return Err(TerrainError::parameter(
                    "origin",
                    "spacing is given without origin",
                    "give both origin = [x, y] and spacing = [dx, dy], or neither",
                ));
            }
        };
        let options = LoadOptions {
            georeference,
            scale: self.scale,
            offset: self.offset,
        };
        let grid = load_grid(&path, format, options)?;
        let (nx, heights) = (grid.nx(), grid.heights());
        if let Some(k) = heights
            .iter()
            .position(|z| z.is_nan() || z.abs() > MAX_HEIGHT)
        {
            return Err(super::error::FileError::at(
                &path,
                super::error::Place::Whole,
                format!(
                    "the height at node (column {}, row {} from the south) is {:e} m after scale and offset; heights must lie within ±{MAX_HEIGHT:e} m",
                    k % nx + 1,
                    k / nx + 1,
                    heights[k]
                ),
                "check the file's values at that node (a no-data value?) and the scale (metres per unit)",
            ));
        }
        Ok(grid
            .with_interpolation(self.interpolation)
            .with_edge_policy(self.edge))
    }
}
