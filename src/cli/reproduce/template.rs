//! The report's prose lives in `report.md`; the code fills its
//! `{{placeholders}}` with numbers, tables and figure lists.

use super::runs::other;
use crate::error::CliError;

/// The values of a report's placeholders.
#[derive(Default)]
pub struct Values(Vec<(String, String)>);

impl Values {
    /// Set `{{key}}` to `value`.
    pub fn set(&mut self, key: &str, value: impl Into<String>) {
        self.0.push((key.into(), value.into()));
    }

    /// Set `{{key}}` to a number with `digits` decimals.
    pub fn num(&mut self, key: &str, value: f64, digits: usize) {
        self.set(key, format!("{value:.digits$}"));
    }
}

/// `template` with every `{{key}}` replaced; a placeholder without a value,
/// or a value without its placeholder, is an error (the template and the
/// code must agree).
pub fn render(template: &str, values: &Values) -> Result<String, CliError> {
    let mut out = String::with_capacity(template.len() * 2);
    let mut rest = template;
    let mut used = vec![false; values.0.len()];
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let after = &rest[start + 2..];
        let end = after
            .find("}}")
            .ok_or_else(|| other("report template: `{{` without `}}`"))?;
        let key = &after[..end];
        let k = values
            .0
            .iter()
            .position(|(k, _)| k == key)
            .ok_or_else(|| other(format!("report template: no value for {{{{{key}}}}}")))?;
        used[k] = true;
        out.push_str(&values.0[k].1);
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    if let Some(k) = used.iter().position(|u| !u) {
        return Err(other(format!(
            "report template: {{{{{}}}}} is set but not in the template",
            values.0[k].0
        )));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_are_filled_and_mismatches_refused() {
        let mut v = Values::default();
        v.set("a", "one");
        v.num("b", 2.345, 1);
        assert_eq!(render("x {{a}} y {{b}}.", &v).unwrap(), "x one y 2.3.");
        assert!(render("{{a}} {{c}}", &v).is_err());
        assert!(render("{{a}}", &v).is_err());
    }
}
