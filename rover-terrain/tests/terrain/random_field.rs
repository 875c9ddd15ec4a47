//! The seeded random field and its statistics.

use rover_dynamics::height_field::*;
use rover_terrain::*;

use super::support::*;

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
