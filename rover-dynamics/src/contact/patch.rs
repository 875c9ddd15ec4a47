//! What the contact search finds for one wheel.

use super::math;
pub(crate) use crate::linalg::{cross, dot, norm};

/// Most contact patches one wheel can have (a wheel straddling a ridge or
/// the two edges of a ditch); fixed so the search never allocates.
pub const MAX_PATCHES: usize = 4;

/// One contact patch: the chord AB of the rim below ground (MODEL.md §6).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Patch {
    /// Contact point H, the midpoint of AB, inertial \[m\].
    pub point: [f64; 3],
    /// Unit normal n = (G_j − H)/|G_j − H|, towards the wheel centre.
    pub normal: [f64; 3],
    /// Unit tangent t along AB, forward (t·f > 0).
    pub tangent: [f64; 3],
    /// Unit lateral c = n × t, to the wheel's left.
    pub lateral: [f64; 3],
    /// Radial deflection Δ = R_w − |G_jH| \[m\].
    pub deflection: f64,
    /// Distance |G_jH| \[m\]: the lever arm of the drive force.
    pub lever: f64,
    /// Rim angle of H, β from the downward direction d towards f \[rad\].
    pub angle: f64,
}

/// All the patches of one wheel.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Contact {
    /// The patches found; only the first `count` are meaningful.
    pub patches: [Patch; MAX_PATCHES],
    /// Number of patches (0: the wheel is in the air).
    pub count: usize,
    /// The lower half of the wheel is entirely below ground at one end
    /// (h < 0 at β = ±90°): the end was taken as the crossing, and the run
    /// summary flags it.
    pub deep: bool,
}

impl Contact {
    /// The patches found.
    pub fn patches(&self) -> &[Patch] {
        &self.patches[..self.count.min(MAX_PATCHES)]
    }

    /// Add a patch if room is left; returns false when the wheel already has
    /// [`MAX_PATCHES`] (the extra patch is dropped; the caller counts it).
    pub(crate) fn push(&mut self, p: Patch) -> bool {
        if self.count < MAX_PATCHES {
            self.patches[self.count] = p;
            self.count += 1;
            true
        } else {
            false
        }
    }
}

/// A rim angle β with its sine and cosine, computed once: a crossing found
/// by the search is also a patch end, and its point is needed again.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct RimAngle {
    pub beta: f64,
    pub sin: f64,
    pub cos: f64,
}

impl RimAngle {
    pub fn new(beta: f64) -> Self {
        let (sin, cos) = math::sin_cos(beta);
        Self { beta, sin, cos }
    }
}

/// Where a rim comes down to a height ([`RimFrame::below`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Below {
    /// A wheel plane near the horizontal, or a non-finite state: anywhere.
    Unknown,
    /// Nowhere: the whole rim is above.
    Nowhere,
    /// On `|β − lowest| ≤ width` \[rad\].
    Around { lowest: f64, width: f64 },
}

/// The wheel's mid-plane frame: `d` downward in the plane, `f = d × a` forward.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RimFrame {
    pub centre: [f64; 3],
    pub down: [f64; 3],
    pub forward: [f64; 3],
    pub radius: f64,
}

impl RimFrame {
    /// From the wheel centre, the unit spin axis and the radius. `d` is −e_Z
    /// projected on the mid-plane; a wheel lying flat (axis vertical) has no
    /// such direction and gets None.
    pub fn new(centre: [f64; 3], axis: [f64; 3], radius: f64) -> Option<Self> {
        let d = [
            axis[2] * axis[0],
            axis[2] * axis[1],
            axis[2] * axis[2] - 1.0,
        ];
        let len = math::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if len < 1e-9 {
            return None;
        }
        let down = [d[0] / len, d[1] / len, d[2] / len];
        let forward = cross(down, axis);
        Some(Self {
            centre,
            down,
            forward,
            radius,
        })
    }

    /// The square of side 2R around the centre, which holds the whole rim.
    pub fn area(&self) -> crate::height_field::Bounds {
        let ([cx, cy, _], r) = (self.centre, self.radius);
        crate::height_field::Bounds {
            x_min: cx - r,
            x_max: cx + r,
            y_min: cy - r,
            y_max: cy + r,
        }
    }

    /// Where the rim comes down to height `z` or below. The rim height is
    /// `Z(β) = Z_G − R·A·cos(β − β_m)` with `A = |(d_z, f_z)|` and β_m the
    /// lowest point, so `Z(β) ≤ z` on `|β − β_m| ≤ acos((Z_G − z)/(R·A))`.
    pub(crate) fn below(&self, z: f64) -> Below {
        let (cz, r) = (self.centre[2], self.radius);
        let (dz, fz) = (self.down[2], self.forward[2]);
        let a = math::hypot(dz, fz);
        if !(a > 1e-6 && z.is_finite() && cz.is_finite() && r > 0.0) {
            return Below::Unknown;
        }
        let c = (cz - z) / (r * a);
        if c > 1.0 {
            return Below::Nowhere;
        }
        Below::Around {
            lowest: math::atan2(-fz, -dz),
            width: math::acos(c.clamp(-1.0, 1.0)),
        }
    }

    /// Rim point P(β) = G + R·(cos β·d + sin β·f).
    pub fn point(&self, beta: f64) -> [f64; 3] {
        let (s, c) = math::sin_cos(beta);
        self.point_sc(s, c)
    }

    /// [`RimFrame::point`] from sin β and cos β.
    #[inline]
    pub fn point_sc(&self, s: f64, c: f64) -> [f64; 3] {
        let (g, d, f, r) = (self.centre, self.down, self.forward, self.radius);
        [
            g[0] + r * (c * d[0] + s * f[0]),
            g[1] + r * (c * d[1] + s * f[1]),
            g[2] + r * (c * d[2] + s * f[2]),
        ]
    }

    /// dP/dβ = R·(−sin β·d + cos β·f), from sin β and cos β.
    #[inline]
    pub fn tangent_sc(&self, s: f64, c: f64) -> [f64; 3] {
        let (d, f, r) = (self.down, self.forward, self.radius);
        [0, 1, 2].map(|k| r * (c * f[k] - s * d[k]))
    }

    /// Build the patch from its crossings A, B (rim angles).
    pub fn patch(&self, end_a: RimAngle, end_b: RimAngle) -> Patch {
        let (beta_a, beta_b) = (end_a.beta, end_b.beta);
        let a = self.point_sc(end_a.sin, end_a.cos);
        let b = self.point_sc(end_b.sin, end_b.cos);
        let h = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
        let gh = [0, 1, 2].map(|k| self.centre[k] - h[k]);
        let lever = norm(gh);
        // A chord through the centre cannot happen for a half-rim search; keep
        // the direction defined anyway by falling back to the mid-angle.
        let mid = 0.5 * (beta_a + beta_b);
        let normal = if lever > 1e-12 {
            gh.map(|v| v / lever)
        } else {
            let p = self.point(mid);
            let r = [0, 1, 2].map(|k| self.centre[k] - p[k]);
            let l = norm(r);
            r.map(|v| v / l)
        };
        let mut ab = [0, 1, 2].map(|k| b[k] - a[k]);
        if dot(ab, self.forward) < 0.0 {
            ab = ab.map(|v| -v);
        }
        let la = norm(ab);
        let tangent = if la > 1e-15 {
            ab.map(|v| v / la)
        } else {
            // A single-point contact: the rim tangent at H.
            let (s, c) = math::sin_cos(mid);
            [0, 1, 2].map(|k| c * self.forward[k] - s * self.down[k])
        };
        let lateral = cross(normal, tangent);
        Patch {
            point: h,
            normal,
            tangent,
            lateral,
            deflection: self.radius - lever,
            lever,
            angle: mid,
        }
    }
}
