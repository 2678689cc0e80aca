//! `shot`: shot guidance on the device. The answer holds the keys of `cuesight shot
//! --json` but the echo of the scene, which the host has; both are built by
//! [`cuesight::guidance::guide`], so the numbers are the same. Units: SI in the table
//! frame, degrees in the keys ending in `_deg` (`docs/protocol.md`).

use serde::{Deserialize, Serialize};

use crate::names::{EndName, ModelName, RegimeName, ShotMode};

/// The answer to `shot`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ShotAnswer {
    /// Whether the aim was given or solved.
    pub mode: ShotMode,
    /// The stroke played.
    pub stroke: StrokePart,
    /// The inverse aim (solve only).
    pub solve: Option<SolvePart>,
    /// The first collision; `None` when the cue ball hits nothing.
    pub contact: Option<ContactPart>,
    /// The cue ball's path.
    pub cue_ball: BallPart,
    /// The object ball's path after the impact.
    pub object_ball: Option<BallPart>,
    /// The target, if one was given.
    pub target: Option<TargetPart>,
}

/// The stroke played.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct StrokePart {
    /// Cue speed at the tip impact (m/s).
    pub cue_speed: f32,
    /// Tip offset asked for (ball radii, right and up).
    pub tip: [f32; 2],
    /// Aim (degrees counter-clockwise from `+x`).
    pub aim_deg: f32,
    /// Aim as a unit vector.
    pub aim: [f32; 2],
    /// Cue-ball speed after the strike (m/s).
    pub launch_speed: f32,
    /// Cue-ball spin after the strike (rad/s, table frame).
    pub launch_spin: [f32; 3],
}

/// The inverse aim.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct SolvePart {
    /// The ball to pocket.
    pub object: u16,
    /// The pocket.
    pub pocket: u16,
    /// The aim that pockets it, throw included (degrees).
    pub aim_deg: f32,
    /// The ghost-ball aim (degrees).
    pub naive_aim_deg: f32,
    /// `aim_deg − naive_aim_deg` (degrees).
    pub correction_deg: f32,
    /// The correction as a shift of the contact point (m).
    pub correction_offset: f32,
    /// Whether the corrected aim hits the object ball thinner.
    pub thinner: bool,
    /// Cut angle at the corrected aim (degrees).
    pub cut_deg: f32,
    /// Ghost-ball centre at the corrected aim (m).
    pub ghost_ball: [f32; 2],
    /// Ghost-ball centre at the naive aim (m).
    pub naive_ghost_ball: [f32; 2],
    /// Shot evaluations the solver made.
    pub evaluations: u32,
    /// Miss at the pocket's mouth at the solution (m).
    pub residual: f32,
}

/// The first collision.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct ContactPart {
    /// The ball hit.
    pub ball: u16,
    /// When (s after the strike).
    pub time: f32,
    /// Cue-ball centre at contact (m).
    pub cue_position: [f32; 2],
    /// Unit vector from the cue ball to the object ball.
    pub line_of_centres: [f32; 2],
    /// Cut angle (degrees).
    pub cut_deg: f32,
    /// Cue-ball speed at contact (m/s).
    pub speed: f32,
    /// Cue-ball spin at contact (rad/s, collision frame).
    pub spin: [f32; 3],
    /// The model asked for.
    pub model: ModelName,
    /// The model that ran (`auto` picks one).
    pub model_used: ModelName,
    /// `auto`'s error estimate, when it ran.
    pub error_estimate: Option<f32>,
    /// Contact regime.
    pub regime: RegimeName,
    /// Throw of the object ball (degrees).
    pub throw_deg: f32,
}

/// One ball's path from its launch to its end.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct BallPart {
    /// The ball (0: the cue ball).
    pub ball: u16,
    /// Launch position (m).
    pub start: [f32; 2],
    /// Launch velocity (m/s).
    pub velocity: [f32; 3],
    /// Launch spin (rad/s).
    pub spin: [f32; 3],
    /// Highest hop (m).
    pub hop_height: f32,
    /// Time in the air (s).
    pub air_time: f32,
    /// Where it lands (m).
    pub landing: [f32; 2],
    /// Time sliding (s).
    pub sliding_time: f32,
    /// Where it starts to roll (m).
    pub rolling_start: [f32; 2],
    /// Rolling velocity (m/s).
    pub rolling_velocity: [f32; 2],
    /// Rolling speed (m/s).
    pub rolling_speed: f32,
    /// Rolling direction (degrees).
    pub rolling_direction_deg: f32,
    /// When it would stop on an endless table (s).
    pub stop_time: f32,
    /// Where it would stop on an endless table (m).
    pub rest: [f32; 2],
    /// How the path ends.
    pub end: EndName,
    /// When (s).
    pub end_time: f32,
    /// Where (m).
    pub end_position: [f32; 2],
    /// The pocket, when it drops.
    pub pocket: Option<u16>,
}

/// The target's outcome.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub struct TargetPart {
    /// The ball.
    pub object: u16,
    /// The pocket.
    pub pocket: u16,
    /// Whether it drops.
    pub pocketed: bool,
    /// Miss at the mouth (m), when it reaches the mouth line.
    pub miss: Option<f32>,
}

#[cfg(feature = "shot")]
mod serve {
    //! The device side: a `shot` request validated, guided and answered.

    use cuesight::guidance::{guide, Aim, BallPath, Guidance, Target};
    use cuesight::shot::ShotSetup;
    use cuesight::strike::TipOffset;
    use cuesight::table::{BallSet, Scene, Table};
    use cuesight::travel::Cloth;
    use cuesight::Vec3;

    use super::*;
    use crate::error::{LinkError, Unsupported};
    use crate::names::TableName;
    use crate::request::{cue, Defaults, Overrides, ShotRequest};
    use crate::response::Response;

    /// `[x, y]` of a vector.
    fn xy(v: Vec3) -> [f32; 2] {
        [v.x, v.y]
    }

    fn table(name: TableName) -> (Table, BallSet) {
        match name {
            TableName::Pool => (Table::pool(), BallSet::POOL),
            TableName::Snooker => (Table::snooker(), BallSet::SNOOKER),
            TableName::Carom => (Table::carom(), BallSet::CAROM),
        }
    }

    /// Validates `request` against `defaults`, plays or solves it, and returns the
    /// answer (as the [`Response`] to send, built in place). The validation, the guidance and the answer each run in a frame of their
    /// own (the guidance is the device's deepest stack): the prepared shot and the
    /// guidance are read where they lie, not moved.
    #[inline(never)]
    pub fn answer(request: &ShotRequest, defaults: &Defaults) -> Result<Response, LinkError> {
        let prepared = prepare(request, defaults);
        let (scene, tip, aim, setup, model) = match prepared {
            Ok(ref prepared) => prepared,
            Err(error) => return Err(error),
        };
        let guidance = run_guide(scene, request.speed, *tip, *aim, setup);
        match guidance {
            Ok(ref guidance) => Ok(Response::Shot(from_guidance(request.tip, *model, guidance))),
            Err(error) => Err(error.into()),
        }
    }

    /// [`guide`] in a frame of its own.
    #[inline(never)]
    fn run_guide(
        scene: &Scene,
        speed: f32,
        tip: TipOffset,
        aim: Aim,
        setup: &ShotSetup,
    ) -> Result<Guidance, cuesight::aim::AimError> {
        guide(scene, speed, tip, aim, setup)
    }

    /// A validated shot: the scene, the tip, the aim, the setup and the model's name.
    type Prepared = (Scene, TipOffset, Aim, ShotSetup, ModelName);

    /// Validates `request` against `defaults`: contact parameters, cue, cloth, tip, the
    /// balls (each on the table, none overlapping), the aim; errors name the field.
    #[inline(never)]
    fn prepare(request: &ShotRequest, defaults: &Defaults) -> Result<Prepared, LinkError> {
        let (table, set) = table(request.table);
        let with = Overrides {
            mu: request.mu,
            mu_b: request.mu_b,
            mu_c: request.mu_c,
            restitution: request.restitution,
            mu_s: request.mu_s,
            radius: Some(set.radius),
            mass: Some(request.mass.unwrap_or(set.mass)),
            model: request.model,
        };
        let Defaults { params, model } = with.apply(defaults)?;
        let core_model = model
            .core()
            .ok_or(LinkError::Unsupported(Unsupported::ReferenceModel))?;
        let cue = cue(request.cue_mass, request.tip_restitution)?;
        let cloth = Cloth::new(
            request.mu_cloth.unwrap_or(Cloth::TYPICAL.sliding()),
            request.mu_roll.unwrap_or(Cloth::TYPICAL.rolling()),
        )?;
        let [side, height] = request.tip;
        let tip = TipOffset::from_radius_fraction(side, height, set.radius)?;
        let mut scene = Scene::new(table, set.radius, request.cue)?;
        for &ball in &request.balls {
            scene.add_ball(ball)?;
        }
        let object = usize::from(request.object.unwrap_or(1));
        let aim = match (request.aim, request.pocket) {
            (Some(aim_deg), pocket) => Aim::Degrees {
                aim_deg,
                target: pocket.map(|p| Target {
                    object,
                    pocket: usize::from(p),
                }),
            },
            (None, Some(pocket)) => Aim::Solve(Target {
                object,
                pocket: usize::from(pocket),
            }),
            (None, None) => return Err(LinkError::MissingAim),
        };
        let setup = ShotSetup {
            params,
            cue,
            cloth,
            model: core_model,
        };
        Ok((scene, tip, aim, setup, model))
    }

    /// The answer's fields from the core's guidance.
    #[inline(never)]
    fn from_guidance(tip: [f32; 2], model: ModelName, g: &Guidance) -> ShotAnswer {
        let s = &g.stroke;
        ShotAnswer {
            mode: if g.solve.is_some() {
                ShotMode::Solve
            } else {
                ShotMode::Play
            },
            stroke: StrokePart {
                cue_speed: s.cue_speed,
                tip,
                aim_deg: s.aim_deg,
                aim: s.aim,
                launch_speed: s.launch_speed,
                launch_spin: s.launch_spin,
            },
            solve: g.solve.as_ref().map(|solve| {
                let a = &solve.solution;
                SolvePart {
                    object: solve.target.object as u16,
                    pocket: solve.target.pocket as u16,
                    aim_deg: solve.aim_deg,
                    naive_aim_deg: solve.naive_aim_deg,
                    correction_deg: a.correction_deg,
                    // m, as the CLI reports it (the solver's figure is in mm).
                    correction_offset: 1e-3 * a.correction_mm,
                    thinner: a.thinner,
                    cut_deg: a.cut_angle_deg,
                    ghost_ball: xy(a.ghost_ball),
                    naive_ghost_ball: xy(a.naive_ghost_ball),
                    evaluations: a.evaluations,
                    residual: a.residual,
                }
            }),
            contact: g.contact.as_ref().map(|c| ContactPart {
                ball: c.ball as u16,
                time: c.time,
                cue_position: c.cue_position,
                line_of_centres: c.line_of_centres,
                cut_deg: c.cut_deg,
                speed: c.speed,
                spin: c.spin,
                model,
                model_used: ModelName::of(c.model_used),
                error_estimate: c.error_estimate,
                regime: c.regime,
                throw_deg: c.throw_deg,
            }),
            cue_ball: ball(&g.cue_ball),
            object_ball: g.object_ball.as_ref().map(ball),
            target: g.target.as_ref().map(|t| TargetPart {
                object: t.target.object as u16,
                pocket: t.target.pocket as u16,
                pocketed: t.pocketed,
                miss: t.miss,
            }),
        }
    }

    fn ball(b: &BallPath) -> BallPart {
        let m = &b.motion;
        BallPart {
            ball: b.ball as u16,
            start: xy(m.start),
            velocity: b.velocity,
            spin: m.initial_spin.to_array(),
            hop_height: m.hop_height,
            air_time: m.air_time,
            landing: xy(m.landing()),
            sliding_time: m.sliding_time,
            rolling_start: xy(m.rolling_start()),
            rolling_velocity: xy(m.rolling_velocity),
            rolling_speed: m.rolling_velocity.length(),
            rolling_direction_deg: b.rolling_direction_deg,
            stop_time: m.stop_time(),
            rest: xy(m.rest()),
            end: b.end.end,
            end_time: b.end.time,
            end_position: b.end_position,
            pocket: b.end.pocket.map(|p| p as u16),
        }
    }
}

#[cfg(feature = "shot")]
pub use serve::answer;
