//! The seeded random terrain of MODEL.md §11, `Z_G = Z_R·Z_ran`.

use super::error::TerrainError;
use super::grid::{EdgePolicy, Grid, Interpolation};
use super::height_field::{Bounds, HeightField};
use super::param::{finite, non_negative, positive};
use super::prng::{lattice_bits, unit_f64};
use super::statistics::TerrainStatistics;

/// Most nodes a random terrain grid may have (about 400 MB of heights).
const MAX_NODES: usize = 50_000_000;

/// Parameters of the random terrain `Z_G = Z_R·w(r)·Z_ran(X, Y)` (MODEL.md §11).
///
/// - **Nodes.** On the infinite lattice `(i·L, j·L)` (`L = node_spacing`, 0.5 m)
///   node (i, j) holds `u_ij = a·(2·U_ij − 1)`, uniform in `[−a, a]`
///   (`a = node_amplitude`, 0.5 m), `U_ij ∈ [0, 1)` from SplitMix64 keyed by
///   (seed, i, j) (see the `prng` module). Node values are independent.
/// - **Field.** `Z_ran` is the Catmull–Rom bicubic interpolant of the nodes
///   (C1), sampled onto the terrain grid of `grid_spacing` (0.05 m) covering
///   `extent` (default X, Y ∈ [−20, 20] m); the terrain then interpolates that
///   grid (bicubic by default).
/// - **Start patch.** `w(r) = 0` within `patch_radius` (0.3 m) of
///   `patch_center` (the start, default the origin), `w = 1` beyond
///   `patch_radius + patch_blend` (0.5 m more), and the C1 smoothstep
///   `w = σ²(3 − 2σ)`, `σ = (r − R)/B`, between: flat ground at Z = 0 where
///   the rover settles.
///
/// Statistics (lattice averages of the phase-averaged field, `σ² = a²/3` the
/// node variance, `K` the Catmull–Rom kernel, `∫K² = 57/70`, `∫K'² = 7/3`):
/// ```text
/// RMS height         Z_R·a/√3·(57/70)                      = 0.2351·Z_R m      (a = 0.5)
/// RMS slope |∇Z|     Z_R·(a/L)·√(2·(7/3)·(57/70)/3)        = 1.1255·Z_R        (a = L = 0.5)
/// autocorrelation    ρ(τx, τy) = A(τx/L)·A(τy/L)/A(0)²,  A(τ) = ∫K(s)·K(s + τ) ds
/// correlation length ρ = 1/e at τ = 0.784·L                = 0.392 m           (L = 0.5)
/// spectrum           S(kx, ky) = σ²·L²·|K̂(kx·L)|²·|K̂(ky·L)|², mostly below 1/(2L) cycles/m
/// ```
/// So `node_amplitude` sets the RMS height and slope, `node_spacing` the
/// correlation length (and, at fixed amplitude, the slope ∝ a/L).
/// `docs/TERRAIN.md` tabulates [`RandomField::statistics`] for Z_R = 0.1 … 1.
#[derive(Debug, Clone, PartialEq)]
pub struct RandomField {
    /// Roughness scale `Z_R` (dimensionless, ≥ 0; the paper uses 0 … 1).
    pub z_r: f64,
    /// Seed of the node values.
    pub seed: u64,
    /// Lattice spacing `L` of the random nodes \[m\].
    pub node_spacing: f64,
    /// Half-range `a` of the node values \[m\]: uniform in `[−a, a]`.
    pub node_amplitude: f64,
    /// Spacing of the terrain grid the field is sampled onto \[m\].
    pub grid_spacing: f64,
    /// Centre of the flat start patch \[m\].
    pub patch_center: [f64; 2],
    /// Radius of the flat start patch \[m\].
    pub patch_radius: f64,
    /// Width of the ring over which the patch blends into the field \[m\].
    pub patch_blend: f64,
    /// The area the terrain grid covers (the grid may reach up to one
    /// `grid_spacing` beyond `x_max`, `y_max`).
    pub extent: Bounds,
    /// Interpolant of the terrain grid.
    pub interpolation: Interpolation,
    /// Edge policy of the terrain grid.
    pub edge: EdgePolicy,
}

impl Default for RandomField {
    /// MODEL.md §11's defaults with `Z_R = 0.2` and seed 1.
    fn default() -> RandomField {
        RandomField {
            z_r: 0.2,
            seed: 1,
            node_spacing: 0.5,
            node_amplitude: 0.5,
            grid_spacing: 0.05,
            patch_center: [0.0, 0.0],
            patch_radius: 0.3,
            patch_blend: 0.5,
            extent: Bounds {
                x_min: -20.0,
                x_max: 20.0,
                y_min: -20.0,
                y_max: 20.0,
            },
            interpolation: Interpolation::Bicubic,
            edge: EdgePolicy::Error,
        }
    }
}

impl RandomField {
    /// The value `u_ij` \[m\] of lattice node (`i`, `j`), uniform in `[−a, a]`.
    pub fn node_value(&self, i: i64, j: i64) -> f64 {
        self.node_amplitude * (2.0 * unit_f64(lattice_bits(self.seed, i, j)) - 1.0)
    }

    /// The blend weight `w(r)` of the start patch at (`x`, `y`).
    pub fn patch_weight(&self, x: f64, y: f64) -> f64 {
        let (dx, dy) = (x - self.patch_center[0], y - self.patch_center[1]);
        // Past the blend along one axis is past it in distance (hypot ≥ either
        // side, and rounding is monotonic): the same 1 as below without the
        // hypot, which is nearly every node of a large map.
        let far = |d: f64| {
            let excess = d.abs() - self.patch_radius;
            excess > 0.0 && excess >= self.patch_blend
        };
        if far(dx) || far(dy) {
            return 1.0;
        }
        let r = dx.hypot(dy);
        let excess = r - self.patch_radius;
        if excess <= 0.0 {
            0.0
        } else if excess >= self.patch_blend {
            1.0
        } else {
            let s = excess / self.patch_blend;
            s * s * (3.0 - 2.0 * s)
        }
    }

    fn check(&self) -> Result<(), TerrainError> {
        non_negative("z_r", self.z_r, "(dimensionless)")?;
        positive("node_spacing", self.node_spacing, "m")?;
        non_negative("node_amplitude", self.node_amplitude, "m")?;
        positive("grid_spacing", self.grid_spacing, "m")?;
        finite("patch_center[0]", self.patch_center[0], "m")?;
        finite("patch_center[1]", self.patch_center[1], "m")?;
        non_negative("patch_radius", self.patch_radius, "m")?;
        non_negative("patch_blend", self.patch_blend, "m")?;
        let e = &self.extent;
        for (name, value) in [
            ("extent[0]", e.x_min),
            ("extent[1]", e.x_max),
            ("extent[2]", e.y_min),
            ("extent[3]", e.y_max),
        ] {
            finite(name, value, "m")?;
        }
        if !(e.x_max > e.x_min && e.y_max > e.y_min) {
            return Err(TerrainError::parameter(
                "extent",
                format!(
                    "[x_min, x_max, y_min, y_max] must have x_max > x_min and y_max > y_min, \
                     got [{}, {}, {}, {}]",
                    e.x_min, e.x_max, e.y_min, e.y_max
                ),
                "give the area the rover may reach, in metres",
            ));
        }
        Ok(())
    }

    /// Nodes along one side for a span, checked against the size limit.
    fn node_count(span: f64, spacing: f64) -> Option<usize> {
        let cells = (span / spacing - 1e-9).ceil();
        if (1.0..MAX_NODES as f64).contains(&cells) {
            Some(cells as usize + 1)
        } else {
            None
        }
    }

    /// The coarse lattice around the extent, with two nodes of margin so that
    /// every Catmull–Rom stencil inside the extent uses real nodes: the field
    /// is then the interpolant of the infinite lattice, whatever the extent.
    fn lattice(&self) -> Result<Grid, TerrainError> {
        let l = self.node_spacing;
        let e = &self.extent;
        let too_big = || {
            TerrainError::parameter(
                "node_spacing",
                format!("{l} m is too fine for the extent"),
                "use a larger node spacing or a smaller extent",
            )
        };
        let i_min = (e.x_min / l).floor() - 2.0;
        // The terrain grid may reach one grid spacing past x_max, y_max.
        let i_max = ((e.x_max + self.grid_spacing) / l).ceil() + 2.0;
        let j_min = (e.y_min / l).floor() - 2.0;
        let j_max = ((e.y_max + self.grid_spacing) / l).ceil() + 2.0;
        let nx = Self::node_count(i_max - i_min, 1.0).ok_or_else(too_big)?;
        let ny = Self::node_count(j_max - j_min, 1.0).ok_or_else(too_big)?;
        if nx.saturating_mul(ny) > MAX_NODES {
            return Err(too_big());
        }
        let (i0, j0) = (i_min as i64, j_min as i64);
        let mut values = Vec::with_capacity(nx * ny);
        for j in 0..ny as i64 {
            for i in 0..nx as i64 {
                values.push(self.node_value(i0 + i, j0 + j));
            }
        }
        Grid::new([i_min * l, j_min * l], [l, l], nx, ny, values)
    }

    /// The unscaled field `Z_ran` \[m\] at (`x`, `y`) (no patch, no `Z_R`),
    /// evaluated from the lattice directly (the terrain grid samples this).
    /// Builds the lattice over the extent on every call: for many points,
    /// use [`RandomField::grid`].
    pub fn z_ran(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        self.check()?;
        Ok(self.lattice()?.height(x, y)?)
    }

    /// The terrain grid: `Z_R·w·Z_ran` sampled at `grid_spacing` from
    /// (`x_min`, `y_min`) to at least (`x_max`, `y_max`).
    pub fn grid(&self) -> Result<Grid, TerrainError> {
        self.check()?;
        let e = &self.extent;
        let h = self.grid_spacing;
        let too_big = || {
            TerrainError::parameter(
                "grid_spacing",
                format!("{h} m is too fine for the extent (more than {MAX_NODES} nodes)"),
                "use a larger grid spacing or a smaller extent",
            )
        };
        let nx = Self::node_count(e.x_max - e.x_min, h).ok_or_else(too_big)?;
        let ny = Self::node_count(e.y_max - e.y_min, h).ok_or_else(too_big)?;
        if nx.saturating_mul(ny) > MAX_NODES {
            return Err(too_big());
        }
        let lattice = self.lattice()?;
        let xs: Vec<f64> = (0..nx).map(|i| e.x_min + i as f64 * h).collect();
        let ys: Vec<f64> = (0..ny).map(|j| e.y_min + j as f64 * h).collect();
        let mut heights = vec![0.0; nx * ny];
        lattice.sample_lattice(&xs, &ys, |i, j, z_ran| {
            let w = self.patch_weight(xs[i], ys[j]);
            heights[j * nx + i] = if w == 0.0 { 0.0 } else { self.z_r * w * z_ran };
        })?;
        Ok(Grid::new([e.x_min, e.y_min], [h, h], nx, ny, heights)?
            .with_interpolation(self.interpolation)
            .with_edge_policy(self.edge))
    }

    /// Height and slope statistics of the terrain grid (over its nodes).
    pub fn statistics(&self) -> Result<TerrainStatistics, TerrainError> {
        Ok(TerrainStatistics::of_grid(&self.grid()?))
    }
}
