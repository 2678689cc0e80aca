//! Shot guidance in one call: from a scene, a stroke and either an aim or a pocket to
//! solve for, everything a player is told — the aim and its throw correction, the first
//! contact, both balls' paths and where each ends, and whether the ball is pocketed.
//!
//! This is the answer of the host CLI's `cuesight shot --json` and of the firmware
//! protocol's `shot` request: both build it here, so the device and the host give the
//! same numbers (see `docs/shot.md`, `docs/protocol.md`).
//!
//! Units: SI (m, s, m/s, rad/s) in the table frame (`x` along the length, `y` across,
//! origin at a corner of the playing surface, `z` up); angles in degrees, counter-
//! clockwise from `+x`, in the fields ending in `_deg`.

use crate::aim::{solve_aim, AimError, AimSolution};
use crate::error::Error;
use crate::estimate::select;
use crate::math;
use crate::model::Model;
use crate::outcome::Regime;
use crate::shot::{play_without_pocket, Contact, ShotSetup, Stroke};
use crate::strike::TipOffset;
use crate::table::{Scene, Table};
use crate::travel::{Motion, GRAVITY};
use crate::vector::Vec3;

/// How far outside the cushion line a centre must go to count as leaving the playing
/// area (m): a ball resting exactly on the line and rolling inward never "leaves".
const CUSHION_SLACK: f32 = 1e-6;

/// An object ball and the pocket it should go into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Target {
    /// Object-ball index in the scene (1 ..; 0 is the cue ball).
    pub object: usize,
    /// Pocket index in the table's pocket list.
    pub pocket: usize,
}

/// Where to aim.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Aim {
    /// Play this aim (degrees, counter-clockwise from `+x`); with a target, report
    /// whether it is pocketed.
    Degrees {
        /// Aim direction (degrees).
        aim_deg: f32,
        /// The ball and pocket to report on, if any.
        target: Option<Target>,
    },
    /// Solve for the aim that pockets the target, including throw
    /// ([`crate::aim::solve_aim`]), then play it.
    Solve(Target),
}

/// How a ball's path ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum End {
    /// It stops on the cloth.
    Rest,
    /// Its centre crosses a pocket's target segment.
    Pocket,
    /// Its centre reaches a cushion line (one radius in from the rail). Cushions are
    /// not modelled, so the path stops there.
    Cushion,
}

impl End {
    /// Lower-case name (`rest`, `pocket`, `cushion`).
    pub const fn name(self) -> &'static str {
        match self {
            End::Rest => "rest",
            End::Pocket => "pocket",
            End::Cushion => "cushion",
        }
    }
}

/// Where and when a motion's path ends: the first of crossing a pocket's target
/// segment, reaching a cushion line, and stopping.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct PathEnd {
    /// Time from the motion's start (s).
    pub time: f32,
    /// Why it ends.
    pub end: End,
    /// The pocket, for [`End::Pocket`].
    pub pocket: Option<usize>,
}

impl PathEnd {
    /// Follow `motion` of a ball of `radius` on `table`. Crossings are the closed-form
    /// roots of [`Motion::crossing`] (each phase is a polynomial of degree ≤ 2 in time),
    /// so no sampling is involved.
    pub fn of(motion: &Motion, table: &Table, radius: f32) -> Self {
        let mut pocket: Option<(usize, f32)> = None;
        for (index, p) in table.pockets().iter().enumerate() {
            if let Some(t) = motion.crossing(p.a, p.b) {
                if pocket.is_none_or(|(_, best)| t < best) {
                    pocket = Some((index, t));
                }
            }
        }
        let until = pocket.map_or(motion.stop_time(), |(_, t)| t);
        match cushion_time(motion, table, radius) {
            Some(t) if t <= until => Self {
                time: t,
                end: End::Cushion,
                pocket: None,
            },
            _ => match pocket {
                Some((index, t)) => Self {
                    time: t,
                    end: End::Pocket,
                    pocket: Some(index),
                },
                None => Self {
                    time: motion.stop_time(),
                    end: End::Rest,
                    pocket: None,
                },
            },
        }
    }
}

/// First time the centre crosses one of the four cushion lines `x = R`, `x = L − R`,
/// `y = R`, `y = W − R` (moved out by [`CUSHION_SLACK`]), if it does before stopping.
fn cushion_time(motion: &Motion, table: &Table, radius: f32) -> Option<f32> {
    let low = radius - CUSHION_SLACK;
    let (high_x, high_y) = (
        table.length() - radius + CUSHION_SLACK,
        table.width() - radius + CUSHION_SLACK,
    );
    let corner = |x: f32, y: f32| Vec3::new(x, y, 0.0);
    let lines = [
        (corner(low, low), corner(high_x, low)),
        (corner(high_x, low), corner(high_x, high_y)),
        (corner(high_x, high_y), corner(low, high_y)),
        (corner(low, high_y), corner(low, low)),
    ];
    let mut first: Option<f32> = None;
    for (a, b) in lines {
        if let Some(t) = motion.crossing(a, b) {
            if first.is_none_or(|best| t < best) {
                first = Some(t);
            }
        }
    }
    first
}

/// Direction of the horizontal part of `v` (degrees; 0 for a zero vector).
// Not inlined into its three uses (120 B of the firmware's flash).
#[inline(never)]
fn direction_deg(v: Vec3) -> f32 {
    if v.x == 0.0 && v.y == 0.0 {
        0.0
    } else {
        math::atan2(v.y, v.x).to_degrees()
    }
}

fn xy(v: Vec3) -> [f32; 2] {
    [v.x, v.y]
}

/// The stroke and the cue ball's launch.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StrokeGuide {
    /// Cue speed at the tip impact (m/s).
    pub cue_speed: f32,
    /// Aim direction played (degrees).
    pub aim_deg: f32,
    /// Unit aim direction.
    pub aim: [f32; 2],
    /// Cue-ball speed just after the strike (m/s).
    pub launch_speed: f32,
    /// Cue-ball spin just after the strike (rad/s, table frame).
    pub launch_spin: [f32; 3],
}

/// The inverse aim: the solver's answer and the two aims in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SolveGuide {
    /// The ball and pocket solved for.
    pub target: Target,
    /// Solved aim (degrees).
    pub aim_deg: f32,
    /// The naive ghost-ball aim (degrees).
    pub naive_aim_deg: f32,
    /// The solver's full answer (correction in degrees and mm, ghost balls, ...).
    pub solution: AimSolution,
}

/// The first collision.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ContactGuide {
    /// Ball hit first.
    pub ball: usize,
    /// Time from the strike (s).
    pub time: f32,
    /// Cue-ball centre at contact: the ghost ball (m).
    pub cue_position: [f32; 2],
    /// Unit line of centres, cue ball to object ball.
    pub line_of_centres: [f32; 2],
    /// Cut angle (degrees): from the line of centres to the cue ball's velocity,
    /// counter-clockwise positive.
    pub cut_deg: f32,
    /// Cue-ball speed at contact (m/s).
    pub speed: f32,
    /// Cue-ball spin at contact (rad/s, table frame).
    pub spin: [f32; 3],
    /// The model asked for.
    pub model: Model,
    /// The tier that predicted it: what `Auto` picked, otherwise the model itself.
    pub model_used: Model,
    /// That tier's a-priori error estimate (relative to the speed), for `Auto`.
    pub error_estimate: Option<f32>,
    /// Contact regime.
    pub regime: Regime,
    /// Throw: the object ball's departure off the line of centres (degrees, signed).
    pub throw_deg: f32,
}

/// One ball's motion, after the impact (or from the strike when nothing is hit).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BallPath {
    /// Ball index (0: cue ball).
    pub ball: usize,
    /// The closed-form motion (TP A.4): everything else here is read off it.
    pub motion: Motion,
    /// Velocity at the start (m/s; `z > 0`: the ball hops).
    pub velocity: [f32; 3],
    /// Rolling direction (degrees).
    pub rolling_direction_deg: f32,
    /// How its path ends.
    pub end: PathEnd,
    /// Where it ends (m).
    pub end_position: [f32; 2],
}

impl BallPath {
    fn new(ball: usize, motion: Motion, table: &Table, radius: f32) -> Self {
        let end = PathEnd::of(&motion, table, radius);
        let v = motion.initial_velocity;
        Self {
            ball,
            motion,
            // Take-off vertical speed from the air time: v_z = g t_air / 2.
            velocity: [v.x, v.y, 0.5 * GRAVITY * motion.air_time],
            rolling_direction_deg: direction_deg(motion.rolling_velocity),
            end,
            end_position: xy(motion.position_at(end.time)),
        }
    }
}

/// Whether the target ball reaches the target pocket.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct TargetGuide {
    /// The ball and pocket.
    pub target: Target,
    /// Whether that ball is hit first and its path ends in that pocket.
    pub pocketed: bool,
    /// Where its centre crosses the pocket's mouth line (the target segment extended),
    /// from the segment's centre along the segment (m, signed); `None` if it does not
    /// get there.
    pub miss: Option<f32>,
}

/// Everything one shot's guidance says.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Guidance {
    /// The stroke played.
    pub stroke: StrokeGuide,
    /// The inverse aim ([`Aim::Solve`] only).
    pub solve: Option<SolveGuide>,
    /// The first collision (`None`: the cue ball hits nothing).
    pub contact: Option<ContactGuide>,
    /// The cue ball: after the impact, or from the strike when nothing is hit.
    pub cue_ball: BallPath,
    /// The object ball after the impact.
    pub object_ball: Option<BallPath>,
    /// The target, if one was given.
    pub target: Option<TargetGuide>,
}

/// Where `motion`'s centre crosses pocket `pocket`'s mouth line, from the segment's
/// centre along the segment (m, signed) — the miss the aim solver drives to zero.
pub fn mouth_miss(motion: &Motion, table: &Table, pocket: usize) -> Option<f32> {
    let p = table.pockets().get(pocket)?;
    let centre = p.centre();
    let along = p.b - p.a;
    let along = along * (1.0 / along.length());
    // A segment far longer than any table stands in for the infinite line.
    let t = motion.crossing(centre - along * 20.0, centre + along * 20.0)?;
    Some(along.dot(motion.position_at(t) - centre))
}

/// The guidance for a stroke of `cue_speed` (m/s) with `tip` on `scene`, aimed (or
/// solved) as `aim` says, with the cue, cloth and collision model of `setup`.
///
/// Errors: an invalid input ([`AimError::Invalid`], with the field), or, when solving,
/// why there is no aim.
///
/// ```
/// use cuesight::guidance::{guide, Aim, End, Target};
/// use cuesight::shot::ShotSetup;
/// use cuesight::strike::{Cue, TipOffset};
/// use cuesight::table::{BallSet, Scene, Table};
/// use cuesight::travel::Cloth;
/// use cuesight::{Model, Params};
///
/// let mut scene = Scene::new(Table::pool(), BallSet::POOL.radius, [1.5, 0.3])?;
/// let object = scene.add_ball([1.9, 0.9])?;
/// let setup = ShotSetup {
///     params: Params::POOL,
///     cue: Cue::TYPICAL,
///     cloth: Cloth::TYPICAL,
///     model: Model::Auto { tolerance: 1e-3 },
/// };
/// // Solve the aim that drops the object ball in the far corner pocket (3), then play it.
/// let target = Target { object, pocket: 3 };
/// let g = guide(&scene, 2.0, TipOffset::CENTRE, Aim::Solve(target), &setup)?;
/// let solved = g.solve.unwrap();
/// assert!(solved.solution.correction_deg.abs() > 0.0); // throw moves the aim
/// assert_eq!(g.object_ball.unwrap().end.end, End::Pocket);
/// assert!(g.target.unwrap().pocketed);
///
/// // The naive ghost-ball aim, played as given: throw makes it miss by some millimetres.
/// let naive = Aim::Degrees { aim_deg: solved.naive_aim_deg, target: Some(target) };
/// let played = guide(&scene, 2.0, TipOffset::CENTRE, naive, &setup)?;
/// let miss = played.target.unwrap().miss.unwrap();
/// assert!(miss.abs() > 1e-3);
/// # Ok::<(), cuesight::aim::AimError>(())
/// ```
pub fn guide(
    scene: &Scene,
    cue_speed: f32,
    tip: TipOffset,
    aim: Aim,
    setup: &ShotSetup,
) -> Result<Guidance, AimError> {
    let (stroke, aim_deg, solve, target) = match aim {
        Aim::Degrees { aim_deg, target } => {
            let stroke = Stroke::at_angle(cue_speed, tip, aim_deg.to_radians())?;
            (stroke, aim_deg, None, target)
        }
        Aim::Solve(target) => {
            let solution = solve_aim(scene, target.object, target.pocket, cue_speed, tip, setup)?;
            let stroke = Stroke::new(cue_speed, tip, xy(solution.aim))?;
            let aim_deg = direction_deg(solution.aim);
            let solve = SolveGuide {
                target,
                aim_deg,
                naive_aim_deg: direction_deg(solution.naive_aim),
                solution,
            };
            (stroke, aim_deg, Some(solve), Some(target))
        }
    };
    if let Some(t) = target {
        check_target(scene, t)?;
    }
    // Borrowed where it lies: moving the `Shot` out of its `Result` is a copy.
    let played = play_without_pocket(scene, &stroke, setup);
    let shot = played.as_ref().map_err(|e| *e)?;
    let table = scene.table();
    let radius = scene.radius();
    let launch = &shot.cue_before;
    let stroke = StrokeGuide {
        cue_speed,
        aim_deg,
        aim: xy(stroke.aim()),
        launch_speed: launch.initial_velocity.length(),
        launch_spin: launch.initial_spin.to_array(),
    };
    let contact = shot.contact.as_ref();
    let cue_motion = contact.map_or(shot.cue_before, |c| c.cue_after);
    let cue_ball = BallPath::new(0, cue_motion, table, radius);
    let object_ball = contact.map(|c| BallPath::new(c.object_ball, c.object_after, table, radius));
    let target = target.map(|t| {
        let hit = contact.filter(|c| c.object_ball == t.object);
        let pocketed = hit.is_some()
            && object_ball
                .is_some_and(|b| b.end.end == End::Pocket && b.end.pocket == Some(t.pocket));
        TargetGuide {
            target: t,
            pocketed,
            miss: hit.and_then(|c| mouth_miss(&c.object_after, table, t.pocket)),
        }
    });
    Ok(Guidance {
        stroke,
        solve,
        contact: contact.map(|c| contact_guide(c, &shot.cue_before, setup)),
        cue_ball,
        object_ball,
        target,
    })
}

/// The target must name an object ball of the scene and a pocket of its table.
fn check_target(scene: &Scene, target: Target) -> Result<(), Error> {
    use crate::error::Field;
    if target.object == 0 || target.object >= scene.balls().len() {
        return Err(Error::OutOfRange {
            field: Field::BallIndex,
            value: target.object as f32,
        });
    }
    if target.pocket >= scene.table().pockets().len() {
        return Err(Error::OutOfRange {
            field: Field::Pocket,
            value: target.pocket as f32,
        });
    }
    Ok(())
}

// Not inlined into `guide`: in a frame of its own the firmware's image is
// smaller (28 B measured).
#[inline(never)]
fn contact_guide(contact: &Contact, cue_before: &Motion, setup: &ShotSetup) -> ContactGuide {
    let (model_used, error_estimate) = match setup.model {
        Model::Auto { tolerance } => {
            let (tier, estimate) = select(&setup.params, &contact.impact, tolerance);
            (tier, Some(estimate))
        }
        model => (model, None),
    };
    ContactGuide {
        ball: contact.object_ball,
        time: contact.time,
        cue_position: xy(contact.cue_position),
        line_of_centres: xy(contact.line_of_centres),
        cut_deg: contact.cut_angle.to_degrees(),
        speed: cue_before.velocity_at(contact.time).length(),
        spin: cue_before.spin_at(contact.time).to_array(),
        model: setup.model,
        model_used,
        error_estimate,
        regime: contact.outcome.regime,
        throw_deg: contact.outcome.throw_angle_deg(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::BallSet;
    use crate::travel::Cloth;

    const R: f32 = BallSet::POOL.radius;

    fn motion(position: [f32; 2], velocity: [f32; 3], spin: [f32; 3]) -> Motion {
        Motion::new(
            Vec3::new(position[0], position[1], 0.0),
            Vec3::new(velocity[0], velocity[1], velocity[2]),
            Vec3::new(spin[0], spin[1], spin[2]),
            R,
            &Cloth::TYPICAL,
        )
        .unwrap()
    }

    /// First time the centre is outside the cushion box, by sampling and bisection —
    /// the independent check of the closed-form crossings.
    fn sampled_exit(m: &Motion, table: &Table) -> Option<f32> {
        let outside = |t: f32| {
            let p = m.position_at(t);
            p.x < R - CUSHION_SLACK
                || p.y < R - CUSHION_SLACK
                || p.x > table.length() - R + CUSHION_SLACK
                || p.y > table.width() - R + CUSHION_SLACK
        };
        let until = m.stop_time();
        let samples = 20_000;
        let mut previous = 0.0;
        for i in 1..=samples {
            let t = until * i as f32 / samples as f32;
            if outside(t) {
                let (mut lo, mut hi) = (previous, t);
                for _ in 0..40 {
                    let mid = 0.5 * (lo + hi);
                    if outside(mid) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Some(hi);
            }
            previous = t;
        }
        None
    }

    #[test]
    fn cushion_time_matches_sampling() {
        let table = Table::carom(); // no pockets: every path ends at a cushion or rests
        let cases = [
            ([1.0, 0.7], [3.0, 0.4, 0.0], [0.0, 0.0, 0.0]),
            ([1.0, 0.7], [-2.0, 1.5, 0.0], [40.0, -60.0, 10.0]),
            ([0.5, 0.2], [0.3, -2.0, 0.0], [-80.0, 0.0, 0.0]),
            ([2.0, 1.0], [1.0, 1.0, 0.4], [0.0, 90.0, 0.0]), // a hop first
            ([1.4, 0.7], [0.2, 0.1, 0.0], [0.0, 0.0, 0.0]),  // stops on the cloth
        ];
        for (position, velocity, spin) in cases {
            let m = motion(position, velocity, spin);
            let end = PathEnd::of(&m, &table, R);
            match sampled_exit(&m, &table) {
                Some(t) => {
                    assert_eq!(end.end, End::Cushion, "{position:?} {velocity:?}");
                    assert!((end.time - t).abs() < 1e-4, "{} vs {t}", end.time);
                }
                None => {
                    assert_eq!(end.end, End::Rest);
                    assert_eq!(end.time, m.stop_time());
                }
            }
        }
    }

    #[test]
    fn ball_on_the_cushion_line_rolling_inward_does_not_end_there() {
        let table = Table::carom();
        let m = motion([R, 0.7], [1.0, 0.0, 0.0], [0.0, 1.0 / R, 0.0]);
        assert_eq!(PathEnd::of(&m, &table, R).end, End::Cushion);
        assert!(PathEnd::of(&m, &table, R).time > 1.0);
    }

    #[test]
    fn straight_rolling_shot_into_a_corner_is_pocketed_with_no_miss() {
        let table = Table::pool();
        let corner = table.pockets()[3].centre();
        let start = Vec3::new(1.5, 0.7, 0.0);
        let d = corner - start;
        let v = d * (2.0 / d.length());
        // Natural roll: ω = z × v / R.
        let m = motion(
            [start.x, start.y],
            [v.x, v.y, 0.0],
            [-v.y / R, v.x / R, 0.0],
        );
        let end = PathEnd::of(&m, &table, R);
        assert_eq!((end.end, end.pocket), (End::Pocket, Some(3)));
        let miss = mouth_miss(&m, &table, 3).unwrap();
        assert!(miss.abs() < 1e-5, "{miss}");
    }
}
