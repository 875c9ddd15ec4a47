//! The plant: what every back end (generic or generated) offers the runtime.
//!
//! The trait speaks `f64` slices so that a generated type can implement it
//! with fixed-size arrays and no allocation, and so that it stays object
//! safe. Vectors are in inertial components unless a name says otherwise.

/// Kinematics of one wheel centre G_j, inertial components.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WheelState {
    /// Position r_Gj \[m\] (eq. 7).
    pub centre: [f64; 3],
    /// Absolute velocity V_j [m/s] (eq. 12).
    pub velocity: [f64; 3],
    /// Unit spin axis a_wj = R·R_wj·e_y (points to the wheel's left).
    pub spin_axis: [f64; 3],
}

/// What the ground does to one wheel, reduced to its centre G_j (MODEL.md §7).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WheelLoad {
    /// Resultant contact force F \[N\], applied at G_j.
    pub force: [f64; 3],
    /// Moment about G_j of the contact force [N·m], less its component along
    /// the spin axis; it acts on the member carrying the wheel.
    pub moment: [f64; 3],
    /// Reaction of the drive motor on its stator, `−τ_eff·a_wj` [N·m]; it acts
    /// on the wheel carrier (hub motor) or on the body (body motor).
    pub stator_torque: [f64; 3],
}

/// Why the accelerations could not be computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlantError {
    /// The mass matrix is not positive definite at this state (pivot index and value).
    SingularMass {
        /// Row of the failing pivot.
        row: usize,
        /// The pivot.
        pivot: f64,
    },
    /// cos φ vanished: the attitude representation is singular (rolled over).
    AttitudeSingular {
        /// Roll angle φ \[rad\].
        roll: f64,
    },
}

impl core::fmt::Display for PlantError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PlantError::SingularMass { row, pivot } => write!(
                f,
                "the mass matrix is not positive definite (pivot {row} = {pivot:e})"
            ),
            PlantError::AttitudeSingular { roll } => write!(
                f,
                "the attitude is singular at roll {:.1}° (cos φ = 0): the rover has rolled over",
                roll.to_degrees()
            ),
        }
    }
}

/// Smallest |cos φ| a plant accepts before it declares the attitude
/// singular (the Euler angles' rates divide by cos φ): the generic plant and
/// every generated one test against this one value.
pub const MIN_COS_ROLL: f64 = 1e-6;

/// A rover plant model: state in, wheel kinematics out; wheel loads in,
/// derivatives out (MODEL.md §2–§5).
///
/// State layout: `x = [X, Y, Z, φ, θ, ψ, y1 … ym]` and
/// `w = [vx, vy, vz, Ωx, Ωy, Ωz, ẏ1 … ẏm]`, both of length [`Plant::dof`].
pub trait Plant {
    /// Number of generalized coordinates, 6 + m.
    fn dof(&self) -> usize;
    /// Number of wheels.
    fn wheel_count(&self) -> usize;
    /// Wheel-centre kinematics for the steering angles `steer` (one per wheel,
    /// ignored for wheels that are not steerable) into `out`.
    fn wheels(&mut self, x: &[f64], w: &[f64], steer: &[f64], out: &mut [WheelState]);
    /// The derivatives `ẋ = B·w` and `ẇ = M⁻¹·(−Ṁ·w − f1 + f2 + Q)` under the
    /// wheel loads `loads` (one per wheel).
    fn derivatives(
        &mut self,
        x: &[f64],
        w: &[f64],
        loads: &[WheelLoad],
        xdot: &mut [f64],
        wdot: &mut [f64],
    ) -> Result<(), PlantError>;
    /// The mass matrix M(y), row-major, `dof × dof`.
    fn mass_matrix(&mut self, x: &[f64], out: &mut [f64]);
    /// Set the neutral value y_0 of coordinate i's spring (active suspension, eq. 42).
    fn set_spring_neutral(&mut self, coord: usize, neutral: f64);
    /// The exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` at fixed wheel loads into `jac`,
    /// row-major `2·dof × 2·dof`, for implicit integrators; the loads' own
    /// dependence on the state is the ground's to add. `None` when the plant
    /// has none: the generic plant, or a generated one built without
    /// `jacobian = true` (the integrators then difference the right-hand side).
    fn jacobian(
        &mut self,
        _x: &[f64],
        _w: &[f64],
        _loads: &[WheelLoad],
        _jac: &mut [f64],
    ) -> Option<()> {
        None
    }
    /// The plant's name, for a run's summary: by default its type's path
    /// (a generated plant's, e.g. `rover_models::generated::mer::Mer`); the
    /// generic plant says `generic`, with its level when reduced.
    fn name(&self) -> &'static str {
        core::any::type_name::<Self>()
    }
}

/// Implements [`Plant`] for an enum each of whose variants holds one plant:
/// every call is forwarded to the plant in hand with a `match` (no
/// allocation, no virtual call). The built-in rovers' `BuiltinPlant` and a
/// run's `RunPlant` (generated or generic) are such enums.
///
/// ```ignore
/// rover_dynamics::forward_plant!(MyPlants { A, B });
/// ```
#[macro_export]
macro_rules! forward_plant {
    ($ty:ty { $($variant:ident),+ $(,)? }) => {
        impl $crate::plant::Plant for $ty {
            fn dof(&self) -> usize {
                match self { $(Self::$variant(p) => p.dof()),+ }
            }
            fn wheel_count(&self) -> usize {
                match self { $(Self::$variant(p) => p.wheel_count()),+ }
            }
            fn wheels(
                &mut self,
                x: &[f64],
                w: &[f64],
                steer: &[f64],
                out: &mut [$crate::plant::WheelState],
            ) {
                match self { $(Self::$variant(p) => p.wheels(x, w, steer, out)),+ }
            }
            fn derivatives(
                &mut self,
                x: &[f64],
                w: &[f64],
                loads: &[$crate::plant::WheelLoad],
                xdot: &mut [f64],
                wdot: &mut [f64],
            ) -> Result<(), $crate::plant::PlantError> {
                match self { $(Self::$variant(p) => p.derivatives(x, w, loads, xdot, wdot)),+ }
            }
            fn mass_matrix(&mut self, x: &[f64], out: &mut [f64]) {
                match self { $(Self::$variant(p) => p.mass_matrix(x, out)),+ }
            }
            fn set_spring_neutral(&mut self, coord: usize, neutral: f64) {
                match self { $(Self::$variant(p) => p.set_spring_neutral(coord, neutral)),+ }
            }
            fn jacobian(
                &mut self,
                x: &[f64],
                w: &[f64],
                loads: &[$crate::plant::WheelLoad],
                jac: &mut [f64],
            ) -> Option<()> {
                match self { $(Self::$variant(p) => p.jacobian(x, w, loads, jac)),+ }
            }
            fn name(&self) -> &'static str {
                match self { $(Self::$variant(p) => p.name()),+ }
            }
        }
    };
}

/// A plant whose sizes are known at compile time: `N` generalized
/// coordinates (6 + m) and `W` wheels. Generated plants implement it on
/// nalgebra's fixed-size types, so a caller gets stack-allocated vectors
/// and matrices, no length checks and no allocation (firmware, `no_std`).
///
/// The methods compute what [`Plant`]'s methods compute; they take `&self`
/// because a fixed plant keeps no workspace.
pub trait FixedPlant<const N: usize, const W: usize>: Plant {
    /// The derivatives `ẋ = B·w` and `ẇ = M⁻¹·(−Ṁ·w − f1 + f2 + Q)` under
    /// the wheel loads `loads`. The outputs are written in any case; the
    /// error says the attitude is singular or M is not positive definite.
    fn derivatives_fixed(
        &self,
        x: &nalgebra::SVector<f64, N>,
        w: &nalgebra::SVector<f64, N>,
        loads: &[WheelLoad; W],
        xdot: &mut nalgebra::SVector<f64, N>,
        wdot: &mut nalgebra::SVector<f64, N>,
    ) -> Result<(), PlantError>;
    /// The mass matrix M(y), symmetric, `N × N`.
    fn mass_matrix_fixed(&self, x: &nalgebra::SVector<f64, N>) -> nalgebra::SMatrix<f64, N, N>;
    /// Wheel-centre kinematics for the steering angles `steer` (one per
    /// wheel, ignored for wheels that are not steerable).
    fn wheels_fixed(
        &self,
        x: &nalgebra::SVector<f64, N>,
        w: &nalgebra::SVector<f64, N>,
        steer: &nalgebra::SVector<f64, W>,
    ) -> [WheelState; W];
}
