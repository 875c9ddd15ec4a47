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

/// A node's pack and lane, if it is packed.
type Slot = Option<(usize, usize)>;

/// The packing of one function.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The packs: lane l of pack p is node `packs[p][l]`.
    packs: Vec<[Id; LANES]>,
    /// The first `inputs` packs are input packs (read, not computed).
    inputs: usize,
    /// Pack and lane of every node, if packed.
    pack_of: Vec<Slot>,
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
fn form(g: &Graph, pack_of: &[Slot], c: [Id; LANES]) -> Form {
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
    pack_of: &[Slot],
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
    let reach = reach(f);
    let (mut packs, mut pack_of) = input_packs(g, seeds);
    let inputs = packs.len();
    let shared = shared(g, &pack_of);
    grow(g, &reach, &shared, &mut packs, &mut pack_of);
    if packs.len() == inputs {
        return None;
    }
    let arith = |k: usize| {
        reach[k]
            && matches!(
                g.node(Id(k as u32)),
                Node::Add(..) | Node::Mul(..) | Node::Div(..)
            )
    };
    let total_ops = (0..g.len()).filter(|&k| arith(k)).count();
    let packed_ops = (0..g.len())
        .filter(|&k| arith(k) && pack_of[k].is_some())
        .count();
    let (sums, absorbed) = lane_sums(f, &reach, &pack_of);
    let order = statement_order(f, &packs, &pack_of)?;
    let mut plan = Plan {
        extracted: vec![false; packs.len()],
        packs,
        inputs,
        pack_of,
        shared,
        order,
        sums,
        absorbed,
        packed_ops,
        total_ops,
    };
    plan.extracted = extracted(f, &plan);
    Some(plan)
}

/// Whether an output of `f` needs each node of its graph.
fn reach(f: &Function) -> Vec<bool> {
    let g = &f.graph;
    let mut reach = vec![false; g.len()];
    for o in &f.outputs {
        reach[o.id.0 as usize] = true;
    }
    for k in (0..g.len()).rev() {
        if reach[k] {
            for c in g.node(Id(k as u32)).children() {
                reach[c.0 as usize] = true;
            }
        }
    }
    reach
}

/// The input packs of `seeds` (each a group of four inputs, one per
/// lane) whose inputs are all in the graph, and each node's pack and lane.
fn input_packs(g: &Graph, seeds: &[[u32; LANES]]) -> (Vec<[Id; LANES]>, Vec<Slot>) {
    let input_node: HashMap<u32, Id> = (0..g.len())
        .filter_map(|k| match g.node(Id(k as u32)) {
            Node::Input(i) => Some((i, Id(k as u32))),
            _ => None,
        })
        .collect();
    let mut packs: Vec<[Id; LANES]> = Vec::new();
    let mut pack_of: Vec<Slot> = vec![None; g.len()];
    for s in seeds {
        let ids: Option<Vec<Id>> = s.iter().map(|k| input_node.get(k).copied()).collect();
        let Some(ids) = ids else { continue };
        let p = packs.len();
        for (l, id) in ids.iter().enumerate() {
            pack_of[id.0 as usize] = Some((p, l));
        }
        packs.push([ids[0], ids[1], ids[2], ids[3]]);
    }
    (packs, pack_of)
}

/// The nodes that no input of a lane reaches.
fn shared(g: &Graph, pack_of: &[Slot]) -> Vec<bool> {
    let mut shared = vec![true; g.len()];
    for k in 0..g.len() {
        shared[k] = match g.node(Id(k as u32)) {
            Node::Input(_) => pack_of[k].is_none(),
            node => node.children().all(|c| shared[c.0 as usize]),
        };
    }
    shared
}

/// Bottom-up to a fixed point: a node joins a pack when the nodes of the
/// other lanes with the same shape exist; the k-th candidate of each lane
/// are matched (the trace runs the same code for every wheel, so their
/// order of appearance agrees).
fn grow(
    g: &Graph,
    reach: &[bool],
    shared: &[bool],
    packs: &mut Vec<[Id; LANES]>,
    pack_of: &mut [Slot],
) {
    loop {
        let buckets = candidates(g, reach, shared, pack_of);
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
}

/// The unpacked arithmetic nodes whose operands are packed in one lane, by
/// shape (operation and operand kinds) and lane, in graph order.
fn candidates(
    g: &Graph,
    reach: &[bool],
    shared: &[bool],
    pack_of: &[Slot],
) -> HashMap<(u8, Vec<Kind>), [Vec<Id>; LANES]> {
    let mut buckets: HashMap<(u8, Vec<Kind>), [Vec<Id>; LANES]> = HashMap::new();
    for k in 0..g.len() {
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
            let (kind, l) = kind_of(g, pack_of, shared, c);
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
    buckets
}

/// Sums: maximal trees of unpacked additions and negations whose inner
/// nodes have one user, an unpacked addition or negation. Those that add
/// all four lanes of some packs (each lane once), by root, and the inner
/// nodes of those trees, absorbed.
fn lane_sums(
    f: &Function,
    reach: &[bool],
    pack_of: &[Slot],
) -> (HashMap<usize, LaneSum>, Vec<bool>) {
    let g = &f.graph;
    let inner = sum_inner(f, reach, pack_of);
    let mut sums = HashMap::new();
    let mut absorbed = vec![false; g.len()];
    for k in 0..g.len() {
        if !reach[k]
            || pack_of[k].is_some()
            || inner[k]
            || !matches!(g.node(Id(k as u32)), Node::Add(..))
        {
            continue;
        }
        let (leaves, inside) = sum_terms(g, k, &inner);
        let Some(sum) = lane_sum(leaves, pack_of) else {
            continue;
        };
        for i in inside {
            absorbed[i] = true;
        }
        sums.insert(k, sum);
    }
    (sums, absorbed)
}

/// The nodes inside a sum: unpacked additions and negations used once, by
/// an unpacked addition or negation (an output is not inside).
fn sum_inner(f: &Function, reach: &[bool], pack_of: &[Slot]) -> Vec<bool> {
    let g = &f.graph;
    let linear = |k: usize| {
        pack_of[k].is_none() && matches!(g.node(Id(k as u32)), Node::Add(..) | Node::Neg(_))
    };
    let mut uses = vec![0usize; g.len()];
    let mut linear_users = vec![true; g.len()];
    for k in 0..g.len() {
        if !reach[k] {
            continue;
        }
        for c in g.node(Id(k as u32)).children() {
            uses[c.0 as usize] += 1;
            linear_users[c.0 as usize] &= linear(k);
        }
    }
    for o in &f.outputs {
        uses[o.id.0 as usize] += 2;
    }
    (0..g.len())
        .map(|k| linear(k) && uses[k] == 1 && linear_users[k])
        .collect()
}

/// The terms of the sum rooted at `root`, with their signs, and the nodes
/// inside it.
fn sum_terms(g: &Graph, root: usize, inner: &[bool]) -> (Vec<(Id, bool)>, Vec<usize>) {
    let mut leaves: Vec<(Id, bool)> = Vec::new();
    let mut inside: Vec<usize> = Vec::new();
    let mut stack = vec![(Id(root as u32), false)];
    while let Some((x, neg)) = stack.pop() {
        let xi = x.0 as usize;
        let expand = xi == root || inner[xi];
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
        if xi != root {
            inside.push(xi);
        }
    }
    (leaves, inside)
}

/// The sum of `leaves` regrouped lane-wise: the packs all four of whose
/// lanes it adds, and the other terms; `None` when no pack is whole or a
/// lane is added twice.
fn lane_sum(leaves: Vec<(Id, bool)>, pack_of: &[Slot]) -> Option<LaneSum> {
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
        return None;
    }
    full.sort_by_key(|(p, _)| *p);
    let rest = leaves
        .into_iter()
        .filter(|(x, _)| {
            !pack_of[x.0 as usize].is_some_and(|(p, _)| full.iter().any(|(q, _)| *q == p))
        })
        .collect();
    Some(LaneSum { packs: full, rest })
}

/// Statement order: depth-first from the outputs, packs as one item;
/// `None` when a pack's lanes depend on each other.
fn statement_order(f: &Function, packs: &[[Id; LANES]], pack_of: &[Slot]) -> Option<Vec<Item>> {
    let g = &f.graph;
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
                    Some(false) => return None,
                    None => stack.push((d, false)),
                }
            }
        }
    }
    Some(order)
}

/// The packs whose lanes are read one by one: by scalar statements, by
/// outputs, and by packs that gather their operands lane by lane.
fn extracted(f: &Function, plan: &Plan) -> Vec<bool> {
    let g = &f.graph;
    let pack_of = &plan.pack_of;
    let mut extracted = vec![false; plan.packs.len()];
    let mut mark = |id: Id| {
        if let Some((p, _)) = pack_of[id.0 as usize] {
            extracted[p] = true;
        }
    };
    for it in &plan.order {
        let Item::Scalar(k) = *it else { continue };
        match plan.sums.get(&k) {
            Some(s) => s.rest.iter().for_each(|(x, _)| mark(*x)),
            None if plan.absorbed[k] => {}
            None => g.node(Id(k as u32)).children().for_each(&mut mark),
        }
    }
    f.outputs.iter().for_each(|o| mark(o.id));
    for members in &plan.packs[plan.inputs..] {
        for i in 0..2 {
            let c = operand_lanes(g, pack_of, &plan.shared, *members, i);
            if form(g, pack_of, c) == Form::Gather {
                c.into_iter().for_each(&mut mark);
            }
        }
    }
    extracted
}

/// The operand kind of child `c` and its lane, if packed (a negation of a
/// packed node is that pack, negated in its lane).
fn kind_of(g: &Graph, pack_of: &[Slot], shared: &[bool], c: Id) -> (Kind, Option<usize>) {
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
    let mut w = Writer {
        f,
        plan,
        libm,
        paired: vec![false; f.graph.len()],
        out: String::from(prelude(avx)),
    };
    for it in &plan.order {
        match *it {
            Item::Scalar(k) => w.scalar_statement(k),
            Item::Pack(q) => w.pack_statement(q),
        }
    }
    for o in &f.outputs {
        let value = w.scalar(o.id);
        let _ = writeln!(w.out, "{} {value};", o.place);
    }
    w.out
}

/// The statements of a plan, as they are written.
struct Writer<'a> {
    f: &'a Function,
    plan: &'a Plan,
    libm: &'a str,
    /// The sines and cosines already computed by a `sincos`.
    paired: Vec<bool>,
    out: String,
}

impl Writer<'_> {
    /// Node `id` as a scalar: a literal, a lane of its pack (`l3[1]`), an
    /// input's name, `s_`/`c_` and the input's name for sin and cos of an
    /// input (as [`crate::emit`] names them), or `t` and its index.
    fn scalar(&self, id: Id) -> String {
        let g = &self.f.graph;
        if let Some(v) = g.value(id) {
            return literal(v);
        }
        if let Some((q, l)) = self.plan.pack_of[id.0 as usize] {
            return format!("l{q}[{l}]");
        }
        let trig = match g.node(id) {
            Node::Sin(a) => self.input_name(a).map(|n| format!("s_{n}")),
            Node::Cos(a) => self.input_name(a).map(|n| format!("c_{n}")),
            _ => None,
        };
        trig.or_else(|| self.input_name(id))
            .unwrap_or_else(|| format!("t{}", id.0))
    }

    fn input_name(&self, id: Id) -> Option<String> {
        match self.f.graph.node(id) {
            Node::Input(i) => Some(self.f.inputs[i as usize].name.clone()),
            _ => None,
        }
    }

    /// Pack `q` as a vector, negated in the lanes marked in `signs` (a
    /// product with ±1, exact).
    fn signed(&self, q: usize, signs: &[bool; LANES]) -> String {
        if signs.iter().all(|s| !s) {
            return format!("v{q}");
        }
        let s: Vec<&str> = signs
            .iter()
            .map(|s| if *s { "-1.0" } else { "1.0" })
            .collect();
        format!("lanes_mul!(v{q}, lanes!({}))", s.join(", "))
    }

    /// An operand of a pack, from its four lanes' nodes `c`.
    fn operand(&self, c: [Id; LANES]) -> String {
        match form(&self.f.graph, &self.plan.pack_of, c) {
            Form::Splat(x) => format!("lanes_splat!({})", self.scalar(x)),
            Form::Pack(q, signs) => self.signed(q, &signs),
            Form::Consts | Form::Gather => {
                let v: Vec<String> = c.iter().map(|x| self.scalar(*x)).collect();
                format!("lanes!({})", v.join(", "))
            }
        }
    }

    /// The `let` of scalar node `k`: a sum over the lanes, a `sincos`, or
    /// the node's operation on scalars; nothing for a node inside a sum.
    fn scalar_statement(&mut self, k: usize) {
        if self.plan.absorbed[k] {
            return;
        }
        if let Some(s) = self.plan.sums.get(&k) {
            self.sum_statement(k, s);
            return;
        }
        let f = self.f;
        let g = &f.graph;
        let id = Id(k as u32);
        if let Node::Sin(a) | Node::Cos(a) = g.node(id)
            && (self.paired[k] || self.sincos_statement(a))
        {
            return;
        }
        let scalar = |x: Id| self.scalar(x);
        let rhs = match g.node(id) {
            Node::Const(_) => return,
            Node::Input(i) => f.inputs[i as usize].access.clone(),
            Node::Add(a, b) => match g.node(b) {
                Node::Neg(y) => format!("{} - {}", scalar(a), scalar(y)),
                _ => format!("{} + {}", scalar(a), scalar(b)),
            },
            Node::Mul(a, b) => format!("{} * {}", scalar(a), scalar(b)),
            Node::Div(a, b) => format!("{} / {}", scalar(a), scalar(b)),
            Node::Neg(a) => format!("-{}", scalar(a)),
            node => function(node, scalar, self.libm).unwrap_or_default(),
        };
        let name = self.scalar(id);
        let _ = writeln!(self.out, "let {name} = {rhs};");
    }

    /// The sum rooted at node `k`, regrouped lane-wise: its packs added
    /// as vectors, their lanes summed once, then its other terms.
    fn sum_statement(&mut self, k: usize, s: &LaneSum) {
        let mut v = String::new();
        for (i, (q, signs)) in s.packs.iter().enumerate() {
            let term = self.signed(*q, signs);
            v = if i == 0 {
                term
            } else {
                format!("lanes_add!({v}, {term})")
            };
        }
        let name = self.scalar(Id(k as u32));
        let mut line = format!("let {name} = lanes_sum!({v})");
        for (x, neg) in &s.rest {
            let _ = write!(
                line,
                " {} {}",
                if *neg { "-" } else { "+" },
                self.scalar(*x)
            );
        }
        let _ = writeln!(self.out, "{line};");
    }

    /// One `sincos` for sin and cos of `a` when both are statements;
    /// whether it was written.
    fn sincos_statement(&mut self, a: Id) -> bool {
        let g = &self.f.graph;
        let order = &self.plan.order;
        let (Some(s), Some(c)) = (g.find(Node::Sin(a)), g.find(Node::Cos(a))) else {
            return false;
        };
        if !order.contains(&Item::Scalar(s.0 as usize))
            || !order.contains(&Item::Scalar(c.0 as usize))
        {
            return false;
        }
        self.paired[s.0 as usize] = true;
        self.paired[c.0 as usize] = true;
        let (sin, cos, angle) = (self.scalar(s), self.scalar(c), self.scalar(a));
        let _ = writeln!(
            self.out,
            "let ({sin}, {cos}) = {}::sincos({angle});",
            self.libm
        );
        true
    }

    /// The `let` of pack `q`: its four inputs read, or its operation on its
    /// operands; then its lanes as an array if they are read one by one.
    fn pack_statement(&mut self, q: usize) {
        let (g, p) = (&self.f.graph, self.plan);
        let m = p.packs[q];
        let value = if q < p.inputs {
            let v: Vec<String> = m
                .iter()
                .map(|x| match g.node(*x) {
                    Node::Input(i) => self.f.inputs[i as usize].access.clone(),
                    _ => self.scalar(*x),
                })
                .collect();
            format!("lanes!({})", v.join(", "))
        } else {
            let a = self.operand(operand_lanes(g, &p.pack_of, &p.shared, m, 0));
            let b = self.operand(operand_lanes(g, &p.pack_of, &p.shared, m, 1));
            let op = match g.node(m[0]) {
                Node::Add(..) => "lanes_add",
                Node::Mul(..) => "lanes_mul",
                _ => "lanes_div",
            };
            format!("{op}!({a}, {b})")
        };
        let _ = writeln!(self.out, "let v{q} = {value};");
        if p.extracted[q] {
            let _ = writeln!(self.out, "let l{q} = lanes_array!(v{q});");
        }
    }
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
