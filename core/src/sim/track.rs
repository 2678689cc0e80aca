//! One ball's motion between two events: a [`Motion`] (TP A.4: flight, sliding,
//! rolling, rest) started at a time of the simulation, plus the decay of the spin about
//! the vertical, which `Motion` leaves out and a cushion's rebound needs (side spin).
//!
//! Spinning friction: the cloth's contact patch resists rotation about `z` with a
//! constant torque, so `ω_z` falls linearly at `5 μ_sp g / (2R)` (rad/s²) until it stops
//! (pooltool 0.6, `pooltool/physics/evolve`, after Leckie & Greenspan; `μ_sp` in the
//! same units as there).

use crate::travel::{Bounds, Motion};
use crate::vector::Vec3;

/// A stretch of the path on which the centre is `p + q τ + s τ²`, `τ = t − from`, for
/// simulation times `t` in `[from, to]` (`to` infinite for the rest at the end).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    pub from: f32,
    pub to: f32,
    pub p: Vec3,
    pub q: Vec3,
    pub s: Vec3,
}

impl Piece {
    /// The same stretch as a polynomial in `σ = t − at`: `(position, velocity, s)` at
    /// `at`.
    pub fn at(&self, at: f32) -> (Vec3, Vec3, Vec3) {
        let tau = at - self.from;
        (
            self.p + self.q * tau + self.s * (tau * tau),
            self.q + self.s * (2.0 * tau),
            self.s,
        )
    }
}

/// A ball's path from its last event on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Track {
    /// Path from `since` on (times relative to `since`).
    pub motion: Motion,
    /// Simulation time at which `motion` starts (s).
    pub since: f32,
    /// `ω_z` at `since` (rad/s).
    spin_z: f32,
    /// Rate at which `|ω_z|` falls (rad/s²).
    spin_decay: f32,
    /// The path's pieces ([`Track::pieces`]), computed once: every event time that
    /// involves the ball reads them.
    pieces: [Piece; 4],
    piece_count: usize,
    /// A box around the whole path (m; [`Motion::bounds`]).
    pub bounds: Bounds,
}

impl Track {
    /// `motion` from simulation time `since`, its spin about `z` falling at `spin_decay`
    /// (rad/s²).
    pub fn new(motion: Motion, since: f32, spin_decay: f32) -> Self {
        let (pieces, piece_count) = pieces_of(&motion, since);
        Self {
            spin_z: motion.initial_spin.z,
            bounds: motion.bounds(),
            motion,
            since,
            spin_decay,
            pieces,
            piece_count,
        }
    }

    /// Simulation time at which the ball stops translating.
    pub fn stop(&self) -> f32 {
        self.since + self.motion.stop_time()
    }

    /// Centre at simulation time `t` (m).
    pub fn position_at(&self, t: f32) -> Vec3 {
        self.motion.position_at(t - self.since)
    }

    /// Horizontal velocity at simulation time `t` (m/s).
    pub fn velocity_at(&self, t: f32) -> Vec3 {
        self.motion.velocity_at(t - self.since)
    }

    /// Spin at simulation time `t` (rad/s): `Motion`'s, with `ω_z` decayed.
    pub fn spin_at(&self, t: f32) -> Vec3 {
        let elapsed = t - self.since;
        let spin = self.motion.spin_at(elapsed);
        let fall = self.spin_decay * if elapsed > 0.0 { elapsed } else { 0.0 };
        let z = if self.spin_z > fall {
            self.spin_z - fall
        } else if self.spin_z < -fall {
            self.spin_z + fall
        } else {
            0.0
        };
        Vec3::new(spin.x, spin.y, z)
    }

    /// The path as pieces in simulation time: the motion's phases of non-zero length,
    /// then the rest from [`Track::stop`] on.
    pub fn pieces(&self) -> &[Piece] {
        self.pieces.get(..self.piece_count).unwrap_or(&[])
    }
}

/// The pieces of `motion` started at `since`, and how many.
fn pieces_of(motion: &Motion, since: f32) -> ([Piece; 4], usize) {
    let rest = Piece {
        from: since + motion.stop_time(),
        to: f32::INFINITY,
        p: motion.rest(),
        q: Vec3::ZERO,
        s: Vec3::ZERO,
    };
    let mut pieces = [rest; 4];
    let mut n = 0;
    for (offset, span, p, q, s) in motion.phases() {
        if span > 0.0 {
            let from = since + offset;
            pieces[n] = Piece {
                from,
                to: from + span,
                p: motion.start + p,
                q,
                s,
            };
            n += 1;
        }
    }
    pieces[n] = rest;
    // Contiguous: each piece ends where the next starts (their separately rounded ends
    // and starts differ by an ulp), the last moving one at the stop.
    for k in 0..n {
        pieces[k].to = pieces[k + 1].from;
    }
    (pieces, n + 1)
}

/// The piece of `pieces` that holds time `t` (the last one from its start on).
pub(crate) fn piece_at(pieces: &[Piece], t: f32) -> Option<&Piece> {
    pieces
        .iter()
        .rev()
        .find(|piece| piece.from <= t)
        .or(pieces.first())
}
