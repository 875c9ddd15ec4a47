//! Names must be unique: suspensions among suspensions, carried bodies
//! (wheels and masses) among themselves, coordinates among coordinates.

use crate::checks::Ctx;

/// Report every name that repeats an earlier one, at the repeat.
/// `items` are (name, path of its `name` field, what it is).
pub fn check_unique(ctx: &mut Ctx, items: &[(String, String, &str)]) {
    for (k, (name, path, what)) in items.iter().enumerate() {
        if let Some((_, first, first_what)) = items[..k].iter().find(|(n, _, _)| n == name) {
            ctx.error(
                path.clone(),
                format!("the name `{name}` of this {what} is already used by the {first_what} at `{first}`"),
                "names identify things in messages, CSV columns and references: give each a distinct name",
            );
        }
    }
}

/// Every string of the description is printable text, and every name is
/// not empty: names head reports, label CSV columns and plots, and appear
/// in messages and generated code, where a control character (a terminal
/// escape sequence, say) would act instead of being read. Returns whether
/// a string holds a control character (the caller then stops: later
/// messages would quote it).
pub fn check_strings(ctx: &mut Ctx, value: &toml::Value) -> bool {
    let mut control = false;
    crate::checks::each_leaf(value, "", &mut |v, path| {
        let toml::Value::String(s) = v else { return };
        if let Some(c) = s.chars().find(|&c| unprintable(c)) {
            control = true;
            ctx.error(
                path,
                format!(
                    "{s:?} holds the unprintable character U+{:04X}",
                    u32::from(c)
                ),
                "names and other strings are printed in reports, messages, CSV headers and generated code: use printable characters only",
            );
        } else if path.ends_with(".name") && s.trim().is_empty() {
            ctx.error(
                path,
                format!("the name {s:?} is empty"),
                "give it a name: names identify things in messages, CSV columns and references",
            );
        }
    });
    control
}

/// A control character (C0, DEL, C1) or a bidirectional formatting
/// character, which reorders the text around it on a terminal.
pub fn unprintable(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}
