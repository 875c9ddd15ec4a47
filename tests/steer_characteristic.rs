//! Fig. 7's dependence on the steer characteristic (docs/REPRODUCTION.md):
//! on flat ground an understeering variant of Example 1 turns wider as it
//! goes faster, an oversteering one tighter, as the single-track model of
//! each variant says: the same radius within 1 % at walking speed and at
//! 0.5 m/s, the same trend within 30 %.

use rover::cli::steer::{VARIANTS, measure, single_track_ratio};

#[test]
fn understeer_widens_the_turn_with_speed_and_oversteer_tightens_it() {
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
        // Each radius as the single-track model's (measured: within 0.6 %).
        for (got, model) in row {
            let (Some(got), Some(model)) = (got, model) else {
                panic!("no radius: {row:?}");
            };
            assert!((got - model).abs() < 0.01, "{row:?}");
        }
        // The trend in speed: same sign and size (measured: 14–17 % apart).
        let got = fast - slow;
        let ratio = got / want;
        assert!(
            (0.7..1.3).contains(&ratio),
            "simulated {got}, single-track {want}"
        );
    }
}
