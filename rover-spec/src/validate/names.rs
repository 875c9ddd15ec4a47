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
