//! The follow-through (`docs/sensors.md` §11, "Follow-through"): how far the cue travels
//! forward from the tip contact until it stops (m), and how long it takes to get slower
//! than 0.02 m/s (s). Measured only with [`super::StreamConfig::follow_through`].
//!
//! The contact spike is clipped at full scale, so the velocity after the contact cannot
//! be integrated forward from the stroke's speed. It is integrated *backwards* from the
//! stop instead, where the cue is known to be still (`v = 0`). With `a_i` the
//! acceleration counts, `L` the level (the stroke's bias less its gyro tilt correction at
//! the onset), `c` the first sample after the contact window and `e` the last sample
//! summed (the cue still there), the velocity at the start of sample `j` is
//!
//! ```text
//! v_j = −Σ_{i=j}^{e} (a_i − L)                         counts·samples (× scale·Δt = m/s)
//! ```
//!
//! and the distance over `[c, e]`, each sample's velocity taken at its end (then the
//! trapezoid's half sample, below), is
//!
//! ```text
//! Σ_{j=c}^{e} v_{j+1} = −Σ_{j=c}^{e} Σ_{i=j+1}^{e} (a_i − L) = −Σ_{i=c}^{e} (i − c)(a_i − L)
//! ```
//!
//! (swap the sums: sample `i` is counted for each `j` in `[c, i)`). Both come from two
//! exact integer sums kept per sample, `S0 = Σ a_i` and `S1 = Σ (i − c) a_i`, the level
//! removed at the end: `Σ (a_i − L) = S0 − L·m`, `Σ (i − c)(a_i − L) = S1 − L·m(m−1)/2`
//! over `m = e + 1 − c` samples. A velocity linear within each sample adds
//! `(v_c − v_{e+1})/2 = v_c/2` (trapezoid rule), and the contact window `[onset, c)` is
//! taken at the velocity `v_c` its end has, from the contact's mean instant, half a
//! sample into the onset sample: `v_c·(skip − ½)`. In all,
//!
//! ```text
//! length = (v_c · skip − Σ_{i=c}^{e} (i − c)(a_i − L)) · scale · Δt²
//! ```
//!
//! The pitch changes during a follow-through: the level is taken as `L + λ (i − c)`,
//! `λ` from the gyro's elevation change between the onset and `e` (linear in time),
//! which removes `λ Σ (i − c) = λ m(m−1)/2` from the velocity sum and
//! `λ Σ (i − c)² = λ m(m−1)(2m−1)/6` from the moment.
//!
//! The stop: a run of two still rest blocks (`rest.rs`) whose first block starts after
//! `c`, at the level of a still cue (the bias less the gyro tilt correction there), the
//! velocity integrated back leaving the cue at least [`MIN_KEPT`] of its speed; `e` is
//! the end of its second block, and the report is on the next sample. The time ends
//! where `v` falls below `slow` (0.02 m/s, the pause's threshold: a cue creeping to a
//! stop has no sharper end): `v = u_b − u_e` at each block boundary `b`, `u_b =
//! Σ_{[c, b)} (a − L)` being kept for the last [`MARKS`] boundaries, interpolated
//! linearly in `√v` between the two boundaries around it (a smooth stop has `v ∝ (t_stop
//! − t)²`).
//!
//! Given up, with no report (tested at block ends): no stop within [`BOUND`] of the
//! onset, a full-scale sample after the contact window, a crossing of the impact
//! threshold after it (a double hit, a knock; `expire` in `rest.rs`), a rest end (a new
//! stroke starts), a non-finite sample, [`super::StreamingEstimator::finish`].
//!
//! Per sample, while measuring: one `i32` add and one 32×32→64 multiply-accumulate; one
//! unsigned comparison otherwise (after the impact test: an impact's sample skips it).
//! Per block end: one mark, and a division at a candidate stop. At the report: one loop
//! of at most [`MARKS`] steps and one division.

use super::{at_or_after, StreamEvent, StreamingEstimator};

/// Left out after the impact onset (s): the contact (about 1 ms) and the ringing it
/// excites, clipped at full scale (the test model's 20–60 g, decaying with 3 ms, is
/// below 7 g 8 ms after the onset).
pub(super) const SKIP: f32 = 0.008;

/// The cue must be still again within this time of the onset (s).
pub(super) const BOUND: f32 = 1.5;

/// The least part of its speed a cue keeps through the contact. A head-on hit leaves a
/// cue of mass `M` with `(M − e m)/(M + m)` of its speed (TP A.30's ball speed
/// `(1 + e) v / (1 + m/M + 2.5 b²)` at `b = 0`, and momentum), ball `m` = 0.17 kg, tip
/// restitution `e` ≤ 0.8: 0.54 for a 0.5 kg cue, 0.24 for a 0.23 kg jump cue; an
/// off-centre hit leaves more. A stop that would leave the cue less (the velocity
/// integrated back from it, at the contact window's end) is a cue moving on at a steady
/// speed, which no accelerometer tells from rest: the measurement goes on.
const MIN_KEPT: f32 = 0.2;

/// Block boundaries kept for the time's end (25 ms each: 200 ms before the stop is found).
const MARKS: usize = 8;

/// The follow-through being measured (counts and sample indices).
#[derive(Clone, Copy, Debug)]
pub(super) struct Follow {
    /// First sample of the sums, `c`: the onset plus the contact window.
    pub from: u32,
    /// Samples from `from` on that the sums take: `plan.follow_span` while measuring, 0
    /// otherwise. One unsigned comparison, `n − from < span`, tests that a measurement
    /// runs, that `n` is past the contact window (before it the difference wraps past
    /// 2³¹) and within the bound.
    pub span: u32,
    /// `S0 = Σ a_i`, `S1 = Σ (i − from) a_i` over `[from, n]` (exact).
    s0: i32,
    s1: i64,
    /// The stroke's impact onset.
    onset: u32,
    /// The level `L` (counts).
    level: f32,
    /// The elevation change from the rest to the onset (counts·samples, `integral.rs`)
    /// and the pitch-rate prefix sum before the onset: the elevation change at a later
    /// sample, for the still level there.
    tilt: f32,
    pitch_prefix: i32,
    /// [`MIN_KEPT`] of the stroke's speed (velocity counts).
    kept: f32,
    /// The level's change per sample over the sums (counts), from the gyro's elevation
    /// change between the onset and the last block end, taken as linear in time.
    drift: f32,
    /// `u_b = Σ_{[from, b)} (a − L)` at the last [`MARKS`] block boundaries `b`;
    /// `taken` counts the boundaries since `from`.
    marks: [f32; MARKS],
    taken: u32,
    /// The stop was found at the block end `count` samples from `from`: the report is
    /// on the next sample (`from` and `span` then select just that one), so that the
    /// block end and the report, the two costliest steps here, share no sample.
    pub ready: bool,
    count: u32,
}

impl Follow {
    /// Nothing measured.
    pub const fn new() -> Self {
        Self {
            from: 0,
            span: 0,
            s0: 0,
            s1: 0,
            onset: 0,
            level: 0.0,
            tilt: 0.0,
            pitch_prefix: 0,
            kept: 0.0,
            drift: 0.0,
            marks: [0.0; MARKS],
            taken: 0,
            ready: false,
            count: 0,
        }
    }

    /// Sample `from + k` of `a` counts (`k < span`, at most 15,000: 1.5 s at 10 kHz).
    #[inline(always)]
    pub fn add(&mut self, k: u32, a: i32) {
        self.s0 = self.s0.wrapping_add(a);
        self.s1 = self.s1.wrapping_add(i64::from(k as i32) * i64::from(a));
    }

    /// `L` as its nearest integer and the difference (the sums less the integer part
    /// stay exact). Out of line (once a block or a report, not per sample): its two
    /// inlined copies were larger than their calls.
    #[inline(never)]
    fn level_parts(&self) -> (i32, f32) {
        let level = self.level;
        let round = if level >= 0.0 {
            level + 0.5
        } else {
            level - 0.5
        } as i32;
        (round, level - round as f32)
    }

    /// `Σ (a − L)` over the first `count` samples, `S0` holding exactly those.
    fn change(&self, count: u32) -> f32 {
        let (round, fraction) = self.level_parts();
        let whole = self.s0.wrapping_sub(round.wrapping_mul(count as i32));
        whole as f32 - fraction * count as f32
    }

    /// Samples from `from` to where `v = u − u_e` falls below `slow` (`change` = `u_e`):
    /// linear between the newest kept boundary (or `from`) with `v ≥ slow` and the next
    /// one; the oldest kept boundary if none is (at most 200 ms late then).
    fn stop(&self, change: f32, slow: f32, block: u32) -> f32 {
        let kept = self.taken.min(MARKS as u32);
        // The newest boundary is the sample after `e`: `v = 0` there.
        let mut newer = (self.count as f32, 0.0);
        let mut j = 1;
        loop {
            let older = if j < kept {
                let u = self.marks[self.taken.wrapping_sub(1 + j) as usize % MARKS];
                let at = newer.0 - block as f32;
                // The drift's part of `u` at `at` samples from `from`.
                (at, u - self.drift * at * (at - 1.0) * 0.5 - change)
            } else if self.taken <= MARKS as u32 {
                (0.0, -change)
            } else {
                return newer.0;
            };
            if older.1 >= slow {
                // Interpolated in √v: a smooth stop (the deceleration easing to zero
                // with it, as a minimum-jerk move ends) has v ∝ (t_stop − t)², so √v is
                // linear near it, where v itself bends and a straight line between
                // boundaries 25 ms apart crosses `slow` late. `older.1 ≥ slow > newer.1`,
                // so the denominator is positive; a noisy `newer.1` below 0 counts as 0.
                let root = cuesight::math::sqrt;
                let (from, to) = (root(older.1), root(cuesight::math::max(newer.1, 0.0)));
                return older.0 + (newer.0 - older.0) * (from - root(slow)) / (from - to);
            }
            if j >= kept {
                return 0.0;
            }
            newer = older;
            j += 1;
        }
    }
}

impl StreamingEstimator {
    /// A stroke was reported with its onset at `onset`, the elevation having changed by
    /// `tilt` counts·samples since the rest, at `speed` m/s: measure its follow-through.
    /// Its level is the bias less the tilt correction at the onset (as the phases' level,
    /// `integral.rs`).
    /// (Out of line: the impact's sample is the costliest.)
    #[inline(never)]
    pub(super) fn start_follow(&mut self, onset: u32, tilt: f32, speed: f32) {
        let level = self.stroke.bias - self.tilt_gain * tilt;
        // `plan.slow` is `REST_SPEED` in velocity counts.
        let kept = speed * self.plan.slow * (MIN_KEPT / super::integral::REST_SPEED);
        let pitch_prefix = self.ring[onset as usize & super::MASK][1];
        let f = &mut self.follow;
        f.tilt = tilt;
        f.pitch_prefix = pitch_prefix;
        f.kept = kept;
        f.from = onset.wrapping_add(self.plan.follow_skip);
        f.span = self.plan.follow_span;
        f.s0 = 0;
        f.s1 = 0;
        f.onset = onset;
        f.level = level;
        f.taken = 0;
        f.ready = false;
    }

    /// Block end at sample `n` while measuring: a mark, and the report set up for the
    /// next sample if the cue is still: a run of two still, level blocks starting after
    /// the contact window, at the level
    /// of a still cue (the bias less the tilt correction at `n`, within the rest level
    /// tolerance: a run of blocks at a steady deceleration is not a stop), the velocity
    /// integrated back from it leaving the cue at least [`MIN_KEPT`] of its speed after
    /// the contact.
    #[inline(never)]
    pub(super) fn follow_block(&mut self, n: u32) {
        let next = n.wrapping_add(1);
        let s = &self.stroke;
        let f = &mut self.follow;
        let count = next.wrapping_sub(f.from);
        if count as i32 <= 0 {
            return; // still in the contact window
        }
        // Given up: no stop within the bound, a rest has ended since (a new stroke), a
        // full-scale sample after the contact window (`last_saturated` is kept longer
        // than a block). A new impact is handled by `expire` (`rest.rs`).
        if count > f.span || s.active || self.last_saturated.is_some_and(|i| at_or_after(i, f.from))
        {
            f.span = 0;
            return;
        }
        let change = f.change(count);
        f.marks[f.taken as usize % MARKS] = change;
        f.taken = f.taken.wrapping_add(1);
        if !(self.run.armed && at_or_after(self.run.first_block(), f.from) && -change >= f.kept) {
            return;
        }
        let tilt = f.tilt + self.c.wrapping_sub(f.pitch_prefix) as f32
            - s.gyro_bias * next.wrapping_sub(f.onset) as f32;
        let still = s.bias - self.tilt_gain * tilt;
        if cuesight::math::abs(self.run.first_level() - still) <= self.plan.level_tolerance {
            f.drift = -self.tilt_gain * (tilt - f.tilt) / count as f32;
            f.count = count;
            f.ready = true;
            f.from = next;
            f.span = 1;
        }
    }

    /// Sample `n`, `a` counts, into the follow-through's sums while one is measured;
    /// `true` on the sample its report is due (the sample after the block end where the
    /// stop was found).
    #[inline(always)]
    pub(super) fn follow_due(&mut self, n: u32, a: i32) -> bool {
        let k = n.wrapping_sub(self.follow.from);
        if k < self.follow.span {
            if self.follow.ready {
                return true;
            }
            self.follow.add(k, a);
        }
        false
    }

    /// The end of a step on the sample after the block end where the stop was found:
    /// the report (module docs), built in the caller's return slot.
    #[inline(never)]
    pub(super) fn report_follow(&mut self) -> Option<StreamEvent> {
        if self.plan.defer {
            self.deferred = super::Deferred::Follow;
            return None;
        }
        self.follow_report()
    }

    /// [`Self::report_follow`]'s report, now or deferred ([`Self::resolve`]).
    #[inline(never)]
    pub(super) fn follow_report(&mut self) -> Option<StreamEvent> {
        let plan = &self.plan;
        let f = &mut self.follow;
        f.span = 0;
        f.ready = false;
        let count = f.count;
        // Σ (i − from)(a_i − L) = S1 − L·m(m−1)/2 (the bound keeps m ≤ 15,000 at 10 kHz:
        // m(m − 1) fits a u32).
        let pairs = count.wrapping_mul(count.wrapping_sub(1)) / 2;
        let (round, fraction) = f.level_parts();
        let moment =
            f.s1.wrapping_sub(i64::from(round) * i64::from(pairs)) as f32 - fraction * pairs as f32;
        // With the level `L + drift·(i − from)`: less `drift Σ (i − from)` and
        // `drift Σ (i − from)² = drift · m(m−1)/2 · (2m−1)/3`.
        let pairs = pairs as f32;
        let change = f.change(count) - f.drift * pairs;
        let moment = moment - f.drift * pairs * (2.0 * count as f32 - 1.0) * (1.0 / 3.0);
        let skip = plan.follow_skip as f32;
        let travel = -change * skip - moment;
        let stop = f.stop(change, plan.slow, plan.block);
        let onset = f.onset;
        Some(StreamEvent::FollowThrough {
            impact: self.unwrap_index(onset),
            length: travel * plan.scale * plan.dt * plan.dt,
            time: (stop + skip - 0.5) * plan.dt,
        })
    }
}
