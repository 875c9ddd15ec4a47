//! Mutations of a valid input file, for fuzzing its loader on stable Rust
//! (with proptest choosing the indices): a number replaced by a hostile
//! literal, bytes deleted or inserted.

/// Literals that a careless or hostile user might put where a number is.
pub const HOSTILE: &[&str] = &[
    "nan",
    "-inf",
    "inf",
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-320",
    "\"x\"",
    "[]",
    "[1, 2]",
    "{}",
    "[[1], [2], [3]]",
    "true",
    "99999999999999999999",
    "-1",
    "=",
    "[",
    "\"",
    "0.0001",
    "1e6",
    "1e12",
    "-1e12",
    "50.0",
    "\"\"",
    "\"\\u001b[2J\"",
    "\"\\u202e\"",
    "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]",
    "[[1, 0, 0], [0, 1, 0, 0, 0], [0, 0, 1]]",
    "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]",
];

/// The byte ranges of the unsigned decimal numbers of `text`.
pub fn numbers(text: &str) -> Vec<(usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_digit() {
            let start = i;
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            out.push((start, i));
        }
        i += 1;
    }
    out
}

/// `text` with its number `which` (modulo their count) replaced by
/// [`HOSTILE`]`[hostile]` (modulo its length); `text` if it has none.
pub fn replace_number(text: &str, which: usize, hostile: usize) -> String {
    replace_range(text, &numbers(text), which, hostile)
}

fn replace_range(text: &str, ranges: &[(usize, usize)], which: usize, hostile: usize) -> String {
    if ranges.is_empty() {
        return text.to_string();
    }
    let (a, b) = ranges[which % ranges.len()];
    format!(
        "{}{}{}",
        &text[..a],
        HOSTILE[hostile % HOSTILE.len()],
        &text[b..]
    )
}

/// The byte ranges of the quoted strings of `text` outside comments,
/// quotes included.
pub fn strings(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let code = line.split('#').next().unwrap_or("");
        let quotes: Vec<usize> = code.match_indices('"').map(|(i, _)| offset + i).collect();
        out.extend(quotes.chunks_exact(2).map(|q| (q[0], q[1] + 1)));
        offset += line.len();
    }
    out
}

/// `text` with its quoted string `which` (modulo their count) replaced by
/// [`HOSTILE`]`[hostile]` (modulo its length); `text` if it has none.
pub fn replace_string(text: &str, which: usize, hostile: usize) -> String {
    replace_range(text, &strings(text), which, hostile)
}

/// `text` with up to `len` bytes from `at` (modulo its length, on char
/// boundaries) replaced by `insert`.
pub fn splice(text: &str, at: usize, len: usize, insert: &str) -> String {
    if text.is_empty() {
        return insert.to_string();
    }
    let mut start = at % text.len();
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = (start + len).min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}{}{}", &text[..start], insert, &text[end..])
}
