//! One 1 ms step of the C library (`rover_step`, the exported symbol),
//! swing4 on rough rigid ground (scenarios/export_rough.toml: its height
//! map, its speed loop, RK4 at 1 ms, the generated plant): criterion's
//! median, then 10⁶ steps each timed on its own for the median and the
//! 99th and 99.9th percentiles, with the heap allocations the steps made
//! counted (allocation_counter); then a fixed arithmetic chain of the
//! same median length timed alike, for the machine's own jitter. The run
//! is reset to t = 0 every 10 s of simulated time, outside the timing, so
//! that the rover stays on its map (docs/EXPORT.md, "Timing").
//!
//! `cargo bench -p rover-plant --bench step -- --warm-up-time 1 --measurement-time 3`

use std::ffi::{CString, c_char, c_int, c_void};
use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::Criterion;

// Link the library whose symbols are declared below.
use rover_plant as _;

unsafe extern "C" {
    fn rover_create(
        scenario: *const c_char,
        out: *mut *mut c_void,
        m: *mut c_char,
        n: usize,
    ) -> c_int;
    fn rover_step(p: *mut c_void, dt: f64) -> c_int;
    fn rover_reset(p: *mut c_void) -> c_int;
    fn rover_destroy(p: *mut c_void);
}

const STEP: f64 = 1e-3;
/// Steps between resets: 10 s simulated.
const RESET_EVERY: u64 = 10_000;

fn plant() -> *mut c_void {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/export_rough.toml"
    );
    let path = CString::new(path).unwrap();
    let mut p = std::ptr::null_mut();
    let mut message = [0 as c_char; 512];
    let s = unsafe { rover_create(path.as_ptr(), &mut p, message.as_mut_ptr(), message.len()) };
    assert_eq!(s, 0, "rover_create failed");
    p
}

fn main() {
    let p = plant();
    let mut c = Criterion::default().configure_from_args();
    let mut k: u64 = 0;
    c.bench_function("c_step_1ms_swing4_rough", |b| {
        b.iter_custom(|iters| {
            let mut total = Duration::ZERO;
            for _ in 0..iters {
                if k.is_multiple_of(RESET_EVERY) {
                    assert_eq!(unsafe { rover_reset(p) }, 0);
                }
                k += 1;
                let start = Instant::now();
                let s = unsafe { rover_step(black_box(p), STEP) };
                total += start.elapsed();
                assert_eq!(s, 0);
            }
            total
        })
    });
    c.final_summary();

    // 10⁶ steps, each timed, the allocations of the steps counted.
    let n = 1_000_000usize;
    let mut times = Vec::with_capacity(n);
    let mut allocations = 0;
    for _ in 0..n as u64 / RESET_EVERY {
        assert_eq!(unsafe { rover_reset(p) }, 0);
        allocations += allocation_counter::measure(|| {
            for _ in 0..RESET_EVERY {
                let start = Instant::now();
                let s = unsafe { rover_step(black_box(p), STEP) };
                let elapsed = start.elapsed();
                assert_eq!(s, 0);
                times.push(elapsed);
            }
        })
        .count_total;
    }
    times.sort();
    let at = |q: f64| times[((n as f64 * q) as usize).min(n - 1)].as_secs_f64() * 1e6;
    println!(
        "rover_step, 1 ms, swing4 on rough rigid ground, {n} steps: median {:.2} µs, 99th percentile {:.2} µs, 99.9th percentile {:.2} µs, max {:.2} µs; {allocations} allocations",
        at(0.5),
        at(0.99),
        at(0.999),
        times[n - 1].as_secs_f64() * 1e6
    );
    unsafe { rover_destroy(p) };

    // The machine's own jitter: a fixed arithmetic chain of about the
    // step's median length, timed the same way. Its tail is what the
    // operating system adds to any 8 µs of work on this machine; the
    // step's tail above it is the step's own.
    let median = at(0.5);
    let mut rounds = 1000u64;
    let work = |rounds: u64| {
        let mut x = black_box(1.0f64);
        for _ in 0..rounds {
            x = x.mul_add(0.999_999_9, 1e-9);
        }
        black_box(x)
    };
    for _ in 0..20 {
        let start = Instant::now();
        work(rounds);
        let us = start.elapsed().as_secs_f64() * 1e6;
        rounds = ((rounds as f64) * median / us.max(1e-3)).max(1.0) as u64;
    }
    let mut control = Vec::with_capacity(n);
    for _ in 0..n {
        let start = Instant::now();
        work(rounds);
        control.push(start.elapsed());
    }
    control.sort();
    let at = |q: f64| control[((n as f64 * q) as usize).min(n - 1)].as_secs_f64() * 1e6;
    println!(
        "fixed work of the same median, {n} runs: median {:.2} µs, 99th percentile {:.2} µs, 99.9th percentile {:.2} µs, max {:.2} µs",
        at(0.5),
        at(0.99),
        at(0.999),
        control[n - 1].as_secs_f64() * 1e6
    );
}
