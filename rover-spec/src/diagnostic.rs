//! One located message, for parser errors and semantic errors alike, and
//! its rendering in rustc's style (the file, line and column, the source
//! line with the offending span underlined, then the fix), the form in
//! which a Rust user already reads errors.

use std::ops::Range;

use annotate_snippets::{AnnotationKind, Level, Renderer, Snippet};

/// A problem with a description: where, what, and how to fix it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// The field path (`wheel[2].radius`); empty for the whole document.
    pub path: String,
    /// The bytes of the source it points at, once located.
    pub span: Option<Range<usize>>,
    /// What is wrong, with the numbers.
    pub message: String,
    /// A short label under the caret.
    pub label: String,
    /// How to fix it.
    pub help: String,
}

impl Diagnostic {
    /// A diagnostic at a field path (located later against the source).
    pub fn at(
        path: impl Into<String>,
        message: impl Into<String>,
        help: impl Into<String>,
    ) -> Self {
        Diagnostic {
            path: path.into(),
            span: None,
            message: message.into(),
            label: String::new(),
            help: help.into(),
        }
    }

    /// Set the caret label.
    pub fn label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Render it: `error: path: message`, then ` --> origin:line:col`, the
    /// source line with a caret and `= help: …`. Without source (a
    /// description built in Rust) the location is the origin and the path.
    pub fn render(&self, origin: &str, source: Option<&str>) -> String {
        let title = if self.path.is_empty() {
            self.message.clone()
        } else {
            format!("{}: {}", self.path, self.message)
        };
        let renderer = Renderer::plain();
        match (source, &self.span) {
            (Some(text), Some(span)) => {
                let text = &printable(text);
                let span = clamp(text, span.clone());
                let report = &[Level::ERROR
                    .primary_title(&title)
                    .element(
                        Snippet::source(text)
                            .path(origin)
                            .annotation(AnnotationKind::Primary.span(span).label(&self.label)),
                    )
                    .element(Level::HELP.message(&self.help))];
                renderer.render(report).to_string()
            }
            _ => {
                let report = &[Level::ERROR
                    .primary_title(format!("{origin}: {title}"))
                    .element(Level::HELP.message(&self.help))];
                renderer.render(report).to_string()
            }
        }
    }
}

impl Diagnostic {
    /// Render it as `error: origin:line:col: path: message` and `= help: …`,
    /// quoting nothing of `source` (which only locates the span).
    pub fn render_unquoted(&self, origin: &str, source: Option<&str>) -> String {
        let place = match (source, &self.span) {
            (Some(text), Some(span)) => {
                let (line, column) = rover_files::line_column(text.as_bytes(), span.start);
                format!("{origin}:{line}:{column}")
            }
            _ => origin.to_string(),
        };
        let title = if self.path.is_empty() {
            self.message.clone()
        } else {
            format!("{}: {}", self.path, self.message)
        };
        let report = &[Level::ERROR
            .primary_title(format!("{place}: {title}"))
            .element(Level::HELP.message(&self.help))];
        Renderer::plain().render(report).to_string()
    }
}

/// Keep a span inside the text and on char boundaries; point at the first
/// line of a multi-line span (a table), so the caret sits on its header.
fn clamp(text: &str, span: Range<usize>) -> Range<usize> {
    let mut start = span.start.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = span.end.clamp(start, text.len());
    if let Some(nl) = text[start..end].find('\n') {
        end = start + nl;
    }
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    start..end
}

/// The source with each control character other than a tab or a line
/// break (a terminal escape, say, which a file may hold where it is
/// invalid) replaced by as many `?` as its UTF-8 bytes, so that spans keep
/// their places and nothing but text reaches the terminal.
fn printable(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let keep = !crate::validate::unprintable(c) || matches!(c, '\t' | '\n' | '\r');
            let (c, n) = if keep { (c, 1) } else { ('?', c.len_utf8()) };
            std::iter::repeat_n(c, n)
        })
        .collect()
}
