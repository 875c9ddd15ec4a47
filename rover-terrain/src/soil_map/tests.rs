use super::*;
use crate::Georeference;

fn circle(center: [f64; 2], radius: f64, class: u16, edge: f64) -> SoilPatch {
    SoilPatch::new(PatchShape::Circle { center, radius }, class, edge).unwrap()
}

/// The weight of `class` in `w` (0 when absent).
fn weight(w: &SoilWeights, class: u16) -> f64 {
    w.iter().find(|&(c, _)| c == class).map_or(0.0, |(_, v)| v)
}

/// The L1 distance between two weight vectors, class by class.
fn distance(a: &SoilWeights, b: &SoilWeights) -> f64 {
    let mut d = 0.0;
    for (c, v) in a.iter() {
        d += (v - weight(b, c)).abs();
    }
    for (c, v) in b.iter() {
        if weight(a, c) == 0.0 {
            d += v;
        }
    }
    d
}

/// Checks the invariants of `w`: 1 … 4 classes, ascending, no repeats,
/// weights > 0 summing to 1.
fn check(w: &SoilWeights, at: (f64, f64)) {
    assert!((1..=4).contains(&w.count), "{at:?}: {w:?}");
    let sum: f64 = w.iter().map(|(_, v)| v).sum();
    assert!((sum - 1.0).abs() < 1e-12, "{at:?}: sum {sum}, {w:?}");
    for k in 0..w.count {
        assert!(w.weights[k] > 0.0, "{at:?}: {w:?}");
        if k > 0 {
            assert!(w.classes[k - 1] < w.classes[k], "{at:?}: {w:?}");
        }
    }
}

/// The largest L1 jump between neighbouring samples `h` apart along the
/// segment from `a` to `b`.
fn largest_jump(map: &SoilMap, a: [f64; 2], b: [f64; 2], h: f64) -> f64 {
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = (length / h).ceil() as usize;
    let at = |k: usize| {
        let t = k as f64 / n as f64;
        let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
        let w = map.weights(x, y);
        check(&w, (x, y));
        w
    };
    let mut previous = at(0);
    let mut largest: f64 = 0.0;
    for k in 1..=n {
        let w = at(k);
        largest = largest.max(distance(&previous, &w));
        previous = w;
    }
    largest
}

/// A 4 × 3 raster of four classes, every cell of mixed corners.
fn raster() -> ClassRaster {
    ClassRaster::new(
        Georeference {
            origin: [-1.0, -0.5],
            spacing: [0.5, 0.4],
        },
        4,
        3,
        vec![0, 1, 2, 3, 3, 2, 1, 0, 1, 3, 0, 2],
    )
    .unwrap()
}

#[test]
fn a_patch_is_its_class_inside_the_ground_outside_and_a_smoothstep_across_its_edge() {
    let edge = 0.4;
    let map = SoilMap::new(Some(0), None, vec![circle([1.0, 2.0], 1.5, 3, edge)]).unwrap();
    // Inside by more than edge/2, outside by more than edge/2.
    assert_eq!(map.weights(1.0, 2.0), SoilWeights::single(3));
    assert_eq!(map.weights(1.0 + 1.5 - 0.21, 2.0), SoilWeights::single(3));
    assert_eq!(map.weights(1.0, 2.0 + 1.5 + 0.21), SoilWeights::single(0));
    assert_eq!(map.weights(40.0, -7.0), SoilWeights::single(0));
    // On the outline: half and half.
    let w = map.weights(1.0 - 1.5, 2.0);
    assert!((weight(&w, 3) - 0.5).abs() < 1e-15 && (weight(&w, 0) - 0.5).abs() < 1e-15);
    // In the band: 1 − smoothstep(d/edge + 1/2) of the signed distance d.
    for d in [-0.19, -0.1, -0.03, 0.05, 0.12, 0.199] {
        let (s, c) = 0.7_f64.sin_cos();
        let w = map.weights(1.0 + (1.5 + d) * c, 2.0 + (1.5 + d) * s);
        let t = d / edge + 0.5;
        let want = 1.0 - (3.0 * t * t - 2.0 * t * t * t);
        assert!((weight(&w, 3) - want).abs() < 1e-12, "d = {d}: {w:?}");
        assert!(
            (weight(&w, 0) - (1.0 - want)).abs() < 1e-12,
            "d = {d}: {w:?}"
        );
        check(&w, (d, 0.0));
    }
}

#[test]
fn a_sharp_patch_switches_on_its_outline() {
    let map = SoilMap::new(Some(0), None, vec![circle([0.0, 0.0], 1.0, 1, 0.0)]).unwrap();
    assert_eq!(map.weights(1.0, 0.0), SoilWeights::single(1));
    assert_eq!(map.weights(1.0 + 1e-12, 0.0), SoilWeights::single(0));
}

#[test]
fn the_weights_across_a_patch_edge_are_continuous() {
    for (edge, shape) in [
        (
            0.2,
            PatchShape::Circle {
                center: [0.0, 0.0],
                radius: 1.0,
            },
        ),
        (
            0.5,
            PatchShape::Rectangle {
                x: [-1.0, 2.0],
                y: [-0.5, 0.5],
            },
        ),
        (
            0.3,
            PatchShape::Polygon {
                points: vec![
                    [-1.0, -1.0],
                    [1.5, -1.0],
                    [0.0, 0.0],
                    [1.5, 1.0],
                    [-1.0, 1.0],
                ],
            },
        ),
    ] {
        let map =
            SoilMap::new(Some(2), None, vec![SoilPatch::new(shape, 5, edge).unwrap()]).unwrap();
        // The weight is a smoothstep (slope ≤ 3/2) of a 1-Lipschitz
        // distance over `edge`: a step h changes the two weights by at
        // most 2·(3/2)·h/edge together.
        let (a, b) = ([-2.3, -1.7], [2.9, 1.3]);
        let coarse = largest_jump(&map, a, b, 1e-2);
        let fine = largest_jump(&map, a, b, 1e-3);
        assert!(coarse <= 3.0 * 1e-2 / edge * (1.0 + 1e-9), "{coarse}");
        assert!(fine <= 3.0 * 1e-3 / edge * (1.0 + 1e-9), "{fine}");
        assert!(fine < 0.2 * coarse, "coarse {coarse}, fine {fine}");
    }
}

#[test]
fn the_raster_merges_its_corners_bilinear_weights_by_class() {
    // Corners: (0, 0) → 1, (1, 0) → 2, (0, 1) → 1, (1, 1) → 3.
    let r = ClassRaster::new(
        Georeference {
            origin: [10.0, 20.0],
            spacing: [2.0, 4.0],
        },
        2,
        2,
        vec![1, 2, 1, 3],
    )
    .unwrap();
    let map = SoilMap::new(None, Some(r), vec![]).unwrap();
    assert_eq!(map.classes(), vec![1, 2, 3]);
    for (fu, fv) in [(0.25, 0.5), (0.9, 0.1), (0.5, 0.75)] {
        let w = map.weights(10.0 + 2.0 * fu, 20.0 + 4.0 * fv);
        check(&w, (fu, fv));
        assert_eq!(w.count, 3);
        assert!((weight(&w, 1) - (1.0 - fu)).abs() < 1e-12, "{w:?}");
        assert!((weight(&w, 2) - fu * (1.0 - fv)).abs() < 1e-12, "{w:?}");
        assert!((weight(&w, 3) - fu * fv).abs() < 1e-12, "{w:?}");
    }
    // The nodes are their classes; a corner with one class is that class.
    assert_eq!(map.weights(12.0, 24.0), SoilWeights::single(3));
    // Without a background, a point off the raster is clamped onto it.
    assert_eq!(map.weights(30.0, 50.0), SoilWeights::single(3));
    let w = map.weights(5.0, 22.0);
    assert!((weight(&w, 1) - 1.0).abs() < 1e-15, "{w:?}");
}

#[test]
fn the_weights_across_raster_cells_are_continuous() {
    let map = SoilMap::new(None, Some(raster()), vec![]).unwrap();
    // Bilinear weights: each corner's changes by at most |Δu| + |Δv| (in
    // cells), a class's by at most that times its corners.
    let (a, b) = ([-1.2, -0.6], [0.7, 0.45]);
    let coarse = largest_jump(&map, a, b, 1e-2);
    let fine = largest_jump(&map, a, b, 1e-3);
    assert!(
        coarse > 0.0 && fine < 0.2 * coarse,
        "coarse {coarse}, fine {fine}"
    );
    let bound = |h: f64| 2.0 * 4.0 * h * (1.0 / 0.5 + 1.0 / 0.4);
    assert!(
        coarse <= bound(1e-2) && fine <= bound(1e-3),
        "{coarse} {fine}"
    );
}

#[test]
fn over_a_background_the_raster_fades_out_over_half_a_spacing_beyond_its_nodes() {
    let map = SoilMap::new(Some(7), Some(raster()), vec![]).unwrap();
    // The south-west node (class 0) and below it: spacing dy = 0.4.
    assert_eq!(map.weights(-1.0, -0.5), SoilWeights::single(0));
    assert_eq!(map.weights(-1.0, -0.5 - 0.2), SoilWeights::single(7));
    assert_eq!(map.weights(-1.0, -5.0), SoilWeights::single(7));
    let w = map.weights(-1.0, -0.5 - 0.1);
    assert!((weight(&w, 0) - 0.5).abs() < 1e-12 && (weight(&w, 7) - 0.5).abs() < 1e-12);
    assert_eq!(map.classes(), vec![0, 1, 2, 3, 7]);
    let coarse = largest_jump(&map, [-1.6, -1.0], [1.0, 0.5], 1e-2);
    let fine = largest_jump(&map, [-1.6, -1.0], [1.0, 0.5], 1e-3);
    assert!(
        coarse > 0.0 && fine < 0.2 * coarse,
        "coarse {coarse}, fine {fine}"
    );
}

#[test]
fn overlapping_patches_compose_as_alpha_blending_in_order() {
    let lower = circle([0.0, 0.0], 1.0, 1, 0.6);
    let upper = circle([1.2, 0.0], 0.6, 2, 0.4);
    let map = SoilMap::new(Some(0), None, vec![lower.clone(), upper.clone()]).unwrap();
    for (x, y) in [
        (0.7, 0.1),
        (0.85, -0.2),
        (1.0, 0.3),
        (0.6, 0.0),
        (1.1, 0.05),
    ] {
        let (a1, a2) = (lower.alpha(x, y), upper.alpha(x, y));
        let w = map.weights(x, y);
        check(&w, (x, y));
        assert!(
            (weight(&w, 0) - (1.0 - a1) * (1.0 - a2)).abs() < 1e-12,
            "{w:?}"
        );
        assert!((weight(&w, 1) - a1 * (1.0 - a2)).abs() < 1e-12, "{w:?}");
        assert!((weight(&w, 2) - a2).abs() < 1e-12, "{w:?}");
    }
    // The later patch covers the earlier one where it is whole.
    assert_eq!(map.weights(1.2, 0.0), SoilWeights::single(2));
    // In the other order the first circle lies over the second.
    let swapped = SoilMap::new(Some(0), None, vec![upper, lower]).unwrap();
    assert_eq!(swapped.weights(0.65, 0.0), SoilWeights::single(1));
    // A patch of the class under it changes nothing.
    let same = SoilMap::new(Some(0), None, vec![circle([0.0, 0.0], 1.0, 0, 0.5)]).unwrap();
    assert_eq!(same.weights(1.0, 0.0), SoilWeights::single(0));
    assert_eq!(same.is_uniform(), Some(0));
}

#[test]
fn more_than_four_soils_keep_the_four_heaviest_continuously() {
    // A cell of four classes under a patch of a fifth, and a sixth patch.
    let map = SoilMap::new(
        None,
        Some(raster()),
        vec![
            circle([-0.6, -0.2], 0.3, 9, 0.5),
            circle([-0.9, -0.3], 0.2, 8, 0.3),
        ],
    )
    .unwrap();
    let mut most = 0;
    for k in 0..=400 {
        for m in 0..=100 {
            let (x, y) = (-1.0 + 1.5 * k as f64 / 400.0, -0.5 + 0.8 * m as f64 / 100.0);
            let w = map.weights(x, y);
            check(&w, (x, y));
            most = most.max(w.count);
        }
    }
    assert_eq!(most, 4);
    for (a, b) in [([-1.0, -0.45], [-0.2, 0.1]), ([-1.2, -0.3], [0.0, -0.1])] {
        let coarse = largest_jump(&map, a, b, 1e-2);
        let fine = largest_jump(&map, a, b, 1e-3);
        assert!(fine < 0.2 * coarse, "coarse {coarse}, fine {fine}");
    }
}

#[test]
fn every_point_of_a_layered_map_has_weights_summing_to_one() {
    let polygon = PatchShape::Polygon {
        points: vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [1.0, 0.5], [0.0, 2.0]],
    };
    let map = SoilMap::new(
        Some(4),
        Some(raster()),
        vec![
            circle([0.0, 0.0], 0.8, 5, 0.3),
            SoilPatch::new(polygon, 6, 0.2).unwrap(),
            SoilPatch::new(
                PatchShape::Rectangle {
                    x: [-0.5, 1.5],
                    y: [0.2, 0.4],
                },
                1,
                0.1,
            )
            .unwrap(),
        ],
    )
    .unwrap();
    assert_eq!(map.classes(), vec![0, 1, 2, 3, 4, 5, 6]);
    assert_eq!(map.is_uniform(), None);
    for k in 0..=200 {
        for m in 0..=200 {
            let (x, y) = (-2.0 + 5.0 * k as f64 / 200.0, -2.0 + 5.0 * m as f64 / 200.0);
            check(&map.weights(x, y), (x, y));
        }
    }
    assert_eq!(map.weights(f64::NAN, 0.0), SoilWeights::single(4));
}

#[test]
fn a_polygons_signed_distance_is_the_rectangles_for_a_rectangle_and_sees_concave_corners() {
    let rect = PatchShape::Rectangle {
        x: [-1.0, 2.0],
        y: [0.5, 1.5],
    };
    let poly = PatchShape::Polygon {
        points: vec![[-1.0, 0.5], [-1.0, 1.5], [2.0, 1.5], [2.0, 0.5]],
    };
    for (x, y) in [(0.0, 1.0), (3.0, 3.0), (-1.5, 1.0), (1.9, 0.6), (0.5, -0.2)] {
        let (a, b) = (rect.signed_distance(x, y), poly.signed_distance(x, y));
        assert!((a - b).abs() < 1e-12, "({x}, {y}): {a} vs {b}");
    }
    assert!((rect.signed_distance(3.0, 3.0) - 1.0_f64.hypot(1.5)).abs() < 1e-12);
    assert!((rect.signed_distance(0.0, 1.0) + 0.5).abs() < 1e-12);
    // An L: the notch is outside.
    let l = PatchShape::Polygon {
        points: vec![
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ],
    };
    assert!((l.signed_distance(1.5, 1.5) - 0.5).abs() < 1e-12);
    assert!((l.signed_distance(1.2, 1.3) - 0.2).abs() < 1e-12);
    assert!((l.signed_distance(3.0, 2.0) - 1.0_f64.hypot(1.0)).abs() < 1e-12);
    assert!((l.signed_distance(0.5, 1.5) + 0.5).abs() < 1e-12);
}

#[test]
fn bad_patches_are_refused_naming_the_key() {
    let refused =
        |shape: PatchShape, edge: f64| SoilPatch::new(shape, 0, edge).unwrap_err().to_string();
    let e = refused(
        PatchShape::Circle {
            center: [0.0, 0.0],
            radius: 0.0,
        },
        0.1,
    );
    assert!(e.starts_with("terrain.radius: must be > 0 m, got 0"), "{e}");
    let e = refused(
        PatchShape::Rectangle {
            x: [1.0, 0.0],
            y: [0.0, 1.0],
        },
        0.1,
    );
    assert!(e.starts_with("terrain.x: [1, 0] is inverted"), "{e}");
    let e = refused(
        PatchShape::Rectangle {
            x: [0.0, 1.0],
            y: [2.0, 2.0],
        },
        0.1,
    );
    assert!(e.starts_with("terrain.y: [2, 2] is empty"), "{e}");
    let e = refused(
        PatchShape::Circle {
            center: [0.0, 0.0],
            radius: 1.0,
        },
        -0.1,
    );
    assert!(
        e.starts_with("terrain.edge: must be ≥ 0 m, got -0.1"),
        "{e}"
    );
    let e = refused(
        PatchShape::Polygon {
            points: vec![[0.0, 0.0], [1.0, 0.0]],
        },
        0.1,
    );
    assert!(e.contains("at least 3 points, got 2"), "{e}");
    let bow_tie = vec![[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]];
    let e = refused(PatchShape::Polygon { points: bow_tie }, 0.1);
    assert!(
        e.contains(
            "the edge from points[0] to points[1] meets the edge from points[2] to points[3]"
        ),
        "{e}"
    );
    let folded = vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    let e = refused(PatchShape::Polygon { points: folded }, 0.1);
    assert!(
        e.contains("turns back on itself at points[1] = [2, 0]"),
        "{e}"
    );
    let e = SoilMap::new(None, None, vec![circle([0.0, 0.0], 1.0, 0, 0.1)])
        .unwrap_err()
        .to_string();
    assert!(e.contains("the patches lie over nothing"), "{e}");
}
