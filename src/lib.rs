//! The `rover` command line.
