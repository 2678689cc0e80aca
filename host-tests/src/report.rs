//! Serializable report of one collision: the inputs that produced it and the
//! [`cuesight::Outcome`], flattened into plain arrays and numbers.
//!
//! Shared by the `cuesight` CLI (`--json` and the human summary) and the test suites;
//! meant to become the payload of the firmware protocol. All quantities are SI (m,
//! s, kg, rad/s, N·s) in the collision frame of physics-notes §1 (`x` from the cue
//! ball to the object ball, `z` up, `y = z × x`); angles are in degrees.

use core::fmt;

use cuesight::{BallState, Impact, Impulses, Outcome, Params, Vec3};
use serde::{Deserialize, Serialize};

/// The inputs of a prediction, echoed next to its result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InputReport {
    /// Cue-ball speed before impact `U_i` (m/s).
    pub speed: f32,
    /// Cut angle `φ` (degrees).
    pub cut_deg: f32,
    /// Cue-ball angular velocity before impact (rad/s); for `roll` the natural roll
    /// that was derived from the velocity.
    pub spin: [f32; 3],
    /// `true` when `spin` was set to natural roll rather than given.
    pub roll: bool,
    /// Ball–ball friction coefficient μ.
    pub mu: f32,
    /// Energetic coefficient of restitution e*.
    pub restitution: f32,
    /// Object-ball/table static friction μ_s.
    pub mu_s: f32,
    /// Ball radius R (m).
    pub radius: f32,
    /// Ball mass M (kg).
    pub mass: f32,
}

impl InputReport {
    /// Echo of a validated `params` and `impact`; `speed` and `cut_deg` are the values
    /// the impact was built from (the impact itself stores only the velocity).
    pub fn new(speed: f32, cut_deg: f32, roll: bool, params: &Params, impact: &Impact) -> Self {
        Self {
            speed,
            cut_deg,
            spin: plain(impact.spin()),
            roll,
            mu: params.mu(),
            restitution: params.restitution(),
            mu_s: params.mu_s(),
            radius: params.radius(),
            mass: params.mass(),
        }
    }
}

/// Components as an array, with `-0.0` shown as `0` (the sign of a zero carries no
/// physics and only clutters the output).
fn plain(v: Vec3) -> [f32; 3] {
    v.to_array().map(|c| c + 0.0)
}

/// One ball just after the impact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BallReport {
    /// Centre velocity (m/s).
    pub v: [f32; 3],
    /// Angular velocity (rad/s).
    pub w: [f32; 3],
}

impl From<&BallState> for BallReport {
    fn from(ball: &BallState) -> Self {
        Self {
            v: plain(ball.velocity),
            w: plain(ball.spin),
        }
    }
}

/// Impulses exchanged during the impact (N·s), all acting on the object ball.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImpulsesReport {
    /// Ball–ball normal impulse, along `+x`.
    pub normal: f32,
    /// Ball–ball friction impulse; `x` is zero.
    pub friction: [f32; 3],
    /// Table friction impulse, along `−x`.
    pub table_friction: f32,
}

impl From<&Impulses> for ImpulsesReport {
    fn from(impulses: &Impulses) -> Self {
        Self {
            normal: impulses.normal,
            friction: plain(impulses.friction),
            table_friction: impulses.table_friction,
        }
    }
}

/// A complete prediction: which model, what went in, what came out.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Model name (`ideal`, `kim`, `kim-grip` or `reference`).
    pub model: String,
    /// Contact regime (`frictionless`, `sliding` or `gripping`).
    pub regime: String,
    /// The inputs.
    pub input: InputReport,
    /// Cue ball after the impact.
    pub cue: BallReport,
    /// Object ball after the impact.
    pub object: BallReport,
    /// Throw angle of the object ball from the line of centres (degrees, positive
    /// towards `+y`).
    pub throw_deg: f32,
    /// Cue-ball deflection from the tangent line towards the line of centres
    /// (degrees).
    pub cue_deflection_deg: f32,
    /// Angle between the balls' horizontal directions of travel (degrees).
    pub separation_deg: f32,
    /// Impulses exchanged.
    pub impulses: ImpulsesReport,
}

impl Report {
    /// Build the report of `outcome`, produced by the model called `model` from
    /// `input`.
    pub fn new(model: &str, input: InputReport, outcome: &Outcome) -> Self {
        Self {
            model: model.to_owned(),
            regime: outcome.regime.name().to_owned(),
            input,
            cue: BallReport::from(&outcome.cue_ball),
            object: BallReport::from(&outcome.object_ball),
            throw_deg: outcome.throw_angle_deg(),
            cue_deflection_deg: outcome.cue_deflection_deg(),
            separation_deg: outcome.separation_angle_deg(),
            impulses: ImpulsesReport::from(&outcome.impulses),
        }
    }

    /// The report as one line of JSON.
    pub fn to_json(&self) -> String {
        // Only plain numbers, strings and arrays with string keys: cannot fail.
        serde_json::to_string(self).expect("a Report always serializes")
    }
}

/// Human-readable summary, a few lines, no trailing newline.
impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let i = &self.input;
        let spin_kind = if i.roll { " (natural roll)" } else { "" };
        writeln!(f, "model {}, regime {}", self.model, self.regime)?;
        writeln!(
            f,
            "input:  speed {} m/s, cut {} deg, w {} rad/s{spin_kind}",
            i.speed,
            i.cut_deg,
            Vector(i.spin)
        )?;
        writeln!(
            f,
            "        mu {}, e* {}, mu_s {}, R {} m, M {} kg",
            i.mu, i.restitution, i.mu_s, i.radius, i.mass
        )?;
        for (name, ball) in [("cue:   ", &self.cue), ("object:", &self.object)] {
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
            self.throw_deg, self.cue_deflection_deg, self.separation_deg
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

#[cfg(test)]
mod tests {
    use super::*;
    use cuesight::{collide, Model};

    fn stun_cut() -> Report {
        let params = Params::POOL;
        let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0; 3]).unwrap();
        let outcome = collide(&params, &impact, Model::KimGrip).unwrap();
        Report::new(
            "kim-grip",
            InputReport::new(2.0, 30.0, false, &params, &impact),
            &outcome,
        )
    }

    #[test]
    fn json_round_trips() {
        let report = stun_cut();
        let json = report.to_json();
        assert!(!json.contains('\n'));
        let back: Report = serde_json::from_str(&json).unwrap();
        assert_eq!(back, report);
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
        assert_eq!(report.regime, outcome.regime.name());
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
