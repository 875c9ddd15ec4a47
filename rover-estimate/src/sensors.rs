//! What a rover's sensors read: their declaration ([`SensorConfig`], the
//! `[sensors]` table of a scenario, in the units of a datasheet) and one
//! instant's readings ([`SensorSample`], in SI).
//!
//! Every sensor but the sparse fixes is read at [`SensorConfig::rate`]:
//! - an IMU ([`ImuConfig`]) at a point of the body, its axes turned from
//!   the body's: the angular velocity (gyros) and the specific force
//!   (accelerometers, `a − g` in the IMU's axes), each with white noise and
//!   a bias that wanders as a first-order Gauss–Markov process;
//! - wheel encoders ([`EncoderConfig`]): each wheel's rotation since the
//!   start, quantized (they see slip where the soil law makes it);
//! - suspension encoders ([`SuspensionEncoderConfig`]): each suspension
//!   coordinate, with noise, quantized;
//! - sparse fixes at their own rates: a position ([`PositionFixConfig`]:
//!   visual odometry, a total station) and a heading
//!   ([`HeadingFixConfig`]: a sun sensor).

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

/// Standard gravity \[m/s²\], the unit `g` of accelerometer datasheets
/// (whatever the planet).
pub const STANDARD_GRAVITY: f64 = 9.806_65;

/// The sensors of a rover.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SensorConfig {
    /// Seed of the sensors' noise: the same seed, the same readings.
    #[cfg_attr(feature = "serde", serde(default))]
    pub seed: u64,
    /// Rate at which the IMU, the encoders and the suspension encoders are
    /// read \[Hz\] (100 by default).
    #[cfg_attr(feature = "serde", serde(default = "default_rate"))]
    pub rate: f64,
    /// The inertial measurement unit, if the rover has one.
    #[cfg_attr(feature = "serde", serde(default))]
    pub imu: Option<ImuConfig>,
    /// The wheel encoders, if the rover has them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub wheel_encoders: Option<EncoderConfig>,
    /// The suspension encoders, if the rover has them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub suspension_encoders: Option<SuspensionEncoderConfig>,
    /// A sparse position fix.
    #[cfg_attr(feature = "serde", serde(default))]
    pub position_fix: Option<PositionFixConfig>,
    /// A sparse heading fix.
    #[cfg_attr(feature = "serde", serde(default))]
    pub heading_fix: Option<HeadingFixConfig>,
}

#[cfg(feature = "serde")]
fn default_rate() -> f64 {
    100.0
}

/// An IMU, declared as its datasheet gives it.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ImuConfig {
    /// Gyro white noise, the angle random walk [°/√h].
    pub gyro_noise_deg_per_sqrt_h: f64,
    /// Gyro bias instability, the bias's standard deviation [°/h].
    pub gyro_bias_deg_per_h: f64,
    /// Accelerometer white noise density [µg/√Hz].
    pub accel_noise_ug_per_sqrt_hz: f64,
    /// Accelerometer bias instability, the bias's standard deviation \[mg\].
    pub accel_bias_mg: f64,
    /// Correlation time of the biases' wander \[s\] (300 by default).
    #[cfg_attr(feature = "serde", serde(default = "default_bias_time"))]
    pub bias_time: f64,
    /// The IMU's origin in body axes, from G \[m\].
    #[cfg_attr(feature = "serde", serde(default))]
    pub position: [f64; 3],
    /// The IMU's axes as roll, pitch, yaw from the body's [°] (docs/MODEL.md
    /// §1's order).
    #[cfg_attr(feature = "serde", serde(default))]
    pub orientation_deg: [f64; 3],
}

#[cfg(feature = "serde")]
fn default_bias_time() -> f64 {
    300.0
}

impl ImuConfig {
    /// Gyro white-noise density [rad/s/√Hz] (= rad/√s).
    pub fn gyro_noise_density(&self) -> f64 {
        self.gyro_noise_deg_per_sqrt_h.to_radians() / 60.0
    }
    /// Gyro bias standard deviation \[rad/s\].
    pub fn gyro_bias_sigma(&self) -> f64 {
        self.gyro_bias_deg_per_h.to_radians() / 3600.0
    }
    /// Accelerometer white-noise density [m/s²/√Hz].
    pub fn accel_noise_density(&self) -> f64 {
        self.accel_noise_ug_per_sqrt_hz * 1e-6 * STANDARD_GRAVITY
    }
    /// Accelerometer bias standard deviation [m/s²].
    pub fn accel_bias_sigma(&self) -> f64 {
        self.accel_bias_mg * 1e-3 * STANDARD_GRAVITY
    }
}

/// Wheel encoders (every wheel has one).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct EncoderConfig {
    /// One count \[rad\].
    pub resolution: f64,
}

/// Suspension encoders (every suspension coordinate has one), in the
/// coordinate's unit (rad, or m for a linear coordinate).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SuspensionEncoderConfig {
    /// One count (rad, or m).
    pub resolution: f64,
    /// White noise's standard deviation (rad, or m).
    #[cfg_attr(feature = "serde", serde(default))]
    pub noise: f64,
}

/// A sparse position fix.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PositionFixConfig {
    /// Fixes per second \[Hz\].
    pub rate: f64,
    /// Standard deviation of each coordinate \[m\].
    pub sigma: f64,
}

/// A sparse heading fix.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct HeadingFixConfig {
    /// Fixes per second \[Hz\].
    pub rate: f64,
    /// Standard deviation of the yaw ψ \[rad\].
    pub sigma: f64,
}

impl SensorConfig {
    /// A MEMS set read at 100 Hz with seed 0: an IMU at G, its axes the
    /// body's (gyros 0.2 °/√h and 10 °/h, accelerometers 100 µg/√Hz and
    /// 0.1 mg, biases wandering over 300 s), wheel encoders of 1 mrad and
    /// suspension encoders of 0.1° (in a linear coordinate's unit,
    /// 1.745 mm), without noise beyond their counts; no fix. What
    /// `rover drive --estimate` gives a rover whose scenario declares none.
    pub fn mems() -> Self {
        SensorConfig {
            seed: 0,
            rate: 100.0,
            imu: Some(ImuConfig {
                gyro_noise_deg_per_sqrt_h: 0.2,
                gyro_bias_deg_per_h: 10.0,
                accel_noise_ug_per_sqrt_hz: 100.0,
                accel_bias_mg: 0.1,
                bias_time: 300.0,
                position: [0.0; 3],
                orientation_deg: [0.0; 3],
            }),
            wheel_encoders: Some(EncoderConfig { resolution: 1e-3 }),
            suspension_encoders: Some(SuspensionEncoderConfig {
                resolution: 0.1_f64.to_radians(),
                noise: 0.0,
            }),
            position_fix: None,
            heading_fix: None,
        }
    }
}

/// One instant's readings, in SI. A sensor the rover does not have, or a
/// fix not due, reads `None` or an empty slice.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SensorSample {
    /// Time \[s\].
    pub t: f64,
    /// Gyros: angular velocity in the IMU's axes \[rad/s\].
    pub gyro: Option<[f64; 3]>,
    /// Accelerometers: specific force `a − g` in the IMU's axes [m/s²].
    pub accel: Option<[f64; 3]>,
    /// Each wheel's rotation since the start, quantized \[rad\], positive
    /// rolling forwards.
    pub wheel_angles: Vec<f64>,
    /// Each suspension coordinate (rad, or m).
    pub suspension: Vec<f64>,
    /// A position fix of G, inertial \[m\].
    pub position: Option<[f64; 3]>,
    /// A heading fix, the yaw ψ \[rad\].
    pub heading: Option<f64>,
    /// The motor torques the rover's computer commanded [N·m], in force
    /// until the next sample.
    pub torques: Vec<f64>,
    /// The steering angles it commanded \[rad\].
    pub steering: Vec<f64>,
}

impl SensorSample {
    /// A sample sized for `config` on a rover of `wheels` wheels and
    /// `coordinates` suspension coordinates, every reading zero and every
    /// fix absent: what [`crate::simulate::SensorSimulator::sample_into`]
    /// fills without allocating.
    pub fn sized(config: &SensorConfig, wheels: usize, coordinates: usize) -> Self {
        SensorSample {
            t: 0.0,
            gyro: config.imu.as_ref().map(|_| [0.0; 3]),
            accel: config.imu.as_ref().map(|_| [0.0; 3]),
            wheel_angles: alloc::vec![0.0; if config.wheel_encoders.is_some() { wheels } else { 0 }],
            suspension: alloc::vec![
                0.0;
                if config.suspension_encoders.is_some() {
                    coordinates
                } else {
                    0
                }
            ],
            position: None,
            heading: None,
            torques: alloc::vec![0.0; wheels],
            steering: alloc::vec![0.0; wheels],
        }
    }
}

/// A `[sensors]` declaration that cannot be used: the field's dotted path
/// in a scenario file, what is wrong and how to fix it.
#[derive(Clone, Debug, PartialEq)]
pub struct InvalidSensor {
    /// The field, as a scenario names it (`sensors.imu.bias_time`).
    pub field: &'static str,
    /// What is wrong (naming the field and its value) and, after
    /// `\n  = help: `, how to fix it.
    pub message: String,
}

impl core::fmt::Display for InvalidSensor {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(&self.message)
    }
}

impl core::error::Error for InvalidSensor {}

impl SensorConfig {
    /// The checks a declaration needs before it can be read: rates and
    /// correlation times > 0, noises and biases ≥ 0, resolutions and fix
    /// σ > 0, every number finite, and no fix faster than the sensors'
    /// rate (a fix is read at a sensor instant).
    pub fn check(&self) -> Result<(), InvalidSensor> {
        positive(
            "sensors.rate",
            self.rate,
            "readings per second of the IMU and the encoders [Hz], e.g. rate = 100.0",
        )?;
        if let Some(imu) = &self.imu {
            let unit = "a datasheet's figure, 0 for a perfect sensor";
            non_negative(
                "sensors.imu.gyro_noise_deg_per_sqrt_h",
                imu.gyro_noise_deg_per_sqrt_h,
                "the gyros' angle random walk [°/√h], e.g. 0.2",
                unit,
            )?;
            non_negative(
                "sensors.imu.gyro_bias_deg_per_h",
                imu.gyro_bias_deg_per_h,
                "the gyros' bias instability [°/h], e.g. 10.0",
                unit,
            )?;
            non_negative(
                "sensors.imu.accel_noise_ug_per_sqrt_hz",
                imu.accel_noise_ug_per_sqrt_hz,
                "the accelerometers' noise density [µg/√Hz], e.g. 100.0",
                unit,
            )?;
            non_negative(
                "sensors.imu.accel_bias_mg",
                imu.accel_bias_mg,
                "the accelerometers' bias instability [mg], e.g. 0.1",
                unit,
            )?;
            positive(
                "sensors.imu.bias_time",
                imu.bias_time,
                "the biases' correlation time [s], e.g. bias_time = 300.0",
            )?;
            finite(
                "sensors.imu.position",
                &imu.position,
                "the IMU's origin from G in body axes [m], e.g. position = [0.1, 0.0, 0.05]",
            )?;
            finite(
                "sensors.imu.orientation_deg",
                &imu.orientation_deg,
                "roll, pitch, yaw of the IMU's axes from the body's [°], e.g. orientation_deg = [0.0, 0.0, 90.0]",
            )?;
        }
        if let Some(e) = &self.wheel_encoders {
            positive(
                "sensors.wheel_encoders.resolution",
                e.resolution,
                "one count of the encoder [rad], e.g. resolution = 0.001 (2π/6283 counts a turn)",
            )?;
        }
        if let Some(e) = &self.suspension_encoders {
            positive(
                "sensors.suspension_encoders.resolution",
                e.resolution,
                "one count [rad, or m for a linear coordinate], e.g. resolution = 0.0017453 (0.1°)",
            )?;
            non_negative(
                "sensors.suspension_encoders.noise",
                e.noise,
                "the reading's white noise, a standard deviation [rad or m]",
                "0 for none",
            )?;
        }
        if let Some(f) = &self.position_fix {
            self.check_fix(
                ("sensors.position_fix.rate", "sensors.position_fix.sigma"),
                f.rate,
                f.sigma,
                "each coordinate's standard deviation [m], e.g. sigma = 0.05",
            )?;
        }
        if let Some(f) = &self.heading_fix {
            self.check_fix(
                ("sensors.heading_fix.rate", "sensors.heading_fix.sigma"),
                f.rate,
                f.sigma,
                "the yaw's standard deviation [rad], e.g. sigma = 0.01",
            )?;
        }
        Ok(())
    }

    /// A fix's rate (> 0, at most the sensors' rate) and σ (> 0).
    fn check_fix(
        &self,
        (rate_field, sigma_field): (&'static str, &'static str),
        rate: f64,
        sigma: f64,
        sigma_help: &str,
    ) -> Result<(), InvalidSensor> {
        positive(rate_field, rate, "fixes per second [Hz], e.g. rate = 0.1")?;
        if rate > self.rate {
            return Err(InvalidSensor {
                field: rate_field,
                message: format!(
                    "{rate_field} = {rate} Hz is faster than sensors.rate = {} Hz: a fix is read at a sensor instant\n  = help: give the fix a rate of at most {} Hz, or raise sensors.rate",
                    self.rate, self.rate
                ),
            });
        }
        if !(sigma.is_finite() && sigma > 0.0) {
            return Err(InvalidSensor {
                field: sigma_field,
                message: format!(
                    "{sigma_field} must be > 0, got {sigma}\n  = help: {sigma_help} (a fix without error would be a truth no filter could weigh)"
                ),
            });
        }
        Ok(())
    }
}

fn positive(field: &'static str, v: f64, help: &str) -> Result<(), InvalidSensor> {
    if v.is_finite() && v > 0.0 {
        return Ok(());
    }
    Err(InvalidSensor {
        field,
        message: format!("{field} must be > 0, got {v}\n  = help: {help}"),
    })
}

fn non_negative(field: &'static str, v: f64, what: &str, zero: &str) -> Result<(), InvalidSensor> {
    if v.is_finite() && v >= 0.0 {
        return Ok(());
    }
    Err(InvalidSensor {
        field,
        message: format!("{field} must be ≥ 0, got {v}\n  = help: {what}; {zero}"),
    })
}

fn finite(field: &'static str, v: &[f64; 3], help: &str) -> Result<(), InvalidSensor> {
    match v.iter().find(|x| !x.is_finite()) {
        None => Ok(()),
        Some(x) => Err(InvalidSensor {
            field,
            message: format!("{field}: every number must be finite, got {x}\n  = help: {help}"),
        }),
    }
}

/// One column of a sensor log (`sensors.csv`): its name, unit and where
/// its value lies in a [`SensorSample`]. [`columns`] lists a declaration's
/// columns; the writer and the reader of the log both go through it, so
/// the names live here only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// `t`: time \[s\].
    Time,
    /// `gx`, `gy`, `gz`: the gyros, IMU axes \[rad/s\].
    Gyro(usize),
    /// `ax`, `ay`, `az`: the accelerometers, IMU axes [m/s²].
    Accel(usize),
    /// `enc{j}`: wheel j's rotation since the start \[rad\] (0-based here,
    /// 1-based in the name).
    WheelAngle(usize),
    /// `susp{i}`: suspension coordinate i (rad, or m).
    Suspension(usize),
    /// `fix_X`, `fix_Y`, `fix_Z`: a position fix of G \[m\], empty when
    /// none is due.
    Position(usize),
    /// `fix_psi`: a heading fix \[rad\], empty when none is due.
    Heading,
    /// `tau{j}`: wheel j's motor torque [N·m].
    Torque(usize),
    /// `delta{j}`: wheel j's steering angle \[rad\].
    Steering(usize),
}

impl core::fmt::Display for Column {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        const XYZ: [&str; 3] = ["x", "y", "z"];
        const BIG_XYZ: [&str; 3] = ["X", "Y", "Z"];
        match *self {
            Column::Time => f.write_str("t"),
            Column::Gyro(i) => write!(f, "g{}", XYZ[i % 3]),
            Column::Accel(i) => write!(f, "a{}", XYZ[i % 3]),
            Column::WheelAngle(j) => write!(f, "enc{}", j + 1),
            Column::Suspension(i) => write!(f, "susp{}", i + 1),
            Column::Position(i) => write!(f, "fix_{}", BIG_XYZ[i % 3]),
            Column::Heading => f.write_str("fix_psi"),
            Column::Torque(j) => write!(f, "tau{}", j + 1),
            Column::Steering(j) => write!(f, "delta{}", j + 1),
        }
    }
}

impl Column {
    /// The column named `name` (as [`Column`]'s `Display` writes it), of
    /// any sensor, wheel or coordinate; `None` for a name no sensor log
    /// has.
    pub fn from_name(name: &str) -> Option<Column> {
        let digits = name.trim_start_matches(|c: char| !c.is_ascii_digit());
        let numbered = digits
            .parse::<usize>()
            .ok()
            .filter(|&k| k >= 1 && !digits.starts_with('0'))
            .map(|k| {
                [
                    Column::WheelAngle(k - 1),
                    Column::Suspension(k - 1),
                    Column::Torque(k - 1),
                    Column::Steering(k - 1),
                ]
            });
        let fixed = [
            Column::Time,
            Column::Gyro(0),
            Column::Gyro(1),
            Column::Gyro(2),
            Column::Accel(0),
            Column::Accel(1),
            Column::Accel(2),
            Column::Position(0),
            Column::Position(1),
            Column::Position(2),
            Column::Heading,
        ];
        let mut text = String::new();
        fixed
            .into_iter()
            .chain(numbered.into_iter().flatten())
            .find(|c| {
                text.clear();
                core::fmt::write(&mut text, format_args!("{c}")).is_ok() && text == name
            })
    }

    /// The column's unit; `rad or m` for a suspension coordinate.
    pub fn unit(&self) -> &'static str {
        match self {
            Column::Time => "s",
            Column::Gyro(_) => "rad/s",
            Column::Accel(_) => "m/s^2",
            Column::WheelAngle(_) | Column::Heading | Column::Steering(_) => "rad",
            Column::Suspension(_) => "rad or m",
            Column::Position(_) => "m",
            Column::Torque(_) => "N*m",
        }
    }

    /// Whether the column may be empty in a row: the fixes, read at their
    /// own rates.
    pub fn sparse(&self) -> bool {
        matches!(self, Column::Position(_) | Column::Heading)
    }

    /// The column's value in `sample`: `None` for a fix not due, or for a
    /// reading the sample does not hold.
    pub fn value(&self, s: &SensorSample) -> Option<f64> {
        match *self {
            Column::Time => Some(s.t),
            Column::Gyro(i) => s.gyro.and_then(|g| g.get(i).copied()),
            Column::Accel(i) => s.accel.and_then(|a| a.get(i).copied()),
            Column::WheelAngle(j) => s.wheel_angles.get(j).copied(),
            Column::Suspension(i) => s.suspension.get(i).copied(),
            Column::Position(i) => s.position.and_then(|p| p.get(i).copied()),
            Column::Heading => s.heading,
            Column::Torque(j) => s.torques.get(j).copied(),
            Column::Steering(j) => s.steering.get(j).copied(),
        }
    }

    /// Puts `value` into `sample` where the column says (a sample of
    /// [`SensorSample::sized`]'s shape). `None` clears a fix (a position
    /// fix whole); a reading the sample has no room for is left out.
    pub fn set(&self, s: &mut SensorSample, value: Option<f64>) {
        fn put(slot: Option<&mut f64>, value: Option<f64>) {
            if let (Some(slot), Some(v)) = (slot, value) {
                *slot = v;
            }
        }
        match *self {
            Column::Time => put(Some(&mut s.t), value),
            Column::Gyro(i) => put(s.gyro.get_or_insert([0.0; 3]).get_mut(i), value),
            Column::Accel(i) => put(s.accel.get_or_insert([0.0; 3]).get_mut(i), value),
            Column::WheelAngle(j) => put(s.wheel_angles.get_mut(j), value),
            Column::Suspension(i) => put(s.suspension.get_mut(i), value),
            Column::Position(i) => match value {
                None => s.position = None,
                v => put(s.position.get_or_insert([0.0; 3]).get_mut(i), v),
            },
            Column::Heading => s.heading = value,
            Column::Torque(j) => put(s.torques.get_mut(j), value),
            Column::Steering(j) => put(s.steering.get_mut(j), value),
        }
    }
}

/// The columns of the sensor log of `config` on a rover of `wheels`
/// wheels and `coordinates` suspension coordinates, in order: `t`; `gx gy
/// gz ax ay az` with an IMU; `enc1…encK` with wheel encoders;
/// `susp1…suspM` with suspension encoders; `fix_X fix_Y fix_Z` with a
/// position fix; `fix_psi` with a heading fix; then the commands
/// `tau1…tauK` and `delta1…deltaK`.
pub fn columns(config: &SensorConfig, wheels: usize, coordinates: usize) -> Vec<Column> {
    let mut out = alloc::vec![Column::Time];
    if config.imu.is_some() {
        out.extend((0..3).map(Column::Gyro));
        out.extend((0..3).map(Column::Accel));
    }
    if config.wheel_encoders.is_some() {
        out.extend((0..wheels).map(Column::WheelAngle));
    }
    if config.suspension_encoders.is_some() {
        out.extend((0..coordinates).map(Column::Suspension));
    }
    if config.position_fix.is_some() {
        out.extend((0..3).map(Column::Position));
    }
    if config.heading_fix.is_some() {
        out.push(Column::Heading);
    }
    out.extend((0..wheels).map(Column::Torque));
    out.extend((0..wheels).map(Column::Steering));
    out
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use alloc::string::ToString;

    fn full() -> SensorConfig {
        SensorConfig {
            suspension_encoders: Some(SuspensionEncoderConfig {
                resolution: 1e-3,
                noise: 0.0,
            }),
            position_fix: Some(PositionFixConfig {
                rate: 1.0,
                sigma: 0.1,
            }),
            heading_fix: Some(HeadingFixConfig {
                rate: 1.0,
                sigma: 0.01,
            }),
            ..SensorConfig::mems()
        }
    }

    #[test]
    fn the_datasheet_units_convert_to_si() {
        let imu = full().imu.unwrap();
        // 0.2 °/√h = 0.2·(π/180) rad / √(3600 s) = 5.818e-5 rad/√s.
        assert!((imu.gyro_noise_density() - 5.817764173314432e-5).abs() < 1e-18);
        // 10 °/h = 4.848e-5 rad/s.
        assert!((imu.gyro_bias_sigma() - 4.84813681109536e-5).abs() < 1e-18);
        assert!((imu.accel_noise_density() - 9.80665e-4).abs() < 1e-18);
        assert!((imu.accel_bias_sigma() - 9.80665e-4).abs() < 1e-18);
    }

    #[test]
    fn every_bad_number_is_refused_naming_its_field() {
        assert_eq!(full().check(), Ok(()));
        type Spoil = fn(&mut SensorConfig);
        let cases: [(Spoil, &str, &str); 10] = [
            (
                |c| c.rate = 0.0,
                "sensors.rate",
                "sensors.rate must be > 0, got 0",
            ),
            (
                |c| c.imu.as_mut().unwrap().gyro_noise_deg_per_sqrt_h = -1.0,
                "sensors.imu.gyro_noise_deg_per_sqrt_h",
                "must be ≥ 0, got -1",
            ),
            (
                |c| c.imu.as_mut().unwrap().accel_bias_mg = f64::NAN,
                "sensors.imu.accel_bias_mg",
                "must be ≥ 0, got NaN",
            ),
            (
                |c| c.imu.as_mut().unwrap().bias_time = 0.0,
                "sensors.imu.bias_time",
                "must be > 0, got 0",
            ),
            (
                |c| c.imu.as_mut().unwrap().position[1] = f64::INFINITY,
                "sensors.imu.position",
                "every number must be finite, got inf",
            ),
            (
                |c| c.wheel_encoders.as_mut().unwrap().resolution = 0.0,
                "sensors.wheel_encoders.resolution",
                "must be > 0, got 0",
            ),
            (
                |c| c.suspension_encoders.as_mut().unwrap().noise = -0.1,
                "sensors.suspension_encoders.noise",
                "must be ≥ 0, got -0.1",
            ),
            (
                |c| c.position_fix.as_mut().unwrap().rate = -1.0,
                "sensors.position_fix.rate",
                "must be > 0, got -1",
            ),
            (
                |c| c.heading_fix.as_mut().unwrap().rate = 200.0,
                "sensors.heading_fix.rate",
                "= 200 Hz is faster than sensors.rate = 100 Hz",
            ),
            (
                |c| c.position_fix.as_mut().unwrap().sigma = 0.0,
                "sensors.position_fix.sigma",
                "must be > 0, got 0",
            ),
        ];
        for (spoil, field, says) in cases {
            let mut c = full();
            spoil(&mut c);
            let e = c.check().unwrap_err();
            assert_eq!(e.field, field);
            let text = e.to_string();
            assert!(text.starts_with(field) && text.contains(says), "{text}");
            assert!(text.contains("\n  = help: "), "{text}");
        }
    }

    #[test]
    fn the_columns_follow_the_declared_sensors() {
        let names = |c: &SensorConfig| -> Vec<String> {
            columns(c, 2, 1).iter().map(|c| c.to_string()).collect()
        };
        assert_eq!(
            names(&full()),
            [
                "t", "gx", "gy", "gz", "ax", "ay", "az", "enc1", "enc2", "susp1", "fix_X", "fix_Y",
                "fix_Z", "fix_psi", "tau1", "tau2", "delta1", "delta2"
            ]
        );
        let bare = SensorConfig {
            imu: None,
            wheel_encoders: None,
            suspension_encoders: None,
            position_fix: None,
            heading_fix: None,
            ..full()
        };
        assert_eq!(names(&bare), ["t", "tau1", "tau2", "delta1", "delta2"]);
        // Every column puts back what it reads.
        let mut s = SensorSample::sized(&full(), 2, 1);
        s.position = Some([1.0, 2.0, 3.0]);
        s.heading = Some(0.5);
        let cols = columns(&full(), 2, 1);
        for (k, c) in cols.iter().enumerate() {
            c.set(&mut s, Some(k as f64 + 0.25));
        }
        for (k, c) in cols.iter().enumerate() {
            assert_eq!(c.value(&s), Some(k as f64 + 0.25), "{c}");
        }
        Column::Position(1).set(&mut s, None);
        assert_eq!(s.position, None);
        // Each name reads back as its column; nothing else does.
        for c in columns(&full(), 12, 11) {
            assert_eq!(Column::from_name(&c.to_string()), Some(c));
        }
        for name in [
            "", "T", "enc0", "enc01", "enc", "gw", "fix_x", "tau-1", "susp1.0",
        ] {
            assert_eq!(Column::from_name(name), None, "{name}");
        }
    }
}
