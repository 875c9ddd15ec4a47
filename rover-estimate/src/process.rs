//! What the filter needs of the rover model: the right-hand side
//! `ẏ = f(t, y, u)` with the commands `u` (motor torques, steering angles)
//! held, its Jacobian `∂f/∂y`, each wheel's spin rate with its gradient,
//! for the wheel encoders, and the gravity the accelerometers feel.
//!
//! `y = [x; w; ω]` (docs/MODEL.md §2): the coordinates, the
//! pseudo-velocities, and on a soil each wheel's spin. The rover runtime's
//! `RoverSystem` implements it (built by `RoverSystem::open_loop`: no
//! controller loops, the commands are the filter's inputs; the `runtime`
//! feature); a firmware build implements it over its own composition of a
//! generated plant and ground.

/// The rover model as the filter's process model.
pub trait ProcessModel {
    /// Why an evaluation failed (a wheel off the map, a singular attitude).
    type Error: core::fmt::Display;

    /// Number of generalized coordinates N = 6 + m.
    fn dof(&self) -> usize;
    /// Length of the state `y`: 2N, plus one spin per wheel on a soil.
    fn dim(&self) -> usize;
    /// Number of wheels.
    fn wheel_count(&self) -> usize;
    /// Where the wheels' spins lie in `y` (empty on rigid ground).
    fn spin_range(&self) -> core::ops::Range<usize>;
    /// Gravity g \[m/s²\], along −Z: what an accelerometer at rest reads
    /// upwards.
    fn gravity(&self) -> f64;

    /// Holds the commanded motor torques [N·m] and steering angles \[rad\]
    /// (one per wheel, the description's order) from now on.
    fn set_inputs(&mut self, torques: &[f64], steering: &[f64]) -> Result<(), Self::Error>;

    /// `dy = f(t, y)` under the inputs held.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error>;

    /// `dy = f(t, y)` and `jac = ∂f/∂y` at `(t, y)`, row-major
    /// `dim × dim`, from one evaluation: the plant's exact Jacobian with
    /// the ground's contribution assembled (a model without an exact one
    /// may difference `f`, and says so).
    fn rhs_and_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), Self::Error>;

    /// Each wheel's spin rate \[rad/s\] at `(t, y)` into `rates` (the spin
    /// state on a soil; on rigid ground, where the tyre rolls, the speed
    /// of its centre along its heading over the radius), and each rate's
    /// gradient `∂rate_k/∂y` into `gradient[k·dim ..][..dim]`.
    fn wheel_rates(
        &mut self,
        t: f64,
        y: &[f64],
        rates: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), Self::Error>;

    /// The wheels' normal loads \[N\] and longitudinal slips of the last
    /// evaluation (slip 0 on rigid ground), for the filter's outputs.
    fn wheel_outputs(&self, normal: &mut [f64], slip: &mut [f64]);
}
