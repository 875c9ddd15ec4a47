//! An inertia tensor as written in a description: the diagonal short form
//! `[Jxx, Jyy, Jzz]` or the full symmetric matrix `[[..], [..], [..]]`.

use serde::de::{self, SeqAccess, Visitor};
use serde::ser::SerializeSeq;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// An inertia tensor [kg·m²] about a centre of mass, body components.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Inertia {
    /// Principal moments `[Jxx, Jyy, Jzz]` along the body axes.
    Diagonal([f64; 3]),
    /// The full symmetric tensor, rows in order x, y, z (off-diagonal entries
    /// are tensor components, i.e. `J_xy = −∫ x·y dm`).
    Full([[f64; 3]; 3]),
}

impl Inertia {
    /// The 3×3 matrix.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        match *self {
            Inertia::Diagonal([a, b, c]) => [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, c]],
            Inertia::Full(m) => m,
        }
    }
}

impl Serialize for Inertia {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Inertia::Diagonal(d) => d.serialize(serializer),
            Inertia::Full(rows) => {
                let mut seq = serializer.serialize_seq(Some(3))?;
                for row in rows {
                    seq.serialize_element(row)?;
                }
                seq.end()
            }
        }
    }
}

/// One element of the inertia array: a number (diagonal form) or a row.
enum Element {
    Number(f64),
    Row([f64; 3]),
}

impl<'de> Deserialize<'de> for Element {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ElementVisitor;
        impl<'de> Visitor<'de> for ElementVisitor {
            type Value = Element;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or a row of 3 numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Element, E> {
                Ok(Element::Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Element, E> {
                Ok(Element::Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Element, E> {
                Ok(Element::Number(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Element, A::Error> {
                let mut row = [0.0; 3];
                let mut len = 0;
                while let Some(v) = seq.next_element::<f64>()? {
                    if let Some(slot) = row.get_mut(len) {
                        *slot = v;
                    }
                    len += 1;
                }
                if len != 3 {
                    return Err(de::Error::custom(format!(
                        "a row of the inertia matrix has {len} number{}, not 3: the matrix is 3×3, [[Jxx, Jxy, Jxz], [Jxy, Jyy, Jyz], [Jxz, Jyz, Jzz]]",
                        if len == 1 { "" } else { "s" }
                    )));
                }
                Ok(Element::Row(row))
            }
        }
        deserializer.deserialize_any(ElementVisitor)
    }
}

impl<'de> Deserialize<'de> for Inertia {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct InertiaVisitor;
        impl<'de> Visitor<'de> for InertiaVisitor {
            type Value = Inertia;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("[Jxx, Jyy, Jzz] or a 3×3 matrix [[..], [..], [..]]")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Inertia, A::Error> {
                let mut items = Vec::new();
                while let Some(e) = seq.next_element::<Element>()? {
                    if items.len() == 3 {
                        return Err(de::Error::custom(match e {
                            Element::Number(_) => {
                                "has more than 3 numbers: write the diagonal [Jxx, Jyy, Jzz] or the 3×3 matrix [[..], [..], [..]]"
                            }
                            Element::Row(_) => {
                                "has more than 3 rows: the inertia matrix is 3×3, [[..], [..], [..]]"
                            }
                        }));
                    }
                    items.push(e);
                }
                match items.as_slice() {
                    [Element::Number(a), Element::Number(b), Element::Number(c)] => {
                        Ok(Inertia::Diagonal([*a, *b, *c]))
                    }
                    [Element::Row(a), Element::Row(b), Element::Row(c)] => {
                        Ok(Inertia::Full([*a, *b, *c]))
                    }
                    [_, _, _] => Err(de::Error::custom(
                        "mixes numbers and rows: write [Jxx, Jyy, Jzz] or [[..], [..], [..]]",
                    )),
                    _ => Err(de::Error::invalid_length(items.len(), &self)),
                }
            }
        }
        deserializer.deserialize_seq(InertiaVisitor)
    }
}
