//! No input makes the loader panic: mutated model files (bytes deleted,
//! inserted, numbers or strings replaced with hostile literals) give a
//! `Result`, and no error prints a control character.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use rover_test_support::mutate::{HOSTILE, replace_number, replace_string, splice};

fn config() -> Config {
    Config {
        cases: 500,
        rng_seed: RngSeed::Fixed(2012),
        failure_persistence: None,
        ..Config::default()
    }
}

/// Load, and render the error if any: neither may panic, and an error
/// renders to a located, non-empty text.
fn survives(text: &str) {
    match rover_spec::load_str(text, "fuzz.toml") {
        Ok(spec) => {
            let _ = rover_spec::report::check_report(&spec);
            assert!(
                spec.model
                    .coordinates
                    .iter()
                    .all(|c| c.rest.is_finite() && c.stop_damping.is_finite())
            );
        }
        Err(e) => {
            let e = e.to_string();
            assert!(e.starts_with("error"));
            assert!(!e.chars().any(|c| c.is_control() && c != '\n'), "{e:?}");
        }
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn replacing_a_number_never_panics(model in 0usize..4, which in 0usize..400, hostile in 0usize..HOSTILE.len()) {
        let text = rover_models::builtin(rover_models::NAMES[model]).unwrap();
        survives(&replace_number(text, which, hostile));
    }

    #[test]
    fn replacing_a_string_never_panics(model in 0usize..4, which in 0usize..200, hostile in 0usize..HOSTILE.len()) {
        let text = rover_models::builtin(rover_models::NAMES[model]).unwrap();
        survives(&replace_string(text, which, hostile));
    }

    #[test]
    fn deleting_or_inserting_bytes_never_panics(model in 0usize..4, at in 0usize..5000, len in 0usize..40, insert in "[ -~\n]{0,12}") {
        let text = rover_models::builtin(rover_models::NAMES[model]).unwrap();
        survives(&splice(text, at, len, &insert));
    }
}
