//! The turning radius of a run: a least-squares circle through the path.

/// A circle in the XY plane.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Circle {
    /// Centre X \[m\].
    pub x: f64,
    /// Centre Y \[m\].
    pub y: f64,
    /// Radius \[m\].
    pub radius: f64,
    /// RMS distance of the points from the circle \[m\].
    pub rms_residual: f64,
}

/// Algebraic (Kåsa) fit: minimise Σ (x² + y² + D·x + E·y + F)², then
/// refine the radius as the mean distance from the centre. Points are
/// centred on their mean first for conditioning. None for fewer than 3
/// points or a straight path (singular normal equations).
pub fn fit_circle(points: &[[f64; 2]]) -> Option<Circle> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |a, p| (a.0 + p[0], a.1 + p[1]));
    let (mx, my) = (mx / n as f64, my / n as f64);
    // Normal equations of [x y 1]·[D E F]ᵀ = −(x² + y²).
    let mut a = [[0.0f64; 3]; 3];
    let mut b = [0.0f64; 3];
    for p in points {
        let (x, y) = (p[0] - mx, p[1] - my);
        let row = [x, y, 1.0];
        let r = -(x * x + y * y);
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * r;
        }
    }
    let sol = solve3(a, b)?;
    let (cx, cy) = (-sol[0] / 2.0, -sol[1] / 2.0);
    let r2 = cx * cx + cy * cy - sol[2];
    if r2.is_nan() || r2 <= 0.0 || !r2.is_finite() {
        return None;
    }
    let dist: Vec<f64> = points
        .iter()
        .map(|p| ((p[0] - mx - cx).powi(2) + (p[1] - my - cy).powi(2)).sqrt())
        .collect();
    let radius = dist.iter().sum::<f64>() / n as f64;
    let rms = (dist.iter().map(|d| (d - radius).powi(2)).sum::<f64>() / n as f64).sqrt();
    Some(Circle {
        x: cx + mx,
        y: cy + my,
        radius,
        rms_residual: rms,
    })
}

fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..3 {
        let p = (c..3).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() <= 1e-13 * scale {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..3 {
            let f = a[r][c] / a[c][c];
            for k in c..3 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 3];
    for c in (0..3).rev() {
        let s: f64 = (c + 1..3).map(|k| a[c][k] * x[k]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    Some(x)
}
