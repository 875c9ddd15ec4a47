//! Fewer operations by regrouping sums: the one place where the generator
//! reassociates (the graph itself never does, see [`crate::graph`]).
//!
//! Every maximal tree of additions, negations and multiplications by a
//! constant whose inner nodes have a single user is read as a linear form
//! `c0 + Σ c_i·t_i` over its other nodes (the terms), and rebuilt with
//! - constant factors multiplied out: `0.6·(0.2·t)` → `0.12·t`;
//! - like terms merged: `t + t + t + t` → `4·t`, `a·t − a·t` → nothing;
//! - one multiplication per distinct coefficient: `0.6·t1 + 0.6·t2 + 0.6·t3`
//!   → `0.6·(t1 + t2 + t3)`;
//! - one multiplication per shared factor: products that only the sum uses
//!   are kept as their factors and factored greedily, `a·x + a·y + b·x`
//!   → `a·(x + y) + b·x` (10–12 % fewer multiplications in every model's
//!   right-hand side);
//! - constants summed into one.
//!
//! Reassociation changes rounding, so generated code agrees with the
//! generic plant to a few ulps per sum rather than bit for bit; the tests
//! hold the two to 1e-12 relative.

use std::collections::HashMap;

use crate::graph::{Graph, Id, Node};
use crate::trace::{Function, OutputVar};

/// A linear form `constant + Σ coefficient·term` over new-graph terms.
#[derive(Default)]
struct Linear {
    constant: f64,
    /// (term, coefficient), first appearance first.
    terms: Vec<(Id, f64)>,
    /// (a, b, coefficient) for terms `coefficient·a·b` whose product has
    /// no other user: factored before they are built (see [`Rebuild::factor`]).
    products: Vec<(Id, Id, f64)>,
    /// Position of each term in `terms`.
    index: HashMap<Id, usize>,
}

impl Linear {
    fn add_term(&mut self, term: Id, coefficient: f64) {
        match self.index.get(&term) {
            Some(&k) => self.terms[k].1 += coefficient,
            None => {
                self.index.insert(term, self.terms.len());
                self.terms.push((term, coefficient));
            }
        }
    }
}

struct Rebuild<'a> {
    old: &'a Graph,
    uses: Vec<usize>,
    new: Graph,
    map: Vec<Option<Id>>,
}

impl Rebuild<'_> {
    /// Whether node `k` is an inner node of a linear tree (absorbed by its
    /// single user when that user is linear too).
    fn is_linear(&self, id: Id) -> bool {
        match self.old.node(id) {
            Node::Add(..) | Node::Neg(_) => true,
            Node::Mul(a, b) => self.old.value(a).is_some() || self.old.value(b).is_some(),
            _ => false,
        }
    }

    /// Accumulate `scale·(old node id)` into `form`.
    fn collect(&mut self, id: Id, scale: f64, form: &mut Linear, root: bool) {
        let k = id.0 as usize;
        let inner = root || (self.uses[k] == 1 && self.is_linear(id));
        if let Some(v) = self.old.value(id) {
            form.constant += scale * v;
            return;
        }
        if !inner {
            self.term(id, scale, form);
            return;
        }
        match self.old.node(id) {
            Node::Add(a, b) => {
                self.collect(a, scale, form, false);
                self.collect(b, scale, form, false);
            }
            Node::Neg(a) => self.collect(a, -scale, form, false),
            Node::Mul(a, b) => match (self.old.value(a), self.old.value(b)) {
                (Some(c), _) => self.collect(b, scale * c, form, false),
                (_, Some(c)) => self.collect(a, scale * c, form, false),
                // Not linear after all: a term.
                _ => self.term(id, scale, form),
            },
            _ => self.term(id, scale, form),
        }
    }

    /// `scale·(old node id)` as a term of `form`: a product of two
    /// non-constants that only this sum uses is kept as its factors.
    fn term(&mut self, id: Id, scale: f64, form: &mut Linear) {
        if let Node::Mul(a, b) = self.old.node(id)
            && self.uses[id.0 as usize] == 1
        {
            let (a, b) = (self.get(a), self.get(b));
            form.products.push((a, b, scale));
            return;
        }
        let t = self.get(id);
        form.add_term(t, scale);
    }

    /// The new node of old node `id`, built on first request.
    fn get(&mut self, id: Id) -> Id {
        let k = id.0 as usize;
        if let Some(n) = self.map[k] {
            return n;
        }
        let built = if self.is_linear(id) {
            let mut form = Linear::default();
            self.collect(id, 1.0, &mut form, true);
            self.emit(&form)
        } else {
            let node = self.old.node(id);
            let mut kids = node.children().map(|c| self.get(c));
            let (a, b) = (kids.next(), kids.next());
            let g = &mut self.new;
            let a = || a.unwrap_or(Id(0));
            let b = || b.unwrap_or(Id(0));
            match node {
                Node::Const(bits) => g.cst(f64::from_bits(bits)),
                Node::Input(i) => g.input(i),
                Node::Mul(..) => g.mul(a(), b()),
                Node::Div(..) => g.div(a(), b()),
                Node::Sin(_) => g.sin(a()),
                Node::Cos(_) => g.cos(a()),
                Node::Sqrt(_) => g.sqrt(a()),
                Node::Exp(_) => g.exp(a()),
                Node::Ln(_) => g.ln(a()),
                Node::Abs(_) => g.abs(a()),
                Node::Atan2(..) => g.atan2(a(), b()),
                Node::Max(..) => g.max(a(), b()),
                Node::Min(..) => g.min(a(), b()),
                Node::Copysign(..) => g.copysign(a(), b()),
                Node::Ge(..) => g.ge(a(), b()),
                // Linear nodes are rebuilt as forms above; kept total.
                Node::Add(..) => g.add(a(), b()),
                Node::Neg(_) => g.neg(a()),
            }
        };
        self.map[k] = Some(built);
        built
    }

    /// `c0 + Σ c·(Σ ± t)`: one product per distinct |coefficient|, every
    /// sum a balanced tree (depth log₂ of its terms, not their number:
    /// the generated code is bound by its longest chain of dependent
    /// operations more than by their count).
    fn emit(&mut self, form: &Linear) -> Id {
        let (sum, negative) = self.emit_signed(form);
        if negative { self.new.neg(sum) } else { sum }
    }

    /// [`Rebuild::emit`] as a sum and whether it is to be negated.
    fn emit_signed(&mut self, form: &Linear) -> (Id, bool) {
        let mut terms = form.terms.clone();
        self.factor(&form.products, &mut terms);
        let mut groups: Vec<(f64, Vec<(Id, bool)>)> = Vec::new();
        for &(t, c) in &terms {
            if c == 0.0 {
                continue;
            }
            let (m, negative) = (c.abs(), c < 0.0);
            match groups.iter_mut().find(|(g, _)| *g == m) {
                Some((_, members)) => members.push((t, negative)),
                None => groups.push((m, vec![(t, negative)])),
            }
        }
        let g = &mut self.new;
        let mut scaled: Vec<(Id, bool)> = groups
            .into_iter()
            .map(|(m, members)| {
                let (sum, negative) = balanced(g, &members);
                if m == 1.0 {
                    (sum, negative)
                } else {
                    let c = g.cst(m);
                    (g.mul(c, sum), negative)
                }
            })
            .collect();
        if form.constant != 0.0 {
            let c = g.cst(form.constant.abs());
            scaled.push((c, form.constant < 0.0));
        }
        if scaled.is_empty() {
            return (g.cst(0.0), false);
        }
        balanced(g, &scaled)
    }

    /// Σ c·a·b as terms, one product per shared factor: greedily, the
    /// factor in the most products is taken out, `f·(Σ c·other)`, until
    /// no factor is in two (multivariate Horner; `mu_x·r + mu_y·r + …`
    /// over four wheels becomes `r·(mu_x + mu_y + …)`).
    fn factor(&mut self, products: &[(Id, Id, f64)], terms: &mut Vec<(Id, f64)>) {
        let mut rest = products.to_vec();
        loop {
            let mut count: Vec<(Id, usize)> = Vec::new();
            for &(a, b, _) in &rest {
                // A square a·a holds its factor once.
                for f in [a, b].into_iter().take(if a == b { 1 } else { 2 }) {
                    match count.iter_mut().find(|(g, _)| *g == f) {
                        Some((_, n)) => *n += 1,
                        None => count.push((f, 1)),
                    }
                }
            }
            // The most shared factor, first appearance on ties.
            let Some(&(f, n)) = count.iter().rev().max_by_key(|(_, n)| *n) else {
                break;
            };
            if n < 2 {
                break;
            }
            let mut inner = Linear::default();
            rest.retain(|&(a, b, c)| {
                let other = if a == f {
                    b
                } else if b == f {
                    a
                } else {
                    return true;
                };
                inner.add_term(other, c);
                false
            });
            let (sum, negative) = self.emit_signed(&inner);
            let p = self.new.mul(f, sum);
            terms.push((p, if negative { -1.0 } else { 1.0 }));
        }
        for (a, b, c) in rest {
            let p = self.new.mul(a, b);
            terms.push((p, c));
        }
    }
}

/// `Σ ±t` as a balanced tree of additions and subtractions; returns the
/// sum and whether it is to be negated.
fn balanced(g: &mut Graph, leaves: &[(Id, bool)]) -> (Id, bool) {
    match leaves {
        [] => (g.cst(0.0), false),
        [one] => *one,
        // Short sums stay chains: a tree keeps more partial sums live.
        _ if leaves.len() <= CHAIN => {
            let (mut acc, mut neg) = leaves[0];
            for &(t, n) in &leaves[1..] {
                (acc, neg) = join(g, (acc, neg), (t, n));
            }
            (acc, neg)
        }
        _ => {
            let (left, right) = leaves.split_at(leaves.len() / 2);
            let a = balanced(g, left);
            let b = balanced(g, right);
            join(g, a, b)
        }
    }
}

/// Longest sum kept as a chain of additions.
const CHAIN: usize = 8;

/// `±a ± b` as one addition or subtraction and a sign.
fn join(g: &mut Graph, (a, na): (Id, bool), (b, nb): (Id, bool)) -> (Id, bool) {
    match (na, nb) {
        (false, false) => (g.add(a, b), false),
        (true, true) => (g.add(a, b), true),
        (false, true) => (g.sub(a, b), false),
        (true, false) => (g.sub(b, a), false),
    }
}

/// `f` with its sums regrouped (see the module docs); same inputs, outputs
/// and groups.
pub fn simplify(f: &Function) -> Function {
    let old = &f.graph;
    let top = old.len();
    let mut uses = vec![0usize; top];
    let mut reach = vec![false; top];
    for o in &f.outputs {
        reach[o.id.0 as usize] = true;
        // An output is used outside: never absorbed.
        uses[o.id.0 as usize] += 2;
    }
    for k in (0..top).rev() {
        if reach[k] {
            for c in old.node(Id(k as u32)).children() {
                uses[c.0 as usize] += 1;
                reach[c.0 as usize] = true;
            }
        }
    }
    let mut r = Rebuild {
        old,
        uses,
        new: Graph::new(),
        map: vec![None; top],
    };
    // Inputs first, in order, so that input k is still node `Input(k)`.
    for k in 0..top {
        if let Node::Input(_) = old.node(Id(k as u32)) {
            r.get(Id(k as u32));
        }
    }
    // Then every node that is not absorbed into its user's sum, children
    // first (index order is topological), so that building one never
    // recurses deeper than one sum.
    let mut user = vec![None; top];
    for k in 0..top {
        if reach[k] {
            for c in old.node(Id(k as u32)).children() {
                user[c.0 as usize] = Some(Id(k as u32));
            }
        }
    }
    for k in 0..top {
        let id = Id(k as u32);
        let absorbed = r.uses[k] == 1 && r.is_linear(id) && user[k].is_some_and(|u| r.is_linear(u));
        if reach[k] && !absorbed {
            r.get(id);
        }
    }
    let outputs = f
        .outputs
        .iter()
        .map(|o| OutputVar {
            id: r.get(o.id),
            place: o.place.clone(),
            group: o.group,
        })
        .collect();
    Function {
        graph: r.new,
        inputs: f.inputs.clone(),
        outputs,
        groups: f.groups.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn function(build: impl FnOnce(&mut Graph) -> Vec<Id>) -> Function {
        Function::for_test(&["x0", "x1", "x2"], build)
    }

    fn ops(f: &Function) -> usize {
        let (_, count) = crate::emit::emit(f, "::libm");
        count.add + count.mul + count.neg
    }

    #[test]
    fn regrouped_sums_take_fewer_operations_and_keep_their_value() {
        let f = function(|g| {
            let (x, y, z) = (g.input(0), g.input(1), g.input(2));
            let (c6, c2, c3) = (g.cst(0.6), g.cst(0.2), g.cst(0.3));
            let xy = g.mul(x, y);
            // 0.6·(0.2·xy) + 0.6·z + 0.6·x − xy − xy + 0.3 + z·(x + 0.3)
            let a = g.mul(c2, xy);
            let a = g.mul(c6, a);
            let b = g.mul(c6, z);
            let c = g.mul(c6, x);
            let s = g.add(a, b);
            let s = g.add(s, c);
            let s = g.sub(s, xy);
            let s = g.sub(s, xy);
            let s = g.add(s, c3);
            let x3 = g.add(x, c3);
            let p = g.mul(z, x3);
            vec![g.add(s, p)]
        });
        let g = simplify(&f);
        assert!(ops(&g) < ops(&f), "{} → {}", ops(&f), ops(&g));
        for v in [[0.3, -1.7, 2.5], [1e3, 1e-3, -7.0], [0.0, 0.0, 0.0]] {
            let a = f.graph.eval(&v, &[f.outputs[0].id])[0];
            let b = g.graph.eval(&v, &[g.outputs[0].id])[0];
            assert!(
                (a - b).abs() <= 1e-14 * a.abs().max(1.0),
                "{a} vs {b} at {v:?}"
            );
        }
    }

    #[test]
    fn a_factor_shared_by_products_is_multiplied_once() {
        // x·y + 0.6·x·z − x·x + y·z: x is in three products, so
        // x·(y + 0.6·z − x) + y·z, three multiplications instead of five.
        let f = function(|g| {
            let (x, y, z) = (g.input(0), g.input(1), g.input(2));
            let c6 = g.cst(0.6);
            let xy = g.mul(x, y);
            let xz = g.mul(x, z);
            let xz = g.mul(c6, xz);
            let xx = g.mul(x, x);
            let yz = g.mul(y, z);
            let s = g.add(xy, xz);
            let s = g.sub(s, xx);
            vec![g.add(s, yz)]
        });
        let g = simplify(&f);
        let (_, before) = crate::emit::emit(&f, "::libm");
        let (_, after) = crate::emit::emit(&g, "::libm");
        assert_eq!((before.mul, after.mul), (5, 3));
        for v in [[0.3, -1.7, 2.5], [1e3, 1e-3, -7.0], [0.0, 0.0, 0.0]] {
            let a = f.graph.eval(&v, &[f.outputs[0].id])[0];
            let b = g.graph.eval(&v, &[g.outputs[0].id])[0];
            assert!(
                (a - b).abs() <= 1e-14 * a.abs().max(1.0),
                "{a} vs {b} at {v:?}"
            );
        }
    }

    #[test]
    fn shared_sums_are_computed_once() {
        let f = function(|g| {
            let (x, y, z) = (g.input(0), g.input(1), g.input(2));
            let s = g.add(x, y);
            let a = g.mul(s, z);
            let b = g.mul(s, x);
            vec![a, b]
        });
        let g = simplify(&f);
        assert_eq!(ops(&g), ops(&f));
    }

    #[test]
    fn cancelling_terms_vanish() {
        let f = function(|g| {
            let (x, y) = (g.input(0), g.input(1));
            let c = g.cst(2.5);
            let a = g.mul(c, x);
            let b = g.mul(c, x);
            let nb = g.neg(b);
            let s = g.add(a, y);
            vec![g.add(s, nb)]
        });
        let g = simplify(&f);
        assert_eq!(g.outputs[0].id, g.graph.find(Node::Input(1)).unwrap());
    }
}
