//! The wheel force laws (MODEL.md §7) in whole runs: rolling resistance.

/// Rolling resistance, closed forms in whole runs of ExoMars on the Moon.
/// Coasting on flat ground from 0.3 m/s with the motors off, every patch
/// carries `F_d = −C_rr·F_n` (the regularized sign is 1 to 1e-4 above 0.07 m/s) and the rover decelerates at `C_rr·g`; parked on a 10° slope
/// below its rolling-resistance angle it creeps down at the speed where the
/// regularized sign balances the slope, `v = v_ε·s/sqrt(1 − s²)` with
/// `s = tan α/C_rr`, where without rolling resistance it rolls away.
#[test]
fn rolling_resistance_decelerates_at_c_rr_g_and_holds_on_a_slope() {
    use crate::support::run::run;
    let c_rr = 0.1;
    let coast = run(
        "exomars",
        &format!(
            "duration = 2.0\noutput_rate = 50.0\n[initial]\nvelocity = [0.3, 0.0, 0.0]\n\
             [contact]\nrolling_resistance = {c_rr}\n"
        ),
    );
    let g = 1.62;
    let (t, vx) = (coast.col("t"), coast.col("vx"));
    // After the landing transient: the deceleration over 0.6–1.4 s.
    let at = |time: f64| t.iter().position(|&s| s >= time).unwrap();
    let (i, j) = (at(0.6), at(1.4));
    let decel = (vx[i] - vx[j]) / (t[j] - t[i]);
    assert!(
        (decel - c_rr * g).abs() < 0.02 * c_rr * g,
        "deceleration {decel} m/s² vs C_rr·g = {}",
        c_rr * g
    );
    // While it still rolls at ≥ 0.07 m/s (it stops at 1.85 s).
    for w in 1..=6 {
        let (fd, fn_) = (coast.col(&format!("Fd{w}")), coast.col(&format!("Fn{w}")));
        for k in i..j {
            assert!(vx[k] > 0.07);
            assert!(
                (fd[k] + c_rr * fn_[k]).abs() < 1e-3 * fn_[k],
                "wheel {w} at {} s: F_d {} vs −C_rr·F_n {}",
                t[k],
                fd[k],
                -c_rr * fn_[k]
            );
        }
    }

    let parked = |c: f64| {
        run(
            "exomars",
            &format!(
                "duration = 20.0\noutput_rate = 10.0\n[terrain]\nkind = \"slope\"\nangle_deg = 10.0\n\
                 [contact]\nrolling_resistance = {c}\n"
            ),
        )
    };
    let held = parked(0.3);
    let s = 10f64.to_radians().tan() / 0.3;
    let creep = rover_dynamics::wheel_law::ROLLING_V_EPS * s / (1.0 - s * s).sqrt();
    for v in held.after("vx", 10.0) {
        assert!(
            (v + creep).abs() < 0.02 * creep,
            "creep {v} m/s vs −{creep}"
        );
    }
    let free = parked(0.0);
    let rolled = free.col("X");
    assert!(
        rolled[rolled.len() - 1] < -1.0,
        "without rolling resistance the parked rover rolls away: X = {}",
        rolled[rolled.len() - 1]
    );
}
