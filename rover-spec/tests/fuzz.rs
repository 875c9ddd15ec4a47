//! No input makes the loader panic: mutated model files (bytes deleted,
//! inserted, numbers or strings replaced with hostile literals) give a
//! `Result`, and no error prints a control character.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

const HOSTILE: &[&str] = &[
    "nan",
    "-inf",
    "inf",
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-320",
    "\"x\"",
    "[]",
    "[1, 2]",
    "{}",
    "[[1], [2], [3]]",
    "true",
    "99999999999999999999",
    "-1",
    "=",
    "[",
    "\"",
    "0.0001",
    "1e6",
    "-1e12",
    "50.0",
    "\"\"",
    "\"\\u001b[2J\"",
    "\"\\u202e\"",
    "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]",
    "[[1, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1]]",
    "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]",
];

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
        let numbers: Vec<(usize, usize)> = {
            let b = text.as_bytes();
            let mut out = Vec::new();
            let mut i = 0;
            while i < b.len() {
                if b[i].is_ascii_digit() {
                    let start = i;
                    while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                        i += 1;
                    }
                    out.push((start, i));
                }
                i += 1;
            }
            out
        };
        let (a, b) = numbers[which % numbers.len()];
        let mutated = format!("{}{}{}", &text[..a], HOSTILE[hostile], &text[b..]);
        survives(&mutated);
    }

    #[test]
    fn replacing_a_string_never_panics(model in 0usize..4, which in 0usize..200, hostile in 0usize..HOSTILE.len()) {
        let text = rover_models::builtin(rover_models::NAMES[model]).unwrap();
        // Each quoted string outside comments: its bytes, quotes included.
        let mut strings = Vec::new();
        let mut offset = 0;
        for line in text.split_inclusive('\n') {
            let code = line.split('#').next().unwrap_or("");
            let quotes: Vec<usize> = code.match_indices('"').map(|(i, _)| offset + i).collect();
            strings.extend(quotes.chunks_exact(2).map(|q| (q[0], q[1] + 1)));
            offset += line.len();
        }
        let (a, b) = strings[which % strings.len()];
        let mutated = format!("{}{}{}", &text[..a], HOSTILE[hostile], &text[b..]);
        survives(&mutated);
    }

    #[test]
    fn deleting_or_inserting_bytes_never_panics(model in 0usize..4, at in 0usize..5000, len in 0usize..40, insert in "[ -~\n]{0,12}") {
        let text = rover_models::builtin(rover_models::NAMES[model]).unwrap();
        let mut start = at % text.len();
        while !text.is_char_boundary(start) {
            start -= 1;
        }
        let mut end = (start + len).min(text.len());
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        let mutated = format!("{}{}{}", &text[..start], insert, &text[end..]);
        survives(&mutated);
    }
}
