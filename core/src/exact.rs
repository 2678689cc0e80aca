//! `Exact`: the full rigid-body impact integrated in fixed memory — the physics of the
//! f64 reference solver, in the evaluation precision `R`, with a fixed step count.
//!
//! Why not the seed's closed "exact" solution (eqs. (24)–(41))? It is exact only under
//! the seed's eq. (7), which points the object ball's table friction along `−x`. The
//! first-principles direction — against the table-contact slip, which turns by `O(μ)`
//! — changes the outcome by up to 0.36 % of U on the foundation grid (measured with the
//! reference, `cargo run --release -p cuesight-host --example table_direction`), well
//! above this tier's 0.02 % target, and it breaks the invariant (24) the closed
//! solution rests on. So this tier integrates the vector dynamics instead
//! (`docs/physics.md` §8).
//!
//! State, per unit mass (m/s): ball–ball tangential slip `(v_y, v_z)` of the object-ball
//! contact point relative to the cue-ball one, normal relative velocity `v_n`, the
//! object ball's table-contact slip `(c_x, c_y)`, both balls' vertical velocities, and
//! the accumulated impulses. The clock is the normal impulse `p`, in [`STEPS`] equal
//! steps across the frictionless impact. Per step of normal impulse `dp` and friction
//! impulse `dJ` on the object ball (`ν = 2/5`):
//!
//! * `Δv_y = (2 + 2/ν) dJ_y = 7 dJ_y`, `Δv_z = 2 dJ_z/ν + ΔV_z − ΔU_z`, `Δv_n = 2 dp`;
//! * the table pushes a ball up only: a downward `dJ_z` on the object ball is cancelled
//!   by its table normal impulse `dN`, which brings Coulomb friction `μ_s dN` against
//!   `c` at the step's middle (or the smaller impulse that stops `c`; `table_impulse`):
//!   `T`, with `Δv_n = T_x`, `Δv_y = T_y`, `Δv_z = −T_x/ν`, `Δc = (1 + 1/ν) T` (torque
//!   `(−R ẑ) × T`); the cue ball's, with μ_ct, likewise;
//! * friction `|dJ| = μ(|v_t|) dp` against the slip, its direction and size taken at the
//!   step midpoint (second order); when a step would stop the slip, the impulse that
//!   zeroes it is solved for and the contact sticks (zero friction from then on — the
//!   normal impulse acts through both centres and cannot restart slip);
//! * a step is split into `k` equal substeps (at most [`MAX_SUBSTEPS`]) where a slip
//!   turns inside it: `k = ⌈angle / TURN_PER_SUBSTEP⌉` for the ball–ball slip and for
//!   each table contact whose friction acts; the most where a slip stops or reverses
//!   inside the step, or where its friction is turned towards the stick impulse
//!   (above). A step takes the substeps its predecessor's turn asked for and is taken
//!   again with more where it stuck, blended, or turned more than twice as much (a
//!   smaller shortfall costs less than the retry is worth). The midpoint rule is
//!   second order only while the friction direction turns little within a step: with
//!   24 unsplit steps 3.4 % of domain scenes were more than 1e-4 of U off, the stick
//!   onset's blend (below) alone up to 8e-4 (issue 16 item 4; the `exact_floor`
//!   example, which also gives each scene's f32 floor);
//! * Stronge's energetic restitution: the impact ends when the normal work since
//!   maximum compression is `e*²` times the compression work (seed eq. (37)); the end
//!   of compression and the impact's end are located inside their substep (normal
//!   velocity linear in `p` within a substep, refined on partial substeps).

use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::impact::Impact;
use crate::kim_grip::initial_slip;
use crate::outcome::{Outcome, Regime, SpecificImpulses};
use crate::params::Params;
use crate::real::Real;

/// Steps across the frictionless normal impulse `(1 + e*) U_x / 2`, before splitting.
/// 12 split steps (was 24 unsplit) cost 10,346 instructions on the Cortex-M4F on average
/// and 18,228 at most on the bench grid (was 12,185 / 16,902) for a grid error 5×
/// smaller (`cargo xtask bench`); 16 split steps cost 13,481 / 29,875.
pub const STEPS: usize = 12;

/// Most substeps one step is split into ([`Model::advance_split`]): 6 or 4 left 0.10 %
/// and 0.50 % of representable domain scenes more than 1e-4 of U off (seed 17).
const MAX_SUBSTEPS: u32 = 8;

/// Largest turn (radians) of a slip's direction within one substep. With 0.01 rad,
/// 99.89 % of the domain scenes whose answer f32 can hold within 1e-5 of U are within
/// 1e-4 of U (seed 17, 20,000 scenes, `exact_floor`); 0.015 rad: 99.82 %, 0.02 rad:
/// 99.68 %.
const TURN_PER_SUBSTEP: f32 = 0.01;

/// Least table friction impulse, relative to the step's normal impulse, whose
/// direction's turn splits a step ([`Model::substeps_needed`]).
const SPLIT_FRICTION: f32 = 1e-4;

/// Newton/bisection refinements of the impact's end inside the last step.
const FINAL_STEP_REFINEMENTS: usize = 3;

/// Bisections for the end of an impact that met its work balance with the balls still
/// approaching (e* near 0): 2⁻¹⁶ of a step, 1/(24·65,536) of the normal impulse.
const SEPARATION_BISECTIONS: usize = 16;

/// Normal approach velocity at the impact's end, relative to the approach speed, left
/// as rounding: 64 units of f32 rounding (2⁻¹⁸).
const APPROACH_TOLERANCE: f32 = 3.814_697_3e-6;

#[derive(Clone, Copy)]
struct State<R> {
    slip_y: R,
    slip_z: R,
    normal_velocity: R,
    table_slip_x: R,
    table_slip_y: R,
    object_vz: R,
    cue_vz: R,
    normal: R,
    friction_y: R,
    friction_z: R,
    table_x: R,
    table_y: R,
    cue_slip_x: R,
    cue_slip_y: R,
    cue_table_x: R,
    cue_table_y: R,
}

/// One step taken as equal substeps ([`Model::advance_split`]), up to the substep in
/// which the impact ends if it does.
#[derive(Clone, Copy)]
struct Split<R> {
    /// The state after the step, or at the start of the substep the impact ends in.
    state: State<R>,
    stuck: bool,
    /// `∫ v_n dp` up to `state` (m²/s², per unit mass): the trapezoid rule per substep.
    work: R,
    /// The work at which the impact ends, once compression is over (Stronge: the
    /// compression work times `1 − e*²`).
    target: Option<R>,
    /// Whether a substep's friction direction was turned towards the stick impulse.
    blended: bool,
    /// Where the impact ends: the substep's length and the fraction of it where
    /// compression ended (0 if before it).
    end: Option<(R, R)>,
}

struct Model<R> {
    law: FrictionLaw,
    restitution: R,
    mu_s: R,
    mu_ct: R,
    inv_nu: R,
}

impl<R: Real> Model<R> {
    /// Apply a normal impulse `dp` and a friction impulse `(j_y, j_z)` on the object
    /// ball, then the object ball's table reaction.
    fn step(&self, s: &State<R>, dp: R, j_y: R, j_z: R) -> State<R> {
        let mut n = *s;
        n.normal = s.normal + dp;
        n.friction_y = s.friction_y + j_y;
        n.friction_z = s.friction_z + j_z;
        let mut object_vz = s.object_vz + j_z;
        let mut pressing = R::ZERO;
        if object_vz < R::ZERO {
            pressing = -object_vz;
            object_vz = R::ZERO;
        }
        let cue_vz = R::max(s.cue_vz - j_z, R::ZERO);
        let cue_pressing = R::max(j_z - s.cue_vz, R::ZERO);
        n.slip_y = s.slip_y + R::of(7.0) * j_y;
        n.slip_z = s.slip_z + R::of(2.0) * self.inv_nu * j_z + (object_vz - s.object_vz)
            - (cue_vz - s.cue_vz);
        n.object_vz = object_vz;
        n.cue_vz = cue_vz;
        n.normal_velocity = s.normal_velocity + R::of(2.0) * dp;
        n.table_slip_x = s.table_slip_x + dp - j_z * self.inv_nu;
        n.table_slip_y = s.table_slip_y + j_y;
        // The cue ball's table-contact slip c' = U + ω × (−R ẑ): −dp − j_z/ν, −j_y.
        n.cue_slip_x = s.cue_slip_x - dp - j_z * self.inv_nu;
        n.cue_slip_y = s.cue_slip_y - j_y;
        let gain = R::ONE + self.inv_nu; // table-contact slip change per table impulse
        if cue_pressing > R::ZERO && self.mu_ct > R::ZERO {
            let (t_x, t_y) = table_impulse(
                self.mu_ct * cue_pressing,
                (s.cue_slip_x, s.cue_slip_y),
                (n.cue_slip_x, n.cue_slip_y),
                gain,
            );
            n.cue_table_x = n.cue_table_x + t_x;
            n.cue_table_y = n.cue_table_y + t_y;
            // On the cue ball: ΔU = T and R Δω_y = −T_x/ν enter the slips with the
            // opposite sign to the object ball's.
            n.normal_velocity = n.normal_velocity - t_x;
            n.slip_y = n.slip_y - t_y;
            n.slip_z = n.slip_z - t_x * self.inv_nu;
            n.cue_slip_x = n.cue_slip_x + gain * t_x;
            n.cue_slip_y = n.cue_slip_y + gain * t_y;
        }
        if pressing > R::ZERO && self.mu_s > R::ZERO {
            let (t_x, t_y) = table_impulse(
                self.mu_s * pressing,
                (s.table_slip_x, s.table_slip_y),
                (n.table_slip_x, n.table_slip_y),
                gain,
            );
            n.table_x = n.table_x + t_x;
            n.table_y = n.table_y + t_y;
            n.normal_velocity = n.normal_velocity + t_x;
            n.slip_y = n.slip_y + t_y;
            n.slip_z = n.slip_z - t_x * self.inv_nu;
            n.table_slip_x = n.table_slip_x + gain * t_x;
            n.table_slip_y = n.table_slip_y + gain * t_y;
        }
        n
    }

    /// Linearised slip compliance for a friction impulse that stops the slip from state
    /// `s` within a step of `dp`: `Δv_z = k_z j_z` and `Δv_y = 7 j_y + k_yz j_z`, with the
    /// pressed object ball's table friction against the table-contact slip the step's
    /// ball–ball impulses leave, `c + (dp − j_z/ν, j_y)` (as [`Self::step`] directs it), `j`
    /// estimated without the table (`j_z ≈ −v_z/(1 + 2/ν)`, `j_y ≈ −v_y/7`). Taking `c`
    /// alone let rounding choose the direction where the table contact grips (`c` a
    /// rounding from zero): at `--cut 0 --roll --mu 1 --mu-s 1 --restitution 1` a
    /// negative `c_x` of rounding size gave `k_z = 8.5` instead of 3.5 and a stick
    /// 2.6 % short (issue 16 item 4's flip: 31 of 951 speeds, up to 1.8e-2 U).
    fn stick_compliance(&self, s: &State<R>, dp: R) -> (R, R) {
        let two_over_nu = R::of(2.0) * self.inv_nu;
        let unit = |x: R, y: R| {
            let length = R::sqrt(x * x + y * y);
            if length > R::ZERO {
                (x / length, y / length)
            } else {
                (R::ONE, R::ZERO)
            }
        };
        if s.slip_z > R::ZERO && s.object_vz == R::ZERO {
            // Downward impulse on the object ball: it is pressed, the cue ball rises;
            // Δv_z = j_z + 2 j_z/ν + μ_s j_z c_x/ν (table torque), Δv_y gets μ_s j_z c_y.
            let (free_y, free_z) = (-s.slip_y / R::of(7.0), -s.slip_z / (R::ONE + two_over_nu));
            let (dir_x, dir_y) = unit(
                s.table_slip_x + dp - free_z * self.inv_nu,
                s.table_slip_y + free_y,
            );
            (
                R::ONE + two_over_nu - self.mu_s * dir_x * self.inv_nu,
                self.mu_s * dir_y,
            )
        } else if s.slip_z < R::ZERO && s.cue_vz == R::ZERO {
            // Upward impulse on the object ball: the cue ball is pressed, with μ_ct.
            let (dir_x, dir_y) = unit(s.cue_slip_x, s.cue_slip_y);
            let mu_ct = if self.mu_ct > R::ZERO {
                self.mu_ct
            } else {
                R::ZERO
            };
            (
                R::ONE + two_over_nu + mu_ct * dir_x * self.inv_nu,
                mu_ct * dir_y,
            )
        } else {
            (R::of(2.0) + two_over_nu, R::ZERO)
        }
    }

    /// Friction impulse `(j_y, j_z)` that zeroes the slip `(slip_y, slip_z)` at the
    /// compliance `(k_z, k_yz)`.
    fn solve_slip(compliance: (R, R), slip_y: R, slip_z: R) -> (R, R) {
        let j_z = -slip_z / compliance.0;
        (-(slip_y + compliance.1 * j_z) / R::of(7.0), j_z)
    }

    /// Friction impulse that zeroes the slip by the end of a step of `dp` (the linearised
    /// solution), with the compliance `(k_z, k_yz)` it used. (Two corrections on the
    /// actual step map, for the table friction's turn within the step, kept the end
    /// of sliding continuous before steps were split; with the split they changed no
    /// domain scene's error by more than 1e-6 of U, and are gone.)
    fn stick_impulse(&self, s: &State<R>, dp: R) -> ((R, R), (R, R)) {
        let compliance = self.stick_compliance(s, dp);
        (Self::solve_slip(compliance, s.slip_y, s.slip_z), compliance)
    }

    /// Advance `split` (its state, work so far and the end's target if known) by one
    /// step of normal impulse `dp` as `substeps` equal substeps, locating the end of
    /// compression (and with it the target) and stopping at the substep the impact ends
    /// in. In place: the firmware's stack holds one `Split` per level, not two.
    fn advance_split(&self, split: &mut Split<R>, dp: R, substeps: u32) {
        let (zero, half) = (R::ZERO, R::of(0.5));
        let h = dp / R::of(substeps as f32);
        for _ in 0..substeps {
            let (next, next_stuck, blended) = self.advance(&split.state, h, split.stuck);
            split.blended = split.blended || blended;
            let (v0, v1) = (split.state.normal_velocity, next.normal_velocity);
            let mut from = zero;
            if split.target.is_none() && v1 >= zero {
                // The end of compression, v_n = 0, linear in the substep: inside one of
                // the step's substeps, not across the whole step, where v_n has kinks (a
                // stick, the tables' friction starting) that put the compression work,
                // and with it the end of an impact at e* ≈ 0, off by up to 1.9e-3 U
                // (`extremes.rs`'s `exact_is_continuous_at_stick_onset`).
                let fraction = if v1 > v0 { -v0 / (v1 - v0) } else { zero };
                let compression = split.work + half * v0 * fraction * h;
                split.target = Some(compression * (R::ONE - self.restitution * self.restitution));
                from = fraction;
            }
            let next_work = split.work + half * (v0 + v1) * h;
            if split.target.is_some_and(|target| next_work >= target) {
                split.end = Some((h, from));
                return;
            }
            split.state = next;
            split.stuck = next_stuck;
            split.work = next_work;
        }
    }

    /// Substeps the step from `s` (`stuck`) to `split` asks for (module docs): the most
    /// any sliding contact's turn asks for; [`MAX_SUBSTEPS`] where the contact stuck
    /// inside the step or a substep was turned towards the stick impulse.
    fn substeps_needed(s: &State<R>, stuck: bool, split: &Split<R>, dp: R) -> u32 {
        let next = &split.state;
        let mut substeps = if split.blended || split.stuck != stuck {
            MAX_SUBSTEPS
        } else {
            1
        };
        // A table contact's turn counts where its friction acts: an impulse of at least
        // SPLIT_FRICTION times the step's normal impulse (below it a turn moves the
        // outcome by less than the f32 rounding of the step, and splitting it only added
        // rounding: kinetic energy up 1.9e-6 at μ 1e-7, μ_ct 0.3, e* 1, found by
        // `properties.rs`).
        let least = R::of(SPLIT_FRICTION) * dp;
        let least_squared = least * least;
        let acts = |dx: R, dy: R| dx * dx + dy * dy > least_squared;
        if !stuck && !split.stuck {
            let turn = turn_substeps((s.slip_y, s.slip_z), (next.slip_y, next.slip_z));
            substeps = substeps.max(turn);
        }
        if acts(next.table_x - s.table_x, next.table_y - s.table_y) {
            let turn = turn_substeps(
                (s.table_slip_x, s.table_slip_y),
                (next.table_slip_x, next.table_slip_y),
            );
            substeps = substeps.max(turn);
        }
        if acts(
            next.cue_table_x - s.cue_table_x,
            next.cue_table_y - s.cue_table_y,
        ) {
            let turn = turn_substeps(
                (s.cue_slip_x, s.cue_slip_y),
                (next.cue_slip_x, next.cue_slip_y),
            );
            substeps = substeps.max(turn);
        }
        substeps
    }

    /// Advance one step of normal impulse `dp`; `stuck` tells whether the contact grips.
    /// Also returns whether the step's friction direction was turned towards the stick
    /// impulse (the blend below).
    fn advance(&self, s: &State<R>, dp: R, stuck: bool) -> (State<R>, bool, bool) {
        if stuck {
            return (self.step(s, dp, R::ZERO, R::ZERO), true, false);
        }
        let slip = R::sqrt(s.slip_y * s.slip_y + s.slip_z * s.slip_z);
        if slip == R::ZERO {
            return (self.step(s, dp, R::ZERO, R::ZERO), true, false);
        }
        // The impulse that stops the slip, and the normal impulse sliding friction needs
        // to deliver it along the slip's decrease (effective compliance k̄ = |v| / s*,
        // the `friction` module's integral of 1/μ).
        let ((stick_y, stick_z), (k_z, k_yz)) = self.stick_impulse(s, dp);
        let stick = R::sqrt(stick_y * stick_y + stick_z * stick_z);
        if stick == R::ZERO {
            return (self.step(s, dp, stick_y, stick_z), true, false);
        }
        let compliance = slip / stick;
        if self.law.normal_impulse_between(slip, R::ZERO, compliance) <= dp {
            return (self.step(s, dp, stick_y, stick_z), true, false);
        }
        // Friction budget ∫ μ dp over this step.
        let budget = match self.law {
            FrictionLaw::Constant(mu) => R::of(mu) * dp,
            FrictionLaw::SpeedDependent { .. } => {
                // μ follows the slip speed, which falls by v̂ · K v̂ per unit friction
                // impulse against the slip (K the step's slip compliance, as
                // `stick_compliance` linearises it). The stick impulse's ratio |v|/|s*|
                // equals it only where v is an eigenvector of K; elsewhere it evaluated
                // μ at the wrong speed, an O(dp) error per step: first-order convergence,
                // 6.6e-4 of U at 24 steps on domain scene 9926 of seed 17 (now 4e-5).
                let (y, z) = (s.slip_y / slip, s.slip_z / slip);
                let along = R::of(7.0) * y * y + k_yz * y * z + k_z * z * z;
                let along = if along > R::ZERO { along } else { compliance };
                self.law.slip_change(slip, dp, along) / along
            }
        };
        // Direction at the step midpoint (second order) ...
        let half = R::of(0.5);
        let first = half * budget / slip;
        let mid = self.step(s, half * dp, -s.slip_y * first, -s.slip_z * first);
        let mid_slip = R::sqrt(mid.slip_y * mid.slip_y + mid.slip_z * mid.slip_z);
        let (mid_y, mid_z) =
            if mid_slip > R::ZERO && mid.slip_y * s.slip_y + mid.slip_z * s.slip_z > R::ZERO {
                (-mid.slip_y / mid_slip, -mid.slip_z / mid_slip)
            } else {
                (-s.slip_y / slip, -s.slip_z / slip)
            };
        // ... turned towards the stick impulse's as the budget nears s*, reaching it at
        // s* so that the step is continuous with the sticking one (as in `KimGrip`).
        let fraction = budget / stick;
        let blended = fraction > half;
        let weight = if blended {
            let w = R::of(2.0) * fraction - R::ONE;
            R::min(w * w, R::ONE)
        } else {
            R::ZERO
        };
        let (blend_y, blend_z) = (
            (R::ONE - weight) * mid_y + weight * stick_y / stick,
            (R::ONE - weight) * mid_z + weight * stick_z / stick,
        );
        let norm = R::sqrt(blend_y * blend_y + blend_z * blend_z);
        let (dir_y, dir_z) = if norm > R::ZERO {
            (blend_y / norm, blend_z / norm)
        } else {
            (mid_y, mid_z)
        };
        let next = self.step(s, dp, dir_y * budget, dir_z * budget);
        if next.slip_y * s.slip_y + next.slip_z * s.slip_z <= R::ZERO {
            // Overshoot: the budget was within a rounding of stopping the slip.
            return (self.step(s, dp, stick_y, stick_z), true, false);
        }
        (next, false, blended)
    }
}

/// Substeps a slip's turn from `start` to `end` asks for: `⌈angle / TURN_PER_SUBSTEP⌉`
/// (at most [`MAX_SUBSTEPS`]), the angle taken as its sine `|start × end| / (|start|
/// |end|)` (1.5 % short at 0.3 rad, where eight substeps are asked for anyway); the most
/// where the slip reverses (`start · end ≤ 0`); one where either end is zero. A turn
/// under one substep's (most steps) costs a few products and one comparison.
fn turn_substeps<R: Real>(start: (R, R), end: (R, R)) -> u32 {
    let norms = (start.0 * start.0 + start.1 * start.1) * (end.0 * end.0 + end.1 * end.1);
    if norms == R::ZERO {
        return 1;
    }
    if start.0 * end.0 + start.1 * end.1 <= R::ZERO {
        return MAX_SUBSTEPS;
    }
    let cross = start.0 * end.1 - start.1 * end.0;
    // The least k with sin² ≤ (k θ)², without a root or a division.
    let (cross_squared, step_squared) = (
        cross * cross,
        R::of(TURN_PER_SUBSTEP * TURN_PER_SUBSTEP) * norms,
    );
    let mut substeps = 1;
    while substeps < MAX_SUBSTEPS
        && cross_squared > R::of((substeps * substeps) as f32) * step_squared
    {
        substeps += 1;
    }
    substeps
}

/// A table contact's friction impulse over one step: at most `limit` (μ times the
/// step's normal impulse there), against the contact's slip, which the step's ball–ball
/// impulses move from `start` to `end`; `gain` the slip change per unit table impulse
/// (`1 + 1/ν`). Where `limit` can stop the slip it does, along `end`; otherwise it acts
/// against the slip at the step's middle, `(start + end)/2`. Directed along `end`
/// alone, the split of each step into the ball–ball impulse and then the table's made
/// the integration first order where a pressed ball's table contact slides and turns:
/// on the worst domain scene (seed 16, index 31132: μ 0.92, μ_ct 0.96, the cue ball
/// pressed) the error was 8.7e-3, 8.6e-4 and 7.4e-5 of U at 24, 240 and 2,400 steps.
/// No impulse where the end slip's length is zero, or rounds to it: at slips of 1e-20
/// the f32 squares underflow, and stopping a slip of unknown length there put `Exact`'s
/// normal impulse 18 % off the f64 one (seed_exact's `an_impact_whose_work_is_subnormal_
/// solves_in_f32`).
fn table_impulse<R: Real>(limit: R, start: (R, R), end: (R, R), gain: R) -> (R, R) {
    let end_length = R::sqrt(end.0 * end.0 + end.1 * end.1);
    if end_length == R::ZERO {
        return (R::ZERO, R::ZERO);
    }
    if limit * gain >= end_length {
        return (-end.0 / gain, -end.1 / gain);
    }
    let half = R::of(0.5);
    let (mid_x, mid_y) = (half * (start.0 + end.0), half * (start.1 + end.1));
    let mid_length = R::sqrt(mid_x * mid_x + mid_y * mid_y);
    let (along_x, along_y, length) = if mid_length > R::ZERO {
        (mid_x, mid_y, mid_length)
    } else {
        (end.0, end.1, end_length)
    };
    (-limit * along_x / length, -limit * along_y / length)
}

/// The state at the impact's end inside the substep of `dp` from `split`'s state, where
/// the work reaches `target`; `from` the fraction of the substep where compression ended
/// (0 if before it).
fn locate_end<R: Real>(
    model: &Model<R>,
    split: &Split<R>,
    (dp, from): (R, R),
    target: R,
    approach: R,
) -> (State<R>, bool) {
    let zero = R::ZERO;
    let (state, stuck, work) = (&split.state, split.stuck, split.work);
    let full = {
        let (next, next_stuck, _) = model.advance(state, dp, stuck);
        (next, next_stuck)
    };
    let (v0, v1) = (state.normal_velocity, full.0.normal_velocity);
    // W(λ) = work + v0 λ dp + (v1 − v0) λ² dp / 2 = target, λ ∈ [from, 1].
    let slope = v1 - v0;
    let gap = (target - work) / dp;
    let fraction = if slope > zero {
        let root = R::sqrt(R::max(v0 * v0 + R::of(2.0) * slope * gap, zero));
        R::min(R::max((-v0 + root) / slope, from), R::ONE)
    } else if v0 > zero {
        R::min(gap / v0, R::ONE)
    } else {
        R::ONE
    };
    // The normal velocity is linear in λ only while the contact's regime and the tables'
    // friction stay the same inside the substep; refine λ on the actual partial substeps
    // (secant, bracketed in [from, 1]) so that the end of the impact does not jump when a
    // regime change moves inside it.
    let work_at = |lambda: R| -> (R, (State<R>, bool)) {
        let (partial, partial_stuck, _) = model.advance(state, lambda * dp, stuck);
        let w = work + R::of(0.5) * (v0 + partial.normal_velocity) * lambda * dp;
        (w - target, (partial, partial_stuck))
    };
    let (mut lo, mut hi) = (from, R::ONE);
    let (mut lambda, mut result) = (fraction, work_at(fraction));
    for _ in 0..FINAL_STEP_REFINEMENTS {
        let residual = result.0;
        if residual == zero {
            break;
        }
        if residual > zero {
            hi = lambda;
        } else {
            lo = lambda;
        }
        // Local slope dW/dλ ≈ v(λ) dp, the normal velocity at the end.
        let rate = result.1 .0.normal_velocity * dp;
        let mut next_lambda = if rate > zero {
            lambda - residual / rate
        } else {
            hi
        };
        if !(next_lambda >= lo && next_lambda <= hi) {
            next_lambda = R::of(0.5) * (lo + hi);
        }
        if next_lambda == lambda {
            break;
        }
        let candidate = work_at(next_lambda);
        if R::abs(candidate.0) > R::abs(residual) {
            break; // no better: keep what we have
        }
        lambda = next_lambda;
        result = candidate;
    }
    // The balls may not end the impact approaching: with e* near 0 the work balance is
    // met within a rounding of the compression's end, where the substep's actual map
    // (table friction, a stick inside it) can leave v_n a little below zero. Then the end
    // is where v_n reaches zero (bisection on the partial substeps; v_n ≥ 0 at λ = 1).
    // Rounding-size approaches (64 f32 units of the approach speed) are left: bisecting
    // them cost every such scene 16 partial steps for nothing.
    let approaching = -R::of(APPROACH_TOLERANCE) * approach;
    if result.1 .0.normal_velocity < approaching {
        let (mut lo, mut hi) = (lambda, R::ONE);
        let mut separated = (zero, full);
        for _ in 0..SEPARATION_BISECTIONS {
            let mid = R::of(0.5) * (lo + hi);
            let candidate = work_at(mid);
            if candidate.1 .0.normal_velocity >= zero {
                hi = mid;
                separated = candidate;
            } else {
                lo = mid;
            }
        }
        if separated.1 .0.normal_velocity >= zero {
            result = separated;
        }
    }
    result.1
}

// Not inlined into `model::collide_in` (see `kim_grip::collide`).
#[inline(never)]
pub(crate) fn collide<R: Real>(params: &Params, impact: &Impact) -> Result<Outcome> {
    let law = params.friction_law();
    let restitution = R::of(params.restitution());
    let approach = R::of(impact.velocity().x);
    let (slip_y, slip_z) = initial_slip::<R>(params, impact);
    let model = Model {
        law,
        restitution,
        mu_s: R::of(params.mu_s()),
        mu_ct: R::of(params.cue_table_friction()),
        inv_nu: R::of(2.5),
    };
    let (u, w, radius) = (impact.velocity(), impact.spin(), R::of(params.radius()));
    let zero = R::ZERO;
    let state = State {
        slip_y,
        slip_z,
        normal_velocity: -approach,
        table_slip_x: zero,
        table_slip_y: zero,
        object_vz: zero,
        cue_vz: zero,
        normal: zero,
        friction_y: zero,
        friction_z: zero,
        table_x: zero,
        table_y: zero,
        cue_slip_x: R::of(u.x) - radius * R::of(w.y),
        cue_slip_y: R::of(u.y) + radius * R::of(w.x),
        cue_table_x: zero,
        cue_table_y: zero,
    };
    let frictionless = law.is_frictionless();
    let stuck = frictionless || (slip_y == zero && slip_z == zero);
    let mut ever_stuck = stuck && !frictionless;
    let dp = R::of(0.5) * (R::ONE + restitution) * approach / R::of(STEPS as f32);
    let mut current = Split {
        state,
        stuck,
        work: zero,
        target: None,
        blended: false,
        end: None,
    };
    // Substeps of the coming step, from the turn of the last (module docs). A step is
    // taken again with more where its slip stuck or was blended towards the stick
    // impulse (up to MAX_SUBSTEPS), or where its turn asks for more than twice its
    // substeps; a smaller shortfall is left (it costs less than a retry for its error).
    let mut substeps = 1;
    // At most 4 × STEPS steps: v_n grows by at least (2 − μ_s) dp per step.
    for _ in 0..4 * STEPS {
        let start = current;
        model.advance_split(&mut current, dp, substeps);
        let needed = Model::substeps_needed(&start.state, start.stuck, &current, dp);
        let event = current.blended || current.stuck != start.stuck;
        if needed > substeps && (event || needed > 2 * substeps) {
            substeps = needed;
            current = start;
            model.advance_split(&mut current, dp, substeps);
        }
        ever_stuck = ever_stuck || current.stuck;
        if let (Some(end), Some(target)) = (current.end, current.target) {
            let (last, last_stuck) = locate_end(&model, &current, end, target, approach);
            current.state = last;
            ever_stuck = ever_stuck || last_stuck;
            break;
        }
        substeps = if current.stuck { 1 } else { needed };
        current.blended = false;
    }
    let state = current.state;
    let regime = if frictionless {
        Regime::Frictionless
    } else if ever_stuck {
        Regime::Gripping
    } else {
        Regime::Sliding
    };
    let impulses = SpecificImpulses {
        normal: state.normal,
        friction_y: state.friction_y,
        friction_z: state.friction_z,
        table: -state.table_x,
        table_y: state.table_y,
        table_size: R::sqrt(state.table_x * state.table_x + state.table_y * state.table_y),
        cue_table_x: state.cue_table_x,
        cue_table_y: state.cue_table_y,
    };
    Outcome::from_impulses(params, impact, impulses, regime)
}
