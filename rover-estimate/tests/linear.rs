//! The filter on a linear process model against the textbook Kalman
//! filter written out here (dense matrices, an explicit inverse, the
//! Joseph-form batch update): equal means and covariances to 1e-12. And
//! the error state's attitude: a correction injected and read back.

use rover_estimate::sensors::{EncoderConfig, ImuConfig, PositionFixConfig};
use rover_estimate::{
    EstimateError, Estimator, FilterConfig, InitialSigma, ProcessModel, SensorConfig,
};

/// A linear rover-shaped model, N = 6 and one wheel: `ẏ = J·y + b·u`,
/// the positions' rates the velocities, springs, dampers and couplings
/// among the positions, the velocities and the angular velocities, a
/// force `u` (the wheel's torque) on vx. The attitude's angles neither
/// move nor act (its rows and columns of J are 0): their error
/// coordinates stay the Euler increments (T = I at zero angles), so the
/// error-state filter is exactly the linear one.
#[derive(Clone, Debug)]
struct Linear {
    jac: Vec<f64>,
    input: f64,
    radius: f64,
}

const DIM: usize = 12;

impl Linear {
    fn new() -> Self {
        let mut jac = vec![0.0; DIM * DIM];
        let mut set = |i: usize, j: usize, v: f64| jac[i * DIM + j] = v;
        for i in 0..3 {
            set(i, 6 + i, 1.0); // Ẋ = v
            set(6 + i, i, -(4.0 + i as f64)); // springs
            set(6 + i, 6 + i, -(0.5 + 0.2 * i as f64)); // dampers
            set(9 + i, 9 + i, -(1.5 + 0.3 * i as f64)); // rotational dampers
        }
        set(6, 11, 0.4); // v̇x from Ωz
        set(11, 6, -0.7); // Ω̇z from vx
        set(7, 10, 0.25);
        set(10, 1, 0.6);
        set(8, 0, -0.3);
        Self {
            jac,
            input: 0.0,
            radius: 0.2,
        }
    }
}

impl ProcessModel for Linear {
    type Error = &'static str;
    fn dof(&self) -> usize {
        6
    }
    fn dim(&self) -> usize {
        DIM
    }
    fn wheel_count(&self) -> usize {
        1
    }
    fn spin_range(&self) -> std::ops::Range<usize> {
        DIM..DIM
    }
    fn gravity(&self) -> f64 {
        0.0
    }
    fn set_inputs(&mut self, torques: &[f64], _steering: &[f64]) -> Result<(), &'static str> {
        self.input = torques[0];
        Ok(())
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), &'static str> {
        for i in 0..DIM {
            dy[i] = (0..DIM).map(|j| self.jac[i * DIM + j] * y[j]).sum();
        }
        dy[6] += self.input;
        Ok(())
    }
    fn rhs_and_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), &'static str> {
        jac.copy_from_slice(&self.jac);
        self.rhs(t, y, dy)
    }
    fn wheel_rates(
        &mut self,
        _t: f64,
        y: &[f64],
        rates: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), &'static str> {
        rates[0] = y[6] / self.radius;
        gradient.iter_mut().for_each(|g| *g = 0.0);
        gradient[6] = 1.0 / self.radius;
        Ok(())
    }
    fn wheel_outputs(&self, normal: &mut [f64], slip: &mut [f64]) {
        normal.fill(0.0);
        slip.fill(0.0);
    }
}

/// A dense square matrix, row-major.
#[derive(Clone, Debug)]
struct Mat {
    n: usize,
    a: Vec<f64>,
}

impl Mat {
    fn zeros(n: usize) -> Self {
        Self {
            n,
            a: vec![0.0; n * n],
        }
    }
    fn identity(n: usize) -> Self {
        let mut m = Self::zeros(n);
        (0..n).for_each(|i| m.a[i * n + i] = 1.0);
        m
    }
    fn at(&self, i: usize, j: usize) -> f64 {
        self.a[i * self.n + j]
    }
    fn mul(&self, b: &Mat) -> Mat {
        let n = self.n;
        let mut c = Mat::zeros(n);
        for i in 0..n {
            for j in 0..n {
                c.a[i * n + j] = (0..n).map(|k| self.at(i, k) * b.at(k, j)).sum();
            }
        }
        c
    }
    fn t(&self) -> Mat {
        let n = self.n;
        let mut c = Mat::zeros(n);
        for i in 0..n {
            for j in 0..n {
                c.a[j * n + i] = self.at(i, j);
            }
        }
        c
    }
    fn mul_vec(&self, x: &[f64]) -> Vec<f64> {
        (0..self.n)
            .map(|i| (0..self.n).map(|k| self.at(i, k) * x[k]).sum())
            .collect()
    }
    /// The inverse by Gauss–Jordan elimination with partial pivoting.
    fn inverse(&self) -> Mat {
        let n = self.n;
        let mut a = self.clone();
        let mut inv = Mat::identity(n);
        for k in 0..n {
            let p = (k..n)
                .max_by(|&i, &j| a.at(i, k).abs().total_cmp(&a.at(j, k).abs()))
                .unwrap();
            for j in 0..n {
                a.a.swap(k * n + j, p * n + j);
                inv.a.swap(k * n + j, p * n + j);
            }
            let d = a.at(k, k);
            for j in 0..n {
                a.a[k * n + j] /= d;
                inv.a[k * n + j] /= d;
            }
            for i in (0..n).filter(|&i| i != k) {
                let m = a.at(i, k);
                for j in 0..n {
                    a.a[i * n + j] -= m * a.a[k * n + j];
                    inv.a[i * n + j] -= m * inv.a[k * n + j];
                }
            }
        }
        inv
    }
}

/// The textbook Kalman filter on the model's discrete form.
struct Textbook {
    x: Vec<f64>,
    p: Mat,
}

impl Textbook {
    fn predict(&mut self, phi: &Mat, gamma: &[f64], q: &[f64]) {
        let mut x = phi.mul_vec(&self.x);
        x.iter_mut().zip(gamma).for_each(|(x, g)| *x += g);
        self.x = x;
        self.p = phi.mul(&self.p).mul(&phi.t());
        for (i, q) in q.iter().enumerate() {
            self.p.a[i * self.p.n + i] += q;
        }
    }

    /// The batch update of readings `z` with rows `h` (each `n` long) and
    /// variances `r` (uncorrelated), Joseph form.
    fn update(&mut self, h: &[Vec<f64>], z: &[f64], r: &[f64]) {
        let n = self.p.n;
        let m = h.len();
        let ph: Vec<Vec<f64>> = h.iter().map(|row| self.p.mul_vec(row)).collect();
        let mut s = Mat::zeros(m);
        for i in 0..m {
            for j in 0..m {
                s.a[i * m + j] = (0..n).map(|k| h[i][k] * ph[j][k]).sum::<f64>();
            }
            s.a[i * m + i] += r[i];
        }
        let s_inv = s.inverse();
        // K = P·Hᵀ·S⁻¹, n × m.
        let k: Vec<Vec<f64>> = (0..n)
            .map(|a| {
                (0..m)
                    .map(|j| (0..m).map(|i| ph[i][a] * s_inv.at(i, j)).sum())
                    .collect()
            })
            .collect();
        let innovation: Vec<f64> = (0..m)
            .map(|i| z[i] - (0..n).map(|a| h[i][a] * self.x[a]).sum::<f64>())
            .collect();
        for a in 0..n {
            self.x[a] += (0..m).map(|j| k[a][j] * innovation[j]).sum::<f64>();
        }
        let mut ikh = Mat::identity(n);
        for a in 0..n {
            for b in 0..n {
                ikh.a[a * n + b] -= (0..m).map(|j| k[a][j] * h[j][b]).sum::<f64>();
            }
        }
        let mut p = ikh.mul(&self.p).mul(&ikh.t());
        for a in 0..n {
            for b in 0..n {
                p.a[a * n + b] += (0..m).map(|j| k[a][j] * r[j] * k[b][j]).sum::<f64>();
            }
        }
        self.p = p;
    }
}

fn sensors() -> SensorConfig {
    SensorConfig {
        seed: 1,
        rate: 50.0,
        imu: Some(ImuConfig {
            gyro_noise_deg_per_sqrt_h: 0.3,
            gyro_bias_deg_per_h: 20.0,
            accel_noise_ug_per_sqrt_hz: 100.0,
            accel_bias_mg: 1.0,
            bias_time: 40.0,
            position: [0.1, 0.0, 0.05],
            orientation_deg: [10.0, -5.0, 30.0],
        }),
        wheel_encoders: Some(EncoderConfig { resolution: 0.01 }),
        suspension_encoders: None,
        position_fix: Some(PositionFixConfig {
            rate: 1.0,
            sigma: 0.05,
        }),
        heading_fix: None,
    }
}

fn assert_close(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len());
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0),
            "{what}[{i}]: filter {x}, textbook {y}"
        );
    }
}

/// The IMU's rotation from its axes to the body's (MODEL.md §1's order),
/// written out here: `C = R_imuᵀ`.
fn body_to_imu(deg: [f64; 3]) -> [[f64; 3]; 3] {
    let [f, t, p] = deg.map(f64::to_radians);
    let rz = [
        [p.cos(), -p.sin(), 0.0],
        [p.sin(), p.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, f.cos(), -f.sin()],
        [0.0, f.sin(), f.cos()],
    ];
    let ry = [
        [t.cos(), 0.0, t.sin()],
        [0.0, 1.0, 0.0],
        [-t.sin(), 0.0, t.cos()],
    ];
    let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    };
    let r = mul(mul(rz, rx), ry);
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = r[j][i];
        }
    }
    c
}

/// Over 60 steps of 20 ms with a varying force, gyro and encoder
/// readings every step and a position fix every 10th: the filter's
/// state and covariance equal the textbook filter's on the discrete
/// model `Φ = (I − hJ)⁻ᵐ` (m substeps), biases decaying by `e^(−dt/τ)`,
/// the torque's noise `dt²·(σ_τ² + (½·Δu)²)` on vx (the model's
/// response to the torque, `b = e_vx`, by the filter's differences).
#[test]
fn equals_the_textbook_kalman_filter_on_a_linear_model() {
    for substeps in [1, 2] {
        let config = FilterConfig {
            substeps,
            ..FilterConfig::default()
        };
        let sensors = sensors();
        let model = Linear::new();
        let mut y0 = vec![0.0; DIM];
        y0[0] = 0.1;
        y0[7] = -0.05;
        y0[11] = 0.02;
        let initial = InitialSigma::default();
        let mut filter =
            Estimator::new(model.clone(), &sensors, config.clone(), 0.0, &y0, &initial).unwrap();
        let imu = sensors.imu.clone().unwrap();
        let n = DIM + 6;
        let dt = 1.0 / sensors.rate;
        let h = dt / substeps as f64;

        // The discrete model.
        let mut a = Mat::identity(DIM);
        a.a.iter_mut()
            .zip(&model.jac)
            .for_each(|(a, j)| *a -= h * j);
        let a_inv = a.inverse();
        let mut phi_y = Mat::identity(DIM);
        for _ in 0..substeps {
            phi_y = a_inv.mul(&phi_y);
        }
        let decay = (-dt / imu.bias_time).exp();
        let mut phi = Mat::identity(n);
        for i in 0..n {
            for j in 0..n {
                phi.a[i * n + j] = if i < DIM && j < DIM {
                    phi_y.at(i, j)
                } else if i == j {
                    decay
                } else {
                    0.0
                };
            }
        }
        let groups = [
            config.position_noise,
            config.attitude_noise,
            config.velocity_noise,
            config.angular_velocity_noise,
        ];
        let mut q = vec![0.0; n];
        for i in 0..DIM {
            q[i] = groups[i / 3].powi(2) * dt;
        }
        for i in 0..3 {
            q[DIM + i] = imu.gyro_bias_sigma().powi(2) * (1.0 - decay * decay);
            q[DIM + 3 + i] = imu.accel_bias_sigma().powi(2) * (1.0 - decay * decay);
        }
        let mut sigma0 = vec![0.0; n];
        for i in 0..DIM {
            sigma0[i] = [
                initial.position,
                initial.attitude,
                initial.velocity,
                initial.angular_velocity,
            ][i / 3];
        }
        for i in 0..3 {
            sigma0[DIM + i] = imu.gyro_bias_sigma();
            sigma0[DIM + 3 + i] = imu.accel_bias_sigma();
        }
        let mut kf = Textbook {
            x: [y0.clone(), vec![0.0; 6]].concat(),
            p: Mat::zeros(n),
        };
        for i in 0..n {
            kf.p.a[i * n + i] = sigma0[i].powi(2);
        }
        let c = body_to_imu(imu.orientation_deg);
        let gyro_variance = imu.gyro_noise_density().powi(2) * sensors.rate;
        let res = sensors.wheel_encoders.as_ref().unwrap().resolution;
        let encoder_variance = res * res / (6.0 * dt * dt) + config.wheel_rate_sigma.powi(2);
        let fix_variance = 0.05f64.powi(2);

        let mut angle = 0.0;
        let mut last_u = None;
        filter.update_wheel_angles(&[angle]).unwrap();
        for step in 1..=60 {
            let u = (0.3 * step as f64).sin();
            let change = last_u.map_or(0.0, |l| u - l);
            last_u = Some(u);
            filter.predict(dt, &[u], &[0.0]).unwrap();
            // Γ·u: each substep adds h·A⁻¹·b·u after the previous ones.
            let mut b = vec![0.0; DIM];
            b[6] = u;
            let mut gamma = vec![0.0; DIM];
            for _ in 0..substeps {
                let mut next: Vec<f64> = gamma.iter().zip(&b).map(|(g, b)| g + h * b).collect();
                next = a_inv.mul_vec(&next);
                gamma = next;
            }
            gamma.extend([0.0; 6]);
            kf.predict(&phi, &gamma, &q);
            let moving = config.torque_change_scale * change;
            kf.p.a[6 * n + 6] += dt * dt * (config.torque_sigma.powi(2) + moving * moving);

            // Readings that differ from the estimate (a made-up truth).
            let s = step as f64;
            let gyro = [0.01 * s.cos(), -0.02, 0.03 * (0.5 * s).sin()];
            angle += 0.5 * dt * (1.0 + 0.1 * s.sin());
            let mut rows = Vec::new();
            let mut z = Vec::new();
            let mut r = Vec::new();
            for axis in 0..3 {
                let mut row = vec![0.0; n];
                row[9..12].copy_from_slice(&c[axis]);
                row[DIM + axis] = 1.0;
                rows.push(row);
                z.push(gyro[axis]);
                r.push(gyro_variance);
            }
            let mut row = vec![0.0; n];
            row[6] = 1.0 / model.radius;
            rows.push(row);
            z.push(0.5 * (1.0 + 0.1 * s.sin()));
            r.push(encoder_variance);
            filter.update_imu(Some(gyro), None).unwrap();
            filter.update_wheel_angles(&[angle]).unwrap();
            if step % 10 == 0 {
                let fix = [0.02 * s, -0.01, 0.005];
                for axis in 0..3 {
                    let mut row = vec![0.0; n];
                    row[axis] = 1.0;
                    rows.push(row);
                    z.push(fix[axis]);
                    r.push(fix_variance);
                }
                filter.update_position(fix).unwrap();
            }
            kf.update(&rows, &z, &r);

            let (bg, ba) = filter.biases().unwrap();
            let state = [filter.state(), &bg[..], &ba[..]].concat();
            assert_close("state", &state, &kf.x);
            assert_close("covariance", filter.covariance(), &kf.p.a);
        }
    }
}

/// A correction injected into an estimate with a large attitude, and
/// read back as the deviation of the corrected state from the old
/// estimate: the same correction (the attitude's turn δθ crosses ψ = π,
/// and ψ stays continuous).
#[test]
fn an_attitude_correction_reads_back_as_itself() {
    let mut y0 = vec![0.0; DIM];
    y0[3..6].copy_from_slice(&[0.3, -0.2, 3.1]);
    y0[6] = 0.4;
    let filter = Estimator::new(
        Linear::new(),
        &sensors(),
        FilterConfig::default(),
        0.0,
        &y0,
        &InitialSigma::default(),
    )
    .unwrap();
    let mut corrected = filter.clone();
    let mut delta = vec![0.0; DIM + 6];
    delta[0] = 0.01;
    delta[3..6].copy_from_slice(&[0.05, -0.02, 0.2]);
    delta[6] = -0.1;
    delta[DIM] = 1e-4;
    corrected.correct(&delta).unwrap();
    let y1 = corrected.state().to_vec();
    assert!(
        y1[5] > std::f64::consts::PI,
        "ψ continuous past π: {}",
        y1[5]
    );
    let mut back = vec![0.0; DIM];
    filter.deviation(&y1, &mut back).unwrap();
    assert_close("deviation", &back, &delta[..DIM]);
    assert_eq!(corrected.biases().unwrap().0[0], 1e-4);
}

/// Bad input is refused with a located error, and leaves the estimate as
/// it was.
#[test]
fn bad_input_is_refused_and_leaves_the_estimate() {
    let y0 = vec![0.0; DIM];
    let mut filter = Estimator::new(
        Linear::new(),
        &sensors(),
        FilterConfig::default(),
        0.0,
        &y0,
        &InitialSigma::default(),
    )
    .unwrap();
    filter.predict(0.02, &[1.0], &[0.0]).unwrap();
    filter.update_wheel_angles(&[0.0]).unwrap();
    let (state, p, t) = (
        filter.state().to_vec(),
        filter.covariance().to_vec(),
        filter.time(),
    );
    let unchanged = |f: &Estimator<Linear>| {
        assert_eq!(f.state(), &state[..]);
        assert_eq!(f.covariance(), &p[..]);
        assert_eq!(f.time(), t);
    };
    let e = filter.predict(f64::NAN, &[1.0], &[0.0]).unwrap_err();
    assert!(matches!(e, EstimateError::Step { .. }), "{e}");
    let e = filter.predict(0.02, &[f64::INFINITY], &[0.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "at t = 0.02 s: torques[0] is inf; readings, commands and states must be finite"
    );
    let e = filter.predict(0.02, &[1.0, 2.0], &[0.0]).unwrap_err();
    assert_eq!(e.to_string(), "torques: expected 1 values, got 2");
    let e = filter
        .update_imu(Some([0.0, f64::NAN, 0.0]), None)
        .unwrap_err();
    assert!(
        matches!(
            e,
            EstimateError::NotFinite {
                what: "gyro",
                index: 1,
                ..
            }
        ),
        "{e}"
    );
    // Readings at the same instant as the last: no rate.
    let e = filter.update_wheel_angles(&[0.1]).unwrap_err();
    assert!(matches!(e, EstimateError::EncoderInterval { .. }), "{e}");
    let e = filter.update_suspension(&[]).unwrap_err();
    assert!(
        matches!(
            e,
            EstimateError::NoSensor {
                sensor: "suspension_encoders",
                ..
            }
        ),
        "{e}"
    );
    unchanged(&filter);

    let mut bad = sensors();
    bad.imu.as_mut().unwrap().bias_time = -1.0;
    let e = Estimator::new(
        Linear::new(),
        &bad,
        FilterConfig::default(),
        0.0,
        &y0,
        &InitialSigma::default(),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "sensors.imu.bias_time must be positive and finite, got -1"
    );
    let e = Estimator::new(
        Linear::new(),
        &sensors(),
        FilterConfig::default(),
        0.0,
        &y0[..5],
        &InitialSigma::default(),
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "y0: expected 12 values, got 5");
}

/// A heading fix across ±π: the innovation is wrapped, so a reading of
/// −3.1 rad on an estimate of 3.1 rad turns the yaw on past π, by the
/// gain times 0.083 rad, not back by 6.2.
#[test]
fn a_heading_fix_across_pi_turns_the_short_way() {
    let mut sensors = sensors();
    sensors.heading_fix = Some(rover_estimate::sensors::HeadingFixConfig {
        rate: 1.0,
        sigma: 0.01,
    });
    let mut y0 = vec![0.0; DIM];
    y0[5] = 3.1;
    let mut filter = Estimator::new(
        Linear::new(),
        &sensors,
        FilterConfig::default(),
        0.0,
        &y0,
        &InitialSigma {
            attitude: 0.01,
            ..InitialSigma::default()
        },
    )
    .unwrap();
    filter.update_heading(-3.1).unwrap();
    let innovation = 2.0 * std::f64::consts::PI - 6.2;
    // At zero roll and pitch δθ_z = δψ: the scalar gain σ²/(σ² + r).
    let gain = 0.01f64.powi(2) / (0.01f64.powi(2) + 0.01f64.powi(2));
    let psi = filter.state()[5];
    assert!((psi - (3.1 + gain * innovation)).abs() < 1e-12, "{psi}");
}
