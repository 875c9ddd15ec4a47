//! Attitude of the body: yaw ψ, roll φ, pitch θ (MODEL.md §1–§2, eq. 1–4, 9).

use crate::linalg::M3;
use crate::scalar::Scalar;

/// Sines and cosines of the three attitude angles, computed once.
#[derive(Clone, Copy, Debug)]
pub struct Attitude<S> {
    /// sin φ, cos φ (roll).
    pub sphi: S,
    /// cos φ.
    pub cphi: S,
    /// sin θ (pitch).
    pub sth: S,
    /// cos θ.
    pub cth: S,
    /// sin ψ (yaw).
    pub spsi: S,
    /// cos ψ.
    pub cpsi: S,
    /// Roll φ and pitch θ themselves (used by the linearized form).
    pub phi: S,
    /// Pitch θ.
    pub theta: S,
    /// The gravity direction (the paper's C, eq. 30) and the angle rates
    /// (Aᵀ, eq. 10) to first order in φ and θ (MODEL.md §9, level 3).
    pub linear: bool,
    /// The rotation R (eq. 4) to first order in φ and θ as well: the
    /// paper's linearized model. `false` with `linear` keeps R exact.
    pub linear_rotation: bool,
}

impl<S: Scalar> Attitude<S> {
    /// From the angles φ (roll), θ (pitch), ψ (yaw) \[rad\].
    pub fn new(phi: S, theta: S, psi: S) -> Self {
        Self {
            sphi: phi.sin(),
            cphi: phi.cos(),
            sth: theta.sin(),
            cth: theta.cos(),
            spsi: psi.sin(),
            cpsi: psi.cos(),
            phi,
            theta,
            linear: false,
            linear_rotation: false,
        }
    }

    /// The linearized attitude of MODEL.md §9 (level 3), the paper's: roll
    /// and pitch small, `R ≈ Rz(ψ)·(I + skew([φ, θ, 0]))` (eq. 4), the
    /// gravity direction (eq. 30) and `E⁻¹` (eq. 10) to first order, exact
    /// in ψ.
    pub fn linear(phi: S, theta: S, psi: S) -> Self {
        Self {
            linear: true,
            linear_rotation: true,
            ..Self::new(phi, theta, psi)
        }
    }

    /// As [`Attitude::linear`] but with R exact: only the gravity direction
    /// and the angle rates are taken to first order.
    pub fn linear_exact_rotation(phi: S, theta: S, psi: S) -> Self {
        Self {
            linear: true,
            ..Self::new(phi, theta, psi)
        }
    }

    /// `R = Rz(ψ)·Rx(φ)·Ry(θ)`: body components → inertial components
    /// (eq. 1–4); with `linear_rotation`, `Rz(ψ)·(I + skew([φ, θ, 0]))`.
    pub fn rotation(&self) -> M3<S> {
        let (sf, cf, st, ct, sp, cp) = (
            self.sphi, self.cphi, self.sth, self.cth, self.spsi, self.cpsi,
        );
        // Rx(φ)·Ry(θ), or its first-order form I + skew([φ, θ, 0]).
        let a = if self.linear_rotation {
            let (f, t) = (self.phi, self.theta);
            [
                [S::one(), S::zero(), t],
                [S::zero(), S::one(), -f],
                [-t, f, S::one()],
            ]
        } else {
            [
                [ct, S::zero(), st],
                [sf * st, cf, -(sf * ct)],
                [-(cf * st), sf, cf * ct],
            ]
        };
        [
            [
                cp * a[0][0] - sp * a[1][0],
                cp * a[0][1] - sp * a[1][1],
                cp * a[0][2] - sp * a[1][2],
            ],
            [
                sp * a[0][0] + cp * a[1][0],
                sp * a[0][1] + cp * a[1][1],
                sp * a[0][2] + cp * a[1][2],
            ],
            a[2],
        ]
    }

    /// `Rᵀ·e_Z`: the inertial vertical in body components (third row of R).
    pub fn up_in_body(&self) -> [S; 3] {
        if self.linear {
            return [-self.theta, self.phi, S::one()];
        }
        [-(self.cphi * self.sth), self.sphi, self.cphi * self.cth]
    }

    /// Euler-angle rates from the body angular velocity, `E⁻¹·Ω` (eq. 9):
    /// `φ̇ = cθ·Ωx + sθ·Ωz`, `ψ̇ = (−sθ·Ωx + cθ·Ωz)/cφ`, `θ̇ = Ωy − sφ·ψ̇`.
    /// Returns `[φ̇, θ̇, ψ̇]`.
    pub fn rates(&self, omega: [S; 3]) -> [S; 3] {
        if self.linear {
            // φ̇ = Ωx + θ·Ωz, θ̇ = Ωy − φ·Ωz, ψ̇ = Ωz − θ·Ωx
            return [
                omega[0] + self.theta * omega[2],
                omega[1] - self.phi * omega[2],
                omega[2] - self.theta * omega[0],
            ];
        }
        let phid = self.cth * omega[0] + self.sth * omega[2];
        let psid = (self.cth * omega[2] - self.sth * omega[0]) / self.cphi;
        let thd = omega[1] - self.sphi * psid;
        [phid, thd, psid]
    }
}
