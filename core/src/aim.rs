//! Inverse aim: the aim that sends a chosen object ball to a pocket's centre, throw and
//! every other collision effect included, and how it differs from the naive ghost-ball
//! aim.
//!
//! The naive aim points the cue ball at the ghost ball `G₀ = O − 2R d̂` (`d̂` from the
//! object ball `O` to the pocket centre), as if the object ball left along the line of
//! centres. The real object ball is thrown off that line (seed eq. (55)) and may curve
//! while it slides, so we solve `m(θ) = 0` for the aim angle `θ`, where `m` is the signed
//! miss of the object ball's centre along the pocket's mouth line, evaluated by the full
//! forward chain ([`crate::shot`]). Secant steps from the naive aim, each limited to
//! 0.05 rad and kept inside the aims that hit the chosen ball first; at most
//! [`MAX_ITERATIONS`] evaluations; converged when `|m| ≤ 10 µm`.

use core::fmt;

use crate::error::{Error, Field, Result};
use crate::impact::Impact;
use crate::math;
use crate::model::collide;
use crate::outcome::Outcome;
use crate::params::Params;
use crate::shot::{play_chain, ShotSetup, Stroke};
use crate::strike::TipOffset;
use crate::table::Scene;
use crate::vector::Vec3;

/// Most forward-chain evaluations of one solve.
pub const MAX_ITERATIONS: u32 = 24;
/// Convergence: the object ball's centre within this of the pocket centre (m): 10 µm,
/// 0.0006° at 1 m, above f32 noise in the chain (~1 µm on a 2.5 m table).
pub const TOLERANCE: f32 = 1e-5;

/// Why no aim was found.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
#[cfg_attr(feature = "schema", derive(postcard_schema::Schema))]
pub enum AimError {
    /// An input is invalid.
    Invalid(Error),
    /// At the naive aim the cue ball does not hit the chosen object ball first (another
    /// ball is in the way, or the cue ball stops short).
    ObjectBallNotHit,
    /// The object ball stops (or leaves the mouth line's side) before the pocket.
    PocketUnreachable,
    /// No aim within [`MAX_ITERATIONS`] evaluations (e.g. the required cut is too thin).
    NotConverged,
}

impl From<Error> for AimError {
    fn from(e: Error) -> Self {
        AimError::Invalid(e)
    }
}

impl fmt::Display for AimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AimError::Invalid(e) => e.fmt(f),
            AimError::ObjectBallNotHit => f.write_str(
                "no aim: at the ghost-ball aim the cue ball does not reach the object ball \
                 first (another ball is in the way, or the cue ball stops short)",
            ),
            AimError::PocketUnreachable => f.write_str(
                "no aim: the object ball cannot reach the pocket (it stops short, or the \
                 cut is too thin)",
            ),
            AimError::NotConverged => write!(
                f,
                "no aim: the solver did not converge in {MAX_ITERATIONS} forward evaluations \
                 (the cut may be too thin)"
            ),
        }
    }
}

/// The message of [`AimError::Invalid`] is the inner [`Error`]'s, so it reports no
/// separate `source`.
impl core::error::Error for AimError {}

/// A solved aim.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct AimSolution {
    /// Unit aim direction that pockets the ball (table frame).
    pub aim: Vec3,
    /// Ghost-ball centre for that aim: where the cue ball's centre is at contact.
    pub ghost_ball: Vec3,
    /// The naive ghost-ball aim direction.
    pub naive_aim: Vec3,
    /// Naive ghost-ball centre.
    pub naive_ghost_ball: Vec3,
    /// Aim correction from the naive aim (degrees, counter-clockwise positive).
    pub correction_deg: f32,
    /// The same correction as a sideways shift of the aim line at the object ball's
    /// distance (mm, unsigned).
    pub correction_mm: f32,
    /// `true` when the corrected aim is a thinner cut than the naive one.
    pub thinner: bool,
    /// Cut angle at the solved aim (degrees, signed).
    pub cut_angle_deg: f32,
    /// Forward-chain evaluations used.
    pub evaluations: u32,
    /// Remaining miss at the pocket centre (m).
    pub residual: f32,
}

/// Solve the aim that pockets ball `object` in pocket `pocket` with a stroke of cue
/// speed `cue_speed` and tip `tip`, using the model of `setup`.
///
/// ```
/// use cuesight::aim::{solve_aim, AimError, TOLERANCE};
/// use cuesight::shot::ShotSetup;
/// use cuesight::strike::{Cue, TipOffset};
/// use cuesight::table::{BallSet, Scene, Table};
/// use cuesight::travel::Cloth;
/// use cuesight::{Model, Params};
///
/// let r = BallSet::POOL.radius;
/// let mut scene = Scene::new(Table::pool(), r, [1.5, 0.3])?;
/// let object = scene.add_ball([1.9, 0.9])?;
/// let setup = ShotSetup {
///     params: Params::POOL,
///     cue: Cue::TYPICAL,
///     cloth: Cloth::TYPICAL,
///     model: Model::KimGrip,
/// };
/// let tip = TipOffset::from_radius_fraction(0.0, 0.3, r)?; // some follow
/// let aim = solve_aim(&scene, object, 3, 2.0, tip, &setup)?;
/// assert!(aim.residual.abs() <= TOLERANCE);
/// // Throw carries the object ball off the line of centres: the ghost-ball aim misses
/// // and the solved aim differs from it by a fraction of a degree.
/// assert!(aim.correction_deg.abs() > 0.05 && aim.correction_deg.abs() < 1.0);
/// println!("aim {:+.2} deg from the ghost ball ({:.1} mm)", aim.correction_deg, aim.correction_mm);
///
/// // A pocket the table does not have is an invalid input, named.
/// let error = solve_aim(&scene, object, 6, 2.0, tip, &setup).unwrap_err();
/// assert!(matches!(error, AimError::Invalid(_)));
/// assert_eq!(error.to_string(), "pocket = 6 is outside an index of a pocket of the table");
/// # Ok::<(), AimError>(())
/// ```
pub fn solve_aim(
    scene: &Scene,
    object: usize,
    pocket: usize,
    cue_speed: f32,
    tip: TipOffset,
    setup: &ShotSetup,
) -> core::result::Result<AimSolution, AimError> {
    crate::shot::check_model(setup.model)?;
    let model = setup.model;
    solve_aim_with(scene, object, pocket, cue_speed, tip, setup, |p, i| {
        collide(p, i, model)
    })
}

/// As [`solve_aim`], with the collision predicted by `collision`.
pub fn solve_aim_with<F>(
    scene: &Scene,
    object: usize,
    pocket: usize,
    cue_speed: f32,
    tip: TipOffset,
    setup: &ShotSetup,
    mut collision: F,
) -> core::result::Result<AimSolution, AimError>
where
    F: FnMut(&Params, &Impact) -> Result<Outcome>,
{
    let balls = scene.balls();
    if object == 0 || object >= balls.len() {
        return Err(Error::OutOfRange {
            field: Field::BallIndex,
            value: object as f32,
        }
        .into());
    }
    let target = scene
        .table()
        .pockets()
        .get(pocket)
        .copied()
        .ok_or(Error::OutOfRange {
            field: Field::Pocket,
            value: pocket as f32,
        })?;
    let (cue, ball) = (balls[0], balls[object]);
    let centre = target.centre();
    let radius = scene.radius();
    // Mouth line: through the pocket centre along its segment. Everything below is
    // relative to the ball and the segment's end `a` (never through absolute
    // positions), so a scene mirrored across the table's long axis solves to exactly
    // the mirrored aim.
    let mouth = target.b - target.a;
    let along = mouth * (1.0 / mouth.length());
    let half_mouth = 0.5 * along.dot(mouth);
    let to_pocket = (target.a - ball) + mouth * 0.5;
    let distance = to_pocket.length();
    let direction = if distance > 0.0 {
        to_pocket * (1.0 / distance)
    } else {
        // The ball sits on the pocket centre: send it straight through the mouth, away
        // from the middle of the table (the direction was 0/0, and the solve failed
        // with a non-finite aim).
        let normal = Vec3::new(-along.y, along.x, 0.0);
        let table = scene.table();
        let middle = Vec3::new(0.5 * table.length(), 0.5 * table.width(), 0.0);
        if normal.dot(centre - middle) < 0.0 {
            normal * -1.0
        } else {
            normal
        }
    };
    let naive_ghost = ball - direction * (2.0 * radius);
    let naive_vector = (ball - cue) - direction * (2.0 * radius);
    let naive_angle = math::atan2(naive_vector.y, naive_vector.x);
    // The first probe turns towards the side the mouth runs to (a side that mirrors
    // with the scene; a fixed +1e-3 rad made mirrored solves take different paths).
    let turn = if direction.x * along.y - direction.y * along.x >= 0.0 {
        1.0
    } else {
        -1.0
    };

    let mut miss = |angle: f32| -> core::result::Result<(f32, Vec3, f32), AimError> {
        let stroke = Stroke::at_angle(cue_speed, tip, angle)?;
        // Borrowed where it lies: moving the shot or its contact out is a copy, on
        // every evaluation.
        let played = play_chain(scene, &stroke, setup, &mut collision);
        let shot = played.as_ref().map_err(|e| *e)?;
        let contact = shot.contact.as_ref().ok_or(AimError::ObjectBallNotHit)?;
        if contact.object_ball != object {
            return Err(AimError::ObjectBallNotHit);
        }
        let path = &contact.object_after; // starts at the object ball
        let t = path
            .crossing_line(target.a, along)
            .ok_or(AimError::PocketUnreachable)?;
        let at = (ball - target.a) + path.displacement_at(t);
        Ok((
            along.dot(at) - half_mouth,
            contact.cue_position,
            contact.cut_angle,
        ))
    };

    let (mut angle_a, mut miss_a) = (naive_angle, miss(naive_angle)?.0);
    let mut angle_b = naive_angle + turn * 1e-3;
    let mut evaluations = 1;
    let mut last = miss(angle_b);
    evaluations += 1;
    loop {
        let (miss_b, ghost, cut) = match last {
            Ok(v) => v,
            Err(error) => {
                // Stepped out of the valid aims: go back halfway. If the valid aims never
                // reach the pocket, that is the answer.
                angle_b = 0.5 * (angle_a + angle_b);
                if evaluations >= MAX_ITERATIONS {
                    return Err(error);
                }
                last = miss(angle_b);
                evaluations += 1;
                continue;
            }
        };
        if math::abs(miss_b) <= TOLERANCE {
            let aim = Vec3::new(math::cos(angle_b), math::sin(angle_b), 0.0);
            let naive_aim = Vec3::new(math::cos(naive_angle), math::sin(naive_angle), 0.0);
            let correction = angle_b - naive_angle;
            let distance = (ball - cue).length();
            let naive_cut = naive_cut_angle(naive_vector, direction);
            return Ok(AimSolution {
                aim,
                ghost_ball: ghost,
                naive_aim,
                naive_ghost_ball: naive_ghost,
                correction_deg: correction.to_degrees(),
                correction_mm: 1000.0 * distance * math::abs(math::sin(correction)),
                thinner: math::abs(cut) > math::abs(naive_cut),
                cut_angle_deg: cut.to_degrees(),
                evaluations,
                residual: miss_b,
            });
        }
        if evaluations >= MAX_ITERATIONS {
            return Err(AimError::NotConverged);
        }
        let slope = (miss_b - miss_a) / (angle_b - angle_a);
        let step = if slope != 0.0 && math::is_finite(slope) {
            -miss_b / slope
        } else {
            turn * 1e-3
        };
        let step = step.clamp(-0.05, 0.05);
        angle_a = angle_b;
        miss_a = miss_b;
        angle_b += step;
        last = miss(angle_b);
        evaluations += 1;
    }
}

/// Cut angle (rad) of the naive aim `aim` (cue ball to ghost ball): between the line of
/// centres there (`direction`, to the pocket) and the aim line.
fn naive_cut_angle(aim: Vec3, direction: Vec3) -> f32 {
    let cross = direction.x * aim.y - direction.y * aim.x;
    math::atan2(cross, direction.dot(aim))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::strike::Cue;
    use crate::table::{BallSet, Table};
    use crate::travel::Cloth;
    use crate::Model;

    /// A pocket index out of range was reported as a ball index ("ball = 6 is outside
    /// an index of a ball in the scene"), and `AimError` had no message of its own.
    #[test]
    fn pocket_index_and_messages() {
        extern crate std;
        use std::string::ToString;
        let setup = ShotSetup {
            params: Params::POOL,
            cue: Cue::TYPICAL,
            cloth: Cloth::TYPICAL,
            model: Model::KimGrip,
        };
        let mut scene = Scene::new(Table::pool(), BallSet::POOL.radius, [0.5, 0.6]).unwrap();
        scene.add_ball([1.5, 0.6]).unwrap();
        let e = solve_aim(&scene, 1, 6, 2.0, TipOffset::CENTRE, &setup).unwrap_err();
        assert_eq!(
            e,
            AimError::Invalid(Error::OutOfRange {
                field: Field::Pocket,
                value: 6.0
            })
        );
        assert_eq!(
            e.to_string(),
            "pocket = 6 is outside an index of a pocket of the table"
        );
        assert!(AimError::NotConverged
            .to_string()
            .contains("24 forward evaluations"));
        assert!(AimError::ObjectBallNotHit
            .to_string()
            .starts_with("no aim: "));
        assert!(AimError::PocketUnreachable
            .to_string()
            .starts_with("no aim: "));
        let mut bad = setup;
        bad.model = Model::Auto { tolerance: 2.0 };
        assert_eq!(
            solve_aim(&scene, 1, 3, 2.0, TipOffset::CENTRE, &bad),
            Err(AimError::Invalid(Error::OutOfRange {
                field: Field::Tolerance,
                value: 2.0
            }))
        );
    }

    /// A scene mirrored across the table's long axis (positions where `W − y` is
    /// exact) solves to exactly the mirrored aim, correction, cut and residual in as
    /// many evaluations. The solver's first probe was always +1e-3 rad and its miss was
    /// measured through absolute positions, so mirrored solves took different paths and
    /// differed by up to the solver's tolerance.
    #[test]
    fn mirrored_scenes_solve_to_mirrored_aims() {
        let setup = ShotSetup {
            params: Params::POOL,
            cue: Cue::TYPICAL,
            cloth: Cloth::TYPICAL,
            model: Model::KimGrip,
        };
        let table = Table::pool();
        let w = table.width();
        let r = BallSet::POOL.radius;
        let mut solved = 0;
        for (cue, object, pocket, image_pocket) in [
            ([0.6f32, 0.3125f32], [1.4f32, 0.5f32], 3usize, 1usize),
            ([0.75, 0.625], [1.5, 0.375], 1, 3),
            ([2.0, 0.25], [1.125, 0.5], 0, 2),
            ([0.5, 0.5], [1.0, 0.25], 4, 5),
        ] {
            for (side, height) in [(0.0f32, 0.0f32), (0.3, -0.2), (-0.25, 0.3)] {
                let scene = |y: fn(f32, f32) -> f32| {
                    let mut s = Scene::new(table.clone(), r, [cue[0], y(w, cue[1])]).unwrap();
                    s.add_ball([object[0], y(w, object[1])]).unwrap();
                    s
                };
                let (a, b) = (scene(|_, y| y), scene(|w, y| w - y));
                let tip = TipOffset::from_radius_fraction(side, height, r).unwrap();
                let image_tip = TipOffset::new(-tip.side(), tip.height()).unwrap();
                let x = solve_aim(&a, 1, pocket, 3.0, tip, &setup);
                let y = solve_aim(&b, 1, image_pocket, 3.0, image_tip, &setup);
                let (x, y) = match (x, y) {
                    (Ok(x), Ok(y)) => (x, y),
                    (Err(e), Err(f)) => {
                        assert_eq!(e, f);
                        continue;
                    }
                    other => panic!("{other:?}"),
                };
                solved += 1;
                assert_eq!(x.aim, Vec3::new(y.aim.x, -y.aim.y, 0.0));
                assert_eq!(x.naive_aim, Vec3::new(y.naive_aim.x, -y.naive_aim.y, 0.0));
                assert_eq!(x.correction_deg, -y.correction_deg);
                assert_eq!(x.correction_mm, y.correction_mm);
                assert_eq!(x.cut_angle_deg, -y.cut_angle_deg);
                assert_eq!(x.thinner, y.thinner);
                assert_eq!(x.evaluations, y.evaluations);
                assert_eq!(x.residual, y.residual);
            }
        }
        assert!(solved >= 9, "{solved}");
    }

    /// An object ball exactly on a pocket's target centre (a legal position: the
    /// centre is inside the cushion lines) made the direction to the pocket 0/0 and the
    /// solve failed with "aim must be a finite number". Now it is solved (the forward
    /// chain sends the ball through the mouth within the tolerance) or reported as
    /// unreachable, never as an invalid input.
    #[test]
    fn object_ball_on_the_pocket_centre() {
        for (table, set) in [
            (Table::pool(), BallSet::POOL),
            (Table::snooker(), BallSet::SNOOKER),
        ] {
            let setup = ShotSetup {
                params: Params::POOL.with_ball(set.radius, set.mass).unwrap(),
                cue: Cue::TYPICAL,
                cloth: Cloth::TYPICAL,
                model: Model::KimGrip,
            };
            let middle = [0.5 * table.length(), 0.5 * table.width()];
            for (index, pocket) in table.pockets().iter().enumerate() {
                let c = pocket.centre();
                let mut scene = Scene::new(table.clone(), set.radius, middle).unwrap();
                scene.add_ball([c.x, c.y]).unwrap();
                match solve_aim(&scene, 1, index, 3.0, TipOffset::CENTRE, &setup) {
                    Ok(solution) => {
                        assert!(solution.aim.is_finite());
                        assert!(math::abs(solution.residual) <= TOLERANCE);
                    }
                    Err(AimError::Invalid(e)) => panic!("pocket {index}: {e}"),
                    Err(_) => {}
                }
            }
        }
    }
}
