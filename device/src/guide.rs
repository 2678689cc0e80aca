//! `shot` on the device: a request validated against the session defaults, played or
//! solved by [`cuesight::guidance::guide`], and its guidance turned into the
//! [`cuesight_link::shot::ShotAnswer`] (whose types are in the link's schema, shared
//! with the host).

use cuesight::guidance::{guide, Aim, BallPath, Guidance, Target};
use cuesight::table::{BallSet, Scene, Table};
use cuesight::{shot::ShotSetup, strike::TipOffset, travel::Cloth, Vec3};

use cuesight_link::error::{LinkError, Unsupported};
use cuesight_link::names::{ModelName, ShotMode, TableName};
use cuesight_link::request::{cue, Defaults, Overrides, ShotRequest};
use cuesight_link::{response::Response, shot::*};

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

/// The live cue's planned shot (`plan`) played at a measured `cue_speed`: the `shot`
/// answer of `plan` with its `speed` replaced.
#[inline(never)]
pub fn play_plan(
    plan: &ShotRequest,
    cue_speed: f32,
    defaults: &Defaults,
) -> Result<ShotAnswer, LinkError> {
    let prepared = prepare(plan, defaults);
    let (scene, tip, aim, setup, model) = match prepared {
        Ok(ref prepared) => prepared,
        Err(error) => return Err(error),
    };
    match run_guide(scene, cue_speed, *tip, *aim, setup) {
        Ok(ref guidance) => Ok(from_guidance(plan.tip, *model, guidance)),
        Err(error) => Err(error.into()),
    }
}

/// Checks a plan as `shot` would, without playing it: the scene, the parameters, the
/// tip, the aim or pocket (its `speed` is each stroke's, so not checked).
pub fn check(plan: &ShotRequest, defaults: &Defaults) -> Result<(), LinkError> {
    prepare(plan, defaults).map(drop)
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
