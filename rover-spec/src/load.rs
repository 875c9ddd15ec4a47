//! Text → [`Description`] → [`Spec`], with every error located.

use std::ops::Range;
use std::path::Path;

use crate::description::Description;
use crate::diagnostic::Diagnostic;
use crate::document::Document;
use crate::error::SpecError;
use crate::spec::Spec;

/// Load and validate a description file.
pub fn load_file(path: &Path) -> Result<Spec, SpecError> {
    let origin = path.display().to_string();
    let problem = |message: String, help: &str| {
        SpecError::new(&origin, None, vec![Diagnostic::at("", message, help)])
    };
    match rover_files::read_text(path, rover_files::Limit::Text) {
        Ok(text) => load_str(&text, &origin),
        Err(e) if e.kind() == std::io::ErrorKind::InvalidData => Err(problem(
            e.to_string(),
            "save the description as UTF-8 text (TOML is UTF-8)",
        )),
        Err(e) => Err(problem(
            format!("cannot read the file: {e}"),
            "check the path (or give a built-in rover's name)",
        )),
    }
}

/// Load and validate a description held in memory; `origin` names it in
/// messages (a path, a built-in's name).
pub fn load_str(text: &str, origin: &str) -> Result<Spec, SpecError> {
    let desc = parse_str(text, origin)?;
    crate::validate::validate(&desc).map_err(|d| SpecError::new(origin, Some(text), d))
}

/// Validate a description built in Rust (no source to point into: the
/// messages name the field paths).
pub fn from_description(desc: &Description, origin: &str) -> Result<Spec, SpecError> {
    crate::validate::validate(desc).map_err(|d| SpecError::new(origin, None, d))
}

/// Parse TOML text into a [`Description`] without validating it.
pub fn parse_str(text: &str, origin: &str) -> Result<Description, SpecError> {
    let (_, syntax) = toml::de::DeTable::parse_recoverable(text);
    if !syntax.is_empty() {
        let diags = syntax
            .iter()
            .map(|e| parser_diagnostic(e, &Document::parse(""), text))
            .collect();
        return Err(SpecError::new(origin, Some(text), diags));
    }
    toml::from_str::<Description>(text).map_err(|e| {
        let doc = Document::parse(text);
        let e = refine_tagged(text, &e).unwrap_or(e);
        SpecError::new(origin, Some(text), vec![parser_diagnostic(&e, &doc, text)])
    })
}

/// serde reads a `kind`-tagged `[[suspension]]` table through a buffer that
/// loses the spans inside it, so its errors point at the whole table. Read
/// the table that holds the error again, straight into its kind's struct,
/// to get the precise error (the key, the value).
fn refine_tagged(text: &str, error: &toml::de::Error) -> Option<toml::de::Error> {
    use serde::de::DeserializeOwned;
    use toml::de::{DeTable, DeValue, ValueDeserializer};

    use crate::description as d;

    fn read<T: DeserializeOwned>(value: toml::Spanned<DeValue<'_>>) -> Option<toml::de::Error> {
        T::deserialize(ValueDeserializer::from(value)).err()
    }

    let span = error.span()?;
    let root = DeTable::parse(text).ok()?.into_inner();
    let array = root.get("suspension")?;
    let suspensions = array.get_ref().as_array()?;
    let inside =
        |s: &toml::Spanned<DeValue>| s.span().start <= span.start && span.end <= s.span().end;
    // The entry whose span holds the error's; when the error is at the
    // whole array's span (the first entry's header), each entry in turn:
    // serde stopped at the first that fails.
    let entries: Vec<_> = if array.span().start == span.start {
        suspensions.iter().collect()
    } else {
        vec![suspensions.iter().find(|s| inside(s))?]
    };
    entries.into_iter().find_map(|entry| {
        let DeValue::Table(table) = entry.get_ref() else {
            return None;
        };
        let mut table = table.clone();
        let kind = table.remove("kind")?;
        let value = toml::Spanned::new(entry.span(), DeValue::Table(table));
        match kind.get_ref().as_str()? {
            "longitudinal_swing_arm" => read::<d::SwingArmDesc>(value),
            "transversal_swing_arm" => read::<d::TransversalSwingArmDesc>(value),
            "double_wishbone" => read::<d::DoubleWishboneDesc>(value),
            "longitudinal_rocker" | "transversal_rocker" => read::<d::RockerDesc>(value),
            "rocker_bogie" => read::<d::RockerBogieDesc>(value),
            "polynomial" => read::<d::PolynomialDesc>(value),
            _ => None,
        }
        .filter(|e| e.span().is_some())
    })
}

/// How deep the TOML parser nests arrays, inline tables and dotted keys.
pub const MAX_NESTING: usize = 80;

/// A TOML error of nesting too deep (arrays in arrays, inline tables in
/// inline tables, or a dotted key of too many parts), which the parser
/// reports as a recursion limit: where it is (the parser's span, or the
/// first key of too many parts) and a sentence saying what is wrong.
pub fn nesting_error(text: &str, error: &toml::de::Error) -> Option<(Range<usize>, String)> {
    let message = error.message();
    if !message.contains("recursion") && !message.contains("recurse") {
        return None;
    }
    let span = error.span().or_else(|| deep_key(text))?;
    Some((
        span,
        format!(
            "nesting deeper than {MAX_NESTING} levels (arrays in arrays, tables in tables, or a key of more than {MAX_NESTING} dotted parts)"
        ),
    ))
}

/// The first key of a header or a key-value line with at least
/// [`MAX_NESTING`] dotted parts.
fn deep_key(text: &str) -> Option<Range<usize>> {
    let mut start = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let key = match trimmed.strip_prefix('[') {
            Some(header) => header.split(']').next().unwrap_or(""),
            None => trimmed.split('=').next().unwrap_or(""),
        };
        if key.matches('.').count() + 1 >= MAX_NESTING {
            let at = start + (line.len() - trimmed.len());
            return Some(at..start + line.trim_end().len());
        }
        start += line.len();
    }
    None
}

/// A parser or serde error as a [`Diagnostic`], with its field path and a hint.
fn parser_diagnostic(e: &toml::de::Error, doc: &Document, text: &str) -> Diagnostic {
    if let Some((span, message)) = nesting_error(text, e) {
        let mut d = Diagnostic::at(
            "",
            message,
            "a rover description is a few tables deep (docs/DESCRIPTION.md): check the brackets and braces here",
        )
        .label("too deep");
        d.span = Some(span);
        return d;
    }
    let message = e.message().trim().to_string();
    let mut span = e.span();
    let mut path = span.as_ref().map(|s| doc.path_at(s)).unwrap_or_default();
    let label;
    let help = if let Some(rest) = message.strip_prefix("unknown field `") {
        let field = rest.split('`').next().unwrap_or_default();
        let expected: Vec<&str> = message
            .split_once("expected")
            .map(|(_, list)| list.split('`').skip(1).step_by(2).collect())
            .unwrap_or_default();
        let on_key = span
            .as_ref()
            .and_then(|s| text.get(s.clone()))
            .is_some_and(|k| k.trim_matches('"') == field);
        if on_key {
            // The span is the key; the innermost value holding it is the table.
            if !path.ends_with(field) {
                path = if path.is_empty() {
                    field.to_string()
                } else {
                    format!("{path}.{field}")
                };
            }
        } else if let Some((p, s)) = doc.find_unknown_key(field, &expected) {
            // Tagged tables (suspensions) lose the key's span in serde.
            path = p;
            span = Some(s);
        }
        label = "unknown field".to_string();
        "remove it or fix its spelling (docs/DESCRIPTION.md lists every field)".to_string()
    } else if let Some(rest) = message.strip_prefix("missing field `") {
        let field = rest.split('`').next().unwrap_or_default();
        label = format!("this table has no `{field}`");
        format!("add `{field} = …` here (docs/DESCRIPTION.md lists every field, with units)")
    } else if message.starts_with("unknown variant") {
        label = "unknown value".to_string();
        "use one of the values listed above".to_string()
    } else if message.starts_with("invalid type")
        || message.starts_with("invalid length")
        || message.starts_with("invalid value")
    {
        label = "wrong value".to_string();
        "write the value in the form the message expects (docs/DESCRIPTION.md)".to_string()
    } else if path.is_empty() && doc_is_empty(doc) {
        label = "here".to_string();
        "fix the TOML syntax here (https://toml.io/en/v1.0.0)".to_string()
    } else {
        label = "here".to_string();
        "see docs/DESCRIPTION.md for the expected form".to_string()
    };
    let mut d = Diagnostic::at(path, first_line(&message), help).label(label);
    d.span = span;
    d
}

/// Whether the document has no parsed tree (a syntax error).
fn doc_is_empty(doc: &Document) -> bool {
    doc.locate("").is_none()
}

/// serde messages may span lines; keep them on one.
fn first_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}
