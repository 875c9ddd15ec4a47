//! A filter step allocates nothing: a prediction over 10 ms, an IMU
//! update and an encoder update, on swing4 and MER (their generated
//! plants) on the paper's rough terrain, and every other update and
//! output. Its own test binary: the counting allocator is global.

#[path = "support/rover.rs"]
mod rover;

use rover_dynamics::plant::Plant;
use rover_estimate::sensors::{HeadingFixConfig, PositionFixConfig, SuspensionEncoderConfig};
use rover_estimate::{Estimator, FilterConfig, InitialSigma};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;

fn steps_allocate_nothing<P: Plant + Clone>(name: &str, plant: P) {
    let (mut filter, steps) = rover::recorded(name, plant, 60, FilterConfig::default());
    // A warm-up step, then none may allocate.
    rover::replay(&mut filter, &steps[0]).unwrap();
    let counts = allocation_counter::measure(|| {
        for step in &steps[1..] {
            rover::replay(&mut filter, step).unwrap();
        }
    });
    assert_eq!(
        counts.count_total, 0,
        "{name}: {} allocations",
        counts.count_total
    );
}

#[test]
fn a_filter_step_allocates_nothing() {
    // The counter counts.
    let probe = allocation_counter::measure(|| {
        std::hint::black_box(vec![0u8; 1]);
    });
    assert_eq!(probe.count_total, 1);
    steps_allocate_nothing("swing4", rover_models::Swing4::new());
    steps_allocate_nothing("mer", rover_models::Mer::new());
}

/// The other updates and the outputs, on swing4, after a few steps.
#[test]
fn the_other_updates_and_outputs_allocate_nothing() {
    let (filter, steps) = rover::recorded(
        "swing4",
        rover_models::Swing4::new(),
        3,
        FilterConfig::default(),
    );
    let mut sensors = rover::imu_and_encoders();
    sensors.suspension_encoders = Some(SuspensionEncoderConfig {
        resolution: 1e-3,
        noise: 0.0,
    });
    sensors.position_fix = Some(PositionFixConfig {
        rate: 1.0,
        sigma: 0.05,
    });
    sensors.heading_fix = Some(HeadingFixConfig {
        rate: 1.0,
        sigma: 0.01,
    });
    let model: RoverSystem<_, Terrain> = filter.model().clone();
    let y = filter.state().to_vec();
    let mut filter = Estimator::new(
        model,
        &sensors,
        FilterConfig::default(),
        filter.time(),
        &y,
        &InitialSigma::default(),
    )
    .unwrap();
    filter.update_wheel_angles(&[0.0; 4]).unwrap();
    rover::replay(&mut filter, &steps[0]).unwrap();
    let n = filter.model().dof();
    let suspension = y[6..n].to_vec();
    let (mut sigma, mut normal, mut slip) = (vec![0.0; filter.error_dim()], [0.0; 4], [0.0; 4]);
    let mut rows = vec![0.0; 6 * filter.error_dim()];
    let counts = allocation_counter::measure(|| {
        rover::replay(&mut filter, &steps[1]).unwrap();
        filter.update_suspension(&suspension).unwrap();
        filter.update_position([y[0], y[1], y[2]]).unwrap();
        filter.update_heading(y[5]).unwrap();
        filter.sigma(&mut sigma).unwrap();
        filter.wheel_outputs(&mut normal, &mut slip).unwrap();
        filter.predicted_imu(Some(&mut rows)).unwrap();
        filter.nees(&y).unwrap();
        // A failing call restores the estimate without allocating either.
        assert!(filter.update_suspension(&[f64::NAN; 4]).is_err());
    });
    assert_eq!(counts.count_total, 0, "{} allocations", counts.count_total);
    assert!(normal.iter().all(|n| *n > 0.0), "{normal:?}");
}
