//! The checked-in generated plants of models/ are what the generator
//! writes today, so that a change of the generator shows up as a reviewed
//! diff of them (CONTRIBUTING.md, "Golden files and snapshots").
//! `ROVER_BLESS=1 cargo test -p rover-codegen --test golden` rewrites
//! them; commit that on its own.

use std::path::PathBuf;

#[test]
fn checked_in_model_plants_are_up_to_date() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let bless = std::env::var_os("ROVER_BLESS").is_some_and(|v| v == "1");
    let mut stale = Vec::new();
    for name in rover_models::NAMES {
        let source = rover_models::builtin_path(name).unwrap();
        let spec = rover_spec::load_str(rover_models::builtin(name).unwrap(), source).unwrap();
        let module = rover_codegen::generate_module(&spec, source).unwrap();
        let path = root.join("models/src/generated").join(format!("{name}.rs"));
        let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
        if on_disk != module {
            if bless {
                std::fs::write(&path, &module).unwrap();
            } else {
                stale.push(path.display().to_string());
            }
        }
    }
    // The reduced fidelity levels of swing4 (MODEL.md §9), frozen at its
    // loaded static equilibrium on flat ground.
    {
        use rover_dynamics::fidelity::Fidelity;
        let source = rover_models::builtin_path("swing4").unwrap();
        let spec = rover_spec::load_str(rover_models::builtin("swing4").unwrap(), source).unwrap();
        let y_ref = rover_runtime::quasi_static::flat_ground_equilibrium(&spec.model).unwrap();
        for (fidelity, file, type_name) in [
            (
                Fidelity::Simplified,
                "swing4_simplified",
                "Swing4Simplified",
            ),
            (
                Fidelity::Linearized,
                "swing4_linearized",
                "Swing4Linearized",
            ),
        ] {
            let options = rover_codegen::ModuleOptions {
                type_name: Some(type_name.into()),
                jacobian: true,
                level: Some(rover_codegen::trace::Level {
                    fidelity,
                    y_ref: y_ref.clone(),
                }),
            };
            let module = rover_codegen::generate_module_with(&spec, source, &options).unwrap();
            let path = root.join("models/src/generated").join(format!("{file}.rs"));
            let on_disk = std::fs::read_to_string(&path).unwrap_or_default();
            if on_disk != module {
                if bless {
                    std::fs::write(&path, &module).unwrap();
                } else {
                    stale.push(path.display().to_string());
                }
            }
        }
    }
    assert!(
        stale.is_empty(),
        "generated plants differ from the generator's output: {stale:?}\n\
         run `ROVER_BLESS=1 cargo test -p rover-codegen --test golden` to rewrite them, \
         review the diff and commit it on its own"
    );
}
