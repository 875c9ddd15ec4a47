//! Numbers as rover's text outputs write them (CSV rows, grids): as Rust's
//! `{}` writes an `f64` — the shortest digits that read back to the same
//! bits, without an exponent — with the digits found by `zmij`'s
//! shortest-digit search, several times faster than the standard
//! formatter's. A run's CSV rows are written inside its timed loop, and a
//! rut map's grids hold millions of numbers. The text is `{}`'s byte for
//! byte but where two shortest forms are equally near the value (its exact
//! decimal expansion ends in a 5 just past them): `zmij` then takes the even
//! last digit, `{}` the one above; both read back to the same bits.

/// Digits kept in the fast path: values whose decimal point falls further
/// than this from their digits (below 1e-30 or above 1e30, in no output
/// of ours) are written by the standard formatter.
const FAST_POINT: i32 = 30;

/// `v` as `format!("{v}")` writes it (up to the tie above), appended to
/// `out`.
pub fn push_f64(out: &mut String, v: f64) {
    let mut buf = [0u8; 80];
    match fast(v, &mut buf) {
        Some(text) => out.push_str(text),
        None => {
            use std::fmt::Write;
            let _ = write!(out, "{v}");
        }
    }
}

/// `v` as `write!(out, "{v}")` writes it (up to the tie above).
pub fn write_f64<W: std::io::Write + ?Sized>(out: &mut W, v: f64) -> std::io::Result<()> {
    let mut buf = [0u8; 80];
    match fast(v, &mut buf) {
        Some(text) => out.write_all(text.as_bytes()),
        None => write!(out, "{v}"),
    }
}

/// The fast path: `None` for a value it leaves to the standard formatter
/// (not finite, or its point far from its digits).
fn fast(v: f64, buf: &mut [u8; 80]) -> Option<&str> {
    if !v.is_finite() {
        return None;
    }
    if v == 0.0 {
        return Some(if v.is_sign_negative() { "-0" } else { "0" });
    }
    let mut z = zmij::Buffer::new();
    let text = z.format_finite(v).as_bytes();
    let (negative, text) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        _ => (false, text),
    };
    // `mantissa` (digits with at most one '.') times 10^`exponent`.
    let (mantissa, exponent) = match text.iter().position(|&c| c == b'e') {
        Some(e) => (
            &text[..e],
            std::str::from_utf8(&text[e + 1..])
                .ok()?
                .parse::<i32>()
                .ok()?,
        ),
        None => (text, 0),
    };
    // The significant digits and the number of them before the point.
    let mut digits = [0u8; 40];
    let mut n = 0;
    let mut point = mantissa.len() as i32;
    for (k, &c) in mantissa.iter().enumerate() {
        if c == b'.' {
            point = k as i32;
        } else {
            *digits.get_mut(n)? = c;
            n += 1;
        }
    }
    point += exponent;
    let first = digits[..n].iter().position(|&c| c != b'0')?;
    let last = digits[..n].iter().rposition(|&c| c != b'0')? + 1;
    point -= first as i32;
    let digits = &digits[first..last];
    if !(-FAST_POINT..=FAST_POINT).contains(&point) {
        return None;
    }
    let mut len = 0;
    let mut put = |bytes: &[u8]| {
        buf[len..len + bytes.len()].copy_from_slice(bytes);
        len += bytes.len();
    };
    if negative {
        put(b"-");
    }
    let whole = point.max(0) as usize;
    if point <= 0 {
        put(b"0.");
        for _ in 0..-point {
            put(b"0");
        }
        put(digits);
    } else if whole >= digits.len() {
        put(digits);
        for _ in digits.len()..whole {
            put(b"0");
        }
    } else {
        put(&digits[..whole]);
        put(b".");
        put(&digits[whole..]);
    }
    std::str::from_utf8(&buf[..len]).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pushed(v: f64) -> String {
        let mut s = String::new();
        push_f64(&mut s, v);
        s
    }

    /// What `{}` writes, or, where the value lies halfway between two
    /// shortest forms, the one below it: the same length and digits but
    /// the last, one less, both reading back to the value.
    fn assert_as_standard(v: f64) {
        let (got, want) = (pushed(v), format!("{v}"));
        if got != want {
            let tie = got.len() == want.len()
                && got[..got.len() - 1] == want[..want.len() - 1]
                && got.parse::<f64>().ok().map(f64::to_bits) == Some(v.to_bits())
                && {
                    let (a, b) = (
                        got.as_bytes()[got.len() - 1],
                        want.as_bytes()[want.len() - 1],
                    );
                    // The one below in magnitude: `2` for `3`, also for a
                    // negative value's text.
                    a + 1 == b && (a - b'0').is_multiple_of(2)
                };
            assert!(tie, "{v:e} ({:#x}): {got} against {want}", v.to_bits());
        }
        let mut w = Vec::new();
        write_f64(&mut w, v).unwrap();
        assert_eq!(w, got.into_bytes());
    }

    /// As `{}` writes them at chosen values, and at values spread over
    /// every decade the fast path takes and beyond it, from a fixed
    /// sequence of bit patterns.
    #[test]
    fn numbers_are_written_as_the_standard_formatter_writes_them() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.2 + 0.1,
            1.0 / 3.0,
            -2.5e-7,
            123_456_789.0,
            1e15,
            1e16,
            1e21,
            1.5e30,
            9.99e-31,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::EPSILON,
            0.000_123,
            -98_765.432_1,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            assert_eq!(pushed(v), format!("{v}"), "{v:e}");
        }
        // A tie: -1149636667324797.25 is as near ….2 as ….3.
        assert_eq!(
            pushed(f64::from_bits(0xc310_565a_94b4_e5f5)),
            "-1149636667324797.2"
        );
        // xorshift over bit patterns, each mapped into decades 1e-40..1e40
        // (its exponent field replaced), and raw.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut ties = 0;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let raw = f64::from_bits(state);
            let exponent = 1023 - 133 + (state >> 52) % 266;
            let spread = f64::from_bits((state & !(0x7ff << 52)) | (exponent << 52));
            for v in [raw, spread] {
                assert_as_standard(v);
                ties += usize::from(pushed(v) != format!("{v}"));
            }
        }
        // Ties come where the spacing of doubles has few decimals (above
        // 2^50, where it is a quarter or more).
        assert!(ties > 0, "no tie met: the tie case is not exercised");
    }
}
