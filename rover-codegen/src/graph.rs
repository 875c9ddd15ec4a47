//! The expression graph: a hash-consed DAG of scalar operations.
//!
//! Every node lives once in an arena; a map from node to index makes a
//! second construction of the same node return the first one, so common
//! subexpressions are shared for free. Construction folds constants and the
//! identities that are exact in IEEE arithmetic for finite values
//! (`x + 0`, `x·1`, `x·0`, `−(−x)`, `x·(−1)`), and puts the operands of
//! commutative operations in a canonical order (smaller index first). It
//! never reassociates, so a traced program computes bit for bit what the
//! same program computes with `f64`.

use std::collections::HashMap;

/// Index of a node in a [`Graph`]. Children always have smaller indices than
/// their parents, so index order is a topological order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

/// One operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, by its bits (−0 is stored as +0).
    Const(u64),
    /// Input number k of the traced function.
    Input(u32),
    /// a + b.
    Add(Id, Id),
    /// a · b.
    Mul(Id, Id),
    /// a / b.
    Div(Id, Id),
    /// −a.
    Neg(Id),
    /// sin a.
    Sin(Id),
    /// cos a.
    Cos(Id),
    /// √a.
    Sqrt(Id),
    /// atan2(a, b).
    Atan2(Id, Id),
    /// exp a.
    Exp(Id),
    /// ln a.
    Ln(Id),
    /// |a|.
    Abs(Id),
    /// max(a, b).
    Max(Id, Id),
    /// min(a, b).
    Min(Id, Id),
    /// |a| with the sign of b.
    Copysign(Id, Id),
    /// 1 if a ≥ b, else 0 (only made by differentiation of max/min).
    Ge(Id, Id),
}

impl Node {
    /// The children of the node.
    pub fn children(&self) -> impl Iterator<Item = Id> {
        let (a, b) = match *self {
            Node::Const(_) | Node::Input(_) => (None, None),
            Node::Neg(a)
            | Node::Sin(a)
            | Node::Cos(a)
            | Node::Sqrt(a)
            | Node::Exp(a)
            | Node::Ln(a)
            | Node::Abs(a) => (Some(a), None),
            Node::Add(a, b)
            | Node::Mul(a, b)
            | Node::Div(a, b)
            | Node::Atan2(a, b)
            | Node::Max(a, b)
            | Node::Min(a, b)
            | Node::Copysign(a, b)
            | Node::Ge(a, b) => (Some(a), Some(b)),
        };
        a.into_iter().chain(b)
    }
}

/// The arena with its hash-consing map.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node at `id`.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.0 as usize]
    }

    /// The node's index if the graph holds it.
    pub fn find(&self, node: Node) -> Option<Id> {
        self.index.get(&node).copied()
    }

    /// The constant value of `id`, if it is a constant.
    pub fn value(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).unwrap_or(u32::MAX));
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// A constant.
    pub fn cst(&mut self, v: f64) -> Id {
        let v = if v == 0.0 { 0.0 } else { v };
        self.intern(Node::Const(v.to_bits()))
    }

    /// Input number `k`.
    pub fn input(&mut self, k: u32) -> Id {
        self.intern(Node::Input(k))
    }

    fn is(&self, id: Id, v: f64) -> bool {
        self.value(id) == Some(v)
    }

    /// a + b.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.value(a), self.value(b)) {
            return self.cst(x + y);
        }
        if self.is(a, 0.0) {
            return b;
        }
        if self.is(b, 0.0) {
            return a;
        }
        if self.node(a) == Node::Neg(b) || self.node(b) == Node::Neg(a) {
            return self.cst(0.0);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// a − b, stored as a + (−b) (bit for bit the same in IEEE arithmetic).
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.cst(0.0);
        }
        let nb = self.neg(b);
        self.add(a, nb)
    }

    /// a · b.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.value(a), self.value(b)) {
            return self.cst(x * y);
        }
        if self.is(a, 0.0) || self.is(b, 0.0) {
            return self.cst(0.0);
        }
        if self.is(a, 1.0) {
            return b;
        }
        if self.is(b, 1.0) {
            return a;
        }
        if self.is(a, -1.0) {
            return self.neg(b);
        }
        if self.is(b, -1.0) {
            return self.neg(a);
        }
        // (−x)·(−y) = x·y and (−x)·y = −(x·y) exactly: keep negations outermost.
        match (self.node(a), self.node(b)) {
            (Node::Neg(x), Node::Neg(y)) => return self.mul(x, y),
            (Node::Neg(x), _) => {
                let p = self.mul(x, b);
                return self.neg(p);
            }
            (_, Node::Neg(y)) => {
                let p = self.mul(a, y);
                return self.neg(p);
            }
            _ => {}
        }
        if let Some(x) = self.value(a)
            && x < 0.0
        {
            let c = self.cst(-x);
            let p = self.mul(c, b);
            return self.neg(p);
        }
        if let Some(y) = self.value(b)
            && y < 0.0
        {
            let c = self.cst(-y);
            let p = self.mul(a, c);
            return self.neg(p);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    /// a / b.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.value(a), self.value(b)) {
            return self.cst(x / y);
        }
        if self.is(a, 0.0) {
            return self.cst(0.0);
        }
        if self.is(b, 1.0) {
            return a;
        }
        if let Node::Neg(x) = self.node(a) {
            let q = self.div(x, b);
            return self.neg(q);
        }
        if let Node::Neg(y) = self.node(b) {
            let q = self.div(a, y);
            return self.neg(q);
        }
        self.intern(Node::Div(a, b))
    }

    /// −a.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.value(a) {
            return self.cst(-x);
        }
        if let Node::Neg(x) = self.node(a) {
            return x;
        }
        self.intern(Node::Neg(a))
    }

    fn unary(&mut self, a: Id, f: fn(f64) -> f64, make: fn(Id) -> Node) -> Id {
        match self.value(a) {
            Some(x) => self.cst(f(x)),
            None => self.intern(make(a)),
        }
    }

    fn binary(&mut self, a: Id, b: Id, f: fn(f64, f64) -> f64, make: fn(Id, Id) -> Node) -> Id {
        match (self.value(a), self.value(b)) {
            (Some(x), Some(y)) => self.cst(f(x, y)),
            _ => self.intern(make(a, b)),
        }
    }

    /// sin a.
    pub fn sin(&mut self, a: Id) -> Id {
        self.unary(a, libm::sin, Node::Sin)
    }
    /// cos a.
    pub fn cos(&mut self, a: Id) -> Id {
        self.unary(a, libm::cos, Node::Cos)
    }
    /// √a.
    pub fn sqrt(&mut self, a: Id) -> Id {
        self.unary(a, libm::sqrt, Node::Sqrt)
    }
    /// exp a.
    pub fn exp(&mut self, a: Id) -> Id {
        self.unary(a, libm::exp, Node::Exp)
    }
    /// ln a.
    pub fn ln(&mut self, a: Id) -> Id {
        self.unary(a, libm::log, Node::Ln)
    }
    /// |a|.
    pub fn abs(&mut self, a: Id) -> Id {
        self.unary(a, f64::abs, Node::Abs)
    }
    /// atan2(a, b).
    pub fn atan2(&mut self, a: Id, b: Id) -> Id {
        self.binary(a, b, libm::atan2, Node::Atan2)
    }
    /// max(a, b).
    pub fn max(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return a;
        }
        self.binary(a, b, f64::max, Node::Max)
    }
    /// min(a, b).
    pub fn min(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return a;
        }
        self.binary(a, b, f64::min, Node::Min)
    }
    /// |a| with the sign of b.
    pub fn copysign(&mut self, a: Id, b: Id) -> Id {
        self.binary(a, b, libm::copysign, Node::Copysign)
    }
    /// 1 if a ≥ b else 0.
    pub fn ge(&mut self, a: Id, b: Id) -> Id {
        self.binary(a, b, |x, y| if x >= y { 1.0 } else { 0.0 }, Node::Ge)
    }

    /// Evaluate `outputs` for the input values `inputs` (a reference
    /// interpreter, for tests).
    pub fn eval(&self, inputs: &[f64], outputs: &[Id]) -> Vec<f64> {
        let mut v = vec![0.0; self.nodes.len()];
        let top = outputs.iter().map(|o| o.0 as usize + 1).max().unwrap_or(0);
        for k in 0..top {
            let g = |id: Id| v[id.0 as usize];
            v[k] = match self.nodes[k] {
                Node::Const(b) => f64::from_bits(b),
                Node::Input(i) => inputs.get(i as usize).copied().unwrap_or(f64::NAN),
                Node::Add(a, b) => g(a) + g(b),
                Node::Mul(a, b) => g(a) * g(b),
                Node::Div(a, b) => g(a) / g(b),
                Node::Neg(a) => -g(a),
                Node::Sin(a) => libm::sin(g(a)),
                Node::Cos(a) => libm::cos(g(a)),
                Node::Sqrt(a) => libm::sqrt(g(a)),
                Node::Exp(a) => libm::exp(g(a)),
                Node::Ln(a) => libm::log(g(a)),
                Node::Abs(a) => f64::abs(g(a)),
                Node::Atan2(a, b) => libm::atan2(g(a), g(b)),
                Node::Max(a, b) => f64::max(g(a), g(b)),
                Node::Min(a, b) => f64::min(g(a), g(b)),
                Node::Copysign(a, b) => libm::copysign(g(a), g(b)),
                Node::Ge(a, b) => {
                    if g(a) >= g(b) {
                        1.0
                    } else {
                        0.0
                    }
                }
            };
        }
        outputs.iter().map(|o| v[o.0 as usize]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_expressions_share_one_node() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let a = g.mul(x, y);
        let b = g.mul(y, x);
        assert_eq!(a, b, "canonical operand order");
        let s1 = g.sin(x);
        let s2 = g.sin(x);
        assert_eq!(s1, s2);
        let n = g.len();
        let _ = g.add(a, s1);
        let _ = g.add(s1, b);
        assert_eq!(g.len(), n + 1);
    }

    #[test]
    fn folds_constants_and_exact_identities() {
        let mut g = Graph::new();
        let x = g.input(0);
        let (zero, one, two, m1) = (g.cst(0.0), g.cst(1.0), g.cst(2.0), g.cst(-1.0));
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.add(x, zero), x);
        let three = g.cst(3.0);
        assert_eq!(g.add(one, two), three);
        let nx = g.mul(m1, x);
        assert_eq!(g.node(nx), Node::Neg(x));
        assert_eq!(g.neg(nx), x);
        assert_eq!(g.sub(x, x), zero);
        let s = g.sin(zero);
        assert_eq!(s, zero);
        let c = g.cos(zero);
        assert_eq!(c, one);
        assert_eq!(g.div(x, one), x);
    }

    #[test]
    fn evaluation_matches_f64() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let c = g.cst(0.3);
        let s = g.sin(x);
        let p = g.mul(s, c);
        let q = g.sub(p, y);
        let r = g.div(q, y);
        let v = g.eval(&[0.7, 1.9], &[r]);
        let expect = ((0.7f64).sin() * 0.3 - 1.9) / 1.9;
        assert_eq!(v[0], expect);
    }
}
