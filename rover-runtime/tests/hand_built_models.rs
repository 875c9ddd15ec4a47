//! The model files against the paper, through an independent route: the
//! parsed `exomars` and `swing4` give the same dynamics as the hand-built
//! models of MODEL.md §10 (`rover_test_support::hand_models`).

use rover_dynamics::plant::{Plant, WheelLoad};
use rover_runtime::GenericPlant;
use rover_test_support::hand_models::{exomars, swing4};
use rover_test_support::rng::Rng;

#[test]
fn parsed_paper_rovers_have_the_hand_built_dynamics() {
    let mut rng = Rng::new(11);
    for (name, hand) in [("exomars", exomars()), ("swing4", swing4())] {
        let spec = rover_spec::load_str(rover_models::builtin(name).unwrap(), name).unwrap();
        let parsed = spec.model;
        assert_eq!(parsed.dof(), hand.dof(), "{name}: DOF");
        assert_eq!(parsed.wheels.len(), hand.wheels.len());
        assert_eq!(parsed.gravity, hand.gravity);
        assert_eq!(parsed.total_mass(), hand.total_mass());
        let n = hand.dof();
        let (mut a, mut b) = (
            GenericPlant::new(hand.clone()).unwrap(),
            GenericPlant::new(parsed.clone()).unwrap(),
        );
        for _ in 0..50 {
            let mut x: Vec<f64> = (0..n).map(|_| rng.uniform(-0.3, 0.3)).collect();
            for (i, c) in hand.coordinates.iter().enumerate() {
                x[6 + i] = rng.uniform(c.min, c.max);
            }
            let w: Vec<f64> = (0..n).map(|_| rng.uniform(-0.5, 0.5)).collect();
            let loads: Vec<WheelLoad> = (0..hand.wheels.len())
                .map(|_| WheelLoad {
                    force: [
                        rng.uniform(-9.0, 9.0),
                        rng.uniform(-9.0, 9.0),
                        rng.uniform(0.0, 20.0),
                    ],
                    ..Default::default()
                })
                .collect();
            let (mut xa, mut wa, mut xb, mut wb) =
                (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            a.derivatives(&x, &w, &loads, &mut xa, &mut wa).unwrap();
            b.derivatives(&x, &w, &loads, &mut xb, &mut wb).unwrap();
            for k in 0..n {
                assert!(
                    (wa[k] - wb[k]).abs() < 1e-10 * (1.0 + wa[k].abs()),
                    "{name}: ẇ[{k}] hand {} vs file {}",
                    wa[k],
                    wb[k]
                );
            }
        }
    }
}
