//! A rigid wheel on deformable soil (terramechanics), written once, generic
//! over the scalar, like the rigid-ground law: runs evaluate it with `f64`,
//! the generator traces it, dual numbers differentiate it.
//!
//! The stresses along the contact arc, from the entry angle θ1 (where the
//! wheel meets undisturbed soil, the sinkage being `z = r·(1 − cos θ1)`) back
//! to the exit angle θ2 = −c_r·θ1 (docs/MODEL.md, "Soft soil"):
//!
//! - normal stress (Bekker's pressure–sinkage law with the Wong–Reece
//!   distribution, its maximum at θm = (a0 + a1·s)·θ1):
//!   `σ(θ) = (k_c/b + k_φ)·rⁿ·(cos θ* − cos θ1)ⁿ`, with θ* = θ in front of
//!   θm and `θ* = θ1 − (θ − θ2)/(θm − θ2)·(θ1 − θm)` behind it;
//! - shear stress (Mohr–Coulomb with Janosi–Hanamoto's shear
//!   displacement): `τ = (c + σ·tan φ)·(1 − exp(−|j|/K))` with the sign of
//!   `j(θ) = r·[a·(θ1 − θ) − b·(sin θ1 − sin θ)]`;
//! - lateral shear under a slip angle β (Ishigami et al., J. Field Robotics
//!   24(3), 2007): `τ_y = (c + σ·tan φ)·(1 − exp(−|j_y|/K_y))` with the
//!   sign of `j_y = r·b·(θ1 − θ)·tan β`;
//!
//! - with the soil's unit weight γ given, the bulldozing resistance on the
//!   wheel's side face under a slip angle (Ishigami et al. 2007):
//!   `F_b = ∫ D1·(c·h + D2·γ·h²/2)·(r − h·cos θ) dθ`, h = r·(cos θ − cos θ1),
//!   D1 = cot X_c + tan(X_c + φ), D2 = cot X_c + cot² X_c/cot φ,
//!   X_c = 45° − φ/2, added to the lateral force with the sign of β;
//!
//! and their resultants on a wheel of radius r and width b: the vertical
//! load `W = r·b·∫(σ cos θ + τ sin θ)dθ`, the drawbar pull
//! `DP = r·b·∫(τ cos θ − σ sin θ)dθ`, the driving torque `T = r²·b·∫τ dθ`
//! and the lateral force `F_y = r·b·∫τ_y dθ`.
//!
//! With u = r·ω the rim's speed and v the centre's, a = u/D and b = v/D,
//! D = max(|u|, v) ([`Shear`]): the shear displacement is the slip
//! velocity `u − v·cos θ` integrated over the time a soil element has been
//! under the wheel, timed by the rim's rotation when driving and by the
//! wheel's travel when braking. Slip is `s = 1 − v/(r·ω)` driving (a = 1,
//! b = 1 − s: Wong and Reece's j) and `s = r·ω/v − 1` braking (a = 1 + s,
//! b = 1: Wong's braked wheel), in [−1, 1] both; a locked wheel (s = −1)
//! shears the soil by the distance it slid, `r·(sin θ1 − sin θ)`.
//!
//! The integrals are taken by Gauss–Legendre quadrature on the arc's two
//! pieces, [θ2, θm] and [θm, θ1], whose ends are where the stresses have a
//! kink or a power-law edge: the nodes never sit on either, so `ln` never
//! sees zero, and each piece's nodes are squeezed towards its power-law
//! edge, so that 4 points a piece hold the forces to 1e-4.

use crate::scalar::Scalar;

/// A soil's terramechanics parameters, SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Soil {
    /// Pressure–sinkage exponent n.
    pub n: f64,
    /// Cohesive modulus k_c [N/m^(n+1)].
    pub k_c: f64,
    /// Frictional modulus k_φ [N/m^(n+2)].
    pub k_phi: f64,
    /// Cohesion c \[Pa\].
    pub cohesion: f64,
    /// Internal friction angle φ \[rad\].
    pub friction_angle: f64,
    /// Janosi–Hanamoto shear modulus K \[m\].
    pub shear_modulus: f64,
    /// Lateral shear modulus K_y \[m\].
    pub lateral_shear_modulus: f64,
    /// Wong–Reece a0: θm = (a0 + a1·s)·θ1.
    pub a0: f64,
    /// Wong–Reece a1.
    pub a1: f64,
    /// Rear ratio c_r: the exit angle is θ2 = −c_r·θ1 (0: the soil does
    /// not rebound behind the wheel).
    pub rear_ratio: f64,
    /// Unit weight γ = ρ·g [N/m³] for the bulldozing resistance on the
    /// wheel's side under a slip angle (Ishigami et al. 2007); 0 leaves it
    /// out.
    pub unit_weight: f64,
    /// Wong's unloading–reloading modulus at zero past sinkage, k_0
    /// \[Pa/m\]: `k_u = k_0 + A_u·z_u` ([`Compaction`]).
    pub reload_k0: f64,
    /// Its growth with the past sinkage z_u, A_u \[Pa/m²\]. With k_0 and
    /// A_u both 0 the soil keeps no memory of its load: a wheel over a
    /// rut meets it as fresh soil at the rut's floor.
    pub reload_au: f64,
}

/// What earlier passes left in the soil under a wheel (docs/MODEL.md,
/// "Ruts and multipass"): the soil there was pressed `past_sinkage` z_u
/// below its undisturbed surface, so it carried the pressure
/// `p_u = k·z_u^n` of Bekker's law (k = k_c/b + k_φ), and it sprang back
/// elastically by `p_u/k_u`, `k_u = k_0 + A_u·z_u`, when the load left
/// (Wong, *Theory of Ground Vehicles*, 4th ed. 2008, "response to
/// repetitive loading"). The rut's floor is the surface a wheel sinks
/// into now; below it the soil answers elastically up to `p_u`, then
/// follows Bekker's law again from z_u on:
/// ```text
/// σ(z) = k_u·z                       z ≤ z_e = p_u/k_u
/// σ(z) = k·(z_u + z − z_e)^n         beyond
/// ```
/// with z the sinkage below the floor: continuous at z_e, and Bekker's
/// own curve when z_u = 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Compaction {
    /// The deepest sinkage below the undisturbed surface the soil has
    /// been pressed to, z_u \[m\] (0: fresh soil).
    pub past_sinkage: f64,
}

/// The reloading law of a wheel over compacted soil ([`Compaction`]), in
/// the units of the stress integrals (sinkages over the radius r).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reload {
    /// k_u·r: the elastic stress per unit of z/r \[Pa\].
    elastic: f64,
    /// z_e/r: where the soil yields again.
    knee: f64,
    /// z_u/r.
    offset: f64,
    /// p_u \[Pa\].
    yield_stress: f64,
}

impl Reload {
    /// The sinkage below the rut's floor at which the soil yields again,
    /// z_e = p_u/k_u \[m\], for a wheel of `radius`.
    pub fn elastic_sinkage(&self, radius: f64) -> f64 {
        self.knee * radius
    }

    /// The pressure the soil already carried, p_u \[Pa\].
    pub fn yield_stress(&self) -> f64 {
        self.yield_stress
    }
}

/// A rigid wheel (radius and width) in a soil, with the constants of the
/// stress integrals derived once: a run evaluates the forces many times
/// for one wheel and soil.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoilWheel {
    /// The soil.
    pub soil: Soil,
    /// Radius r \[m\].
    pub radius: f64,
    /// Width b \[m\].
    pub width: f64,
    /// (k_c/b + k_φ)·rⁿ: the normal stress over (cos θ* − cos θ1)ⁿ \[Pa\].
    pressure: f64,
    /// k_c/b + k_φ: Bekker's pressure over zⁿ [N/m^(n+2)].
    modulus: f64,
    /// tan φ.
    tan_phi: f64,
    /// 1/K and 1/K_y \[1/m\].
    inv_k: f64,
    inv_ky: f64,
    /// The side's bulldozing factors D1 and D2·γ/2 \[N/m³\] (Ishigami et
    /// al. 2007), when the soil has a unit weight.
    bulldozing: Option<(f64, f64)>,
}

impl SoilWheel {
    /// A wheel of `radius` and `width` in `soil`.
    pub fn new(soil: &Soil, radius: f64, width: f64) -> Self {
        Self {
            soil: *soil,
            radius,
            width,
            pressure: (soil.k_c / width + soil.k_phi) * libm::pow(radius, soil.n),
            modulus: soil.k_c / width + soil.k_phi,
            tan_phi: libm::tan(soil.friction_angle),
            inv_k: 1.0 / soil.shear_modulus,
            inv_ky: 1.0 / soil.lateral_shear_modulus,
            bulldozing: (soil.unit_weight > 0.0).then(|| {
                // The failure wedge's angle X_c = 45° − φ/2 (Terzaghi).
                let phi = soil.friction_angle;
                let x_c = core::f64::consts::FRAC_PI_4 - 0.5 * phi;
                let cot = |a: f64| 1.0 / libm::tan(a);
                let d1 = cot(x_c) + libm::tan(x_c + phi);
                let d2 = cot(x_c) + cot(x_c) * cot(x_c) / cot(phi);
                (d1, 0.5 * d2 * soil.unit_weight)
            }),
        }
    }

    /// Bekker's pressure under this wheel at sinkage `z` \[m\] in fresh
    /// soil, `(k_c/b + k_φ)·zⁿ` \[Pa\].
    pub fn pressure_at(&self, z: f64) -> f64 {
        self.modulus * libm::pow(z.max(0.0), self.soil.n)
    }

    /// The reloading law over soil pressed to `compaction` ([`Compaction`]);
    /// `None` for fresh soil, or a soil without memory (k_0 = A_u = 0).
    ///
    /// The elastic line is never softer than the secant `p_u/z_u`: the
    /// soil springs back at most as far as it sank. Wong's `k_0 + A_u·z_u`,
    /// measured at sinkages of centimetres, is softer than that for a firm
    /// soil pressed a few millimetres (LETE sand under a rover's wheel: it
    /// would spring back 40 mm from 2.4), and a wheel after it would sink
    /// deeper into compacted soil than into fresh.
    pub fn reload(&self, compaction: Compaction) -> Option<Reload> {
        let z_u = compaction.past_sinkage;
        let wong = self.soil.reload_k0 + self.soil.reload_au * z_u;
        // NaN is fresh soil too.
        if !(z_u > 0.0 && wong > 0.0) {
            return None;
        }
        let r = self.radius;
        let p_u = self.pressure_at(z_u);
        let k_u = wong.max(p_u / z_u);
        Some(Reload {
            elastic: k_u * r,
            knee: p_u / k_u / r,
            offset: z_u / r,
            yield_stress: p_u,
        })
    }

    /// The depth of the rut a pass pressing the soil `past_sinkage` z_u
    /// \[m\] below its undisturbed surface leaves once the load is gone:
    /// z_u less the elastic spring-back `p_u/k_u` ([`Compaction`]); z_u for
    /// a soil without memory.
    pub fn rut_depth(&self, past_sinkage: f64) -> f64 {
        match self.reload(Compaction { past_sinkage }) {
            Some(reload) => (past_sinkage - reload.elastic_sinkage(self.radius)).max(0.0),
            None => past_sinkage.max(0.0),
        }
    }
}

/// Gauss–Legendre quadrature of `Q` points on [−1, 1]: nodes and weights,
/// computed once (Newton's iteration on the Legendre polynomial), without
/// allocation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GaussLegendre<const Q: usize> {
    /// Nodes, ascending, in (−1, 1).
    pub nodes: [f64; Q],
    /// Weights, summing to 2.
    pub weights: [f64; Q],
}

impl<const Q: usize> Default for GaussLegendre<Q> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const Q: usize> GaussLegendre<Q> {
    /// The rule, exact for polynomials of degree 2Q − 1.
    pub fn new() -> Self {
        let mut nodes = [0.0; Q];
        let mut weights = [0.0; Q];
        for i in 0..Q {
            // Tricomi's initial guess for the i-th root, from the right.
            let k = (i + 1) as f64;
            let q = Q as f64;
            let mut x = libm::cos(core::f64::consts::PI * (k - 0.25) / (q + 0.5));
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(Q, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(Q, x);
            dp = if d != 0.0 { d } else { dp };
            nodes[Q - 1 - i] = x;
            weights[Q - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
        }
        Self { nodes, weights }
    }
}

/// P_q(x) and its derivative, by the three-term recurrence.
fn legendre(q: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    for k in 2..=q {
        let k = k as f64;
        let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    if q == 0 {
        return (1.0, 0.0);
    }
    let d = q as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

/// A rigid wheel's state in the soil.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoilContact<S = f64> {
    /// Entry angle θ1 \[rad\], in [0, π/2]: the sinkage is r·(1 − cos θ1).
    pub entry_angle: S,
    /// Slip s, in (−1, 1): positive driving, negative braking.
    pub slip: S,
    /// Slip angle β \[rad\] between the wheel's heading and its velocity.
    pub slip_angle: S,
}

/// The soil's forces on the wheel, in the wheel's frame: vertical (up),
/// along its heading, across it, and the torque resisting its spin.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SoilForces<S = f64> {
    /// Vertical load carried, W \[N\].
    pub vertical: S,
    /// Drawbar pull DP along the heading \[N\].
    pub drawbar: S,
    /// Torque the soil's shear takes from the wheel, T [N·m].
    pub torque: S,
    /// Lateral force F_y, along the wheel's axle (positive towards the
    /// side the slip angle points to) \[N\].
    pub lateral: S,
}

/// The shear displacement's two rates, `j = r·[a·(θ1 − θ) − b·(sin θ1 −
/// sin θ)]`: the rim's speed a and the centre's b, each over the larger of
/// the two (the module's doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shear<S = f64> {
    /// a = r·ω / max(|r·ω|, v), in [−1, 1].
    pub rim: S,
    /// b = v / max(|r·ω|, v), in [0, 1].
    pub travel: S,
}

impl<S: Scalar> Shear<S> {
    /// The rates at slip `s` in [−1, 1]: a = 1 + min(s, 0), b = 1 − max(s, 0).
    pub fn of_slip(s: S) -> Self {
        Self {
            rim: S::one() + s.min(S::zero()),
            travel: S::one() - s.max(S::zero()),
        }
    }
}

/// The soil's forces on `wheel` in the state `contact`, by the quadrature
/// `rule` on each piece of the arc.
/// Allocates nothing; generic over the scalar (the generator traces it).
pub fn soil_forces<S: Scalar, const Q: usize>(
    wheel: &SoilWheel,
    contact: SoilContact<S>,
    rule: &GaussLegendre<Q>,
) -> SoilForces<S> {
    soil_forces_sheared(wheel, contact, Shear::of_slip(contact.slip), rule)
}

/// [`soil_forces`] with the shear's rates given ([`Shear`]): a wheel whose
/// rim turns against its travel (a < 0) too. The slip of `contact` places
/// the stress's maximum only.
pub fn soil_forces_sheared<S: Scalar, const Q: usize>(
    wheel: &SoilWheel,
    contact: SoilContact<S>,
    shear: Shear<S>,
    rule: &GaussLegendre<Q>,
) -> SoilForces<S> {
    forces_at(wheel, contact, shear, None, rule)
}

/// [`soil_forces`] over soil that earlier passes compacted
/// ([`Compaction`]): `contact`'s entry angle is measured from the rut's
/// floor.
pub fn soil_forces_compacted<S: Scalar, const Q: usize>(
    wheel: &SoilWheel,
    contact: SoilContact<S>,
    compaction: Compaction,
    rule: &GaussLegendre<Q>,
) -> SoilForces<S> {
    let shear = Shear::of_slip(contact.slip);
    forces_at(
        wheel,
        contact,
        shear,
        wheel.reload(compaction).as_ref(),
        rule,
    )
}

/// [`forces_on_arc`] at `contact`'s entry angle (its sine and cosine
/// taken here) and slip angle.
fn forces_at<S: Scalar, const Q: usize>(
    wheel: &SoilWheel,
    contact: SoilContact<S>,
    shear: Shear<S>,
    reload: Option<&Reload>,
    rule: &GaussLegendre<Q>,
) -> SoilForces<S> {
    let theta1 = contact.entry_angle;
    let beta = contact.slip_angle;
    let arc = EntryAngle {
        angle: theta1,
        sin: theta1.sin(),
        cos: theta1.cos(),
    };
    let tan_beta = beta.sin() / beta.cos();
    forces_on_arc(wheel, arc, contact.slip, tan_beta, shear, reload, rule)
}

/// The entry angle θ1 with its sine and cosine, as a caller that knows
/// them from the geometry gives them ([`crate::wheel_soil`]: the sinkage).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EntryAngle<S> {
    /// θ1 \[rad\].
    pub(crate) angle: S,
    /// sin θ1.
    pub(crate) sin: S,
    /// cos θ1.
    pub(crate) cos: S,
}

/// [`soil_forces_sheared`] at the entry angle `entry`, slip `s` (which
/// places the stress's maximum) and the tangent of the slip angle,
/// `tan_beta`, over fresh soil or, with `reload`, over soil an earlier
/// pass compacted ([`Compaction`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn forces_on_arc<S: Scalar, const Q: usize>(
    wheel: &SoilWheel,
    entry: EntryAngle<S>,
    s: S,
    tan_beta: S,
    shear: Shear<S>,
    reload: Option<&Reload>,
    rule: &GaussLegendre<Q>,
) -> SoilForces<S> {
    let soil = &wheel.soil;
    let r = S::cst(wheel.radius);
    let EntryAngle {
        angle: theta1,
        sin: sin1,
        cos: cos1,
    } = entry;
    let zero = S::zero();
    let one = S::one();
    let theta2 = S::cst(-soil.rear_ratio) * theta1;
    // θm between the ends.
    let theta_m = (S::cst(soil.a0) + S::cst(soil.a1) * s) * theta1;
    let theta_m = theta_m.min(theta1).max(theta2);
    let (rim, travel) = (shear.rim, shear.travel);
    let k = S::cst(wheel.pressure);
    let tan_phi = S::cst(wheel.tan_phi);
    let cohesion = S::cst(soil.cohesion);
    let inv_k = S::cst(wheel.inv_k);
    let inv_ky = S::cst(wheel.inv_ky);
    // A power of zero (no contact) is taken of a tiny positive number.
    let tiny = S::cst(1e-300);
    let mut out = SoilForces {
        vertical: zero,
        drawbar: zero,
        torque: zero,
        lateral: zero,
    };
    let mut bulldozing = zero;
    // The front piece [θm, θ1] (θ* = θ) and the rear one [θ2, θm]. Each
    // piece's nodes are squeezed quadratically towards the end where the
    // normal stress vanishes like a power (θ1 in front, θ2 behind):
    // θ = θ1 − L·(1 − u)² and θ = θ2 + L·u², u in (0, 1), turn an edge
    // (θ1 − θ)ⁿ into (1 − u)^(2n+1), which Gauss–Legendre integrates to
    // 1e-4 with 4 points a piece (to 1e-9 with 16). The rule is symmetric
    // (nodes ±x, equal weights), so the front piece is taken at the
    // mirrored nodes, θ = θ1 − L_f·u², weight L_f·w·u: the rear piece's
    // θ* at a node, θ1 − (θ − θ2)/L_r·(θ1 − θm) = θ1 − L_f·u², is then the
    // front piece's θ at the same node, and the normal stress there is
    // evaluated once for both.
    let front_len = theta1 - theta_m;
    let rear_len = theta_m - theta2;
    for (x, w) in rule.nodes.iter().zip(&rule.weights) {
        let u = 0.5 * (x + 1.0);
        let (squeeze, weight) = (S::cst(u * u), S::cst(w * u));
        let front = theta1 - front_len * squeeze;
        let rear = theta2 + rear_len * squeeze;
        let (sin_front, cos_front) = (front.sin(), front.cos());
        // σ at θ* = `front` (cos θ* − cos θ1 ≥ 0): Bekker's law, or over
        // compacted soil the elastic line up to the knee z_e and Bekker's
        // law from z_u on beyond it, written as one sum that is each of
        // them on its side ([`Compaction`]).
        let base = (cos_front - cos1).max(tiny);
        let sigma = match reload {
            None => k * base.powf(soil.n),
            Some(rl) => {
                let knee = S::cst(rl.knee);
                let beyond = S::cst(rl.offset) + (base - knee).max(zero);
                S::cst(rl.elastic) * base.min(knee) + k * beyond.powf(soil.n)
                    - S::cst(rl.yield_stress)
            }
        };
        let strength = cohesion + sigma * tan_phi;
        for (theta, sin, cos, wq) in [
            (front, sin_front, cos_front, front_len * weight),
            (rear, rear.sin(), rear.cos(), rear_len * weight),
        ] {
            let j = r * (rim * (theta1 - theta) - travel * (sin1 - sin));
            let tau = (strength * (one - (-(j.abs() * inv_k)).exp())).copysign(j);
            let jy = r * travel * (theta1 - theta) * tan_beta;
            let tau_y = (strength * (one - (-(jy.abs() * inv_ky)).exp())).copysign(jy);
            out.vertical += wq * (sigma * cos + tau * sin);
            out.drawbar += wq * (tau * cos - sigma * sin);
            out.torque += wq * tau;
            out.lateral += wq * tau_y;
            if let Some((d1, d2_gamma)) = wheel.bulldozing {
                // The side face's depth below the surface at θ, and the
                // soil it pushes: R_b = D1·(c·h + D2·γ·h²/2) per unit of
                // the face, at the lever r − h·cos θ.
                let h = (r * (cos - cos1)).max(zero);
                let resistance = S::cst(d1) * (cohesion * h + S::cst(d2_gamma) * h * h);
                bulldozing += wq * resistance * (r - h * cos);
            }
        }
    }
    let rb = r * S::cst(wheel.width);
    out.vertical *= rb;
    out.drawbar *= rb;
    out.torque *= rb * r;
    out.lateral *= rb;
    // Against the side slip, its sign made continuous over 1e-3 of tan β.
    out.lateral += bulldozing * tan_beta / tan_beta.hypot(S::cst(1e-3));
    out
}

/// A load that the soil cannot carry under the wheel: even sunk to its
/// axle (θ1 = π/2, sinkage = r), the soil's vertical force is smaller.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SinksPastAxle {
    /// The load asked for \[N\].
    pub load: f64,
    /// The most the soil carries under this wheel at this slip \[N\].
    pub most: f64,
}

impl core::fmt::Display for SinksPastAxle {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "the soil carries at most {:.4} N under this wheel (sunk to its axle), less than the load {} N: give a smaller load, or a wider or larger wheel",
            self.most, self.load
        )
    }
}

impl core::error::Error for SinksPastAxle {}

/// The steady state of `wheel` carrying `load` at `slip` and
/// `slip_angle` (a single-wheel testbed's run): the entry angle at which
/// the soil's vertical force equals the load, and the forces there.
pub fn steady_state<const Q: usize>(
    wheel: &SoilWheel,
    load: f64,
    slip: f64,
    slip_angle: f64,
    rule: &GaussLegendre<Q>,
) -> Result<(f64, SoilForces), SinksPastAxle> {
    steady_state_on(wheel, Compaction::default(), load, slip, slip_angle, rule)
}

/// [`steady_state`] over soil an earlier pass compacted ([`Compaction`]):
/// the entry angle is measured from the rut's floor.
pub fn steady_state_on<const Q: usize>(
    wheel: &SoilWheel,
    compaction: Compaction,
    load: f64,
    slip: f64,
    slip_angle: f64,
    rule: &GaussLegendre<Q>,
) -> Result<(f64, SoilForces), SinksPastAxle> {
    carrying(load, |entry_angle| {
        let contact = SoilContact {
            entry_angle,
            slip,
            slip_angle,
        };
        soil_forces_compacted(wheel, contact, compaction, rule)
    })
}

/// The state of `wheel` at rest carrying `load` (no travel, no spin: no
/// shear), as [`steady_state`] finds it: where a run on a soil starts.
pub fn rest_state<const Q: usize>(
    wheel: &SoilWheel,
    load: f64,
    rule: &GaussLegendre<Q>,
) -> Result<(f64, SoilForces), SinksPastAxle> {
    let still = Shear {
        rim: 0.0,
        travel: 0.0,
    };
    carrying(load, |entry_angle| {
        let contact = SoilContact {
            entry_angle,
            slip: 0.0,
            slip_angle: 0.0,
        };
        soil_forces_sheared(wheel, contact, still, rule)
    })
}

/// The entry angle in [0, π/2] at which `forces`' vertical force equals
/// `load` (bisection to rounding: the vertical force grows with the entry
/// angle), and the forces there.
fn carrying(
    load: f64,
    forces: impl Fn(f64) -> SoilForces,
) -> Result<(f64, SoilForces), SinksPastAxle> {
    let (mut lo, mut hi) = (0.0, core::f64::consts::FRAC_PI_2);
    let most = forces(hi).vertical;
    // NaN (a soil or wheel outside physics) is refused too.
    if most.partial_cmp(&load).is_none_or(|o| o.is_lt()) {
        return Err(SinksPastAxle { load, most });
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if forces(mid).vertical < load {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok((hi, forces(hi)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_to_its_degree() {
        let rule = GaussLegendre::<8>::new();
        assert!((rule.weights.iter().sum::<f64>() - 2.0).abs() < 1e-14);
        for p in 0..16 {
            let got: f64 = rule
                .nodes
                .iter()
                .zip(&rule.weights)
                .map(|(x, w)| w * libm::pow(*x, p as f64))
                .sum();
            let exact = if p % 2 == 1 {
                0.0
            } else {
                2.0 / (p as f64 + 1.0)
            };
            assert!((got - exact).abs() < 1e-14, "x^{p}: {got} vs {exact}");
        }
        assert!(rule.nodes.windows(2).all(|w| w[0] < w[1]));
    }

    /// LETE sand (Wong, Theory of Ground Vehicles, 4th ed., 2008), K = 1 cm.
    fn lete() -> Soil {
        Soil {
            n: 0.79,
            k_c: 102e3,
            k_phi: 5301e3,
            cohesion: 1.3e3,
            friction_angle: 31.1f64.to_radians(),
            shear_modulus: 0.01,
            lateral_shear_modulus: 0.01,
            a0: 0.4,
            a1: 0.15,
            rear_ratio: 0.0,
            unit_weight: 0.0,
            reload_k0: 0.0,
            reload_au: 5.03e8,
        }
    }

    /// ∫_lo^hi cos(pθ + q) dθ and ∫ sin(pθ + q) dθ.
    fn int_cos(p: f64, q: f64, lo: f64, hi: f64) -> f64 {
        if p == 0.0 {
            q.cos() * (hi - lo)
        } else {
            ((p * hi + q).sin() - (p * lo + q).sin()) / p
        }
    }
    fn int_sin(p: f64, q: f64, lo: f64, hi: f64) -> f64 {
        if p == 0.0 {
            q.sin() * (hi - lo)
        } else {
            -((p * hi + q).cos() - (p * lo + q).cos()) / p
        }
    }

    /// With n = 1 the normal stress on a piece is k·(cos(pθ + q) − cos θ1),
    /// and with c = 0 and K → 0 the shear is σ·tan φ: W, DP and T are sums
    /// of integrals of cosines and sines. (W, DP, T) / (r·b·k) on [lo, hi].
    fn closed_piece(p: f64, q: f64, c1: f64, t: f64, lo: f64, hi: f64) -> [f64; 3] {
        // ∫σ/k·cos θ, ∫σ/k·sin θ, ∫σ/k, by product-to-sum.
        let s_cos = 0.5 * (int_cos(p - 1.0, q, lo, hi) + int_cos(p + 1.0, q, lo, hi))
            - c1 * int_cos(1.0, 0.0, lo, hi);
        let s_sin = 0.5 * (int_sin(p + 1.0, q, lo, hi) - int_sin(p - 1.0, q, lo, hi))
            - c1 * int_sin(1.0, 0.0, lo, hi);
        let s_one = int_cos(p, q, lo, hi) - c1 * (hi - lo);
        [s_cos + t * s_sin, t * s_cos - s_sin, t * s_one]
    }

    #[test]
    fn with_n_1_and_no_cohesion_the_forces_are_the_closed_forms() {
        let soil = Soil {
            n: 1.0,
            cohesion: 0.0,
            shear_modulus: 1e-12,
            rear_ratio: 0.3,
            unit_weight: 0.0,
            reload_k0: 0.0,
            reload_au: 5.03e8,
            ..lete()
        };
        let (r, b) = (0.25, 0.16);
        let rule = GaussLegendre::<24>::new();
        for (theta1, slip) in [(0.3, 0.2), (0.5, 0.6), (0.15, 0.05)] {
            let got = soil_forces(
                &SoilWheel::new(&soil, r, b),
                SoilContact {
                    entry_angle: theta1,
                    slip,
                    slip_angle: 0.0,
                },
                &rule,
            );
            let k = (soil.k_c / b + soil.k_phi) * r;
            let t = soil.friction_angle.tan();
            let theta2 = -soil.rear_ratio * theta1;
            let theta_m = (soil.a0 + soil.a1 * slip) * theta1;
            let c1 = theta1.cos();
            // Front: θ* = θ; rear: θ* = θ1 − α(θ − θ2).
            let alpha = (theta1 - theta_m) / (theta_m - theta2);
            let front = closed_piece(1.0, 0.0, c1, t, theta_m, theta1);
            let rear = closed_piece(-alpha, theta1 + alpha * theta2, c1, t, theta2, theta_m);
            let scale = [r * b * k, r * b * k, r * r * b * k];
            let want: [f64; 3] = core::array::from_fn(|i| scale[i] * (front[i] + rear[i]));
            let got = [got.vertical, got.drawbar, got.torque];
            for i in 0..3 {
                assert!(
                    (got[i] - want[i]).abs() < 1e-6 * want[0].abs(),
                    "θ1 {theta1}, s {slip}: {i}: {} vs {}",
                    got[i],
                    want[i]
                );
            }
        }
    }

    #[test]
    fn the_drawbar_pull_rises_with_slip_and_the_sinkage_with_load() {
        let (soil, r, b) = (lete(), 0.25, 0.16);
        let rule = GaussLegendre::<32>::new();
        let mut last = f64::NEG_INFINITY;
        for k in 0..=18 {
            let slip = -0.45 + 0.075 * k as f64;
            let (_, f) =
                steady_state(&SoilWheel::new(&soil, r, b), 150.0, slip, 0.0, &rule).unwrap();
            assert!((f.vertical - 150.0).abs() < 1e-9);
            assert!(
                f.drawbar > last,
                "slip {slip}: DP {} after {last}",
                f.drawbar
            );
            last = f.drawbar;
        }
        let mut last = 0.0;
        for load in [20.0, 50.0, 100.0, 200.0, 400.0] {
            let (theta1, _) =
                steady_state(&SoilWheel::new(&soil, r, b), load, 0.2, 0.0, &rule).unwrap();
            let sinkage = r * (1.0 - theta1.cos());
            assert!(sinkage > last, "{load} N: sinkage {sinkage} after {last}");
            last = sinkage;
        }
    }

    #[test]
    fn a_wheel_at_rest_sinks_as_bekkers_formula_says() {
        // Bekker's rigid wheel: the pressure k·zⁿ under each point, projected
        // vertically, no shear (φ → 0, c = 0), the stress peaking at the
        // exit (θm = θ2 = 0). For a shallow sinkage z0 the rim is a parabola
        // and W = b·k·√(2r)·z0^(n+½)·G(n), G(n) = √π·Γ(n + 1)/(2·Γ(n + 3/2));
        // Bekker's closed form takes G ≈ (3 − n)/3, exact at n = 1 (and 2.9 %
        // off in z at n = 0.79). The rim's departure from the parabola is
        // of order z/r.
        let (r, b) = (0.25, 0.16);
        let rule = GaussLegendre::<64>::new();
        for n in [0.79, 1.0, 1.1] {
            let soil = Soil {
                n,
                cohesion: 0.0,
                friction_angle: 1e-9,
                a0: 0.0,
                a1: 0.0,
                ..lete()
            };
            let k = soil.k_c / b + soil.k_phi;
            let g = libm::sqrt(core::f64::consts::PI) * libm::tgamma(n + 1.0)
                / (2.0 * libm::tgamma(n + 1.5));
            for load in [2.0, 20.0, 80.0] {
                let (theta1, _) =
                    steady_state(&SoilWheel::new(&soil, r, b), load, 0.0, 0.0, &rule).unwrap();
                let z = r * (1.0 - theta1.cos());
                let shallow = libm::pow(load / (b * k * libm::sqrt(2.0 * r) * g), 1.0 / (n + 0.5));
                let rel = (z - shallow).abs() / shallow;
                assert!(
                    rel < z / r + 1e-4,
                    "n {n}, {load} N: {z} m, shallow {shallow} m"
                );
                if n == 1.0 {
                    let bekker = libm::pow(
                        3.0 * load / ((3.0 - n) * k * b * libm::sqrt(2.0 * r)),
                        2.0 / (2.0 * n + 1.0),
                    );
                    assert!((bekker - shallow).abs() < 1e-12 * shallow);
                }
            }
        }
    }

    #[test]
    fn a_load_past_the_axle_is_refused_with_what_the_soil_carries() {
        let rule = GaussLegendre::<16>::new();
        let e =
            steady_state(&SoilWheel::new(&lete(), 0.1, 0.05), 1e6, 0.2, 0.0, &rule).unwrap_err();
        assert!(e.most > 0.0 && e.most < 1e6 && e.load == 1e6, "{e:?}");
    }

    #[test]
    fn a_slip_angle_pushes_the_wheel_sideways_by_the_lateral_shear() {
        let rule = GaussLegendre::<16>::new();
        let force = |beta: f64| {
            steady_state(
                &SoilWheel::new(&lete(), 0.25, 0.16),
                150.0,
                0.2,
                beta,
                &rule,
            )
            .unwrap()
            .1
            .lateral
        };
        assert_eq!(force(0.0), 0.0);
        let (a, b) = (force(5f64.to_radians()), force(15f64.to_radians()));
        assert!(a > 0.0 && b > a, "{a} {b}");
        assert_eq!(force(-5f64.to_radians()), -a);
    }

    #[test]
    fn dual_numbers_give_the_forces_exact_derivatives() {
        use crate::dual::Dual;
        let (soil, r, b) = (lete(), 0.25, 0.16);
        let rule = GaussLegendre::<16>::new();
        let at = |theta1: f64, slip: f64| {
            let c = SoilContact {
                entry_angle: theta1,
                slip,
                slip_angle: 0.1,
            };
            soil_forces(&SoilWheel::new(&soil, r, b), c, &rule)
        };
        for (theta1, slip) in [(0.3, 0.25), (0.2, -0.3)] {
            let d_theta = soil_forces(
                &SoilWheel::new(&soil, r, b),
                SoilContact {
                    entry_angle: Dual::var(theta1),
                    slip: Dual::lift(slip),
                    slip_angle: Dual::lift(0.1),
                },
                &rule,
            );
            let d_slip = soil_forces(
                &SoilWheel::new(&soil, r, b),
                SoilContact {
                    entry_angle: Dual::lift(theta1),
                    slip: Dual::var(slip),
                    slip_angle: Dual::lift(0.1),
                },
                &rule,
            );
            let h = 1e-6;
            let fd = |f: fn(&SoilForces) -> f64, dt: f64, ds: f64| {
                (f(&at(theta1 + dt, slip + ds)) - f(&at(theta1 - dt, slip - ds))) / (2.0 * h)
            };
            type Part = (fn(&SoilForces) -> f64, Dual<f64>, Dual<f64>);
            let parts: [Part; 4] = [
                (|f| f.vertical, d_theta.vertical, d_slip.vertical),
                (|f| f.drawbar, d_theta.drawbar, d_slip.drawbar),
                (|f| f.torque, d_theta.torque, d_slip.torque),
                (|f| f.lateral, d_theta.lateral, d_slip.lateral),
            ];
            for (k, (f, dt, ds)) in parts.into_iter().enumerate() {
                let (a, b) = (fd(f, h, 0.0), fd(f, 0.0, h));
                assert!(
                    (dt.eps - a).abs() < 1e-5 * (1.0 + a.abs()),
                    "{k}: ∂θ1 {} vs {a}",
                    dt.eps
                );
                assert!(
                    (ds.eps - b).abs() < 1e-5 * (1.0 + b.abs()),
                    "{k}: ∂s {} vs {b}",
                    ds.eps
                );
            }
        }
    }

    #[test]
    fn four_points_a_piece_hold_the_forces_to_a_ten_thousandth() {
        // Fractional and whole exponents, a rebounding rear, driving and
        // braking, shallow and deep: against 512 points a piece.
        let soils = [
            lete(),
            Soil { n: 1.1, ..lete() },
            Soil {
                n: 0.5,
                rear_ratio: 0.5,
                unit_weight: 0.0,
                reload_k0: 0.0,
                reload_au: 5.03e8,
                ..lete()
            },
        ];
        for soil in soils {
            for (entry_angle, slip) in [(0.35, 0.3), (0.1, 0.6), (0.25, -0.4), (0.6, 0.05)] {
                let c = SoilContact {
                    entry_angle,
                    slip,
                    slip_angle: 0.05,
                };
                let fine = soil_forces(
                    &SoilWheel::new(&soil, 0.25, 0.16),
                    c,
                    &GaussLegendre::<512>::new(),
                );
                let four = soil_forces(
                    &SoilWheel::new(&soil, 0.25, 0.16),
                    c,
                    &GaussLegendre::<4>::new(),
                );
                for (a, b) in [
                    (four.vertical, fine.vertical),
                    (four.drawbar, fine.drawbar),
                    (four.torque / 0.25, fine.torque / 0.25),
                    (four.lateral, fine.lateral),
                ] {
                    assert!(
                        (a - b).abs() < 1e-4 * fine.vertical,
                        "n {}, θ1 {entry_angle}, s {slip}: {a} vs {b}",
                        soil.n
                    );
                }
            }
        }
    }

    /// Over compacted soil the law is Bekker's own where nothing was
    /// compacted (the same bits), and continuous in the past sinkage:
    /// a rut pressed 1 nm changes the forces by far less than a newton.
    #[test]
    fn fresh_soil_is_bekkers_law_and_compaction_enters_continuously() {
        let wheel = SoilWheel::new(&lete(), 0.2, 0.15);
        let rule = GaussLegendre::<4>::new();
        let contact = SoilContact {
            entry_angle: 0.3,
            slip: 0.2,
            slip_angle: 0.05,
        };
        let fresh = soil_forces(&wheel, contact, &rule);
        let none = soil_forces_compacted(&wheel, contact, Compaction::default(), &rule);
        assert_eq!(fresh, none);
        let barely = Compaction { past_sinkage: 1e-9 };
        let f = soil_forces_compacted(&wheel, contact, barely, &rule);
        assert!(
            (f.vertical - fresh.vertical).abs() < 1e-3 * fresh.vertical,
            "{f:?} {fresh:?}"
        );
        // Without memory (k_0 = A_u = 0) the rut's floor is fresh soil.
        let forgetful = SoilWheel::new(
            &Soil {
                reload_au: 0.0,
                ..lete()
            },
            0.2,
            0.15,
        );
        let deep = Compaction { past_sinkage: 0.02 };
        assert_eq!(forgetful.reload(deep), None);
        assert_eq!(forgetful.rut_depth(0.02), 0.02);
    }

    /// The reloading stress is the elastic line up to the knee and
    /// Bekker's curve from z_u beyond it: a wheel whose arc stays above
    /// the knee carries exactly the integral of k_u·z, and the forces over
    /// compacted soil converge with the quadrature as fresh soil's do
    /// (4 points a piece within 2 % of 512 across the kink, 16 within
    /// 0.2 %).
    #[test]
    fn compacted_soil_answers_elastically_up_to_its_past_pressure() {
        let (r, b) = (0.2, 0.15);
        let soil = Soil {
            a0: 0.0,
            a1: 0.0,
            ..lete()
        };
        let wheel = SoilWheel::new(&soil, r, b);
        let past = Compaction { past_sinkage: 0.03 };
        let reload = wheel.reload(past).unwrap();
        let k_u = soil.reload_au * 0.03;
        let z_e = reload.elastic_sinkage(r);
        assert!((reload.yield_stress() - k_u * z_e).abs() < 1e-9 * reload.yield_stress());
        assert!((wheel.rut_depth(0.03) - (0.03 - z_e)).abs() < 1e-15);
        // θm = 0 (a0 = a1 = 0): the whole arc is the front piece, σ = k_u·z
        // with z = r·(cos θ − cos θ1) below the knee; at zero slip and
        // standstill no shear: W = r·b·∫σ·cos θ dθ in closed form.
        let fine = GaussLegendre::<64>::new();
        let theta1 = libm::acos(1.0 - 0.5 * z_e / r);
        let still = Shear {
            rim: 0.0,
            travel: 0.0,
        };
        let entry = EntryAngle {
            angle: theta1,
            sin: theta1.sin(),
            cos: theta1.cos(),
        };
        let f = forces_on_arc(&wheel, entry, 0.0, 0.0, still, Some(&reload), &fine);
        let (s1, c1) = (theta1.sin(), theta1.cos());
        // ∫₀^θ1 (cos θ − cos θ1)·cos θ dθ = θ1/2 + sin 2θ1/4 − cos θ1·sin θ1.
        let integral = theta1 / 2.0 + (2.0 * theta1).sin() / 4.0 - c1 * s1;
        let want = r * b * k_u * r * integral;
        assert!(
            (f.vertical - want).abs() < 1e-9 * want,
            "{} vs {want}",
            f.vertical
        );
        // Across the knee, the quadrature converges.
        let deep = 3.0 * z_e;
        let theta1 = libm::acos(1.0 - deep / r);
        let contact = SoilContact {
            entry_angle: theta1,
            slip: 0.3,
            slip_angle: 0.0,
        };
        let at = |q: &dyn Fn() -> SoilForces| q();
        let exact =
            at(&|| soil_forces_compacted(&wheel, contact, past, &GaussLegendre::<512>::new()));
        for (got, tol) in [
            (
                soil_forces_compacted(&wheel, contact, past, &GaussLegendre::<4>::new()),
                2e-2,
            ),
            (
                soil_forces_compacted(&wheel, contact, past, &GaussLegendre::<16>::new()),
                2e-3,
            ),
        ] {
            for (g, e) in [
                (got.vertical, exact.vertical),
                (got.torque / r, exact.torque / r),
            ] {
                assert!((g - e).abs() < tol * exact.vertical, "{g} vs {e}");
            }
        }
    }

    /// The multipass effect: a wheel driven at the same load and slip
    /// over the rut it left sinks less below the rut's floor and needs
    /// less torque; the soil is pressed back to about where the first
    /// pass left it, and a third pass, which compacts nothing more, is
    /// the second one again. (Its pull at that slip is smaller too: the
    /// shorter arc mobilizes less shear, docs/SOIL.md.)
    #[test]
    fn a_wheel_over_its_own_rut_sinks_less_and_needs_less_torque() {
        let (r, b, load, slip) = (0.13, 0.16, 150.0, 0.2);
        let rule = GaussLegendre::<16>::new();
        // LLL dry sand (Wong 2008) and Bekker's lunar soil; LETE sand under
        // this load sinks a few millimetres and springs back fully (the
        // test below).
        let dry = Soil {
            n: 1.1,
            k_c: 990.0,
            k_phi: 1.528e6,
            ..lete()
        };
        let lunar = Soil {
            n: 1.0,
            k_c: 1400.0,
            k_phi: 820e3,
            cohesion: 170.0,
            friction_angle: 35f64.to_radians(),
            ..lete()
        };
        for soil in [dry, lunar] {
            let wheel = SoilWheel::new(&soil, r, b);
            let sink = |theta1: f64| r * (1.0 - theta1.cos());
            let (t1, first) = steady_state(&wheel, load, slip, 0.0, &rule).unwrap();
            let z1 = sink(t1);
            let pressed = Compaction { past_sinkage: z1 };
            let (t2, second) = steady_state_on(&wheel, pressed, load, slip, 0.0, &rule).unwrap();
            let z2 = sink(t2);
            let rut = wheel.rut_depth(z1);
            assert!(rut > 0.5 * z1 && rut < z1, "rut {rut} of {z1}");
            assert!(
                z2 < 0.5 * z1,
                "second pass sinks {z2} below the floor, first {z1}"
            );
            assert!(
                second.torque < 0.8 * first.torque,
                "{second:?} vs {first:?}"
            );
            // Back to within a fifth of the first pass's depth.
            assert!(((rut + z2) - z1).abs() < 0.2 * z1, "{rut} + {z2} vs {z1}");
            let deeper = Compaction {
                past_sinkage: z1.max(rut + z2),
            };
            let (t3, _) = steady_state_on(&wheel, deeper, load, slip, 0.0, &rule).unwrap();
            assert!(sink(t3) <= z2 * 1.0001, "{} vs {z2}", sink(t3));
        }
    }

    /// A firm soil pressed a few millimetres springs back fully: Wong's
    /// linear k_u would be softer than the soil's secant there, and the
    /// floor on it leaves no rut, the reloading line through the press.
    #[test]
    fn a_firm_soil_pressed_lightly_springs_back_fully() {
        let wheel = SoilWheel::new(&lete(), 0.13, 0.16);
        let z = 0.0024;
        let reload = wheel.reload(Compaction { past_sinkage: z }).unwrap();
        assert!(lete().reload_au * z < wheel.pressure_at(z) / z);
        assert_eq!(wheel.rut_depth(z), 0.0);
        assert!((reload.elastic_sinkage(0.13) - z).abs() < 1e-15);
        assert!((reload.yield_stress() - wheel.pressure_at(z)).abs() < 1e-9);
    }

    /// The side's bulldozing resistance (a soil with a unit weight) adds
    /// to the lateral force its integral, `∫ D1·(c·h + D2·γ·h²/2)·(r −
    /// h·cos θ) dθ` over the arc (here by a fine midpoint sum), with the
    /// slip angle's sign (continuous over 1e-3 of tan β), and nothing at
    /// zero slip angle.
    #[test]
    fn the_side_bulldozing_is_its_integral_against_the_side_slip() {
        let (r, b, theta1) = (0.2, 0.15, 0.45);
        let plain = Soil {
            rear_ratio: 0.4,
            ..lete()
        };
        let heavy = Soil {
            unit_weight: 16_000.0,
            ..plain
        };
        let rule = GaussLegendre::<16>::new();
        let lateral = |soil: &Soil, beta: f64| {
            let contact = SoilContact {
                entry_angle: theta1,
                slip: 0.2,
                slip_angle: beta,
            };
            soil_forces(&SoilWheel::new(soil, r, b), contact, &rule).lateral
        };
        let phi = heavy.friction_angle;
        let x_c = core::f64::consts::FRAC_PI_4 - phi / 2.0;
        let cot = |a: f64| 1.0 / libm::tan(a);
        let d1 = cot(x_c) + libm::tan(x_c + phi);
        let d2 = cot(x_c) + cot(x_c) * cot(x_c) / cot(phi);
        let theta2 = -heavy.rear_ratio * theta1;
        let steps = 200_000;
        let dtheta = (theta1 - theta2) / steps as f64;
        let expected: f64 = (0..steps)
            .map(|i| {
                let theta = theta2 + (i as f64 + 0.5) * dtheta;
                let h = r * (libm::cos(theta) - libm::cos(theta1));
                let rb = d1 * (heavy.cohesion * h + d2 * heavy.unit_weight * h * h / 2.0);
                rb * (r - h * libm::cos(theta)) * dtheta
            })
            .sum();
        assert!(expected > 1.0, "{expected}");
        for beta in [0.1, -0.3] {
            let added = lateral(&heavy, beta) - lateral(&plain, beta);
            // The sign of tan β, made continuous over 1e-3.
            let tan = libm::tan(beta);
            let want = expected * tan / tan.hypot(1e-3);
            assert!(
                (added - want).abs() < 1e-6 * expected,
                "β = {beta}: {added} N against {want} N"
            );
        }
        assert_eq!(lateral(&heavy, 0.0), 0.0);
    }
}
