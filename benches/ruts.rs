//! What the wheels' ruts cost (docs/PERFORMANCE.md, "Ruts"): MER (its
//! generated plant) on dry sand under its speed loop, ruts in 2 cm cells
//! against the same ground that keeps none, in one criterion run:
//!
//! - `ruts_fixed_step`: one 1 ms semi-implicit Euler step on the paper's
//!   rough terrain (`support::rough_field`), the rut recording of
//!   `step_accepted` included, once the middle and rear wheels run in the
//!   front wheels' ruts (checked before timing); and 1 ms in 0.25 ms steps
//!   under the soil_pocket scenarios' stiff speed loop, which 1 ms steps
//!   do not hold (shown);
//! - `ruts_default_integrator`: the whole 20 s drive with the scenario's
//!   default integrator (BDF), and the shipped `soil_pocket` scenarios
//!   whole, as `rover simulate` runs them;
//! - `ruts_kilometre`: a 1 km drive at 1 m/s on flat sand; the heap the rut
//!   map and the process hold after it (a counting global allocator), and
//!   the cost of 10,000 steps from the first metres against from 990 m.
//!
//! Medians and ratios are printed at the end, and beside each ratio of two
//! criterion medians the median ratio of runs timed in turn, which the
//! shared machine's changing load moves less. A name given on the command
//! line that none of a part's benchmark ids contains skips that part's setup.
//! `cargo bench --bench ruts -- --warm-up-time 1 --measurement-time 3`.

mod support;

use std::alloc::{GlobalAlloc, Layout, System};
use std::hint::black_box;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use criterion::{Bencher, BenchmarkId, Criterion, SamplingMode};
use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::soil::Soil;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{FixedStepConfig, Integrator, OdeSystem, SemiImplicitEuler};
use rover_models::Mer;
use rover_runtime::control::{Controller, ControllerConfig, Profile, SpeedConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::soil::SoilConfig;
use rover_runtime::terrain::Terrain;
use rover_runtime::wheel_law::WheelLawConfig;
use rover_scenario::prepare::Prepared;
use rover_terrain::ruts::RutMap;

/// The system allocator, watched: the bytes live now, and the most ever
/// live since [`reset_peak`].
struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn added(bytes: usize) {
    let live = LIVE.fetch_add(bytes, Ordering::Relaxed) + bytes;
    PEAK.fetch_max(live, Ordering::Relaxed);
}

fn removed(bytes: usize) {
    LIVE.fetch_sub(bytes, Ordering::Relaxed);
}

// SAFETY: every call goes to `System` with the caller's arguments; the
// counters only watch.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is `System`'s.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            added(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: as `alloc`.
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            added(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from this allocator, that is from `System`.
        unsafe { System.dealloc(ptr, layout) };
        removed(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: as `dealloc`.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            removed(layout.size());
            added(new_size);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The bytes live now.
fn live() -> usize {
    LIVE.load(Ordering::Relaxed)
}

/// The peak starts again from what is live now.
fn reset_peak() {
    PEAK.store(live(), Ordering::Relaxed);
}

fn peak() -> usize {
    PEAK.load(Ordering::Relaxed)
}

const MB: f64 = 1e6;

/// The side of the ruts' cells \[m\], the scenario's default.
const CELL: f64 = 0.02;

/// The fixed step \[s\].
const STEP: f64 = 1e-3;

/// A speed loop's gains: on a soil it holds the wheels' mean rim speed.
#[derive(Clone, Copy)]
struct Gains {
    /// N·m per m/s of rim speed, per wheel.
    kp: f64,
    /// N·m per m, per wheel.
    ki: f64,
}

/// The default proportional gain, and the soil_pocket scenarios' integral
/// one: the P loop alone would leave MER short of the 2–4 N·m per wheel
/// that dry sand asks of it.
const GAINS: Gains = Gains {
    kp: 10.0,
    ki: 1000.0,
};

/// The soil_pocket scenarios' stiff wheel-rate loop: each wheel's torque
/// falls by kp·r per rad/s of its own spin (its term about the mean and
/// its share of the mean), so its spin decays at kp·r/J = 500 · 0.13 /
/// 0.0169 ≈ 3800 s⁻¹, and an explicit step must stay under 2/3800 s ≈
/// 0.5 ms (at the default gain, 77 s⁻¹, under 26 ms).
const STIFF: Gains = Gains {
    kp: 500.0,
    ki: 1000.0,
};

/// MER's description.
fn mer() -> Model {
    support::model("mer")
}

fn dry_sand() -> Soil {
    SoilConfig::builtin("dry_sand").unwrap().soil().unwrap()
}

/// MER on `terrain` covered with `soil`, keeping ruts in cells of `ruts`
/// \[m\] if given, its speed loop holding `speed` \[m/s\]: at rest, the
/// suspension at its rest angles, the wheels 2 mm into the soil's surface
/// and rolling.
fn soft_system(
    terrain: Terrain,
    model: &Model,
    soil: &Soil,
    ruts: Option<f64>,
    speed: f64,
    gains: Gains,
) -> (RoverSystem<Mer, Terrain>, Vec<f64>) {
    let ground = Ground::new(
        terrain,
        model,
        ContactMethod::default(),
        RimSampling::default(),
        WheelLawConfig::default(),
    )
    .with_soil(soil, model)
    .unwrap();
    let ground = match ruts {
        Some(cell) => ground.with_ruts(cell),
        None => ground,
    };
    let config = ControllerConfig {
        speed: Some(SpeedConfig {
            speed: Profile::Constant(speed),
            kp: gains.kp,
            ki: gains.ki,
            ..Default::default()
        }),
        ..Default::default()
    };
    let control = Controller::new(config, model, 0.0).unwrap();
    let mut sys = RoverSystem::new(Mer::new(), Some(ground), control);
    let mut y = vec![0.0; sys.dim()];
    let n = model.dof();
    y[6..n].copy_from_slice(&model.rest());
    y[2] = support::start_height(model);
    sys.roll_spins(0.0, &mut y);
    (sys, y)
}

/// A drive with the fixed-step semi-implicit Euler method: the system, the
/// integrator and where they are.
#[derive(Clone)]
struct Drive {
    sys: RoverSystem<Mer, Terrain>,
    integ: SemiImplicitEuler,
    y: Vec<f64>,
    t: f64,
}

impl Drive {
    fn new(sys: RoverSystem<Mer, Terrain>, y: Vec<f64>, step: f64) -> Self {
        let integ = SemiImplicitEuler::new(y.len(), &FixedStepConfig { step }).unwrap();
        Self {
            sys,
            integ,
            y,
            t: 0.0,
        }
    }

    /// `count` advances of 1 ms each (one step, or several of a shorter
    /// step).
    fn millis(&mut self, count: usize) {
        for _ in 0..count {
            let to = self.t + 1e-3;
            self.integ
                .advance(&mut self.sys, &mut self.t, &mut self.y, to)
                .unwrap();
        }
    }

    /// On to time `t_end`.
    fn until(&mut self, t_end: f64) {
        self.integ
            .advance(&mut self.sys, &mut self.t, &mut self.y, t_end)
            .unwrap();
    }

    /// The map of the ruts, if the ground keeps them.
    fn ruts(&self) -> Option<&RutMap> {
        let ground = self.sys.ground.as_ref()?;
        Some(ground.ruts()?.map())
    }

    /// Each wheel's rut depth under it at the present state \[m\].
    fn ruts_under(&mut self) -> Vec<f64> {
        let mut dy = vec![0.0; self.y.len()];
        self.sys.rhs(self.t, &self.y, &mut dy).unwrap();
        self.sys.reports().iter().map(|r| r.rut).collect()
    }
}

/// The median of the last `n` entries (criterion's measured samples come
/// after its warm-up's); NaN for a benchmark the filter left out.
fn median_of_last(v: &[f64], n: usize) -> f64 {
    let mut last = v[v.len().saturating_sub(n)..].to_vec();
    last.sort_by(f64::total_cmp);
    last.get(last.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Times `run` on a fresh clone of `from` per iteration, the clone and its
/// drop outside the timer; each sample's time per iteration goes into
/// `samples`.
fn time_from<T: Clone>(
    b: &mut Bencher<'_>,
    from: &T,
    samples: &mut Vec<f64>,
    mut run: impl FnMut(&mut T),
) {
    b.iter_custom(|iters| {
        let mut total = Duration::ZERO;
        for _ in 0..iters {
            let mut x = from.clone();
            let start = Instant::now();
            run(&mut x);
            total += start.elapsed();
            black_box(&x);
        }
        samples.push(total.as_secs_f64() / iters as f64);
        total
    });
}

/// The median over `pairs` of the ratio of `run` on a clone of `a` to `run`
/// on a clone of `b`, timed one after the other (clones outside the
/// timer): the shared machine's load, which moves from one criterion
/// benchmark to the next, weighs on both sides of each ratio alike.
fn paired<T: Clone>(a: &T, b: &T, pairs: usize, mut run: impl FnMut(&mut T)) -> f64 {
    let mut time = |from: &T| {
        let mut x = from.clone();
        let start = Instant::now();
        run(&mut x);
        let took = start.elapsed().as_secs_f64();
        black_box(&x);
        took
    };
    let mut ratios: Vec<f64> = (0..pairs).map(|_| time(a) / time(b)).collect();
    ratios.sort_by(f64::total_cmp);
    ratios[pairs / 2]
}

/// Whether a part that benchmarks `ids` (`group/function/parameter`)
/// runs: no name on the command line (other than flags and their
/// numbers), or one that one of its ids contains, as criterion filters.
fn wanted(ids: &[&str]) -> bool {
    let names: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-') && a.parse::<f64>().is_err())
        .collect();
    names.is_empty()
        || names
            .iter()
            .any(|n| ids.iter().any(|id| id.contains(n.as_str())))
}

/// Simulated time of the rough drives before timing \[s\]: the rear
/// wheels, 1.35 m behind the front ones, reach the front ones' ruts after
/// 13.5 s at 0.1 m/s.
const DRIVEN: f64 = 20.0;

/// Milliseconds advanced from one saved state before the timed drive goes
/// back to it (2 s simulated, 0.2 m at 0.1 m/s): the steps timed are those
/// of a stretch of the drive, not of one state.
const WINDOW: usize = 2000;

/// The smallest step that holds the stiff loop (the largest that agrees
/// with a 0.05 ms drive to the millimetre over 20 s; 0.4 ms lets one
/// wheel's spin ring) \[s\].
const STIFF_STEP: f64 = 2.5e-4;

/// Rounded to 0.1 mm, in mm, for the report.
fn mm(v: impl Iterator<Item = f64>) -> Vec<f64> {
    v.map(|r| (r * 1e4).round() / 10.0).collect()
}

/// MER driven [`DRIVEN`] s on the rough terrain under dry sand: a line
/// saying where it is, then the drive.
fn rough_drive(ruts: Option<f64>, gains: Gains, step: f64) -> (String, Drive) {
    let model = mer();
    let rough = Terrain::Grid(support::rough_field());
    let (sys, y) = soft_system(rough, &model, &dry_sand(), ruts, support::SPEED, gains);
    let mut d = Drive::new(sys, y, step);
    let start = Instant::now();
    d.until(DRIVEN);
    let wall = start.elapsed().as_secs_f64();
    let under = d.ruts_under();
    let line = format!(
        "{DRIVEN} s at kp {}, step {} ms, ruts {}, in {wall:.2} s wall: x = {:.3} m, \
         v_x = {:.3} m/s, torques [N·m] {:?}, rut under the wheels [mm] {:?}, sinkage [mm] \
         {:?}, {} tiles",
        gains.kp,
        1e3 * step,
        ruts.is_some(),
        d.y[0],
        d.y[model.dof()],
        d.sys
            .torques()
            .iter()
            .map(|v| (v * 10.0).round() / 10.0)
            .collect::<Vec<_>>(),
        mm(under.iter().copied()),
        mm(d.sys.reports().iter().map(|r| r.sinkage)),
        d.ruts().map_or(0, RutMap::tile_count),
    );
    (line, d)
}

/// Part 1: one 1 ms advance on the rough terrain under dry sand, with ruts
/// and without: one 1 ms semi-implicit Euler step at the default gain, and
/// four 0.25 ms steps under the stiff loop, which a 1 ms step does not hold
/// (the bench shows it: the spins ring, the torques saturate, the rover
/// stalls).
fn fixed_step(c: &mut Criterion, out: &mut Vec<String>) {
    const GROUP: &str = "ruts_fixed_step";
    if !wanted(&[
        "ruts_fixed_step/advance_1ms/ruts",
        "ruts_fixed_step/advance_1ms/no_ruts",
        "ruts_fixed_step/advance_1ms/stiff_loop_ruts",
        "ruts_fixed_step/advance_1ms/stiff_loop_no_ruts",
    ]) {
        return;
    }
    let (line, _) = rough_drive(Some(CELL), STIFF, STEP);
    out.push(format!("stiff loop, 1 ms steps: {line}"));
    let mut drives = Vec::new();
    for (id, ruts, gains, step) in [
        ("ruts", Some(CELL), GAINS, STEP),
        ("no_ruts", None, GAINS, STEP),
        ("stiff_loop_ruts", Some(CELL), STIFF, STIFF_STEP),
        ("stiff_loop_no_ruts", None, STIFF, STIFF_STEP),
    ] {
        let (line, mut d) = rough_drive(ruts, gains, step);
        out.push(format!("{id}: {line}"));
        // Driving, and if it keeps ruts, its middle and rear wheels
        // (2..6) in the front ones'.
        assert!(d.y[0] > 1.5, "{line}");
        if ruts.is_some() {
            let under = d.ruts_under();
            assert!(under[2..].iter().all(|&r| r > 1e-4), "{line}");
        }
        drives.push((id, d));
    }
    let mut group = c.benchmark_group(GROUP);
    let mut medians = Vec::new();
    for (id, saved) in &drives {
        let mut d = saved.clone();
        let mut taken = 0;
        let mut samples = Vec::new();
        group.bench_function(BenchmarkId::new("advance_1ms", id), |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                let mut left = iters as usize;
                while left > 0 {
                    if taken == WINDOW {
                        d.clone_from(saved);
                        taken = 0;
                    }
                    let chunk = left.min(WINDOW - taken);
                    let start = Instant::now();
                    d.millis(chunk);
                    total += start.elapsed();
                    taken += chunk;
                    left -= chunk;
                }
                samples.push(total.as_secs_f64() / iters as f64);
                total
            })
        });
        medians.push(median_of_last(&samples, 100));
    }
    group.finish();
    // The same windows of 2000 ms, with ruts and without, in turn.
    let window = |d: &mut Drive| d.millis(WINDOW);
    let pair = [
        paired(&drives[0].1, &drives[1].1, 21, window),
        paired(&drives[2].1, &drives[3].1, 11, window),
    ];
    out.push(format!(
        "one 1 ms semi-implicit Euler step, rough dry sand: with ruts {:.2} µs, without {:.2} µs, \
         ratio {:.3} (paired {:.3}); stiff loop, 4 steps of 0.25 ms: with ruts {:.2} µs per \
         simulated ms, without {:.2} µs, ratio {:.3} (paired {:.3}) (target ≤ 10 µs per 1 ms step)",
        1e6 * medians[0],
        1e6 * medians[1],
        medians[0] / medians[1],
        pair[0],
        1e6 * medians[2],
        1e6 * medians[3],
        medians[2] / medians[3],
        pair[1],
    ));
}

/// Simulated time of the whole drive with the default integrator \[s\].
const WHOLE: f64 = 20.0;

/// When the middle and rear wheels meet the ruts of the wheels ahead
/// (0.65–0.7 m ahead of them, at about 0.09 m/s) \[s\]: where they
/// stood at the start, then along them. Until then both drives are the
/// same to the bit.
const MEET_RUTS: [f64; 2] = [6.0, 8.0];

/// Part 2: the whole 20 s drive with the scenario's default integrator
/// (BDF), with ruts and without; and the shipped soil_pocket scenarios
/// whole, as `rover simulate` runs them (generated plant, CSV to a sink).
fn default_integrator(c: &mut Criterion, out: &mut Vec<String>) {
    const GROUP: &str = "ruts_default_integrator";
    if !wanted(&[
        "ruts_default_integrator/drive_20s/ruts",
        "ruts_default_integrator/drive_20s/no_ruts",
        "ruts_default_integrator/scenario/soil_pocket",
        "ruts_default_integrator/scenario/soil_pocket_no_ruts",
    ]) {
        return;
    }
    let model = mer();
    let sand = dry_sand();
    let rough = Terrain::Grid(support::rough_field());
    let config = rover_scenario::scenario::default_integrator();
    let mut group = c.benchmark_group(GROUP);
    // Long runs: as many iterations in every sample.
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    let mut medians = Vec::new();
    let mut starts = Vec::new();
    for (id, ruts) in [("ruts", Some(CELL)), ("no_ruts", None)] {
        let start = soft_system(rough.clone(), &model, &sand, ruts, support::SPEED, GAINS);
        starts.push(start.clone());
        // One run outside the timing, to say where it ends.
        let (mut sys, mut y) = start.clone();
        let mut integ = config.build(y.len()).unwrap();
        let mut t = 0.0;
        // Steps before the middle and rear wheels meet the ruts, while they
        // enter them, and in them.
        let mut steps = Vec::new();
        for t_end in [MEET_RUTS[0], MEET_RUTS[1], WHOLE] {
            integ.advance(&mut sys, &mut t, &mut y, t_end).unwrap();
            steps.push(integ.stats().steps - steps.iter().sum::<u64>());
        }
        let stats = integ.stats();
        let mut dy = vec![0.0; y.len()];
        sys.rhs(t, &y, &mut dy).unwrap();
        let under: Vec<f64> = sys.reports().iter().map(|r| r.rut).collect();
        out.push(format!(
            "BDF {id}: x = {:.3} m after {WHOLE} s, {} steps ({:?} over 0–{}–{}–{WHOLE} s; \
             {} rejected), {} right-hand sides, {} Jacobians, rut under wheels [mm] {:?}",
            y[0],
            stats.steps,
            steps,
            MEET_RUTS[0],
            MEET_RUTS[1],
            stats.rejected_steps,
            stats.rhs_evals,
            stats.jacobian_evals,
            mm(under.iter().copied()),
        ));
        if ruts.is_some() {
            assert!(
                under[2..].iter().all(|&r| r > 1e-4),
                "BDF: the middle and rear wheels are not in ruts: {under:?}"
            );
        }
        let mut samples = Vec::new();
        group.bench_function(BenchmarkId::new("drive_20s", id), |b| {
            time_from(b, &start, &mut samples, |(sys, y)| {
                let mut integ = config.build(y.len()).unwrap();
                let mut t = 0.0;
                integ.advance(sys, &mut t, y, WHOLE).unwrap();
            })
        });
        medians.push(median_of_last(&samples, 10));
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for name in ["soil_pocket", "soil_pocket_no_ruts"] {
        let path = root.join("scenarios").join(format!("{name}.toml"));
        let prepared = Prepared::from_file(None, &path).unwrap();
        let run = || {
            prepared
                .run(false, std::io::sink(), &AtomicBool::new(false), |_| {})
                .unwrap()
        };
        let summary = run();
        assert!(summary.complete, "{name}: {:?}", summary.error);
        let mut samples = Vec::new();
        group.bench_function(BenchmarkId::new("scenario", name), |b| {
            time_from(b, &(), &mut samples, |_| {
                black_box(run().rhs_evals);
            })
        });
        medians.push(median_of_last(&samples, 10));
        out.push(format!(
            "{name}: {} s simulated, {} right-hand sides, plant {}",
            summary.t_end, summary.rhs_evals, summary.plant
        ));
    }
    group.finish();
    let pair = paired(&starts[0], &starts[1], 5, |(sys, y)| {
        let mut integ = config.build(y.len()).unwrap();
        let mut t = 0.0;
        integ.advance(sys, &mut t, y, WHOLE).unwrap();
    });
    let pocket = 50.0;
    out.push(format!(
        "default integrator (BDF), whole runs: 20 s rough drive with ruts {:.1} ms ({:.0}× real \
         time), without {:.1} ms ({:.0}×), ratio {:.3} (paired {pair:.3}); soil_pocket {:.1} ms \
         ({:.0}×), soil_pocket_no_ruts {:.1} ms ({:.0}×), ratio {:.3} (target ≥ 500×)",
        1e3 * medians[0],
        WHOLE / medians[0],
        1e3 * medians[1],
        WHOLE / medians[1],
        medians[0] / medians[1],
        1e3 * medians[2],
        pocket / medians[2],
        1e3 * medians[3],
        pocket / medians[3],
        medians[2] / medians[3],
    ));
}

/// The kilometre drive's speed \[m/s\].
const FAST: f64 = 1.0;

/// Steps timed from each end of the kilometre (10 m at 1 m/s).
const TEN_METRES: usize = 10_000;

/// Part 3: 1 km on flat dry sand at 1 m/s, ruts on: the heap after it, and
/// 10 m from the first metres against 10 m from 990 m.
fn kilometre(c: &mut Criterion, out: &mut Vec<String>) {
    const GROUP: &str = "ruts_kilometre";
    if !wanted(&[
        "ruts_kilometre/steps_10000/first_10m",
        "ruts_kilometre/steps_10000/last_10m",
    ]) {
        return;
    }
    let model = mer();
    let sand = dry_sand();
    let before = live();
    reset_peak();
    let (sys, y) = soft_system(Terrain::default(), &model, &sand, Some(CELL), FAST, GAINS);
    let mut d = Drive::new(sys, y, STEP);
    let start = Instant::now();
    // Up to speed first.
    d.until(3.0);
    let x0 = d.y[0];
    let held = live();
    let first = d.clone();
    // What the snapshots hold is not the drive's.
    let mut snapshots = live() - held;
    let mut peak_drive = peak() - snapshots;
    // A stalled rover would never get there.
    let stalled = |d: &Drive| assert!(d.t < 2000.0, "x = {} m at t = {} s", d.y[0], d.t);
    while d.y[0] < x0 + 990.0 {
        d.millis(1000);
        stalled(&d);
    }
    let held = live();
    peak_drive = peak_drive.max(peak() - snapshots);
    let last = d.clone();
    snapshots += live() - held;
    reset_peak();
    while d.y[0] < x0 + 1000.0 {
        d.millis(1000);
        stalled(&d);
    }
    let wall = start.elapsed().as_secs_f64();
    peak_drive = peak_drive.max(peak() - snapshots);
    let live_drive = live() - snapshots - before;
    let peak_drive = peak_drive - before;
    let map = d.ruts().unwrap();
    out.push(format!(
        "1 km at {FAST} m/s (x {x0:.2} → {:.1} m, {:.1} s simulated) in {wall:.1} s wall; rut map: \
         {} tiles, heap_bytes {:.2} MB; allocated by the drive: {:.2} MB live, {:.2} MB peak; \
         the process: {:.2} MB live (the two snapshots' {:.2} MB included) (target < 50 MB)",
        d.y[0],
        d.t,
        map.tile_count(),
        map.heap_bytes() as f64 / MB,
        live_drive as f64 / MB,
        peak_drive as f64 / MB,
        live() as f64 / MB,
        snapshots as f64 / MB,
    ));
    drop(d);
    let mut group = c.benchmark_group(GROUP);
    // Long runs: as many iterations in every sample.
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    let mut medians = Vec::new();
    for (id, from) in [("first_10m", &first), ("last_10m", &last)] {
        let tiles = from.ruts().unwrap().tile_count();
        let mut samples = Vec::new();
        group.bench_function(BenchmarkId::new("steps_10000", id), |b| {
            time_from(b, from, &mut samples, |d| d.millis(TEN_METRES))
        });
        medians.push(median_of_last(&samples, 10));
        let mut d = from.clone();
        let x = d.y[0];
        d.millis(TEN_METRES);
        out.push(format!(
            "{id}: from x = {x:.1} m ({tiles} tiles) to {:.1} m ({} tiles)",
            d.y[0],
            d.ruts().unwrap().tile_count()
        ));
    }
    group.finish();
    let pair = paired(&last, &first, 11, |d| d.millis(TEN_METRES));
    out.push(format!(
        "10,000 steps of 1 ms at {FAST} m/s: first 10 m {:.2} µs per step, last 10 m {:.2} µs, \
         ratio last/first {:.3} (paired {pair:.3}) (target ≤ 1.10)",
        1e6 * medians[0] / TEN_METRES as f64,
        1e6 * medians[1] / TEN_METRES as f64,
        medians[1] / medians[0],
    ));
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    let mut out = Vec::new();
    fixed_step(&mut c, &mut out);
    default_integrator(&mut c, &mut out);
    kilometre(&mut c, &mut out);
    c.final_summary();
    println!("\nRuts (MER on dry sand, {CELL} m cells):");
    for line in &out {
        println!("  {line}");
    }
}
