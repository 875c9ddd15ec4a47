//! The analytic library, the terrain interface and the grids' interpolants.

use std::path::Path;

use rover_dynamics::height_field::*;
use rover_terrain::*;

use super::support::*;

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
    // A micrometre texture, and spikes: no ground a wheel rolls over.
    assert!(
        message(Sinusoid::new(0.01, 1e-6, 0.0, 0.0))
            .starts_with("terrain.wavelength: 0.000001 m is shorter than 0.001 m")
    );
    let steep = message(Sinusoid::new(0.01, 0.01, 0.0, 0.0));
    assert!(
        steep.starts_with("terrain.amplitude: amplitude 0.01 m on a wavelength of 0.01 m gives slopes of 81.0°, steeper than 80°")
            && steep.contains("amplitude ≤ 0.0090 m"),
        "{steep}"
    );
    // Just within both bounds.
    assert!(Sinusoid::new(0.009, 0.01, 0.0, 0.0).is_ok());
    assert!(Sinusoid::new(1e-4, 1e-3, 0.0, 0.0).is_ok());
}
