//! A description written as Rust tokens (`name = "toy", body = { mass = 30.0 }, …`)
//! and its translation to TOML text, remembering which token wrote which
//! bytes so that a diagnostic of `rover-spec` lands on the token.
//!
//! ```text
//! entries := (key '=' value) (',' key '=' value)* ','?
//! key     := identifier | "string"
//! value   := "string" | number | '-' number | true | false
//!          | '[' (value (',' value)* ','?)? ']' | '{' entries? '}'
//! ```
//! The keys and values are exactly those of the TOML format
//! (docs/DESCRIPTION.md): `[[suspension]]` tables become
//! `suspension = [{ … }, { … }]`.

use std::ops::Range;

use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};

/// A parsed value with the span of the tokens that wrote it.
#[derive(Clone, Debug)]
pub enum Value {
    /// A string.
    Str(String, Span),
    /// A number, in TOML syntax.
    Number(String, Span),
    /// A boolean.
    Bool(bool, Span),
    /// An array.
    Array(Vec<Value>, Span),
    /// A table.
    Table(Vec<Entry>, Span),
}

impl Value {
    /// The span of the value's tokens.
    pub fn span(&self) -> Span {
        match self {
            Value::Str(_, s)
            | Value::Number(_, s)
            | Value::Bool(_, s)
            | Value::Array(_, s)
            | Value::Table(_, s) => *s,
        }
    }
}

/// `key = value`.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The key.
    pub key: String,
    /// The key's span.
    pub key_span: Span,
    /// The value.
    pub value: Value,
}

/// Parse `entries` from tokens; every mistake is an error at its token.
pub fn parse_entries(tokens: TokenStream) -> syn::Result<Vec<Entry>> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut i = 0;
    let mut entries = Vec::new();
    while i < trees.len() {
        let (key, key_span) = match &trees[i] {
            TokenTree::Ident(id) => {
                let s = id.to_string();
                (s.strip_prefix("r#").unwrap_or(&s).to_string(), id.span())
            }
            TokenTree::Literal(lit) => match syn::Lit::new(lit.clone()) {
                syn::Lit::Str(s) => (s.value(), lit.span()),
                _ => return Err(err(lit.span(), "expected a key (a field name)")),
            },
            t => return Err(err(t.span(), "expected a key (a field name)")),
        };
        i += 1;
        match trees.get(i) {
            Some(TokenTree::Punct(p)) if p.as_char() == '=' => i += 1,
            Some(t) => {
                return Err(err(
                    t.span(),
                    &format!("expected `=` after `{key}`: write `{key} = <value>`"),
                ));
            }
            None => {
                return Err(err(
                    key_span,
                    &format!("`{key}` has no value: write `{key} = <value>`"),
                ));
            }
        }
        let start = i;
        let value = parse_value(&trees, &mut i, key_span)?;
        entries.push(Entry {
            key,
            key_span,
            value,
        });
        match trees.get(i) {
            None => {}
            Some(TokenTree::Punct(p)) if p.as_char() == ',' => i += 1,
            Some(t) if continues_expression(t) => return Err(not_a_literal(&trees, start)),
            Some(t) => {
                return Err(err(t.span(), "expected `,` between fields: `a = 1, b = 2`"));
            }
        }
    }
    Ok(entries)
}

fn err(span: Span, msg: &str) -> syn::Error {
    syn::Error::new(span, msg)
}

/// Whether `t`, right after a value, makes it an expression (`2.0 * M`,
/// `X.0`, `f(1)`) rather than ending it.
fn continues_expression(t: &TokenTree) -> bool {
    match t {
        TokenTree::Punct(p) => p.as_char() != ',',
        TokenTree::Group(g) => g.delimiter() != Delimiter::Brace,
        _ => false,
    }
}

/// The error for an expression or a constant written as a value (the
/// tokens from `start` to the next `,`), with why and what to write.
fn not_a_literal(trees: &[TokenTree], start: usize) -> syn::Error {
    let expr: TokenStream = trees[start..]
        .iter()
        .take_while(|t| !matches!(t, TokenTree::Punct(p) if p.as_char() == ','))
        .cloned()
        .collect();
    syn::Error::new_spanned(
        &expr,
        format!(
            "`{expr}` is not a literal: the derive validates the description and generates the plant \
             while compiling, before constants and expressions have values, so values are literals \
             (a string, a number, `true`/`false`, `[…]`, `{{ key = value, … }}`); write the value, or \
             build a rover from Rust values at run time (docs/RUST.md, \"A rover built at run time\")"
        ),
    )
}

fn parse_value(trees: &[TokenTree], i: &mut usize, before: Span) -> syn::Result<Value> {
    let Some(t) = trees.get(*i) else {
        return Err(err(before, "expected a value after `=`"));
    };
    *i += 1;
    match t {
        TokenTree::Literal(lit) => literal(lit, false),
        TokenTree::Punct(p) if p.as_char() == '-' => match trees.get(*i) {
            Some(TokenTree::Literal(lit)) => {
                *i += 1;
                literal(lit, true).map(|v| match v {
                    Value::Number(s, _) => {
                        Value::Number(s, p.span().join(lit.span()).unwrap_or(lit.span()))
                    }
                    v => v,
                })
            }
            Some(_) => Err(not_a_literal(trees, *i - 1)),
            None => Err(err(p.span(), "expected a number after `-`")),
        },
        TokenTree::Ident(id) if id == "true" || id == "false" => {
            Ok(Value::Bool(id == "true", id.span()))
        }
        // A constant, a path, a call or a block: Rust, not a literal.
        TokenTree::Ident(_) => Err(not_a_literal(trees, *i - 1)),
        TokenTree::Group(g) if g.delimiter() == Delimiter::Parenthesis => {
            Err(not_a_literal(trees, *i - 1))
        }
        TokenTree::Punct(p) if matches!(p.as_char(), '&' | '*' | '!' | '<' | ':') => {
            Err(not_a_literal(trees, *i - 1))
        }
        TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket => {
            let inner: Vec<TokenTree> = g.stream().into_iter().collect();
            let mut k = 0;
            let mut items = Vec::new();
            while k < inner.len() {
                let start = k;
                items.push(parse_value(&inner, &mut k, g.span())?);
                match inner.get(k) {
                    None => {}
                    Some(TokenTree::Punct(p)) if p.as_char() == ',' => k += 1,
                    Some(t) if continues_expression(t) => {
                        return Err(not_a_literal(&inner, start));
                    }
                    Some(t) => return Err(err(t.span(), "expected `,` between array items")),
                }
            }
            Ok(Value::Array(items, g.span()))
        }
        TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
            Ok(Value::Table(parse_entries(g.stream())?, g.span()))
        }
        t => Err(err(
            t.span(),
            "expected a value: a string, a number, `true`/`false`, `[…]` or `{ key = value, … }`",
        )),
    }
}

fn literal(lit: &proc_macro2::Literal, negative: bool) -> syn::Result<Value> {
    let sign = if negative { "-" } else { "" };
    match syn::Lit::new(lit.clone()) {
        syn::Lit::Str(s) if !negative => Ok(Value::Str(s.value(), lit.span())),
        syn::Lit::Int(n) if n.suffix().is_empty() => Ok(Value::Number(
            format!("{sign}{}", n.base10_digits()),
            lit.span(),
        )),
        syn::Lit::Float(f) if f.suffix().is_empty() => {
            let digits = f.base10_digits();
            // TOML wants a digit after the point: `1.` → `1.0`.
            let digits = if digits.ends_with('.') {
                format!("{digits}0")
            } else {
                digits.to_string()
            };
            Ok(Value::Number(format!("{sign}{digits}"), lit.span()))
        }
        syn::Lit::Int(_) | syn::Lit::Float(_) => Err(err(
            lit.span(),
            "remove the type suffix: description numbers are plain (`30.0`, not `30.0f64`)",
        )),
        _ => Err(err(
            lit.span(),
            "expected a string, a number or `true`/`false`",
        )),
    }
}

/// TOML text of `entries` (top-level `key = value` lines, inline tables
/// and arrays below), and the byte range each key and value wrote with its span.
pub fn to_toml(entries: &[Entry]) -> (String, Vec<(Range<usize>, Span)>) {
    let mut out = String::new();
    let mut spans = Vec::new();
    for e in entries {
        write_entry(e, &mut out, &mut spans);
        out.push('\n');
    }
    (out, spans)
}

fn write_entry(e: &Entry, out: &mut String, spans: &mut Vec<(Range<usize>, Span)>) {
    let start = out.len();
    write_key(&e.key, out);
    spans.push((start..out.len(), e.key_span));
    out.push_str(" = ");
    write_value(&e.value, out, spans);
}

fn write_key(key: &str, out: &mut String) {
    if !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        out.push_str(key);
    } else {
        write_str(key, out);
    }
}

fn write_str(s: &str, out: &mut String) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
}

fn write_value(v: &Value, out: &mut String, spans: &mut Vec<(Range<usize>, Span)>) {
    let start = out.len();
    match v {
        Value::Str(s, _) => write_str(s, out),
        Value::Number(n, _) => out.push_str(n),
        Value::Bool(b, _) => out.push_str(if *b { "true" } else { "false" }),
        Value::Array(items, _) => {
            out.push('[');
            for (k, item) in items.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                write_value(item, out, spans);
            }
            out.push(']');
        }
        Value::Table(entries, _) => {
            out.push_str("{ ");
            for (k, e) in entries.iter().enumerate() {
                if k > 0 {
                    out.push_str(", ");
                }
                write_entry(e, out, spans);
            }
            out.push_str(" }");
        }
    }
    spans.push((start..out.len(), v.span()));
}

/// The span of the smallest recorded range holding byte `at`.
pub fn span_at(spans: &[(Range<usize>, Span)], at: usize) -> Option<Span> {
    spans
        .iter()
        .filter(|(r, _)| r.start <= at && at < r.end.max(r.start + 1))
        .min_by_key(|(r, _)| r.end - r.start)
        .map(|(_, s)| *s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    #[test]
    fn tokens_become_toml() {
        let entries = parse_entries(quote! {
            name = "toy", gravity = 9.81,
            body = { mass = 30.0, inertia = [0.7, 0.9, 1] },
            suspension = [{ name = "a", pivot = [0.1, -0.2, 1e-3], r#type = true }],
        })
        .unwrap();
        let (text, spans) = to_toml(&entries);
        assert_eq!(
            text,
            "name = \"toy\"\ngravity = 9.81\nbody = { mass = 30.0, inertia = [0.7, 0.9, 1] }\n\
             suspension = [{ name = \"a\", pivot = [0.1, -0.2, 1e-3], type = true }]\n"
        );
        assert!(span_at(&spans, text.find("30.0").unwrap()).is_some());
    }

    #[test]
    fn token_mistakes_are_errors_with_a_hint() {
        let e = parse_entries(quote! { name: "toy" }).unwrap_err();
        assert_eq!(
            e.to_string(),
            "expected `=` after `name`: write `name = <value>`"
        );
        let e = parse_entries(quote! { mass = 30.0f64 }).unwrap_err();
        assert!(e.to_string().starts_with("remove the type suffix"));
        let e = parse_entries(quote! { a = 1 b = 2 }).unwrap_err();
        assert_eq!(e.to_string(), "expected `,` between fields: `a = 1, b = 2`");
    }

    #[test]
    fn constants_and_expressions_are_refused_as_not_literals() {
        for (tokens, expr) in [
            (quote! { mass = MASS, x = 1 }, "`MASS`"),
            (quote! { mass = 2.0 * 10.0 }, "`2.0 * 10.0`"),
            (quote! { mass = -MASS }, "`- MASS`"),
            (
                quote! { body = { mass = consts::MASS } },
                "`consts :: MASS`",
            ),
            (quote! { inertia = [0.1, X * 2.0, 0.3] }, "`X * 2.0`"),
            (quote! { inertia = [0.1, 2.0 * X, 0.3] }, "`2.0 * X`"),
            (quote! { mass = (1.0), a = 2 }, "`(1.0)`"),
            (quote! { mass = f(1.0) }, "`f (1.0)`"),
        ] {
            let e = parse_entries(tokens).unwrap_err().to_string();
            assert!(
                e.starts_with(&format!("{expr} is not a literal: the derive validates")),
                "{e}"
            );
            assert!(e.contains("A rover built at run time"), "{e}");
        }
    }
}
