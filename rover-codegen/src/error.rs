//! Why code could not be generated.

use std::fmt;

/// An error of the generator.
#[derive(Debug)]
pub enum CodegenError {
    /// The description is invalid (every diagnostic, rendered).
    Spec(rover_spec::SpecError),
    /// An option cannot be used (a type name that is not a Rust
    /// identifier, a frozen configuration outside the travel): the message
    /// says which and how to fix it.
    Invalid(String),
    /// The generated code did not parse: a bug of the generator.
    Internal(String),
}

// Written out rather than derived with thiserror: this crate is compiled
// for the compiler's host by every user of `#[derive(Rover)]`.
impl fmt::Display for CodegenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CodegenError::Spec(e) => write!(f, "{e}"),
            CodegenError::Invalid(e) => write!(f, "{e}"),
            CodegenError::Internal(e) => write!(
                f,
                "internal error: the generated code does not parse ({e}); please report it"
            ),
        }
    }
}

impl std::error::Error for CodegenError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            CodegenError::Spec(e) => Some(e),
            CodegenError::Invalid(_) | CodegenError::Internal(_) => None,
        }
    }
}

impl From<rover_spec::SpecError> for CodegenError {
    fn from(e: rover_spec::SpecError) -> Self {
        CodegenError::Spec(e)
    }
}
