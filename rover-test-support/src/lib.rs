//! Helpers shared by the tests of `rover-dynamics`, `rover-runtime` and the
//! workspace: a seeded generator ([`rng::Rng`]), the paper's two rovers
//! built by hand ([`hand_models`]), a norm-wise relative difference
//! ([`rel`]), scratch files ([`scratch_file`]) and mutations of valid
//! inputs for fuzzing ([`mutate`]). Only tests depend on it.

pub mod hand_models;
pub mod mutate;
pub mod rng;

/// Largest |a − b| over the largest |a|, |b| (0 when both are 0): a
/// norm-wise relative difference.
pub fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().chain(b).fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if scale == 0.0 { diff } else { diff / scale }
}

/// A file of `text` named `name` in the scratch folder `folder` under
/// `tmp_dir` (a test target's `env!("CARGO_TARGET_TMPDIR")`, which cargo
/// sets only when it compiles the test itself); its absolute path.
pub fn scratch_file(tmp_dir: &str, folder: &str, name: &str, text: &str) -> String {
    let dir = std::path::Path::new(tmp_dir).join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// The `[[suspension]]` and `[[wheel]]` tables of a four-wheeled test rover
/// (swing4's layout: a longitudinal swing arm per wheel, front arms
/// trailing and rear arms leading), to follow a description's `[body]` and
/// `[wheel_defaults]`.
pub fn swing_arm_quad_tables() -> String {
    let mut s = String::new();
    for (name, x, y, rest, min, max) in [
        ("fl", 0.18, 0.2, -17.2, -60.0, -2.0),
        ("fr", 0.18, -0.2, -17.2, -60.0, -2.0),
        ("rl", -0.22, 0.2, 17.2, 2.0, 60.0),
        ("rr", -0.22, -0.2, 17.2, 2.0, 60.0),
    ] {
        s += &format!(
            "[[suspension]]\nname = \"{name}\"\nkind = \"longitudinal_swing_arm\"\n\
             pivot = [{x:?}, {y:?}, -0.01]\nlength = 0.2\n\
             coordinate = {{ rest_deg = {rest:?}, min_deg = {min:?}, max_deg = {max:?}, stiffness = 15.0, damping = 3.5 }}\n"
        );
    }
    for name in ["fl", "fr", "rl", "rr"] {
        s += &format!("[[wheel]]\nname = \"{name}\"\nsuspension = \"{name}\"\n");
    }
    s
}
