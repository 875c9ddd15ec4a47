//! Tick labels: shortest decimal form, and never `-0`.

use plotters::data::float::FloatPrettyPrinter;

/// The label of an axis tick at `value`: up to 5 decimals, trailing zeros
/// trimmed, and a rounded-off negative zero written `0`.
pub(crate) fn tick_label(value: &f64) -> String {
    let text = FloatPrettyPrinter {
        allow_scientific: false,
        min_decimal: 0,
        max_decimal: 5,
    }
    .print(*value);
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

#[cfg(test)]
mod tests {
    use super::tick_label;

    #[test]
    fn labels_are_short_and_never_negative_zero() {
        assert_eq!(tick_label(&-1.0e-17), "0");
        assert_eq!(tick_label(&0.0), "0");
        assert_eq!(tick_label(&-0.5), "-0.5");
        assert_eq!(tick_label(&20.0), "20");
        assert_eq!(tick_label(&0.31), "0.31");
    }
}
