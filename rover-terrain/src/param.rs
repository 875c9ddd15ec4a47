//! Checks of terrain parameters, and horizontal directions given as azimuths.

use super::error::TerrainError;

/// The horizontal unit vector `[cos ψ, sin ψ]` of the azimuth `ψ = direction_deg`,
/// measured from +X towards +Y (counter-clockwise seen from above): 0° is +X,
/// 90° is +Y. Any finite angle is accepted.
pub(crate) fn unit_vector(name: &str, direction_deg: f64) -> Result<[f64; 2], TerrainError> {
    if !direction_deg.is_finite() {
        return Err(TerrainError::parameter(
            name,
            format!("the direction must be a finite angle, got {direction_deg}"),
            "give an azimuth in degrees from +X towards +Y (0 = +X, 90 = +Y)",
        ));
    }
    let (s, c) = direction_deg.to_radians().sin_cos();
    Ok([c, s])
}

/// Checks that a parameter is finite.
pub(crate) fn finite(name: &str, value: f64, unit: &str) -> Result<f64, TerrainError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(TerrainError::parameter(
            name,
            format!("must be a finite number, got {value}"),
            format!("give a value in {unit}"),
        ))
    }
}

/// Checks that a parameter is finite and > 0.
pub(crate) fn positive(name: &str, value: f64, unit: &str) -> Result<f64, TerrainError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(TerrainError::parameter(
            name,
            format!("must be > 0 {unit}, got {value}"),
            format!("give a positive value in {unit}"),
        ))
    }
}

/// Checks that a parameter is finite and ≥ 0.
pub(crate) fn non_negative(name: &str, value: f64, unit: &str) -> Result<f64, TerrainError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(TerrainError::parameter(
            name,
            format!("must be ≥ 0 {unit}, got {value}"),
            format!("give a non-negative value in {unit}"),
        ))
    }
}
