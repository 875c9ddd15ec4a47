//! Shared helpers of the integration tests: running scenarios ([`run`]),
//! and the helpers the crates' tests share (`rover-test-support`).

pub mod run;

pub use rover_test_support::{rel, rng};

/// A file of `text` named `name` in the scratch folder `folder` of the
/// tests; its absolute path.
pub fn scratch_file(folder: &str, name: &str, text: &str) -> String {
    rover_test_support::scratch_file(env!("CARGO_TARGET_TMPDIR"), folder, name, text)
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
