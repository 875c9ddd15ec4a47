//! A TOML source kept beside its parsed tree, to turn a field path
//! (`wheel[2].radius`) into the bytes it came from, and back.

use std::ops::Range;

use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// One step of a field path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Segment {
    /// A table key.
    Key(String),
    /// An array index.
    Index(usize),
}

/// Split a field path such as `suspension[0].coordinate.min_deg`.
pub fn parse_path(path: &str) -> Vec<Segment> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !key.is_empty() {
            out.push(Segment::Key(key.to_string()));
        }
        while let Some(stripped) = rest.strip_prefix('[') {
            let Some(end) = stripped.find(']') else { break };
            if let Ok(i) = stripped[..end].parse() {
                out.push(Segment::Index(i));
            }
            rest = &stripped[end + 1..];
        }
    }
    out
}

/// Join path segments back into text.
fn join(segments: &[Segment]) -> String {
    let mut s = String::new();
    for seg in segments {
        match seg {
            Segment::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Segment::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// The parsed source of a description.
pub struct Document<'a> {
    root: Option<Spanned<DeTable<'a>>>,
}

impl<'a> Document<'a> {
    /// Parse `text`; a document with a syntax error locates nothing.
    pub fn parse(text: &'a str) -> Self {
        Document {
            root: DeTable::parse(text).ok(),
        }
    }

    /// The span of the value at `path`, or of its longest prefix present in
    /// the file (a missing field points at the table that lacks it), with
    /// whether the whole path was found.
    pub fn locate(&self, path: &str) -> Option<(Range<usize>, bool)> {
        let root = self.root.as_ref()?;
        let segments = parse_path(path);
        let mut span = None;
        let mut table: Option<&DeTable> = Some(root.get_ref());
        let mut array: Option<&[Spanned<DeValue>]> = None;
        for seg in &segments {
            let value: &Spanned<DeValue> = match seg {
                Segment::Key(k) => {
                    let Some(t) = table else {
                        return span.map(|s| (s, false));
                    };
                    let Some((_, v)) = t
                        .iter()
                        .find(|(key, _)| key.get_ref().as_ref() == k.as_str())
                    else {
                        return span.map(|s| (s, false));
                    };
                    v
                }
                Segment::Index(i) => {
                    let Some(v) = array.and_then(|a| a.get(*i)) else {
                        return span.map(|s| (s, false));
                    };
                    v
                }
            };
            span = Some(value.span());
            table = None;
            array = None;
            match value.get_ref() {
                DeValue::Table(t) => table = Some(t),
                DeValue::Array(a) => array = Some(a),
                _ => {}
            }
        }
        span.map(|s| (s, true))
    }

    /// The path of the innermost value whose span holds `span`. (The span
    /// of a `[[table]]` covers only its header, so a value is searched for
    /// through its children too.)
    pub fn path_at(&self, span: &Range<usize>) -> String {
        let Some(root) = self.root.as_ref() else {
            return String::new();
        };
        let mut path = Vec::new();
        let mut node = DeNode::Table(root.get_ref());
        'walk: loop {
            let children: Vec<Child> = match node {
                DeNode::Table(t) => t
                    .iter()
                    .map(|(k, v)| (Segment::Key(k.get_ref().to_string()), Some(k.span()), v))
                    .collect(),
                DeNode::Array(a) => a
                    .iter()
                    .enumerate()
                    .map(|(i, v)| (Segment::Index(i), None, v))
                    .collect(),
            };
            for (seg, key, child) in children {
                // An error on a key (unknown field) points at the key itself.
                if key.is_some_and(|k| k.start <= span.start && span.end <= k.end) {
                    path.push(seg);
                    break 'walk;
                }
                if holds(child, span) {
                    path.push(seg);
                    match child.get_ref() {
                        DeValue::Table(t) => node = DeNode::Table(t),
                        DeValue::Array(a) => node = DeNode::Array(a),
                        _ => break 'walk,
                    }
                    continue 'walk;
                }
            }
            break;
        }
        join(&path)
    }
}

impl Document<'_> {
    /// Where an unknown key `key` sits: the first table (in file order)
    /// holding it whose other keys are all in `expected` (the table serde
    /// was reading). Gives the key's path and the key's span.
    pub fn find_unknown_key(&self, key: &str, expected: &[&str]) -> Option<(String, Range<usize>)> {
        let root = self.root.as_ref()?;
        let mut found: Option<(String, Range<usize>)> = None;
        let mut stack: Vec<(Vec<Segment>, DeNode)> =
            vec![(Vec::new(), DeNode::Table(root.get_ref()))];
        while let Some((path, node)) = stack.pop() {
            match node {
                DeNode::Table(t) => {
                    let holds = t.iter().find(|(k, _)| k.get_ref().as_ref() == key);
                    let fits = t.iter().all(|(k, _)| {
                        let k = k.get_ref().as_ref();
                        k == key || k == "kind" || expected.contains(&k)
                    });
                    if let (Some((k, _)), true) = (holds, fits)
                        && found.as_ref().is_none_or(|f| k.span().start < f.1.start)
                    {
                        let mut p = path.clone();
                        p.push(Segment::Key(key.to_string()));
                        found = Some((join(&p), k.span()));
                    }
                    for (k, v) in t.iter() {
                        let mut p = path.clone();
                        p.push(Segment::Key(k.get_ref().to_string()));
                        match v.get_ref() {
                            DeValue::Table(t) => stack.push((p, DeNode::Table(t))),
                            DeValue::Array(a) => stack.push((p, DeNode::Array(a))),
                            _ => {}
                        }
                    }
                }
                DeNode::Array(a) => {
                    for (i, v) in a.iter().enumerate() {
                        let mut p = path.clone();
                        p.push(Segment::Index(i));
                        match v.get_ref() {
                            DeValue::Table(t) => stack.push((p, DeNode::Table(t))),
                            DeValue::Array(a) => stack.push((p, DeNode::Array(a))),
                            _ => {}
                        }
                    }
                }
            }
        }
        found
    }
}

/// Whether `value` or anything inside it spans `span`.
fn holds(value: &Spanned<DeValue>, span: &Range<usize>) -> bool {
    let s = value.span();
    if s.start <= span.start && span.end <= s.end {
        return true;
    }
    match value.get_ref() {
        DeValue::Table(t) => t.iter().any(|(k, v)| {
            let k = k.span();
            (k.start <= span.start && span.end <= k.end) || holds(v, span)
        }),
        DeValue::Array(a) => a.iter().any(|v| holds(v, span)),
        _ => false,
    }
}

/// A child while walking the tree: its path step, its key's span (tables)
/// and its value.
type Child<'d, 'a> = (Segment, Option<Range<usize>>, &'d Spanned<DeValue<'a>>);

/// A container while walking the tree.
#[derive(Clone, Copy)]
enum DeNode<'d, 'a> {
    Table(&'d DeTable<'a>),
    Array(&'d [Spanned<DeValue<'a>>]),
}
