//! The error of loading a description: every diagnostic, rendered.

use std::fmt;

use crate::diagnostic::Diagnostic;

/// A description that cannot be loaded: all its diagnostics, in file order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecError {
    /// Where the description came from (a path, a built-in name, `<rust>`).
    pub origin: String,
    /// The source text, when there is one.
    pub source_text: Option<String>,
    /// The problems, sorted by position in the source.
    pub diagnostics: Vec<Diagnostic>,
    /// Whether messages quote the source's lines (see [`unquoted`](Self::unquoted)).
    pub quote_source: bool,
}

impl SpecError {
    /// Build the error, locating each diagnostic in `source` by its path
    /// (or its path by its span) and sorting them in file order.
    pub fn new(origin: &str, source: Option<&str>, mut diagnostics: Vec<Diagnostic>) -> Self {
        if let Some(text) = source {
            let doc = crate::document::Document::parse(text);
            for d in &mut diagnostics {
                if d.span.is_none() {
                    d.span = doc.locate(&d.path).map(|(span, _)| span);
                }
            }
            // Stable: diagnostics at the same place keep their order.
            diagnostics.sort_by_key(|d| d.span.as_ref().map_or(usize::MAX, |s| s.start));
        }
        SpecError {
            origin: origin.to_string(),
            source_text: source.map(str::to_string),
            diagnostics,
            quote_source: true,
        }
    }

    /// The same error, located by line and column but quoting none of the
    /// file's text: for a file that a scenario names, which may be any file
    /// on the machine (a scenario naming `/etc/passwd` as its rover must not
    /// print the password file's lines).
    pub fn unquoted(mut self) -> Self {
        self.quote_source = false;
        self
    }
}

impl fmt::Display for SpecError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for d in &self.diagnostics {
            let text = if self.quote_source {
                d.render(&self.origin, self.source_text.as_deref())
            } else {
                d.render_unquoted(&self.origin, self.source_text.as_deref())
            };
            writeln!(f, "{text}")?;
            writeln!(f)?;
        }
        let n = self.diagnostics.len();
        write!(
            f,
            "error: could not load `{}` due to {n} previous error{}",
            self.origin,
            if n == 1 { "" } else { "s" }
        )
    }
}

impl std::error::Error for SpecError {}
