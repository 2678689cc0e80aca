//! `KimGrip`'s slide on the general path (every scene the fast paths decline: their
//! region ends at `μ >` [`CURVED_MIN_MU`], `μ_s >` [`CURVED_MIN_MU_S`], `μ·μ_s >`
//! [`CURVED_MIN_MU_MU_S`]); the slip's turn followed in pieces, and the object ball's
//! table friction along the table-contact slip the pieces turn through.
//!
//! While it slides the slip obeys `dv/dS = −K v̂` (`S` the friction budget spent, m/s;
//! `K = [[k_y, k_yz], [0, k_z]]`, seed eqs. (19), (23) with erratum E1), and the friction
//! impulse is exactly `J(S) = K⁻¹(v(S) − v₀)`. A pressed object ball has `k_z = 6 − 2.5
//! μ_s`, so `k_y/k_z` grows from 7/6 at `μ_s = 0` to 2 at `μ_s = 1`: the slip turns
//! further while it shrinks, and the parent module's single mid-point direction and its
//! grip threshold `s* = |K⁻¹v₀|` (within 1.3 % of the sliding path's length up to `μ_s =
//! 0.4`, `docs/physics.md` §4) lose accuracy near the grip. Against the reference,
//! 400,000 scenes of `KimGrip`'s validity domain with topspin and `μ_s` up to 1 put the
//! single direction 0.48 % of U off in velocity and 0.72 % in `R ω` (issue 16 item 3
//! asks 0.25 % / 0.5 %), all at `μ_s > 0.4` with the contact sliding to 80–95 % of `s*`.
//! With `μ > 0.15` the slide is long beside the impact (the grip comes early in the
//! normal impulse), and the single direction erred by up to 0.65 % / 1.6 %; with `μ·μ_s`
//! up to 0.2, its table friction (a first-order rate along the end slip) by up to 0.5 %
//! / 1.1 % (`docs/physics.md` §4 item 8).
//!
//! Here the slide is taken in at most [`PIECES`] pieces. Each piece but the last spends
//! [`PIECE_SHARE`] of the budget that would stop the slip at its start, `|K⁻¹v_k|`; the
//! last spends what is left. Each piece takes the parent module's mid-point direction
//! from its own starting slip (`α(S)`, whose end value `α_b` makes the direction
//! parallel to that piece's stick impulse `K⁻¹v_k`: `α_b = (v × K⁻¹v)/(Kv × K⁻¹v)`,
//! which for this triangular `K` is `|v|/(k_y + k_z)` whatever `k_yz` and `v`: both
//! cross products are `z ((k_y − k_z) y + k_yz z)/(k_y k_z)` times 1 and `k_y + k_z`),
//! which meets that piece's stick impulse at its
//! end, so the pieces add up to `−K⁻¹v₀` exactly when the last one stops the slip: the
//! impulse is continuous across the grip, and the budget that stops the slip (the
//! sliding path's length, the grip threshold used instead of `s*`) is the budget the
//! first pieces spent plus the last one's stick budget. Against the exact solution of
//! `dv/dS = −K v̂` the pieces' impulse is within 0.5 % of `s*` for `k_z ≥ 3.5`, every
//! slip direction and every budget (`tests::curved_slide_follows_the_exact_slide`), and
//! their stopping budget within 1 % of the sliding path's length
//! (`tests::curved_stop_budget_is_the_sliding_path_length`).
//!
//! `k_yz`: with draw, the cue ball's table friction (`μ_ct`, parent module); with the
//! object ball pressed, the `y` component of its table friction's direction `ĉ` (the
//! parent module's second pass; `μ_s ĉ_y`: that friction's `y` component moves the
//! object ball, and with it the contact, along `y`, while its torque, about `x`, leaves
//! the contact's velocity along `y` and `z` unchanged).

use super::k_y;
use crate::real::Real;

/// The fast paths' region (the single mid-point direction; `Params::derived`), outside
/// which every scene takes the general path's pieces: `μ_s` at most this (`k_y/k_z ≤
/// 1.4` with the object ball pressed). The foundation grid (`μ_s` 0–0.4) is inside.
pub(crate) const CURVED_MIN_MU_S: f32 = 0.4;

/// ... μ at most this (a constant law's; a speed-dependent law's `μ(0)` stays at or
/// below it in `KimGrip`'s domain, `validity`): beyond it the single direction erred by
/// up to 0.65 % of U (`docs/physics.md` §4 item 8).
pub(crate) const CURVED_MIN_MU: f32 = 0.15;

/// ... and `μ·μ_s` at most this: the single direction's table friction, at a rate fixed
/// from the first-order budget, held the bound only to here near μ = 0.15, μ_s = 0.4
/// (13 of 400,000 scenes at μ 0.14–0.15, μ_s 0.35–0.4 up to 0.553 % in R ω, before).
pub(crate) const CURVED_MIN_MU_MU_S: f32 = 0.04;

/// Pieces at most.
pub(super) const PIECES: usize = 12;
/// Share of its stick budget each piece but the last spends.
const PIECE_SHARE: f32 = 0.25;

/// A slip and its compliance, in units where the slip's largest component is 1 (as the
/// single-direction path's `TangentialSlip`).
#[derive(Clone, Copy)]
pub(super) struct CurvedSlide<R> {
    /// `v₀ / scale`.
    unit_y: R,
    unit_z: R,
    /// `scale` (m/s).
    scale: R,
    /// `k_yz` and `k_z` (`k_y` is 7).
    k_yz: R,
    k_z: R,
    /// The pressed ball's table-contact slip before the impact, negated (units of
    /// `scale`), and the coefficient of `j_z` in it, `∓1/ν` (object ball, cue ball):
    /// [`Self::march`] follows `±c`.
    contact: (R, R),
    spin_share: R,
}

impl<R: Real> CurvedSlide<R> {
    pub(super) fn new(unit_y: R, unit_z: R, scale: R, k_yz: R, k_z: R) -> Self {
        Self {
            unit_y,
            unit_z,
            scale,
            k_yz,
            k_z,
            contact: (R::ZERO, R::ZERO),
            spin_share: R::of(-2.5),
        }
    }

    /// The same slide with [`Self::march`]'s table friction direction that of the ball
    /// pressed into the cloth: `(−c₀_x, −c₀_y, s)`, its table-contact slip before the
    /// impact, negated, in units of `scale`, and the share `s` of `j_z` in it: the object
    /// ball's `(0, 0, −1/ν)`, the cue ball's (draw) `(−c'₀_x, −c'₀_y, 1/ν)`.
    pub(super) fn pressed(self, (c_x, c_y, spin_share): (R, R, R)) -> Self {
        Self {
            contact: (c_x, c_y),
            spin_share,
            ..self
        }
    }

    /// `K⁻¹ v` for a slip `v` in units of `scale`.
    fn inverse(&self, (y, z): (R, R)) -> (R, R) {
        let i_z = z / self.k_z;
        ((y - self.k_yz * i_z) / k_y::<R>(), i_z)
    }

    /// The stick impulse `−K⁻¹v₀` (m/s), which stops the slip.
    pub(super) fn stick_impulse(&self) -> (R, R) {
        let (i_y, i_z) = self.inverse((self.unit_y, self.unit_z));
        (-i_y * self.scale, -i_z * self.scale)
    }

    /// `K v`.
    fn apply(&self, (y, z): (R, R)) -> (R, R) {
        (k_y::<R>() * y + self.k_yz * z, self.k_z * z)
    }

    /// `|K⁻¹ v|` for a slip `v` in units of `scale`: the budget that would stop it were
    /// its direction fixed.
    fn stick_budget(&self, slip: (R, R)) -> R {
        let (i_y, i_z) = self.inverse(slip);
        R::sqrt(i_y * i_y + i_z * i_z)
    }

    /// One piece: the friction impulse (units of `scale`) after spending `budget` from
    /// slip `v` whose stick budget is `stick > budget` (the parent module's `α(S)` with
    /// `f = budget/stick`, `σ = stick/|v|` and `α_b/|v| = 1/(k_y + k_z)`, module docs).
    fn piece(&self, slip: (R, R), norm: R, stick: R, budget: R) -> (R, R) {
        let half = R::of(0.5);
        let (y, z) = slip;
        let (k_y_v, k_z_v) = self.apply(slip);
        let boundary = R::ONE / (k_y::<R>() + self.k_z);
        let fraction = budget / stick;
        let half_sigma = half * stick / norm;
        let alpha_per_norm = fraction * (half_sigma + (boundary - half_sigma) * fraction);
        let mid_y = y - alpha_per_norm * k_y_v;
        let mid_z = z - alpha_per_norm * k_z_v;
        let scale = budget / R::sqrt(mid_y * mid_y + mid_z * mid_z);
        (-scale * mid_y, -scale * mid_z)
    }

    /// The slip after an impulse `j` on the object ball: `v + K j`.
    fn advance(&self, (y, z): (R, R), impulse: (R, R)) -> (R, R) {
        let (d_y, d_z) = self.apply(impulse);
        (y + d_y, z + d_z)
    }

    /// [`Self::profile`]'s stop budget alone.
    #[cfg(test)]
    pub(super) fn stop_budget(&self) -> R {
        self.profile(false).0
    }

    /// The budget (m/s) that stops the slip, the sliding path's length (the first
    /// `PIECES − 1` pieces' budgets and the last one's stick budget), and with `record`
    /// the whole slide's [`Profile`]: the budget spent and the slip speed at each piece's
    /// start, and at the grip (slip speed zero; without `record`, every point zero).
    pub(super) fn profile(&self, record: bool) -> (R, Profile<R>) {
        let point = Point {
            budget: R::ZERO,
            speed: R::ZERO,
            normal: R::ZERO,
        };
        let mut profile = Profile {
            points: [point; PIECES + 1],
        };
        let stop = self
            .walk(
                R::of(f32::INFINITY),
                R::ZERO,
                record.then_some(&mut profile),
            )
            .spent;
        (stop, profile)
    }

    /// The friction impulse `(j_y, j_z)` (m/s) on the object ball after a budget
    /// `budget` (m/s) below [`Self::stop_budget`]; at or above it (rounding), the stick
    /// impulse `−K⁻¹v₀`.
    pub(super) fn impulse(&self, budget: R) -> (R, R) {
        self.march(budget, R::ZERO).impulse
    }

    /// The pieces up to `budget` (m/s): the impulse (m/s) and the budget spent, which
    /// is where the slip stopped if it did (`budget = ∞`: always, in the last piece).
    /// With the normal impulse `normal_per_budget` times the budget spent, also the
    /// pressed ball's table friction direction (unnormalised): each piece's pressing along
    /// that ball's table-contact slip at its middle, which turns as the slip does. For the
    /// object ball the pressing is `−Δj_z` and the slip `c_free = (p − j_z/ν, j_y)` (the
    /// parent module's `table_contact_slip`); for the cue ball (draw, [`Self::pressed`])
    /// `Δj_z` and `c'₀ + (−p − j_z/ν, −j_y)`: it takes `−p x̂ − j` at its contact point
    /// `R x̂`, whose torque spins it by `Ω_y = j_z/(ν R)`, moving its table contact by
    /// `−R Ω_y x̂`.
    pub(super) fn march(&self, budget: R, normal_per_budget: R) -> Marched<R> {
        self.walk(budget, normal_per_budget, None)
    }

    /// [`Self::march`], recording each piece's start (and the grip) in `profile`.
    #[inline(never)]
    fn walk(
        &self,
        budget: R,
        normal_per_budget: R,
        mut profile: Option<&mut Profile<R>>,
    ) -> Marched<R> {
        let target = budget / self.scale;
        let half = R::of(0.5);
        let mut slip = (self.unit_y, self.unit_z);
        let (mut j_y, mut j_z, mut spent) = (R::ZERO, R::ZERO, R::ZERO);
        let mut table = (R::ZERO, R::ZERO);
        for piece in 0..PIECES {
            let left = target - spent;
            if left <= R::ZERO {
                break;
            }
            let stick = self.stick_budget(slip);
            let norm = R::sqrt(slip.0 * slip.0 + slip.1 * slip.1);
            if let Some(profile) = profile.as_deref_mut() {
                profile.record(piece, spent * self.scale, norm * self.scale, false);
            }
            let budget = if piece + 1 < PIECES {
                R::min(R::of(PIECE_SHARE) * stick, left)
            } else {
                left
            };
            let stops = stick <= budget;
            let (impulse, step) = if stops {
                // The rest of the stick impulse: the pieces add up to −K⁻¹v₀.
                let (i_y, i_z) = self.inverse(slip);
                ((-i_y, -i_z), stick)
            } else {
                (self.piece(slip, norm, stick, budget), budget)
            };
            let (mid_y, mid_z) = (j_y + half * impulse.0, j_z + half * impulse.1);
            // `c` for the object ball, `−c'` for the cue ball (whose pressing `+Δj_z`
            // then weighs it with the object ball's sign).
            let c_x = self.contact.0
                + (spent + half * step) * normal_per_budget
                + self.spin_share * mid_z;
            let c_y = self.contact.1 + mid_y;
            let length = R::sqrt(c_x * c_x + c_y * c_y);
            if length > R::ZERO {
                let weight = -impulse.1 / length;
                table = (table.0 + weight * c_x, table.1 + weight * c_y);
            }
            if stops {
                if let Some(profile) = profile {
                    profile.record(piece + 1, (spent + stick) * self.scale, R::ZERO, true);
                }
                return Marched {
                    impulse: self.stick_impulse(),
                    spent: (spent + stick) * self.scale,
                    table,
                };
            }
            slip = self.advance(slip, impulse);
            j_y = j_y + impulse.0;
            j_z = j_z + impulse.1;
            spent = spent + budget;
        }
        Marched {
            impulse: (j_y * self.scale, j_z * self.scale),
            spent: spent * self.scale,
            table,
        }
    }
}

/// The slide's course (`super::budget`): at each piece's start and at the grip, in
/// order, the budget spent, the slip speed and (filled in by `budget`) the normal
/// impulse.
pub(super) struct Profile<R> {
    /// Past the grip (the slip stops in its last piece but for NaN), copies of it.
    pub points: [Point<R>; PIECES + 1],
}

/// One point of a [`Profile`] (each m/s).
#[derive(Clone, Copy)]
pub(super) struct Point<R> {
    pub budget: R,
    pub speed: R,
    pub normal: R,
}

impl<R: Real> Profile<R> {
    /// Point `index`; for the grip (`to_end`), every one after it too. (Out of line:
    /// flash.)
    #[inline(never)]
    fn record(&mut self, index: usize, budget: R, speed: R, to_end: bool) {
        for point in self.points.iter_mut().skip(index) {
            (point.budget, point.speed) = (budget, speed);
            if !to_end {
                break;
            }
        }
    }
}

/// What [`CurvedSlide::march`] found.
pub(super) struct Marched<R> {
    /// The friction impulse `(j_y, j_z)` (m/s).
    pub impulse: (R, R),
    /// The budget spent (m/s).
    pub spent: R,
    /// The object ball's table friction direction, unnormalised (any unit).
    pub table: (R, R),
}

#[cfg(test)]
mod tests;
