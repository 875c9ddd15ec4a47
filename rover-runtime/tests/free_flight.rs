//! Conservation laws in free flight: with g = 0 and no springs,
//! dampers or contacts, T and the inertial linear and angular momenta are
//! conserved; with gravity and springs but no damping, T + U is.

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::model::Spring;
use rover_dynamics::plant::Plant;
use rover_integrate::{AdaptiveConfig, Integrator, IntegratorConfig};
use rover_runtime::GenericPlant;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_test_support::hand_models::{exomars, swing4, swing4_rich};

struct Invariants {
    energy: f64,
    momentum: [f64; 3],
    angular_momentum: [f64; 3],
}

fn invariants(model: &Model, plant: &mut GenericPlant, y: &[f64]) -> Invariants {
    let n = model.dof();
    let (x, w) = (&y[..n], &y[n..2 * n]);
    let mut mm = vec![0.0; n * n];
    plant.mass_matrix(x, &mut mm);
    let p: Vec<f64> = (0..n)
        .map(|a| (0..n).map(|b| mm[a * n + b] * w[b]).sum())
        .collect();
    let kinetic = 0.5 * (0..n).map(|a| w[a] * p[a]).sum::<f64>();
    let r = Attitude::new(x[3], x[4], x[5]).rotation();
    let rot = |v: [f64; 3]| [0, 1, 2].map(|k| r[k][0] * v[0] + r[k][1] * v[1] + r[k][2] * v[2]);
    let lin = rot([p[0], p[1], p[2]]);
    let ang_g = rot([p[3], p[4], p[5]]);
    let pos = [x[0], x[1], x[2]];
    let cross = [
        pos[1] * lin[2] - pos[2] * lin[1],
        pos[2] * lin[0] - pos[0] * lin[2],
        pos[0] * lin[1] - pos[1] * lin[0],
    ];
    // Potential: gravity of every mass, and the linear springs.
    let g = model.gravity;
    let mut potential = g * model.body.mass * x[2];
    for b in &model.bodies {
        let u = b.position.value(&x[6..]);
        potential += g * b.mass * (x[2] + r[2][0] * u[0] + r[2][1] * u[1] + r[2][2] * u[2]);
    }
    for (i, c) in model.coordinates.iter().enumerate() {
        if let Spring::Linear { stiffness } = c.spring {
            potential += 0.5 * stiffness * (x[6 + i] - c.neutral).powi(2);
        }
        assert!(
            x[6 + i] > c.min && x[6 + i] < c.max,
            "y{} reached a bump stop: the test must stay in range",
            i + 1
        );
    }
    Invariants {
        energy: kinetic + potential,
        momentum: lin,
        angular_momentum: [
            cross[0] + ang_g[0],
            cross[1] + ang_g[1],
            cross[2] + ang_g[2],
        ],
    }
}

/// Integrate 10 s of free flight with tight tolerances and return the
/// invariants at the start and the largest drift seen at 100 instants.
fn drift(mut model: Model, gravity: bool, springs: bool) -> (f64, f64, f64) {
    if !gravity {
        model.gravity = 0.0;
    }
    for c in &mut model.coordinates {
        c.damping = 0.0;
        c.stop_damping = 0.0;
        if !springs {
            c.spring = Spring::None;
        }
    }
    let n = model.dof();
    let plant = GenericPlant::new(model.clone()).unwrap();
    let control = Controller::new(ControllerConfig::default(), &model, 0.0).unwrap();
    let mut sys = RoverSystem::<_, Terrain>::new(plant, None, control);
    let mut y = vec![0.0; 2 * n + 1];
    y[..n].copy_from_slice(
        &[0.3, -0.2, 1.0, 0.1, -0.05, 0.4]
            .iter()
            .copied()
            .chain(model.rest())
            .collect::<Vec<_>>(),
    );
    let w0 = [0.2, -0.1, 0.15, 0.04, -0.03, 0.05];
    y[n..n + 6].copy_from_slice(&w0);
    for i in 0..model.m() {
        y[n + 6 + i] = if i % 2 == 0 { 0.02 } else { -0.03 };
    }
    let mut integ = IntegratorConfig::Dopri5(AdaptiveConfig {
        rtol: 1e-12,
        atol: 1e-14,
        ..Default::default()
    })
    .build(2 * n + 1)
    .unwrap();
    let mut probe = GenericPlant::new(model.clone()).unwrap();
    let start = invariants(&model, &mut probe, &y);
    let (mut de, mut dp, mut dh) = (0.0f64, 0.0f64, 0.0f64);
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let mut t = 0.0;
    for k in 1..=100 {
        integ
            .advance(&mut sys, &mut t, &mut y, k as f64 * 0.1)
            .unwrap();
        let now = invariants(&model, &mut probe, &y);
        de = de.max((now.energy - start.energy).abs() / start.energy.abs());
        let d = [0, 1, 2].map(|i| now.momentum[i] - start.momentum[i]);
        dp = dp.max(norm(d) / norm(start.momentum));
        let d = [0, 1, 2].map(|i| now.angular_momentum[i] - start.angular_momentum[i]);
        dh = dh.max(norm(d) / norm(start.angular_momentum));
    }
    (de, dp, dh)
}

#[test]
fn energy_and_momenta_are_conserved_without_gravity_springs_or_contact() {
    for (name, model) in [
        ("exomars", exomars()),
        ("swing4", swing4()),
        ("swing4_rich", swing4_rich()),
    ] {
        let (de, dp, dh) = drift(model, false, false);
        assert!(de < 1e-9, "{name}: energy drift {de:e}");
        assert!(dp < 1e-9, "{name}: linear momentum drift {dp:e}");
        assert!(dh < 1e-9, "{name}: angular momentum drift {dh:e}");
    }
}

#[test]
fn kinetic_plus_potential_energy_is_conserved_with_gravity_and_springs() {
    for (name, model) in [("exomars", exomars()), ("swing4", swing4())] {
        let (de, _, _) = drift(model, true, true);
        assert!(de < 1e-9, "{name}: T + U drift {de:e}");
    }
}
