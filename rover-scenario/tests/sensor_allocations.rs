//! The sensors' path allocates nothing per sample once built: the
//! simulator turning a truth into a sample, and the sensor log writing its
//! row. Its own test binary: it installs a counting global allocator.

use rover_estimate::sensors::{
    EncoderConfig, HeadingFixConfig, ImuConfig, PositionFixConfig, SensorConfig,
    SuspensionEncoderConfig,
};
use rover_estimate::{SensorSimulator, Truth};
use rover_scenario::sensor_log::SensorLogWriter;

#[test]
fn a_thousand_samples_simulated_and_logged_allocate_nothing() {
    let config = SensorConfig {
        seed: 5,
        rate: 100.0,
        imu: Some(ImuConfig {
            gyro_noise_deg_per_sqrt_h: 0.2,
            gyro_bias_deg_per_h: 10.0,
            accel_noise_ug_per_sqrt_hz: 100.0,
            accel_bias_mg: 0.1,
            bias_time: 300.0,
            position: [0.1, 0.0, 0.05],
            orientation_deg: [0.0, 0.0, 90.0],
        }),
        wheel_encoders: Some(EncoderConfig { resolution: 1e-3 }),
        suspension_encoders: Some(SuspensionEncoderConfig {
            resolution: 1e-3,
            noise: 1e-4,
        }),
        position_fix: Some(PositionFixConfig {
            rate: 10.0,
            sigma: 0.05,
        }),
        heading_fix: Some(HeadingFixConfig {
            rate: 1.0,
            sigma: 0.01,
        }),
    };
    let (wheels, coordinates) = (6, 4);
    let mut sim = SensorSimulator::new(&config, wheels, coordinates).unwrap();
    let mut sample = sim.new_sample();
    let mut log = SensorLogWriter::new(std::io::sink(), &config, wheels, coordinates).unwrap();
    let n = 6 + coordinates;
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    let w_dot = vec![0.01; n];
    let rates = vec![1.0; wheels];
    let commands = vec![0.5; wheels];
    let mut step = |k: usize| {
        let t = k as f64 * 0.01;
        x[0] = 0.05 * t;
        x[6] = 0.1 * t.sin();
        w[0] = 0.05;
        w[5] = 0.02;
        let truth = Truth {
            t,
            x: &x,
            w: &w,
            w_dot: &w_dot,
            wheel_rates: &rates,
            torques: &commands,
            steering: &commands,
            gravity: 3.71,
        };
        sim.sample_into(&truth, &mut sample).unwrap();
        log.write(&sample).unwrap();
    };
    step(0);
    let counts = allocation_counter::measure(|| (1..=1000).for_each(&mut step));
    assert_eq!(counts.count_total, 0, "{} allocations", counts.count_total);
    // The counter counts: one Vec is one allocation.
    let probe = allocation_counter::measure(|| {
        std::hint::black_box(vec![1u8; 8]);
    });
    assert_eq!(probe.count_total, 1);
}
