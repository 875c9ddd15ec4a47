//! Snapshot of the generated code of a 2-wheel toy rover: any change of
//! the emitter shows up as a reviewed diff (CONTRIBUTING.md, "Golden files
//! and snapshots").
//! `INSTA_UPDATE=always cargo test -p rover-codegen --test snapshot` accepts one.

#[test]
fn toy_rover_module() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/toy.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let spec = rover_spec::load_str(&text, "tests/data/toy.toml").unwrap();
    let options = rover_codegen::ModuleOptions {
        type_name: None,
        jacobian: false,
        level: None,
    };
    let module =
        rover_codegen::generate_module_with(&spec, "tests/data/toy.toml", &options).unwrap();
    insta::assert_snapshot!(module);
}
