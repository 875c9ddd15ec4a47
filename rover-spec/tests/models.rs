//! The built-in models load, with the geometry MODEL.md §10 fixes.

use rover_spec::report::check_report;

#[test]
fn print_reports() {
    for name in rover_models::NAMES {
        match rover_spec::load_str(
            rover_models::builtin(name).unwrap(),
            rover_models::builtin_path(name).unwrap(),
        ) {
            Ok(spec) => println!("{}", check_report(&spec)),
            Err(e) => println!("{e}"),
        }
    }
}
