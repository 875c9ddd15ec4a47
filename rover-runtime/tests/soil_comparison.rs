//! The single-wheel testbed against published numbers (docs/SOIL.md,
//! "Compared with published measurements"); the soils are the files in
//! docs/soil/compare/, each number in them sourced there.
//! Each tolerance is the largest difference seen when the comparison was
//! made, plus a stated margin.

use rover_runtime::soil::{SoilConfig, WheelTestPoint, wheel_test};

/// The testbed's steady states for a soil file of docs/soil/compare/.
fn testbed(file: &str, radius: f64, width: f64, load: f64, slips: &[f64]) -> Vec<WheelTestPoint> {
    let path = format!("{}/../docs/soil/compare/{file}", env!("CARGO_MANIFEST_DIR"));
    let soil = SoilConfig::named_or_file(&path)
        .and_then(|c| c.soil())
        .unwrap_or_else(|e| panic!("{path}: {e}"));
    wheel_test(&soil, radius, width, load, slips, 0.0).unwrap()
}

/// Published model numbers: N. Mizukami, T. Yoshimitsu, T. Kubota,
/// "Proposal of Terramechanics-Based Wheel Model for Dynamic Sinkage",
/// Trans. JSME Series C 78(788), 2012, pp. 1109-1118. The classical
/// (Wong-Reece, Janosi-Hanamoto) model of a rigid wheel, r = b = 0.1 m,
/// mass 6.5 kg (Table 2), on the Tohoku regolith simulant (Table 1, k_phi
/// read as 814000, see the soil file):
/// - Fig. 6, drawbar pull at slips 0, 0.1, ..., 0.9 (the vertices of the
///   plotted polyline, read from the PDF's vector drawing to < 0.01 N);
/// - section 3.3 and 4.1: steady sinkage 0.0238 m where the pull is zero,
///   at slip 0.29.
///
/// Seen: at most 0.115 N apart (s = 0.9), sinkage 0.02381 m at s = 0.29,
/// zero pull at s = 0.288. Tolerances: 0.25 N (0.115 + 0.135 margin, 0.4 %
/// of the load); 1e-4 m (the published value's last digit); the zero
/// crossing between slips 0.28 and 0.30.
#[test]
fn the_classical_model_of_mizukami_2012_on_regolith_simulant() {
    const FILE: &str = "tohoku_regolith_simulant_2012.toml";
    let load = 6.5 * 9.81;
    let fig6 = [
        (0.0, -12.165),
        (0.1, -7.116),
        (0.2, -3.031),
        (0.3, 0.300),
        (0.4, 3.020),
        (0.5, 5.254),
        (0.6, 7.075),
        (0.7, 8.575),
        (0.8, 9.785),
        (0.9, 10.767),
    ];
    let slips: Vec<f64> = fig6.iter().map(|p| p.0).collect();
    for (p, (s, published)) in testbed(FILE, 0.1, 0.1, load, &slips).iter().zip(fig6) {
        assert!(
            (p.drawbar_pull - published).abs() <= 0.25,
            "s = {s}: DP {} N, published {published} N",
            p.drawbar_pull
        );
    }
    let at = testbed(FILE, 0.1, 0.1, load, &[0.28, 0.29, 0.30]);
    assert!(
        (at[1].sinkage - 0.0238).abs() <= 1e-4,
        "sinkage {}",
        at[1].sinkage
    );
    assert!(
        at[0].drawbar_pull < 0.0 && at[2].drawbar_pull > 0.0,
        "the pull changes sign between s = 0.28 and 0.30: {} N, {} N",
        at[0].drawbar_pull,
        at[2].drawbar_pull
    );
}
