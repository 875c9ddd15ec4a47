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
use rover_estimate::{Estimator, ProcessModel};

/// Steps recorded, replayed in turn.
const STEPS: usize = 500;

/// `iters` filter steps of the replay, timed without its restarts.
fn replayed<M: ProcessModel + Clone>(
    start: &Estimator<M>,
    steps: &[rover::Step],
    iters: u64,
    part: impl Fn(&mut Estimator<M>, &rover::Step),
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
        let begin = Instant::now();
        part(&mut filter, &steps[k]);
        elapsed += begin.elapsed();
        black_box(filter.state());
        k += 1;
    }
    elapsed
}

fn one_step<P: Plant + Clone>(c: &mut Criterion, name: &str, plant: P) {
    let (start, steps) = rover::recorded(name, plant, STEPS);
    let mut group = c.benchmark_group("filter_step");
    group.bench_function(BenchmarkId::new("generated", name), |b| {
        b.iter_custom(|iters| {
            replayed(&start, &steps, iters, |f, s| rover::replay(f, s).unwrap())
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
