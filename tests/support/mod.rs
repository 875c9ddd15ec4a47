//! Shared helpers of the integration tests: running scenarios ([`run`]),
//! and the helpers the crates' tests share (`rover-test-support`).

pub mod run;

pub use rover_test_support::{rel, rng};

/// A file of `text` named `name` in the scratch folder `folder` of the
/// tests; its absolute path.
pub fn scratch_file(folder: &str, name: &str, text: &str) -> String {
    rover_test_support::scratch_file(env!("CARGO_TARGET_TMPDIR"), folder, name, text)
}

/// Run the shipped `scenario` (loaded from `path`) on `plant`, CSV to a
/// sink, as `rover simulate` would; panics naming the file on a setup error.
pub fn simulate_shipped<P: rover_dynamics::plant::Plant>(
    plant: P,
    scenario: &rover_scenario::scenario::Scenario,
    path: &std::path::Path,
) -> rover_scenario::output::Summary {
    let rover = scenario
        .rover
        .clone()
        .expect("a shipped scenario names its rover");
    let spec = rover_spec::load_str(rover_models::builtin(&rover).unwrap(), &rover).unwrap();
    rover_scenario::simulate::simulate(
        plant,
        &spec.model,
        &rover,
        scenario,
        path.parent().unwrap(),
        std::io::sink(),
        &std::sync::atomic::AtomicBool::new(false),
        |_| {},
    )
    .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The scenario files shipped in `scenarios/`, sorted.
pub fn shipped_scenarios() -> Vec<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    names
}
