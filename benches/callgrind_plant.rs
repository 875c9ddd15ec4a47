//! The callgrind driver of the force path: each built-in rover's
//! generated `derivatives_on_ground` on the paper's rough terrain, at the
//! 200 states 1 ms apart of the `force_path_<rover>` benches of
//! `benches/plant.rs`, evaluated in turn, `passes` times over. The
//! evaluations run inside [`measured`], which callgrind's
//! `--toggle-collect` isolates from the setup (building the terrain,
//! driving 5 s to the path's start, one pass over the path that fills the
//! terrain's lazily computed bounds), so the instruction count divided by
//! the number of evaluations is one evaluation's, on any machine.
//! `scripts/callgrind-plant` runs it under valgrind and prints the counts.
//!
//! `cargo bench --bench callgrind_plant -- [rover|all] [passes]`: run
//! natively it only prints what it evaluated (a check that it works).

mod support;

use std::hint::black_box;

use rover_dynamics::wheel_ground::Search;
use rover_runtime::GenericPlant;
use rover_runtime::terrain::Terrain;
use rover_runtime::wheel_law::WheelLawConfig;
use support::{driven, model, path_from};

/// `evaluate` at `states` in turn, `passes` times over: the function
/// whose instructions callgrind counts. Returns a sum of the derivatives,
/// so that nothing is optimized away.
#[inline(never)]
fn measured<const N: usize>(
    states: &[([f64; N], [f64; N])],
    passes: usize,
    mut evaluate: impl FnMut(&[f64; N], &[f64; N], &mut [f64; N], &mut [f64; N]),
) -> f64 {
    let mut sum = 0.0;
    for _ in 0..passes {
        for (x, w) in states {
            let (mut xd, mut wd) = ([0.0; N], [0.0; N]);
            evaluate(black_box(x), w, &mut xd, &mut wd);
            sum += xd[0] + wd[N - 1];
        }
    }
    sum
}

macro_rules! one {
    ($name:literal, $plant:ty, $passes:expr) => {{
        type P = $plant;
        const N: usize = P::DOF;
        const W: usize = P::WHEELS;
        let model = model($name);
        let grid = support::rough_field();
        let rough = Terrain::Grid(grid.clone());
        let generic = GenericPlant::new(model.clone()).unwrap();
        let state = driven(&rough, &model, generic.clone(), 5.0);
        let path = path_from(&rough, &model, generic, &state, 200);
        let states: Vec<([f64; N], [f64; N])> = path
            .iter()
            .map(|y| (y[..N].try_into().unwrap(), y[N..2 * N].try_into().unwrap()))
            .collect();
        let plant = P::new();
        let mut ground = P::ground(Search::default());
        let torques = [0.1 * model.wheels[0].max_torque; W];
        let law = WheelLawConfig::default();
        let mut evaluate = |x: &[f64; N], w: &[f64; N], xd: &mut [f64; N], wd: &mut [f64; N]| {
            plant
                .derivatives_on_ground(
                    &mut ground,
                    &grid,
                    &law,
                    &P::TYRES,
                    x,
                    w,
                    &[0.0; W],
                    |_| torques,
                    xd,
                    wd,
                )
                .unwrap()
        };
        // One pass outside the count: the terrain's bounds under the path
        // are computed where the search first asks for them, once a run
        // (as criterion's warm-up does before it times).
        for (x, w) in &states {
            evaluate(x, w, &mut [0.0; N], &mut [0.0; N]);
        }
        let sum = measured(&states, $passes, &mut evaluate);
        println!(
            "{}: {} evaluations (checksum {sum:.6e})",
            $name,
            $passes * states.len()
        );
    }};
}

fn main() {
    // Criterion's `--bench` and any other flag are ignored.
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let which = args.first().map_or("all", String::as_str);
    let passes: usize = args.get(1).and_then(|p| p.parse().ok()).unwrap_or(5);
    let all = which == "all";
    if all || which == "swing4" {
        one!("swing4", rover_models::Swing4, passes);
    }
    if all || which == "exomars" {
        one!("exomars", rover_models::Exomars, passes);
    }
    if all || which == "mer" {
        one!("mer", rover_models::Mer, passes);
    }
    if all || which == "lrv" {
        one!("lrv", rover_models::Lrv, passes);
    }
}
