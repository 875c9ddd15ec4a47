//! The rover's assembled Jacobian (the generated plant's exact one, chained
//! with the wheels' load derivatives) against central differences of the
//! whole right-hand side, on the paper's rough ground; and what it buys the
//! implicit integrators.

use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::height_field::Bounds;
use rover_dynamics::plant::Plant;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{BdfConfig, Integrator, IntegratorConfig, JacobianSource, OdeSystem};
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::{RandomField, Terrain};
use rover_runtime::wheel_law::WheelLawConfig;

fn model(name: &str) -> Model {
    rover_spec::load_str(rover_models::builtin(name).unwrap(), name)
        .unwrap()
        .model
}

/// The rover on the paper's rough terrain (Z_R = 0.2), 2 mm into the
/// ground, under a PI speed loop at 0.1 m/s.
fn rough<P: Plant>(model: &Model, plant: P) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    rough_on(model, plant, None)
}

/// [`rough`], the ground covered by `soil` when given.
fn rough_on<P: Plant>(
    model: &Model,
    plant: P,
    soil: Option<&rover_dynamics::soil::Soil>,
) -> (RoverSystem<P, Terrain>, Vec<f64>) {
    let field = RandomField {
        z_r: 0.2,
        node_amplitude: 0.25,
        patch_radius: 0.6,
        extent: Bounds {
            x_min: -3.0,
            x_max: 6.5,
            y_min: -2.0,
            y_max: 2.0,
        },
        ..RandomField::default()
    }
    .grid()
    .unwrap();
    let ground = Ground::new(
        Terrain::Grid(field),
        model,
        ContactMethod::Bounded,
        RimSampling::default(),
        WheelLawConfig::default(),
    );
    let ground = match soil {
        Some(soil) => ground.with_soil(soil, model).unwrap(),
        None => ground,
    };
    let control: ControllerConfig = toml::from_str("[speed]\nspeed = 0.1\nki = 2.0\n").unwrap();
    let control = Controller::new(control, model, 0.0).unwrap();
    let sys = RoverSystem::new(plant, Some(ground), control);
    let n = model.dof();
    let mut y = vec![0.0; sys.dim()];
    y[6..n].copy_from_slice(&model.rest());
    y[2] = model.touchdown_height() - 2e-3;
    (sys, y)
}

/// `∂f/∂y` by central differences of the whole right-hand side.
fn central<S: OdeSystem>(sys: &mut S, t: f64, y: &[f64]) -> Vec<f64> {
    let dim = y.len();
    let (mut plus, mut minus) = (vec![0.0; dim], vec![0.0; dim]);
    let mut jac = vec![0.0; dim * dim];
    let mut yp = y.to_vec();
    for j in 0..dim {
        let h = 1e-6 * y[j].abs().max(1.0);
        yp[j] = y[j] + h;
        sys.rhs(t, &yp, &mut plus).ok().unwrap();
        yp[j] = y[j] - h;
        sys.rhs(t, &yp, &mut minus).ok().unwrap();
        yp[j] = y[j];
        for i in 0..dim {
            jac[i * dim + j] = (plus[i] - minus[i]) / (2.0 * h);
        }
    }
    jac
}

/// Frobenius norm of rows `rows` of a `dim`-column matrix.
fn norm(m: &[f64], dim: usize, rows: std::ops::Range<usize>) -> f64 {
    m[rows.start * dim..rows.end * dim]
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt()
}

/// States of a 4 s drive, every 0.5 s.
fn states<P: Plant + Clone>(sys: &RoverSystem<P, Terrain>, y0: &[f64]) -> Vec<(f64, Vec<f64>)> {
    let mut sys = sys.clone();
    let mut y = y0.to_vec();
    let mut integ = IntegratorConfig::Bdf(BdfConfig::default())
        .build(y.len())
        .unwrap();
    let mut t = 0.0;
    (1..=8)
        .map(|k| {
            integ
                .advance(&mut sys, &mut t, &mut y, 0.5 * k as f64)
                .unwrap();
            (t, y.clone())
        })
        .collect()
}

/// The accelerations' rows of the assembled Jacobian, on every built-in
/// rover driving on rough ground, against central differences: what the
/// assembly leaves out (the patch frames turning, `∂V/∂x` at fixed `w`, the
/// steering) is small next to what it keeps, and next to `1/h` at the
/// implicit methods' steps (a Newton iteration's contraction is about
/// `h·‖ΔJ‖`). Without the wheels' load derivatives, the plant's exact
/// Jacobian alone misses the tyres entirely.
#[test]
fn assembled_jacobian_is_the_stiff_part_of_the_whole_one() {
    fn check<P: Plant + Clone>(name: &str, plant: P) {
        let m = model(name);
        let n = m.dof();
        let (mut sys, y0) = rough(&m, plant);
        let dim = y0.len();
        for (t, y) in states(&sys, &y0) {
            let mut assembled = vec![0.0; dim * dim];
            let spent = sys.jacobian(t, &y, &mut assembled).unwrap().unwrap();
            assert_eq!(spent, 1, "{name}: one right-hand side per Jacobian");
            let reference = central(&mut sys, t, &y);
            let diff: Vec<f64> = assembled
                .iter()
                .zip(&reference)
                .map(|(a, b)| a - b)
                .collect();
            let rows = n..2 * n;
            let relative = norm(&diff, dim, rows.clone()) / norm(&reference, dim, rows.clone());
            // The plant's exact Jacobian at fixed loads alone.
            let mut plant_only = vec![0.0; dim * dim];
            let mut fixed = vec![0.0; 4 * n * n];
            let loads = loads_at(&mut sys, t, &y);
            sys.plant
                .jacobian(&y[..n], &y[n..2 * n], &loads, &mut fixed)
                .unwrap();
            for i in n..2 * n {
                plant_only[i * dim..i * dim + 2 * n]
                    .copy_from_slice(&fixed[i * 2 * n..(i + 1) * 2 * n]);
            }
            let without: Vec<f64> = plant_only
                .iter()
                .zip(&reference)
                .map(|(a, b)| a - b)
                .collect();
            let missed = norm(&without, dim, rows.clone()) / norm(&reference, dim, rows);
            assert!(
                relative < 0.02,
                "{name}, t = {t}: the assembled Jacobian is {relative:.2e} off the whole one"
            );
            assert!(
                missed > 0.9,
                "{name}, t = {t}: the tyres dominate the Jacobian ({missed:.2e} without them)"
            );
        }
    }
    check("swing4", rover_models::Swing4::new());
    check("exomars", rover_models::Exomars::new());
    check("mer", rover_models::Mer::new());
    check("lrv", rover_models::Lrv::new());
}

/// On a soil, the assembled Jacobian against central differences, rows of
/// the accelerations and of the wheels' spins: the soil law's dual-number
/// derivatives (sinkage, velocity, spin) and the spins' own rows
/// `(∂τ − ∂T)/I_w` hold the stiff part; what the patch frames turning leave
/// out is small next to it.
#[test]
fn on_soil_the_assembled_jacobian_is_the_stiff_part_of_the_whole_one() {
    fn check<P: Plant + Clone>(name: &str, plant: P) {
        let sand = rover_runtime::soil::SoilConfig::builtin("dry_sand")
            .unwrap()
            .soil()
            .unwrap();
        let m = model(name);
        let n = m.dof();
        let (mut sys, y0) = rough_on(&m, plant, Some(&sand));
        let dim = y0.len();
        let spins = sys.spin_range();
        assert_eq!(spins.len(), m.wheels.len());
        for (t, y) in states(&sys, &y0) {
            let mut assembled = vec![0.0; dim * dim];
            sys.jacobian(t, &y, &mut assembled).unwrap().unwrap();
            let reference = central(&mut sys, t, &y);
            let diff: Vec<f64> = assembled
                .iter()
                .zip(&reference)
                .map(|(a, b)| a - b)
                .collect();
            for rows in [n..2 * n, spins.clone()] {
                let relative = norm(&diff, dim, rows.clone()) / norm(&reference, dim, rows.clone());
                assert!(
                    relative < 0.02,
                    "{name}, t = {t}, rows {rows:?}: the assembled Jacobian is {relative:.2e} off the whole one"
                );
            }
        }
    }
    check("exomars", rover_models::Exomars::new());
    check("mer", rover_models::Mer::new());
    check("lrv", rover_models::Lrv::new());
}

fn loads_at<P: Plant>(
    sys: &mut RoverSystem<P, Terrain>,
    t: f64,
    y: &[f64],
) -> Vec<rover_dynamics::plant::WheelLoad> {
    let mut dy = vec![0.0; y.len()];
    sys.rhs(t, y, &mut dy).ok().unwrap();
    sys.loads().to_vec()
}

/// BDF at its defaults on a 10 s drive on rough ground, with the assembled
/// Jacobian and with differences: the same run to well within its
/// tolerance, for fewer right-hand sides.
#[test]
fn bdf_with_the_assembled_jacobian_runs_the_same_for_fewer_evaluations() {
    fn drive(source: JacobianSource) -> (Vec<f64>, u64) {
        let m = model("swing4");
        let (mut sys, mut y) = rough(&m, rover_models::Swing4::new());
        let config = BdfConfig {
            jacobian: source,
            ..BdfConfig::default()
        };
        let mut integ = rover_integrate::Bdf::new(y.len(), &config).unwrap();
        let mut t = 0.0;
        integ.advance(&mut sys, &mut t, &mut y, 10.0).unwrap();
        (y, integ.stats().rhs_evals)
    }
    let (assembled, with) = drive(JacobianSource::System);
    let (differenced, without) = drive(JacobianSource::Differences);
    println!(
        "rhs: assembled {with}, differences {without}; X {} vs {}",
        assembled[0], differenced[0]
    );
    for k in 0..3 {
        assert!(
            (assembled[k] - differenced[k]).abs() < 1e-4,
            "coordinate {k}: {} vs {}",
            assembled[k],
            differenced[k]
        );
    }
    assert!(with < without, "{with} right-hand sides against {without}");
}
