//! The answer of `cuesight shot`: one serializable report (what `--json` prints), its
//! human-readable guidance (`Display`), and where each ball's drawn path ends.
//!
//! Units: SI (m, s, m/s, rad/s) in the table frame (`x` along the length, `y` across,
//! origin at a corner of the playing surface, `z` up); angles in degrees, counter-
//! clockwise from `+x` (keys ending in `_deg`).

use std::fmt;

use cuesight::guidance::{BallPath, End, Guidance};
use cuesight::table::Table;
use cuesight::Vec3;
use serde::Serialize;

use super::input::{pocket_name, Request};
use super::table_report::{EventReport, TableOutcome, ThreeCushion, WholeTarget};

/// Serialize a path end by its name (`rest`, `pocket`, `cushion`).
fn end_name<S: serde::Serializer>(end: &End, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(end.name())
}

fn xy(v: Vec3) -> [f32; 2] {
    [v.x, v.y]
}

fn direction_deg(v: Vec3) -> f32 {
    if v.x == 0.0 && v.y == 0.0 {
        0.0
    } else {
        v.y.atan2(v.x).to_degrees()
    }
}

/// The table.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TableReport {
    /// `pool`, `snooker`, `carom` or `custom`.
    pub name: &'static str,
    /// Playing-surface length (m).
    pub length: f32,
    /// Playing-surface width (m).
    pub width: f32,
    /// Ball radius (m).
    pub radius: f32,
    /// Ball mass (kg).
    pub mass: f32,
    /// The pockets' target segments for a ball centre.
    pub pockets: Vec<PocketReport>,
}

/// One pocket.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PocketReport {
    /// Index.
    pub index: usize,
    /// Name (`top-right`, ...).
    pub name: &'static str,
    /// Target segment end.
    pub a: [f32; 2],
    /// Target segment end.
    pub b: [f32; 2],
    /// Target centre.
    pub centre: [f32; 2],
}

impl TableReport {
    /// Describe `table` for balls of `radius` and `mass`.
    pub fn new(name: &'static str, table: &Table, radius: f32, mass: f32) -> Self {
        Self {
            name,
            length: table.length(),
            width: table.width(),
            radius,
            mass,
            pockets: table
                .pockets()
                .iter()
                .enumerate()
                .map(|(index, p)| PocketReport {
                    index,
                    name: pocket_name(table, index),
                    a: xy(p.a),
                    b: xy(p.b),
                    centre: xy(p.centre()),
                })
                .collect(),
        }
    }
}

/// The stroke and the cue ball's launch.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StrokeReport {
    /// Cue speed at the tip impact (m/s).
    pub cue_speed: f32,
    /// Tip offset (side right, height up) in ball radii.
    pub tip: [f32; 2],
    /// Aim direction (degrees).
    pub aim_deg: f32,
    /// Unit aim direction.
    pub aim: [f32; 2],
    /// Cue-ball speed just after the strike (m/s).
    pub launch_speed: f32,
    /// Cue-ball spin just after the strike (rad/s, table frame).
    pub launch_spin: [f32; 3],
}

/// The inverse-aim solution.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolveReport {
    /// Ball pocketed.
    pub object: usize,
    /// Pocket index.
    pub pocket: usize,
    /// Pocket name.
    pub pocket_name: &'static str,
    /// Solved aim (degrees).
    pub aim_deg: f32,
    /// The naive ghost-ball aim (degrees).
    pub naive_aim_deg: f32,
    /// `aim_deg − naive_aim_deg` (degrees, counter-clockwise positive).
    pub correction_deg: f32,
    /// The correction as a sideways shift of the aim line at the object ball (m).
    pub correction_offset: f32,
    /// Whether the solved aim is a thinner cut than the ghost-ball aim.
    pub thinner: bool,
    /// Cut angle at the solved aim (degrees, signed as in `contact.cut_deg`).
    pub cut_deg: f32,
    /// Ghost ball of the solved aim: the cue-ball centre at contact (m).
    pub ghost_ball: [f32; 2],
    /// Ghost ball of the naive aim (m).
    pub naive_ghost_ball: [f32; 2],
    /// Forward-chain evaluations the solver used.
    pub evaluations: u32,
    /// Remaining miss at the pocket centre (m).
    pub residual: f32,
}

/// The first collision.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactReport {
    /// Ball hit first.
    pub ball: usize,
    /// Time from the strike (s).
    pub time: f32,
    /// Cue-ball centre at contact: the ghost ball (m).
    pub cue_position: [f32; 2],
    /// Unit line of centres, cue ball to object ball.
    pub line_of_centres: [f32; 2],
    /// Cut angle (degrees): from the line of centres to the cue ball's velocity,
    /// counter-clockwise positive (positive: the object ball goes to the right of the
    /// cue ball's line).
    pub cut_deg: f32,
    /// Cue-ball speed at contact (m/s).
    pub speed: f32,
    /// Cue-ball spin at contact (rad/s, table frame).
    pub spin: [f32; 3],
    /// Collision model asked for.
    pub model: &'static str,
    /// The tier that predicted it (what `auto` picked; otherwise the model itself).
    pub model_used: &'static str,
    /// The tier's a-priori error estimate, for `auto`.
    pub error_estimate: Option<f32>,
    /// Contact regime (`sliding`, `gripping`, ...).
    pub regime: &'static str,
    /// Throw: the object ball's departure off the line of centres (degrees, signed).
    pub throw_deg: f32,
}

/// One ball's motion after the strike (no contact) or after the impact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BallReport {
    /// Ball index (0: cue ball).
    pub ball: usize,
    /// Where the motion starts (m).
    pub start: [f32; 2],
    /// Velocity at the start (m/s; `z > 0`: the ball hops).
    pub velocity: [f32; 3],
    /// Spin at the start (rad/s).
    pub spin: [f32; 3],
    /// Hop height of the centre (m; 0: stays on the cloth).
    pub hop_height: f32,
    /// Time in the air (s).
    pub air_time: f32,
    /// Where it lands (m; the start when it does not hop).
    pub landing: [f32; 2],
    /// Sliding time on the cloth (s).
    pub sliding_time: f32,
    /// Where it starts to roll (m).
    pub rolling_start: [f32; 2],
    /// Rolling velocity (m/s).
    pub rolling_velocity: [f32; 2],
    /// Rolling speed (m/s).
    pub rolling_speed: f32,
    /// Rolling direction (degrees).
    pub rolling_direction_deg: f32,
    /// Time until it would stop (s).
    pub stop_time: f32,
    /// Where it would stop on an unbounded cloth (m).
    pub rest: [f32; 2],
    /// How its path ends: `rest`, `pocket`, or `cushion` (not modelled beyond).
    #[serde(serialize_with = "end_name")]
    pub end: End,
    /// When (s from the start).
    pub end_time: f32,
    /// Where (m).
    pub end_position: [f32; 2],
    /// Pocket it drops into (for `end = pocket`).
    pub pocket: Option<usize>,
    /// That pocket's name.
    pub pocket_name: Option<&'static str>,
}

impl BallReport {
    /// Present the core's path of one ball on `table`.
    pub fn new(path: &BallPath, table: &Table) -> Self {
        let motion = &path.motion;
        let rolling = motion.rolling_velocity;
        Self {
            ball: path.ball,
            start: xy(motion.start),
            velocity: path.velocity,
            spin: motion.initial_spin.to_array(),
            hop_height: motion.hop_height,
            air_time: motion.air_time,
            landing: xy(motion.landing()),
            sliding_time: motion.sliding_time,
            rolling_start: xy(motion.rolling_start()),
            rolling_velocity: xy(rolling),
            rolling_speed: rolling.length(),
            rolling_direction_deg: path.rolling_direction_deg,
            stop_time: motion.stop_time(),
            rest: xy(motion.rest()),
            end: path.end.end,
            end_time: path.end.time,
            end_position: path.end_position,
            pocket: path.end.pocket,
            pocket_name: path.end.pocket.map(|i| pocket_name(table, i)),
        }
    }
}

/// Whether the object ball reaches the chosen pocket.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TargetReport {
    /// Object ball.
    pub object: usize,
    /// Chosen pocket.
    pub pocket: usize,
    /// Its name.
    pub pocket_name: &'static str,
    /// Whether that ball is hit first and its centre crosses that pocket's target
    /// segment before anything else ends its path.
    pub pocketed: bool,
    /// Where its centre crosses the pocket's mouth line, from the target centre along
    /// the segment (m, signed; `null` if it does not get there).
    pub miss: Option<f32>,
}

/// Everything `cuesight shot` answers.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShotReport {
    /// `solve` (the aim was solved) or `play` (the given aim was played).
    pub mode: &'static str,
    /// The table and balls' size.
    pub table: TableReport,
    /// Ball centres before the shot (m; index 0: the cue ball).
    pub balls: Vec<[f32; 2]>,
    /// Ball–cloth sliding friction μ_c.
    pub mu_cloth: f32,
    /// Rolling resistance μ_r.
    pub mu_roll: f32,
    /// The stroke.
    pub stroke: StrokeReport,
    /// The inverse aim (mode `solve`).
    pub solve: Option<SolveReport>,
    /// The first collision (`null`: the cue ball hits nothing).
    pub contact: Option<ContactReport>,
    /// The cue ball: after the impact, or from the strike when there is no contact.
    pub cue_ball: BallReport,
    /// The object ball after the impact.
    pub object_ball: Option<BallReport>,
    /// The chosen object ball and pocket, if a pocket was chosen.
    pub target: Option<TargetReport>,
    /// Where every ball ends after the whole table is simulated ([`TableOutcome`]):
    /// `[x, y]` (m) per ball in scene order, cue ball first; `null` if pocketed.
    #[serde(rename = "final")]
    pub final_positions: Vec<Option<[f32; 2]>>,
    /// Every event of the whole table in time order.
    pub events: Vec<EventReport>,
    /// Time until the last ball stops or drops (s).
    pub table_time: f32,
    /// The three-cushion scoring check (a carom table with three balls).
    pub three_cushion: Option<ThreeCushion>,
    /// The chosen object ball and pocket on the whole table: `pocketed` only if the ball
    /// drops there before anything else touches it (the guidance's `target` follows its
    /// first path alone); `in_the_way`, the ball it meets first.
    pub target_whole_table: Option<WholeTarget>,
}

/// The report as one line of JSON (what `--json` prints).
pub fn to_json(report: &ShotReport) -> String {
    // Numbers, strings, booleans, arrays and nulls under string keys: serializing cannot
    // fail (a non-finite number would become null).
    serde_json::to_string(report).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
}

struct Point([f32; 2]);

impl fmt::Display for Point {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "({:.3}, {:.3})", self.0[0], self.0[1])
    }
}

/// "right"/"left" of the cue ball's line for a signed cut angle.
fn cut_side(cut_deg: f32) -> &'static str {
    if cut_deg >= 0.0 {
        "right"
    } else {
        "left"
    }
}

impl ShotReport {
    /// Present the core's `guidance` for `request`: the scene echo, the pocket names,
    /// and every number of the guidance.
    pub fn new(request: &Request, guidance: &Guidance, whole: &TableOutcome) -> Self {
        let scene = &request.scene;
        let table = scene.table();
        let setup = &request.setup;
        let g = guidance;
        Self {
            mode: if g.solve.is_some() { "solve" } else { "play" },
            table: TableReport::new(request.table_name, table, scene.radius(), request.mass),
            balls: scene.balls().iter().map(|b| [b.x, b.y]).collect(),
            mu_cloth: setup.cloth.sliding(),
            mu_roll: setup.cloth.rolling(),
            stroke: StrokeReport {
                cue_speed: g.stroke.cue_speed,
                tip: request.tip_radii,
                aim_deg: g.stroke.aim_deg,
                aim: g.stroke.aim,
                launch_speed: g.stroke.launch_speed,
                launch_spin: g.stroke.launch_spin,
            },
            solve: g.solve.map(|s| SolveReport {
                object: s.target.object,
                pocket: s.target.pocket,
                pocket_name: pocket_name(table, s.target.pocket),
                aim_deg: s.aim_deg,
                naive_aim_deg: s.naive_aim_deg,
                correction_deg: s.solution.correction_deg,
                correction_offset: 1e-3 * s.solution.correction_mm,
                thinner: s.solution.thinner,
                cut_deg: s.solution.cut_angle_deg,
                ghost_ball: xy(s.solution.ghost_ball),
                naive_ghost_ball: xy(s.solution.naive_ghost_ball),
                evaluations: s.solution.evaluations,
                residual: s.solution.residual,
            }),
            contact: g.contact.map(|c| ContactReport {
                ball: c.ball,
                time: c.time,
                cue_position: c.cue_position,
                line_of_centres: c.line_of_centres,
                cut_deg: c.cut_deg,
                speed: c.speed,
                spin: c.spin,
                model: c.model.name(),
                model_used: c.model_used.name(),
                error_estimate: c.error_estimate,
                regime: c.regime.name(),
                throw_deg: c.throw_deg,
            }),
            cue_ball: BallReport::new(&g.cue_ball, table),
            object_ball: g.object_ball.map(|b| BallReport::new(&b, table)),
            target: g.target.map(|t| TargetReport {
                object: t.target.object,
                pocket: t.target.pocket,
                pocket_name: pocket_name(table, t.target.pocket),
                pocketed: t.pocketed,
                miss: t.miss,
            }),
            final_positions: whole.final_positions.clone(),
            events: whole.events.clone(),
            table_time: whole.time,
            three_cushion: whole.three_cushion.clone(),
            target_whole_table: whole.target.clone(),
        }
    }

    /// The whole-table lines: events by kind, where each ball ends, the three-cushion
    /// check.
    fn whole_table(&self) -> String {
        let count = |kind: &str| self.events.iter().filter(|e| e.kind == kind).count();
        let names = self.table_for_names();
        let ends: Vec<String> = self
            .final_positions
            .iter()
            .enumerate()
            .map(|(i, end)| {
                let name = if i == 0 {
                    "cue ball".to_owned()
                } else {
                    format!("ball {i}")
                };
                match end {
                    Some(p) => format!("{name} {}", Point(*p)),
                    None => {
                        let pocket = self
                            .events
                            .iter()
                            .find(|e| e.kind == "pocket" && e.balls == [i])
                            .and_then(|e| e.pocket);
                        match pocket {
                            Some(p) => format!("{name} in {}", names.phrase(p)),
                            None => format!("{name} pocketed"),
                        }
                    }
                }
            })
            .collect();
        let mut text = format!(
            "whole table: {}, {}, {} in {:.2} s; ends: {}",
            plural(count("ball"), "collision"),
            plural(count("cushion"), "cushion"),
            plural(count("pocket"), "pocket"),
            self.table_time,
            ends.join(", ")
        );
        if let (Some(whole), Some(target)) = (&self.target_whole_table, &self.target) {
            let object = target.object;
            let rattles = match whole.jaw_contacts {
                1 => " off its jaw".to_owned(),
                n => format!(" after {n} contacts with its jaws"),
            };
            let verdict = match (whole.pocketed, whole.first, whole.in_the_way) {
                (true, ..) if whole.jaw_contacts > 0 => format!(
                    "ball {object} drops into {}{rattles}",
                    names.phrase(target.pocket)
                ),
                (true, ..) => format!("ball {object} drops into {}", names.phrase(target.pocket)),
                (false, "cushion", _) if whole.jaw_contacts > 0 => format!(
                    "the jaws of {} turn ball {object} away",
                    names.phrase(target.pocket)
                ),
                (false, "ball", Some(ball)) => {
                    format!("ball {ball} is in the way: ball {object} meets it before the pocket")
                }
                (false, "pocket", _) => format!("ball {object} drops into another pocket"),
                (false, "cushion", _) => format!("ball {object} hits a cushion first"),
                (false, "none", _) => format!("the cue ball does not reach ball {object}"),
                _ => format!("ball {object} stops short"),
            };
            text.push_str(&format!("\nwhole table, target: {verdict}"));
        }
        if let Some(check) = &self.three_cushion {
            let detail = match (check.first, check.second) {
                (Some(first), Some(second)) => format!(
                    "the cue ball touches ball {first}, then ball {second} after {}",
                    plural(check.cushions, "cushion")
                ),
                (Some(first), None) => format!("the cue ball touches ball {first} only"),
                _ => "the cue ball touches neither object ball".to_owned(),
            };
            text.push_str(&format!(
                "\nthree-cushion: {} ({detail})",
                if check.scored { "scores" } else { "no point" }
            ));
        }
        text
    }

    fn table_for_names(&self) -> TableNames<'_> {
        TableNames(&self.table)
    }

    /// How a ball's path ends, in words ("stops at (x, y)", ...).
    fn ending(&self, ball: &BallReport) -> String {
        match ball.end {
            End::Rest => format!("stops at {}", Point(ball.end_position)),
            End::Pocket => {
                let pocket = ball.pocket.unwrap_or(0);
                let verb = if ball.ball == 0 {
                    "scratches in"
                } else {
                    "pockets in"
                };
                format!("{verb} {}", self.table_for_names().phrase(pocket))
            }
            End::Cushion => format!(
                "reaches the cushion at {} (then: whole table)",
                Point(ball.end_position)
            ),
        }
    }

    fn ball_line(&self, name: &str, ball: &BallReport) -> String {
        let [vx, vy, _] = ball.velocity;
        let speed = vx.hypot(vy);
        let mut line = format!(
            "{name} leaves at {speed:.2} m/s toward {:.1}°",
            direction_deg(Vec3::new(vx, vy, 0.0))
        );
        if ball.air_time > 0.0 {
            line += &format!(
                ", hops {:.2} mm for {:.1} ms",
                1e3 * ball.hop_height,
                1e3 * ball.air_time
            );
        }
        if ball.sliding_time > 0.0 {
            line += &format!(", slides {:.2} s", ball.sliding_time);
        }
        if ball.rolling_speed > 0.0 && ball.end_time > ball.air_time + ball.sliding_time {
            line += &format!(
                ", rolls toward {:.1}° at {:.2} m/s",
                ball.rolling_direction_deg, ball.rolling_speed
            );
        }
        line += &format!(", {} after {:.2} s", self.ending(ball), ball.end_time);
        line
    }
}

/// Pocket phrases from the report's own pocket list.
struct TableNames<'a>(&'a TableReport);

impl TableNames<'_> {
    fn phrase(&self, index: usize) -> String {
        let name = self.0.pockets.get(index).map_or("unknown", |p| p.name);
        match name.strip_suffix("-side") {
            Some(edge) => format!("the {edge} side pocket (pocket {index})"),
            None => format!("the {name} corner (pocket {index})"),
        }
    }
}

/// `1 cushion`, `3 cushions`.
fn plural(count: usize, noun: &str) -> String {
    format!("{count} {noun}{}", if count == 1 { "" } else { "s" })
}

/// The guidance, a few lines, no trailing newline.
impl fmt::Display for ShotReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let t = &self.table;
        let s = &self.stroke;
        let names = self.table_for_names();
        writeln!(
            f,
            "{} table {} x {} m, R {:.3} mm; cue ball at {}, {} other ball{}",
            t.name,
            t.length,
            t.width,
            1e3 * t.radius,
            Point(self.balls[0]),
            self.balls.len() - 1,
            if self.balls.len() == 2 { "" } else { "s" }
        )?;
        writeln!(
            f,
            "stroke: cue {} m/s, tip {} R right, {} R up; the cue ball leaves at {:.2} m/s",
            s.cue_speed, s.tip[0], s.tip[1], s.launch_speed
        )?;
        if let Some(solve) = &self.solve {
            let rotation = if solve.correction_deg >= 0.0 {
                "counter-clockwise"
            } else {
                "clockwise"
            };
            let stops = self.ending(&self.cue_ball);
            writeln!(
                f,
                "aim {:.3}° (ghost ball at {}): {:.1} mm {} ({:.2}° {rotation}) than the ghost-ball aim; cut {:.1}°; object ball {}; cue ball {stops}",
                solve.aim_deg,
                Point(solve.ghost_ball),
                1e3 * solve.correction_offset,
                if solve.thinner { "thinner" } else { "thicker" },
                solve.correction_deg.abs(),
                solve.cut_deg.abs(),
                match &self.object_ball {
                    Some(ball) if ball.end == End::Pocket => self.ending(ball),
                    _ => format!("goes to {}", names.phrase(solve.pocket)),
                },
            )?;
            writeln!(
                f,
                "  (ghost-ball aim {:.3}° at {}; solved in {} evaluations)",
                solve.naive_aim_deg,
                Point(solve.naive_ghost_ball),
                solve.evaluations
            )?;
        } else {
            writeln!(f, "aim {}°", s.aim_deg)?;
        }
        match &self.contact {
            None => write!(
                f,
                "no contact: the cue ball hits no ball; {}",
                self.ball_line("it", &self.cue_ball)
            )?,
            Some(c) => {
                writeln!(
                    f,
                    "contact: ball {} after {:.3} s, cue ball at {} at {:.2} m/s; cut {:.2}° (object ball to the {})",
                    c.ball,
                    c.time,
                    Point(c.cue_position),
                    c.speed,
                    c.cut_deg.abs(),
                    cut_side(c.cut_deg)
                )?;
                let model = if c.model == c.model_used {
                    c.model.to_owned()
                } else {
                    format!("{} -> {}", c.model, c.model_used)
                };
                writeln!(
                    f,
                    "collision: model {model}, regime {}; throw {:.2}°",
                    c.regime, c.throw_deg
                )?;
                write!(f, "{}", self.ball_line("cue ball:", &self.cue_ball))?;
                if let Some(object) = &self.object_ball {
                    write!(
                        f,
                        "\n{}",
                        self.ball_line(&format!("ball {}:", object.ball), object)
                    )?;
                }
            }
        }
        if let Some(target) = &self.target {
            let hit = self.contact.as_ref().map(|c| c.ball);
            let what = match (target.pocketed, target.miss, hit) {
                (_, _, None) => "not pocketed: the cue ball hits no ball".to_owned(),
                (_, _, Some(ball)) if ball != target.object => {
                    format!("not pocketed: ball {ball} is hit first")
                }
                (true, Some(miss), _) => format!(
                    "pocketed, {:.1} mm from the pocket centre",
                    1e3 * miss.abs()
                ),
                (true, None, _) => "pocketed".to_owned(),
                (false, Some(miss), _) => format!(
                    "not pocketed: crosses the mouth line {:.1} mm from the pocket centre",
                    1e3 * miss.abs()
                ),
                (false, None, _) => "not pocketed: does not reach the pocket".to_owned(),
            };
            write!(
                f,
                "\ntarget: ball {} into {}: {what}",
                target.object,
                names.phrase(target.pocket)
            )?;
        }
        write!(f, "\n{}", self.whole_table())
    }
}
