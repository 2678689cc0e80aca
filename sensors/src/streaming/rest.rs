//! Rest detection: 25 ms block statistics, runs of still and level blocks, and the
//! per-sample motion test that ends a rest (steps 1–3 of the module docs).

use super::{at_or_after, StreamingEstimator};

/// The block being filled (counts).
#[derive(Clone, Copy, Debug)]
pub(super) struct Block {
    /// Index of its first sample, and the acceleration prefix sum there.
    pub start: u32,
    p_start: i32,
    c_start: i32,
    /// Smallest and largest sum of `W` consecutive samples lying inside the block.
    window_min: i32,
    window_max: i32,
    /// Its first sample: the variance is accumulated about it (shifted data), so the
    /// f32 sum of squares stays small for a still block.
    first: f32,
    /// Samples so far.
    pub pos: u32,
    /// `Σ (a − first)²`.
    ss: f32,
    /// Holds a knock, a full-scale or non-finite sample, or a motion departure: not a
    /// rest block.
    pub bad: bool,
    /// Prefix sums `guard` samples before the end of this block and of the previous one
    /// (the rest end when a run fails its block tests without a departure).
    guard_mark: [i32; 2],
    prev_guard_mark: [i32; 2],
}

impl Block {
    pub const fn new() -> Self {
        Self {
            start: 0,
            p_start: 0,
            c_start: 0,
            window_min: i32::MAX,
            window_max: i32::MIN,
            first: 0.0,
            pos: 0,
            ss: 0.0,
            bad: false,
            guard_mark: [0; 2],
            prev_guard_mark: [0; 2],
        }
    }
}

/// The current run of still, level blocks (counts).
#[derive(Clone, Copy, Debug)]
pub(super) struct Run {
    /// Complete blocks in the run, the first included.
    pub blocks: u32,
    /// Mean of the first block: every later block's mean must lie within
    /// `rest_level_tolerance` of it.
    level0: f32,
    /// Start of the rest window (the end of the run's first block, or a later bucket
    /// boundary) and the prefix sums there.
    pub rest_start: u32,
    pub p_rest: i32,
    pub c_rest: i32,
    /// The run's first block `(start, P, C, window min, window max)`: it joins the rest
    /// window at the rest end if none of its `W`-sums departs from the final level.
    lead: (u32, i32, i32, i32, i32),
    /// Blocks in the rest window, and the bucket boundary that becomes its start when
    /// it reaches two buckets (so that it spans 1–2 s and its sums cannot wrap).
    interior: u32,
    mid: (u32, i32, i32),
    /// The window's start has moved to a bucket boundary.
    shifted: bool,
    /// Mean variance of the rest window's blocks (counts²).
    pub variance: f32,
    /// The motion test runs (the run has a level: two blocks or more).
    pub armed: bool,
    /// `W ·` the rest window's mean, and the squared motion threshold
    /// `max(36 W σ², (W · motion_floor)²)` (counts).
    w_level: f32,
    threshold_sq: f32,
}

impl Run {
    pub const fn new() -> Self {
        Self {
            blocks: 0,
            level0: 0.0,
            rest_start: 0,
            p_rest: 0,
            c_rest: 0,
            lead: (0, 0, 0, 0, 0),
            interior: 0,
            mid: (0, 0, 0),
            shifted: false,
            variance: 0.0,
            armed: false,
            w_level: 0.0,
            threshold_sq: 0.0,
        }
    }

    /// Drop the run (a departure, a fault). Only `blocks` and `armed` change: a rest
    /// end found as the run ends still reads its window from it.
    pub fn abandon(&mut self) {
        self.blocks = 0;
        self.armed = false;
    }
}

impl StreamingEstimator {
    /// Block statistics of one sample (counts); the prefix sums are already updated and
    /// `w_sum` is the sum of the last `W` samples.
    #[inline(always)]
    pub(super) fn block_sample(&mut self, a: i32, w_sum: i32) {
        let b = &mut self.block;
        let a = a as f32;
        if b.pos == 0 {
            b.first = a;
        }
        let d = a - b.first;
        b.ss += d * d;
        b.pos += 1;
        if b.pos >= self.plan.window {
            b.window_min = b.window_min.min(w_sum);
            b.window_max = b.window_max.max(w_sum);
        }
        if b.pos == self.plan.guard_pos {
            b.guard_mark = [self.p, self.c];
        }
    }

    /// Step 2: the moving average of the last `W` samples, `(P(n+1) − P(n+1−W)) / W`,
    /// against the rest level, as `|Σ − W·level|² > max(36 W σ², (W·floor)²)` (the
    /// windowed estimator's `|mean − level| > max(6σ/√W, floor)`, squared, times W).
    #[inline(always)]
    pub(super) fn moved(&self, w_sum: i32) -> bool {
        let deviation = w_sum as f32 - self.run.w_level;
        deviation * deviation > self.run.threshold_sq
    }

    /// The motion test fired at sample `n`: the rest ends at `n + 1 − W − guard`.
    #[inline(never)]
    pub(super) fn depart(&mut self, n: u32) {
        let (blocks, rest_start) = (self.run.blocks, self.run.rest_start);
        self.run.abandon();
        // The block holding the departure is not a rest block: a new run starts after it.
        self.block.bad = true;
        // (Before the stream's first `delay` samples this wraps; no run is long enough
        // to qualify then: three blocks are 75 ms, the delay 12.4 ms.)
        let rest_end = n.wrapping_add(1).wrapping_sub(self.plan.delay);
        let [p, c] = self.ring[rest_end as usize & super::MASK];
        self.rest_ended(n, blocks, rest_start, rest_end, p, c);
    }

    /// A run ended at `rest_end`: the speed's new origin if it [`Self::qualifies`];
    /// otherwise, if it is a rest within a stroke (an address after a settling move,
    /// shorter than the rest before it), a new start for the stroke's phases only.
    fn rest_ended(&mut self, n: u32, blocks: u32, rest_start: u32, rest_end: u32, p: i32, c: i32) {
        if self.qualifies(blocks, rest_start, rest_end, p) {
            self.anchor(n, rest_end, p, c, blocks);
        } else if self.stroke.active && self.long_enough(blocks, rest_start, rest_end) {
            self.start_phases(n, rest_end, p, true);
        }
    }

    /// `min_rest` of blocks and half a block of rest window.
    fn long_enough(&self, blocks: u32, rest_start: u32, rest_end: u32) -> bool {
        blocks >= self.plan.rest_blocks
            && rest_end.wrapping_sub(rest_start) as i32 >= (self.plan.block / 2) as i32
    }

    /// Step 3: a run of `blocks` whose rest window starts at `rest_start`, ending at
    /// `rest_end` (acceleration prefix sum `p` there), is a rest (`min_rest` of blocks,
    /// half a block of rest window) that replaces the integration's current origin:
    /// none, a shorter one, or one it is `trusted_rest` long and the cue's speed at its
    /// end, integrated from that origin, is below [`super::integral::REST_SPEED`] (a
    /// smooth move's acceleration plateau is not).
    fn qualifies(&self, blocks: u32, rest_start: u32, rest_end: u32, p: i32) -> bool {
        let plan = &self.plan;
        self.long_enough(blocks, rest_start, rest_end)
            && (!self.stroke.active
                || blocks >= self.stroke.rest_blocks
                || (blocks >= plan.trusted_blocks && self.at_rest(rest_end, p)))
    }

    /// Block end at sample `n` (its last): fold the stroke sums, test the block, extend
    /// or end the run, mark the follow-through.
    #[inline(never)]
    pub(super) fn end_block(&mut self, n: u32) {
        self.fold(n);
        self.expire(n);
        let plan = &self.plan;
        let b = &self.block;
        let mean = self.p.wrapping_sub(b.p_start) as f32 * plan.inv_block;
        let shift = mean - b.first;
        let variance = cuesight::math::max(b.ss * plan.inv_block - shift * shift, 0.0);
        let still = !b.bad && variance <= plan.noise_limit_sq;
        let run = &mut self.run;
        let level_ok =
            run.blocks == 0 || cuesight::math::abs(mean - run.level0) <= plan.level_tolerance;
        let boundary = (n.wrapping_add(1), self.p, self.c);
        let lead = (b.start, b.p_start, b.c_start, b.window_min, b.window_max);
        if still && level_ok {
            if run.blocks == 0 {
                run.start(mean, boundary, lead);
            } else {
                run.extend(variance, boundary, plan);
            }
            run.blocks += 1;
        } else {
            // The run ends without a motion departure: as the windowed estimator, the
            // motion starts at the end of its last block and the rest `guard` before.
            let (armed, blocks, rest_start) = (run.armed, run.blocks, run.rest_start);
            run.abandon();
            // (A qualifying run has three blocks or more, so this does not wrap.)
            let rest_end = b.start.wrapping_sub(plan.guard);
            let [p, c] = b.prev_guard_mark;
            if armed {
                self.rest_ended(n, blocks, rest_start, rest_end, p, c);
            }
            if still {
                // Still, but off the run's level: a new run starts with this block.
                self.run.start(mean, boundary, lead);
                self.run.blocks = 1;
            }
        }
        if self.gravity.is_none() {
            let (sin, cos) = cuesight::math::sin_cos(self.plan.elevation);
            let g_cos = crate::lsm6dsox::STANDARD_GRAVITY * cos;
            self.gravity = Some((g_cos, crate::lsm6dsox::STANDARD_GRAVITY * sin));
            self.tilt_gain = g_cos * self.plan.pitch_scale * self.plan.dt / self.plan.scale;
        }
        self.block_base += u64::from(self.plan.block);
        let b = &mut self.block;
        b.prev_guard_mark = b.guard_mark;
        b.start = n.wrapping_add(1);
        b.p_start = self.p;
        b.c_start = self.c;
        b.window_min = i32::MAX;
        b.window_max = i32::MIN;
        b.pos = 0;
        b.ss = 0.0;
        b.bad = false;
        // (`first` is set by the block's first sample, `guard_mark` by its sample at
        // `guard_pos`, before either is read.)
        #[cfg(feature = "follow-through")]
        if self.follow.span != 0 {
            self.follow_block(n);
        }
    }

    /// Drop the markers that can no longer matter at block end `n`, before a `u32`
    /// index could wrap around to them: a crossing more than `gap` old (the next one is
    /// a new impact either way), an impact past its double-hit window, a saturated
    /// sample older than any rest end still to come (`block + guard` before a block
    /// end, `delay` before a departure).
    fn expire(&mut self, n: u32) {
        let plan = &self.plan;
        if let Some(last) = self.last_crossing {
            // A crossing after a follow-through's contact window is a new impact (a
            // double hit, a knock): that measurement is given up (`follow.rs`).
            #[cfg(feature = "follow-through")]
            if at_or_after(last, self.follow.from) {
                self.follow.span = 0;
            }
            if n.wrapping_sub(last) > plan.gap {
                self.last_crossing = None;
            }
        }
        if self
            .last_impact
            .is_some_and(|(_, until)| !at_or_after(until, n))
        {
            self.last_impact = None;
        }
        if self
            .last_saturated
            .is_some_and(|s| n.wrapping_sub(s) > plan.block + plan.delay)
        {
            self.last_saturated = None;
        }
    }
}

impl Run {
    /// The first sample of the run's first block.
    #[cfg(feature = "follow-through")]
    pub fn first_block(&self) -> u32 {
        self.lead.0
    }

    /// The mean of the run's first block (counts).
    #[cfg(feature = "follow-through")]
    pub fn first_level(&self) -> f32 {
        self.level0
    }

    /// The rest window's start and its prefix sums: the run's first block joins it when
    /// the window has not moved on (runs under two buckets) and every `W`-sum inside
    /// that block lies within the motion threshold of the final level — the windowed
    /// estimator's backward search from the interior, at block resolution.
    pub fn window_start(&self) -> (u32, i32, i32) {
        let (start, p, c, low, high) = self.lead;
        let clean = |sum: i32| {
            let d = sum as f32 - self.w_level;
            d * d <= self.threshold_sq
        };
        if !self.shifted && clean(low) && clean(high) {
            (start, p, c)
        } else {
            (self.rest_start, self.p_rest, self.c_rest)
        }
    }

    /// First block of a run, ending at `boundary` (index, prefix sums).
    fn start(&mut self, mean: f32, boundary: (u32, i32, i32), lead: (u32, i32, i32, i32, i32)) {
        self.level0 = mean;
        self.lead = lead;
        (self.rest_start, self.p_rest, self.c_rest) = boundary;
        self.interior = 0;
        self.shifted = false;
        self.variance = 0.0;
        self.armed = false;
    }

    /// A further still, level block ending at `boundary`: update the rest window (mean
    /// variance, buckets), its level and the motion threshold; arm the motion test.
    fn extend(&mut self, variance: f32, boundary: (u32, i32, i32), plan: &super::Plan) {
        self.interior += 1;
        let weight = self.interior.min(plan.bucket) as f32;
        self.variance += (variance - self.variance) / weight;
        if self.interior == plan.bucket {
            self.mid = boundary;
        } else if self.interior == 2 * plan.bucket {
            (self.rest_start, self.p_rest, self.c_rest) = self.mid;
            self.interior = plan.bucket;
            self.mid = boundary;
            self.shifted = true;
        }
        let (end, p_end, _) = boundary;
        let level =
            p_end.wrapping_sub(self.p_rest) as f32 / end.wrapping_sub(self.rest_start) as f32;
        let w = plan.window as f32;
        self.w_level = w * level;
        self.threshold_sq = cuesight::math::max(36.0 * w * self.variance, plan.floor_sq);
        self.armed = true;
    }
}
