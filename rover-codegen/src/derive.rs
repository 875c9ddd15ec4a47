//! `#[derive(Rover)]`: everything the proc-macro crate does, as an ordinary
//! function that tests can call: parse the `#[rover(…)]` attribute, load
//! and validate the description, emit the plant, or errors at the culprit.
//!
//! ```text
//! #[derive(Rover)]
//! #[rover(file = "models/toy.toml")]         // relative to CARGO_MANIFEST_DIR
//! struct Toy;                                // → ToyPlant
//!
//! #[derive(Rover)]
//! #[rover(name = "toy", gravity = 1.62, body = { mass = 30.0, … }, …)]
//! struct Toy;                                // the same fields as Rust tokens
//! ```
//! A derive cannot add fields to the struct it is put on, and a plant keeps
//! state (the spring neutrals that active suspension moves), so the plant
//! is a companion type `<Name>Plant` with the struct's visibility;
//! `<Name>::plant()` makes one. `jacobian = true` in the attribute adds the
//! exact Jacobian; `fidelity = "simplified"` or `"linearized"` generates a
//! reduced level (MODEL.md §9), frozen at `y_ref = [...]` (one value per
//! suspension coordinate, rad or m) or, without it, at the description's
//! rest configuration y_c. `no_std = true` names `rover_dynamics` and
//! `libm` directly rather than through `rover_runtime` ([`crate::crates`]).
//! These four combine with `file`.

use std::path::{Path, PathBuf};

use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote};

use rover_dynamics::fidelity::Fidelity;

use crate::crates::{Crates, route};
use crate::plant_source::{Options, plant_source};
use crate::tokens::{Entry, Value, parse_entries, span_at, to_toml};
use crate::trace::Level;

mod stub;

/// Expand `#[derive(Rover)]` on `input`, reading files relative to the
/// `CARGO_MANIFEST_DIR` of the crate being compiled.
pub fn expand_derive(input: &syn::DeriveInput) -> TokenStream {
    let base = std::env::var_os("CARGO_MANIFEST_DIR")
        .map(PathBuf::from)
        .unwrap_or_default();
    expand_derive_in(input, &base)
}

/// [`expand_derive`] with an explicit base directory (for tests).
pub fn expand_derive_in(input: &syn::DeriveInput, base: &Path) -> TokenStream {
    let code = match expand(input, base) {
        Ok(tokens) => tokens,
        Err(e) => {
            let mut out = e.to_compile_error();
            out.extend(stub::stub(input));
            out
        }
    };
    route(code, crates_of(input))
}

/// Where the generated code finds `rover_dynamics` and `libm`: through
/// `rover_runtime` unless the attribute says `no_std = true` (also for
/// the stub of a description with mistakes, so that its code resolves).
fn crates_of(input: &syn::DeriveInput) -> Crates {
    let no_std = rover_attribute(input)
        .ok()
        .and_then(|a| a.meta.require_list().ok())
        .and_then(|l| parse_entries(l.tokens.clone()).ok())
        .is_some_and(|entries| {
            entries
                .iter()
                .any(|e| e.key == "no_std" && matches!(e.value, Value::Bool(true, _)))
        });
    if no_std {
        Crates::Direct
    } else {
        Crates::Runtime
    }
}

fn expand(input: &syn::DeriveInput, base: &Path) -> syn::Result<TokenStream> {
    check_shape(input)?;
    let attr = rover_attribute(input)?;
    let list = attr.meta.require_list()?;
    let mut entries = parse_entries(list.tokens.clone())?;
    let jacobian = take_bool(&mut entries, "jacobian")?.unwrap_or(false);
    // Read by `crates_of`.
    take_bool(&mut entries, "no_std")?;
    let fidelity = take_fidelity(&mut entries)?;
    let y_ref = take_numbers(&mut entries, "y_ref")?;
    let (spec, description) = match entries.iter().position(|e| e.key == "file") {
        Some(k) => file_description(&mut entries, k, base)?,
        None if entries.is_empty() => {
            return Err(syn::Error::new(
                list.delimiter.span().join(),
                "empty description: write `#[rover(file = \"….toml\")]` or the description's fields",
            ));
        }
        None => inline_description(&entries, attr_span(attr))?,
    };
    let level = level(fidelity, y_ref, &spec)?;
    let (fidelity, y_ref) = match &level {
        None => ("full", Vec::new()),
        Some(l) => (fidelity_name(l.fidelity), l.y_ref.clone()),
    };
    let name = &input.ident;
    let plant = format_ident!("{}Plant", name);
    let items = plant_items(&spec, &plant, &input.vis, jacobian, level)?;
    let companion = companion(name, &plant);
    let described = described(name, &plant, &spec.name, &description, fidelity, &y_ref);
    Ok(quote! {
        #items
        #companion
        #described
    })
}

/// The description of `file = "…"`, entry `k` of `entries`, the only one:
/// the other fields are written in the file.
fn file_description(
    entries: &mut Vec<Entry>,
    k: usize,
    base: &Path,
) -> syn::Result<(rover_spec::Spec, Source)> {
    let entry = entries.remove(k);
    if let Some(other) = entries.first() {
        return Err(syn::Error::new(
            other.key_span,
            format!(
                "`{}` cannot be combined with `file`: write it in the file",
                other.key
            ),
        ));
    }
    let Value::Str(rel, span) = entry.value else {
        return Err(syn::Error::new(
            entry.value.span(),
            "`file` takes a string: the path of the TOML description, relative to the crate's Cargo.toml",
        ));
    };
    let path = base.join(&rel);
    let text = rover_files::read_text(&path, rover_files::Limit::Text)
        .map_err(|e| syn::Error::new(span, format!("cannot read `{}`: {e}", path.display())))?;
    let spec = rover_spec::load_str(&text, &rel).map_err(|e| file_errors(&e, &rel, &text, span))?;
    // `include_str!` makes the file an input of the crate: editing
    // it rebuilds, and the text carried is the text validated.
    let abs = path.display().to_string();
    let source = Source {
        text: quote! { include_str!(#abs) },
        origin: quote! { #rel },
    };
    Ok((spec, source))
}

/// The description written in the attribute's fields, its errors at the
/// tokens that wrote them (`whole`, the attribute, for the others).
fn inline_description(entries: &[Entry], whole: Span) -> syn::Result<(rover_spec::Spec, Source)> {
    let (text, spans) = to_toml(entries);
    let spec = rover_spec::load_str(&text, "<inline>")
        .map_err(|e| inline_errors(&e, &spans, &text, whole))?;
    let source = Source {
        text: quote! { #text },
        origin: quote! { ::core::concat!(::core::file!(), ":", ::core::line!()) },
    };
    Ok((spec, source))
}

/// A fidelity level as the attribute writes it.
fn fidelity_name(fidelity: Fidelity) -> &'static str {
    fidelity.name()
}

/// The generated plant `plant` of `spec`, with the struct's visibility
/// `vis`; the derive's code is compiled, never read, so it goes without
/// the block headings.
fn plant_items(
    spec: &rover_spec::Spec,
    plant: &syn::Ident,
    vis: &syn::Visibility,
    jacobian: bool,
    level: Option<Level>,
) -> syn::Result<TokenStream> {
    let options = Options {
        type_name: plant.to_string(),
        jacobian,
        comments: false,
        visibility: quote!(#vis).to_string(),
        level,
    };
    let source = plant_source(spec, &options).map_err(|e| {
        syn::Error::new(
            Span::call_site(),
            format!("internal error of rover-codegen: generated code does not parse ({e})"),
        )
    })?;
    Ok(source.code)
}

/// `<Name>::plant()`: the plant of the struct the derive is on, which a
/// derive cannot give fields.
fn companion(name: &syn::Ident, plant: &syn::Ident) -> TokenStream {
    let doc = format!("A [`{plant}`] with the description's spring neutrals.");
    quote! {
        impl #name {
            #[doc = #doc]
            pub const fn plant() -> #plant {
                #plant::new()
            }
        }
    }
}

/// The description as the generated code carries it: its TOML text (a
/// literal, or `include_str!` of the file) and where it was written.
struct Source {
    text: TokenStream,
    origin: TokenStream,
}

/// `rover_dynamics::described::Described` for the struct and for its
/// plant, so that either names the description (`MyRover::report()`,
/// `Simulation::new(MyRover::plant())`).
fn described(
    name: &syn::Ident,
    plant: &syn::Ident,
    rover: &str,
    source: &Source,
    fidelity: &str,
    y_ref: &[f64],
) -> TokenStream {
    let Source { text, origin } = source;
    let y_ref = y_ref.iter().map(|v| proc_macro2::Literal::f64_suffixed(*v));
    quote! {
        impl ::rover_dynamics::described::Described for #name {
            type Plant = #plant;
            const NAME: &'static str = #rover;
            const DESCRIPTION: &'static str = #text;
            const ORIGIN: &'static str = #origin;
            const FIDELITY: &'static str = #fidelity;
            const Y_REF: &'static [f64] = &[#(#y_ref),*];
            fn plant() -> #plant {
                #plant::new()
            }
        }
        impl ::rover_dynamics::described::Described for #plant {
            type Plant = #plant;
            const NAME: &'static str = <#name as ::rover_dynamics::described::Described>::NAME;
            const DESCRIPTION: &'static str =
                <#name as ::rover_dynamics::described::Described>::DESCRIPTION;
            const ORIGIN: &'static str = <#name as ::rover_dynamics::described::Described>::ORIGIN;
            const FIDELITY: &'static str =
                <#name as ::rover_dynamics::described::Described>::FIDELITY;
            const Y_REF: &'static [f64] = <#name as ::rover_dynamics::described::Described>::Y_REF;
            fn plant() -> #plant {
                #plant::new()
            }
        }
    }
}

fn attr_span(attr: &syn::Attribute) -> Span {
    attr.meta
        .require_list()
        .map(|l| l.delimiter.span().join())
        .unwrap_or_else(|_| Span::call_site())
}

/// Only a unit struct without generics: the plant is a companion type.
fn check_shape(input: &syn::DeriveInput) -> syn::Result<()> {
    if let Some(p) = input.generics.params.first() {
        return Err(syn::Error::new_spanned(
            p,
            "#[derive(Rover)] takes no generic parameters",
        ));
    }
    match &input.data {
        syn::Data::Struct(s) if matches!(s.fields, syn::Fields::Unit) => Ok(()),
        syn::Data::Struct(s) => Err(syn::Error::new_spanned(
            &s.fields,
            format!(
                "#[derive(Rover)] goes on a unit struct (`struct {};`): the plant with its state is generated as `{}Plant`",
                input.ident, input.ident
            ),
        )),
        _ => Err(syn::Error::new(
            input.ident.span(),
            format!(
                "#[derive(Rover)] goes on a unit struct (`struct {};`)",
                input.ident
            ),
        )),
    }
}

fn rover_attribute(input: &syn::DeriveInput) -> syn::Result<&syn::Attribute> {
    let mut found = input.attrs.iter().filter(|a| a.path().is_ident("rover"));
    let first = found.next().ok_or_else(|| {
        syn::Error::new(
            input.ident.span(),
            "missing #[rover(…)]: add `#[rover(file = \"my_rover.toml\")]` (relative to Cargo.toml) or the description's fields as `#[rover(name = \"…\", …)]`",
        )
    })?;
    if let Some(second) = found.next() {
        return Err(syn::Error::new_spanned(
            second,
            "more than one #[rover(…)]: give the whole description in one attribute",
        ));
    }
    Ok(first)
}

fn take_bool(entries: &mut Vec<Entry>, key: &str) -> syn::Result<Option<bool>> {
    let Some(k) = entries.iter().position(|e| e.key == key) else {
        return Ok(None);
    };
    match entries.remove(k).value {
        Value::Bool(b, _) => Ok(Some(b)),
        v => Err(syn::Error::new(
            v.span(),
            format!("`{key}` takes `true` or `false`"),
        )),
    }
}

/// `fidelity = "full" | "simplified" | "linearized" | "linearized_exact_rotation"`
/// (MODEL.md §9).
fn take_fidelity(entries: &mut Vec<Entry>) -> syn::Result<Option<(Fidelity, Span)>> {
    let Some(k) = entries.iter().position(|e| e.key == "fidelity") else {
        return Ok(None);
    };
    let value = entries.remove(k).value;
    let level = match &value {
        Value::Str(s, _) if s == "full" => Fidelity::Full,
        Value::Str(s, _) if s == "simplified" => Fidelity::Simplified,
        Value::Str(s, _) if s == "linearized" => Fidelity::Linearized,
        Value::Str(s, _) if s == "linearized_exact_rotation" => Fidelity::LinearizedExactRotation,
        v => {
            return Err(syn::Error::new(
                v.span(),
                "`fidelity` takes \"full\", \"simplified\", \"linearized\" or \"linearized_exact_rotation\" (MODEL.md §9)",
            ));
        }
    };
    Ok(Some((level, value.span())))
}

/// An array of numbers, such as `y_ref = [-0.52, -0.52, 0.52, 0.52]`.
fn take_numbers(entries: &mut Vec<Entry>, key: &str) -> syn::Result<Option<(Vec<f64>, Span)>> {
    let Some(k) = entries.iter().position(|e| e.key == key) else {
        return Ok(None);
    };
    let value = entries.remove(k).value;
    let bad = |span| {
        syn::Error::new(
            span,
            format!("`{key}` takes an array of numbers, one per suspension coordinate (rad or m)"),
        )
    };
    let Value::Array(items, span) = &value else {
        return Err(bad(value.span()));
    };
    let numbers = items
        .iter()
        .map(|v| match v {
            Value::Number(text, span) => text
                .replace('_', "")
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(*span)),
            other => Err(bad(other.span())),
        })
        .collect::<syn::Result<Vec<f64>>>()?;
    Ok(Some((numbers, *span)))
}

/// The fidelity level to trace: none for the full model; a reduced level
/// frozen at `y_ref`, or at the description's rest configuration y_c
/// (MODEL.md §9) when `y_ref` is not given.
fn level(
    fidelity: Option<(Fidelity, Span)>,
    y_ref: Option<(Vec<f64>, Span)>,
    spec: &rover_spec::Spec,
) -> syn::Result<Option<Level>> {
    let m = spec.model.coordinates.len();
    match (fidelity, y_ref) {
        (None | Some((Fidelity::Full, _)), Some((_, span))) => Err(syn::Error::new(
            span,
            "`y_ref` is the configuration a reduced level is frozen at: add `fidelity = \"simplified\"` or `\"linearized\"`, or remove it",
        )),
        (None | Some((Fidelity::Full, _)), None) => Ok(None),
        (Some((fidelity, _)), Some((y, span))) => {
            if y.len() != m {
                return Err(syn::Error::new(
                    span,
                    format!(
                        "`y_ref` has {} values but the rover has {m} suspension coordinate{} ({}): give one per coordinate, in this order",
                        y.len(),
                        if m == 1 { "" } else { "s" },
                        spec.coordinate_names.join(", ")
                    ),
                ));
            }
            let level = Level { fidelity, y_ref: y };
            crate::trace::check_level(spec, &level).map_err(|m| syn::Error::new(span, m))?;
            Ok(Some(level))
        }
        (Some((fidelity, _)), None) => Ok(Some(Level {
            fidelity,
            y_ref: spec.model.rest(),
        })),
    }
}

/// The bytes of the first line of `text` that starts with `start`.
fn line_starting(text: &str, start: &str) -> Option<std::ops::Range<usize>> {
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        if line.trim_start().starts_with(start) {
            let indent = line.len() - line.trim_start().len();
            return Some(at + indent..at + line.trim_end().len());
        }
        at += line.len();
    }
    None
}

/// The diagnostics with those of wheels that lack the same fields, which
/// the wheel defaults (`defaults`, written at `at` if at all) do not give
/// either, made one: a field missing from the defaults is one mistake,
/// not one per wheel. The others are kept as they are.
fn merge_missing_wheel_fields(
    diagnostics: &[rover_spec::Diagnostic],
    at: Option<std::ops::Range<usize>>,
    defaults: &str,
) -> Vec<rover_spec::Diagnostic> {
    // `wheel `fl` has no `radius` (and `[wheel_defaults]` gives none)`.
    let missing = |d: &rover_spec::Diagnostic| -> Option<(String, String)> {
        let rest = d.message.strip_prefix("wheel `")?;
        let (name, rest) = rest.split_once("` has no ")?;
        let fields = rest.strip_suffix(" (and `[wheel_defaults]` gives none)")?;
        Some((name.to_string(), fields.to_string()))
    };
    let mut out: Vec<rover_spec::Diagnostic> = Vec::new();
    let mut groups: Vec<(String, Vec<String>, usize)> = Vec::new();
    for d in diagnostics {
        match missing(d) {
            Some((wheel, fields)) => match groups.iter_mut().find(|g| g.0 == fields) {
                Some(group) => group.1.push(wheel),
                None => {
                    groups.push((fields, vec![wheel], out.len()));
                    out.push(d.clone());
                }
            },
            None => out.push(d.clone()),
        }
    }
    for (fields, wheels, k) in groups {
        if wheels.len() < 2 {
            continue;
        }
        let names: Vec<String> = wheels.iter().map(|w| format!("`{w}`")).collect();
        let mut merged = rover_spec::Diagnostic::at(
            "wheel_defaults",
            format!(
                "{} wheels ({}) have no {fields}, and {defaults} gives none",
                wheels.len(),
                names.join(", ")
            ),
            format!("add {fields} to {defaults} (for every wheel), or to each of these wheels"),
        );
        merged.span = at.clone();
        out[k] = merged;
    }
    out
}

/// Line and column (1-based, in characters) of byte `at` of `text`.
fn line_col(text: &str, at: usize) -> (usize, usize) {
    let at = at.min(text.len());
    let before = text.get(..at).unwrap_or("");
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    (line, col)
}

/// One compile error per diagnostic, at the `file = "…"` literal, quoting
/// the file's line: `path:line:col: field: message`, the line, `help:`.
fn file_errors(e: &rover_spec::SpecError, rel: &str, text: &str, span: Span) -> syn::Error {
    let defaults = line_starting(text, "[wheel_defaults]");
    let diagnostics = merge_missing_wheel_fields(&e.diagnostics, defaults, "`[wheel_defaults]`");
    let mut errors = diagnostics.iter().map(|d| {
        let title = if d.path.is_empty() {
            d.message.clone()
        } else {
            format!("{}: {}", d.path, d.message)
        };
        let msg = match &d.span {
            Some(s) => {
                let (line, col) = line_col(text, s.start);
                let quoted = text.lines().nth(line - 1).unwrap_or("");
                format!(
                    "{rel}:{line}:{col}: {title}\n  {line} | {quoted}\n  = help: {}",
                    d.help
                )
            }
            None => format!("{rel}: {title}\n  = help: {}", d.help),
        };
        syn::Error::new(span, msg)
    });
    let mut first = errors
        .next()
        .unwrap_or_else(|| syn::Error::new(span, e.to_string()));
    for more in errors {
        first.combine(more);
    }
    first
}

/// One compile error per diagnostic, at the token that wrote the value.
fn inline_errors(
    e: &rover_spec::SpecError,
    spans: &[(std::ops::Range<usize>, Span)],
    text: &str,
    whole: Span,
) -> syn::Error {
    let defaults = line_starting(text, "wheel_defaults =");
    let diagnostics =
        merge_missing_wheel_fields(&e.diagnostics, defaults, "`wheel_defaults = { … }`");
    let mut errors = diagnostics.iter().map(|d| {
        let at = d
            .span
            .as_ref()
            .and_then(|s| span_at(spans, s.start))
            .unwrap_or(whole);
        let title = if d.path.is_empty() {
            d.message.clone()
        } else {
            format!("{}: {}", d.path, d.message)
        };
        syn::Error::new(at, format!("{title}\n  = help: {}", d.help))
    });
    let mut first = errors
        .next()
        .unwrap_or_else(|| syn::Error::new(whole, e.to_string()));
    for more in errors {
        first.combine(more);
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expand_str(src: &str) -> String {
        let input: syn::DeriveInput = syn::parse_str(src).unwrap();
        let base = Path::new(env!("CARGO_MANIFEST_DIR"));
        expand_derive_in(&input, base).to_string()
    }

    #[test]
    fn a_file_becomes_a_companion_plant_and_an_include() {
        let out = expand_str(r#"#[rover(file = "tests/data/toy.toml")] pub struct Toy;"#);
        assert!(out.contains("pub struct ToyPlant"), "{out}");
        assert!(out.contains("include_str !"), "{out}");
        assert!(out.contains(
            "impl :: rover_runtime :: __private :: rover_dynamics :: plant :: Plant for ToyPlant"
        ));
        assert!(!out.contains("compile_error"));
        // Every path to the two crates goes through the runtime.
        for name in ["rover_dynamics", "libm"] {
            let all = out.matches(&format!(":: {name} ::")).count();
            let routed = out.matches(&format!("__private :: {name} ::")).count();
            assert!(all > 0 && routed == all, "{name}: {routed} of {all}");
        }
        let direct =
            expand_str(r#"#[rover(file = "tests/data/toy.toml", no_std = true)] pub struct Toy;"#);
        assert!(direct.contains("impl :: rover_dynamics :: plant :: Plant for ToyPlant"));
        assert!(!direct.contains("rover_runtime"), "{direct}");
        assert!(!out.contains("jacobian_fixed"));
    }

    #[test]
    fn errors_come_with_a_stub_and_name_the_problem() {
        let out =
            expand_str(r#"#[rover(name = "x", gravity = -1.0, jacobian = true)] struct Bad;"#);
        assert!(out.contains("compile_error"), "{out}");
        assert!(out.contains("missing field `body`"), "{out}");
        // The stub keeps `Bad::plant()` and `BadPlant` resolvable.
        assert!(out.contains("struct BadPlant"), "{out}");
        let out = expand_str(r#"#[rover(jacobian = 1)] struct Bad;"#);
        assert!(out.contains("`jacobian` takes `true` or `false`"), "{out}");
    }

    #[test]
    fn a_field_missing_from_every_wheel_is_one_error_at_the_defaults() {
        let toy = include_str!("../tests/data/toy.toml");
        assert!(toy.contains("radius = "), "{toy}");
        let text: String = toy
            .lines()
            .filter(|l| !l.trim_start().starts_with("radius ="))
            .map(|l| format!("{l}\n"))
            .collect();
        let e = rover_spec::load_str(&text, "x.toml").unwrap_err();
        let per_wheel = e
            .diagnostics
            .iter()
            .filter(|d| d.message.contains("has no `radius`"))
            .count();
        assert!(per_wheel >= 2, "{e}");
        let msg = file_errors(&e, "x.toml", &text, Span::call_site()).to_string();
        assert_eq!(msg.matches("no `radius`").count(), 1, "{msg}");
        let (line, _) = line_col(&text, text.find("[wheel_defaults]").unwrap());
        assert!(
            msg.starts_with(&format!(
                "x.toml:{line}:1: wheel_defaults: {per_wheel} wheels (`"
            )) && msg.contains("have no `radius`, and `[wheel_defaults]` gives none"),
            "{msg}"
        );
        assert!(
            msg.contains("help: add `radius` to `[wheel_defaults]`"),
            "{msg}"
        );
    }

    #[test]
    fn file_errors_quote_the_line() {
        let toy = include_str!("../tests/data/toy.toml");
        let text = toy.replace("gravity = 1.62", "gravity = -1.0");
        let e = rover_spec::load_str(&text, "x.toml").unwrap_err();
        let msg = file_errors(&e, "x.toml", &text, Span::call_site()).to_string();
        assert!(
            msg.starts_with("x.toml:4:11: gravity: must be > 0"),
            "{msg}"
        );
        assert!(msg.contains("\n  4 | gravity = -1.0\n"), "{msg}");
    }

    #[test]
    fn reduced_levels_are_checked_where_written() {
        let toy = r#"#[rover(file = "tests/data/toy.toml", fidelity = "#;
        let out = expand_str(&format!(r#"{toy}"medium")] struct T;"#));
        assert!(out.contains("`fidelity` takes"), "{out}");
        let out = expand_str(r#"#[rover(file = "tests/data/toy.toml", y_ref = [0.1])] struct T;"#);
        assert!(out.contains("add `fidelity"), "{out}");
        let out = expand_str(&format!(
            r#"{toy}"simplified", y_ref = [0.1, 0.2, 0.3])] struct T;"#
        ));
        assert!(
            out.contains("`y_ref` has 3 values but the rover has"),
            "{out}"
        );
        let out = expand_str(&format!(r#"{toy}"simplified", y_ref = ["a"])] struct T;"#));
        assert!(out.contains("`y_ref` takes an array of numbers"), "{out}");
        // Inside the travel [-40°, 0°] of each coordinate, or refused naming it.
        let out = expand_str(&format!(
            r#"{toy}"simplified", y_ref = [-0.3, 0.5])] struct T;"#
        ));
        assert!(
            out.contains("coordinate y2 `right` of suspension `right`")
                && out.contains("outside its travel [-40°, 0°]"),
            "{out}"
        );
        // A good one: the reduced plant, no error.
        let out = expand_str(&format!(r#"{toy}"linearized")] struct T;"#));
        assert!(!out.contains("compile_error"), "{out}");
        assert!(out.contains("struct TPlant"), "{out}");
    }
}
