//! Four lanes, one per wheel: the right-hand side of a four-wheeled rover
//! with its per-wheel work packed into four-lane vector operations.
//!
//! The four wheels of such a rover run the same operations on their own
//! numbers: each arm's kinematics, its share of M and of the Schur
//! complement, its loads. [`plan`] finds those operations in the traced
//! graph, bottom-up from the per-wheel inputs (a coordinate, its rate and
//! neutral, a wheel's loads): four nodes, one per lane, make a pack when
//! they are the same operation on operands that are themselves one pack
//! (possibly negated in some lanes), constants, or values that no lane's
//! input reaches (broadcast when equal, gathered when they differ). A sum
//! that adds all four lanes of packs is regrouped lane-wise: the packs are
//! added as vectors and the four lanes summed once, `(l0 + l2) + (l1 + l3)`,
//! before the sum's other terms. That regrouping is the only change of
//! rounding; every other lane computes exactly its node's IEEE operation.
//!
//! [`emit`] prints the plan twice from one statement list: with AVX
//! intrinsics for the x86-64-v4 copy and with `[f64; 4]` arrays for the
//! portable one. The two perform the same operations in the same order, so
//! they give the same bits (docs/CODEGEN.md, "Lanes").

use std::collections::HashMap;
use std::fmt::Write;

use crate::emit::{function, literal};
use crate::graph::{Graph, Id, Node};
use crate::trace::Function;

/// Number of lanes (one 256-bit vector of `f64`).
pub const LANES: usize = 4;

/// The packing of one function.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The packs: lane l of pack p is node `packs[p][l]`.
    packs: Vec<[Id; LANES]>,
    /// The first `inputs` packs are input packs (read, not computed).
    inputs: usize,
    /// Pack and lane of every node, if packed.
    pack_of: Vec<Option<(usize, usize)>>,
    /// Nodes that no input of a lane reaches.
    shared: Vec<bool>,
    /// Statements in an order that respects every dependency.
    order: Vec<Item>,
    /// Sums regrouped lane-wise: root node → (packs with their lane
    /// signs, the remaining terms with their signs).
    sums: HashMap<usize, LaneSum>,
    /// Nodes absorbed into a regrouped sum (never emitted).
    absorbed: Vec<bool>,
    /// Packs whose lanes are read one by one (by scalar code or outputs).
    extracted: Vec<bool>,
    /// Scalar operations that the packs compute (add, mul, div).
    pub packed_ops: usize,
    /// Scalar operations of the function (add, mul, div).
    pub total_ops: usize,
}

impl Plan {
    /// Number of four-lane operations (computed packs).
    pub fn vector_ops(&self) -> usize {
        self.packs.len() - self.inputs
    }

    /// Number of sums regrouped lane-wise.
    pub fn lane_sums(&self) -> usize {
        self.sums.len()
    }
}

#[derive(Clone, Debug)]
struct LaneSum {
    packs: Vec<(usize, [bool; LANES])>,
    rest: Vec<(Id, bool)>,
}

#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
enum Item {
    Scalar(usize),
    Pack(usize),
}

/// How a pack's operand looks in one lane, without the lane's own data:
/// lanes match when their operands' kinds do.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
enum Kind {
    /// A lane of this pack (or its negation).
    Pack(usize),
    /// A value some lane's input reaches but no pack holds: the same node
    /// in every lane, or no match.
    Scalar(Id),
    /// A constant or a value no lane's input reaches: may differ per lane.
    Const,
}

/// How a pack's operand is formed from its four lanes' operands.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Form {
    /// Four constants.
    Consts,
    /// One shared value in every lane.
    Splat(Id),
    /// A pack, negated in the lanes marked.
    Pack(usize, [bool; LANES]),
    /// Anything else, gathered lane by lane.
    Gather,
}

/// The form of operand `c` (one node per lane) of a pack.
fn form(g: &Graph, pack_of: &[Option<(usize, usize)>], c: [Id; LANES]) -> Form {
    if c.iter().all(|x| g.value(*x).is_some()) {
        return Form::Consts;
    }
    if c.iter().all(|x| *x == c[0]) && pack_of[c[0].0 as usize].is_none() {
        return Form::Splat(c[0]);
    }
    let lane = |x: Id| match pack_of[x.0 as usize] {
        Some((q, l)) => Some((q, l, false)),
        None => match g.node(x) {
            Node::Neg(y) => pack_of[y.0 as usize].map(|(q, l)| (q, l, true)),
            _ => None,
        },
    };
    let Some((q, _, _)) = lane(c[0]) else {
        return Form::Gather;
    };
    let mut signs = [false; LANES];
    for (l, x) in c.iter().enumerate() {
        match lane(*x) {
            Some((qq, ll, neg)) if qq == q && ll == l => signs[l] = neg,
            _ => return Form::Gather,
        }
    }
    Form::Pack(q, signs)
}

/// Operand `i` of pack `members`, lane by lane, in the order the matching
/// compared them (commutative operands sorted by kind).
fn operand_lanes(
    g: &Graph,
    pack_of: &[Option<(usize, usize)>],
    shared: &[bool],
    members: [Id; LANES],
    i: usize,
) -> [Id; LANES] {
    members.map(|x| {
        let mut c: Vec<Id> = g.node(x).children().collect();
        if !matches!(g.node(x), Node::Div(..)) {
            c.sort_by_key(|y| kind_of(g, pack_of, shared, *y).0);
        }
        c[i]
    })
}

/// Input lane groups of a function: `lane_of(k)` gives input k's group
/// key and lane (its wheel or coordinate), or `None` for a shared input.
/// A group makes an input pack when it has exactly one input per lane.
pub fn seeds(
    f: &Function,
    lane_of: impl Fn(usize) -> Option<(String, usize)>,
) -> Vec<[u32; LANES]> {
    let mut groups: HashMap<String, [Option<u32>; LANES]> = HashMap::new();
    let mut bad: Vec<String> = Vec::new();
    for k in 0..f.inputs.len() {
        if let Some((key, lane)) = lane_of(k) {
            let slot = groups.entry(key.clone()).or_insert([None; LANES]);
            match slot.get_mut(lane) {
                Some(s @ None) => *s = Some(k as u32),
                _ => bad.push(key),
            }
        }
    }
    let mut out: Vec<(String, [u32; LANES])> = groups
        .into_iter()
        .filter(|(key, _)| !bad.contains(key))
        .filter_map(|(key, s)| {
            let all: Option<Vec<u32>> = s.iter().copied().collect();
            all.map(|v| (key, [v[0], v[1], v[2], v[3]]))
        })
        .collect();
    out.sort();
    out.into_iter().map(|(_, s)| s).collect()
}

/// The packing of `f` from its input packs, or `None` when nothing packs.
pub fn plan(f: &Function, seeds: &[[u32; LANES]]) -> Option<Plan> {
    let g = &f.graph;
    let top = g.len();
    let mut reach = vec![false; top];
    for o in &f.outputs {
        reach[o.id.0 as usize] = true;
    }
    for k in (0..top).rev() {
        if reach[k] {
            for c in g.node(Id(k as u32)).children() {
                reach[c.0 as usize] = true;
            }
        }
    }
    let input_node: HashMap<u32, Id> = (0..top)
        .filter_map(|k| match g.node(Id(k as u32)) {
            Node::Input(i) => Some((i, Id(k as u32))),
            _ => None,
        })
        .collect();
    let mut packs: Vec<[Id; LANES]> = Vec::new();
    let mut pack_of: Vec<Option<(usize, usize)>> = vec![None; top];
    for s in seeds {
        let ids: Option<Vec<Id>> = s.iter().map(|k| input_node.get(k).copied()).collect();
        let Some(ids) = ids else { continue };
        let p = packs.len();
        for (l, id) in ids.iter().enumerate() {
            pack_of[id.0 as usize] = Some((p, l));
        }
        packs.push([ids[0], ids[1], ids[2], ids[3]]);
    }
    let inputs = packs.len();
    let mut shared = vec![true; top];
    for k in 0..top {
        shared[k] = match g.node(Id(k as u32)) {
            Node::Input(_) => pack_of[k].is_none(),
            node => node.children().all(|c| shared[c.0 as usize]),
        };
    }
    // Bottom-up to a fixed point: a node joins a pack when the nodes of the
    // other lanes with the same shape exist; the k-th candidate of each
    // lane are matched (the trace runs the same code for every wheel, so
    // their order of appearance agrees).
    loop {
        let mut buckets: HashMap<(u8, Vec<Kind>), [Vec<Id>; LANES]> = HashMap::new();
        for k in 0..top {
            if !reach[k] || pack_of[k].is_some() {
                continue;
            }
            let node = g.node(Id(k as u32));
            let op = match node {
                Node::Add(..) => 0u8,
                Node::Mul(..) => 1,
                Node::Div(..) => 2,
                _ => continue,
            };
            let mut kinds = Vec::new();
            let mut lane = None;
            let mut agree = true;
            for c in node.children() {
                let (kind, l) = kind_of(g, &pack_of, &shared, c);
                if let Some(l) = l {
                    agree &= lane.is_none_or(|x| x == l);
                    lane = Some(l);
                }
                kinds.push(kind);
            }
            let (Some(lane), true) = (lane, agree) else {
                continue;
            };
            if op != 2 {
                kinds.sort();
            }
            buckets.entry((op, kinds)).or_default()[lane].push(Id(k as u32));
        }
        let mut keys: Vec<_> = buckets.keys().cloned().collect();
        keys.sort();
        let before = packs.len();
        for key in keys {
            let b = &buckets[&key];
            let n = b.iter().map(Vec::len).min().unwrap_or(0);
            for i in 0..n {
                let p = packs.len();
                let members = [b[0][i], b[1][i], b[2][i], b[3][i]];
                for (l, id) in members.iter().enumerate() {
                    pack_of[id.0 as usize] = Some((p, l));
                }
                packs.push(members);
            }
        }
        if packs.len() == before {
            break;
        }
    }
    if packs.len() == inputs {
        return None;
    }
    let arith = |k: usize| {
        matches!(
            g.node(Id(k as u32)),
            Node::Add(..) | Node::Mul(..) | Node::Div(..)
        )
    };
    let total_ops = (0..top).filter(|&k| reach[k] && arith(k)).count();
    let packed_ops = (0..top)
        .filter(|&k| reach[k] && arith(k) && pack_of[k].is_some())
        .count();
    // Sums: maximal trees of unpacked additions and negations whose inner
    // nodes have one user, an unpacked addition or negation.
    let mut uses = vec![0usize; top];
    let mut linear_users = vec![true; top];
    for k in 0..top {
        if !reach[k] {
            continue;
        }
        let node = g.node(Id(k as u32));
        let linear = pack_of[k].is_none() && matches!(node, Node::Add(..) | Node::Neg(_));
        for c in node.children() {
            uses[c.0 as usize] += 1;
            linear_users[c.0 as usize] &= linear;
        }
    }
    for o in &f.outputs {
        uses[o.id.0 as usize] += 2;
    }
    let inner = |k: usize| {
        pack_of[k].is_none()
            && matches!(g.node(Id(k as u32)), Node::Add(..) | Node::Neg(_))
            && uses[k] == 1
            && linear_users[k]
    };
    let mut sums = HashMap::new();
    let mut absorbed = vec![false; top];
    for k in 0..top {
        if !reach[k]
            || pack_of[k].is_some()
            || inner(k)
            || !matches!(g.node(Id(k as u32)), Node::Add(..))
        {
            continue;
        }
        let mut leaves: Vec<(Id, bool)> = Vec::new();
        let mut inside: Vec<usize> = Vec::new();
        let mut stack = vec![(Id(k as u32), false)];
        while let Some((x, neg)) = stack.pop() {
            let xi = x.0 as usize;
            let expand = xi == k || inner(xi);
            match g.node(x) {
                Node::Add(a, b) if expand => {
                    stack.push((b, neg));
                    stack.push((a, neg));
                }
                Node::Neg(a) if expand => stack.push((a, !neg)),
                _ => {
                    leaves.push((x, neg));
                    continue;
                }
            }
            if xi != k {
                inside.push(xi);
            }
        }
        let mut lanes_of: HashMap<usize, [Option<bool>; LANES]> = HashMap::new();
        let mut twice = false;
        for &(x, neg) in &leaves {
            if let Some((p, l)) = pack_of[x.0 as usize] {
                let e = lanes_of.entry(p).or_insert([None; LANES]);
                twice |= e[l].is_some();
                e[l] = Some(neg);
            }
        }
        let mut full: Vec<(usize, [bool; LANES])> = lanes_of
            .iter()
            .filter_map(|(p, e)| {
                let s: Option<Vec<bool>> = e.iter().copied().collect();
                s.map(|s| (*p, [s[0], s[1], s[2], s[3]]))
            })
            .collect();
        if twice || full.is_empty() {
            continue;
        }
        full.sort_by_key(|(p, _)| *p);
        let rest = leaves
            .into_iter()
            .filter(|(x, _)| {
                !pack_of[x.0 as usize].is_some_and(|(p, _)| full.iter().any(|(q, _)| *q == p))
            })
            .collect();
        for i in inside {
            absorbed[i] = true;
        }
        sums.insert(k, LaneSum { packs: full, rest });
    }
    // Statement order: depth-first from the outputs, packs as one item.
    let item_of = |id: Id| match pack_of[id.0 as usize] {
        Some((p, _)) => Item::Pack(p),
        None => Item::Scalar(id.0 as usize),
    };
    let deps = |it: Item| -> Vec<Item> {
        match it {
            Item::Scalar(k) => g.node(Id(k as u32)).children().map(item_of).collect(),
            Item::Pack(p) => packs[p]
                .iter()
                .flat_map(|m| g.node(*m).children().map(item_of).collect::<Vec<_>>())
                .collect(),
        }
    };
    let mut state: HashMap<Item, bool> = HashMap::new();
    let mut order = Vec::new();
    for o in &f.outputs {
        let mut stack = vec![(item_of(o.id), false)];
        while let Some((it, done)) = stack.pop() {
            if done {
                state.insert(it, true);
                order.push(it);
                continue;
            }
            if state.contains_key(&it) {
                continue;
            }
            state.insert(it, false);
            stack.push((it, true));
            for d in deps(it).into_iter().rev() {
                match state.get(&d) {
                    Some(true) => {}
                    // A pack whose lanes depend on each other: give up.
                    Some(false) => return None,
                    None => stack.push((d, false)),
                }
            }
        }
    }
    let mut extracted = vec![false; packs.len()];
    for it in &order {
        let Item::Scalar(k) = *it else { continue };
        let used: Vec<Id> = match sums.get(&k) {
            Some(s) => s.rest.iter().map(|(x, _)| *x).collect(),
            None if absorbed[k] => Vec::new(),
            None => g.node(Id(k as u32)).children().collect(),
        };
        for c in used {
            if let Some((p, _)) = pack_of[c.0 as usize] {
                extracted[p] = true;
            }
        }
    }
    for o in &f.outputs {
        if let Some((p, _)) = pack_of[o.id.0 as usize] {
            extracted[p] = true;
        }
    }
    for members in &packs[inputs..] {
        for i in 0..2 {
            let c = operand_lanes(g, &pack_of, &shared, *members, i);
            if form(g, &pack_of, c) == Form::Gather {
                for x in c {
                    if let Some((q, _)) = pack_of[x.0 as usize] {
                        extracted[q] = true;
                    }
                }
            }
        }
    }
    Some(Plan {
        packs,
        inputs,
        pack_of,
        shared,
        order,
        sums,
        absorbed,
        extracted,
        packed_ops,
        total_ops,
    })
}

/// The operand kind of child `c` and its lane, if packed (a negation of a
/// packed node is that pack, negated in its lane).
fn kind_of(
    g: &Graph,
    pack_of: &[Option<(usize, usize)>],
    shared: &[bool],
    c: Id,
) -> (Kind, Option<usize>) {
    if g.value(c).is_some() {
        return (Kind::Const, None);
    }
    if let Some((p, l)) = pack_of[c.0 as usize] {
        return (Kind::Pack(p), Some(l));
    }
    if let Node::Neg(x) = g.node(c)
        && let Some((p, l)) = pack_of[x.0 as usize]
    {
        return (Kind::Pack(p), Some(l));
    }
    // A value that no lane's input reaches may differ from lane to lane
    // (gathered like constants: it cannot depend on its own pack).
    if shared[c.0 as usize] {
        return (Kind::Const, None);
    }
    (Kind::Scalar(c), None)
}

/// The lane operations, as local macros: AVX intrinsics for the x86-64-v4
/// copy, `[f64; 4]` arithmetic for the portable one (the same IEEE
/// operations lane by lane, and the same order in `lanes_sum`).
fn prelude(avx: bool) -> &'static str {
    if avx {
        "use ::core::arch::x86_64::*;\n\
         #[allow(unused_macros)] macro_rules! lanes { ($a:expr, $b:expr, $c:expr, $d:expr) => { _mm256_setr_pd($a, $b, $c, $d) }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_splat { ($a:expr) => { _mm256_set1_pd($a) }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_add { ($a:expr, $b:expr) => { _mm256_add_pd($a, $b) }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_mul { ($a:expr, $b:expr) => { _mm256_mul_pd($a, $b) }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_div { ($a:expr, $b:expr) => { _mm256_div_pd($a, $b) }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_array { ($a:expr) => { { let mut r = [0.0f64; 4]; \
         unsafe { _mm256_storeu_pd(r.as_mut_ptr(), $a) }; r } }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_sum { ($a:expr) => { { let r4 = $a; \
         let r2 = _mm_add_pd(_mm256_castpd256_pd128(r4), _mm256_extractf128_pd::<1>(r4)); \
         _mm_cvtsd_f64(r2) + _mm_cvtsd_f64(_mm_unpackhi_pd(r2, r2)) } }; }\n"
    } else {
        "#[allow(unused_macros)] macro_rules! lanes { ($a:expr, $b:expr, $c:expr, $d:expr) => { [$a, $b, $c, $d] }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_splat { ($a:expr) => { [$a; 4] }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_add { ($a:expr, $b:expr) => { { let (p, q): ([f64; 4], [f64; 4]) = ($a, $b); \
         [p[0] + q[0], p[1] + q[1], p[2] + q[2], p[3] + q[3]] } }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_mul { ($a:expr, $b:expr) => { { let (p, q): ([f64; 4], [f64; 4]) = ($a, $b); \
         [p[0] * q[0], p[1] * q[1], p[2] * q[2], p[3] * q[3]] } }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_div { ($a:expr, $b:expr) => { { let (p, q): ([f64; 4], [f64; 4]) = ($a, $b); \
         [p[0] / q[0], p[1] / q[1], p[2] / q[2], p[3] / q[3]] } }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_array { ($a:expr) => { $a }; }\n\
         #[allow(unused_macros)] macro_rules! lanes_sum { ($a:expr) => { { let r: [f64; 4] = $a; (r[0] + r[2]) + (r[1] + r[3]) } }; }\n"
    }
}

/// The statements of `plan` for `f`: with AVX intrinsics (`avx`, for the
/// x86-64-v4 copy) or with `[f64; 4]` arrays. `libm` is the path of libm.
pub fn emit(f: &Function, plan: &Plan, avx: bool, libm: &str) -> String {
    let g = &f.graph;
    let p = plan;
    let mut out = String::from(prelude(avx));
    let input_name = |k: usize| match g.node(Id(k as u32)) {
        Node::Input(i) => Some(f.inputs[i as usize].name.clone()),
        _ => None,
    };
    let scalar = |id: Id| -> String {
        if let Some(v) = g.value(id) {
            return literal(v);
        }
        if let Some((q, l)) = p.pack_of[id.0 as usize] {
            return format!("l{q}[{l}]");
        }
        // sin and cos of an input are named after it, as in `emit`.
        let trig = match g.node(id) {
            Node::Sin(a) => input_name(a.0 as usize).map(|n| format!("s_{n}")),
            Node::Cos(a) => input_name(a.0 as usize).map(|n| format!("c_{n}")),
            _ => None,
        };
        trig.or_else(|| input_name(id.0 as usize))
            .unwrap_or_else(|| format!("t{}", id.0))
    };
    let signed = |q: usize, signs: &[bool; LANES]| -> String {
        if signs.iter().all(|s| !s) {
            return format!("v{q}");
        }
        let s: Vec<&str> = signs
            .iter()
            .map(|s| if *s { "-1.0" } else { "1.0" })
            .collect();
        format!("lanes_mul!(v{q}, lanes!({}))", s.join(", "))
    };
    let operand = |c: [Id; LANES]| -> String {
        match form(g, &p.pack_of, c) {
            Form::Splat(x) => format!("lanes_splat!({})", scalar(x)),
            Form::Pack(q, signs) => signed(q, &signs),
            Form::Consts | Form::Gather => {
                let v: Vec<String> = c.iter().map(|x| scalar(*x)).collect();
                format!("lanes!({})", v.join(", "))
            }
        }
    };
    let mut paired = vec![false; g.len()];
    for it in &p.order {
        match *it {
            Item::Scalar(k) => {
                if p.absorbed[k] {
                    continue;
                }
                let id = Id(k as u32);
                let name = scalar(id);
                if let Some(s) = p.sums.get(&k) {
                    let mut v = String::new();
                    for (i, (q, signs)) in s.packs.iter().enumerate() {
                        let term = signed(*q, signs);
                        v = if i == 0 {
                            term
                        } else {
                            format!("lanes_add!({v}, {term})")
                        };
                    }
                    let mut line = format!("let {name} = lanes_sum!({v})");
                    for (x, neg) in &s.rest {
                        let _ = write!(line, " {} {}", if *neg { "-" } else { "+" }, scalar(*x));
                    }
                    let _ = writeln!(out, "{line};");
                    continue;
                }
                let rhs = match g.node(id) {
                    Node::Const(_) => continue,
                    Node::Input(i) => f.inputs[i as usize].access.clone(),
                    Node::Add(a, b) => match g.node(b) {
                        Node::Neg(y) => format!("{} - {}", scalar(a), scalar(y)),
                        _ => format!("{} + {}", scalar(a), scalar(b)),
                    },
                    Node::Mul(a, b) => format!("{} * {}", scalar(a), scalar(b)),
                    Node::Div(a, b) => format!("{} / {}", scalar(a), scalar(b)),
                    Node::Neg(a) => format!("-{}", scalar(a)),
                    Node::Sin(a) | Node::Cos(a) => {
                        if paired[k] {
                            continue;
                        }
                        let (s, c) = (g.find(Node::Sin(a)), g.find(Node::Cos(a)));
                        if let (Some(s), Some(c)) = (s, c)
                            && p.order.contains(&Item::Scalar(s.0 as usize))
                            && p.order.contains(&Item::Scalar(c.0 as usize))
                        {
                            paired[s.0 as usize] = true;
                            paired[c.0 as usize] = true;
                            let _ = writeln!(
                                out,
                                "let ({}, {}) = {libm}::sincos({});",
                                scalar(s),
                                scalar(c),
                                scalar(a)
                            );
                            continue;
                        }
                        function(g.node(id), scalar, libm).unwrap_or_default()
                    }
                    node => function(node, scalar, libm).unwrap_or_default(),
                };
                let _ = writeln!(out, "let {name} = {rhs};");
            }
            Item::Pack(q) => {
                let m = p.packs[q];
                if q < p.inputs {
                    let v: Vec<String> = m
                        .iter()
                        .map(|x| match g.node(*x) {
                            Node::Input(i) => f.inputs[i as usize].access.clone(),
                            _ => scalar(*x),
                        })
                        .collect();
                    let _ = writeln!(out, "let v{q} = lanes!({});", v.join(", "));
                } else {
                    let a = operand(operand_lanes(g, &p.pack_of, &p.shared, m, 0));
                    let b = operand(operand_lanes(g, &p.pack_of, &p.shared, m, 1));
                    let op = match g.node(m[0]) {
                        Node::Add(..) => "lanes_add",
                        Node::Mul(..) => "lanes_mul",
                        _ => "lanes_div",
                    };
                    let _ = writeln!(out, "let v{q} = {op}!({a}, {b});");
                }
                if p.extracted[q] {
                    let _ = writeln!(out, "let l{q} = lanes_array!(v{q});");
                }
            }
        }
    }
    for o in &f.outputs {
        let _ = writeln!(out, "{} {};", o.place, scalar(o.id));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four wheels' `a_l·s + c_l` (front lanes +, rear lanes − offsets),
    /// their sum, and one lane read alone; inputs a0…a3 then s.
    fn wheels(build_extra: bool) -> Function {
        Function::for_test(&["a0", "a1", "a2", "a3", "s"], |g| {
            let s = g.input(4);
            let mut outs = Vec::new();
            let mut total = g.cst(0.5);
            for l in 0..4u32 {
                let a = g.input(l);
                let p = g.mul(a, s);
                let c = g.cst(if l < 2 { 0.25 } else { -0.25 });
                let y = g.add(p, c);
                // Rear lanes enter the sum negated.
                total = if l < 2 {
                    g.add(total, y)
                } else {
                    g.sub(total, y)
                };
                outs.push(y);
            }
            if build_extra {
                // A lane that does something else: not a pack.
                let a3 = g.input(3);
                let odd = g.div(a3, s);
                outs.push(odd);
            }
            outs.push(total);
            outs
        })
    }

    fn lanes_of(f: &Function) -> Vec<[u32; LANES]> {
        seeds(f, |k| (k < 4).then(|| ("a".to_string(), k)))
    }

    #[test]
    fn the_same_operation_on_four_lanes_is_one_pack_and_their_sum_one_lane_sum() {
        let f = wheels(true);
        let seeds = lanes_of(&f);
        assert_eq!(seeds, [[0, 1, 2, 3]]);
        let plan = plan(&f, &seeds).expect("packs");
        // a·s and + c in four lanes; the division of lane 3 alone stays scalar.
        assert_eq!(plan.vector_ops(), 2);
        assert_eq!((plan.packed_ops, plan.total_ops), (8, 13));
        assert_eq!(plan.lane_sums(), 1);
        let avx = emit(&f, &plan, true, "::libm");
        let arrays = emit(&f, &plan, false, "::libm");
        for text in [&avx, &arrays] {
            assert!(text.contains("lanes_mul!(v0, lanes_splat!(s))"), "{text}");
            // The offsets are lane constants; the rear lanes' signs a lane factor.
            assert!(text.contains("lanes!(0.25, 0.25, -0.25, -0.25)"), "{text}");
            assert!(
                text.contains("lanes_sum!(lanes_mul!(v2, lanes!(1.0, 1.0, -1.0, -1.0))) + 0.5"),
                "{text}"
            );
        }
        assert!(avx.contains("_mm256_add_pd") && !arrays.contains("_mm256"));
    }

    #[test]
    fn shared_values_that_differ_from_lane_to_lane_are_gathered() {
        // Left lanes scale by s, right lanes by r (a body point's velocity
        // on each side): one pack, its factor gathered lane by lane.
        let f = Function::for_test(&["a0", "a1", "a2", "a3", "s", "r"], |g| {
            let (s, r) = (g.input(4), g.input(5));
            (0..4u32)
                .map(|l| {
                    let a = g.input(l);
                    g.mul(a, if l % 2 == 0 { s } else { r })
                })
                .collect()
        });
        let seeds = lanes_of(&f);
        let plan = plan(&f, &seeds).expect("packs");
        assert_eq!(plan.vector_ops(), 1);
        let text = emit(&f, &plan, false, "::libm");
        assert!(
            text.contains("lanes_mul!(v0, lanes!(s, r, s, r))"),
            "{text}"
        );
    }

    #[test]
    fn nothing_packs_without_four_matching_lanes() {
        // Three lanes only: no input pack, so no plan.
        let f = wheels(false);
        let three = seeds(&f, |k| (k < 3).then(|| ("a".to_string(), k)));
        assert!(three.is_empty());
        assert!(plan(&f, &three).is_none());
        // Two inputs claiming one lane: the group is dropped.
        let clash = seeds(&f, |k| (k < 4).then(|| ("a".to_string(), k.min(2))));
        assert!(clash.is_empty());
    }
}
