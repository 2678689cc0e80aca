//! `KimGrip`: the seed's first-order model with a gripping branch (erratum E6) and a
//! second-order correction of the friction direction. Continuous in the scene (across
//! the grip, and as μ, μ_s → 0). It has two methods (below): the fast path's single
//! mid-point direction, where it holds (constant μ ≤ 0.15, μ_s ≤ 0.4, μ·μ_s ≤ 0.04,
//! μ_ct = 0), and the general path's slide in pieces everywhere else. Across the edges
//! of the fast path's region the answer moves by up to 0.44 % of U (max of |Δv| and
//! R|Δω| over 200,000 scenes either side of each edge, each side within its bound of
//! the reference; `host-tests/tests/extremes.rs`,
//! `kim_grip_method_edges_move_it_within_its_bound`), and by up to 4.4e-4 U on the grid
//! as μ_ct → 0 (`core/tests/extremes.rs`, `friction_to_zero_is_continuous`).
//!
//! Everything is per unit mass (impulses in m/s). Notation: approach speed
//! `a = U_i cos φ`; tangential slip `v₀ = (v_y0, v_z0)` (seed eq. (11)).
//!
//! **Tangential compliance.** A friction impulse `j` on the object ball (and `−j` on
//! the cue ball) changes the slip by `K j` with `K = diag(k_y, k_z)` (seed eqs. (19),
//! (23) with erratum E1):
//! `k_y = 2(1+ν)/ν`, and `k_z = (2+ν−μ_s)/ν` when the object ball is pressed into the
//! table (`v_z0 > 0`, topspin: its table friction `μ_s` per unit of pressing impulse
//! spins it back) or `k_z = (2+ν)/ν` when the cue ball is (draw; the seed neglects the
//! cue-ball/table friction).
//!
//! **Grip.** If the slip vanishes during the impact the contact then sticks with zero
//! friction (the normal impulse acts through both centres and cannot restart slip),
//! so the total friction impulse is exactly `j_stick = −K⁻¹ v₀`. Sliding needs a
//! friction "budget" `μ p` of at least `s* ≈ |j_stick|` (exact when `K` is isotropic;
//! within 1.3 % for `k_y/k_z ≤ 1.4`, see `docs/physics.md`).
//!
//! **Slide.** `K` is anisotropic, so the slip direction rotates during the impact
//! (seed eq. (21)) and the impulse direction differs from `−v̂₀` at second order. The
//! exact sliding impulse after a budget `S = μ p` is `K⁻¹(v(S) − v₀)` along the curve of
//! the invariant (24). The fast path uses the direction of `v_m = v₀ − α(S) K v̂₀` with
//! `α(S) = S/2 + (|v₀|/(k_y+k_z) − s*/2)(S/s*)²`: the midpoint rule (second order) for
//! small `S`, and at `S = s*` exactly parallel to `K⁻¹v₀`, so the slide impulse meets
//! `j_stick` there and the model is continuous across the boundary. The general path
//! takes the slide in pieces, each by that rule from its own starting slip (`curved`),
//! whose sliding path's length replaces `s*` as the grip threshold.
//!
//! **Normal impulse.** While the object ball slides against the table its friction
//! `μ_s` times the pressing impulse acts along `−x`, at a rate `ρ` per unit normal
//! impulse, and stops when the contact grips at `p*`. The fast path takes one rate, `ρ =
//! μ μ_s |ĵ_z|` (`|ĵ_z|` at the first-order end of the slide, linear in the spent budget
//! between its exact values at the start and at the grip); the general path one up to
//! the first-order compression end and another after it, from the pieces' pressing
//! (`normal::two_rate_normal_impulse`), times `ĉ_x` (below). With `v_x(p) = −a + 2p −
//! ρ min(p, p*)`, the compression end and Stronge's energetic restitution
//! (`W_restitution = e*² |W_compression|`, seed eq. (37)) give `p_f` in closed form on
//! each linear piece.
//!
//! **Table friction.** The object ball's table contact slides, so its friction is on its
//! Coulomb cone, `μ_s (−j_z)` (the table's normal impulse on the object ball is the
//! downward friction `−j_z`). The fast path takes the rate's `ρ min(p, p*)`, capped by
//! that cone, along the table-contact slip of the ball–ball impulses alone at the end
//! ([`table_contact_slip`]). The general path takes the cone itself, along the sum of
//! each piece's pressing along its own table-contact slip (which turns as the slip
//! does), and with the object ball pressed takes a second pass with that direction `ĉ`
//! in `K` (`k_z = (2+ν−μ_s ĉ_x)/ν`, `k_yz = μ_s ĉ_y`; `docs/physics.md` §4 item 8). The
//! fast paths decline every `Params` outside their region.

use crate::error::Result;
use crate::impact::Impact;
use crate::outcome::Outcome;
use crate::params::Params;
use crate::real::Real;

mod budget;
mod curved;
mod fast_path;
mod general;
mod normal;
#[cfg(any(test, feature = "speed-path"))]
mod slip;
#[cfg(feature = "speed-path")]
mod speed_path;
#[cfg(any(test, feature = "speed-path"))]
mod straight;
pub(crate) use curved::{CURVED_MIN_MU, CURVED_MIN_MU_MU_S, CURVED_MIN_MU_S};
pub(crate) use fast_path::MIN_SLIP_SQUARED as FAST_PATH_MIN_SLIP_SQUARED;
use general::general;
use normal::{final_normal_impulse, gripped_normal_impulse};

/// Largest `|v₀|²` ((m/s)²) treated as exact gearing, a slip of 1 pm/s: the fast
/// path's smallest slip, so that with a constant μ every scene is either on the fast
/// path or without friction.
const GEARING_SLIP_SQUARED: f32 = FAST_PATH_MIN_SLIP_SQUARED;

/// `ν = 2/5`, exact in `R`.
fn nu<R: Real>() -> R {
    R::of(2.0) / R::of(5.0)
}

/// Slip change per unit specific friction impulse along `y` (seed eq. (19)):
/// `2(1+ν)/ν = 7`.
fn k_y<R: Real>() -> R {
    R::of(7.0)
}

// Not inlined into `model::collide_in`: there LLVM hoists work shared by several models'
// code (divisions included) above the dispatch, where every model pays for it.
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    // The fast path declines (`None`) every scene it does not cover, those whose
    // `Params` it does not apply to included (their minimum slip is +∞).
    match fast_path::collide::<R>(params, impact) {
        Some(outcome) => Ok(outcome),
        #[cfg(feature = "speed-path")]
        None => beyond_fast_path::<R>(params, impact),
        #[cfg(not(feature = "speed-path"))]
        None => general::<R>(params, impact),
    }
}

/// Every scene the constant-μ fast path declines: in the speed-dependent fast path's
/// region, TP A.14's μ(v) in closed form (`speed_path`, f32 only) and, in `f64` or where
/// it declines, the single-direction general path whose equations it specialises
/// (`straight`: `f32` and `f64` answer by one method); else the general path. Not
/// inlined, so that the constant-μ fast path's code stays as it was without it.
#[cfg(feature = "speed-path")]
#[inline(never)]
fn beyond_fast_path<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    if params.derived().kim_grip_speed_law.is_some() {
        if R::SINGLE {
            if let Some(outcome) = speed_path::collide(params, impact) {
                return Ok(outcome);
            }
        }
        return straight::general::<R>(params, impact);
    }
    general::<R>(params, impact)
}

/// Initial tangential slip `(v_y0, v_z0)` (seed eq. (11)) evaluated in `R`.
pub(crate) fn initial_slip<R: Real>(params: &Params, impact: &Impact) -> (R, R) {
    let radius = R::of(params.radius());
    let u = impact.velocity();
    let w = impact.spin();
    (-R::of(u.y) - radius * R::of(w.z), radius * R::of(w.y))
}

/// The direction `(c_x, c_y)` (m/s) of the object ball's table-contact slip at the end of
/// the pressing span (see [`table_friction_components`]): that of the slip the ball–ball
/// impulses alone give, `c_free = (p − j_z/ν, j_y)` per unit mass (the normal impulse `p`
/// along x; the friction `j_z`, acting at `−R x̂`, spins the ball by `Ω_y = j_z/(ν R)`,
/// which adds `−R Ω_y`; `j_y` moves it along y and spins it about z only). The table
/// friction `T` (m/s, at `−R ẑ`) moves the contact by `(1 + 1/ν) T` (its impulse plus the
/// spin it gives, `I = ν m R²`), and Coulomb's law directs it against the slip,
/// `T = −|T| ĉ`, so while the contact slides (`(1 + 1/ν)|T| < |c_free|`, as the model
/// assumes) `c = c_free − (1 + 1/ν)|T| ĉ` stays parallel to `c_free`. Before issue 16
/// item 3 this took `c_x = p − X − (j_z + X)/ν` with `X` the friction's whole size but
/// `c_y = j_y`, as if all of `T` acted along x: that turned the direction towards y, and
/// reversed `c_x` where `(1 + 1/ν) X` exceeded `c_free`'s x component.
/// `1/ν = 5/2` is exact in `R` (`nu()` is 2/5 rounded); both components are `≥ 0`
/// along x (`p ≥ 0`, `j_z ≤ 0` with the object ball pressed), so `c_x ≥ 0` exactly.
#[inline(always)]
fn table_contact_slip<R: Real>(span: R, j_y: R, j_z: R) -> (R, R) {
    (span - j_z * R::of(2.5), j_y)
}

#[cfg(test)]
mod tests;
