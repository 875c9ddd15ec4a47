//! Fig. 7's dependence on the steer characteristic (docs/REPRODUCTION.md):
//! on flat ground an understeering variant of Example 1 turns wider as it
//! goes faster, an oversteering one tighter, as the single-track model of
//! each variant says, in sign and order of magnitude.

use rover::cli::steer::{VARIANTS, measure, single_track_ratio};

#[test]
fn understeer_widens_the_turn_with_speed_and_oversteer_tightens_it() {
    for v in &VARIANTS {
        let model = v.single_track().unwrap();
        let ratios: Vec<String> = [0.05, 0.1, 0.2, 0.5, 1.0]
            .iter()
            .map(|&s| format!("{:.4}", single_track_ratio(&model, s).unwrap()))
            .collect();
        eprintln!("single-track {}: {}", v.name, ratios.join(" "));
    }
    // The single-track model's trend in speed, for the variants tested.
    let trend = |k: usize| {
        let m = VARIANTS[k].single_track().unwrap();
        single_track_ratio(&m, 0.5).unwrap() - single_track_ratio(&m, 0.05).unwrap()
    };
    let (under, over) = (2, 1);
    assert!(
        trend(under) > 0.0 && trend(over) < 0.0,
        "{} {}",
        trend(under),
        trend(over)
    );
    let dir = std::env::temp_dir().join(format!("rover-steer-{}", std::process::id()));
    let speeds = [0.05, 0.5];
    let rows = measure(&dir, &[VARIANTS[under], VARIANTS[over]], &speeds).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    for (row, want) in rows.iter().zip([trend(under), trend(over)]) {
        let [(Some(slow), _), (Some(fast), _)] = row[..] else {
            panic!("a run did not complete: {row:?}");
        };
        let got = fast - slow;
        eprintln!("{row:?}: simulated {got:.4}, single-track {want:.4}");
        // Same sign, within a factor of three.
        assert!(got * want > 0.0, "simulated {got}, single-track {want}");
        let ratio = got / want;
        assert!(
            (1.0 / 3.0..3.0).contains(&ratio),
            "simulated {got}, single-track {want}"
        );
    }
}
