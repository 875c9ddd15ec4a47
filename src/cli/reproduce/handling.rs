//! The uncoupled handling model of Fig. 5: the single-track (bicycle)
//! model in steady turning, one linear tyre per axle with the wheels'
//! cornering stiffness summed, flat ground, no suspension.

use rover_dynamics::model::Model;

/// One axle of the single-track model.
#[derive(Clone, Debug)]
pub struct Axle {
    /// Body x of the axle \[m\].
    pub x: f64,
    /// Its wheels (0-based).
    pub wheels: Vec<usize>,
    /// Summed cornering stiffness [N/rad].
    pub stiffness: f64,
}

/// The single-track model of a rover: its axles, its mass, the wheels'
/// rest positions and the Ackermann turn centre x_c (MODEL.md §8).
pub struct SingleTrack {
    pub axles: Vec<Axle>,
    pub mass: f64,
    rest_xy: Vec<(f64, f64)>,
    steerable: Vec<bool>,
    centre_x: f64,
}

impl SingleTrack {
    /// From a rover description: axles by rest x (within 1 cm), the turn
    /// centre on the mean x of the non-steerable wheels.
    pub fn new(model: &Model) -> Self {
        let rest_xy: Vec<(f64, f64)> = model
            .rest_wheel_centres()
            .iter()
            .map(|u| (u[0], u[1]))
            .collect();
        let xs: Vec<f64> = rest_xy.iter().map(|p| p.0).collect();
        let axles = rover_scenario::output::axles_by_rest_x(&xs)
            .into_iter()
            .map(|(wheels, x)| {
                let wheels: Vec<usize> = wheels.iter().map(|j| j - 1).collect();
                Axle {
                    x,
                    stiffness: wheels
                        .iter()
                        .map(|&j| model.wheels[j].cornering_stiffness)
                        .sum(),
                    wheels,
                }
            })
            .collect();
        let steerable: Vec<bool> = model.wheels.iter().map(|w| w.steerable).collect();
        let fixed: Vec<f64> = rest_xy
            .iter()
            .zip(&steerable)
            .filter(|(_, s)| !**s)
            .map(|(p, _)| p.0)
            .collect();
        let centre_x = fixed.iter().sum::<f64>() / fixed.len().max(1) as f64;
        Self {
            axles,
            mass: model.total_mass(),
            rest_xy,
            steerable,
            centre_x,
        }
    }

    /// The Ackermann curvature κ of a front-left angle δ₁ and the
    /// kinematic radius R_k = √(x_c² + R²) (MODEL.md §8).
    pub fn ackermann(&self, delta1: f64) -> (f64, f64) {
        let first = (0..self.steerable.len())
            .find(|&j| self.steerable[j])
            .unwrap_or(0);
        let (x1, y1) = self.rest_xy[first];
        let t = delta1.tan();
        let kappa = t / ((x1 - self.centre_x) + y1 * t);
        (kappa, self.centre_x.hypot(1.0 / kappa))
    }

    /// Steady turning at forward speed `v` with the Ackermann angles of δ₁:
    /// the radius of G's path \[m\]. Each axle that steers (any of its
    /// wheels steerable) is the single track's wheel at the axle's centre,
    /// steered by the Ackermann angle of that point,
    /// `δ_a = atan(κ·(x_a − x_c))`: the wheels of an Ackermann axle roll
    /// without slip on the kinematic turn, and so does this equivalent
    /// wheel (the mean of the left and right angles would not: it makes a
    /// slip of its own, 2.7 % of R_k at δ₁ = 20°). F_a = C_a·(δ_a −
    /// atan((v_y + r·x_a)/v)); ΣF_a = m·v·r and Σx_a·F_a = 0 are solved for
    /// (v_y, r) by Newton.
    pub fn radius(&self, delta1: f64, v: f64) -> Option<f64> {
        let (kappa, rk) = self.ackermann(delta1);
        let steer: Vec<f64> = self
            .axles
            .iter()
            .map(|a| {
                if a.wheels.iter().any(|&j| self.steerable[j]) {
                    (kappa * (a.x - self.centre_x)).atan()
                } else {
                    0.0
                }
            })
            .collect();
        let residual = |vy: f64, r: f64| {
            let mut f = [-self.mass * v * r, 0.0];
            for (a, d) in self.axles.iter().zip(&steer) {
                let force = a.stiffness * (d - ((vy + r * a.x) / v).atan());
                f[0] += force;
                f[1] += a.x * force;
            }
            f
        };
        // From the kinematic turn about x_c.
        let mut x = [
            -self.centre_x * v / rk.copysign(kappa),
            v / rk.copysign(kappa),
        ];
        for _ in 0..50 {
            let f = residual(x[0], x[1]);
            let h = 1e-9;
            let fa = residual(x[0] + h, x[1]);
            let fb = residual(x[0], x[1] + h);
            let j = [
                [(fa[0] - f[0]) / h, (fb[0] - f[0]) / h],
                [(fa[1] - f[1]) / h, (fb[1] - f[1]) / h],
            ];
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if det.abs() < 1e-300 {
                return None;
            }
            let dx = [
                (f[0] * j[1][1] - f[1] * j[0][1]) / det,
                (j[0][0] * f[1] - j[1][0] * f[0]) / det,
            ];
            x = [x[0] - dx[0], x[1] - dx[1]];
            if dx[0].abs() < 1e-15 && dx[1].abs() < 1e-15 {
                break;
            }
        }
        let speed = v.hypot(x[0]);
        (x[1] != 0.0 && speed.is_finite()).then(|| speed / x[1].abs())
    }
}
