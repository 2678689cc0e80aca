//! `shot`: shot guidance on the device — the request (a scene, a stroke, an aim or a
//! pocket to solve for) and its answer, the core's [`cuesight::guidance::Guidance`]
//! with the keys of `cuesight shot --json`.
//!
//! The answer holds the same keys and values as the CLI's JSON except the echo of the
//! scene (`table`, `balls`, `mu_cloth`, `mu_roll`) and the pocket names, which the host
//! adds for people; both are built by [`cuesight::guidance::guide`], so the numbers are
//! the same (bit for bit, by the end-to-end test). Units: SI in the table frame, angles
//! in degrees in the keys ending in `_deg` (`docs/protocol.md`).

use cuesight::guidance::{self, Aim, BallPath, End, Guidance, Target};
use cuesight::shot::ShotSetup;
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
use cuesight::travel::Cloth;
use heapless::Vec;
use serde::ser::{Serialize, SerializeStruct, Serializer};
use serde::Deserialize;

use crate::answer::{Answer, ErrorAnswer};
use crate::encode::Writer;
use crate::names::{ModelName, RegimeName};
use crate::problem::Problem;
use crate::request::{Defaults, Overrides};
use crate::session::AnswerLine;

/// Most object balls in a `shot` (the scene holds the cue ball and these).
pub const MAX_OBJECT_BALLS: usize = MAX_BALLS - 1;

/// A table preset, with its ball set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TableName {
    /// 9-ft pool table, pool balls.
    #[default]
    Pool,
    /// Snooker table, snooker balls.
    Snooker,
    /// Carom table (no pockets), carom balls.
    Carom,
}

impl TableName {
    /// The wire names.
    pub const NAMES: &'static str = "pool, snooker or carom";

    /// The preset for a wire name.
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "pool" => Some(TableName::Pool),
            "snooker" => Some(TableName::Snooker),
            "carom" => Some(TableName::Carom),
            _ => None,
        }
    }

    /// The wire name.
    pub const fn name(self) -> &'static str {
        match self {
            TableName::Pool => "pool",
            TableName::Snooker => "snooker",
            TableName::Carom => "carom",
        }
    }

    /// The table, its pocket targets set for its own balls.
    pub fn table(self) -> Table {
        match self {
            TableName::Pool => Table::pool(),
            TableName::Snooker => Table::snooker(),
            TableName::Carom => Table::carom(),
        }
    }

    /// Its ball set (radius, mass).
    pub const fn balls(self) -> BallSet {
        match self {
            TableName::Pool => BallSet::POOL,
            TableName::Snooker => BallSet::SNOOKER,
            TableName::Carom => BallSet::CAROM,
        }
    }
}

/// `shot`: the scene, the stroke, and the aim — given (`aim`, degrees) or solved for
/// (`pocket`, and `object`, default 1).
///
/// The balls are the table's ball set (`radius` is not a `shot` field; `mass` may be
/// given); μ, `mu_b`, `mu_c`, e*, μ_s and the model come from the session defaults
/// unless given here.
#[derive(Clone, Debug, PartialEq)]
pub struct Shot {
    /// Table preset.
    pub table: TableName,
    /// Cue-ball centre (m, table frame).
    pub cue: [f32; 2],
    /// The other balls' centres (m), numbered 1, 2, ... in this order.
    pub balls: Vec<[f32; 2], MAX_OBJECT_BALLS>,
    /// Cue speed at the tip impact (m/s).
    pub speed: f32,
    /// Tip offset `[side right, height up]` in ball radii; centre when absent.
    pub tip: [f32; 2],
    /// Aim (degrees counter-clockwise from `+x`); `None`: solve for `pocket`.
    pub aim: Option<f32>,
    /// The ball to pocket (default 1).
    pub object: Option<u32>,
    /// The pocket (index in the table's pocket list).
    pub pocket: Option<u32>,
    /// Ball–cloth sliding friction μ_c; [`Cloth::TYPICAL`] when absent.
    pub mu_cloth: Option<f32>,
    /// Rolling resistance μ_r; [`Cloth::TYPICAL`] when absent.
    pub mu_roll: Option<f32>,
    /// Cue mass (kg); [`Cue::TYPICAL`] when absent.
    pub cue_mass: Option<f32>,
    /// Tip restitution; [`Cue::TYPICAL`] when absent.
    pub tip_restitution: Option<f32>,
    /// Contact parameters and model for this shot (`radius` stays `None`).
    pub with: Overrides,
}

/// A validated `shot`, ready for [`guidance::guide`].
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedShot {
    /// The balls on the table.
    pub scene: Scene,
    /// Tip offset.
    pub tip: TipOffset,
    /// The aim or the target to solve for.
    pub aim: Aim,
    /// Parameters, cue, cloth and model.
    pub setup: ShotSetup,
    /// The model's wire name.
    pub model: ModelName,
}

impl Shot {
    /// Field names, in wire order (the [`Overrides::FIELDS`] but `radius` follow).
    pub const FIELDS: [&'static str; 12] = [
        "table",
        "cue",
        "balls",
        "speed",
        "tip",
        "aim",
        "object",
        "pocket",
        "mu_cloth",
        "mu_roll",
        "cue_mass",
        "tip_restitution",
    ];

    /// Validate against `defaults` through the core's constructors: contact
    /// parameters, cue, cloth, tip, then the balls (each on the table, none
    /// overlapping), then the aim or target. Errors name the field.
    // Not inlined: see `decode::read_shot`.
    #[inline(never)]
    pub fn prepare(&self, defaults: &Defaults) -> Result<PreparedShot, Problem> {
        let set = self.table.balls();
        let mut with = self.with;
        with.radius = Some(set.radius);
        with.mass = Some(with.mass.unwrap_or(set.mass));
        let Defaults { params, model } = with.apply(defaults)?;
        let core_model = model.core().ok_or(Problem::Unsupported {
            field: "model",
            reason: "reference runs on the host only (cuesight shot --model reference)",
        })?;
        let cue = Cue::new(
            self.cue_mass.unwrap_or(Cue::TYPICAL.mass()),
            self.tip_restitution
                .unwrap_or(Cue::TYPICAL.tip_restitution()),
        )?;
        let cloth = Cloth::new(
            self.mu_cloth.unwrap_or(Cloth::TYPICAL.sliding()),
            self.mu_roll.unwrap_or(Cloth::TYPICAL.rolling()),
        )?;
        let tip = TipOffset::from_radius_fraction(self.tip[0], self.tip[1], set.radius)?;
        let mut scene = Scene::new(self.table.table(), set.radius, self.cue)?;
        for &ball in &self.balls {
            scene.add_ball(ball)?;
        }
        let index = |i: Option<u32>, default: u32| i.unwrap_or(default) as usize;
        let aim = match (self.aim, self.pocket) {
            (Some(aim_deg), pocket) => Aim::Degrees {
                aim_deg,
                target: pocket.map(|p| Target {
                    object: index(self.object, 1),
                    pocket: p as usize,
                }),
            },
            (None, Some(pocket)) => Aim::Solve(Target {
                object: index(self.object, 1),
                pocket: pocket as usize,
            }),
            (None, None) => return Err(Problem::MissingField("aim")),
        };
        Ok(PreparedShot {
            scene,
            tip,
            aim,
            setup: ShotSetup {
                params,
                cue,
                cloth,
                model: core_model,
            },
            model,
        })
    }
}

/// The `shot` answer: the guidance, with the keys of `cuesight shot --json`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShotAnswer {
    /// The tip offset asked for (ball radii), echoed under `stroke`.
    pub tip: [f32; 2],
    /// The model asked for, by its wire name.
    pub model: ModelName,
    /// The guidance.
    pub guidance: Guidance,
}

impl ShotAnswer {
    /// The answer line, `{"shot":{...}}` and its `\n`, into `out`, as the session writes it.
    pub fn write(&self, out: &mut AnswerLine) {
        write_shot(out, self.tip, self.model, &self.guidance);
    }
}

/// Writes the `shot` answer line for `guidance` into `out`: `{"shot":{...}}` and its
/// `\n`, byte for byte what serde-json-core wrote for a [`ShotAnswer`] (its
/// `Serialize` is kept for hosts, and as the tests' oracle), by hand (`encode.rs`);
/// if it does not fit, the `internal` error line.
#[inline(never)]
pub(crate) fn write_shot(out: &mut AnswerLine, tip: [f32; 2], model: ModelName, g: &Guidance) {
    let mut w = Writer::new(out);
    w.tag("shot");
    w.open();
    w.str_field("mode", if g.solve.is_some() { "solve" } else { "play" });

    let stroke = &g.stroke;
    w.key("stroke");
    w.open();
    w.f32_field("cue_speed", stroke.cue_speed);
    w.f32s_field("tip", &tip);
    w.f32_field("aim_deg", stroke.aim_deg);
    w.f32s_field("aim", &stroke.aim);
    w.f32_field("launch_speed", stroke.launch_speed);
    w.f32s_field("launch_spin", &stroke.launch_spin);
    w.close();

    w.key("solve");
    match &g.solve {
        Some(solve) => {
            let a = &solve.solution;
            w.open();
            w.u32_field("object", solve.target.object as u32);
            w.u32_field("pocket", solve.target.pocket as u32);
            w.f32_field("aim_deg", solve.aim_deg);
            w.f32_field("naive_aim_deg", solve.naive_aim_deg);
            w.f32_field("correction_deg", a.correction_deg);
            // m, as the CLI reports it (the solver's figure is in mm).
            w.f32_field("correction_offset", 1e-3 * a.correction_mm);
            w.key("thinner");
            w.bool(a.thinner);
            w.f32_field("cut_deg", a.cut_angle_deg);
            w.f32s_field("ghost_ball", &xy(a.ghost_ball));
            w.f32s_field("naive_ghost_ball", &xy(a.naive_ghost_ball));
            w.u32_field("evaluations", a.evaluations);
            w.f32_field("residual", a.residual);
            w.close();
        }
        None => w.null(),
    }

    w.key("contact");
    match &g.contact {
        Some(c) => {
            w.open();
            w.u32_field("ball", c.ball as u32);
            w.f32_field("time", c.time);
            w.f32s_field("cue_position", &c.cue_position);
            w.f32s_field("line_of_centres", &c.line_of_centres);
            w.f32_field("cut_deg", c.cut_deg);
            w.f32_field("speed", c.speed);
            w.f32s_field("spin", &c.spin);
            w.str_field("model", model.name());
            w.str_field("model_used", c.model_used.name());
            w.key("error_estimate");
            optional_f32(&mut w, c.error_estimate);
            w.str_field("regime", RegimeName::from(c.regime).name());
            w.f32_field("throw_deg", c.throw_deg);
            w.close();
        }
        None => w.null(),
    }

    w.key("cue_ball");
    write_ball(&mut w, &g.cue_ball);
    w.key("object_ball");
    match &g.object_ball {
        Some(ball) => write_ball(&mut w, ball),
        None => w.null(),
    }

    w.key("target");
    match &g.target {
        Some(t) => {
            w.open();
            w.u32_field("object", t.target.object as u32);
            w.u32_field("pocket", t.target.pocket as u32);
            w.key("pocketed");
            w.bool(t.pocketed);
            w.key("miss");
            optional_f32(&mut w, t.miss);
            w.close();
        }
        None => w.null(),
    }
    w.close();
    w.close();
    if !w.finish() {
        Answer::Error(ErrorAnswer::internal()).write(out);
    }
}

/// A number or `null`.
fn optional_f32(w: &mut Writer<'_>, value: Option<f32>) {
    match value {
        Some(value) => w.f32(value),
        None => w.null(),
    }
}

/// One ball's path: the keys of `BallPart`.
fn write_ball(w: &mut Writer<'_>, b: &BallPath) {
    let m = &b.motion;
    w.open();
    w.u32_field("ball", b.ball as u32);
    w.f32s_field("start", &xy(m.start));
    w.f32s_field("velocity", &b.velocity);
    w.f32s_field("spin", &m.initial_spin.to_array());
    w.f32_field("hop_height", m.hop_height);
    w.f32_field("air_time", m.air_time);
    w.f32s_field("landing", &xy(m.landing()));
    w.f32_field("sliding_time", m.sliding_time);
    w.f32s_field("rolling_start", &xy(m.rolling_start()));
    w.f32s_field("rolling_velocity", &xy(m.rolling_velocity));
    w.f32_field("rolling_speed", m.rolling_velocity.length());
    w.f32_field("rolling_direction_deg", b.rolling_direction_deg);
    w.f32_field("stop_time", m.stop_time());
    w.f32s_field("rest", &xy(m.rest()));
    w.str_field("end", b.end.end.name());
    w.f32_field("end_time", b.end.time);
    w.f32s_field("end_position", &b.end_position);
    w.key("pocket");
    match b.end.pocket {
        Some(pocket) => w.u32(pocket as u32),
        None => w.null(),
    }
    w.close();
}

/// `[x, y]` of a vector.
fn xy(v: cuesight::Vec3) -> [f32; 2] {
    [v.x, v.y]
}

struct StrokePart<'a>(&'a ShotAnswer);

impl Serialize for StrokePart<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let g = &self.0.guidance.stroke;
        let mut s = serializer.serialize_struct("Stroke", 6)?;
        s.serialize_field("cue_speed", &g.cue_speed)?;
        s.serialize_field("tip", &self.0.tip)?;
        s.serialize_field("aim_deg", &g.aim_deg)?;
        s.serialize_field("aim", &g.aim)?;
        s.serialize_field("launch_speed", &g.launch_speed)?;
        s.serialize_field("launch_spin", &g.launch_spin)?;
        s.end()
    }
}

struct SolvePart<'a>(&'a guidance::SolveGuide);

impl Serialize for SolvePart<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let g = self.0;
        let a = &g.solution;
        let mut s = serializer.serialize_struct("Solve", 12)?;
        s.serialize_field("object", &(g.target.object as u32))?;
        s.serialize_field("pocket", &(g.target.pocket as u32))?;
        s.serialize_field("aim_deg", &g.aim_deg)?;
        s.serialize_field("naive_aim_deg", &g.naive_aim_deg)?;
        s.serialize_field("correction_deg", &a.correction_deg)?;
        // m, as the CLI reports it (the solver's figure is in mm).
        s.serialize_field("correction_offset", &(1e-3 * a.correction_mm))?;
        s.serialize_field("thinner", &a.thinner)?;
        s.serialize_field("cut_deg", &a.cut_angle_deg)?;
        s.serialize_field("ghost_ball", &xy(a.ghost_ball))?;
        s.serialize_field("naive_ghost_ball", &xy(a.naive_ghost_ball))?;
        s.serialize_field("evaluations", &a.evaluations)?;
        s.serialize_field("residual", &a.residual)?;
        s.end()
    }
}

struct ContactPart<'a>(&'a guidance::ContactGuide, ModelName);

impl Serialize for ContactPart<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let c = self.0;
        let mut s = serializer.serialize_struct("Contact", 12)?;
        s.serialize_field("ball", &(c.ball as u32))?;
        s.serialize_field("time", &c.time)?;
        s.serialize_field("cue_position", &c.cue_position)?;
        s.serialize_field("line_of_centres", &c.line_of_centres)?;
        s.serialize_field("cut_deg", &c.cut_deg)?;
        s.serialize_field("speed", &c.speed)?;
        s.serialize_field("spin", &c.spin)?;
        s.serialize_field("model", &self.1)?;
        s.serialize_field("model_used", &ModelName::from(c.model_used))?;
        s.serialize_field("error_estimate", &c.error_estimate)?;
        s.serialize_field("regime", &RegimeName::from(c.regime))?;
        s.serialize_field("throw_deg", &c.throw_deg)?;
        s.end()
    }
}

struct BallPart<'a>(&'a BallPath);

impl Serialize for BallPart<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let b = self.0;
        let m = &b.motion;
        let mut s = serializer.serialize_struct("Ball", 18)?;
        s.serialize_field("ball", &(b.ball as u32))?;
        s.serialize_field("start", &xy(m.start))?;
        s.serialize_field("velocity", &b.velocity)?;
        s.serialize_field("spin", &m.initial_spin.to_array())?;
        s.serialize_field("hop_height", &m.hop_height)?;
        s.serialize_field("air_time", &m.air_time)?;
        s.serialize_field("landing", &xy(m.landing()))?;
        s.serialize_field("sliding_time", &m.sliding_time)?;
        s.serialize_field("rolling_start", &xy(m.rolling_start()))?;
        s.serialize_field("rolling_velocity", &xy(m.rolling_velocity))?;
        s.serialize_field("rolling_speed", &m.rolling_velocity.length())?;
        s.serialize_field("rolling_direction_deg", &b.rolling_direction_deg)?;
        s.serialize_field("stop_time", &m.stop_time())?;
        s.serialize_field("rest", &xy(m.rest()))?;
        s.serialize_field("end", end_name(b.end.end))?;
        s.serialize_field("end_time", &b.end.time)?;
        s.serialize_field("end_position", &b.end_position)?;
        s.serialize_field("pocket", &b.end.pocket.map(|p| p as u32))?;
        s.end()
    }
}

const fn end_name(end: End) -> &'static str {
    end.name()
}

struct TargetPart<'a>(&'a guidance::TargetGuide);

impl Serialize for TargetPart<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let t = self.0;
        let mut s = serializer.serialize_struct("Target", 4)?;
        s.serialize_field("object", &(t.target.object as u32))?;
        s.serialize_field("pocket", &(t.target.pocket as u32))?;
        s.serialize_field("pocketed", &t.pocketed)?;
        s.serialize_field("miss", &t.miss)?;
        s.end()
    }
}

impl Serialize for ShotAnswer {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let g = &self.guidance;
        let mut s = serializer.serialize_struct("Shot", 7)?;
        s.serialize_field("mode", if g.solve.is_some() { "solve" } else { "play" })?;
        s.serialize_field("stroke", &StrokePart(self))?;
        s.serialize_field("solve", &g.solve.as_ref().map(SolvePart))?;
        s.serialize_field(
            "contact",
            &g.contact.as_ref().map(|c| ContactPart(c, self.model)),
        )?;
        s.serialize_field("cue_ball", &BallPart(&g.cue_ball))?;
        s.serialize_field("object_ball", &g.object_ball.as_ref().map(BallPart))?;
        s.serialize_field("target", &g.target.as_ref().map(TargetPart))?;
        s.end()
    }
}

impl Serialize for Shot {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let options = [
            ("aim", self.aim),
            ("mu_cloth", self.mu_cloth),
            ("mu_roll", self.mu_roll),
            ("cue_mass", self.cue_mass),
            ("tip_restitution", self.tip_restitution),
        ];
        let given = options.iter().filter(|(_, v)| v.is_some()).count()
            + usize::from(self.object.is_some())
            + usize::from(self.pocket.is_some());
        let mut s = serializer.serialize_struct("Shot", 5 + given + self.with.count())?;
        s.serialize_field("table", self.table.name())?;
        s.serialize_field("cue", &self.cue)?;
        s.serialize_field("balls", self.balls.as_slice())?;
        s.serialize_field("speed", &self.speed)?;
        s.serialize_field("tip", &self.tip)?;
        for (key, value) in &options[..1] {
            match value {
                Some(value) => s.serialize_field(key, value)?,
                None => s.skip_field(key)?,
            }
        }
        for (key, value) in [("object", self.object), ("pocket", self.pocket)] {
            match value {
                Some(value) => s.serialize_field(key, &value)?,
                None => s.skip_field(key)?,
            }
        }
        for (key, value) in &options[1..] {
            match value {
                Some(value) => s.serialize_field(key, value)?,
                None => s.skip_field(key)?,
            }
        }
        self.with.serialize_fields(&mut s)?;
        s.end()
    }
}

#[cfg(test)]
mod tests {
    //! The hand-written answer against serde-json-core's serialization of the same
    //! [`ShotAnswer`] (the encoder it replaced): the same bytes.

    extern crate std;

    use std::format;
    use std::string::String;

    use cuesight::guidance::guide;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::encode::Writer;
    use crate::MAX_ANSWER;

    /// `{"shot": answer}`, as the session serialized it before.
    struct Tagged<'a>(&'a ShotAnswer);

    impl Serialize for Tagged<'_> {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            serializer.serialize_newtype_variant("Answer", 0, "shot", self.0)
        }
    }

    /// serde-json-core's answer line.
    fn serde_line(answer: &ShotAnswer) -> String {
        let mut buf = [0u8; MAX_ANSWER];
        let n = serde_json_core::to_slice(&Tagged(answer), &mut buf).unwrap();
        assert!(n < MAX_ANSWER);
        format!("{}\n", std::str::from_utf8(&buf[..n]).unwrap())
    }

    fn our_line(answer: &ShotAnswer) -> String {
        let mut out = AnswerLine::new();
        answer.write(&mut out);
        String::from_utf8(out.to_vec()).unwrap()
    }

    /// A random scene on a random table with a random stroke: an aim near the first
    /// object ball or a pocket to solve for.
    fn random_shot(rng: &mut ChaCha8Rng) -> Shot {
        let table = [TableName::Pool, TableName::Snooker, TableName::Carom][rng.random_range(0..3)];
        let (length, width) = match table {
            TableName::Pool => (2.54, 1.27),
            TableName::Snooker => (3.569, 1.778),
            TableName::Carom => (2.84, 1.42),
        };
        let r = table.balls().radius;
        let mut centres: std::vec::Vec<[f32; 2]> = std::vec::Vec::new();
        let count = rng.random_range(2..=16);
        while centres.len() < count {
            let p = [
                rng.random_range(2.0 * r..length - 2.0 * r),
                rng.random_range(2.0 * r..width - 2.0 * r),
            ];
            if centres
                .iter()
                .all(|c| (c[0] - p[0]).hypot(c[1] - p[1]) > 2.2 * r)
            {
                centres.push(p);
            }
        }
        let [dx, dy] = [centres[1][0] - centres[0][0], centres[1][1] - centres[0][1]];
        let pockets = table.table().pockets().len() as u32;
        let solve = pockets > 0 && rng.random_bool(0.5);
        let models = ["ideal", "kim", "kim-grip", "seed-exact", "exact", "auto"];
        let with = Overrides {
            model: ModelName::from_name(models[rng.random_range(0..models.len())]),
            mu: Some(rng.random_range(0.0..0.1)),
            ..Overrides::default()
        };
        Shot {
            table,
            cue: centres[0],
            balls: centres[1..].iter().copied().collect(),
            speed: rng.random_range(0.2..7.0),
            tip: [rng.random_range(-0.3..0.3), rng.random_range(-0.35..0.35)],
            aim: (!solve).then(|| dy.atan2(dx).to_degrees() + rng.random_range(-4.0..4.0)),
            object: None,
            pocket: (pockets > 0 && (solve || rng.random_bool(0.5)))
                .then(|| rng.random_range(0..pockets)),
            mu_cloth: None,
            mu_roll: None,
            cue_mass: None,
            tip_restitution: None,
            with,
        }
    }

    #[test]
    fn answers_are_serde_json_cores_bytes() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let defaults = Defaults::POOL;
        let (mut guided, mut solved, mut longest) = (0, 0, 0);
        for _ in 0..3000 {
            let shot = random_shot(&mut rng);
            let Ok(prepared) = shot.prepare(&defaults) else {
                continue;
            };
            let Ok(guidance) = guide(
                &prepared.scene,
                shot.speed,
                prepared.tip,
                prepared.aim,
                &prepared.setup,
            ) else {
                continue;
            };
            guided += 1;
            solved += usize::from(guidance.solve.is_some());
            let answer = ShotAnswer {
                tip: shot.tip,
                model: prepared.model,
                guidance,
            };
            let ours = our_line(&answer);
            assert_eq!(ours, serde_line(&answer));
            longest = longest.max(ours.len());
            // Every optional part absent, and numbers that are not finite (`null`).
            let mut bare = answer.clone();
            bare.guidance.solve = None;
            bare.guidance.contact = None;
            bare.guidance.object_ball = None;
            bare.guidance.target = None;
            bare.guidance.stroke.aim_deg = f32::NAN;
            bare.guidance.stroke.launch_speed = f32::INFINITY;
            bare.guidance.cue_ball.end.pocket = Some(usize::MAX);
            assert_eq!(our_line(&bare), serde_line(&bare));
        }
        std::println!("{guided} guided ({solved} solved), longest answer {longest} bytes");
        assert!(guided > 1000 && solved > 100, "{guided} {solved}");
    }

    #[test]
    fn numbers_are_written_as_serde_json_core_writes_them() {
        use serde::ser::SerializeTuple;
        struct Both(f32, u32);
        impl Serialize for Both {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let mut t = serializer.serialize_tuple(2)?;
                t.serialize_element(&self.0)?;
                t.serialize_element(&self.1)?;
                t.end()
            }
        }
        let floats = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            2.0,
            0.1,
            1e-7,
            1.5e10,
            123_456_790.0,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            f32::from_bits(1),
            -f32::from_bits(0x007f_ffff),
            f32::EPSILON,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let randoms: std::vec::Vec<f32> =
            (0..20_000).map(|_| f32::from_bits(rng.random())).collect();
        let ints = [0, 1, 9, 10, 99, 100, 65_535, 4_294_967_295];
        for (i, x) in floats.into_iter().chain(randoms).enumerate() {
            let n = if i < ints.len() {
                ints[i]
            } else {
                rng.random()
            };
            let mut buf = [0u8; 64];
            let len = serde_json_core::to_slice(&Both(x, n), &mut buf).unwrap();
            let mut out = AnswerLine::new();
            let mut w = Writer::new(&mut out);
            w.raw(b"[");
            w.f32(x);
            w.raw(b",");
            w.u32(n);
            w.raw(b"]");
            assert!(w.finish());
            assert_eq!(&out[..out.len() - 1], &buf[..len], "{x:?} {n}");
        }
    }

    #[test]
    fn an_answer_that_does_not_fit_is_not_cut() {
        let mut out = AnswerLine::new();
        let mut w = Writer::new(&mut out);
        w.raw(&[b' '; MAX_ANSWER - 1]);
        assert!(w.finish(), "MAX_ANSWER - 1 bytes and the newline fit");
        let mut w = Writer::new(&mut out);
        w.raw(&[b' '; MAX_ANSWER]);
        assert!(!w.finish(), "no room for the newline");
        assert!(out.is_empty());
        let mut w = Writer::new(&mut out);
        w.raw(&[b' '; MAX_ANSWER - 4]);
        w.raw(b"12345");
        assert!(!w.finish(), "a piece that does not fit");
        assert!(out.is_empty());
    }
}
