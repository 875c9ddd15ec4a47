//! Every bad-input class gives its own located message (snapshots of the
//! whole rendered text).

use rover_spec::Description;

/// A small valid rover: two swing arms and a rocker, every field used.
const BASE: &str = r#"name = "toy"
gravity = 1.62

[body]
mass = 30.0
inertia = [0.7, 0.9, 1.5]

[wheel_defaults]
mass = 0.6
radius = 0.09
stiffness = 4000.0
damping = 300.0
mu_x = 0.5
mu_y = 0.5
cornering_stiffness = 50.0
max_torque = 1.29

[[suspension]]
name = "front"
kind = "longitudinal_swing_arm"
pivot = [0.18, 0.2, -0.01]
length = 0.2
coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 }
fit = { method = "taylor", terms = 5 }

[[suspension]]
name = "rear"
kind = "longitudinal_rocker"
pivot = [-0.2, 0.0, -0.01]
arms = [
    { name = "left", length = 0.25, angle_deg = 45.0 },
    { name = "right", length = 0.25, angle_deg = -45.0 },
]
coordinate = { min_deg = -30.0, max_deg = 30.0 }

[[wheel]]
name = "front"
suspension = "front"

[[wheel]]
name = "rear_left"
suspension = "rear"
point = "left"

[[wheel]]
name = "rear_right"
suspension = "rear"
point = "right"
"#;

/// The rendered error of loading `BASE` with `from` replaced by `to`.
fn bad(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "`{from}` is not in the base file");
    let text = BASE.replacen(from, to, 1);
    match rover_spec::load_str(&text, "toy.toml") {
        Ok(_) => panic!("`{to}` was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn base_is_valid() {
    let spec = rover_spec::load_str(BASE, "toy.toml").expect("valid");
    assert_eq!(spec.model.dof(), 8);
    assert_eq!(spec.wheel_names, ["front", "rear_left", "rear_right"]);
}

#[test]
fn malformed_toml() {
    insta::assert_snapshot!(bad("mass = 30.0", "mass = 30.0.0\nradius = = 2"));
}

#[test]
fn unknown_field_nested() {
    insta::assert_snapshot!(bad("{ min_deg = -30.0,", "{ minimum_deg = -30.0,"));
}

#[test]
fn unknown_field_in_suspension() {
    insta::assert_snapshot!(bad("length = 0.2\n", "length = 0.2\nlenght = 0.3\n"));
}

#[test]
fn unknown_kind() {
    insta::assert_snapshot!(bad("\"longitudinal_rocker\"", "\"longitudinal_rockr\""));
}

#[test]
fn missing_field() {
    insta::assert_snapshot!(bad("mass = 30.0\n", ""));
}

#[test]
fn wrong_type() {
    insta::assert_snapshot!(bad("gravity = 1.62", "gravity = \"moon\""));
}

#[test]
fn non_positive_mass() {
    insta::assert_snapshot!(bad("mass = 30.0", "mass = -30.0"));
}

#[test]
fn non_positive_radius() {
    insta::assert_snapshot!(bad(
        "point = \"left\"\n",
        "point = \"left\"\nradius = 0.0\n"
    ));
}

#[test]
fn inertia_not_positive_definite() {
    insta::assert_snapshot!(bad("[0.7, 0.9, 1.5]", "[0.7, -0.9, 1.5]"));
}

#[test]
fn inertia_full_not_positive_definite() {
    insta::assert_snapshot!(bad(
        "[0.7, 0.9, 1.5]",
        "[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.5]]"
    ));
}

#[test]
fn inertia_not_symmetric() {
    insta::assert_snapshot!(bad(
        "[0.7, 0.9, 1.5]",
        "[[0.7, 0.1, 0.0], [0.0, 0.9, 0.0], [0.0, 0.0, 1.5]]"
    ));
}

#[test]
fn inertia_triangle_inequality() {
    insta::assert_snapshot!(bad("[0.7, 0.9, 1.5]", "[0.7, 0.9, 2.5]"));
}

#[test]
fn wheel_refers_to_missing_suspension() {
    insta::assert_snapshot!(bad("suspension = \"front\"", "suspension = \"frnot\""));
}

#[test]
fn wheel_refers_to_missing_point() {
    insta::assert_snapshot!(bad("point = \"left\"", "point = \"middle\""));
}

#[test]
fn wheel_without_point_on_rocker() {
    insta::assert_snapshot!(bad("point = \"left\"\n", ""));
}

#[test]
fn two_wheels_on_one_point() {
    insta::assert_snapshot!(bad("point = \"right\"", "point = \"left\""));
}

#[test]
fn duplicate_names() {
    insta::assert_snapshot!(bad("name = \"rear_right\"", "name = \"rear_left\""));
}

#[test]
fn fit_error_over_tolerance() {
    insta::assert_snapshot!(bad(
        "fit = { method = \"taylor\", terms = 5 }",
        "fit = { method = \"taylor\", terms = 3, tolerance = 1e-4 }"
    ));
}

#[test]
fn nan_number() {
    insta::assert_snapshot!(bad("length = 0.2", "length = nan"));
}

#[test]
fn infinite_number() {
    insta::assert_snapshot!(bad("gravity = 1.62", "gravity = inf"));
}

#[test]
fn rest_outside_travel() {
    insta::assert_snapshot!(bad("rest_deg = -17.2", "rest_deg = 17.2"));
}

#[test]
fn empty_travel() {
    insta::assert_snapshot!(bad(
        "min_deg = -30.0, max_deg = 30.0",
        "min_deg = 30.0, max_deg = -30.0"
    ));
}

#[test]
fn missing_travel_limit() {
    insta::assert_snapshot!(bad(
        "{ min_deg = -30.0, max_deg = 30.0 }",
        "{ min_deg = -30.0 }"
    ));
}

#[test]
fn radians_and_degrees_both() {
    insta::assert_snapshot!(bad("{ min_deg = -30.0,", "{ min = -0.5, min_deg = -30.0,"));
}

#[test]
fn wheel_field_missing_everywhere() {
    insta::assert_snapshot!(bad("radius = 0.09\n", ""));
}

#[test]
fn too_many_terms() {
    insta::assert_snapshot!(bad("terms = 5", "terms = 20"));
}

#[test]
fn spring_table_not_through_zero() {
    insta::assert_snapshot!(bad(
        "stiffness = 5.0,",
        "spring_table = { deflection_deg = [-10.0, 5.0, 20.0], force = [1.0, -0.5, -3.0] },"
    ));
}

#[test]
fn wishbone_cannot_cover_range() {
    let wishbone = r#"[[suspension]]
name = "corner"
kind = "double_wishbone"
x = 1.0
lower_pivot = [0.45, -0.25]
lower_length = 0.36
upper_pivot = [0.45, -0.05]
upper_length = 0.32
upright_length = 0.22
wheel_offset = [0.075, 0.121]
coordinate = { min_deg = -70.0, max_deg = 20.0 }

[[suspension]]
name = "rear""#;
    insta::assert_snapshot!(bad("[[suspension]]\nname = \"rear\"", wishbone));
}

#[test]
fn several_errors_in_file_order() {
    let text = BASE
        .replacen("mass = 30.0", "mass = 0.0", 1)
        .replacen("length = 0.2", "length = -0.2", 1)
        .replacen("point = \"right\"", "point = \"centre\"", 1);
    let e = rover_spec::load_str(&text, "toy.toml").unwrap_err();
    let lines: Vec<usize> = e
        .diagnostics
        .iter()
        .map(|d| text[..d.span.clone().unwrap().start].lines().count())
        .collect();
    assert_eq!(lines.len(), 3);
    assert!(lines.windows(2).all(|w| w[0] < w[1]), "{lines:?}");
    insta::assert_snapshot!(e.to_string());
}

#[test]
fn rust_built_description_errors_name_the_path() {
    let mut desc: Description = rover_spec::parse_str(BASE, "toy.toml").unwrap();
    desc.wheels[1].radius = Some(-0.1);
    let e = rover_spec::from_description(&desc, "<rust>").unwrap_err();
    insta::assert_snapshot!(e.to_string());
}

#[test]
fn unreadable_file() {
    let e = rover_spec::load_file(std::path::Path::new("/nonexistent/rover.toml")).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("error: /nonexistent/rover.toml: cannot read the file:"),
        "{e}"
    );
}

#[test]
fn missing_field_in_suspension() {
    insta::assert_snapshot!(bad("length = 0.2\n", ""));
}

#[test]
fn wrong_type_in_suspension() {
    insta::assert_snapshot!(bad("length = 0.2", "length = \"short\""));
}

/// The `file:line:col` the first diagnostic of loading `text` points at.
fn location(text: &str) -> String {
    let e = rover_spec::load_str(text, "toy.toml").unwrap_err();
    let rendered = e.to_string();
    let at = rendered
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("--> "))
        .unwrap_or_else(|| panic!("no location in {rendered}"));
    at.to_string()
}

#[test]
fn inertia_rows_of_other_than_three_numbers() {
    for (matrix, row) in [
        (
            "[[0.7, 0.0, 0.0, 0.0], [0.0, 0.9, 0.0, 0.0], [0.0, 0.0, 1.5, 0.0]]",
            "4 numbers",
        ),
        (
            "[[0.7, 0.0, 0.0], [0.0, 0.9, 0.0, 0.0, 0.0], [0.0, 0.0, 1.5]]",
            "5 numbers",
        ),
        ("[[0.7, 0.0], [0.0, 0.9], [0.0, 0.0]]", "2 numbers"),
    ] {
        let e = bad("[0.7, 0.9, 1.5]", matrix);
        assert!(e.contains("body.inertia[") && e.contains(row), "{e}");
    }
    let e = bad(
        "[0.7, 0.9, 1.5]",
        "[[0.7, 0.0, 0.0], [0.0, 0.9, 0.0], [0.0, 0.0, 1.5], [0.0, 0.0, 0.0]]",
    );
    assert!(e.contains("more than 3 rows"), "{e}");
    insta::assert_snapshot!(bad(
        "[0.7, 0.9, 1.5]",
        "[[0.7, 0.0, 0.0], [0.0, 0.9, 0.0, 0.0, 0.0], [0.0, 0.0, 1.5]]"
    ));
}

#[test]
fn spring_neutral_outside_the_travel() {
    insta::assert_snapshot!(bad(
        "rest_deg = -17.2,",
        "rest_deg = -17.2, neutral_deg = 1e6,"
    ));
    let e = bad(
        "rest_deg = -17.2,",
        "rest_deg = -17.2, neutral_deg = -61.0,",
    );
    assert!(
        e.contains("neutral_deg") && e.contains("[-60°, -2°]"),
        "{e}"
    );
    // At a limit it is still inside.
    let text = BASE.replacen(
        "rest_deg = -17.2,",
        "rest_deg = -17.2, neutral_deg = -2.0,",
        1,
    );
    rover_spec::load_str(&text, "toy.toml").unwrap();
}

#[test]
fn empty_names() {
    insta::assert_snapshot!(bad("name = \"rear_left\"", "name = \"\""));
    for (from, to, path) in [
        (
            "name = \"front\"\nkind",
            "name = \" \"\nkind",
            "suspension[0].name",
        ),
        (
            "{ name = \"left\",",
            "{ name = \"\",",
            "suspension[1].arms[0].name",
        ),
        (
            "{ min_deg = -30.0,",
            "{ name = \"\", min_deg = -30.0,",
            "suspension[1].coordinate.name",
        ),
    ] {
        let e = bad(from, to);
        assert!(e.contains(&format!("{path}: the name")), "{e}");
    }
}

#[test]
fn names_with_control_characters() {
    let e = bad("name = \"rear_left\"", "name = \"\\u001b[2J\"");
    assert!(!e.contains('\u{1b}'), "{e:?}");
    assert!(e.contains(r#""\u{1b}[2J""#), "{e}");
    insta::assert_snapshot!(e);
    // Anywhere a string is written, a reference included; the bidirectional
    // overrides too.
    let e = bad("suspension = \"front\"", "suspension = \"fr\\u202eont\"");
    assert!(
        e.contains("wheel[0].suspension") && e.contains("U+202E"),
        "{e}"
    );
    assert!(!e.contains('\u{202e}'), "{e:?}");
    let e = bad("name = \"toy\"", "name = \"toy\\u0007\"");
    assert!(e.contains("error: name:") && e.contains("U+0007"), "{e}");
}

#[test]
fn raw_control_characters_in_the_source_are_not_echoed() {
    let text = BASE.replacen("gravity = 1.62", "gravity = 1.62 # \u{1b}[2J", 1);
    let e = rover_spec::load_str(&text, "toy.toml")
        .unwrap_err()
        .to_string();
    assert!(!e.contains('\u{1b}'), "{e:?}");
}

#[test]
fn overlapping_wheels() {
    // The rocker's wheels are 0.35 m apart: radii of 0.09 m and 0.3 m overlap.
    let e = bad("point = \"right\"\n", "point = \"right\"\nradius = 0.3\n");
    assert!(
        e.contains("wheel[2].radius") && e.contains("overlap"),
        "{e}"
    );
    insta::assert_snapshot!(bad("radius = 0.09", "radius = 50.0"));
}

#[test]
fn wheels_larger_than_the_rover() {
    // The front wheel clears the rocker's across, but is larger than the
    // rover (0.62 m between its wheel centres farthest apart).
    let e = bad(
        "suspension = \"front\"\n",
        "suspension = \"front\"\nradius = 5.0\n",
    );
    assert!(
        e.contains("wheel[0].radius") && e.contains("more than the rover's size"),
        "{e}"
    );
}

#[test]
fn value_errors_point_at_the_value() {
    let cases = [
        ("gravity = 1.62", "gravity = \"moon\"", "toy.toml:2:11"),
        ("length = 0.2", "length = \"short\"", "toy.toml:22:10"),
        ("terms = 5 }", "terms = -5 }", "toy.toml:24:36"),
        ("stiffness = 5.0,", "stiffness = \"5\",", "toy.toml:23:79"),
        ("max_torque = 1.29", "max_torque = [1.29]", "toy.toml:16:14"),
        (
            "{ name = \"right\", length = 0.25,",
            "{ name = \"right\", length = true,",
            "toy.toml:32:32",
        ),
    ];
    for (from, to, at) in cases {
        assert!(BASE.contains(from), "{from}");
        let text = BASE.replacen(from, to, 1);
        assert_eq!(location(&text), at, "{to}");
    }
}

#[test]
fn nesting_too_deep_is_located() {
    let deep = format!(
        "name = \"toy\"\ngravity = {}1.62{}\n",
        "[".repeat(10_000),
        "]".repeat(10_000)
    );
    let e = rover_spec::load_str(&deep, "toy.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("nesting deeper than 80 levels"), "{e}");
    assert!(e.contains("--> toy.toml:2:"), "{e}");
    let deep = format!(
        "name = \"toy\"\nbody = {}1{}\n",
        "{ a = ".repeat(10_000),
        " }".repeat(10_000)
    );
    let e = rover_spec::load_str(&deep, "toy.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("nesting deeper") && e.contains("--> toy.toml:2:"),
        "{e}"
    );
    // A dotted key of too many parts: the parser gives no place; the key's line.
    let deep = format!("name = \"toy\"\n\n{} = 1\n", vec!["a"; 100].join("."));
    assert_eq!(location(&deep), "toy.toml:3:1");
    let e = rover_spec::load_str(&deep, "toy.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("nesting deeper"), "{e}");
}

#[test]
fn a_motor_line_without_a_positive_no_load_speed_is_refused_with_the_fix() {
    let e = bad(
        "max_torque = 1.29",
        "max_torque = 1.29\nno_load_speed = 0.0",
    );
    assert!(e.contains("no_load_speed"), "{e}");
    assert!(e.contains("rad/s and positive"), "{e}");
    let e = bad("max_torque = 1.29", "max_torque = 1.29\nstall_torque = 2.0");
    assert!(e.contains("wheel_defaults.stall_torque"), "{e}");
    assert!(e.contains("add `no_load_speed`"), "{e}");
}
