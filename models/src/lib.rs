//! The built-in rovers.
#![warn(missing_docs)]
