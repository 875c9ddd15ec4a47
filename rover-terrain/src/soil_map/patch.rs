//! Soil patches: a shape, the class it lays over what lies under it, and
//! the width of the band over which it fades out.

use serde::{Deserialize, Serialize};

use super::super::error::TerrainError;
use super::smoothstep;

/// A patch's outline, as the scenario's `shape` key names it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum PatchShape {
    /// A disc of `radius` \[m\] (> 0) about `center` \[m\].
    Circle {
        /// `[X, Y]` of the centre \[m\].
        center: [f64; 2],
        /// \[m\], > 0.
        radius: f64,
    },
    /// An axis-aligned rectangle `x[0] ≤ X ≤ x[1]`, `y[0] ≤ Y ≤ y[1]` \[m\].
    Rectangle {
        /// `[min, max]` of X \[m\], min < max.
        x: [f64; 2],
        /// `[min, max]` of Y \[m\], min < max.
        y: [f64; 2],
    },
    /// A simple polygon (no edge crossing another) through `points` \[m\],
    /// at least 3, in either winding; closed from the last point to the
    /// first.
    Polygon {
        /// `[[X, Y], …]` \[m\].
        points: Vec<[f64; 2]>,
    },
}

/// A soil class over a shape: weight 1 well inside, 0 well outside, and a
/// C1 smoothstep of the signed distance to the outline across a band of
/// width `edge` centred on it (weight ½ on the outline itself), so that
/// the soil under a wheel changes continuously (`edge = 0`: a sharp
/// outline, the points on it inside).
#[derive(Clone, Debug, PartialEq)]
pub struct SoilPatch {
    shape: PatchShape,
    class: u16,
    edge: f64,
    /// `[x_min, x_max, y_min, y_max]` of the shape grown by `edge/2`:
    /// outside it the weight is 0, found with four comparisons.
    bbox: [f64; 4],
}

/// A parameter error naming the key.
fn bad(name: &str, problem: String, help: &str) -> TerrainError {
    TerrainError::parameter(name, problem, help)
}

fn finite_point(name: &str, p: [f64; 2]) -> Result<(), TerrainError> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(bad(
            name,
            format!("[{}, {}] is not a finite point", p[0], p[1]),
            "give [X, Y] in metres",
        ))
    }
}

/// The orientation of `c` seen from the segment `a → b`: > 0 to the left.
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Whether `c`, collinear with `a → b`, lies within its bounding box.
fn on_segment(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    c[0] >= a[0].min(b[0])
        && c[0] <= a[0].max(b[0])
        && c[1] >= a[1].min(b[1])
        && c[1] <= a[1].max(b[1])
}

/// Whether the closed segments `p1 p2` and `q1 q2` share a point.
fn segments_meet(p1: [f64; 2], p2: [f64; 2], q1: [f64; 2], q2: [f64; 2]) -> bool {
    let d1 = cross(q1, q2, p1);
    let d2 = cross(q1, q2, p2);
    let d3 = cross(p1, p2, q1);
    let d4 = cross(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_segment(q1, q2, p1))
        || (d2 == 0.0 && on_segment(q1, q2, p2))
        || (d3 == 0.0 && on_segment(p1, p2, q1))
        || (d4 == 0.0 && on_segment(p1, p2, q2))
}

/// Checks a polygon: ≥ 3 finite points, no repeated neighbours, no edge
/// folding back on the previous one, no two other edges meeting (so the
/// outline encloses an area).
fn check_polygon(points: &[[f64; 2]]) -> Result<(), TerrainError> {
    let n = points.len();
    if n < 3 {
        return Err(bad(
            "points",
            format!("a polygon needs at least 3 points, got {n}"),
            "give points = [[x, y], [x, y], [x, y], …] in metres, the outline in order",
        ));
    }
    for (k, &p) in points.iter().enumerate() {
        finite_point(&format!("points[{k}]"), p)?;
    }
    let simple_help = "give the outline's corners in order around it, each once, so that no \
                       edge crosses or touches another (a simple polygon)";
    for k in 0..n {
        let (a, b, c) = (points[k], points[(k + 1) % n], points[(k + 2) % n]);
        if a == b {
            return Err(bad(
                "points",
                format!(
                    "points[{k}] and points[{}] are the same point [{}, {}]",
                    (k + 1) % n,
                    a[0],
                    a[1]
                ),
                simple_help,
            ));
        }
        let folds = cross(a, b, c) == 0.0
            && (b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1]) < 0.0;
        if folds {
            return Err(bad(
                "points",
                format!(
                    "the outline turns back on itself at points[{}] = [{}, {}]",
                    (k + 1) % n,
                    b[0],
                    b[1]
                ),
                simple_help,
            ));
        }
    }
    for k in 0..n {
        for m in k + 2..n {
            if k == 0 && m == n - 1 {
                continue; // neighbours through the closing edge
            }
            let (p1, p2) = (points[k], points[(k + 1) % n]);
            let (q1, q2) = (points[m], points[(m + 1) % n]);
            if segments_meet(p1, p2, q1, q2) {
                return Err(bad(
                    "points",
                    format!(
                        "the edge from points[{k}] to points[{}] meets the edge from \
                         points[{m}] to points[{}]",
                        (k + 1) % n,
                        (m + 1) % n
                    ),
                    simple_help,
                ));
            }
        }
    }
    Ok(())
}

impl PatchShape {
    /// Checks the shape's numbers; the error names the key.
    pub fn check(&self) -> Result<(), TerrainError> {
        match self {
            PatchShape::Circle { center, radius } => {
                finite_point("center", *center)?;
                if !(radius.is_finite() && *radius > 0.0) {
                    return Err(bad(
                        "radius",
                        format!("must be > 0 m, got {radius}"),
                        "give the circle's radius in metres",
                    ));
                }
            }
            PatchShape::Rectangle { x, y } => {
                for (name, [lo, hi]) in [("x", x), ("y", y)] {
                    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                        let what = if lo == hi { "empty" } else { "inverted" };
                        return Err(bad(
                            name,
                            format!(
                                "[{lo}, {hi}] is {what}: the rectangle needs finite \
                                 {name} = [min, max] with min < max",
                            ),
                            "give the rectangle's extent along the axis as [min, max] in metres",
                        ));
                    }
                }
            }
            PatchShape::Polygon { points } => check_polygon(points)?,
        }
        Ok(())
    }

    /// `[x_min, x_max, y_min, y_max]` of the shape.
    fn bounding_box(&self) -> [f64; 4] {
        match self {
            PatchShape::Circle { center, radius } => [
                center[0] - radius,
                center[0] + radius,
                center[1] - radius,
                center[1] + radius,
            ],
            PatchShape::Rectangle { x, y } => [x[0], x[1], y[0], y[1]],
            PatchShape::Polygon { points } => points.iter().fold(
                [
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                ],
                |b, p| {
                    [
                        b[0].min(p[0]),
                        b[1].max(p[0]),
                        b[2].min(p[1]),
                        b[3].max(p[1]),
                    ]
                },
            ),
        }
    }

    /// The signed distance from (x, y) to the outline \[m\]: negative
    /// inside, positive outside (Euclidean, so 1-Lipschitz: the weight
    /// made from it is continuous).
    pub fn signed_distance(&self, x: f64, y: f64) -> f64 {
        match self {
            PatchShape::Circle { center, radius } => (x - center[0]).hypot(y - center[1]) - radius,
            PatchShape::Rectangle { x: xs, y: ys } => {
                let qx = (x - 0.5 * (xs[0] + xs[1])).abs() - 0.5 * (xs[1] - xs[0]);
                let qy = (y - 0.5 * (ys[0] + ys[1])).abs() - 0.5 * (ys[1] - ys[0]);
                qx.max(0.0).hypot(qy.max(0.0)) + qx.max(qy).min(0.0)
            }
            PatchShape::Polygon { points } => {
                let n = points.len();
                let mut nearest = f64::INFINITY;
                let mut inside = false;
                for k in 0..n {
                    let a = points[k];
                    let b = points[(k + 1) % n];
                    let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
                    let (px, py) = (x - a[0], y - a[1]);
                    let t = ((px * ex + py * ey) / (ex * ex + ey * ey)).clamp(0.0, 1.0);
                    nearest = nearest.min((px - t * ex).hypot(py - t * ey));
                    // Even–odd crossings of the ray towards +X.
                    if (a[1] > y) != (b[1] > y) && x < a[0] + (y - a[1]) / ey * ex {
                        inside = !inside;
                    }
                }
                if inside { -nearest } else { nearest }
            }
        }
    }
}

impl SoilPatch {
    /// A patch of `class` over `shape`, fading over `edge` \[m\] (≥ 0)
    /// centred on its outline; the error names the key at fault.
    pub fn new(shape: PatchShape, class: u16, edge: f64) -> Result<SoilPatch, TerrainError> {
        shape.check()?;
        if !(edge.is_finite() && edge >= 0.0) {
            return Err(bad(
                "edge",
                format!("must be ≥ 0 m, got {edge}"),
                "give the width of the band over which the patch fades into what lies under \
                 it, in metres (0: a sharp outline)",
            ));
        }
        let b = shape.bounding_box();
        let h = 0.5 * edge;
        Ok(SoilPatch {
            bbox: [b[0] - h, b[1] + h, b[2] - h, b[3] + h],
            shape,
            class,
            edge,
        })
    }

    /// The outline.
    pub fn shape(&self) -> &PatchShape {
        &self.shape
    }

    /// The soil class it lays.
    pub fn class(&self) -> u16 {
        self.class
    }

    /// The fade band's width \[m\].
    pub fn edge(&self) -> f64 {
        self.edge
    }

    /// The patch's weight at (x, y), in [0, 1].
    #[inline]
    pub fn alpha(&self, x: f64, y: f64) -> f64 {
        let b = &self.bbox;
        if !(x >= b[0] && x <= b[1] && y >= b[2] && y <= b[3]) {
            return 0.0;
        }
        let d = self.shape.signed_distance(x, y);
        if self.edge == 0.0 {
            return if d <= 0.0 { 1.0 } else { 0.0 };
        }
        1.0 - smoothstep(d / self.edge + 0.5)
    }
}
