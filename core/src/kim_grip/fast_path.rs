//! `KimGrip` for the common scene, written for the instruction count: constant μ, no
//! cue-ball/table friction acting (μ_ct = 0, or the cue ball not pressed into the
//! cloth), and a slip in the normal floating-point range. Same equations as the general
//! path of the parent module, specialised:
//!
//! * `K = diag(7, k_z)`, so the boundary parameter is `α_b/|v₀| = 1/(k_y + k_z)` (the
//!   general cross-product formula reduces to it exactly), and `K⁻¹` is two divisions;
//! * constant μ makes the friction budget `S(p) = μ p`, so the fraction of the stick
//!   budget spent is `p / p*` and the table-friction rate is `ρ = μ μ_s |ĵ_z|` with no
//!   division by the span;
//! * with the object ball pressed, `(1+e)a/2 ≥ p*` settles the grip before `ρ` is
//!   known (the table friction only raises the normal impulse);
//! * the slip is used unscaled: `|v₀|² ≥ MIN_SLIP_SQUARED` keeps every square far from
//!   underflow (tinier slips are exact gearing in the general path);
//! * no clamps where only rounding (or a zero-length table-contact slip) could take a
//!   square root's argument below zero or divide zero by zero: the NaN that results
//!   fails the final guard, and the general path, which has the clamps, repeats the
//!   scene.
//!
//! Every branch is straight-line code: `bench-firmware`'s `kimgrip-count` counts one
//! shot per branch, and `cargo xtask test` fails if one takes more than 150
//! instructions on the Cortex-M4F.
//!
//! Returns `None` when the scene is outside that case; the caller then runs the
//! general path. `host-tests` and the unit tests below check that both paths agree.

use super::{final_normal_impulse, gripped_normal_impulse, k_y, table_contact_slip};
use crate::impact::Impact;
use crate::outcome::{Lifted, Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

/// Smallest `|v₀|²` ((m/s)²) handled here: 1e-24, a slip of 1 pm/s. Squares of the
/// slip, of the stick impulse (`|v₀|/7`) and of the mid-point slip stay above 1e-28,
/// ten orders of magnitude above `f32`'s smallest normal number.
pub(crate) const MIN_SLIP_SQUARED: f32 = 1e-24;

/// Bit pattern of the bound on the sum of impulses `finish` accepts: 0x5B5B_5B5B is
/// 6.17e16 m/s, chosen because a Cortex-M4 `cmp` takes it as an immediate (1e17's pattern
/// it does not, and one with its low bits zero LLVM compares by a shift first).
const MAX_GUARDED_BITS: u32 = 0x5B5B_5B5B;

/// The fast path, or `None` if the scene needs the general one: its `Params` have a
/// friction law other than a constant μ > 0 or a cue-ball/table friction (their
/// derived minimum slip is +∞), its slip is below [`MIN_SLIP_SQUARED`], or the guard
/// of `Outcome::from_impulses` would trip (the general path then reports the error).
#[inline(always)]
pub(super) fn collide<R: Real>(params: &Params, impact: &Impact) -> Option<Outcome> {
    let derived = params.derived();
    let radius = R::of(params.radius());
    let (u, w) = (impact.velocity(), impact.spin());
    // Initial slip (seed eq. (11)), m/s.
    let slip_y = -R::of(u.y) - radius * R::of(w.z);
    let slip_z = radius * R::of(w.y);
    let slip_squared = slip_y * slip_y + slip_z * slip_z;
    // Validated inputs keep `slip_squared` finite, so +∞ sends every scene away. In f32
    // the test compares bit patterns (as integers; for numbers ≥ +0 the same order):
    // `sqrt_pair` below takes `slip_squared` in a core register anyway, so the compare
    // reuses that move and needs no FPU status transfer. (A NaN, which validated inputs
    // cannot give either, would pass here and fail the final guard.)
    let covered = if R::SINGLE {
        slip_squared.to_f32().to_bits() >= derived.kim_grip_min_slip_squared.to_bits()
    } else {
        slip_squared >= R::of(derived.kim_grip_min_slip_squared)
    };
    if !covered {
        return None;
    }
    let mu = R::of(derived.kim_grip_mu);
    if slip_z > R::ZERO {
        slide::<R, true>(params, impact, mu, slip_y, slip_z, slip_squared)
    } else {
        slide::<R, false>(params, impact, mu, slip_y, slip_z, slip_squared)
    }
}

/// The rest of the fast path, compiled separately for `OBJECT_PRESSED` (`v_z0 > 0`,
/// topspin: the object ball is pressed into the cloth and its table friction acts)
/// and not, so that each keeps only its own work.
#[inline(always)]
fn slide<R: Real, const OBJECT_PRESSED: bool>(
    params: &Params,
    impact: &Impact,
    mu: R,
    slip_y: R,
    slip_z: R,
    slip_squared: R,
) -> Option<Outcome> {
    let mu_s = R::of(params.mu_s());
    let derived = params.derived();
    // k_z = (2 + ν − μ_s)/ν = 6 − 2.5 μ_s when the object ball is pressed, else 6
    // (seed eq. (23) with erratum E1), and the boundary parameter 1/(k_y + k_z).
    let (k_z, boundary) = if !OBJECT_PRESSED {
        (R::of(6.0), R::ONE / R::of(13.0))
    } else if R::SINGLE {
        (R::of(derived.pressed_k_z), R::of(derived.pressed_boundary))
    } else {
        let k_z = R::of(6.0) - R::of(2.5) * mu_s;
        (k_z, R::ONE / (k_y::<R>() + k_z))
    };
    let half_one_plus_restitution = if R::SINGLE {
        R::of(derived.half_one_plus_restitution)
    } else {
        R::of(0.5) * (R::ONE + R::of(params.restitution()))
    };
    // Stick impulse j_stick = −K⁻¹ v₀ and the budget s* = |j_stick| that stops the
    // slip. `stick_z` is kept as −K⁻¹v₀'s z component with its sign flipped (> 0 with
    // the object ball pressed): only its square and its ratio to s* are needed unless
    // the contact grips.
    let stick_y = -slip_y / k_y::<R>();
    let stick_z_flipped = slip_z / k_z;
    let (stick_budget, slip_norm) = R::sqrt_pair(
        stick_y * stick_y + stick_z_flipped * stick_z_flipped,
        slip_squared,
    );
    let grip_normal = stick_budget / mu; // p*, m/s
    let approach = R::of(impact.velocity().x);
    // The first-order normal impulse (1+e)a/2 (no table friction).
    let first_normal = half_one_plus_restitution * approach;
    // `certain`: the contact grips whatever the table friction ((1+e)a/2 ≥ p*).
    let (table_rate, normal, slides, certain) = if !OBJECT_PRESSED {
        let restitution = R::of(params.restitution());
        let (normal, slides) = final_normal_impulse::<R, false>(
            approach,
            restitution,
            first_normal,
            R::ZERO,
            grip_normal,
        );
        (R::ZERO, normal, slides, false)
    } else {
        // ρ = μ μ_s |ĵ_z| (`docs/physics.md` §4 item 5): |ĵ_z| is v̂₀'s
        // z component at f = 0 and the stick impulse's at f = 1, interpolated at the
        // first-order end of the slide, f = min((1+e)a/2 / p*, 1). Both are > 0 here.
        let mu_mu_s = if R::SINGLE {
            R::of(derived.kim_grip_mu_mu_s)
        } else {
            mu * mu_s
        };
        let end = stick_z_flipped / stick_budget;
        if first_normal >= grip_normal {
            // f = 1, and the contact grips: the table friction (ρ ≥ 0) only raises
            // the normal impulse above (1+e)a/2 ≥ p*.
            let table_rate = mu_mu_s * end;
            let relief = R::ONE - R::of(0.5) * table_rate;
            let restitution = R::of(params.restitution());
            let normal =
                gripped_normal_impulse::<R, false>(approach, restitution, relief, grip_normal);
            (table_rate, normal, false, true)
        } else {
            let start = slip_z / slip_norm;
            let fraction = first_normal / grip_normal;
            let table_rate = mu_mu_s * (start + fraction * (end - start));
            // e* is read in each branch that needs it, not once above: only the grips
            // use it, and here LLVM then loads it after the slide/grip test.
            let restitution = R::of(params.restitution());
            let (normal, slides) = final_normal_impulse::<R, false>(
                approach,
                restitution,
                first_normal,
                table_rate,
                grip_normal,
            );
            (table_rate, normal, slides, false)
        }
    };
    // The span over which the object ball is pressed is min(p, p*): the branch
    // taken says which.
    let (j_y, j_z, regime, span) = if slides {
        // σ = s*/|v₀| and α_b/|v₀| = 1/(k_y + k_z): the direction's shape parameters.
        // (σ/2 as s*/(2|v₀|): the same rounding as 0.5 s*/|v₀|, one instruction fewer.)
        let half_sigma = stick_budget / (slip_norm + slip_norm);
        // The fraction f = μp/s* ≤ 1 of the stick budget spent.
        let fraction = normal / grip_normal;
        let (j_y, j_z) = sliding_impulse(
            (slip_y, slip_z),
            k_z,
            boundary,
            half_sigma,
            fraction,
            mu * normal,
        );
        (j_y, j_z, Regime::Sliding, normal)
    } else {
        (stick_y, -stick_z_flipped, Regime::Gripping, grip_normal)
    };
    let (table, table_y, table_size) = if OBJECT_PRESSED {
        table_friction(certain, (mu_s, stick_z_flipped, table_rate), span, j_y, j_z)
    } else {
        (R::ZERO, R::ZERO, R::ZERO)
    };
    // The guard of `Outcome::from_impulses` (Σ j² ≤ 1e36 over the four impulses the
    // others derive from), implied by a bound on the normal impulse alone: |j| ≤
    // max(μ p, s*) and table_size ≤ ρ span ≤ p, with μ ≤ 1 and s* ≤ |v₀|/k_z below
    // 1e4 m/s for validated inputs, so p below `finish`'s bound (6.17e16) keeps the
    // sum under 1.2e34 + 1e8. A NaN anywhere upstream makes p NaN and fails the test
    // too. With the object ball pressed, `table` joins the sum: it is at most
    // `table_size ≤ p`, unless the table direction above failed; then `scale` is ∞ or
    // NaN and `table = scale c_x` is ∞ or NaN too (`∞ · 0` is NaN), while `table_y` can
    // only fail along with it. It needs no `abs`: `scale ≥ 0` and `c_x = p − j_z/ν ≥ 0`
    // (j_z < 0 here), so `table` is never below zero.
    let guarded = if OBJECT_PRESSED {
        normal + table
    } else {
        normal
    };
    finish::<R, OBJECT_PRESSED>(
        params,
        impact,
        guarded,
        (normal, j_y, j_z),
        (table, table_y, table_size),
        regime,
    )
}

/// The end of both fast paths: `None` unless `guarded` (the sum of impulses whose bound
/// implies `Outcome::from_impulses`'s guard, see `slide`) is below 6.17e16
/// ([`MAX_GUARDED_BITS`]; a NaN fails too: the general path then repeats the scene, its
/// guard returns the error or its zero-slip branch gives the table friction a
/// direction), else the outcome of the ball–ball impulses `(p, j_y, j_z)` and the
/// pressed object ball's table friction `(table, table_y, size)`. The friction opposes the slip, whose z component keeps its
/// sign while it shrinks (`α k_z ≤ k_z/(k_y + k_z) < 1`), and so does the stick impulse:
/// with `v_z0 > 0` the friction pushes the cue ball up (`j_z < 0`), else the object ball.
#[inline(always)]
pub(super) fn finish<R: Real, const OBJECT_PRESSED: bool>(
    params: &Params,
    impact: &Impact,
    guarded: R,
    (normal, j_y, j_z): (R, R, R),
    (table, table_y, table_size): (R, R, R),
    regime: Regime,
) -> Option<Outcome> {
    // An unsigned compare of the bit patterns: for `guarded ≥ +0` (a sum of impulses
    // that are, see `slide`) it orders as the numbers do, and every NaN (of either sign),
    // every infinity and every number below zero has a larger pattern. One move to a
    // core register and a compare with an immediate, instead of loading the bound,
    // comparing in the FPU and moving its flags.
    let bounded = guarded.to_f32().to_bits() < MAX_GUARDED_BITS;
    if !bounded {
        return None;
    }
    let impulses = SpecificImpulses {
        normal,
        friction_y: j_y,
        friction_z: j_z,
        table,
        table_y,
        table_size,
        cue_table_x: R::ZERO,
        cue_table_y: R::ZERO,
    };
    let lifted = if OBJECT_PRESSED {
        Lifted::Cue
    } else {
        Lifted::Object
    };
    Some(Outcome::assemble::<R, OBJECT_PRESSED>(
        params, impact, impulses, regime, lifted,
    ))
}

/// The sliding friction impulse on the object ball, `j = S (−v_m/|v_m|)`, after the
/// budget `S = budget` (m/s), the fraction `f = fraction` of the stick budget: `v_m = v₀ −
/// α K v₀/|v₀|`, `α/|v₀| = f (σ/2 + (α_b/|v₀| − σ/2) f)` (parent module docs), with
/// `half_sigma = σ/2 = s*/(2|v₀|)` and `boundary = α_b/|v₀| = 1/(k_y + k_z)`. Shared with
/// the speed-dependent fast path.
#[inline(always)]
pub(super) fn sliding_impulse<R: Real>(
    (slip_y, slip_z): (R, R),
    k_z: R,
    boundary: R,
    half_sigma: R,
    fraction: R,
    budget: R,
) -> (R, R) {
    let curvature = boundary - half_sigma;
    let alpha = fraction * (half_sigma + curvature * fraction);
    let mid_y = slip_y - alpha * (k_y::<R>() * slip_y);
    let mid_z = slip_z - alpha * (k_z * slip_z);
    let scale = budget / R::sqrt_inline(mid_y * mid_y + mid_z * mid_z);
    (-scale * mid_y, -scale * mid_z)
}

/// The pressed object ball's table friction `(table, table_y, size)` (m/s: `−x`
/// magnitude, `y` component, size) after the pressing span `span`. Its size is the rate
/// `ρ = table_rate` over the span, capped by Coulomb's cone, μ_s times the table's
/// normal impulse `−j_z` (j_z < 0 here, the friction pressing the object ball down; see
/// the general path) — or, when the grip is `certain` (`(1+e)a/2 ≥ p*`), the cone itself,
/// `μ_s |j_stick,z|` (there `ρ p* = μ_s |j_stick,z|` by construction, so no `min`). Its
/// direction is the table-contact slip of the ball–ball impulses alone
/// (`table_contact_slip`), with no zero-length branch: a slip of zero length (or whose
/// square underflows) makes the result infinite or NaN (`∞ · 0` included), which the
/// callers' guards hand to the general path. Shared with the speed-dependent fast path.
#[inline(always)]
pub(super) fn table_friction<R: Real>(
    certain: bool,
    (mu_s, stick_z_flipped, table_rate): (R, R, R),
    span: R,
    j_y: R,
    j_z: R,
) -> (R, R, R) {
    let size = if certain {
        mu_s * stick_z_flipped
    } else {
        R::min(table_rate * span, -(mu_s * j_z))
    };
    let (slip_x, slip_y) = table_contact_slip(span, j_y, j_z);
    let scale = size / R::sqrt_inline(slip_x * slip_x + slip_y * slip_y);
    (scale * slip_x, -scale * slip_y, size)
}
