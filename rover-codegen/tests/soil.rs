//! The soil law through the generator: traced with symbolic scalars, its
//! graph gives the `f64` law's forces, and the graph's derivatives give the
//! dual numbers', to rounding. What a generated plant on soil will carry.

use rover_codegen::Sym;
use rover_codegen::diff::derivative;
use rover_codegen::sym::trace;
use rover_dynamics::dual::Dual;
use rover_dynamics::soil::{GaussLegendre, Soil, SoilContact, SoilForces, SoilWheel, soil_forces};

fn lunar() -> Soil {
    Soil {
        n: 0.85,
        k_c: 1400.0,
        k_phi: 820e3,
        cohesion: 170.0,
        friction_angle: 35f64.to_radians(),
        shear_modulus: 0.018,
        lateral_shear_modulus: 0.012,
        a0: 0.4,
        a1: 0.15,
        rear_ratio: 0.2,
        unit_weight: 15_000.0,
        reload_k0: 0.0,
        reload_au: 5.03e8,
    }
}

fn parts<S: Copy>(f: &SoilForces<S>) -> [S; 4] {
    [f.vertical, f.drawbar, f.torque, f.lateral]
}

#[test]
fn the_traced_soil_law_is_the_f64_law_and_its_derivatives_the_duals() {
    let (soil, r, b) = (lunar(), 0.4, 0.23);
    let rule = GaussLegendre::<12>::new();
    let (forces, mut graph) = trace(|| {
        let c = SoilContact {
            entry_angle: Sym::input(0),
            slip: Sym::input(1),
            slip_angle: Sym::input(2),
        };
        parts(&soil_forces(&SoilWheel::new(&soil, r, b), c, &rule))
    });
    let outputs: Vec<_> = forces.iter().map(|s| s.0).collect();
    let inputs: Vec<_> = (0..3).map(|k| graph.input(k)).collect();
    let d_theta = derivative(&mut graph, &outputs, inputs[0]);
    let d_slip = derivative(&mut graph, &outputs, inputs[1]);
    for (theta1, slip, beta) in [(0.3, 0.25, 0.05), (0.5, -0.4, -0.1), (0.12, 0.7, 0.0)] {
        let values = graph.eval(&[theta1, slip, beta], &outputs);
        let exact = parts(&soil_forces(
            &SoilWheel::new(&soil, r, b),
            SoilContact {
                entry_angle: theta1,
                slip,
                slip_angle: beta,
            },
            &rule,
        ));
        let scale = exact[0].abs();
        for k in 0..4 {
            assert!(
                (values[k] - exact[k]).abs() <= 1e-12 * scale,
                "θ1 {theta1}, s {slip}: output {k}: {} vs {}",
                values[k],
                exact[k]
            );
        }
        for (wrt, ids) in [(0, &d_theta), (1, &d_slip)] {
            let dual = |k: usize| if wrt == k { Dual::var } else { Dual::lift };
            let c = SoilContact {
                entry_angle: dual(0)(theta1),
                slip: dual(1)(slip),
                slip_angle: Dual::lift(beta),
            };
            let want = parts(&soil_forces(&SoilWheel::new(&soil, r, b), c, &rule));
            let got = graph.eval(&[theta1, slip, beta], ids);
            for k in 0..4 {
                let w = want[k].eps;
                assert!(
                    (got[k] - w).abs() <= 1e-9 * (1.0 + w.abs()),
                    "∂/∂input {wrt} of output {k}: {} vs {w}",
                    got[k]
                );
            }
        }
    }
}
