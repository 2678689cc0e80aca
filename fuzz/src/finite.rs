//! Assertions that every number a successful call returned is finite; a failure panics
//! (which libFuzzer reports as a crash) naming the first number that is not.

use std::fmt::Debug;

use cuesight::aim::AimSolution;
use cuesight::shot::{Contact, Shot};
use cuesight::travel::Motion;
use cuesight::{Impact, Outcome, Vec3};

/// Each of `values`, named `what[i]`, is finite.
pub fn numbers(what: &str, values: &[f32]) {
    for (i, value) in values.iter().enumerate() {
        assert!(value.is_finite(), "{what}[{i}] = {value} is not finite");
    }
}

/// `v`'s three components are finite.
pub fn vector(what: &str, v: Vec3) {
    numbers(what, &v.to_array());
}

/// Both balls' velocities and spins and every impulse.
pub fn outcome(what: &str, o: &Outcome) {
    vector(&format!("{what}.cue_ball.velocity"), o.cue_ball.velocity);
    vector(&format!("{what}.cue_ball.spin"), o.cue_ball.spin);
    vector(
        &format!("{what}.object_ball.velocity"),
        o.object_ball.velocity,
    );
    vector(&format!("{what}.object_ball.spin"), o.object_ball.spin);
    numbers(
        &format!("{what}.impulses"),
        &[o.impulses.normal, o.impulses.table_friction],
    );
    vector(&format!("{what}.impulses.friction"), o.impulses.friction);
}

/// The throw, deflection and separation angles of an outcome (for validated input: an
/// outcome of a law that skipped validation may be finite but too large to square).
pub fn angles(what: &str, o: &Outcome) {
    numbers(
        &format!("{what} angles"),
        &[
            o.throw_angle(),
            o.cue_deflection(),
            o.separation_angle_deg(),
        ],
    );
}

/// The cue ball's velocity and spin at contact.
pub fn impact(what: &str, i: &Impact) {
    vector(&format!("{what}.velocity"), i.velocity());
    vector(&format!("{what}.spin"), i.spin());
}

/// A motion's fields, its phase times (finite and not negative), and where it is, how
/// fast it goes and how it spins at the phase boundaries and after it stops.
pub fn motion(what: &str, m: &Motion) {
    vector(&format!("{what}.start"), m.start);
    vector(&format!("{what}.initial_velocity"), m.initial_velocity);
    vector(
        &format!("{what}.sliding_acceleration"),
        m.sliding_acceleration,
    );
    vector(&format!("{what}.rolling_velocity"), m.rolling_velocity);
    vector(&format!("{what}.initial_spin"), m.initial_spin);
    let times = [
        m.air_time,
        m.hop_height,
        m.sliding_time,
        m.rolling_time,
        m.stop_time(),
    ];
    numbers(&format!("{what} times"), &times);
    for (i, t) in times.iter().enumerate() {
        assert!(*t >= 0.0, "{what} times[{i}] = {t} is negative");
    }
    for (name, p) in [
        ("landing", m.landing()),
        ("rolling_start", m.rolling_start()),
        ("rest", m.rest()),
        ("bounds.min", m.bounds().min),
        ("bounds.max", m.bounds().max),
    ] {
        vector(&format!("{what}.{name}"), p);
    }
    let stop = m.stop_time();
    for t in [
        0.0,
        m.air_time,
        m.air_time + 0.5 * m.sliding_time,
        m.air_time + m.sliding_time,
        stop - 0.5 * m.rolling_time,
        stop,
        stop + 1.0,
    ] {
        at(what, m, t);
    }
}

/// Position, velocity and spin of `m` at time `t` (finite for a finite `t`).
pub fn at(what: &str, m: &Motion, t: f32) {
    if !t.is_finite() {
        return;
    }
    vector(&format!("{what}.position_at({t})"), m.position_at(t));
    vector(&format!("{what}.velocity_at({t})"), m.velocity_at(t));
    vector(&format!("{what}.spin_at({t})"), m.spin_at(t));
}

/// A played shot: launch, the cue ball's motion and the contact, if any.
pub fn shot(s: &Shot) {
    numbers("launch.speed", &[s.launch.speed]);
    vector("launch.spin", s.launch.spin);
    motion("cue_before", &s.cue_before);
    if let Some(c) = &s.contact {
        contact(c);
    }
}

fn contact(c: &Contact) {
    numbers("contact", &[c.time, c.cut_angle]);
    vector("contact.cue_position", c.cue_position);
    vector("contact.line_of_centres", c.line_of_centres);
    impact("contact.impact", &c.impact);
    outcome("contact.outcome", &c.outcome);
    angles("contact.outcome", &c.outcome);
    motion("contact.cue_after", &c.cue_after);
    motion("contact.object_after", &c.object_after);
    if let Some((_, t)) = c.pocket {
        numbers("contact.pocket time", &[t]);
    }
}

/// A solved aim.
pub fn aim(a: &AimSolution) {
    vector("aim.aim", a.aim);
    vector("aim.ghost_ball", a.ghost_ball);
    vector("aim.naive_aim", a.naive_aim);
    vector("aim.naive_ghost_ball", a.naive_ghost_ball);
    numbers(
        "aim",
        &[
            a.correction_deg,
            a.correction_mm,
            a.cut_angle_deg,
            a.residual,
        ],
    );
}

/// Every number in `value`'s `Debug` form is finite: no `NaN` or `inf` written out (for
/// answers with many nested numbers, e.g. `guidance::Guidance`).
pub fn debug(what: &str, value: &impl Debug) {
    let text = format!("{value:?}");
    for word in ["NaN", "inf"] {
        assert!(!has_word(&text, word), "{what} holds {word}: {text}");
    }
}

/// `word` in `text` with no letter, digit or `_` on either side.
pub fn has_word(text: &str, word: &str) -> bool {
    let is_word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
    text.match_indices(word).any(|(at, _)| {
        !is_word(text[..at].chars().next_back()) && !is_word(text[at + word.len()..].chars().next())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_are_found_only_whole() {
        assert!(has_word("speed = inf is outside", "inf"));
        assert!(has_word("\"-inf\"", "inf"));
        assert!(has_word("x: NaN }", "NaN"));
        assert!(!has_word("info", "inf"));
        assert!(!has_word("NaNo", "NaN"));
    }
}
