//! Serializable report of one collision: the protocol's [`CollideAnswer`], which is
//! both what `cuesight collide --json` prints and the body of the firmware's answer to
//! a `collide` request (one schema, one struct: serde_json here, serde-json-core on the
//! device, the same text for the same numbers).
//!
//! All quantities are SI (m, s, kg, rad/s, N·s) in the collision frame of
//! physics-notes §1 (`x` from the cue ball to the object ball, `z` up, `y = z × x`);
//! angles are in degrees. The human summary is [`CollideAnswer`]'s `Display`.

pub use cuesight_protocol::answer::{
    BallAnswer as BallReport, CollideAnswer as Report, ImpulsesAnswer as ImpulsesReport,
    InputEcho as InputReport,
};

/// The report as one line of JSON (what `--json` prints).
pub fn to_json(report: &Report) -> String {
    // Plain numbers, strings and arrays under string keys: serializing cannot fail,
    // and non-finite numbers (which a report never holds) would become `null`.
    serde_json::to_string(report).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight::{collide, Impact, Model, Params};
    use cuesight_protocol::ModelName;

    fn stun_cut() -> Report {
        let params = Params::POOL;
        let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0; 3]).unwrap();
        let outcome = collide(&params, &impact, Model::KimGrip).unwrap();
        Report::new(
            ModelName::from(Model::KimGrip),
            InputReport::new(2.0, 30.0, false, &params, &impact),
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
    fn json_is_the_firmware_text() {
        let report = stun_cut();
        let mut buf = [0u8; cuesight_protocol::MAX_ANSWER];
        let n = serde_json_core::to_slice(&report, &mut buf).unwrap();
        assert_eq!(std::str::from_utf8(&buf[..n]).unwrap(), to_json(&report));
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
    fn summary_names_model_and_angles() {
        let text = stun_cut().to_string();
        assert!(text.starts_with("model kim-grip, regime "));
        assert!(text.contains("throw "));
        assert!(text.contains("cue deflection "));
        assert!(text.contains("separation "));
    }
}
