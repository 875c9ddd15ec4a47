//! Single-field checks: each reports a located [`Diagnostic`] and says how
//! to fix it. Non-finite numbers are reported once, by [`non_finite`], and
//! skipped here.

use crate::diagnostic::Diagnostic;

/// Collects diagnostics while validating.
#[derive(Default)]
pub struct Ctx {
    /// Everything found so far.
    pub diags: Vec<Diagnostic>,
}

/// Format a number for a message: short, round-trippable enough to read.
pub fn num(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e6).contains(&a) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        // Four significant digits, without trailing zeros: 1e-4, 1.2346e-5.
        let s = format!("{v:.4e}");
        match s.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => {
                format!(
                    "{}e{exp}",
                    mantissa.trim_end_matches('0').trim_end_matches('.')
                )
            }
            _ => s,
        }
    }
}

/// A coordinate value in its unit: degrees for angles, metres for lengths.
pub fn coord_value(v: f64, linear: bool) -> String {
    if linear {
        format!("{} m", num(v))
    } else {
        format!("{}°", num(v.to_degrees()))
    }
}

impl Ctx {
    /// Report a problem at `path`.
    pub fn error(
        &mut self,
        path: impl Into<String>,
        message: impl Into<String>,
        help: impl Into<String>,
    ) {
        let path = path.into();
        // One report per field: the first says what is wrong.
        if self.diags.iter().any(|d| d.path == path) {
            return;
        }
        self.diags.push(Diagnostic::at(path, message, help));
    }

    /// `v > 0`, or a report; `what` names the quantity and its unit.
    pub fn positive(&mut self, path: &str, v: f64, help: &str) -> Option<f64> {
        if !v.is_finite() {
            return None;
        }
        if v > 0.0 {
            Some(v)
        } else {
            self.error(path, format!("must be > 0, got {}", num(v)), help);
            None
        }
    }

    /// `v ≥ 0`, or a report.
    pub fn non_negative(&mut self, path: &str, v: f64, help: &str) -> Option<f64> {
        if !v.is_finite() {
            return None;
        }
        if v >= 0.0 {
            Some(v)
        } else {
            self.error(path, format!("must be ≥ 0, got {}", num(v)), help);
            None
        }
    }

    /// A finite number (non-finite ones are already reported).
    pub fn finite(&mut self, v: f64) -> Option<f64> {
        v.is_finite().then_some(v)
    }

    /// A field given in radians or in degrees (`<field>_deg`), at most one
    /// of the two; the value in radians (or metres for a linear coordinate).
    pub fn angle(
        &mut self,
        base: &str,
        field: &str,
        rad: Option<f64>,
        deg: Option<f64>,
        linear: bool,
    ) -> Result<Option<f64>, ()> {
        match (rad, deg) {
            (Some(_), Some(_)) => {
                self.error(
                    format!("{base}.{field}_deg"),
                    format!("`{field}` and `{field}_deg` are both given"),
                    format!("keep one: `{field}` in radians or `{field}_deg` in degrees"),
                );
                Err(())
            }
            (None, Some(_)) if linear => {
                self.error(
                    format!("{base}.{field}_deg"),
                    "a linear coordinate has no degrees",
                    format!("give `{field}` in metres"),
                );
                Err(())
            }
            (Some(v), None) => self.finite(v).map(Some).ok_or(()),
            (None, Some(d)) => self.finite(d).map(|d| Some(d.to_radians())).ok_or(()),
            (None, None) => Ok(None),
        }
    }

    /// The path of a field given in radians or degrees (whichever is present).
    pub fn angle_path(base: &str, field: &str, deg_given: bool) -> String {
        if deg_given {
            format!("{base}.{field}_deg")
        } else {
            format!("{base}.{field}")
        }
    }
}

/// Every non-finite number of the description, reported where it is
/// (TOML allows `nan` and `inf`; a Rust description may hold them too).
pub fn non_finite(ctx: &mut Ctx, value: &toml::Value, path: &str) {
    each_leaf(value, path, &mut |v, path| {
        if let toml::Value::Float(f) = v
            && !f.is_finite()
        {
            ctx.error(
                path,
                format!("must be a finite number, got {f}"),
                "every number of a description is finite: replace it with a value in SI units",
            );
        }
    });
}

/// Calls `f(value, path)` for every value of a TOML document that is not an
/// array or a table, `path` its dotted field path (`a.b[2]`) below `path`.
pub fn each_leaf(value: &toml::Value, path: &str, f: &mut impl FnMut(&toml::Value, &str)) {
    match value {
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                each_leaf(v, &format!("{path}[{i}]"), f);
            }
        }
        toml::Value::Table(t) => {
            for (k, v) in t {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                each_leaf(v, &p, f);
            }
        }
        leaf => f(leaf, path),
    }
}

/// Eigenvalues of a symmetric 3×3 matrix (cyclic Jacobi), ascending.
#[allow(clippy::needless_range_loop)]
pub fn symmetric_eigenvalues(m: [[f64; 3]; 3]) -> [f64; 3] {
    let mut a = m;
    for _ in 0..50 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if off < 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]).max(1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ·A·J with the rotation in the (p, q) plane.
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
        }
    }
    let mut e = [a[0][0], a[1][1], a[2][2]];
    e.sort_by(f64::total_cmp);
    e
}
