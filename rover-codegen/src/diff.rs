//! Exact derivatives on the expression graph (forward mode, one input at a
//! time, every node's derivative memoized), for the generated Jacobians.
//!
//! ```text
//! d(a+b) = da + db         d(a·b) = da·b + a·db      d(a/b) = (da − (a/b)·db)/b
//! d sin a = cos a·da       d cos a = −sin a·da        d √a = da/(2√a)
//! d exp a = exp a·da       d|a| = copysign(1, a)·da
//! d atan2(a, b) = (b·da − a·db)/(a² + b²)
//! d max(a, b) = [a ≥ b]·da + (1 − [a ≥ b])·db        (min: the other way)
//! d copysign(a, b) = copysign(1, a)·copysign(1, b)·da
//! ```
//! The derivative nodes go into the same graph, so they share everything
//! with the values (sin and cos of an angle, products of M).

use crate::graph::{Graph, Id, Node};

/// ∂outputs/∂input for the input node `wrt`, as new nodes of `graph`.
pub fn derivative(graph: &mut Graph, outputs: &[Id], wrt: Id) -> Vec<Id> {
    let top = outputs.iter().map(|o| o.0 as usize + 1).max().unwrap_or(0);
    let zero = graph.cst(0.0);
    let one = graph.cst(1.0);
    let mut d = vec![zero; top];
    // Only nodes that depend on `wrt` have a derivative; they come after it.
    for k in (wrt.0 as usize)..top {
        let id = Id(k as u32);
        let node = graph.node(id);
        if id == wrt {
            d[k] = one;
            continue;
        }
        if node.children().all(|c| d[c.0 as usize] == zero) {
            continue;
        }
        let dd = |c: Id| d[c.0 as usize];
        d[k] = match node {
            Node::Const(_) | Node::Input(_) => zero,
            Node::Add(a, b) => graph.add(dd(a), dd(b)),
            Node::Mul(a, b) => {
                let (da, db) = (dd(a), dd(b));
                let l = graph.mul(da, b);
                let r = graph.mul(a, db);
                graph.add(l, r)
            }
            Node::Div(a, b) => {
                let (da, db) = (dd(a), dd(b));
                let q = graph.mul(id, db);
                let n = graph.sub(da, q);
                graph.div(n, b)
            }
            Node::Neg(a) => graph.neg(dd(a)),
            Node::Sin(a) => {
                let c = graph.cos(a);
                graph.mul(c, dd(a))
            }
            Node::Cos(a) => {
                let s = graph.sin(a);
                let p = graph.mul(s, dd(a));
                graph.neg(p)
            }
            Node::Sqrt(a) => {
                let two = graph.cst(2.0);
                let den = graph.mul(two, id);
                graph.div(dd(a), den)
            }
            Node::Exp(a) => graph.mul(id, dd(a)),
            Node::Ln(a) => graph.div(dd(a), a),
            Node::Abs(a) => {
                let s = graph.copysign(one, a);
                graph.mul(s, dd(a))
            }
            Node::Atan2(a, b) => {
                let (da, db) = (dd(a), dd(b));
                let l = graph.mul(b, da);
                let r = graph.mul(a, db);
                let n = graph.sub(l, r);
                let a2 = graph.mul(a, a);
                let b2 = graph.mul(b, b);
                let den = graph.add(a2, b2);
                graph.div(n, den)
            }
            Node::Max(a, b) | Node::Min(a, b) => {
                let (da, db) = (dd(a), dd(b));
                let pick_a = match node {
                    Node::Max(..) => graph.ge(a, b),
                    _ => graph.ge(b, a),
                };
                let pick_b = graph.sub(one, pick_a);
                let l = graph.mul(pick_a, da);
                let r = graph.mul(pick_b, db);
                graph.add(l, r)
            }
            Node::Copysign(a, b) => {
                let sa = graph.copysign(one, a);
                let sb = graph.copysign(one, b);
                let s = graph.mul(sa, sb);
                graph.mul(s, dd(a))
            }
            Node::Ge(..) => zero,
        };
    }
    outputs.iter().map(|o| d[o.0 as usize]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivative_of_a_product_of_trig_and_division() {
        let mut g = Graph::new();
        let (x, y) = (g.input(0), g.input(1));
        let s = g.sin(x);
        let p = g.mul(s, y);
        let q = g.div(p, x); // sin x · y / x
        let m = g.max(q, y);
        let dx = derivative(&mut g, &[q, m], x);
        let dy = derivative(&mut g, &[q], y);
        let (xv, yv) = (0.8f64, 1.3f64);
        let v = g.eval(&[xv, yv], &[dx[0], dy[0], dx[1]]);
        let expect_dx = yv * (xv.cos() * xv - xv.sin()) / (xv * xv);
        assert!((v[0] - expect_dx).abs() < 1e-15, "{} vs {expect_dx}", v[0]);
        assert!((v[1] - xv.sin() / xv).abs() < 1e-15);
        // q = 1.17 < y: max picks y, whose x-derivative is 0.
        assert_eq!(v[2], 0.0);
    }

    #[test]
    fn derivative_of_a_power_through_its_logarithm() {
        // x^n as exp(n·ln x), the form a soil's pressure–sinkage law takes.
        let mut g = Graph::new();
        let x = g.input(0);
        let l = g.ln(x);
        let n = g.cst(0.79);
        let nl = g.mul(n, l);
        let p = g.exp(nl);
        let dx = derivative(&mut g, &[p], x);
        let xv = 0.37f64;
        let v = g.eval(&[xv], &[p, dx[0]]);
        assert!((v[0] - xv.powf(0.79)).abs() < 1e-15, "{}", v[0]);
        let expect = 0.79 * xv.powf(-0.21);
        assert!((v[1] - expect).abs() < 1e-14, "{} vs {expect}", v[1]);
    }
}
