//! The paper's runs at the accuracy the user is promised: each scenario's
//! own integrator (BDF at its default tolerances) ends within 1 mm and 0.01° of a
//! tight-tolerance run of the same model, stored in
//! `tests/data/paper_final_states.toml` so that CI need not repeat it.

use std::collections::BTreeMap;
use std::path::Path;

use crate::support::run::{rover_of, run_in};

#[test]
fn the_paper_runs_end_within_a_millimetre_and_a_hundredth_of_a_degree_of_the_reference() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("tests/data/paper_final_states.toml")).unwrap();
    let references: BTreeMap<String, BTreeMap<String, f64>> = toml::from_str(&text).unwrap();
    assert_eq!(references.len(), 5, "Figs. 5, 8, 13, 15 and 16");
    let dir = root.join("scenarios");
    for (name, reference) in &references {
        let scenario = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
        let rover = rover_of(&scenario);
        let run = run_in(&rover, &scenario, &dir);
        assert!(run.summary.complete, "{name}: {:?}", run.summary.error);
        let value = |k: &str| run.final_value(k);
        assert_eq!(value("t"), reference["t"], "{name}: the run's end");
        let distance = ["X", "Y", "Z"]
            .map(|k| value(k) - reference[k])
            .iter()
            .map(|d| d * d)
            .sum::<f64>()
            .sqrt();
        // Measured: 5e-7 to 2.3e-4 m and 3e-5 to 1.2e-3° (Fig. 15 the largest).
        assert!(distance < 1e-3, "{name}: {distance} m from the reference");
        for k in ["phi", "theta", "psi"] {
            let d = (value(k) - reference[k]).to_degrees();
            assert!(d.abs() < 0.01, "{name}: {k} {d}° from the reference");
        }
    }
}
