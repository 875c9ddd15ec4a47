//! Why code could not be generated.

/// An error of the generator.
#[derive(Debug, thiserror::Error)]
pub enum CodegenError {
    /// The description is invalid (every diagnostic, rendered).
    #[error("{0}")]
    Spec(#[from] rover_spec::SpecError),
    /// The generated code did not parse: a bug of the generator.
    #[error("internal error: the generated code does not parse ({0}); please report it")]
    Internal(String),
}
