//! Terrain: interpolants, library, random field, file formats, config.

use std::path::{Path, PathBuf};

use rover_terrain::*;

// ---------------------------------------------------------------- helpers

/// A scratch file path under Cargo's per-target temporary directory.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("terrain");
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir.join(name)
}

/// Writes `text` to a scratch file and returns its path.
fn file(name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = scratch(name);
    std::fs::write(&path, bytes).expect("write scratch file");
    path
}

/// A deterministic pseudo-random grid (heights in [−0.5, 0.5] m).
fn bumpy_grid(nx: usize, ny: usize) -> Grid {
    let mut g = prng::SplitMix64::new(7);
    let heights = (0..nx * ny).map(|_| g.next_f64() - 0.5).collect();
    Grid::new([-1.0, 2.0], [0.25, 0.4], nx, ny, heights).unwrap()
}

fn h(t: &impl HeightField, x: f64, y: f64) -> f64 {
    t.height(x, y).unwrap()
}

fn hg(t: &impl HeightField, x: f64, y: f64) -> (f64, [f64; 2]) {
    t.height_gradient(x, y).unwrap()
}

/// Central finite-difference gradient.
fn fd_gradient(t: &impl HeightField, x: f64, y: f64, step: f64) -> [f64; 2] {
    [
        (h(t, x + step, y) - h(t, x - step, y)) / (2.0 * step),
        (h(t, x, y + step) - h(t, x, y - step)) / (2.0 * step),
    ]
}

fn assert_close(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual}, expected {expected} (tolerance {tol})"
    );
}

/// The error's full message.
fn message<T: std::fmt::Debug>(result: Result<T, TerrainError>) -> String {
    result.expect_err("expected an error").to_string()
}

// ---------------------------------------------------------------- interface

#[test]
fn terrain_is_send_sync_clone_and_defaults_to_flat_zero() {
    fn assert_traits<T: Send + Sync + Clone + 'static>() {}
    assert_traits::<Terrain>();
    assert_traits::<OffMap>();
    let t = Terrain::default();
    assert_eq!(hg(&t, 123.0, -4.0), (0.0, [0.0, 0.0]));
    let built = TerrainConfig::default().build(Path::new(".")).unwrap();
    assert_eq!(built, Terrain::default());
}

// ---------------------------------------------------------------- interpolants

#[test]
fn both_interpolants_pass_through_the_nodes() {
    for interpolation in [Interpolation::Bicubic, Interpolation::Bilinear] {
        let g = bumpy_grid(6, 5).with_interpolation(interpolation);
        let [x0, y0] = g.origin();
        let [dx, dy] = g.spacing();
        for j in 0..g.ny() {
            for i in 0..g.nx() {
                let z = h(&g, x0 + i as f64 * dx, y0 + j as f64 * dy);
                assert_close(z, g.node(i, j).unwrap(), 1e-15, "node height");
            }
        }
    }
}

#[test]
fn bicubic_is_exact_for_a_quadratic_up_to_the_edges() {
    let q = |x: f64, y: f64| 1.0 + 0.3 * x - 0.2 * y + 0.05 * x * x + 0.02 * x * y - 0.04 * y * y;
    let dq = |x: f64, y: f64| [0.3 + 0.1 * x + 0.02 * y, -0.2 + 0.02 * x - 0.08 * y];
    let g = Grid::from_fn([-1.0, 2.0], [0.25, 0.4], 7, 5, q).unwrap();
    let b = g.bounds();
    for a in 0..=24 {
        for c in 0..=16 {
            let x = b.x_min + (b.x_max - b.x_min) * f64::from(a) / 24.0;
            let y = b.y_min + (b.y_max - b.y_min) * f64::from(c) / 16.0;
            let (z, grad) = hg(&g, x, y);
            assert_close(z, q(x, y), 1e-13, "quadratic height");
            assert_close(grad[0], dq(x, y)[0], 1e-12, "quadratic ∂Z/∂X");
            assert_close(grad[1], dq(x, y)[1], 1e-12, "quadratic ∂Z/∂Y");
        }
    }
}

#[test]
fn bilinear_is_exact_for_a_plane_and_not_for_a_quadratic() {
    let plane = |x: f64, y: f64| 0.5 - 0.7 * x + 0.25 * y;
    let g = Grid::from_fn([0.0, 0.0], [0.5, 0.3], 5, 4, plane)
        .unwrap()
        .with_interpolation(Interpolation::Bilinear);
    for (x, y) in [(0.1, 0.05), (1.23, 0.77), (2.0, 0.9), (0.75, 0.45)] {
        let (z, grad) = hg(&g, x, y);
        assert_close(z, plane(x, y), 1e-14, "plane height");
        assert_close(grad[0], -0.7, 1e-13, "plane ∂Z/∂X");
        assert_close(grad[1], 0.25, 1e-13, "plane ∂Z/∂Y");
    }
    // The bilinear interpolant misses a quadratic between nodes (so the
    // bicubic test above can tell the two apart).
    let g = Grid::from_fn([0.0, 0.0], [1.0, 1.0], 3, 3, |x, _| x * x)
        .unwrap()
        .with_interpolation(Interpolation::Bilinear);
    assert_close(h(&g, 0.5, 0.5), 0.5, 1e-15, "bilinear x² at 0.5");
}

#[test]
fn bicubic_gradient_is_continuous_across_cell_edges_and_bilinear_is_not() {
    let g = bumpy_grid(8, 7);
    let [x0, y0] = g.origin();
    let [dx, dy] = g.spacing();
    let eps = 1e-9;
    let mut bilinear_jump: f64 = 0.0;
    let lin = g.clone().with_interpolation(Interpolation::Bilinear);
    for i in 1..g.nx() - 1 {
        for frac in [0.17, 0.5, 0.83] {
            // Across the vertical edge X = x0 + i·dx.
            let (x, y) = (x0 + i as f64 * dx, y0 + (2.0 + frac) * dy);
            let (_, left) = hg(&g, x - eps, y);
            let (_, right) = hg(&g, x + eps, y);
            for k in 0..2 {
                assert_close(left[k], right[k], 1e-6, "bicubic gradient across X edge");
            }
            bilinear_jump =
                bilinear_jump.max((hg(&lin, x - eps, y).1[0] - hg(&lin, x + eps, y).1[0]).abs());
        }
    }
    for j in 1..g.ny() - 1 {
        let (x, y) = (x0 + 3.4 * dx, y0 + j as f64 * dy);
        let (_, below) = hg(&g, x, y - eps);
        let (_, above) = hg(&g, x, y + eps);
        for k in 0..2 {
            assert_close(below[k], above[k], 1e-6, "bicubic gradient across Y edge");
        }
    }
    assert!(
        bilinear_jump > 0.1,
        "bilinear gradient should jump, max jump {bilinear_jump}"
    );
}

#[test]
fn grid_gradients_match_finite_differences() {
    for interpolation in [Interpolation::Bicubic, Interpolation::Bilinear] {
        let g = bumpy_grid(9, 9).with_interpolation(interpolation);
        let [x0, y0] = g.origin();
        let [dx, dy] = g.spacing();
        let mut r = prng::SplitMix64::new(3);
        for _ in 0..200 {
            // Interior points away from cell edges (bilinear kinks there).
            let x = x0 + dx * (1.0 + (r.next_f64() * 6.0).floor() + 0.1 + 0.8 * r.next_f64());
            let y = y0 + dy * (1.0 + (r.next_f64() * 6.0).floor() + 0.1 + 0.8 * r.next_f64());
            let (_, grad) = hg(&g, x, y);
            let fd = fd_gradient(&g, x, y, 1e-6);
            assert_close(grad[0], fd[0], 1e-6, "∂Z/∂X vs finite difference");
            assert_close(grad[1], fd[1], 1e-6, "∂Z/∂Y vs finite difference");
        }
    }
}

#[test]
fn leaving_the_map_is_an_off_map_error_with_a_clear_message() {
    let g = Grid::from_fn([0.0, -5.0], [0.5, 0.5], 21, 21, |x, y| x + y).unwrap();
    for (x, y) in [(-0.001, 0.0), (10.001, 0.0), (5.0, -5.001), (5.0, 5.001)] {
        let e = g.height(x, y).unwrap_err();
        assert_eq!((e.x, e.y), (x, y));
        assert_eq!(
            e.bounds,
            Bounds {
                x_min: 0.0,
                x_max: 10.0,
                y_min: -5.0,
                y_max: 5.0
            }
        );
        assert_eq!(g.height_gradient(x, y).unwrap_err(), e);
    }
    // The edges themselves are on the map, as `bounds()` reports them.
    assert_close(h(&g, 10.0, 5.0), 15.0, 1e-12, "corner height");
    // (−1.3 + 24·0.1 + 1.3)/0.1 = 24.000000000000004 in floating point.
    let odd = Grid::from_fn([-1.3, 0.7], [0.1, 0.07], 25, 23, |x, y| x - y).unwrap();
    let b = odd.bounds();
    for (x, y) in [
        (b.x_min, b.y_min),
        (b.x_max, b.y_max),
        (b.x_max, b.y_min),
        (b.x_min, b.y_max),
    ] {
        assert_close(h(&odd, x, y), x - y, 1e-12, "corner of an odd grid");
    }
    assert!(odd.height(b.x_max + 1e-6, b.y_max).is_err());
    assert_eq!(
        g.height(12.5, 0.0).unwrap_err().to_string(),
        "point (X = 12.5 m, Y = 0 m) is off the terrain map, which covers X from 0 m to 10 m \
         and Y from -5 m to 5 m; make the terrain larger or set edge = \"clamp\" to hold the \
         edge height beyond it"
    );
    // Non-finite queries never produce a height, on any terrain.
    let nan = g.height(f64::NAN, 0.0).unwrap_err();
    assert_eq!(
        nan.to_string(),
        "terrain queried at a non-finite point (X = NaN m, Y = 0 m); the state has diverged \
         before the contact search"
    );
    let clamped = g.clone().with_edge_policy(EdgePolicy::Clamp);
    assert!(clamped.height(f64::NAN, 0.0).is_err());
    assert!(clamped.height(0.0, f64::INFINITY).is_err());
    for t in library() {
        assert!(t.height(f64::NAN, 1.0).is_err(), "{t:?}");
        assert!(t.height_gradient(1.0, f64::NEG_INFINITY).is_err(), "{t:?}");
    }
}

#[test]
fn clamp_policy_holds_the_edge_height_with_zero_normal_slope() {
    let g = Grid::from_fn([0.0, 0.0], [1.0, 1.0], 4, 4, |x, y| 0.1 * x + 0.2 * y)
        .unwrap()
        .with_edge_policy(EdgePolicy::Clamp);
    let (z, grad) = hg(&g, 7.0, 1.5);
    assert_close(z, 0.3 + 0.3, 1e-14, "clamped east height");
    assert_close(grad[0], 0.0, 0.0, "clamped ∂Z/∂X");
    assert_close(grad[1], 0.2, 1e-14, "unclamped ∂Z/∂Y");
    let (z, grad) = hg(&g, -2.0, -9.0);
    assert_eq!((z, grad), (0.0, [0.0, 0.0]));
    assert_eq!(Terrain::Grid(g).bounds(), Bounds::UNBOUNDED);
}

#[test]
fn grid_constructor_rejects_bad_grids() {
    assert_eq!(
        message(Grid::new([0.0, 0.0], [0.0, 1.0], 2, 2, vec![0.0; 4])),
        "terrain.spacing[0]: the grid spacing must be > 0 m, got 0\n  = help: give the \
         distance between neighbouring nodes in metres"
    );
    assert_eq!(
        message(Grid::new([0.0, 0.0], [1.0, 1.0], 2, 2, vec![0.0; 3])),
        "terrain.grid: 2 × 2 nodes need 4 heights, got 3\n  = help: give one height per \
         node, south row first, west to east"
    );
    assert_eq!(
        message(Grid::new(
            [0.0, 0.0],
            [1.0, 1.0],
            2,
            2,
            vec![0.0, 1.0, f64::NAN, 0.0]
        )),
        "terrain.grid: the height at node (i = 0, j = 1) is NaN, not a finite number\n  = \
         help: every node needs a finite height in metres"
    );
    assert_eq!(
        message(Grid::new([0.0, 0.0], [1.0, 1.0], 1, 4, vec![0.0; 4])),
        "terrain.grid: a grid needs at least 2 × 2 nodes, got 1 × 4\n  = help: interpolation \
         needs a node on each side of every cell"
    );
}

// ---------------------------------------------------------------- library

fn library() -> Vec<Terrain> {
    vec![
        Terrain::Flat(Flat::new(0.25).unwrap()),
        Terrain::Slope(Slope::new(10.0, 30.0, [1.0, 2.0], 0.5).unwrap()),
        Terrain::Bump(Bump::new(0.1, 0.6, 0.2, [1.0, 0.5], 20.0, Footprint::Ridge).unwrap()),
        Terrain::Bump(Bump::new(0.1, 0.6, 0.0, [1.0, 0.5], 0.0, Footprint::Round).unwrap()),
        Terrain::Ditch(Ditch::new(0.08, 0.5, 0.1, [2.0, 0.0], -45.0, Footprint::Ridge).unwrap()),
        Terrain::Step(Step::new(0.05, [1.0, 1.0], 135.0, 0.02).unwrap()),
        Terrain::Sinusoid(Sinusoid::new(0.03, 0.8, 60.0, 15.0).unwrap()),
    ]
}

#[test]
fn library_terrains_have_their_documented_heights() {
    let t = Terrain::Flat(Flat::new(0.25).unwrap());
    assert_eq!(hg(&t, -3.0, 8.0), (0.25, [0.0, 0.0]));

    // Slope: 10° rising towards 90° (+Y) through (1, 2) at 0.5 m.
    let t = Slope::new(10.0, 90.0, [1.0, 2.0], 0.5).unwrap();
    let tan = 10f64.to_radians().tan();
    assert_close(h(&t, 1.0, 3.0), 0.5 + tan, 1e-15, "slope one metre up");
    assert_close(h(&t, 7.0, 2.0), 0.5, 1e-15, "slope across");
    assert_close(hg(&t, 0.0, 0.0).1[0], 0.0, 1e-16, "slope ∂Z/∂X");
    assert_close(hg(&t, 0.0, 0.0).1[1], tan, 1e-16, "slope ∂Z/∂Y");
    // Any direction: 20° towards 225° descends towards +X and +Y.
    let t = Slope::new(20.0, 225.0, [0.0, 0.0], 0.0).unwrap();
    let d = 20f64.to_radians().tan() / 2f64.sqrt();
    assert_close(h(&t, 1.0, 1.0), -2.0 * d, 1e-15, "diagonal slope");

    // Bump, ridge across X, 0.1 m high, 0.6 m base, no top: h(1+cos(2πs/w))/2.
    let t = Bump::new(0.1, 0.6, 0.0, [1.0, 0.5], 0.0, Footprint::Ridge).unwrap();
    assert_close(h(&t, 1.0, -7.0), 0.1, 1e-16, "bump crest");
    assert_close(h(&t, 1.15, 3.0), 0.05, 1e-15, "bump mid-flank");
    assert_close(h(&t, 0.85, 3.0), 0.05, 1e-15, "bump mid-flank, other side");
    assert_eq!(h(&t, 1.3, 0.0), 0.0);
    assert_eq!(h(&t, 0.6, 0.0), 0.0);
    let steepest = 0.1 * std::f64::consts::PI / 0.6;
    assert_close(
        hg(&t, 1.15, 0.0).1[0],
        -steepest,
        1e-14,
        "bump steepest slope",
    );
    // With a flat top of 0.2 m.
    let t = Bump::new(0.1, 0.6, 0.2, [0.0, 0.0], 90.0, Footprint::Ridge).unwrap();
    assert_close(h(&t, 5.0, 0.099), 0.1, 0.0, "bump top");
    assert_close(h(&t, 5.0, -0.2), 0.05, 1e-15, "flanked bump mid-flank");
    // Round: a function of the distance from the centre.
    let t = Bump::new(0.2, 1.0, 0.0, [1.0, 1.0], 0.0, Footprint::Round).unwrap();
    assert_close(
        h(&t, 1.0 + 0.25 * 0.6, 1.0 + 0.25 * 0.8),
        0.1,
        1e-15,
        "round bump",
    );
    assert_eq!(hg(&t, 1.0, 1.0), (0.2, [0.0, 0.0]));

    // Ditch: 0.08 m deep, 0.5 m wide at the top, 0.1 m floor, along 0°.
    let t = Ditch::new(0.08, 0.5, 0.1, [2.0, 0.0], 0.0, Footprint::Ridge).unwrap();
    assert_close(h(&t, 2.04, 9.0), -0.08, 0.0, "ditch floor");
    assert_close(h(&t, 2.15, 9.0), -0.04, 1e-15, "ditch mid-wall");
    assert_close(h(&t, 1.85, 9.0), -0.04, 1e-15, "ditch other wall");
    assert_eq!(h(&t, 2.26, 0.0), 0.0);

    // Step: 0.05 m up towards +X at X = 1, 2 cm cosine ramp.
    let t = Step::new(0.05, [1.0, 0.0], 0.0, 0.02).unwrap();
    assert_eq!(h(&t, 0.98, 4.0), 0.0);
    assert_close(h(&t, 1.0, 4.0), 0.025, 1e-15, "step middle");
    assert_eq!(h(&t, 1.011, 4.0), 0.05);
    assert_close(
        hg(&t, 1.0, 0.0).1[0],
        0.05 * std::f64::consts::PI / 0.04,
        1e-12,
        "step slope",
    );
    // Kept sharp: the upper value from the line on, zero slope both sides.
    let t = Step::new(0.05, [1.0, 0.0], 0.0, 0.0).unwrap();
    assert_eq!(hg(&t, 1.0, 0.0), (0.05, [0.0, 0.0]));
    assert_eq!(hg(&t, 1.0 - 1e-12, 0.0), (0.0, [0.0, 0.0]));
    // A step down towards +Y.
    let t = Step::new(-0.1, [0.0, 2.0], 90.0, 0.0).unwrap();
    assert_eq!(h(&t, 0.0, 2.5), -0.1);

    // Sinusoid: A sin(2π s/λ + φ).
    let t = Sinusoid::new(0.03, 0.8, 0.0, 0.0).unwrap();
    assert_close(h(&t, 0.2, 5.0), 0.03, 1e-17, "sinusoid crest");
    assert_close(h(&t, 0.6, 5.0), -0.03, 1e-17, "sinusoid trough");
    let t = Sinusoid::new(0.03, 0.8, 90.0, 90.0).unwrap();
    assert_close(h(&t, 5.0, 0.0), 0.03, 1e-17, "phase 90°");
}

#[test]
fn library_gradients_match_finite_differences() {
    let mut r = prng::SplitMix64::new(11);
    for t in library() {
        for _ in 0..300 {
            let x = -1.0 + 4.0 * r.next_f64();
            let y = -1.0 + 3.0 * r.next_f64();
            let (z, grad) = hg(&t, x, y);
            assert_eq!(z, h(&t, x, y));
            let fd = fd_gradient(&t, x, y, 1e-7);
            for k in 0..2 {
                assert_close(
                    grad[k],
                    fd[k],
                    2e-6,
                    &format!("{t:?} gradient {k} at ({x}, {y})"),
                );
            }
        }
    }
}

#[test]
fn library_rejects_bad_parameters() {
    assert_eq!(
        message(Slope::new(90.0, 0.0, [0.0, 0.0], 0.0)),
        "terrain.angle_deg: the slope angle must be between -90° and 90°, got 90\n  = help: \
         give the inclination in degrees; use direction_deg to say which way it rises"
    );
    assert_eq!(
        message(Bump::new(0.1, -0.5, 0.0, [0.0, 0.0], 0.0, Footprint::Ridge)),
        "terrain.width: must be > 0 m, got -0.5\n  = help: give a positive value in m"
    );
    assert_eq!(
        message(Ditch::new(0.1, 0.5, 0.5, [0.0, 0.0], 0.0, Footprint::Ridge)),
        "terrain.bottom_width: must be smaller than width (0.5 m), got 0.5 m\n  = help: width \
         is the full width at the base, bottom_width the flat part; the flanks take the rest"
    );
    assert_eq!(
        message(Ditch::new(
            -0.1,
            0.5,
            0.0,
            [0.0, 0.0],
            0.0,
            Footprint::Ridge
        )),
        "terrain.depth: must be > 0 m, got -0.1\n  = help: give the depth below the \
         surrounding ground as a positive number of metres"
    );
    assert_eq!(
        message(Step::new(0.1, [0.0, 0.0], f64::NAN, 0.0)),
        "terrain.direction_deg: the direction must be a finite angle, got NaN\n  = help: give \
         an azimuth in degrees from +X towards +Y (0 = +X, 90 = +Y)"
    );
    assert_eq!(
        message(Sinusoid::new(0.1, 0.0, 0.0, 0.0)),
        "terrain.wavelength: must be > 0 m, got 0\n  = help: give a positive value in m"
    );
}

// ---------------------------------------------------------------- random field

#[test]
fn random_node_values_are_the_same_bits_on_every_machine() {
    // Expected values computed independently (Python integers, SplitMix64 as
    // documented in the prng module): value = a·(2·(bits >> 11)·2⁻⁵³ − 1).
    assert_eq!(prng::lattice_bits(1, 0, 0), 7_213_539_819_183_638_022);
    assert_eq!(prng::lattice_bits(1, -3, 7), 3_754_600_800_469_990_485);
    let f = RandomField::default();
    assert_eq!(f.node_value(0, 0), -0.10895322283652042);
    assert_eq!(f.node_value(-3, 7), -0.2964626827657312);
    let f = RandomField {
        seed: 42,
        ..RandomField::default()
    };
    assert_eq!(f.node_value(100, -100), 0.14612136578728663);
}

#[test]
fn random_node_values_are_uniform_in_plus_minus_the_amplitude() {
    let f = RandomField::default();
    let n = 300 * 300;
    let (mut sum, mut sum_sq, mut min, mut max) = (0.0, 0.0, f64::MAX, f64::MIN);
    for j in -150..150 {
        for i in -150..150 {
            let u = f.node_value(i, j);
            sum += u;
            sum_sq += u * u;
            min = min.min(u);
            max = max.max(u);
        }
    }
    let mean = sum / f64::from(n);
    let var = sum_sq / f64::from(n) - mean * mean;
    assert_close(mean, 0.0, 0.005, "node mean");
    assert_close(var, 0.25 / 3.0, 0.002, "node variance a²/3");
    assert!(
        min >= -0.5 && max < 0.5 && min < -0.499 && max > 0.499,
        "{min} {max}"
    );
}

fn small_field(seed: u64) -> RandomField {
    RandomField {
        seed,
        extent: Bounds {
            x_min: -2.0,
            x_max: 3.0,
            y_min: -1.5,
            y_max: 1.5,
        },
        ..RandomField::default()
    }
}

#[test]
fn random_terrain_is_deterministic_per_seed_and_differs_across_seeds() {
    let a = small_field(1).grid().unwrap();
    let b = small_field(1).grid().unwrap();
    assert_eq!(a, b);
    assert_eq!(
        (a.nx(), a.ny(), a.origin(), a.spacing()),
        (101, 61, [-2.0, -1.5], [0.05, 0.05])
    );
    let c = small_field(2).grid().unwrap();
    let differing = a
        .heights()
        .iter()
        .zip(c.heights())
        .filter(|(p, q)| p != q)
        .count();
    // Only the flat patch (about π·0.8² m² of 15 m²) agrees.
    assert!(
        differing > a.heights().len() * 8 / 10,
        "{differing} of {}",
        a.heights().len()
    );
}

#[test]
fn random_terrain_has_a_flat_start_patch_and_scales_with_z_r() {
    let field = small_field(5);
    let g = field.grid().unwrap();
    let [x0, y0] = g.origin();
    let mut inside = 0;
    let mut outside = 0;
    for j in 0..g.ny() {
        for i in 0..g.nx() {
            let (x, y) = (x0 + i as f64 * 0.05, y0 + j as f64 * 0.05);
            let r = x.hypot(y);
            let z = g.node(i, j).unwrap();
            if r <= 0.3 {
                assert_eq!(z, 0.0, "patch at ({x}, {y})");
                inside += 1;
            } else if r >= 0.8 {
                let expected = 0.2 * field.z_ran(x, y).unwrap();
                assert_close(z, expected, 1e-15, "field outside the blend");
                outside += 1;
            }
        }
    }
    assert!(inside > 100 && outside > 5000, "{inside} {outside}");
    assert_close(
        field.patch_weight(0.55, 0.0),
        0.5,
        1e-15,
        "mid-blend weight",
    );
    // Z_G = Z_R·Z_ran: doubling Z_R doubles every height.
    let double = RandomField {
        z_r: 0.4,
        ..field.clone()
    }
    .grid()
    .unwrap();
    for (a, b) in g.heights().iter().zip(double.heights()) {
        assert_close(*b, 2.0 * a, 1e-15, "Z_R scaling");
    }
}

/// The grid is built row by row (each column's and row's kernel weights
/// found once, the start patch's distance skipped far from it); every node
/// is still, bit for bit, the field's definition at that point:
/// `Z_R·w(x, y)·Z_ran(x, y)`, inside the patch, across the blend ring and
/// beyond, and with a blend of zero width.
#[test]
fn random_terrain_nodes_are_the_field_at_their_points_bit_for_bit() {
    for field in [
        small_field(3),
        RandomField {
            patch_center: [0.4, -0.25],
            patch_blend: 0.0,
            ..small_field(4)
        },
    ] {
        let g = field.grid().unwrap();
        let [x0, y0] = g.origin();
        let mut ring = 0;
        for j in 0..g.ny() {
            for i in 0..g.nx() {
                let (x, y) = (x0 + i as f64 * 0.05, y0 + j as f64 * 0.05);
                let w = field.patch_weight(x, y);
                let want = if w == 0.0 {
                    0.0
                } else {
                    field.z_r * w * field.z_ran(x, y).unwrap()
                };
                let got = g.node(i, j).unwrap();
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "node ({i}, {j}) at ({x}, {y})"
                );
                let (dx, dy) = (x - field.patch_center[0], y - field.patch_center[1]);
                let r = dx.hypot(dy) - field.patch_radius;
                // Reference weight from the distance itself.
                let w_ref = if r <= 0.0 {
                    0.0
                } else if r >= field.patch_blend {
                    1.0
                } else {
                    let s = r / field.patch_blend;
                    s * s * (3.0 - 2.0 * s)
                };
                assert_eq!(w.to_bits(), w_ref.to_bits(), "weight at ({x}, {y})");
                ring += usize::from(w > 0.0 && w < 1.0);
            }
        }
        assert!(
            field.patch_blend == 0.0 || ring > 100,
            "{ring} nodes in the ring"
        );
    }
    // With no blend, a point exactly on the patch's rim is still flat.
    let sharp = RandomField {
        patch_blend: 0.0,
        ..small_field(4)
    };
    assert_eq!(sharp.patch_weight(0.3, 0.0), 0.0);
    assert_eq!(sharp.patch_weight(0.0, -0.3), 0.0);
    assert_eq!(sharp.patch_weight(0.3000000000000001, 0.0), 1.0);
}

#[test]
fn random_terrain_does_not_depend_on_its_extent() {
    let small = small_field(9);
    let large = RandomField {
        extent: Bounds {
            x_min: -4.0,
            x_max: 6.0,
            y_min: -3.0,
            y_max: 2.0,
        },
        ..small.clone()
    };
    let (a, b) = (small.grid().unwrap(), large.grid().unwrap());
    for (x, y) in [(-1.9, 1.4), (2.95, -1.45), (0.123, 0.987), (1.0, 1.0)] {
        assert_close(
            h(&a, x, y),
            h(&b, x, y),
            1e-12,
            "same ground on a larger map",
        );
    }
    assert!(a.height(3.5, 0.0).is_err());
    assert!(b.height(3.5, 0.0).is_ok());
}

#[test]
fn random_terrain_has_the_documented_statistics() {
    // docs/TERRAIN.md, seed 1, default extent; printed to these precisions.
    let table = [
        (0.1, 0.0235, 0.111, 6.3, 16.4),
        (0.2, 0.0470, 0.222, 12.5, 30.5),
        (0.5, 0.1175, 0.554, 29.0, 55.8),
        (1.0, 0.2349, 1.109, 47.9, 71.2),
    ];
    for (z_r, rms_height, rms_slope, rms_slope_deg, max_slope_deg) in table {
        let s = RandomField {
            z_r,
            ..RandomField::default()
        }
        .statistics()
        .unwrap();
        assert_eq!(s.samples, 801 * 801);
        assert_close(s.rms_height, rms_height, 0.00005, "RMS height");
        assert_close(s.rms_slope, rms_slope, 0.0005, "RMS slope");
        assert_close(
            s.rms_slope.atan().to_degrees(),
            rms_slope_deg,
            0.05,
            "RMS slope angle",
        );
        assert_close(s.max_slope_deg, max_slope_deg, 0.05, "max slope");
        let [lx, ly] = s.correlation_length;
        assert_close(lx.unwrap(), 0.390, 0.0005, "correlation length X");
        assert_close(ly.unwrap(), 0.397, 0.0005, "correlation length Y");
    }
    // And the closed forms of the random_field docs, for three seeds (the
    // 40 m × 40 m map holds 6400 independent nodes: a few % of scatter).
    for seed in [1, 2, 3] {
        let s = RandomField {
            z_r: 1.0,
            seed,
            ..RandomField::default()
        }
        .statistics()
        .unwrap();
        let rms_height = 0.5 / 3f64.sqrt() * 57.0 / 70.0;
        let rms_slope = (2.0 * 7.0 / 3.0 * 57.0 / 70.0 / 3.0f64).sqrt();
        assert_close(s.rms_height / rms_height, 1.0, 0.03, "RMS height vs theory");
        assert_close(s.rms_slope / rms_slope, 1.0, 0.03, "RMS slope vs theory");
        for l in s.correlation_length {
            assert_close(
                l.unwrap() / (0.784 * 0.5),
                1.0,
                0.03,
                "correlation length vs theory",
            );
        }
    }
}

#[test]
fn statistics_of_known_surfaces() {
    // A sinusoid of amplitude A along X: RMS height A/√2, RMS slope 2πA/λ/√2,
    // max slope atan(2πA/λ); never drops below 1/e? It does, at
    // cos(2πτ/λ) = 1/e, τ = λ·acos(1/e)/(2π).
    let t = Sinusoid::new(0.1, 1.0, 0.0, 0.0).unwrap();
    let bounds = Bounds {
        x_min: 0.0,
        x_max: 20.0,
        y_min: 0.0,
        y_max: 1.0,
    };
    let s = TerrainStatistics::sample(&t, bounds, [0.01, 0.5]).unwrap();
    let k = 2.0 * std::f64::consts::PI;
    assert_close(s.rms_height, 0.1 / 2f64.sqrt(), 1e-4, "sinusoid RMS height");
    assert_close(
        s.rms_slope,
        0.1 * k / 2f64.sqrt(),
        1e-3,
        "sinusoid RMS slope",
    );
    assert_close(
        s.max_slope_deg,
        (0.1 * k).atan().to_degrees(),
        1e-6,
        "sinusoid max slope",
    );
    let lx = s.correlation_length[0].unwrap();
    assert_close(
        lx,
        (-1f64).exp().acos() / k,
        2e-3,
        "sinusoid correlation length",
    );
    assert_eq!(s.correlation_length[1], None);
    let flat = TerrainStatistics::sample(&Flat::default(), bounds, [0.5, 0.5]).unwrap();
    assert_eq!(
        (flat.rms_height, flat.rms_slope, flat.max_slope_deg),
        (0.0, 0.0, 0.0)
    );
    assert_eq!(flat.correlation_length, [None, None]);
}

#[test]
fn random_field_rejects_bad_parameters() {
    let bad = RandomField {
        extent: Bounds {
            x_min: 1.0,
            x_max: -1.0,
            y_min: 0.0,
            y_max: 1.0,
        },
        ..RandomField::default()
    };
    assert_eq!(
        message(bad.grid()),
        "terrain.extent: [x_min, x_max, y_min, y_max] must have x_max > x_min and y_max > \
         y_min, got [1, -1, 0, 1]\n  = help: give the area the rover may reach, in metres"
    );
    let bad = RandomField {
        z_r: -0.2,
        ..RandomField::default()
    };
    assert_eq!(
        message(bad.grid()),
        "terrain.z_r: must be ≥ 0 (dimensionless), got -0.2\n  = help: give a non-negative \
         value in (dimensionless)"
    );
    let bad = RandomField {
        grid_spacing: 1e-5,
        ..RandomField::default()
    };
    assert_eq!(
        message(bad.grid()),
        "terrain.grid_spacing: 0.00001 m is too fine for the extent (more than 50000000 \
         nodes)\n  = help: use a larger grid spacing or a smaller extent"
    );
}

// ---------------------------------------------------------------- ESRI ASCII grids

/// Parses `text` as an .asc file written to a scratch file; returns the path too.
fn asc(name: &str, text: &str) -> (PathBuf, Result<Grid, TerrainError>) {
    let path = file(name, text);
    let grid = read_asc(&path);
    (path, grid)
}

/// Pins the whole message of a corrupt .asc file: `{path}:{line}: {rest}`.
fn bad_asc(name: &str, text: &str, line: usize, rest: &str) {
    let (path, grid) = asc(name, text);
    assert_eq!(
        message(grid),
        format!("{}:{line}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn asc_round_trips() {
    for (name, grid) in [
        (
            "round_square.asc",
            bumpy_grid(5, 4).with_interpolation(Interpolation::Bicubic),
        ),
        ("round_rect.asc", bumpy_grid(3, 7)),
        (
            "round_square_cells.asc",
            Grid::from_fn([-0.1, 1e3], [0.05, 0.05], 4, 3, |x, y| {
                1e-3 * x * y + 1.0 / 3.0
            })
            .unwrap(),
        ),
    ] {
        let path = scratch(name);
        write_asc(&grid, &path).unwrap();
        assert_eq!(read_asc(&path).unwrap(), grid, "{name}");
    }
}

#[test]
fn asc_reads_corners_any_key_case_and_rows_north_to_south() {
    let text = "NCOLS 3\r\nnRows\t2\r\nXLLCORNER 10\r\nyllcorner -4\r\nCellSize 0.5\r\n\
                NODATA_value -9999\r\n\r\n1 2 3\r\n4\t5 6\r\n";
    let (_, grid) = asc("corner.asc", text);
    let grid = grid.unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing(), grid.nx(), grid.ny()),
        ([10.25, -3.75], [0.5, 0.5], 3, 2)
    );
    // The first row of the file is the north row (j = 1).
    assert_eq!(grid.heights(), &[4.0, 5.0, 6.0, 1.0, 2.0, 3.0]);
    assert_eq!(h(&grid, 10.25, -3.25), 1.0);
    // dx/dy instead of cellsize, centres instead of corners.
    let text = "ncols 2\nnrows 2\nxllcenter 1\nyllcenter 2\ndx 0.5\ndy 0.25\n1 2\n3 4\n";
    let grid = asc("dxdy.asc", text).1.unwrap();
    assert_eq!((grid.origin(), grid.spacing()), ([1.0, 2.0], [0.5, 0.25]));
}

const ASC_HEAD: &str = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";

#[test]
fn asc_corrupt_files_each_say_what_and_where() {
    let grid_help = "each line holds one whole row of the grid; check for a missing or extra value";
    bad_asc(
        "short_row.asc",
        &format!("{ASC_HEAD}1 2 3\n4 5\n"),
        7,
        &format!("row 2 has 2 values, expected ncols = 3\n  = help: {grid_help}"),
    );
    bad_asc(
        "long_row.asc",
        &format!("{ASC_HEAD}1 2 3 4\n4 5 6\n"),
        6,
        &format!("row 1 has 4 values, expected ncols = 3\n  = help: {grid_help}"),
    );
    bad_asc(
        "word.asc",
        &format!("{ASC_HEAD}1 2 3\n4 five 6\n"),
        7,
        "row 2, column 2: `five` is not a number\n  = help: heights are decimal numbers in metres",
    );
    bad_asc(
        "nan.asc",
        &format!("{ASC_HEAD}1 NaN 3\n4 5 6\n"),
        6,
        "row 1, column 2: the height NaN is not a finite number\n  = help: every cell needs a \
         finite height in metres (mark holes with NODATA_value)",
    );
    bad_asc(
        "nodata.asc",
        &format!("{ASC_HEAD}NODATA_value -9999\n1 2 3\n4 5 -9999\n"),
        8,
        "row 2, column 3 (X = 2.5 m, Y = 0.5 m) holds the NODATA_value -9999: the map has no \
         height there\n  = help: fill the holes before loading (e.g. gdal_fillnodata.py) or \
         crop the map to the measured area",
    );
    bad_asc(
        "missing_nrows.asc",
        "ncols 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        5,
        "missing header key `nrows` before the first row of heights\n  = help: the header \
         needs ncols, nrows, xllcorner (or xllcenter), yllcorner (or yllcenter) and cellsize",
    );
    bad_asc(
        "missing_cellsize.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3\n4 5 6\n",
        5,
        "missing header key `cellsize` before the first row of heights\n  = help: give the \
         cell size in metres (`cellsize 0.05`), or `dx` and `dy` for rectangular cells",
    );
    bad_asc(
        "missing_yll.asc",
        "ncols 3\nnrows 2\nxllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        5,
        "missing header key `yllcorner` before the first row of heights\n  = help: give the \
         south-west cell's corner (xllcorner, yllcorner) or centre (xllcenter, yllcenter) in \
         metres",
    );
    bad_asc(
        "negative_cellsize.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -0.5\n1 2 3\n4 5 6\n",
        5,
        "`cellsize` must be > 0, got -0.5\n  = help: the cell size is the distance between cell \
         centres in metres",
    );
    bad_asc(
        "zero_dy.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 1\ndy 0\n1 2 3\n4 5 6\n",
        6,
        "`dy` must be > 0, got 0\n  = help: the cell size is the distance between cell centres \
         in metres",
    );
    bad_asc(
        "truncated.asc",
        "ncols 3\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        7,
        "the file ends after 2 rows of heights, expected nrows = 4\n  = help: the file is \
         truncated, or nrows is wrong",
    );
    bad_asc(
        "header_only.asc",
        ASC_HEAD,
        5,
        "the file ends after 0 rows of heights, expected nrows = 2\n  = help: the file is \
         truncated, or nrows is wrong",
    );
    bad_asc(
        "extra_row.asc",
        &format!("{ASC_HEAD}1 2 3\n4 5 6\n7 8 9\n"),
        8,
        "more rows of heights than nrows = 2\n  = help: make nrows match the number of rows, or \
         remove the extra lines",
    );
    bad_asc(
        "unknown_key.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2 3\n4 5 6\n",
        5,
        "unknown header key `celsize`\n  = help: the header keys are ncols, nrows, xllcorner or \
         xllcenter, yllcorner or yllcenter, cellsize (or dx and dy) and NODATA_value",
    );
    bad_asc(
        "twice.asc",
        &format!("{ASC_HEAD}CELLSIZE 2\n1 2 3\n4 5 6\n"),
        6,
        "header key `CELLSIZE` is given twice\n  = help: keep one of the two lines",
    );
    bad_asc(
        "corner_and_center.asc",
        &format!("{ASC_HEAD}xllcenter 0.5\n1 2 3\n4 5 6\n"),
        6,
        "both `xllcorner` and `xllcenter` are given\n  = help: keep one: llcorner is the \
         south-west cell's outer corner, llcenter its centre",
    );
    bad_asc(
        "no_value.asc",
        "ncols\nnrows 2\n",
        1,
        "header line `ncols` must be a key and one value\n  = help: write one `key value` pair \
         per header line, e.g. `cellsize 0.05`",
    );
    bad_asc(
        "bad_count.asc",
        "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
        1,
        "`ncols` must be a whole number ≥ 2, got 2.5\n  = help: a grid needs at least 2 × 2 \
         cells; ncols counts columns, nrows rows",
    );
    bad_asc(
        "inf_header.asc",
        "ncols 2\nnrows 2\nxllcorner inf\n",
        3,
        "the value of `xllcorner` is `inf`, not a finite number\n  = help: header values are \
         numbers, e.g. `cellsize 0.05`",
    );
    // A binary file given as text.
    let path = file("binary.asc", b"ncols 2\n\xff\xfe\x00PNG");
    assert_eq!(
        message(read_asc(&path)),
        format!(
            "{}:2: byte 8 is not valid UTF-8 text\n  = help: this format is plain text; is it a \
             binary file (PNG, TIFF) with the wrong format or extension?",
            path.display()
        )
    );
    // A missing file.
    let path = scratch("does_not_exist.asc");
    assert_eq!(
        message(read_asc(&path)),
        format!(
            "{}: cannot read the terrain file: No such file or directory (os error 2)\n  = help: \
             check the path (a relative path is resolved from the scenario file's directory)",
            path.display()
        )
    );
}

// ---------------------------------------------------------------- CSV grids

fn bad_csv(name: &str, text: &str, georeference: Option<Georeference>, line: usize, rest: &str) {
    let path = file(name, text);
    assert_eq!(
        message(read_csv(&path, georeference)),
        format!("{}:{line}: {rest}", path.display()),
        "case {name}"
    );
}

const PLACE: Georeference = Georeference {
    origin: [1.0, 2.0],
    spacing: [0.5, 0.25],
};

#[test]
fn csv_round_trips_and_reads_rows_south_to_north() {
    let grid = bumpy_grid(4, 6);
    let path = scratch("round.csv");
    write_csv(&grid, &path).unwrap();
    assert_eq!(read_csv(&path, None).unwrap(), grid);

    // Header keys in any order and case; comments and blank lines anywhere.
    let path = file(
        "order.csv",
        "# a test grid\nDY, dx ,y0,X0\n0.25,0.5,2,1\n\n1,2,3\n# north\n4,5,6\n",
    );
    let grid = read_csv(&path, None).unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing(), grid.nx(), grid.ny()),
        ([1.0, 2.0], [0.5, 0.25], 3, 2)
    );
    assert_eq!(grid.heights(), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(h(&grid, 1.0, 2.25), 4.0);

    // A bare matrix placed by the scenario.
    let path = file("bare.csv", "1,2,3\n4,5,6\n");
    let grid = read_csv(&path, Some(PLACE)).unwrap();
    assert_eq!((grid.origin(), grid.spacing()), ([1.0, 2.0], [0.5, 0.25]));
}

#[test]
fn csv_corrupt_files_each_say_what_and_where() {
    let header = "x0,y0,dx,dy\n0,0,1,1\n";
    bad_csv(
        "short_row.csv",
        &format!("{header}1,2,3\n4,5\n"),
        None,
        4,
        "row 2 has 2 values, expected 3 as in the first row\n  = help: every row of the matrix \
         has one value per column; check for a missing or extra value (or a truncated file)",
    );
    bad_csv(
        "word.csv",
        &format!("{header}1,2,3\n4,x,6\n"),
        None,
        4,
        "row 2, column 2: `x` is not a number\n  = help: heights are decimal numbers in metres, \
         separated by commas",
    );
    bad_csv(
        "empty.csv",
        &format!("{header}1,,3\n4,5,6\n"),
        None,
        3,
        "row 1, column 2 is empty\n  = help: every cell needs a height; check for a doubled or \
         trailing comma",
    );
    bad_csv(
        "nan.csv",
        &format!("{header}1,2,3\n4,5,nan\n"),
        None,
        4,
        "row 2, column 3: the height nan is not a finite number\n  = help: every cell needs a \
         finite height in metres; fill holes before loading",
    );
    bad_csv(
        "no_place.csv",
        "1,2\n3,4\n",
        None,
        1,
        "the grid has no georeference: no `x0,y0,dx,dy` header\n  = help: add the header line \
         `x0,y0,dx,dy` and a line with their values before the heights, or set origin = [x0, \
         y0] and spacing = [dx, dy] in [terrain]",
    );
    bad_csv(
        "two_places.csv",
        &format!("{header}1,2\n3,4\n"),
        Some(PLACE),
        3,
        "the file has an `x0,y0,dx,dy` header and the scenario gives origin and spacing too\n  \
         = help: remove origin and spacing from [terrain] or the header from the file, so the \
         two cannot disagree",
    );
    bad_csv(
        "missing_key.csv",
        "x0,y0,dx\n0,0,1\n1,2\n3,4\n",
        None,
        1,
        "the header has no `dy`\n  = help: the header line is `x0,y0,dx,dy`, each key once",
    );
    bad_csv(
        "unknown_key.csv",
        "x0,y0,dx,dz\n0,0,1,1\n1,2\n3,4\n",
        None,
        1,
        "unknown header key `dz`\n  = help: the header line is `x0,y0,dx,dy` (any order); \
         heights follow as numbers",
    );
    bad_csv(
        "negative.csv",
        "x0,y0,dx,dy\n0,0,1,-1\n1,2\n3,4\n",
        None,
        2,
        "`dy` must be > 0, got -1\n  = help: dx and dy are the distances between neighbouring \
         nodes in metres",
    );
    bad_csv(
        "header_values.csv",
        "x0,y0,dx,dy\n0,0,1\n1,2\n3,4\n",
        None,
        2,
        "the header has 4 keys but this line has 3 values\n  = help: give x0, y0, dx and dy, in \
         the order of the header line",
    );
    bad_csv(
        "one_row.csv",
        &format!("{header}1,2,3\n"),
        None,
        3,
        "the matrix has 1 rows of 3 values; a grid needs at least 2 × 2\n  = help: give at \
         least two rows of at least two heights",
    );
}

// ---------------------------------------------------------------- PNG height maps

const PNG_SCALE: SampleScale = SampleScale {
    scale: 0.001,
    offset: -10.0,
};

fn png_bytes(
    width: u32,
    height: u32,
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(data).unwrap();
    writer.finish().unwrap();
    out
}

fn bad_png(name: &str, bytes: &[u8], rest: &str) {
    let path = file(name, bytes);
    assert_eq!(
        message(read_png(&path, PLACE, PNG_SCALE)),
        format!("{}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn png_round_trips_and_reads_the_top_row_as_north() {
    let mut r = prng::SplitMix64::new(5);
    let heights = (0..5 * 4)
        .map(|_| PNG_SCALE.offset + PNG_SCALE.scale * (r.next_u64() >> 48) as f64)
        .collect();
    let grid = Grid::new(PLACE.origin, PLACE.spacing, 5, 4, heights).unwrap();
    let path = scratch("round.png");
    write_png(&grid, &path, PNG_SCALE).unwrap();
    assert_eq!(read_png(&path, PLACE, PNG_SCALE).unwrap(), grid);

    // 2 × 2 samples, big-endian: top row 1, 2; bottom row 256, 65535.
    let data = [0, 1, 0, 2, 1, 0, 255, 255];
    let path = file(
        "tiny.png",
        png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &data,
        ),
    );
    let grid = read_png(
        &path,
        PLACE,
        SampleScale {
            scale: 0.5,
            offset: 1.0,
        },
    )
    .unwrap();
    assert_eq!(grid.heights(), &[129.0, 32768.5, 1.5, 2.0]);

    // Heights that do not fit the 16-bit range are refused on writing.
    assert_eq!(
        message(write_png(
            &grid,
            &scratch("unfit.png"),
            SampleScale {
                scale: 0.001,
                offset: 0.0
            }
        )),
        "terrain.scale: the height 129 m at node (i = 0, j = 0) maps to sample 129000, outside \
         0 … 65535\n  = help: choose offset below the lowest height and scale so that the \
         highest fits"
    );
}

#[test]
fn png_corrupt_files_each_say_what_and_where() {
    let fix = "re-export the height map as a 16-bit grayscale PNG (8 bits give only 256 height \
               levels; colour has no single height per pixel)";
    bad_png(
        "eight_bit.png",
        &png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &[1, 2, 3, 4],
        ),
        &format!(
            "the image is 8-bit Grayscale; a height map must be 16-bit Grayscale\n  = help: {fix}"
        ),
    );
    bad_png(
        "rgb.png",
        &png_bytes(2, 2, png::ColorType::Rgb, png::BitDepth::Sixteen, &[0; 24]),
        &format!("the image is 16-bit Rgb; a height map must be 16-bit Grayscale\n  = help: {fix}"),
    );
    let good = png_bytes(
        16,
        16,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &[7; 512],
    );
    bad_png(
        "truncated.png",
        &good[..good.len() - 30],
        "the image data is corrupt or truncated (unexpected end of file)\n  = \
         help: re-export or re-copy the file",
    );
    bad_png(
        "not_png.png",
        b"ncols 3\nnrows 2\n",
        "not a readable PNG image (Invalid PNG signature.)\n  = help: check that the \
         file is a complete PNG (re-export or re-copy it), or set format",
    );
    bad_png(
        "one_row.png",
        &png_bytes(
            3,
            1,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &[0; 6],
        ),
        "the image is 3 × 1 pixels; a grid needs at least 2 × 2\n  = help: give a height map \
         of at least two rows and two columns",
    );
}

// ---------------------------------------------------------------- GeoTIFF DEMs

/// A hand-made GeoTIFF of i16 samples, tie point at the top-left pixel's
/// corner (PixelIsArea: no GeoKeyDirectory), optional GDAL_NODATA.
fn i16_geotiff(width: u32, height: u32, data: &[i16], nodata: Option<&str>) -> Vec<u8> {
    use tiff::encoder::{TiffEncoder, colortype::GrayI16};
    use tiff::tags::Tag;
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut encoder = TiffEncoder::new(&mut out).unwrap();
        let mut image = encoder.new_image::<GrayI16>(width, height).unwrap();
        let tags = image.encoder();
        tags.write_tag(Tag::ModelPixelScaleTag, &[2.0, 3.0, 0.0][..])
            .unwrap();
        tags.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, 100.0, 500.0, 0.0][..],
        )
        .unwrap();
        if let Some(nodata) = nodata {
            tags.write_tag(Tag::GdalNodata, nodata).unwrap();
        }
        image.write_data(data).unwrap();
    }
    out.into_inner()
}

fn bad_tiff(name: &str, bytes: &[u8], rest: &str) {
    let path = file(name, bytes);
    assert_eq!(
        message(read_geotiff(&path, 1.0, 0.0)),
        format!("{}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn geotiff_round_trips_and_places_pixel_is_area_rasters() {
    let grid = bumpy_grid(6, 3);
    let path = scratch("round.tif");
    write_geotiff(&grid, &path).unwrap();
    assert_eq!(read_geotiff(&path, 1.0, 0.0).unwrap(), grid);

    // PixelIsArea: top-left corner at (100, 500), pixels 2 m × 3 m.
    let path = file(
        "area.tif",
        i16_geotiff(3, 2, &[1, 2, 3, -4, -5, -6], Some("-32768")),
    );
    let grid = read_geotiff(&path, 0.5, 10.0).unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing()),
        ([101.0, 495.5], [2.0, 3.0])
    );
    assert_eq!(grid.heights(), &[8.0, 7.5, 7.0, 10.5, 11.0, 11.5]);
}

#[test]
fn a_geotiff_placed_by_a_transformation_matrix_is_refused_even_with_a_pixel_scale() {
    use tiff::encoder::{TiffEncoder, colortype::GrayI16};
    use tiff::tags::Tag;
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut encoder = TiffEncoder::new(&mut out).unwrap();
        let mut image = encoder.new_image::<GrayI16>(2, 2).unwrap();
        let tags = image.encoder();
        tags.write_tag(Tag::ModelPixelScaleTag, &[2.0, 3.0, 0.0][..])
            .unwrap();
        tags.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, 100.0, 500.0, 0.0][..],
        )
        .unwrap();
        // A 30° rotation.
        let (s, c) = 30f64.to_radians().sin_cos();
        let matrix = [
            2.0 * c,
            -3.0 * s,
            0.0,
            100.0,
            2.0 * s,
            3.0 * c,
            0.0,
            500.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1.0,
        ];
        tags.write_tag(Tag::ModelTransformationTag, &matrix[..])
            .unwrap();
        image.write_data(&[1i16, 2, 3, 4][..]).unwrap();
    }
    let path = file("rotated.tif", out.into_inner());
    let text = message(read_geotiff(&path, 1.0, 0.0));
    assert!(
        text.contains("tag ModelTransformation (34264)") && text.contains("gdalwarp"),
        "{text}"
    );
}

#[test]
fn geotiff_corrupt_files_each_say_what_and_where() {
    let path = file(
        "hole.tif",
        i16_geotiff(3, 2, &[1, 2, 3, 4, -9999, 6], Some("-9999 ")),
    );
    assert_eq!(
        message(read_geotiff(&path, 1.0, 0.0)),
        format!(
            "{}: pixel (row 2, column 2): holds the GDAL_NODATA value -9999: the DEM has no \
             height there\n  = help: fill the holes before loading (gdal_fillnodata.py) or crop \
             the DEM to the measured area (gdal_translate -projwin)",
            path.display()
        )
    );
    bad_tiff(
        "bad_nodata.tif",
        &i16_geotiff(2, 2, &[1, 2, 3, 4], Some("none")),
        "tag GDAL_NODATA (42113): `none` is not a number\n  = help: GDAL_NODATA holds the \
         no-data value as text, e.g. \"-9999\"; fix it with gdal_edit.py -a_nodata",
    );
    // A plain TIFF: no georeference.
    let mut plain = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut plain)
        .unwrap()
        .write_image::<tiff::encoder::colortype::Gray32Float>(2, 2, &[1.0, 2.0, 3.0, 4.0])
        .unwrap();
    bad_tiff(
        "plain.tif",
        plain.get_ref(),
        "tag ModelPixelScale (33550): is missing: the TIFF has no georeference\n  = help: export \
         a GeoTIFF (gdal_translate -of GTiff, with a spatial reference), or convert the DEM to \
         .asc",
    );
    let mut rgb = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut rgb)
        .unwrap()
        .write_image::<tiff::encoder::colortype::RGB8>(2, 2, &[0; 12])
        .unwrap();
    bad_tiff(
        "rgb.tif",
        rgb.get_ref(),
        "the image is RGB(8); a DEM has one band of heights\n  = help: export the elevation \
         band alone (e.g. gdal_translate -b 1)",
    );
    let good = i16_geotiff(64, 64, &[3; 64 * 64], None);
    bad_tiff(
        "truncated.tif",
        &good[..4000],
        // The writer puts the directory after the data, so a cut loses the directory.
        "not a readable TIFF image (failed to fill whole buffer)\n  = help: check that the file \
         is a complete GeoTIFF (re-export or re-copy it)",
    );
    bad_tiff(
        "not_tiff.tif",
        b"P5 2 2 255\n....",
        "not a readable TIFF image (format error: TIFF signature not found)\n  = help: check \
         that the file is a complete GeoTIFF (re-export or re-copy it)",
    );
}

// ---------------------------------------------------------------- scenario config

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Scenario {
    #[serde(default)]
    terrain: TerrainConfig,
}

fn config(toml_text: &str) -> Result<TerrainConfig, toml::de::Error> {
    toml::from_str::<Scenario>(toml_text).map(|s| s.terrain)
}

fn build(toml_text: &str, base_dir: &Path) -> Result<Terrain, TerrainError> {
    config(toml_text).expect("valid TOML").build(base_dir)
}

#[test]
fn config_builds_every_kind() {
    let here = Path::new(".");
    assert_eq!(config("").unwrap(), TerrainConfig::default());
    let t = build("[terrain]\nkind = \"flat\"\nheight = -1.5\n", here).unwrap();
    assert_eq!(h(&t, 3.0, 4.0), -1.5);
    let t = build(
        "[terrain]\nkind = \"slope\"\nangle_deg = 45\ndirection_deg = 180\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, -2.0, 7.0), 2.0, 1e-15, "45° slope rising towards -X");
    let t = build(
        "[terrain]\nkind = \"bump\"\nheight = 0.1\nwidth = 0.4\ncenter = [2.0, 0.0]\n\
         footprint = \"round\"\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 2.0, 0.1), 0.05, 1e-15, "round bump mid-flank");
    let t = build(
        "[terrain]\nkind = \"ditch\"\ndepth = 0.2\nwidth = 1.0\nbottom_width = 0.5\n\
         center = [0.0, 3.0]\ndirection_deg = 90\n",
        here,
    )
    .unwrap();
    assert_eq!(h(&t, 9.0, 3.2), -0.2);
    let t = build(
        "[terrain]\nkind = \"step\"\nheight = 0.1\nposition = [1.0, 0.0]\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 1.0, 0.0), 0.05, 1e-15, "default 1 cm ramp, middle");
    assert_eq!(h(&t, 1.005, 0.0), 0.1);
    let t = build(
        "[terrain]\nkind = \"sinusoid\"\namplitude = 0.02\nwavelength = 2.0\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 0.5, 0.0), 0.02, 1e-17, "sinusoid crest");
    let t = build(
        "[terrain]\nkind = \"random\"\nz_r = 0.2\nseed = 3\nextent = [-1.0, 2.0, -1.0, 1.0]\n\
         interpolation = \"bilinear\"\nedge = \"clamp\"\n",
        here,
    )
    .unwrap();
    let Terrain::Grid(grid) = &t else {
        panic!("random terrain is a grid: {t:?}")
    };
    let expected = RandomField {
        seed: 3,
        extent: Bounds {
            x_min: -1.0,
            x_max: 2.0,
            y_min: -1.0,
            y_max: 1.0,
        },
        interpolation: Interpolation::Bilinear,
        edge: EdgePolicy::Clamp,
        ..RandomField::default()
    };
    assert_eq!(grid, &expected.grid().unwrap());
    assert!(t.height(50.0, 0.0).is_ok());
}

#[test]
fn config_loads_files_relative_to_the_scenario() {
    let dir = scratch("scenario");
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    let grid = bumpy_grid(4, 4);
    write_asc(&grid, &dir.join("maps/site.ASC")).unwrap();
    write_geotiff(&grid, &dir.join("maps/site.tiff")).unwrap();
    std::fs::write(dir.join("maps/site.txt"), "1,2\n3,4\n").unwrap();
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.ASC\"\nedge = \"clamp\"\n",
        &dir,
    )
    .unwrap();
    assert_eq!(
        t,
        Terrain::Grid(grid.clone().with_edge_policy(EdgePolicy::Clamp))
    );
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.tiff\"\n",
        &dir,
    )
    .unwrap();
    assert_eq!(t, Terrain::Grid(grid.clone()));
    // scale and offset apply to every format.
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.txt\"\nformat = \"csv\"\n\
         origin = [0.0, 0.0]\nspacing = [1.0, 1.0]\nscale = 0.5\noffset = 10\n",
        &dir,
    )
    .unwrap();
    assert_eq!(h(&t, 1.0, 1.0), 12.0);
}

#[test]
fn config_errors_name_the_parameter() {
    let dir = scratch("scenario_errors");
    std::fs::create_dir_all(&dir).unwrap();
    write_asc(&bumpy_grid(3, 3), &dir.join("a.asc")).unwrap();
    write_png(
        &Grid::new([0.0, 0.0], [1.0, 1.0], 2, 2, vec![0.0; 4]).unwrap(),
        &dir.join("a.png"),
        SampleScale {
            scale: 1.0,
            offset: 0.0,
        },
    )
    .unwrap();
    let cases = [
        (
            "kind = \"file\"\npath = \"a.png\"\norigin = [0.0, 0.0]\nspacing = [1.0, 1.0]\n",
            "terrain.scale: a PNG height map needs scale (metres per count)\n  = help: set scale \
             (and offset, the height of sample 0), e.g. scale = 0.001",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\n",
            "terrain.origin: a PNG height map needs origin and spacing\n  = help: set origin = \
             [x, y] (centre of the bottom-left pixel) and spacing = [dx, dy] in metres",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\norigin = [0.0, 0.0]\n",
            "terrain.spacing: origin is given without spacing\n  = help: give both origin = [x, \
             y] and spacing = [dx, dy], or neither",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\norigin = [0.0, 0.0]\nspacing = [0.0, 1.0]\n",
            "terrain.spacing[0]: must be > 0 m, got 0\n  = help: give a positive value in m",
        ),
        (
            "kind = \"file\"\npath = \"a.asc\"\norigin = [0.0, 0.0]\nspacing = [1.0, 1.0]\n",
            "terrain.origin: ESRI ASCII grid files carry their own origin and spacing\n  = help: \
             remove origin and spacing from [terrain]",
        ),
        (
            "kind = \"file\"\npath = \"a.dem\"\n",
            &format!(
                "terrain.format: cannot tell the format of `{}` from its extension\n  = help: set \
                 format = \"asc\", \"csv\", \"png\" or \"geotiff\"",
                dir.join("a.dem").display()
            ),
        ),
        (
            "kind = \"bump\"\nheight = 0.1\nwidth = 0.0\ncenter = [0.0, 0.0]\n",
            "terrain.width: must be > 0 m, got 0\n  = help: give a positive value in m",
        ),
        (
            "kind = \"random\"\nz_r = 0.2\npatch_radius = -1\n",
            "terrain.patch_radius: must be ≥ 0 m, got -1\n  = help: give a non-negative value in m",
        ),
    ];
    for (body, expected) in cases {
        let result = build(&format!("[terrain]\n{body}"), &dir);
        assert_eq!(message(result), expected, "case:\n{body}");
    }
}

#[test]
fn config_rejects_unknown_keys_and_kinds() {
    for (body, needle) in [
        (
            "kind = \"random\"\nz_r = 0.2\nsede = 4\n",
            "unknown field `sede`",
        ),
        (
            "kind = \"bump\"\nheight = 0.1\nwidth = 1\ncenter = [0, 0]\nradius = 2\n",
            "unknown field `radius`",
        ),
        ("kind = \"flat\"\nheigth = 1\n", "unknown field `heigth`"),
        ("kind = \"hills\"\n", "unknown variant `hills`"),
        ("kind = \"random\"\n", "missing field `z_r`"),
        (
            "kind = \"file\"\npath = \"a.asc\"\nformat = \"tif\"\n",
            "unknown variant `tif`",
        ),
        (
            "kind = \"random\"\nz_r = 0.1\nedge = \"wrap\"\n",
            "unknown variant `wrap`",
        ),
    ] {
        let error = config(&format!("[terrain]\n{body}"))
            .unwrap_err()
            .to_string();
        assert!(error.contains(needle), "case:\n{body}\ngot: {error}");
    }
}

#[test]
fn config_serializes_back_to_the_same_table() {
    for body in [
        "kind = \"flat\"\n",
        "kind = \"random\"\nz_r = 0.5\nseed = 9\nnode_spacing = 0.25\n",
        "kind = \"file\"\npath = \"x.png\"\nscale = 0.001\norigin = [1.0, 2.0]\nspacing = [0.1, 0.1]\n",
        "kind = \"step\"\nheight = 0.1\nposition = [1.0, 0.0]\nramp_width = 0.0\n",
    ] {
        let c = config(&format!("[terrain]\n{body}")).unwrap();
        let text = toml::to_string(&c).unwrap();
        let back: TerrainConfig = toml::from_str(&text).unwrap();
        assert_eq!(back, c, "{text}");
    }
}

// ---------------------------------------------------------------- robustness

/// Mutated and truncated files never panic a reader: they load or they error.
#[test]
fn readers_never_panic_on_damaged_files() {
    let grid = bumpy_grid(7, 5);
    let samples: Vec<(&str, Vec<u8>)> = vec![
        ("asc", asc::format_asc(&grid).into_bytes()),
        ("csv", csv_grid::format_csv(&grid).into_bytes()),
        (
            "png",
            png_map::encode_png(
                &Grid::new([0.0, 0.0], [1.0, 1.0], 7, 5, vec![1.0; 35]).unwrap(),
                SampleScale {
                    scale: 0.01,
                    offset: 0.0,
                },
            )
            .unwrap(),
        ),
        ("tif", geotiff::encode_geotiff(&grid).unwrap()),
    ];
    let path = Path::new("damaged");
    let mut r = prng::SplitMix64::new(99);
    let mut outcomes = [0usize; 2];
    for (kind, original) in &samples {
        for round in 0..400 {
            let mut bytes = original.clone();
            match round % 4 {
                0 => bytes.truncate((r.next_u64() % bytes.len() as u64) as usize),
                1 => {
                    for _ in 0..1 + r.next_u64() % 4 {
                        let k = (r.next_u64() % bytes.len() as u64) as usize;
                        bytes[k] = r.next_u64() as u8;
                    }
                }
                2 => {
                    let k = (r.next_u64() % bytes.len() as u64) as usize;
                    let printable = b"0123456789-.eE \n,#naifNAIF";
                    bytes[k] = printable[(r.next_u64() % printable.len() as u64) as usize];
                }
                _ => {
                    let k = (r.next_u64() % bytes.len() as u64) as usize;
                    bytes.insert(k, r.next_u64() as u8);
                }
            }
            let ok = match *kind {
                "asc" => asc::parse_asc(&String::from_utf8_lossy(&bytes), path).is_ok(),
                "csv" => csv_grid::parse_csv(&String::from_utf8_lossy(&bytes), path, None).is_ok(),
                "png" => png_map::decode_png(&bytes, path, PLACE, PNG_SCALE).is_ok(),
                _ => geotiff::decode_geotiff(&bytes, path, 1.0, 0.0).is_ok(),
            };
            outcomes[usize::from(ok)] += 1;
        }
    }
    // Both outcomes happen: the damage is sometimes harmless, often fatal.
    assert!(outcomes[0] > 100 && outcomes[1] > 10, "{outcomes:?}");
}

/// A header claiming a huge grid gets an error, not a huge allocation.
#[test]
fn huge_headers_do_not_allocate_their_claims() {
    let (path, grid) = asc(
        "huge.asc",
        "ncols 100000000\nnrows 100000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
    );
    assert_eq!(
        message(grid),
        format!(
            "{}: the grid is 100000000 × 100000000 = 10000000000000000 nodes; at most 50000000 \
             are loaded\n  = help: crop or downsample the map (gdal_translate -outsize, or \
             -srcwin) to the area the rover drives over",
            path.display()
        )
    );
}
