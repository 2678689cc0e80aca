//! What `cuesight shot` reads: the scene file (TOML or JSON, one schema), the flags that
//! override it, and their resolution into a validated core scene and shot set-up.
//!
//! A scene file holds the same keys as the flags (snake case), all optional:
//!
//! ```toml
//! table = "pool"            # pool | snooker | carom, or { length, width, corner_mouth, side_mouth } (m)
//! radius = 0.028575         # ball radius (m); default: the table's ball set (pool balls for a custom table)
//! mass = 0.17               # ball mass (kg)
//! cue = [0.635, 0.635]      # cue-ball centre (m, table frame)
//! balls = [[1.6, 0.9]]      # the other balls, numbered 1, 2, ... in this order
//! object = 1                # the ball to pocket (default 1)
//! pocket = "top-right"      # a pocket name or index
//! speed = 3.0               # cue speed at the tip impact (m/s)
//! tip = [0.0, 0.2]          # tip offset (side right, height up) in ball radii
//! aim = 12.5                # aim (degrees counter-clockwise from +x); none: solve for it
//! model = "auto"            # ideal | kim | kim-grip | exact | auto
//! tolerance = 1e-3          # auto's accepted error, relative to the speed, in (0, 1]
//! mu = 0.05                 # ball-ball friction; also restitution, mu_s, mu_cloth,
//!                           # mu_roll, cue_mass, tip_restitution
//! ```

use std::fmt;
use std::path::{Path, PathBuf};

use cuesight::shot::ShotSetup;
use cuesight::strike::{Cue, TipOffset};
use cuesight::table::{BallSet, Scene, Table, MAX_BALLS};
use cuesight::travel::Cloth;
use cuesight::{Model, Params, Vec3};
use serde::de::{self, Deserializer, MapAccess, Visitor};
use serde::Deserialize;

use super::ShotError;

/// A table preset, as `--table` names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum TablePreset {
    /// 9-ft pool table (2.54 × 1.27 m), pool balls.
    Pool,
    /// Full-size snooker table (3.569 × 1.778 m), snooker balls.
    Snooker,
    /// Carom match table (2.84 × 1.42 m, no pockets), carom balls.
    Carom,
}

impl TablePreset {
    const ALL: [TablePreset; 3] = [TablePreset::Pool, TablePreset::Snooker, TablePreset::Carom];

    /// Lower-case name.
    pub const fn name(self) -> &'static str {
        match self {
            TablePreset::Pool => "pool",
            TablePreset::Snooker => "snooker",
            TablePreset::Carom => "carom",
        }
    }

    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    fn table(self) -> Table {
        match self {
            TablePreset::Pool => Table::pool(),
            TablePreset::Snooker => Table::snooker(),
            TablePreset::Carom => Table::carom(),
        }
    }

    fn balls(self) -> BallSet {
        match self {
            TablePreset::Pool => BallSet::POOL,
            TablePreset::Snooker => BallSet::SNOOKER,
            TablePreset::Carom => BallSet::CAROM,
        }
    }
}

/// A table in a scene file: a preset name or explicit dimensions.
#[derive(Clone, Debug, PartialEq)]
pub enum TableSpec {
    /// `table = "pool"`.
    Preset(String),
    /// `table = { length = 2.54, width = 1.27, corner_mouth = 0.116, side_mouth = 0.13 }`.
    Custom(CustomTable),
}

/// Explicit table dimensions (m).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CustomTable {
    /// Playing-surface length (along `x`).
    pub length: f32,
    /// Playing-surface width (along `y`).
    pub width: f32,
    /// Corner pocket mouth width (0: no corner pockets).
    #[serde(default)]
    pub corner_mouth: f32,
    /// Side pocket mouth width (0: no side pockets).
    #[serde(default)]
    pub side_mouth: f32,
}

impl<'de> Deserialize<'de> for TableSpec {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TableVisitor;
        impl<'de> Visitor<'de> for TableVisitor {
            type Value = TableSpec;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a table name (pool, snooker, carom) or { length, width, corner_mouth, side_mouth }")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<TableSpec, E> {
                Ok(TableSpec::Preset(v.to_owned()))
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<TableSpec, A::Error> {
                CustomTable::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(TableSpec::Custom)
            }
        }
        deserializer.deserialize_any(TableVisitor)
    }
}

/// A pocket, by index or by name (see [`pocket_name`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PocketRef {
    /// Index in the table's pocket list.
    Index(usize),
    /// A name such as `top-right`.
    Name(String),
}

impl PocketRef {
    /// Parse a `--pocket` value: a non-negative integer is an index, anything else a name.
    pub fn parse(text: &str) -> Result<Self, String> {
        let text = text.trim();
        if text.is_empty() {
            return Err("pocket needs an index or a name".to_owned());
        }
        Ok(match text.parse::<usize>() {
            Ok(index) => PocketRef::Index(index),
            Err(_) => PocketRef::Name(text.to_owned()),
        })
    }
}

impl<'de> Deserialize<'de> for PocketRef {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct PocketVisitor;
        impl Visitor<'_> for PocketVisitor {
            type Value = PocketRef;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a pocket index (0, 1, ...) or name (e.g. \"top-right\")")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<PocketRef, E> {
                Ok(PocketRef::Index(usize::try_from(v).unwrap_or(usize::MAX)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<PocketRef, E> {
                usize::try_from(v)
                    .map(PocketRef::Index)
                    .map_err(|_| E::invalid_value(de::Unexpected::Signed(v), &self))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<PocketRef, E> {
                Ok(PocketRef::Name(v.to_owned()))
            }
        }
        deserializer.deserialize_any(PocketVisitor)
    }
}

/// The contents of a scene file (every key optional; unknown keys are errors).
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Table preset or dimensions.
    pub table: Option<TableSpec>,
    /// Ball radius (m).
    pub radius: Option<f32>,
    /// Ball mass (kg).
    pub mass: Option<f32>,
    /// Cue-ball centre (m).
    pub cue: Option<[f32; 2]>,
    /// The other balls' centres (m), numbered from 1.
    pub balls: Option<Vec<[f32; 2]>>,
    /// Ball to pocket.
    pub object: Option<usize>,
    /// Pocket to send it to.
    pub pocket: Option<PocketRef>,
    /// Cue speed (m/s).
    pub speed: Option<f32>,
    /// Tip offset (side, height) in ball radii.
    pub tip: Option<[f32; 2]>,
    /// Aim (degrees).
    pub aim: Option<f32>,
    /// Collision model name.
    pub model: Option<String>,
    /// `auto`'s tolerance.
    pub tolerance: Option<f32>,
    /// Ball–ball friction μ.
    pub mu: Option<f32>,
    /// Restitution e*.
    pub restitution: Option<f32>,
    /// Object-ball/table static friction μ_s.
    pub mu_s: Option<f32>,
    /// Ball–cloth sliding friction μ_c.
    pub mu_cloth: Option<f32>,
    /// Rolling resistance μ_r.
    pub mu_roll: Option<f32>,
    /// Cue mass (kg).
    pub cue_mass: Option<f32>,
    /// Cue-tip restitution.
    pub tip_restitution: Option<f32>,
}

impl SceneFile {
    /// Read a scene file; the format follows the extension (`.toml` or `.json`).
    pub fn read(path: &Path) -> Result<Self, ShotError> {
        let shown = path.display();
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_toml = match extension.as_deref() {
            Some("toml") => true,
            Some("json") => false,
            _ => {
                return Err(ShotError::usage(format!(
                    "scene file {shown}: expected a .toml or .json file"
                )))
            }
        };
        let text = crate::cli::read_input(path)
            .and_then(|bytes| {
                String::from_utf8(bytes).map_err(|_| "stream did not contain valid UTF-8".into())
            })
            .map_err(|e| ShotError::usage(format!("scene file {shown}: {e}")))?;
        let parsed = if is_toml {
            Self::from_toml(&text)
        } else {
            Self::from_json(&text)
        };
        parsed.map_err(|e| ShotError::usage(format!("scene file {shown}: {e}")))
    }

    /// Parse TOML text; the error is one line, with the line number.
    pub fn from_toml(text: &str) -> Result<Self, String> {
        toml::from_str(text).map_err(|e| {
            let message = one_line(e.message());
            match e.span() {
                Some(span) => {
                    let line = text[..span.start.min(text.len())].matches('\n').count() + 1;
                    format!("line {line}: {message}")
                }
                None => message,
            }
        })
    }

    /// Parse JSON text; the error is one line, with the line number.
    pub fn from_json(text: &str) -> Result<Self, String> {
        serde_json::from_str(text).map_err(|e| one_line(&e.to_string()))
    }
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Parse `X,Y` (two comma-separated numbers). Only the syntax is checked here.
pub fn parse_pair(text: &str) -> Result<[f32; 2], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() != 2 {
        return Err(format!(
            "expected two comma-separated numbers X,Y, got {}",
            parts.len()
        ));
    }
    let mut pair = [0.0; 2];
    for (value, part) in pair.iter_mut().zip(&parts) {
        *value = part
            .parse::<f32>()
            .map_err(|_| format!("'{part}' is not a number"))?;
    }
    Ok(pair)
}

/// Parse a `--model` name.
pub fn parse_model(name: &str) -> Result<Model, String> {
    Model::from_name(name.trim()).ok_or_else(|| {
        format!(
            "unknown model '{name}', expected one of {}, auto",
            Model::ALL.map(Model::name).join(", ")
        )
    })
}

/// Flags of `cuesight shot`; each one given overrides the scene file's key.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct Flags {
    /// Scene file (.toml or .json) with any of the keys below (snake case); flags
    /// override it. See docs/shot-cli.md.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Contact parameters from a JSON file (mu, mu_b, mu_c, restitution, mu_s, radius,
    /// mass; what `cuesight calibrate --json` prints). Its values override the scene
    /// file's; flags override both.
    #[arg(long, value_name = "FILE")]
    pub params: Option<PathBuf>,
    /// Table preset [default: pool]; sets the ball size too.
    #[arg(long, value_enum)]
    pub table: Option<TablePreset>,
    /// Cue-ball centre (m, table frame: x along the length, y across, origin at a corner
    /// of the playing surface).
    #[arg(long, value_name = "X,Y", value_parser = parse_pair, allow_hyphen_values = true)]
    pub cue: Option<[f32; 2]>,
    /// Another ball's centre (m); repeat for each ball, numbered 1, 2, ... in order.
    /// Given once or more, replaces the file's balls.
    #[arg(long = "ball", value_name = "X,Y", value_parser = parse_pair,
          allow_hyphen_values = true)]
    pub balls: Vec<[f32; 2]>,
    /// Ball to pocket (1 = first --ball) [default: 1].
    #[arg(long, value_name = "N")]
    pub object: Option<usize>,
    /// Pocket: index (0..5 on pool and snooker) or name (bottom-left, bottom-right,
    /// top-left, top-right, bottom-side, top-side; the table drawn with x to the right).
    #[arg(long, value_name = "N|NAME", value_parser = PocketRef::parse)]
    pub pocket: Option<PocketRef>,
    /// Cue speed at the tip impact (m/s) [default: 2.5].
    #[arg(long, value_name = "V_CUE", allow_negative_numbers = true)]
    pub speed: Option<f32>,
    /// Tip offset in ball radii: SIDE > 0 right english, HEIGHT > 0 follow; |b| <= 0.5
    /// [default: 0,0].
    #[arg(long, value_name = "SIDE,HEIGHT", value_parser = parse_pair,
          allow_hyphen_values = true)]
    pub tip: Option<[f32; 2]>,
    /// Aim direction: degrees counter-clockwise from the table's +x axis. Without it
    /// (or with --solve) the aim is solved for the object ball and pocket.
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        conflicts_with = "solve"
    )]
    pub aim: Option<f32>,
    /// Solve the aim that pockets the object ball (ignores an aim in the file).
    #[arg(long)]
    pub solve: bool,
    /// Collision model: ideal, kim, kim-grip, seed-exact, exact, or auto (the cheapest
    /// tier within 1e-3) [default: auto].
    #[arg(long, value_name = "NAME", value_parser = parse_model)]
    pub model: Option<Model>,
    /// With model auto: the accepted error of the tier it picks, relative to the speed,
    /// in (0, 1] [default: 1e-3].
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub tolerance: Option<f32>,
    /// Ball–ball friction μ [default: 0.05].
    #[arg(long, allow_negative_numbers = true)]
    pub mu: Option<f32>,
    /// Energetic coefficient of restitution e* [default: 0.95].
    #[arg(long, allow_negative_numbers = true)]
    pub restitution: Option<f32>,
    /// Object-ball/table static friction μ_s during the impact [default: 0.3].
    #[arg(long, allow_negative_numbers = true)]
    pub mu_s: Option<f32>,
    /// Ball–cloth sliding friction μ_c [default: 0.2].
    #[arg(long, allow_negative_numbers = true)]
    pub mu_cloth: Option<f32>,
    /// Rolling resistance μ_r [default: 0.01].
    #[arg(long, allow_negative_numbers = true)]
    pub mu_roll: Option<f32>,
    /// Ball radius (m) [default: the table's ball set].
    #[arg(long, allow_negative_numbers = true)]
    pub radius: Option<f32>,
    /// Ball mass (kg) [default: the table's ball set].
    #[arg(long, allow_negative_numbers = true)]
    pub mass: Option<f32>,
    /// Cue mass (kg) [default: 0.54].
    #[arg(long, allow_negative_numbers = true)]
    pub cue_mass: Option<f32>,
    /// Cue-tip coefficient of restitution [default: 0.75].
    #[arg(long, allow_negative_numbers = true)]
    pub tip_restitution: Option<f32>,
    /// Print one JSON object (SI units, table frame) instead of the guidance.
    #[arg(long)]
    pub json: bool,
    /// Also draw the table, balls, ghost ball, paths and pocket to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// Default cue speed (m/s).
pub const DEFAULT_SPEED: f32 = 2.5;
/// Tolerance of `--model auto`.
pub const AUTO_TOLERANCE: f32 = 1e-3;

/// A validated shot request.
#[derive(Clone, Debug)]
pub struct Request {
    /// Table name (`pool`, `snooker`, `carom` or `custom`).
    pub table_name: &'static str,
    /// The scene (ball 0: cue ball).
    pub scene: Scene,
    /// Ball mass (kg).
    pub mass: f32,
    /// Object ball (for solving and for the report's target).
    pub object: Option<usize>,
    /// Chosen pocket index.
    pub pocket: Option<usize>,
    /// Cue speed (m/s).
    pub speed: f32,
    /// Tip offset in ball radii (side, height).
    pub tip_radii: [f32; 2],
    /// Tip offset.
    pub tip: TipOffset,
    /// Aim (degrees) to play; `None`: solve.
    pub aim_deg: Option<f32>,
    /// Model, cue, cloth and collision parameters.
    pub setup: ShotSetup,
}

impl Request {
    /// Merge the scene file (if any) and the flags, and validate everything.
    pub fn resolve(flags: &Flags) -> Result<Self, ShotError> {
        let file = match &flags.scene {
            Some(path) => SceneFile::read(path)?,
            None => SceneFile::default(),
        };
        Self::from_parts(&file, flags)
    }

    /// As [`Request::resolve`], from an already parsed file.
    pub fn from_parts(file: &SceneFile, flags: &Flags) -> Result<Self, ShotError> {
        let invalid = |e: cuesight::Error| ShotError::invalid(e.to_string());
        // `--params`: between the scene file and the flags.
        let contact = match &flags.params {
            Some(path) => crate::calibrate::ParamsFile::read(path).map_err(ShotError::usage)?,
            None => crate::calibrate::ParamsFile::default(),
        };
        let file = &SceneFile {
            radius: contact.radius.or(file.radius),
            mass: contact.mass.or(file.mass),
            mu: contact.mu.or(file.mu),
            restitution: contact.restitution.or(file.restitution),
            mu_s: contact.mu_s.or(file.mu_s),
            ..file.clone()
        };
        // Table and ball set.
        let (table_name, preset, custom) = match (flags.table, &file.table) {
            (Some(preset), _) => (preset.name(), Some(preset), None),
            (None, None) => ("pool", Some(TablePreset::Pool), None),
            (None, Some(TableSpec::Preset(name))) => {
                let preset = TablePreset::from_name(name).ok_or_else(|| {
                    ShotError::usage(format!(
                        "unknown table '{name}', expected pool, snooker, carom or {{ length, width, corner_mouth, side_mouth }}"
                    ))
                })?;
                (preset.name(), Some(preset), None)
            }
            (None, Some(TableSpec::Custom(custom))) => ("custom", None, Some(*custom)),
        };
        let set = preset.map_or(BallSet::POOL, TablePreset::balls);
        let radius = flags.radius.or(file.radius).unwrap_or(set.radius);
        let mass = flags.mass.or(file.mass).unwrap_or(set.mass);
        let params = Params::POOL.with_ball(radius, mass).map_err(invalid)?;
        let table = match (preset, custom) {
            (Some(preset), _) if radius == set.radius => preset.table(),
            (Some(preset), _) => {
                // Same table, pocket targets moved in by the given radius.
                let t = preset.table();
                let (corner, side) = mouths(&t);
                Table::new(t.length(), t.width(), corner, side, radius).map_err(invalid)?
            }
            (None, Some(c)) => Table::new(c.length, c.width, c.corner_mouth, c.side_mouth, radius)
                .map_err(invalid)?,
            (None, None) => Table::pool(),
        };

        // Balls.
        let cue = flags.cue.or(file.cue).ok_or_else(|| {
            ShotError::usage("no cue ball: give --cue X,Y or `cue` in the scene file")
        })?;
        let others: Vec<[f32; 2]> = if flags.balls.is_empty() {
            file.balls.clone().unwrap_or_default()
        } else {
            flags.balls.clone()
        };
        let mut positions = vec![cue];
        positions.extend(others);
        check_balls(&table, radius, &positions)?;
        let mut scene = Scene::new(table, radius, cue).map_err(invalid)?;
        for p in &positions[1..] {
            scene.add_ball(*p).map_err(invalid)?;
        }

        // Object ball and pocket.
        let object = flags.object.or(file.object);
        if let Some(object) = object {
            check_object(object, positions.len())?;
        }
        let pocket = match flags.pocket.clone().or_else(|| file.pocket.clone()) {
            None => None,
            Some(reference) => Some(resolve_pocket(scene.table(), table_name, &reference)?),
        };

        // Stroke.
        let speed = flags.speed.or(file.speed).unwrap_or(DEFAULT_SPEED);
        let tip_radii = flags.tip.or(file.tip).unwrap_or([0.0, 0.0]);
        let tip = check_tip(tip_radii, radius)?;
        let aim_deg = if flags.solve {
            None
        } else {
            flags.aim.or(file.aim)
        };
        if let Some(aim) = aim_deg {
            if !aim.is_finite() {
                return Err(ShotError::invalid("aim must be a finite number (degrees)"));
            }
        }

        // Physics.
        let model = match (flags.model, &file.model) {
            (Some(model), _) => model,
            (None, Some(name)) => parse_model(name).map_err(ShotError::usage)?,
            (None, None) => Model::Auto {
                tolerance: AUTO_TOLERANCE,
            },
        };
        let model = match (model, flags.tolerance.or(file.tolerance)) {
            // The core checks the tolerance.
            (Model::Auto { .. }, Some(tolerance)) => Model::Auto { tolerance },
            (model, Some(_)) => {
                return Err(ShotError::usage(format!(
                    "tolerance is for model auto, not {}",
                    model.name()
                )))
            }
            (model, None) => model,
        };
        let mut params = params;
        if let Some(mu) = flags.mu.or(file.mu) {
            params = params.with_mu(mu).map_err(invalid)?;
        }
        if contact.mu_b.is_some() || contact.mu_c.is_some() {
            // μ(v) from the params file, its `a` the μ above.
            let (b, c) = (contact.mu_b.unwrap_or(0.0), contact.mu_c.unwrap_or(0.0));
            if b != 0.0 || c != 0.0 {
                let law =
                    cuesight::FrictionLaw::speed_dependent(params.mu(), b, c).map_err(invalid)?;
                params = params.with_friction_law(law);
            }
        }
        if let Some(e) = flags.restitution.or(file.restitution) {
            params = params.with_restitution(e).map_err(invalid)?;
        }
        if let Some(mu_s) = flags.mu_s.or(file.mu_s) {
            params = params.with_mu_s(mu_s).map_err(invalid)?;
        }
        let cloth = Cloth::new(
            flags
                .mu_cloth
                .or(file.mu_cloth)
                .unwrap_or(Cloth::TYPICAL.sliding()),
            flags
                .mu_roll
                .or(file.mu_roll)
                .unwrap_or(Cloth::TYPICAL.rolling()),
        )
        .map_err(invalid)?;
        let cue_stick = Cue::new(
            flags
                .cue_mass
                .or(file.cue_mass)
                .unwrap_or(Cue::TYPICAL.mass()),
            flags
                .tip_restitution
                .or(file.tip_restitution)
                .unwrap_or(Cue::TYPICAL.tip_restitution()),
        )
        .map_err(invalid)?;
        // The cue speed is checked by the strike; check it here to name the flag.
        if !speed.is_finite() || speed <= 0.0 || speed > cuesight::strike::MAX_CUE_SPEED {
            return Err(ShotError::invalid(format!(
                "speed = {speed} is outside (0, {}] m/s (cue speed)",
                cuesight::strike::MAX_CUE_SPEED
            )));
        }
        Ok(Self {
            table_name,
            scene,
            mass,
            object,
            pocket,
            speed,
            tip_radii,
            tip,
            aim_deg,
            setup: ShotSetup {
                params,
                cue: cue_stick,
                cloth,
                model,
            },
        })
    }
}

/// Corner and side mouth widths of a table built by `Table::new` (its target segments
/// are as long as the mouths).
fn mouths(table: &Table) -> (f32, f32) {
    let (mut corner, mut side) = (0.0, 0.0);
    for p in table.pockets() {
        let length = (p.b - p.a).length();
        if pocket_kind(table, p.centre()).1 {
            side = length;
        } else {
            corner = length;
        }
    }
    (corner, side)
}

/// `(name, is_side)` of the pocket whose target centre is `centre`: `bottom`/`top` by
/// `y` (the table drawn with `x` to the right and `y` up), `left`/`right`/`side` by `x`.
fn pocket_kind(table: &Table, centre: Vec3) -> (&'static str, bool) {
    let top = centre.y > 0.5 * table.width();
    let third = table.length() / 3.0;
    match (centre.x < third, centre.x > 2.0 * third, top) {
        (true, _, false) => ("bottom-left", false),
        (true, _, true) => ("top-left", false),
        (_, true, false) => ("bottom-right", false),
        (_, true, true) => ("top-right", false),
        (false, false, false) => ("bottom-side", true),
        (false, false, true) => ("top-side", true),
    }
}

/// Name of pocket `index` of `table` (`top-right`, `bottom-side`, ...).
pub fn pocket_name(table: &Table, index: usize) -> &'static str {
    table
        .pockets()
        .get(index)
        .map_or("none", |p| pocket_kind(table, p.centre()).0)
}

/// "the top-right corner (pocket 3)" / "the bottom side pocket (pocket 4)".
pub fn pocket_phrase(table: &Table, index: usize) -> String {
    let name = pocket_name(table, index);
    match name.strip_suffix("-side") {
        Some(edge) => format!("the {edge} side pocket (pocket {index})"),
        None => format!("the {name} corner (pocket {index})"),
    }
}

fn resolve_pocket(
    table: &Table,
    table_name: &str,
    reference: &PocketRef,
) -> Result<usize, ShotError> {
    let count = table.pockets().len();
    if count == 0 {
        return Err(ShotError::invalid(format!(
            "pocket: the {table_name} table has no pockets"
        )));
    }
    match reference {
        PocketRef::Index(index) if *index < count => Ok(*index),
        PocketRef::Index(index) => Err(ShotError::invalid(format!(
            "pocket {index} does not exist: the {table_name} table has pockets 0..={}",
            count - 1
        ))),
        PocketRef::Name(name) => {
            let wanted = name.trim().to_ascii_lowercase();
            (0..count)
                .find(|&i| pocket_name(table, i) == wanted)
                .ok_or_else(|| {
                    let names: Vec<&str> = (0..count).map(|i| pocket_name(table, i)).collect();
                    ShotError::usage(format!(
                        "unknown pocket '{name}', expected an index 0..={} or one of {}",
                        count - 1,
                        names.join(", ")
                    ))
                })
        }
    }
}

fn check_object(object: usize, balls: usize) -> Result<(), ShotError> {
    if object == 0 {
        return Err(ShotError::invalid(
            "object 0 is the cue ball: the object ball is 1 or more",
        ));
    }
    if object >= balls {
        return Err(ShotError::invalid(if balls == 1 {
            format!("object {object} does not exist: the scene has no other ball")
        } else {
            format!(
                "object {object} does not exist: the scene has balls 1..={}",
                balls - 1
            )
        }));
    }
    Ok(())
}

fn ball_label(index: usize) -> String {
    if index == 0 {
        "cue ball".to_owned()
    } else {
        format!("ball {index}")
    }
}

/// Check the ball count, that every centre is on the playing surface and that no two
/// balls overlap, with a message naming the ball (the core's scene errors only name the
/// field).
fn check_balls(table: &Table, radius: f32, positions: &[[f32; 2]]) -> Result<(), ShotError> {
    if positions.len() > MAX_BALLS {
        return Err(ShotError::invalid(format!(
            "{} balls (cue ball included): a scene holds at most {MAX_BALLS}",
            positions.len()
        )));
    }
    for (i, p) in positions.iter().enumerate() {
        if !p[0].is_finite() || !p[1].is_finite() {
            return Err(ShotError::invalid(format!(
                "{} position must be finite numbers",
                ball_label(i)
            )));
        }
        if !table.contains(Vec3::new(p[0], p[1], 0.0), radius) {
            return Err(ShotError::invalid(format!(
                "{} at ({}, {}) is off the table: its centre must lie within [{r:.4}, {:.4}] x [{r:.4}, {:.4}] m",
                ball_label(i),
                p[0],
                p[1],
                table.length() - radius,
                table.width() - radius,
                r = radius,
            )));
        }
        for (j, q) in positions[..i].iter().enumerate() {
            let gap = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
            if gap < 2.0 * radius * (1.0 - 1e-6) {
                return Err(ShotError::invalid(format!(
                    "{} at ({}, {}) overlaps {} at ({}, {}): centres {gap:.4} m apart, less than 2R = {:.4} m",
                    ball_label(i),
                    p[0],
                    p[1],
                    ball_label(j),
                    q[0],
                    q[1],
                    2.0 * radius
                )));
            }
        }
    }
    Ok(())
}

fn check_tip(tip: [f32; 2], radius: f32) -> Result<TipOffset, ShotError> {
    let [side, height] = tip;
    if !side.is_finite() || !height.is_finite() {
        return Err(ShotError::invalid("tip must be finite numbers"));
    }
    let limit = cuesight::strike::MAX_TIP_OFFSET_FRACTION;
    if side.hypot(height) > limit + 1e-6 {
        return Err(ShotError::invalid(format!(
            "tip = ({side}, {height}) R is outside |b| <= {limit} R"
        )));
    }
    TipOffset::from_radius_fraction(side, height, radius)
        .map_err(|e| ShotError::invalid(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_parse() {
        assert_eq!(parse_pair("1,-2.5"), Ok([1.0, -2.5]));
        assert_eq!(parse_pair(" 0.5 , 1e-1"), Ok([0.5, 0.1]));
        assert!(parse_pair("1").is_err());
        assert!(parse_pair("1,2,3").is_err());
        assert!(parse_pair("1,x").unwrap_err().contains("'x'"));
    }

    #[test]
    fn pool_pockets_have_names() {
        let t = Table::pool();
        let names: Vec<&str> = (0..6).map(|i| pocket_name(&t, i)).collect();
        assert_eq!(
            names,
            [
                "bottom-left",
                "bottom-right",
                "top-left",
                "top-right",
                "bottom-side",
                "top-side"
            ]
        );
        let (corner, side) = mouths(&t);
        assert!((corner - 0.116).abs() < 1e-6 && (side - 0.13).abs() < 1e-6);
    }

    #[test]
    fn toml_and_json_read_the_same_scene() {
        let toml = "table = \"snooker\"\ncue = [1, 0.5]\nballs = [[2.0, 1.0]]\npocket = 3\n";
        let json = r#"{"table": "snooker", "cue": [1, 0.5], "balls": [[2.0, 1.0]], "pocket": 3}"#;
        let a = SceneFile::from_toml(toml).unwrap();
        assert_eq!(a, SceneFile::from_json(json).unwrap());
        assert_eq!(a.pocket, Some(PocketRef::Index(3)));
        let custom = SceneFile::from_toml("[table]\nlength = 2\nwidth = 1\n").unwrap();
        assert_eq!(
            custom.table,
            Some(TableSpec::Custom(CustomTable {
                length: 2.0,
                width: 1.0,
                corner_mouth: 0.0,
                side_mouth: 0.0
            }))
        );
    }

    #[test]
    fn file_errors_are_one_line_with_the_line_number() {
        let e = SceneFile::from_toml("cue = [1, 0.5]\nspeeed = 2\n").unwrap_err();
        assert!(e.starts_with("line 2: unknown field `speeed`"), "{e}");
        assert!(!e.contains('\n'));
        let e = SceneFile::from_json("{\"cue\": [1, 0.5],\n \"tip\": [1]}").unwrap_err();
        assert!(e.contains("line 2"), "{e}");
        let e = SceneFile::from_toml("table = { length = 2, width = 1, pockets = 6 }").unwrap_err();
        assert!(e.contains("unknown field `pockets`"), "{e}");
    }
}
