//! The prebuilt plant library of `rover export` (docs/EXPORT.md): the FMI
//! 3.0, FMI 2.0 and C symbols of [`rover_export::entry_points!`] with the
//! plant `rover simulate` runs ([`rover_export::run::builtin`]: a built-in
//! rover's generated plant, the generic plant of a rover file). Built by
//! `cargo build -p rover-plant` beside the `rover` executable, as
//! `librover_plant.so` (an FMU's binary) and `librover_plant.a` (the C
//! export's).

rover_export::entry_points!(rover_export::run::builtin);
