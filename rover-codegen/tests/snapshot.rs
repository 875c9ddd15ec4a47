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

/// A type name that is a keyword or not an identifier is refused with
/// what is wrong, before any code is generated; a rover named `self`
/// gets a type name that is not the keyword `Self`.
#[test]
fn type_names_are_identifiers_and_not_keywords() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/toy.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let spec = rover_spec::load_str(&text, "tests/data/toy.toml").unwrap();
    for (name, what) in [
        ("Self", "is a Rust keyword"),
        ("type", "is a Rust keyword"),
        ("My Rover", "is not a Rust identifier"),
        ("r#Toy", "is not a Rust identifier"),
        ("", "is not a Rust identifier"),
    ] {
        let options = rover_codegen::ModuleOptions {
            type_name: Some(name.to_string()),
            jacobian: false,
            level: None,
        };
        let e = rover_codegen::generate_module_with(&spec, "toy.toml", &options).unwrap_err();
        assert!(
            matches!(e, rover_codegen::CodegenError::Invalid(_)),
            "{name}: {e}"
        );
        let e = e.to_string();
        assert!(e.contains(&format!("{name:?} {what}")), "{e}");
        assert!(!e.contains("internal error"), "{e}");
    }
    assert_eq!(rover_codegen::module::type_name("self"), "RoverSelf");
    let named_self = text.replace("name = \"toy\"", "name = \"self\"");
    let spec = rover_spec::load_str(&named_self, "self.toml").unwrap();
    let module = rover_codegen::generate_module(&spec, "self.toml").unwrap();
    assert!(module.contains("pub struct RoverSelf"));
}
