//! Integration tests of rover-dynamics (one binary): the equations'
//! invariants against independent routes, and the contact search against a
//! dense reference.

mod contact_accuracy;
mod dynamics;
mod lagrange;
