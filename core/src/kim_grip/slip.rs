//! The general path's tangential slip: its compliance, the stick impulse that stops it,
//! and the single mid-point direction of the slide (parent module docs; `curved` follows
//! the slide in pieces instead where the compliance is strongly anisotropic).

use super::k_y;
use crate::real::Real;

/// The initial tangential slip and the quantities derived from it. The slip
/// compliance is `K = [[k_y, k_yz], [0, k_z]]` (`Δv = K J`).
pub(super) struct TangentialSlip<R> {
    /// Slip direction scaled so its largest component is ±1 (`v₀ / scale`).
    pub(super) unit_y: R,
    pub(super) unit_z: R,
    pub(super) k_yz: R,
    pub(super) k_z: R,
    /// `|v₀| / scale`.
    pub(super) unit_norm: R,
    /// Stick impulse `j_stick = −K⁻¹ v₀` (m/s).
    pub(super) stick_y: R,
    pub(super) stick_z: R,
    /// `s* = |j_stick|` (m/s): friction budget that stops the slip.
    pub(super) stick_budget: R,
    /// `α_b / |v₀|`: where `v₀ − α K v̂₀` turns parallel to `K⁻¹ v₀`.
    pub(super) boundary_alpha_per_norm: R,
    /// `s* / |v₀|`.
    pub(super) stick_per_norm: R,
    /// `|v̂₀_z|` and `|ĵ_stick,z|`: the friction direction's vertical share when the
    /// slide starts and when it ends in a grip.
    pub(super) start_share_z: R,
    pub(super) stick_share_z: R,
}

impl<R: Real> TangentialSlip<R> {
    pub(super) fn new(slip_y: R, slip_z: R, scale: R, k_yz: R, k_z: R) -> Self {
        let unit_y = slip_y / scale;
        let unit_z = slip_z / scale;
        let unit_norm = R::sqrt(unit_y * unit_y + unit_z * unit_z);
        // K⁻¹ u, u = v₀ / scale.
        let inverse_z = unit_z / k_z;
        let inverse_y = (unit_y - k_yz * inverse_z) / k_y::<R>();
        let unit_stick = R::sqrt(inverse_y * inverse_y + inverse_z * inverse_z);
        // α_b/|v₀| = cross(u, K⁻¹u) / cross(K u, K⁻¹u); 1/(k_y + k_z) when K is
        // diagonal, and any value when v₀ is an eigenvector (the direction cannot turn).
        let (ku_y, ku_z) = (k_y::<R>() * unit_y + k_yz * unit_z, k_z * unit_z);
        let numerator = unit_y * inverse_z - unit_z * inverse_y;
        let denominator = ku_y * inverse_z - ku_z * inverse_y;
        let boundary_alpha_per_norm = if R::abs(denominator) > R::of(1e-12) {
            numerator / denominator
        } else {
            R::ONE / (k_y::<R>() + k_z)
        };
        Self {
            unit_y,
            unit_z,
            k_yz,
            k_z,
            unit_norm,
            stick_y: -inverse_y * scale,
            stick_z: -inverse_z * scale,
            stick_budget: unit_stick * scale,
            boundary_alpha_per_norm,
            stick_per_norm: unit_stick / unit_norm,
            start_share_z: R::abs(unit_z) / unit_norm,
            stick_share_z: R::abs(inverse_z) / unit_stick,
        }
    }

    /// Unit direction of the friction impulse on the object ball after a friction
    /// budget `budget = μ p` (m/s), `budget ≤ s*` (clamped).
    pub(super) fn friction_direction(&self, budget: R) -> (R, R) {
        let half = R::of(0.5);
        // f = S / s* in [0, 1], written so that no 0/0 or ∞/∞ can occur.
        let fraction = if budget >= self.stick_budget {
            R::ONE
        } else {
            budget / self.stick_budget
        };
        // α / |v₀| in units where |v₀| = unit_norm · scale; σ = s*/|v₀|.
        let sigma = self.stick_budget_per_norm();
        let alpha_per_norm = half * fraction * sigma
            + (self.boundary_alpha_per_norm - half * sigma) * fraction * fraction;
        // v_m / scale = u − (α/|v₀|) K u.
        let mid_y =
            self.unit_y - alpha_per_norm * (k_y::<R>() * self.unit_y + self.k_yz * self.unit_z);
        let mid_z = self.unit_z * (R::ONE - alpha_per_norm * self.k_z);
        let inv = R::ONE / R::sqrt(mid_y * mid_y + mid_z * mid_z);
        (-mid_y * inv, -mid_z * inv)
    }

    /// `|ĵ_z|`, the friction direction's vertical share, for the table-friction rate
    /// after a budget `budget` (m/s): linear in the spent fraction `f = S/s*` (clamped
    /// at 1) between its exact values at the start of the slide (`v̂₀`) and at the
    /// grip (`K⁻¹v₀`, where the direction meets the stick impulse). The mid-point
    /// direction of [`Self::friction_direction`] gives the same ends and costs a square
    /// root in between; against the reference on the 10k grid the interpolation moves
    /// `KimGrip`'s largest velocity error from 0.100 % to 0.111 % of U
    /// (`docs/physics.md` §4).
    pub(super) fn pressing_share(&self, budget: R) -> R {
        let fraction = if budget >= self.stick_budget {
            R::ONE
        } else {
            budget / self.stick_budget
        };
        self.start_share_z + fraction * (self.stick_share_z - self.start_share_z)
    }

    /// `σ = s* / |v₀|`, a pure number of order `1/k`.
    pub(super) fn stick_budget_per_norm(&self) -> R {
        self.stick_per_norm
    }
}
