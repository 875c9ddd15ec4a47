//! Wheel–ground interaction (issue 4): static equilibrium on flat ground,
//! contact geometry over a bump, the two contact methods against each other.

use rover_dynamics::Model;
use rover_runtime::GenericPlant;
use rover_runtime::contact::RimSampling;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::{ContactMethod, Ground};
use rover_runtime::integrate::{BdfConfig, Integrator, IntegratorConfig, OdeSystem};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_runtime::wheel_law::WheelLawConfig;

use crate::support::hand_models::{exomars, swing4};

/// Drop `model` on flat ground at Z = 0 and let it settle for `seconds`.
fn settle(model: &Model, seconds: f64) -> (RoverSystem<GenericPlant, Terrain>, Vec<f64>) {
    let n = model.dof();
    let plant = GenericPlant::new(model.clone()).unwrap();
    let ground = Ground::new(
        Terrain::default(),
        model,
        ContactMethod::Meridional,
        RimSampling::default(),
        WheelLawConfig::default(),
    );
    let control = Controller::new(ControllerConfig::default(), model, 0.0).unwrap();
    let mut sys = RoverSystem::new(plant, Some(ground), control);
    let mut y = vec![0.0; 2 * n + 1];
    let rest = model.rest();
    y[6..n].copy_from_slice(&rest);
    // Lowest wheel just touching.
    let lowest = model
        .wheels
        .iter()
        .map(|w| model.bodies[w.body].position.value(&rest)[2] - w.radius)
        .fold(f64::INFINITY, f64::min);
    y[2] = -lowest;
    // Stiff: at standstill the regularized cornering law (v_ε = 1e-3 m/s) is
    // a lateral damper of C/v_ε = 5e4 N·s/m per wheel, so BDF, as the paper's ode15s.
    let mut integ = IntegratorConfig::Bdf(BdfConfig {
        rtol: 1e-6,
        atol: 1e-8,
        ..Default::default()
    })
    .build(2 * n + 1)
    .unwrap();
    let mut t = 0.0;
    integ.advance(&mut sys, &mut t, &mut y, seconds).unwrap();
    let mut dy = vec![0.0; 2 * n + 1];
    sys.rhs(t, &y, &mut dy).unwrap();
    let speed = y[n..2 * n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!(
        speed < 1e-6,
        "not settled after {seconds} s: max |w| = {speed:e}"
    );
    (sys, y)
}

#[test]
fn paper_rovers_settle_to_static_equilibrium_on_flat_ground() {
    for (name, model) in [("exomars", exomars()), ("swing4", swing4())] {
        let (sys, y) = settle(&model, 30.0);
        let weight = model.total_mass() * model.gravity;
        let reports = sys.reports();
        let states = sys.wheel_states();
        let total: f64 = reports.iter().map(|r| r.normal).sum();
        assert!(
            (total - weight).abs() < 1e-6 * weight,
            "{name}: ΣF_n = {total} N, weight {weight} N"
        );
        // Front/rear split from the moment balance about G's y axis: the
        // normal forces at H_j balance the wheels' weights at G_j (the
        // body's weight acts at G).
        let (xg, mg) = (y[0], model.bodies[0].mass * model.gravity);
        let front: Vec<usize> = (0..states.len())
            .filter(|&k| states[k].centre[0] > xg)
            .collect();
        let rear: Vec<usize> = (0..states.len())
            .filter(|&k| states[k].centre[0] <= xg)
            .collect();
        let mean_x = |ks: &[usize]| {
            let f: f64 = ks.iter().map(|&k| reports[k].normal).sum();
            (
                f,
                ks.iter()
                    .map(|&k| reports[k].normal * (reports[k].point[0] - xg))
                    .sum::<f64>()
                    / f,
            )
        };
        let (f_front, x_front) = mean_x(&front);
        let (_, x_rear) = mean_x(&rear);
        let wheel_moment: f64 = states.iter().map(|s| mg * (s.centre[0] - xg)).sum();
        let expected_front = (wheel_moment - weight * x_rear) / (x_front - x_rear);
        assert!(
            (f_front - expected_front).abs() < 1e-6 * weight,
            "{name}: front axle carries {f_front} N, the moment balance gives {expected_front} N"
        );
        if name == "exomars" {
            // Free rockers with equal arms (±45°): on each side the front and
            // middle wheels carry the same load, and by symmetry so do the two
            // rear wheels. Every wheel carries about (m_B/6 + m_w)·g; not
            // exactly, because the paper's rounded geometry puts the rear
            // wheel centres 0.1 mm below the others (0.267·cos 48.5° vs
            // 0.250·cos 45°), which pitches the body by 3e-4 rad.
            let f: Vec<f64> = reports.iter().map(|r| r.normal).collect();
            assert!(
                (f[0] - f[2]).abs() < 1e-8 * f[0] && (f[1] - f[3]).abs() < 1e-8 * f[1],
                "rocker loads {f:?}"
            );
            assert!((f[4] - f[5]).abs() < 1e-8 * f[4], "rear loads {f:?}");
            let each = (model.body.mass / 6.0 + model.bodies[0].mass) * model.gravity;
            for (k, v) in f.iter().enumerate() {
                assert!(
                    (v - each).abs() < 1e-3 * each,
                    "exomars wheel {}: F_n = {v} N, expected about {each} N",
                    k + 1
                );
            }
        }
        for (k, (r, s)) in reports.iter().zip(states).enumerate() {
            let w = &model.wheels[k];
            let deflection = w.radius - (s.centre[2] - r.point[2]);
            assert!(
                (deflection - r.normal / w.stiffness).abs() < 1e-9,
                "{name}: wheel {} deflection {deflection} m vs F_n/k_w = {} m",
                k + 1,
                r.normal / w.stiffness
            );
        }
    }
}
