//! Soils as users give them: a `[soil]` table (SI units, degrees where the
//! key says so) or a built-in soil by name, checked, then turned into the
//! law's [`Soil`]; and the single-wheel
//! testbed's sweep over slip (docs/SOIL.md).

use std::path::Path;

use rover_dynamics::soil::{GaussLegendre, SinksPastAxle, Soil, SoilWheel, steady_state};
use serde::{Deserialize, Serialize};

/// A soil as a `[soil]` table writes it (docs/SOIL.md).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SoilConfig {
    /// Pressure–sinkage exponent n (> 0).
    pub n: f64,
    /// Cohesive modulus k_c [N/m^(n+1)] (≥ 0).
    pub k_c: f64,
    /// Frictional modulus k_φ [N/m^(n+2)] (≥ 0).
    pub k_phi: f64,
    /// Cohesion c \[Pa\] (≥ 0).
    pub cohesion: f64,
    /// Internal friction angle φ \[°\], in (0, 90).
    pub friction_angle_deg: f64,
    /// Janosi–Hanamoto shear modulus K \[m\] (> 0).
    pub shear_modulus: f64,
    /// Lateral shear modulus K_y \[m\] (> 0; default: K).
    #[serde(default)]
    pub lateral_shear_modulus: Option<f64>,
    /// Wong–Reece a0 (default 0.4).
    #[serde(default = "default_a0")]
    pub a0: f64,
    /// Wong–Reece a1 (default 0.15).
    #[serde(default = "default_a1")]
    pub a1: f64,
    /// Rear ratio c_r in [0, 1] (default 0).
    #[serde(default)]
    pub rear_ratio: f64,
    /// Unit weight γ = ρ·g [N/m³] (> 0): given, the bulldozing resistance
    /// on the wheel's side under a slip angle is included (Ishigami et al.
    /// 2007); left out by default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit_weight: Option<f64>,
    /// Wong's unloading–reloading modulus at zero past sinkage, k_0
    /// \[Pa/m\] (≥ 0, default 0): `k_u = k_0 + A_u·z_u`, the soil's
    /// stiffness when a wheel reloads ground an earlier pass pressed to
    /// z_u (docs/MODEL.md, "Ruts and multipass").
    #[serde(default)]
    pub reload_k0: f64,
    /// Its growth with the past sinkage, A_u \[Pa/m²\] (≥ 0; default
    /// 5.03e8, Wong's LETE sand). k_0 = A_u = 0: the soil keeps no memory
    /// of its load, and a rut's floor is fresh soil.
    #[serde(default = "default_reload_au")]
    pub reload_au: f64,
}

/// A_u of LETE sand, 503 000 kN/m⁴ (Wong, *Theory of Ground Vehicles*,
/// 4th ed. 2008, the repetitive-loading parameters) \[Pa/m²\].
pub const LETE_RELOAD_AU: f64 = 5.03e8;

fn default_reload_au() -> f64 {
    LETE_RELOAD_AU
}

fn default_a0() -> f64 {
    0.4
}

fn default_a1() -> f64 {
    0.15
}

/// A soil parameter outside physics, or a soil that cannot be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SoilError {
    /// A field's value is out of its range.
    #[error("soil.{field} = {value}: {help}")]
    Field {
        /// The key.
        field: &'static str,
        /// Its value.
        value: f64,
        /// Its range, and how to fix it.
        help: &'static str,
    },
    /// Neither a built-in name nor a readable soil file.
    #[error("{0}")]
    Source(String),
}

impl SoilConfig {
    /// The law's soil, once every field is within physics.
    pub fn soil(&self) -> Result<Soil, SoilError> {
        let lateral = self.lateral_shear_modulus.unwrap_or(self.shear_modulus);
        let unit_weight = self.unit_weight.unwrap_or(0.0);
        let checks: [(&'static str, f64, bool, &'static str); 13] = [
            (
                "n",
                self.n,
                self.n > 0.0,
                "the pressure-sinkage exponent must be > 0 (sands 0.7-1.1)",
            ),
            (
                "k_c",
                self.k_c,
                self.k_c >= 0.0,
                "a modulus in N/m^(n+1), >= 0",
            ),
            (
                "k_phi",
                self.k_phi,
                self.k_phi >= 0.0,
                "a modulus in N/m^(n+2), >= 0",
            ),
            (
                "cohesion",
                self.cohesion,
                self.cohesion >= 0.0,
                "a stress in Pa, >= 0",
            ),
            (
                "friction_angle_deg",
                self.friction_angle_deg,
                self.friction_angle_deg > 0.0 && self.friction_angle_deg < 90.0,
                "an angle in degrees, in (0, 90)",
            ),
            (
                "shear_modulus",
                self.shear_modulus,
                self.shear_modulus > 0.0,
                "K in m, > 0 (sands 0.01-0.04)",
            ),
            (
                "lateral_shear_modulus",
                lateral,
                lateral > 0.0,
                "K_y in m, > 0",
            ),
            (
                "a0",
                self.a0,
                (0.0..=1.0).contains(&self.a0),
                "the stress peak's place, in [0, 1]",
            ),
            (
                "a1",
                self.a1,
                self.a1.abs() <= 1.0,
                "the stress peak's slip dependence, in [-1, 1]",
            ),
            (
                "rear_ratio",
                self.rear_ratio,
                (0.0..=1.0).contains(&self.rear_ratio),
                "in [0, 1]",
            ),
            (
                "unit_weight",
                unit_weight,
                self.unit_weight.is_none() || unit_weight > 0.0,
                "the soil's weight per volume in N/m³, > 0 (ρ·g: 1600 kg/m³ on the Moon is 2592 N/m³); leave it out to leave out the side's bulldozing",
            ),
            (
                "reload_k0",
                self.reload_k0,
                self.reload_k0 >= 0.0,
                "the reloading modulus at zero sinkage in Pa/m, >= 0 (sands: 0)",
            ),
            (
                "reload_au",
                self.reload_au,
                self.reload_au >= 0.0,
                "the reloading modulus's growth with the past sinkage in Pa/m², >= 0 (sands 0.86e8-5.03e8; 0 with reload_k0 = 0 for a soil without memory)",
            ),
        ];
        for (field, value, ok, help) in checks {
            if !(ok && value.is_finite()) {
                return Err(SoilError::Field { field, value, help });
            }
        }
        if self.k_c + self.k_phi <= 0.0 {
            return Err(SoilError::Field {
                field: "k_phi",
                value: self.k_phi,
                help: "k_c and k_phi are both 0: the soil would carry nothing; give k_phi > 0",
            });
        }
        Ok(Soil {
            n: self.n,
            k_c: self.k_c,
            k_phi: self.k_phi,
            cohesion: self.cohesion,
            friction_angle: self.friction_angle_deg.to_radians(),
            shear_modulus: self.shear_modulus,
            lateral_shear_modulus: lateral,
            a0: self.a0,
            a1: self.a1,
            rear_ratio: self.rear_ratio,
            unit_weight,
            reload_k0: self.reload_k0,
            reload_au: self.reload_au,
        })
    }

    /// A built-in soil by name ([`SOIL_NAMES`]; docs/SOIL.md gives the
    /// source of each number).
    pub fn builtin(name: &str) -> Option<Self> {
        let soil = |n, k_c: f64, k_phi: f64, c: f64, phi, k, k_y| SoilConfig {
            n,
            k_c: k_c * 1e3,
            k_phi: k_phi * 1e3,
            cohesion: c * 1e3,
            friction_angle_deg: phi,
            shear_modulus: k,
            lateral_shear_modulus: k_y,
            a0: 0.4,
            a1: 0.15,
            rear_ratio: 0.0,
            unit_weight: None,
            reload_k0: 0.0,
            reload_au: LETE_RELOAD_AU,
        };
        Some(match name {
            "lete_sand" => soil(0.79, 102.0, 5301.0, 1.3, 31.1, 0.01, None),
            "dry_sand" => soil(1.1, 0.99, 1528.43, 1.04, 28.0, 0.01, None),
            "lunar_nominal" => soil(1.0, 1.4, 820.0, 0.17, 35.0, 0.018, None),
            "lunar_simulant" => soil(1.0, 1.37, 814.0, 0.8, 37.2, 0.036, Some(0.013)),
            "mars_simulant" => soil(0.8, 5.79, 180.0, 0.3, 17.8, 0.01, None),
            _ => return None,
        })
    }

    /// A built-in name, or a TOML file holding a `[soil]` table.
    pub fn named_or_file(source: &str) -> Result<Self, SoilError> {
        if let Some(s) = Self::builtin(source) {
            return Ok(s);
        }
        let path = Path::new(source);
        if !path.exists() {
            return Err(SoilError::Source(format!(
                "{source}: no built-in soil of that name ({}) and no such file; give a name or a TOML file with a [soil] table",
                SOIL_NAMES.join(", ")
            )));
        }
        let text = rover_files::read_text(path, rover_files::Limit::Text)
            .map_err(|e| SoilError::Source(format!("{source}: cannot read: {e}")))?;
        // Located, never quoted: a scenario may name any file as its soil.
        Self::parse_toml(&text).map_err(|e| {
            let place = e.span().map_or(String::new(), |s| {
                let (line, column) = rover_files::line_column(text.as_bytes(), s.start);
                format!(":{line}:{column}")
            });
            SoilError::Source(format!("{source}{place}: {}", e.message().trim_end()))
        })
    }

    /// A soil file's text: a `[soil]` table and nothing else (checked for
    /// its keys and types here, for physics by [`soil`](Self::soil)).
    pub fn from_toml(text: &str) -> Result<Self, SoilError> {
        Self::parse_toml(text).map_err(|e| SoilError::Source(e.to_string()))
    }

    /// The `[soil]` table of a soil file's text.
    fn parse_toml(text: &str) -> Result<Self, toml::de::Error> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            soil: SoilConfig,
        }
        toml::from_str::<File>(text).map(|f| f.soil)
    }
}

/// The built-in soils' names.
pub const SOIL_NAMES: [&str; 5] = [
    "lete_sand",
    "dry_sand",
    "lunar_nominal",
    "lunar_simulant",
    "mars_simulant",
];

/// One point of a single-wheel test: a rigid wheel at a load and slip in
/// its steady state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WheelTestPoint {
    /// Slip s.
    pub slip: f64,
    /// Sinkage z = r·(1 − cos θ1) \[m\].
    pub sinkage: f64,
    /// Entry angle θ1 \[rad\].
    pub entry_angle: f64,
    /// Drawbar pull DP \[N\].
    pub drawbar_pull: f64,
    /// Driving torque T [N·m].
    pub torque: f64,
    /// Lateral force F_y under the slip angle \[N\].
    pub lateral_force: f64,
}

impl WheelTestPoint {
    /// The testbed's columns (`rover wheel-test`'s CSV header), in
    /// [`row`](Self::row)'s order.
    pub const COLUMNS: [&'static str; 8] = [
        "slip",
        "sinkage",
        "drawbar_pull",
        "torque",
        "lateral_force",
        "entry_angle",
        "drawbar_pull_over_load",
        "torque_over_load_radius",
    ];

    /// DP/W under the test's `load` \[N\].
    pub fn drawbar_pull_over_load(&self, load: f64) -> f64 {
        self.drawbar_pull / load
    }

    /// T/(W·r) under the test's `load` \[N\] on a wheel of `radius` \[m\].
    pub fn torque_over_load_radius(&self, load: f64, radius: f64) -> f64 {
        self.torque / (load * radius)
    }

    /// The point's values in [`COLUMNS`](Self::COLUMNS)' order.
    pub fn row(&self, load: f64, radius: f64) -> [f64; 8] {
        [
            self.slip,
            self.sinkage,
            self.drawbar_pull,
            self.torque,
            self.lateral_force,
            self.entry_angle,
            self.drawbar_pull_over_load(load),
            self.torque_over_load_radius(load, radius),
        ]
    }
}

/// Quadrature points on each piece of the contact arc for the testbed:
/// the forces to 1e-9 of their converged values (4 points hold 1e-4;
/// docs/SOIL.md).
pub const TESTBED_POINTS: usize = 16;

/// Why a single-wheel test cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WheelTestError {
    /// A wheel or load outside physics; names the flag.
    #[error("--{flag} {value}: {help}")]
    Input {
        /// The flag.
        flag: &'static str,
        /// Its value.
        value: f64,
        /// Its range.
        help: &'static str,
    },
    /// The soil cannot carry the load under this wheel.
    #[error("at slip {slip}: {source}")]
    Sinks {
        /// The slip.
        slip: f64,
        /// What the soil carries.
        source: SinksPastAxle,
    },
}

/// The steady states of a rigid wheel (`radius`, `width`) carrying `load`
/// on `soil` at each of `slips`, under `slip_angle` \[rad\].
pub fn wheel_test(
    soil: &Soil,
    radius: f64,
    width: f64,
    load: f64,
    slips: &[f64],
    slip_angle: f64,
) -> Result<Vec<WheelTestPoint>, WheelTestError> {
    let input = |flag, value: f64, ok: bool, help| {
        if ok && value.is_finite() {
            Ok(())
        } else {
            Err(WheelTestError::Input { flag, value, help })
        }
    };
    input(
        "radius",
        radius,
        radius > 0.0,
        "the wheel's radius in m, > 0",
    )?;
    input("width", width, width > 0.0, "the wheel's width in m, > 0")?;
    input("load", load, load > 0.0, "the vertical load in N, > 0")?;
    input(
        "slip-angle-deg",
        slip_angle.to_degrees(),
        slip_angle.abs() < std::f64::consts::FRAC_PI_2,
        "degrees, in (-90, 90)",
    )?;
    for &s in slips {
        input(
            "slip",
            s,
            s > -1.0 && s < 1.0,
            "each slip in (-1, 1): positive driving, negative braking",
        )?;
    }
    let rule = GaussLegendre::<TESTBED_POINTS>::new();
    let wheel = SoilWheel::new(soil, radius, width);
    slips
        .iter()
        .map(|&slip| {
            let (entry_angle, f) = steady_state(&wheel, load, slip, slip_angle, &rule)
                .map_err(|source| WheelTestError::Sinks { slip, source })?;
            Ok(WheelTestPoint {
                slip,
                sinkage: radius * (1.0 - entry_angle.cos()),
                entry_angle,
                drawbar_pull: f.drawbar,
                torque: f.torque,
                lateral_force: f.lateral,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_built_in_soil_is_within_physics() {
        for name in SOIL_NAMES {
            let s = SoilConfig::builtin(name).unwrap().soil().unwrap();
            assert!(s.k_phi > 1e5 && s.friction_angle > 0.2, "{name}");
        }
        assert_eq!(SoilConfig::builtin("mud"), None);
    }

    #[test]
    fn a_soil_outside_physics_names_its_field() {
        let good = SoilConfig::builtin("lete_sand").unwrap();
        for (bad, field) in [
            (SoilConfig { n: 0.0, ..good }, "n"),
            (
                SoilConfig {
                    friction_angle_deg: 90.0,
                    ..good
                },
                "friction_angle_deg",
            ),
            (
                SoilConfig {
                    shear_modulus: -0.01,
                    ..good
                },
                "shear_modulus",
            ),
            (SoilConfig { k_c: -1.0, ..good }, "k_c"),
            (
                SoilConfig {
                    cohesion: f64::NAN,
                    ..good
                },
                "cohesion",
            ),
            (
                SoilConfig {
                    k_c: 0.0,
                    k_phi: 0.0,
                    ..good
                },
                "k_phi",
            ),
        ] {
            match bad.soil() {
                Err(SoilError::Field { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{field}: {other:?}"),
            }
        }
    }

    #[test]
    fn the_testbed_refuses_a_slip_outside_its_range_and_a_load_past_the_axle() {
        let soil = SoilConfig::builtin("lete_sand").unwrap().soil().unwrap();
        let e = wheel_test(&soil, 0.25, 0.16, 150.0, &[0.2, 1.0], 0.0).unwrap_err();
        assert!(e.to_string().starts_with("--slip 1:"), "{e}");
        let e = wheel_test(&soil, 0.05, 0.02, 1e5, &[0.2], 0.0).unwrap_err();
        assert!(e.to_string().contains("sunk to its axle"), "{e}");
        let e = wheel_test(&soil, 0.25, 0.0, 150.0, &[0.2], 0.0).unwrap_err();
        assert!(e.to_string().starts_with("--width 0:"), "{e}");
    }
}
