//! Straight-line Rust from a traced [`Function`]: inputs unpacked once,
//! every temporary assigned once, constants as literals, one block per
//! group (wheel) after the terms the groups share.
//!
//! A node gets a `let` when it is used more than once or is a call
//! (`sin`, `sqrt`, …); a node used once is written inline into its user.
//! `sin`/`cos` of an input are named after it (`s_phi`, `c_phi`), other
//! temporaries `tN`. Operands are parenthesized wherever Rust's
//! left-associative parsing would group them differently from the graph,
//! so the printed code evaluates exactly the traced operations.

use crate::graph::{Graph, Id, Node};
use crate::trace::Function;

/// Operation counts of emitted code (every evaluated node, inlined or not).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// Negations.
    pub neg: usize,
    /// sin and cos.
    pub trig: usize,
    /// Square roots.
    pub sqrt: usize,
    /// Other calls (exp, atan2, abs, min, max, copysign, comparisons).
    pub other: usize,
    /// The longest chain of dependent operations (negations not counted):
    /// straight-line code is bound by its latency as much as by its count.
    pub depth: usize,
}

impl std::ops::AddAssign for OpCount {
    fn add_assign(&mut self, o: OpCount) {
        self.add += o.add;
        self.mul += o.mul;
        self.div += o.div;
        self.neg += o.neg;
        self.trig += o.trig;
        self.sqrt += o.sqrt;
        self.other += o.other;
        self.depth = self.depth.max(o.depth);
    }
}

impl std::fmt::Display for OpCount {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} mul, {} add, {} div, {} neg, {} sin/cos, {} sqrt, {} other, depth {}",
            self.mul, self.add, self.div, self.neg, self.trig, self.sqrt, self.other, self.depth
        )
    }
}

/// A block of statements under a title (`None`: the shared terms).
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The block's heading comment.
    pub title: Option<String>,
    /// The statements, each a complete Rust statement.
    pub lines: Vec<String>,
}

/// Which groups use a node.
#[derive(Clone, Copy, PartialEq)]
enum Owner {
    None,
    One(usize),
    Many,
}

impl Owner {
    fn join(self, o: Owner) -> Owner {
        match (self, o) {
            (Owner::None, x) | (x, Owner::None) => x,
            (Owner::One(a), Owner::One(b)) if a == b => Owner::One(a),
            _ => Owner::Many,
        }
    }
}

const ADD: u8 = 1;
const MUL: u8 = 2;
const UNARY: u8 = 3;
const ATOM: u8 = 4;

struct Printer<'a> {
    graph: &'a Graph,
    names: Vec<Option<String>>,
    path: &'a str,
}

impl Printer<'_> {
    /// The expression of node `id` and its precedence.
    fn expr(&self, id: Id) -> (String, u8) {
        if let Some(n) = &self.names[id.0 as usize] {
            return (n.clone(), ATOM);
        }
        self.body(id)
    }

    fn wrap(&self, id: Id, min: u8) -> String {
        let (s, p) = self.expr(id);
        if p < min { format!("({s})") } else { s }
    }

    /// The defining expression of `id`, ignoring its own name.
    fn body(&self, id: Id) -> (String, u8) {
        let g = self.graph;
        match g.node(id) {
            Node::Const(bits) => {
                let v = f64::from_bits(bits);
                (literal(v), if v < 0.0 { UNARY } else { ATOM })
            }
            Node::Input(k) => (format!("input_{k}"), ATOM),
            Node::Add(a, b) => {
                let neg_of = |i: Id| match g.node(i) {
                    Node::Neg(x) if self.names[i.0 as usize].is_none() => Some(x),
                    _ => None,
                };
                let (l, r, op) = if let Some(y) = neg_of(b) {
                    (a, y, "-")
                } else if let Some(x) = neg_of(a) {
                    (b, x, "-")
                } else if let Some(c) = g.value(b).filter(|c| *c < 0.0) {
                    return (format!("{} - {}", self.wrap(a, ADD), literal(-c)), ADD);
                } else if let Some(c) = g.value(a).filter(|c| *c < 0.0) {
                    return (format!("{} - {}", self.wrap(b, ADD), literal(-c)), ADD);
                } else {
                    (a, b, "+")
                };
                (
                    format!("{} {op} {}", self.wrap(l, ADD), self.wrap(r, MUL)),
                    ADD,
                )
            }
            Node::Mul(a, b) => (
                format!("{} * {}", self.wrap(a, MUL), self.wrap(b, UNARY)),
                MUL,
            ),
            Node::Div(a, b) => (
                format!("{} / {}", self.wrap(a, MUL), self.wrap(b, UNARY)),
                MUL,
            ),
            Node::Neg(a) => (format!("-{}", self.wrap(a, ATOM)), UNARY),
            // Every other node prints as a call; its operands need no
            // parentheses (`wrap` at the lowest precedence adds none).
            node => (
                function(node, |i| self.wrap(i, ADD), self.path).unwrap_or_default(),
                ATOM,
            ),
        }
    }
}

/// A node that is a function of its operands (not `+ · / −`) as Rust:
/// libm's function at `libm` for the transcendental ones, a method of
/// `f64` in `core` for `abs`, `max`, `min`, `copysign` (inlined, unlike a
/// libm call, with libm's IEEE semantics), a comparison for `Ge`.
/// `arg` prints an operand; `None` for arithmetic, constants and inputs.
pub fn function(node: Node, arg: impl Fn(Id) -> String, libm: &str) -> Option<String> {
    let libm_call = |f: &str, args: &[Id]| {
        let a: Vec<String> = args.iter().map(|&i| arg(i)).collect();
        format!("{libm}::{f}({})", a.join(", "))
    };
    let core_call = |f: &str, args: &[Id]| {
        let a: Vec<String> = args.iter().map(|&i| arg(i)).collect();
        format!("f64::{f}({})", a.join(", "))
    };
    Some(match node {
        Node::Sin(a) => libm_call("sin", &[a]),
        Node::Cos(a) => libm_call("cos", &[a]),
        Node::Sqrt(a) => libm_call("sqrt", &[a]),
        Node::Exp(a) => libm_call("exp", &[a]),
        Node::Ln(a) => libm_call("log", &[a]),
        Node::Atan2(a, b) => libm_call("atan2", &[a, b]),
        Node::Abs(a) => core_call("abs", &[a]),
        Node::Max(a, b) => core_call("max", &[a, b]),
        Node::Min(a, b) => core_call("min", &[a, b]),
        Node::Copysign(a, b) => core_call("copysign", &[a, b]),
        Node::Ge(a, b) => format!("if {} >= {} {{ 1.0 }} else {{ 0.0 }}", arg(a), arg(b)),
        Node::Const(_)
        | Node::Input(_)
        | Node::Add(..)
        | Node::Mul(..)
        | Node::Div(..)
        | Node::Neg(_) => {
            return None;
        }
    })
}

/// A float literal that reads back to the same bits.
pub fn literal(v: f64) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") || s.contains("NaN") {
        s
    } else {
        format!("{s}.0")
    }
}

/// Emit `f`: the input unpacking, the shared terms, one block per group.
/// `libm` is the path of the libm crate in the generated code.
pub fn emit(f: &Function, libm: &str) -> (Vec<Block>, OpCount) {
    let g = &f.graph;
    let top = f
        .outputs
        .iter()
        .map(|o| o.id.0 as usize + 1)
        .max()
        .unwrap_or(0);
    let usage = Usage::new(f, top);
    let mut ops = count(g, &usage.reach);
    ops.depth = depth(f, top);
    let bound = bindings(g, &usage);
    let names = names(f, &usage, &bound);
    let partner = sincos_partners(g, &usage.owner, &bound);
    let statements = Statements {
        f,
        printer: Printer {
            graph: g,
            names,
            path: libm,
        },
        rank: use_order(g, f, top),
        partner,
        usage,
        bound,
    };
    (statements.blocks(), ops)
}

/// How the outputs use the nodes below them, by node index.
struct Usage {
    /// Uses of the node (by parents and outputs).
    uses: Vec<usize>,
    /// Whether an output needs the node.
    reach: Vec<bool>,
    /// Which groups need it.
    owner: Vec<Owner>,
}

impl Usage {
    /// The uses of the nodes below `top` (one past the highest output),
    /// from the outputs down.
    fn new(f: &Function, top: usize) -> Usage {
        let mut uses = vec![0usize; top];
        let mut reach = vec![false; top];
        let mut owner = vec![Owner::None; top];
        for o in &f.outputs {
            let k = o.id.0 as usize;
            uses[k] += 1;
            reach[k] = true;
            owner[k] = owner[k].join(Owner::One(o.group));
        }
        for k in (0..top).rev() {
            if !reach[k] {
                continue;
            }
            for c in f.graph.node(Id(k as u32)).children() {
                let c = c.0 as usize;
                uses[c] += 1;
                reach[c] = true;
                owner[c] = owner[c].join(owner[k]);
            }
        }
        Usage { uses, reach, owner }
    }
}

/// The operations of the reachable nodes, by kind (no depth).
fn count(g: &Graph, reach: &[bool]) -> OpCount {
    let mut ops = OpCount::default();
    for (k, _) in reach.iter().enumerate().filter(|(_, r)| **r) {
        match g.node(Id(k as u32)) {
            Node::Const(_) | Node::Input(_) => {}
            Node::Add(..) => ops.add += 1,
            Node::Mul(..) => ops.mul += 1,
            Node::Div(..) => ops.div += 1,
            Node::Neg(..) => ops.neg += 1,
            Node::Sin(..) | Node::Cos(..) => ops.trig += 1,
            Node::Sqrt(..) => ops.sqrt += 1,
            _ => ops.other += 1,
        }
    }
    ops
}

/// The longest chain of dependent operations from an input to an output,
/// negations not counted (they fold into their users).
fn depth(f: &Function, top: usize) -> usize {
    let mut depth = vec![0usize; top];
    for k in 0..top {
        let node = f.graph.node(Id(k as u32));
        let below = node
            .children()
            .map(|c| depth[c.0 as usize])
            .max()
            .unwrap_or(0);
        depth[k] = match node {
            Node::Const(_) | Node::Input(_) => 0,
            Node::Neg(_) => below,
            _ => below + 1,
        };
    }
    f.outputs
        .iter()
        .map(|o| depth[o.id.0 as usize])
        .max()
        .unwrap_or(0)
}

/// Which nodes get a `let`: the inputs, the calls and whatever is used
/// more than once; a node used once is written inline into its user.
fn bindings(g: &Graph, usage: &Usage) -> Vec<bool> {
    let mut bound = vec![false; usage.reach.len()];
    for (k, b) in bound.iter_mut().enumerate() {
        if !usage.reach[k] {
            continue;
        }
        *b = match g.node(Id(k as u32)) {
            Node::Const(_) => false,
            Node::Input(_) => true,
            Node::Add(..) | Node::Mul(..) | Node::Div(..) | Node::Neg(..) => usage.uses[k] > 1,
            _ => true,
        };
    }
    // A negation is never a temporary: `-t6` costs nothing where it is
    // used; its operand is named instead when the negation is shared.
    for k in 0..bound.len() {
        if let Node::Neg(a) = g.node(Id(k as u32))
            && bound[k]
        {
            bound[k] = false;
            if !matches!(g.node(a), Node::Const(_) | Node::Input(_)) {
                bound[a.0 as usize] = true;
            }
        }
    }
    bound
}

/// The names of the bound nodes: an input's own, `s_phi` and `c_phi` for
/// sin and cos of an input, `tN` for the other temporaries, numbered in
/// emission order (shared terms, then each group).
fn names(f: &Function, usage: &Usage, bound: &[bool]) -> Vec<Option<String>> {
    let g = &f.graph;
    let input_name = |a: Id| match g.node(a) {
        Node::Input(i) => f.inputs.get(i as usize).map(|v| v.name.clone()),
        _ => None,
    };
    let mut names: Vec<Option<String>> = (0..bound.len())
        .map(|k| usage.reach[k].then(|| input_name(Id(k as u32))).flatten())
        .collect();
    let owner = &usage.owner;
    let order = (0..bound.len()).filter(|&k| owner[k] == Owner::Many).chain(
        (0..f.groups.len())
            .flat_map(|grp| (0..bound.len()).filter(move |&k| owner[k] == Owner::One(grp))),
    );
    let mut counter = 0;
    for k in order {
        if !bound[k] || names[k].is_some() {
            continue;
        }
        names[k] = match g.node(Id(k as u32)) {
            Node::Sin(a) => input_name(a).map(|n| format!("s_{n}")),
            Node::Cos(a) => input_name(a).map(|n| format!("c_{n}")),
            _ => None,
        }
        .or_else(|| {
            counter += 1;
            Some(format!("t{counter}"))
        });
    }
    names
}

/// sin and cos of one angle, both bound in the same block: the other of
/// each, so that one `sincos` call computes both.
fn sincos_partners(g: &Graph, owner: &[Owner], bound: &[bool]) -> Vec<Option<usize>> {
    let top = bound.len();
    let mut partner: Vec<Option<usize>> = vec![None; top];
    for k in 0..top {
        if let Node::Sin(a) = g.node(Id(k as u32))
            && bound[k]
            && let Some(c) = g.find(Node::Cos(a)).map(|c| c.0 as usize)
            && c < top
            && bound[c]
            && owner[c] == owner[k]
        {
            partner[k] = Some(c);
            partner[c] = Some(k);
        }
    }
    partner
}

/// What the statements of `f` are printed from.
struct Statements<'a> {
    f: &'a Function,
    printer: Printer<'a>,
    /// Each node's position in [`use_order`].
    rank: Vec<usize>,
    /// Each node's `sincos` partner, see [`sincos_partners`].
    partner: Vec<Option<usize>>,
    usage: Usage,
    bound: Vec<bool>,
}

impl Statements<'_> {
    /// The blocks: with groups, the inputs, the terms shared by the
    /// groups, then each group's block; without, one block in use order.
    fn blocks(&self) -> Vec<Block> {
        let grouped = self.f.groups.len() > 1;
        let owner = &self.usage.owner;
        // Ungrouped code is one block in use order: inputs are read where
        // they are first needed, which keeps fewer values live.
        let inputs = self.lets(|k| self.usage.reach[k] && self.is_input(k) && grouped);
        let shared = self.lets(|k| {
            owner[k] == Owner::Many
                && self.bound[k]
                && (!self.is_input(k) || !grouped)
                && self.usage.reach[k]
        });
        let mut blocks = Vec::new();
        let mut head = inputs;
        if grouped {
            blocks.push(Block {
                title: Some("inputs".into()),
                lines: head,
            });
            head = Vec::new();
            if !shared.is_empty() {
                blocks.push(Block {
                    title: Some("terms shared by the wheels".into()),
                    lines: shared,
                });
            }
        } else {
            head.extend(shared);
        }
        for (grp, title) in self.f.groups.iter().enumerate() {
            let mut lines = std::mem::take(&mut head);
            lines.extend(self.group_lines(grp, grouped));
            blocks.push(Block {
                title: Some(title.clone()),
                lines,
            });
        }
        blocks
    }

    /// Group `grp`'s own terms and its outputs.
    fn group_lines(&self, grp: usize, grouped: bool) -> Vec<String> {
        let owner = &self.usage.owner;
        let mut lines = self.lets(|k| {
            owner[k] == Owner::One(grp) && self.bound[k] && (!self.is_input(k) || !grouped)
        });
        for o in self.f.outputs.iter().filter(|o| o.group == grp) {
            lines.push(format!("{} {};", o.place, self.printer.expr(o.id).0));
        }
        lines
    }

    fn is_input(&self, k: usize) -> bool {
        matches!(self.f.graph.node(Id(k as u32)), Node::Input(_))
    }

    /// The `let`s of the nodes that `pick` selects, in use order.
    fn lets(&self, pick: impl Fn(usize) -> bool) -> Vec<String> {
        let mut ks: Vec<usize> = (0..self.bound.len()).filter(|&k| pick(k)).collect();
        ks.sort_by_key(|&k| self.rank[k]);
        ks.into_iter().filter_map(|k| self.let_line(k)).collect()
    }

    /// The `let` of node `k`: an input read from its place, a `sincos`
    /// for the first of a pair (none for the second), its expression.
    fn let_line(&self, k: usize) -> Option<String> {
        let g = &self.f.graph;
        let node = g.node(Id(k as u32));
        let name = self.printer.names[k].as_ref()?;
        if let Some(other) = self.partner[k] {
            if self.rank[other] < self.rank[k] {
                return None;
            }
            let other_name = self.printer.names[other].as_ref()?;
            let (Node::Sin(a) | Node::Cos(a)) = node else {
                return None;
            };
            let (s, c) = if matches!(node, Node::Sin(_)) {
                (name, other_name)
            } else {
                (other_name, name)
            };
            let libm = self.printer.path;
            return Some(format!(
                "let ({s}, {c}) = {libm}::sincos({});",
                self.printer.expr(a).0
            ));
        }
        match node {
            Node::Const(_) => None,
            Node::Input(i) => Some(format!(
                "let {name} = {};",
                self.f.inputs[i as usize].access
            )),
            _ => Some(format!(
                "let {name} = {};",
                self.printer.body(Id(k as u32)).0
            )),
        }
    }
}

/// Every reachable node's position in a depth-first post-order from the
/// outputs, taken in order: a term is computed just before the first
/// expression that needs it, so fewer values are live at once and the
/// compiler spills fewer registers than with the tracing order.
fn use_order(g: &Graph, f: &Function, top: usize) -> Vec<usize> {
    let mut need = vec![1u32; top];
    for k in 0..top {
        let mut kids: Vec<u32> = g
            .node(Id(k as u32))
            .children()
            .map(|c| need[c.0 as usize])
            .collect();
        kids.sort_unstable_by(|a, b| b.cmp(a));
        need[k] = match kids.as_slice() {
            [] => 1,
            [a] => *a,
            [a, b, ..] if a == b => a + 1,
            [a, ..] => *a,
        };
    }
    let mut rank = vec![usize::MAX; top];
    let mut next = 0;
    let mut stack: Vec<(usize, bool)> = Vec::new();
    for o in &f.outputs {
        stack.push((o.id.0 as usize, false));
        while let Some((k, expanded)) = stack.pop() {
            if rank[k] != usize::MAX {
                continue;
            }
            if expanded {
                rank[k] = next;
                next += 1;
                continue;
            }
            stack.push((k, true));
            let mut children: Vec<Id> = g.node(Id(k as u32)).children().collect();
            // The operand that needs more registers first (Sethi–Ullman):
            // its temporaries are dead before the other one starts.
            children.sort_by_key(|c| core::cmp::Reverse(need[c.0 as usize]));
            for c in children.into_iter().rev() {
                if rank[c.0 as usize] == usize::MAX {
                    stack.push((c.0 as usize, false));
                }
            }
        }
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;

    fn function(build: impl FnOnce(&mut Graph) -> Vec<Id>) -> Function {
        Function::for_test(&["a", "b", "phi"], build)
    }

    #[test]
    fn parenthesizes_exactly_where_the_graph_groups_differently() {
        let f = function(|g| {
            let (a, b) = (g.input(0), g.input(1));
            let s = g.add(a, b);
            let d = g.sub(a, s); // a − (a + b)
            let c = g.cst(0.25);
            let p = g.mul(c, s); // 0.25·(a + b)
            let q = g.div(a, p); // a / (0.25·(a + b))
            let h = g.cst(-2.0);
            let r = g.add(q, h);
            vec![d, r]
        });
        let (blocks, ops) = emit(&f, "libm");
        assert_eq!(
            blocks[0].lines,
            vec![
                "let a = x[0];",
                "let b = x[1];",
                "let t1 = a + b;",
                "out[0] = a - t1;",
                "out[1] = a / (t1 * 0.25) - 2.0;",
            ]
        );
        assert_eq!(ops.add, 3);
        assert_eq!(ops.mul, 1);
        assert_eq!(ops.div, 1);
    }

    #[test]
    fn trig_of_an_input_is_named_after_it_and_computed_once() {
        let f = function(|g| {
            let phi = g.input(2);
            let s = g.sin(phi);
            let c = g.cos(phi);
            let p = g.mul(s, c);
            let n = g.neg(s);
            vec![p, n]
        });
        let (blocks, _) = emit(&f, "libm");
        assert_eq!(
            blocks[0].lines,
            vec![
                "let phi = x[2];",
                "let (s_phi, c_phi) = libm::sincos(phi);",
                "out[0] = s_phi * c_phi;",
                "out[1] = -s_phi;",
            ]
        );
    }

    #[test]
    fn literals_read_back_exactly() {
        for v in [0.1, 30.0, 1e-5, 1.0 / 3.0, 6.02e23, -0.5] {
            assert_eq!(literal(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(literal(2.0), "2.0");
    }
}
