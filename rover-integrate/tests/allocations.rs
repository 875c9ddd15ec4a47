//! The integrators allocate nothing per step: a counting global allocator (installed by
//! `allocation-counter`, hence this file of its own) sees 0 allocations after a warm-up.

use std::convert::Infallible;

use rover_integrate::{
    AdaptiveConfig, BdfConfig, FixedStepConfig, Integrator, IntegratorConfig, OdeSystem,
};

/// A rover-sized (n = 12, dimension 24) nonlinear mechanical system of the rover's shape,
/// `ẋ = B(x)·w`, `ẇ = a(x, w)`: a damped chain of pendulum-like coordinates with a stiff
/// spring on the last one (a tyre), so the BDF's Newton iteration has work to do.
struct Chain;

const N: usize = 12;

impl OdeSystem for Chain {
    type Error = Infallible;
    fn dim(&self) -> usize {
        2 * N
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Infallible> {
        let (x, w) = y.split_at(N);
        for i in 0..N {
            let next = x[(i + 1) % N];
            dy[i] = w[i] * (1.0 + 0.1 * next.sin());
            let stiffness = if i == N - 1 { 1e4 } else { 4.0 };
            dy[N + i] = -stiffness * x[i].sin() - 0.5 * w[i] + 0.3 * (next - x[i]);
        }
        Ok(())
    }
}

fn initial_state() -> Vec<f64> {
    (0..2 * N).map(|i| 0.1 * ((i % 5) as f64 - 2.0)).collect()
}

#[test]
fn integrators_allocate_nothing_per_step_after_warm_up() {
    // The counter counts: one boxed value is one allocation.
    let probe = allocation_counter::measure(|| {
        std::hint::black_box(Box::new(1.0f64));
    });
    assert_eq!(probe.count_total, 1);

    // Real-time path: 10 000 single steps, one `advance` call each.
    let h = 1e-4;
    for config in [
        IntegratorConfig::Rk4(FixedStepConfig { step: h }),
        IntegratorConfig::SemiImplicitEuler(FixedStepConfig { step: h }),
    ] {
        let mut integrator = config.build(2 * N).unwrap();
        let (mut t, mut y) = (0.0, initial_state());
        integrator.advance(&mut Chain, &mut t, &mut y, h).unwrap();
        let info = allocation_counter::measure(|| {
            for i in 2..=10_001 {
                integrator
                    .advance(&mut Chain, &mut t, &mut y, i as f64 * h)
                    .unwrap();
            }
        });
        assert_eq!(integrator.stats().steps, 10_001, "{}", config.method());
        assert_eq!(info.count_total, 0, "{}: {info:?}", config.method());
    }

    // Adaptive methods: 200 output intervals, with a control change (restart) every 10, which
    // exercises starting, landing, step rejection and (BDF) Jacobian updates.
    for config in [
        IntegratorConfig::Dopri5(AdaptiveConfig {
            rtol: 1e-6,
            atol: 1e-9,
            ..AdaptiveConfig::default()
        }),
        IntegratorConfig::Bdf(BdfConfig {
            rtol: 1e-6,
            atol: Some(1e-9),
            ..BdfConfig::default()
        }),
    ] {
        let mut integrator = config.build(2 * N).unwrap();
        let (mut t, mut y) = (0.0, initial_state());
        integrator
            .advance(&mut Chain, &mut t, &mut y, 0.01)
            .unwrap();
        let before = integrator.stats();
        let info = allocation_counter::measure(|| {
            for i in 2..=201 {
                if i % 10 == 0 {
                    integrator.restart();
                }
                integrator
                    .advance(&mut Chain, &mut t, &mut y, i as f64 * 0.01)
                    .unwrap();
            }
        });
        let after = integrator.stats();
        let steps = after.steps - before.steps;
        eprintln!("{}: {steps} steps, {after:?}", config.method());
        assert!(steps > 200, "{}: {after:?}", config.method());
        assert_eq!(
            info.count_total,
            0,
            "{}: {info:?} over {steps} steps",
            config.method()
        );
    }
}
