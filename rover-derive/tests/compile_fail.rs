//! Bad descriptions are compile errors with our messages, one mistake per
//! file, each message checked in as a `.stderr` file so that a change shows
//! up as a reviewed diff (CONTRIBUTING.md, "Golden files and snapshots").
//! `TRYBUILD=overwrite cargo test -p rover-derive` rewrites the `.stderr`
//! files; review and commit them on their own.
//!
//! trybuild compiles each file in its own project under
//! `target/tests/trybuild/rover-derive/`, which is then the
//! `CARGO_MANIFEST_DIR` the derive resolves `file = "…"` against: the
//! files name the TOML files by `../../../../rover-derive/tests/ui/…`
//! (the default target directory; the test says so when it is elsewhere).
//!
//! Each case then uses every item of the rover (`uses/use_all.rs`), as a
//! user's code does, so that its `.stderr` holds the description's error
//! and no error of the code that uses the rover.

use std::path::Path;

#[test]
fn bad_descriptions_fail_to_compile_and_good_ones_run() {
    // The cases' `../../../../` reaches the workspace only from trybuild's
    // project under the workspace's own target directory.
    let target = Path::new(env!("CARGO_TARGET_TMPDIR")).parent().unwrap();
    let project = target.join("tests/trybuild/rover-derive");
    std::fs::create_dir_all(&project).unwrap();
    let fixture = project.join("../../../../rover-derive/tests/ui/good.toml");
    assert!(
        fixture.exists(),
        "the cases name their TOML files relative to trybuild's project in the workspace's \
         target directory, and {} is elsewhere: run these tests with CARGO_TARGET_DIR unset \
         (or set to the workspace's `target`)",
        target.display()
    );
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
    // The same rover from a file and inline, both compiled and run.
    t.pass("tests/pass/*.rs");
}

/// One mistake, one error: every `.stderr` holds exactly one `error`, and
/// none from rustc (an `error[E…]` would be code that uses the rover
/// failing because of the stub, not the description).
#[test]
fn each_mistake_is_exactly_one_error() {
    let mut cases = 0;
    for entry in std::fs::read_dir("tests/ui").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "stderr") {
            let text = std::fs::read_to_string(&path).unwrap();
            let errors = text.lines().filter(|l| l.starts_with("error")).count();
            assert_eq!(errors, 1, "{}:\n{text}", path.display());
            assert!(!text.contains("error["), "{}:\n{text}", path.display());
            cases += 1;
        }
    }
    assert!(cases >= 13, "{cases} cases");
}

/// `uses/use_all.rs` uses every item a generated plant has
/// (`rover_codegen::Item::ALL`): a constant as `$plant::NAME`, a method as
/// `.name(` or `$plant::name(`, a trait impl as a bound `P: Trait`. With
/// it, the cases above hold the stub and a real plant to every item.
#[test]
fn use_all_uses_every_listed_item() {
    use rover_codegen::items::{Item, Kind};
    let uses = std::fs::read_to_string("tests/uses/use_all.rs").unwrap();
    let missing: Vec<&str> = Item::ALL
        .iter()
        .filter(|item| {
            let name = item.name();
            let forms = match item.kind() {
                Kind::Const => vec![format!("$plant::{name}")],
                Kind::Method => vec![format!(".{name}("), format!("$plant::{name}(")],
                Kind::Impl => vec![format!("P: {name}")],
            };
            !forms.iter().any(|form| uses.contains(form.as_str()))
        })
        .map(|item| item.name())
        .collect();
    assert!(
        missing.is_empty(),
        "not used in uses/use_all.rs: {missing:?}"
    );
}
