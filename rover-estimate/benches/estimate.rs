//! One filter step: a prediction over 10 ms (the commands held), an IMU
//! update (gyros and accelerometers) and a wheel-encoder update, on
//! swing4 and MER (their generated plants) on the paper's Fig. 13
//! terrain, rigid, after 8 s of driving at 0.1 m/s; 500 recorded steps
//! replayed in turn (the replay restarts from the same filter, outside
//! the timing). And the step's parts for swing4.
//! `cargo bench -p rover-estimate --features runtime --bench estimate -- --warm-up-time 1 --measurement-time 3`.

#[path = "../tests/support/rover.rs"]
mod rover;

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rover_dynamics::plant::Plant;
use rover_estimate::{Estimator, FilterConfig, ProcessModel};

/// Steps recorded, replayed in turn.
const STEPS: usize = 500;

/// The parts of a step.
#[derive(Clone, Copy, PartialEq)]
enum Part {
    /// The prediction over 10 ms.
    Predict,
    /// The sample's updates: the IMU's, the encoders'.
    Update,
}

/// `iters` filter steps of the replay, the parts in `timed` timed,
/// the replay's restarts not.
fn replayed<M: ProcessModel + Clone>(
    start: &Estimator<M>,
    steps: &[rover::Step],
    iters: u64,
    timed: &[Part],
) -> Duration
where
    M::Error: std::fmt::Debug,
{
    let mut filter = start.clone();
    let mut elapsed = Duration::ZERO;
    let mut k = 0;
    for _ in 0..iters {
        if k == steps.len() {
            filter = start.clone();
            k = 0;
        }
        let step = &steps[k];
        for part in [Part::Predict, Part::Update] {
            let begin = Instant::now();
            match part {
                Part::Predict => filter.predict(0.01, &step.torques, &step.steering).unwrap(),
                Part::Update => filter.update(&step.sample).unwrap(),
            }
            if timed.contains(&part) {
                elapsed += begin.elapsed();
            }
        }
        black_box(filter.state());
        k += 1;
    }
    elapsed
}

/// The replay's states, in turn.
fn states<M: ProcessModel + Clone>(
    start: &Estimator<M>,
    steps: &[rover::Step],
) -> Vec<(f64, Vec<f64>)>
where
    M::Error: std::fmt::Debug,
{
    let mut filter = start.clone();
    steps
        .iter()
        .map(|s| {
            rover::replay(&mut filter, s).unwrap();
            (filter.time(), filter.state().to_vec())
        })
        .collect()
}

fn one_step<P: Plant + Clone>(c: &mut Criterion, name: &str, plant: P) {
    let all = [Part::Predict, Part::Update];
    let mut group = c.benchmark_group("filter_step");
    for every in [1, 2] {
        let config = FilterConfig {
            jacobian_every: every,
            ..FilterConfig::default()
        };
        let (start, steps) = rover::recorded(name, plant.clone(), STEPS, config);
        let id = format!("{name}/jacobian_every_{every}");
        group.bench_function(BenchmarkId::new("generated", id), |b| {
            b.iter_custom(|iters| replayed(&start, &steps, iters, &all))
        });
    }
    group.finish();
    let (start, steps) = rover::recorded(name, plant, STEPS, FilterConfig::default());
    if name != "swing4" {
        return;
    }
    let mut group = c.benchmark_group("filter_step_parts_swing4");
    for (id, part) in [("predict", Part::Predict), ("update", Part::Update)] {
        group.bench_function(id, |b| {
            b.iter_custom(|iters| replayed(&start, &steps, iters, &[part]))
        });
    }
    // The model's right-hand side and its assembled Jacobian, at the
    // replay's states in turn.
    let states = states(&start, &steps);
    let mut model = start.model().clone();
    let dim = ProcessModel::dim(&model);
    let (mut f, mut jac) = (vec![0.0; dim], vec![0.0; dim * dim]);
    let mut k = 0;
    group.bench_function("model_rhs", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            model
                .rhs(states[k].0, black_box(&states[k].1), &mut f)
                .unwrap();
            black_box(&f);
        })
    });
    group.bench_function("model_rhs_and_jacobian", |b| {
        b.iter(|| {
            k = (k + 1) % states.len();
            model
                .rhs_and_jacobian(states[k].0, black_box(&states[k].1), &mut f, &mut jac)
                .unwrap();
            black_box(&jac);
        })
    });
    group.finish();
}

fn steps(c: &mut Criterion) {
    one_step(c, "swing4", rover_models::Swing4::new());
    one_step(c, "mer", rover_models::Mer::new());
}

criterion_group!(benches, steps);
criterion_main!(benches);
