//! The symbolic scalar: a [`rover_dynamics::Scalar`] whose arithmetic
//! records nodes in a [`Graph`] instead of computing numbers.
//!
//! The equations of `rover-dynamics` are generic over `Scalar`; running them
//! with [`Sym`] inside [`trace`] yields the expression graph of the whole
//! computation, folded and shared as it is built. The graph of the running
//! trace lives in a thread-local slot (the `Scalar` trait's constructors,
//! `cst`, `zero`, take no context), so traces on different threads do not
//! interfere; a `Sym` made outside a trace is meaningless.

use std::cell::RefCell;
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

use rover_dynamics::Scalar;

use crate::graph::{Graph, Id};

thread_local! {
    static GRAPH: RefCell<Graph> = RefCell::new(Graph::new());
}

/// A symbolic real: a node of the graph being traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sym(pub Id);

/// Run `f` with a fresh graph and return its result with the graph.
/// Traces nest: the graph of an enclosing trace is restored afterwards.
pub fn trace<R>(f: impl FnOnce() -> R) -> (R, Graph) {
    let outer = GRAPH.with(|g| g.replace(Graph::new()));
    let r = f();
    let graph = GRAPH.with(|g| g.replace(outer));
    (r, graph)
}

fn with<R>(f: impl FnOnce(&mut Graph) -> R) -> R {
    GRAPH.with(|g| f(&mut g.borrow_mut()))
}

impl Sym {
    /// Input number `k` of the traced function.
    pub fn input(k: usize) -> Self {
        Sym(with(|g| g.input(u32::try_from(k).unwrap_or(u32::MAX))))
    }
}

impl Add for Sym {
    type Output = Sym;
    fn add(self, o: Sym) -> Sym {
        Sym(with(|g| g.add(self.0, o.0)))
    }
}
impl Sub for Sym {
    type Output = Sym;
    fn sub(self, o: Sym) -> Sym {
        Sym(with(|g| g.sub(self.0, o.0)))
    }
}
impl Mul for Sym {
    type Output = Sym;
    fn mul(self, o: Sym) -> Sym {
        Sym(with(|g| g.mul(self.0, o.0)))
    }
}
impl Div for Sym {
    type Output = Sym;
    fn div(self, o: Sym) -> Sym {
        Sym(with(|g| g.div(self.0, o.0)))
    }
}
impl Neg for Sym {
    type Output = Sym;
    fn neg(self) -> Sym {
        Sym(with(|g| g.neg(self.0)))
    }
}
impl AddAssign for Sym {
    fn add_assign(&mut self, o: Sym) {
        *self = *self + o;
    }
}
impl SubAssign for Sym {
    fn sub_assign(&mut self, o: Sym) {
        *self = *self - o;
    }
}
impl MulAssign for Sym {
    fn mul_assign(&mut self, o: Sym) {
        *self = *self * o;
    }
}

impl Scalar for Sym {
    fn cst(value: f64) -> Self {
        Sym(with(|g| g.cst(value)))
    }
    fn sin(self) -> Self {
        Sym(with(|g| g.sin(self.0)))
    }
    fn cos(self) -> Self {
        Sym(with(|g| g.cos(self.0)))
    }
    fn sqrt(self) -> Self {
        Sym(with(|g| g.sqrt(self.0)))
    }
    fn atan2(self, x: Self) -> Self {
        Sym(with(|g| g.atan2(self.0, x.0)))
    }
    fn exp(self) -> Self {
        Sym(with(|g| g.exp(self.0)))
    }
    fn ln(self) -> Self {
        Sym(with(|g| g.ln(self.0)))
    }
    fn abs(self) -> Self {
        Sym(with(|g| g.abs(self.0)))
    }
    fn max(self, other: Self) -> Self {
        Sym(with(|g| g.max(self.0, other.0)))
    }
    fn min(self, other: Self) -> Self {
        Sym(with(|g| g.min(self.0, other.0)))
    }
    fn copysign(self, sign: Self) -> Self {
        Sym(with(|g| g.copysign(self.0, sign.0)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rover_dynamics::linalg::cross;

    #[test]
    fn tracing_generic_code_records_a_shared_graph() {
        let ((c, d), graph) = trace(|| {
            let a = [Sym::input(0), Sym::input(1), Sym::input(2)];
            let b = [Sym::cst(1.0), Sym::zero(), Sym::input(3)];
            (cross(a, b), cross(a, b))
        });
        assert_eq!(c, d);
        // a × (1, 0, b3) = (a1·b3, a2 − a0·b3, −a1)
        let v = graph.eval(&[1.0, 2.0, 3.0, 4.0], &[c[0].0, c[1].0, c[2].0]);
        assert_eq!(v, vec![8.0, -1.0, -2.0]);
    }
}
