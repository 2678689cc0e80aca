//! Serializable report of one collision: the link's [`Report`]
//! (`cuesight_link::CollideAnswer`), which is both what `cuesight collide --json` prints
//! (serde_json) and the body of the device's answer to a `collide` request (postcard):
//! one schema, one struct.
//!
//! All quantities are SI (m, s, kg, rad/s, N·s) in the collision frame of
//! physics-notes §1 (`x` from the cue ball to the object ball, `z` up, `y = z × x`);
//! angles are in degrees. The human summary is [`Text`].

use core::fmt;

pub use cuesight_link::response::{
    BallAnswer as BallReport, CollideAnswer as Report, ImpulsesAnswer as ImpulsesReport,
    InputEcho as InputReport,
};

/// The report as one line of JSON (what `--json` prints).
pub fn to_json(report: &Report) -> String {
    // Plain numbers, strings and arrays under string keys: serializing cannot fail,
    // and non-finite numbers (which a report never holds) would become `null`.
    serde_json::to_string(report).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
}

/// `collide --json` with `--model auto`: the report's keys, then the tolerance, the tier
/// `auto` evaluated and its estimate (the names of `shot --json`'s contact).
#[derive(serde::Serialize)]
struct AutoJson<'a> {
    #[serde(flatten)]
    report: &'a Report,
    tolerance: f32,
    model_used: &'static str,
    error_estimate: f32,
}

/// The report as one line of JSON, with `auto`'s pick when there is one: the keys of
/// [`to_json`], then `tolerance`, `model_used` and `error_estimate`.
pub fn to_json_with(report: &Report, pick: Option<&crate::cli::AutoPick>) -> String {
    match pick {
        None => to_json(report),
        Some(pick) => serde_json::to_string(&AutoJson {
            report,
            tolerance: pick.tolerance,
            model_used: pick.tier.name(),
            error_estimate: pick.estimate,
        })
        .unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}")),
    }
}

/// The line [`Text`] gets for `auto`'s pick (no newline).
pub struct AutoLine<'a>(pub &'a crate::cli::AutoPick);

impl fmt::Display for AutoLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let pick = self.0;
        write!(
            f,
            "auto: {} (estimated error {:.3e} of U, tolerance {})",
            pick.tier.name(),
            pick.estimate,
            pick.tolerance
        )
    }
}

/// `(x, y, z)` with fixed-width components, for aligned columns.
struct Vector([f32; 3]);

impl fmt::Display for Vector {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [x, y, z] = self.0;
        write!(f, "({x:9.4}, {y:9.4}, {z:9.4})")
    }
}

/// `mu 0.05`, or `mu 0.00995 + 0.108 exp(-1.088 v)` for a speed-dependent law.
pub struct Friction {
    /// `a`, the constant μ or the high-speed limit.
    pub mu: f32,
    /// `b`.
    pub mu_b: f32,
    /// `c` (s/m).
    pub mu_c: f32,
}

impl fmt::Display for Friction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.mu_b == 0.0 && self.mu_c == 0.0 {
            write!(f, "mu {}", self.mu)
        } else {
            write!(f, "mu {} + {} exp(-{} v)", self.mu, self.mu_b, self.mu_c)
        }
    }
}

/// The human summary of a report, a few lines, no trailing newline (`cuesight collide`).
pub struct Text<'a>(pub &'a Report);

impl fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let report = self.0;
        let i = &report.input;
        let spin_kind = if i.roll { " (natural roll)" } else { "" };
        writeln!(
            f,
            "model {}, regime {}",
            report.model.name(),
            report.regime.name()
        )?;
        writeln!(
            f,
            "input:  speed {} m/s, cut {} deg, w {} rad/s{spin_kind}",
            i.speed,
            i.cut_deg,
            Vector(i.spin)
        )?;
        let friction = Friction {
            mu: i.mu,
            mu_b: i.mu_b,
            mu_c: i.mu_c,
        };
        writeln!(
            f,
            "        {friction}, e* {}, mu_s {}, R {} m, M {} kg",
            i.restitution, i.mu_s, i.radius, i.mass
        )?;
        for (name, ball) in [("cue:   ", &report.cue), ("object:", &report.object)] {
            writeln!(
                f,
                "{name} v {} m/s   w {} rad/s",
                Vector(ball.v),
                Vector(ball.w)
            )?;
        }
        write!(
            f,
            "throw {:.3} deg, cue deflection {:.3} deg, separation {:.3} deg",
            report.throw_deg, report.cue_deflection_deg, report.separation_deg
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight::{collide, Impact, Model, Params};
    use cuesight_link::{Collide, Defaults, ModelName};

    fn stun_cut() -> Report {
        let request = Collide::new(2.0, 30.0);
        let prepared = request.prepare(&Defaults::POOL).unwrap();
        let outcome = collide(&prepared.params, &prepared.impact, Model::KimGrip).unwrap();
        Report::new(
            ModelName::of(Model::KimGrip),
            InputReport::of(&request, &prepared),
            &outcome,
        )
    }

    #[test]
    fn json_round_trips() {
        let report = stun_cut();
        let json = to_json(&report);
        assert!(!json.contains('\n'));
        let back: Report = serde_json::from_str(&json).unwrap();
        assert_eq!(back, report);
    }

    #[test]
    fn frame_round_trips() {
        use cuesight_link::frame::{self, MAX_FRAME};
        let report = stun_cut();
        let mut wire = [0u8; MAX_FRAME];
        let len = frame::encode(cuesight_link::SCHEMA_HASH, 0, &report, &mut wire).unwrap();
        let mut raw = [0u8; MAX_FRAME];
        let n = cobs::decode(&wire[..len - 1], &mut raw).unwrap();
        let (_, body) = frame::open(&raw[..n]).unwrap();
        assert_eq!(frame::decode::<Report>(body), Ok(report));
    }

    #[test]
    fn conversion_keeps_the_outcome() {
        let params = Params::POOL;
        let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0; 3]).unwrap();
        let outcome = collide(&params, &impact, Model::KimGrip).unwrap();
        let report = stun_cut();
        assert_eq!(report.object.v, outcome.object_ball.velocity.to_array());
        assert_eq!(report.cue.w, outcome.cue_ball.spin.to_array());
        assert_eq!(report.impulses.normal, outcome.impulses.normal);
        assert_eq!(report.throw_deg, outcome.throw_angle_deg());
        assert_eq!(report.regime.name(), outcome.regime.name());
        assert_eq!(report.input.mu, 0.05);
    }

    #[test]
    fn auto_json_appends_the_pick_to_the_same_keys() {
        let report = stun_cut();
        let pick = crate::cli::AutoPick {
            tolerance: 0.01,
            tier: Model::Kim,
            estimate: 0.005,
        };
        let plain = to_json(&report);
        let with = to_json_with(&report, Some(&pick));
        assert_eq!(
            with,
            format!(
                "{},\"tolerance\":0.01,\"model_used\":\"kim\",\"error_estimate\":0.005}}",
                plain.strip_suffix('}').unwrap()
            )
        );
        assert_eq!(to_json_with(&report, None), plain);
        assert_eq!(
            AutoLine(&pick).to_string(),
            "auto: kim (estimated error 5.000e-3 of U, tolerance 0.01)"
        );
    }

    #[test]
    fn summary_names_model_and_angles() {
        let text = Text(&stun_cut()).to_string();
        assert!(text.starts_with("model kim-grip, regime "));
        assert!(text.contains("throw "));
        assert!(text.contains("cue deflection "));
        assert!(text.contains("separation "));
    }
}
