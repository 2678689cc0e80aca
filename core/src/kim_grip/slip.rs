//! The single-direction path's tangential slip and the stick impulse that stops it
//! (`straight`, the fast paths' oracle; the general path follows the slide in pieces,
//! `curved`).

use super::k_y;
use crate::real::Real;

/// The initial tangential slip and the quantities derived from it. The slip
/// compliance is `K = [[k_y, k_yz], [0, k_z]]` (`Δv = K J`).
pub(super) struct TangentialSlip<R> {
    /// Slip direction scaled so its largest component is ±1 (`v₀ / scale`).
    pub(super) unit_y: R,
    pub(super) unit_z: R,
    /// Stick impulse `j_stick = −K⁻¹ v₀` (m/s).
    pub(super) stick_y: R,
    pub(super) stick_z: R,
    /// `s* = |j_stick|` (m/s): the friction budget that would stop the slip were its
    /// direction fixed.
    pub(super) stick_budget: R,
}

impl<R: Real> TangentialSlip<R> {
    pub(super) fn new(slip_y: R, slip_z: R, scale: R, k_yz: R, k_z: R) -> Self {
        let unit_y = slip_y / scale;
        let unit_z = slip_z / scale;
        // K⁻¹ u, u = v₀ / scale.
        let inverse_z = unit_z / k_z;
        let inverse_y = (unit_y - k_yz * inverse_z) / k_y::<R>();
        let unit_stick = R::sqrt(inverse_y * inverse_y + inverse_z * inverse_z);
        Self {
            unit_y,
            unit_z,
            stick_y: -inverse_y * scale,
            stick_z: -inverse_z * scale,
            stick_budget: unit_stick * scale,
        }
    }
}
