//! Endless event chains, and how the simulation ends them: inelastic collapse, where
//! the same contacts would repeat ever faster (two balls pressed together by their
//! different decelerations, a ball pressed into a cushion by its own slip, two balls
//! wedged in a pocket's jaws).

use crate::vector::Vec3;

/// Two balls that collide again within this time (s) of their last collision, closing
/// slower than [`LOCK_SPEED`], are locked together ([`super::pair::lock`]); a ball that hits a cushion
/// so soon after its last cushion (the same one, or the other of a corner) and so slowly
/// runs along it ([`along_cushion`]).
pub(super) const LOCK_TIME: f32 = 0.01;
/// See [`LOCK_TIME`] (m/s).
pub(super) const LOCK_SPEED: f32 = 0.01;

/// A ball that takes part in more events than this at one instant (time no longer
/// advancing in f32) is jammed: wedged between balls and cushions that push it into
/// each other, typically two balls side by side in a pocket's jaws, each against its
/// face and the other, whose collisions would otherwise repeat without end. It stops
/// translating there ([`jam`]).
pub(super) const JAM_EVENTS: u16 = 32;

/// A ball pressed into a cushion by its own slip (side spin or a sliding curve into
/// it), whose rebounds would otherwise repeat without end: it keeps the velocity and
/// spin parallel to the cushion and loses their parts that move the contact into it
/// (the normal velocity, and the spin about the horizontal along the cushion, which
/// drives the cloth slip across it), so it runs along the cushion. It leaves the
/// cushion at [`SEPARATION`]: along a normal that is not an axis (a jaw's face) the
/// removal leaves a rounding's worth of normal velocity, which, into the cushion, would
/// meet it again at once, for ever. Kinetic energy grows by at most `SEPARATION² / 2`
/// (5e-13 J/kg), within f32 rounding of a moving ball's; the cushion's friction while
/// the ball runs along it is not modelled.
pub(super) fn along_cushion(velocity: Vec3, spin: Vec3, normal: Vec3) -> (Vec3, Vec3) {
    let along = Vec3::new(-normal.y, normal.x, 0.0); // ẑ × n
    let velocity = Vec3::new(velocity.x, velocity.y, 0.0);
    (
        velocity - normal * (velocity.dot(normal) + SEPARATION),
        spin - along * spin.dot(along),
    )
}

/// A jammed ball ([`JAM_EVENTS`]) with spin `spin`: it stops translating and rolling
/// (velocity and horizontal spin zero), keeping its spin about the vertical, which the
/// cloth then slows. Kinetic energy only falls.
pub(super) fn jam(spin: Vec3) -> (Vec3, Vec3) {
    (Vec3::ZERO, Vec3::new(0.0, 0.0, spin.z))
}

/// Speed (m/s) at which [`along_cushion`] moves a ball off the cushion: 1 µm/s.
const SEPARATION: f32 = 1e-6;
