//! Bad descriptions are compile errors with our messages, one mistake per
//! file (STYLE.md §6). `TRYBUILD=overwrite cargo test -p rover-derive`
//! rewrites the `.stderr` files; review and commit them on their own.
//!
//! trybuild compiles each file in its own project under
//! `target/tests/trybuild/rover-derive/`, which is then the
//! `CARGO_MANIFEST_DIR` the derive resolves `file = "…"` against: the
//! files name the TOML files by `../../../../rover-derive/tests/ui/…`
//! (the default target directory).

#[test]
fn bad_descriptions_fail_to_compile_and_good_ones_run() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/*.rs");
    // The same rover from a file and inline, both compiled and run.
    t.pass("tests/pass/*.rs");
}
