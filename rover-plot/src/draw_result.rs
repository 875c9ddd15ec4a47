//! What every drawing step returns, shared by the panels and the figures
//! (a leaf module: it imports nothing of the crate).

/// What a drawing step returns: the plotting library's message on failure.
pub(crate) type DrawResult = Result<(), String>;

/// Turns a plotting-library error into its message.
pub(crate) fn failed<E: std::fmt::Display>(error: E) -> String {
    error.to_string()
}
