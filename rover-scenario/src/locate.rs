//! The place of a value error in a scenario file. serde reads a table
//! chosen by `kind` (the terrain, the steering, the wheel law) and the
//! `[terrain]` table (its soil beside its shape) through a buffer that
//! loses the spans inside it, so toml locates their errors at the table's
//! header. The table that holds the error is read again, straight into the
//! type its `kind` names, which locates the key or the value at fault.

use std::ops::Range;

use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

use rover_runtime::control::{Ackermann, HeadingHold, Profile};
use rover_runtime::soil::SoilConfig;
use rover_runtime::wheel_law::{ChenGenta, MagicFormula};
use rover_terrain::{
    BumpConfig, DitchConfig, FileConfig, FlatConfig, RandomConfig, SinusoidConfig, SlopeConfig,
    StepConfig,
};

/// `kind = "slip"` of `[control.steering]`, as its variant reads it.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct Slip {
    delta_tau: Profile,
}

/// The error of `error`'s table read again: its span and message, when
/// that locates it more precisely than `error` does.
pub(crate) fn refine(text: &str, error: &toml::de::Error) -> Option<(Range<usize>, String)> {
    let span = error.span()?;
    let root = DeTable::parse(text).ok()?.into_inner();
    let holds = |v: &Spanned<DeValue>| v.span().start <= span.start && span.end <= v.span().end;
    let found = if let Some(terrain) = root.get("terrain").filter(|v| holds(v)) {
        if let DeValue::Table(t) = terrain.get_ref()
            && let Some(soil) = t.get("soil")
            && !matches!(soil.get_ref(), DeValue::String(_) | DeValue::Table(_))
        {
            return Some((soil.span(), error.message().trim().to_string()));
        }
        terrain_error(terrain)
    } else if let Some(steering) = child(&root, &["control", "steering"]).filter(|v| holds(v)) {
        tagged(steering, |kind, value| match kind {
            "ackermann" => read::<Ackermann>(value),
            "heading" => read::<HeadingHold>(value),
            "slip" => read::<Slip>(value),
            _ => None,
        })
        .map(|e| ("control.steering", e))
    } else if let Some(law) = child(&root, &["contact", "law"]).filter(|v| holds(v)) {
        tagged(law, |kind, value| match kind {
            "chen_genta" => read::<ChenGenta>(value),
            "magic_formula" => read::<MagicFormula>(value),
            _ => None,
        })
        .map(|e| ("contact.law", e))
    } else {
        None
    };
    let (table, found) = found?;
    let refined = found.span()?;
    (refined != span).then(|| (refined, format!("{table}: {}", found.message().trim())))
}

/// The value at `path` below the root table.
fn child<'a, 'd>(root: &'d DeTable<'a>, path: &[&str]) -> Option<&'d Spanned<DeValue<'a>>> {
    let (first, rest) = path.split_first()?;
    let mut value = root.get(*first)?;
    for key in rest {
        let DeValue::Table(t) = value.get_ref() else {
            return None;
        };
        value = t.get(*key)?;
    }
    Some(value)
}

/// `T` read from `value`: its error, if any.
fn read<'de, T: Deserialize<'de>>(value: Spanned<DeValue<'de>>) -> Option<toml::de::Error> {
    T::deserialize(ValueDeserializer::from(value)).err()
}

/// The error of a table chosen by `kind`, read as the type `kind` names.
fn tagged<'a>(
    value: &Spanned<DeValue<'a>>,
    read: impl Fn(&str, Spanned<DeValue<'a>>) -> Option<toml::de::Error>,
) -> Option<toml::de::Error> {
    let DeValue::Table(table) = value.get_ref() else {
        return None;
    };
    let mut table = table.clone();
    let kind = table.remove("kind")?;
    let kind = kind.get_ref().as_str()?;
    read(kind, Spanned::new(value.span(), DeValue::Table(table)))
}

/// The error of `[terrain]`: of its soil table, else of its shape, with
/// the table's path.
fn terrain_error(value: &Spanned<DeValue<'_>>) -> Option<(&'static str, toml::de::Error)> {
    let DeValue::Table(table) = value.get_ref() else {
        return None;
    };
    let mut table = table.clone();
    // The soils by region and the ruts are read (and their errors named)
    // by the ground.
    for key in ["soil_map", "soil_patches", "ruts", "rut_cell"] {
        table.remove(key);
    }
    if let Some(soil) = table.remove("soil")
        && matches!(soil.get_ref(), DeValue::Table(_))
        && let Some(e) = read::<SoilConfig>(soil)
    {
        return Some(("terrain.soil", e));
    }
    tagged(
        &Spanned::new(value.span(), DeValue::Table(table)),
        |kind, value| match kind {
            "flat" => read::<FlatConfig>(value),
            "slope" => read::<SlopeConfig>(value),
            "bump" => read::<BumpConfig>(value),
            "ditch" => read::<DitchConfig>(value),
            "step" => read::<StepConfig>(value),
            "sinusoid" => read::<SinusoidConfig>(value),
            "random" => read::<RandomConfig>(value),
            "file" => read::<FileConfig>(value),
            _ => None,
        },
    )
    .map(|e| ("terrain", e))
}

/// The error at `span` of `text` as toml renders it: the line and column,
/// the line with a caret under the span, the message.
pub(crate) fn render(text: &str, span: Range<usize>, message: &str) -> String {
    let (line, column) = rover_spec::line_column(text.as_bytes(), span.start);
    let start = text[..span.start.min(text.len())]
        .rfind('\n')
        .map_or(0, |p| p + 1);
    let end = text[start..].find('\n').map_or(text.len(), |p| start + p);
    let source = &text[start..end];
    let width = line.to_string().len();
    let gutter = " ".repeat(width);
    let carets = text[span.start.min(end)..span.end.clamp(span.start.min(end), end)]
        .chars()
        .count()
        .max(1);
    format!(
        "TOML parse error at line {line}, column {column}\n{gutter} |\n{line} | {source}\n{gutter} | {}{}\n{message}\n",
        " ".repeat(column - 1),
        "^".repeat(carets)
    )
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::scenario::Scenario;

    /// `line, column` of the error of parsing `text`.
    fn at(text: &str) -> String {
        let e = Scenario::parse(text, Path::new("s.toml")).unwrap_err();
        let head = e.message.lines().next().unwrap_or_default().to_string();
        head.split_once("at line ")
            .map(|(_, l)| l.replace(" column ", ""))
            .unwrap_or(head)
    }

    #[test]
    fn value_errors_point_at_the_value_inside_kind_chosen_tables() {
        let seed = "rover = \"swing4\"\nduration = 10.0\nsettle = 1.0\noutput_rate = 20.0\n\n# rough ground\n\n[terrain]\nseed = -3\nkind = \"random\"\nz_r = 0.1\n";
        assert_eq!(at(seed), "9,8");
        let cases = [
            (
                "duration = 1.0\n[terrain]\nkind = \"random\"\nz_r = 0.1\nseed = \"x\"\n",
                "5,8",
            ),
            (
                "duration = 1.0\n[terrain]\nkind = \"slope\"\nangel_deg = 1.0\n",
                "4,1",
            ),
            (
                "duration = 1.0\n[terrain]\nkind = \"flat\"\nsoil = { n = \"x\" }\n",
                "4,14",
            ),
            (
                "duration = 1.0\n[terrain]\nkind = \"flat\"\nsoil = 5\n",
                "4,8",
            ),
            (
                "duration = 1.0\n[control.steering]\nkind = \"ackermann\"\nradius = \"x\"\n",
                "4,10",
            ),
            (
                "duration = 1.0\n[control.steering]\nkind = \"slip\"\ndelta_tau = true\n",
                "4,13",
            ),
            (
                "duration = 1.0\n[contact]\nlaw = { kind = \"magic_formula\", shape = \"x\" }\n",
                "3,41",
            ),
            // Outside such tables toml locates them itself.
            ("duration = 1.0\n[integrator.bdf]\nrtol = \"x\"\n", "3,8"),
        ];
        for (text, want) in cases {
            assert_eq!(at(text), want, "{text}");
        }
    }

    #[test]
    fn nesting_too_deep_is_located_with_a_sentence() {
        let deep = format!(
            "duration = 1.0\na = {}1{}\n",
            "[".repeat(10_000),
            "]".repeat(10_000)
        );
        let e = Scenario::parse(&deep, Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("line 2, column") && e.contains("nesting deeper than 80 levels"),
            "{e}"
        );
        let deep = format!("duration = 1.0\n\n{} = 1\n", vec!["a"; 100].join("."));
        assert_eq!(at(&deep), "3,1");
        let e = Scenario::parse(&deep, Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("nesting deeper") && !e.contains("recursion"),
            "{e}"
        );
    }
}
