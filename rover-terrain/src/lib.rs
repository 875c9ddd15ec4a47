//! Terrain height fields for rover contact: the ground height `Z_G(X, Y)`
//! the wheels touch (docs/MODEL.md §6, §11).
//!
//! - Every terrain implements [`rover_dynamics::HeightField`], what the
//!   contact code queries: height and gradient at a point, or an
//!   [`OffMap`](rover_dynamics::height_field::OffMap) error, with no
//!   allocation. The interface is `rover-dynamics`'s (no_std, so that
//!   generated code can name it): users name it from there.
//! - [`Terrain`] is any terrain: the analytic library ([`Flat`], [`Slope`],
//!   [`Bump`], [`Ditch`], [`Step`], [`Sinusoid`], exact and unbounded) or a
//!   [`Grid`] of heights with a C1 Catmull–Rom bicubic (default) or bilinear
//!   interpolant and an [`EdgePolicy`].
//! - [`RandomField`] builds the seeded random terrain `Z_G = Z_R·Z_ran` of
//!   MODEL.md §11 (SplitMix64 node values, see [`prng`]); [`TerrainStatistics`]
//!   gives its RMS height, RMS slope, steepest slope and correlation length.
//! - Files: ESRI ASCII grids ([`asc`]), CSV matrices ([`csv_grid`]), 16-bit PNG
//!   height maps (`png_map`, feature `png`) and GeoTIFF DEMs (`geotiff`,
//!   feature `geotiff`), each with a reader and a writer; corrupt files give
//!   a [`TerrainError`] naming the file, the line (or pixel, or tag), the
//!   problem and the fix. Both features are on by default; a rig that only
//!   needs the contact can leave them (and their decoders) out.
//! - [`RutMap`] is the ground's memory of the wheels that passed: the ruts
//!   they left and how deep they pressed the soil, in sparse tiles.
//! - [`SoilMap`] says which soil classes lie where (a background, a
//!   [`ClassRaster`] read from a CSV or PNG file, [`SoilPatch`]es), as
//!   [`SoilWeights`] continuous in (X, Y).
//! - [`TerrainConfig`] is the scenario's `[terrain]` table;
//!   [`TerrainConfig::build`] checks it and makes the [`Terrain`].
//!
//! `docs/TERRAIN.md` is the long form: formats, the library's formulas, the
//! random field's statistics.

#![warn(missing_docs)]

pub mod asc;
mod bump;
mod config;
pub mod csv_grid;
mod ditch;
mod error;
mod file_format;
mod flat;
mod georeference;
#[cfg(feature = "geotiff")]
pub mod geotiff;
mod grid;
mod height_field;
mod io;
mod kernel;
mod lazy_cells;
mod param;
#[cfg(feature = "png")]
pub mod png_map;
pub mod prng;
mod profile;
mod random_field;
mod range_pyramid;
pub mod ruts;
mod sinusoid;
mod slope;
mod smoothing;
pub mod soil_map;
mod statistics;
mod step;
#[allow(clippy::module_inception)]
mod terrain;

pub use asc::{read_asc, write_asc};
pub use bump::Bump;
pub use config::{
    BumpConfig, DitchConfig, FileConfig, FlatConfig, RandomConfig, SinusoidConfig, SlopeConfig,
    StepConfig, TerrainConfig,
};
pub use csv_grid::{read_csv, write_csv};
pub use ditch::Ditch;
pub use error::{FileError, Place, TerrainError};
pub use file_format::{FileFormat, LoadOptions, load_grid};
pub use flat::Flat;
pub use georeference::Georeference;
#[cfg(feature = "geotiff")]
pub use geotiff::{read_geotiff, write_geotiff};
pub use grid::{EdgePolicy, Grid, Interpolation, MAX_FILE_NODES};
#[cfg(feature = "png")]
pub use png_map::{SampleScale, read_png, write_png};
pub use profile::Footprint;
pub use random_field::RandomField;
pub use ruts::{Footprint as RutFootprint, RutMap, RutSample};
pub use sinusoid::Sinusoid;
pub use slope::Slope;
pub use smoothing::gaussian_sigma;
pub use soil_map::{
    ClassFile, ClassRaster, PatchShape, SoilMap, SoilPatch, SoilWeights, read_class_raster,
};
pub use statistics::TerrainStatistics;
pub use step::Step;
pub use terrain::Terrain;
