//! Scratch storage of the equations, sized once per model and reused, so
//! that nothing in a right-hand-side evaluation allocates: a real-time loop
//! never waits on the allocator.

use alloc::vec;
use alloc::vec::Vec;

use crate::linalg::M3;
use crate::model::Model;
use crate::scalar::Scalar;

/// Everything the equations compute at one state, reused across calls.
#[derive(Clone, Debug)]
pub struct Workspace<S> {
    /// Number of generalized coordinates N = 6 + m.
    pub dof: usize,
    /// Number of suspension coordinates m.
    pub m: usize,
    /// u_j per carried body, body components.
    pub u: Vec<[S; 3]>,
    /// S_j columns, `s[j*m + i] = ∂u_j/∂y_i`.
    pub s: Vec<[S; 3]>,
    /// Second derivatives, `h[j*m + i] = ∂²u_j/∂y_i²` (the Hessian is diagonal).
    pub h: Vec<[S; 3]>,
    /// Member angular velocity per unit rate, `a[j*m + i] = a_ij(y)`.
    pub a: Vec<[S; 3]>,
    /// `∂a_ij/∂y_i`.
    pub da: Vec<[S; 3]>,
    /// Member inertia in body components `R_m·J_j·R_mᵀ` (bodies with inertia).
    pub inertia: Vec<M3<S>>,
    /// Rate of the single member rotation of body j, `(coord, axis, α'(y))`
    /// (bodies with inertia and a rotating member).
    pub inertia_rate: Vec<Option<(usize, [f64; 3], S)>>,
    /// Mass matrix, row-major N×N.
    pub mass: Vec<S>,
    /// Right-hand side, then accelerations, N.
    pub rhs: Vec<S>,
    /// Momentum p = M·w, N.
    pub p: Vec<S>,
    /// Scratch row of length N.
    pub row: Vec<S>,
}

impl<S: Scalar> Workspace<S> {
    /// Storage for `model`.
    pub fn new(model: &Model) -> Self {
        let m = model.m();
        let n = model.bodies.len();
        let dof = model.dof();
        let z3 = [S::zero(); 3];
        Self {
            dof,
            m,
            u: vec![z3; n],
            s: vec![z3; n * m],
            h: vec![z3; n * m],
            a: vec![z3; n * m],
            da: vec![z3; n * m],
            inertia: vec![[z3; 3]; n],
            inertia_rate: vec![None; n],
            mass: vec![S::zero(); dof * dof],
            rhs: vec![S::zero(); dof],
            p: vec![S::zero(); dof],
            row: vec![S::zero(); dof],
        }
    }
}
