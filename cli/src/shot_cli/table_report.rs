//! The whole table after the shot (issue 17): every ball simulated from the stroke
//! until all rest or drop ([`cuesight::sim`]), as `cuesight shot` reports it: where each
//! ball ends (`"final"`), every event in time order (`"events"`), each ball's path
//! through cushions and collisions for the drawing, and on a carom table with three
//! balls the three-cushion scoring check.

use cuesight::shot::Stroke;
use cuesight::sim::{self, Cushion, EventKind};
use cuesight::travel::Motion;
use cuesight::Vec3;
use serde::Serialize;

use super::input::Request;
use super::ShotError;

/// Cushion nose height in ball radii: pool's `0.64 × 2R` (pooltool 0.6), and carom's
/// 37 mm for 61.5 mm balls; snooker and custom tables take pool's.
fn nose_height_in_radii(table_name: &str) -> f32 {
    match table_name {
        "carom" => 0.037 / 0.03075,
        _ => 1.28,
    }
}

/// The cushions of the request's table for its balls.
pub fn cushion_for(request: &Request) -> Result<Cushion, ShotError> {
    let preset = match request.table_name {
        "carom" => Cushion::CAROM,
        "snooker" => Cushion::SNOOKER,
        _ => Cushion::POOL,
    };
    let height = nose_height_in_radii(request.table_name) * request.scene.radius();
    Cushion::new(preset.restitution(), preset.friction(), height)
        .map_err(|e| ShotError::invalid(e.to_string()))
}

/// One event, as `"events"` lists it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EventReport {
    /// Time from the stroke (s).
    pub time: f32,
    /// `ball`, `cushion`, `pocket` or `rest`.
    pub kind: &'static str,
    /// The ball, or the two balls of a collision (scene numbering, cue ball 0).
    pub balls: Vec<usize>,
    /// Centre of the (first) ball at the event (m).
    pub position: [f32; 2],
    /// The pocket's index, for `pocket`, and for a `cushion` that is one of the
    /// pocket's jaws (its face or rounded nose).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pocket: Option<usize>,
}

/// The three-cushion scoring check: the cue ball touches both object balls and at least
/// three cushions before the second.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThreeCushion {
    /// Whether the shot scores.
    pub scored: bool,
    /// The object ball the cue ball touches first.
    pub first: Option<usize>,
    /// The other object ball, if the cue ball touches it.
    pub second: Option<usize>,
    /// Cushions the cue ball touches before the second object ball (all of them if it
    /// never does).
    pub cushions: usize,
}

impl ThreeCushion {
    /// The check over `events` (time order).
    pub fn check(events: &[EventReport]) -> Self {
        let (mut first, mut cushions) = (None, 0);
        for event in events {
            match (event.kind, event.balls.as_slice()) {
                ("cushion", [0]) => cushions += 1,
                ("ball", [a, b]) if *a == 0 || *b == 0 => {
                    let other = if *a == 0 { *b } else { *a };
                    match first {
                        None => first = Some(other),
                        Some(f) if f != other => {
                            return Self {
                                scored: cushions >= 3,
                                first,
                                second: Some(other),
                                cushions,
                            }
                        }
                        Some(_) => {}
                    }
                }
                _ => {}
            }
        }
        Self {
            scored: false,
            first,
            second: None,
            cushions,
        }
    }
}

/// The chosen object ball and pocket on the whole table: whether the ball drops there,
/// and if not, what it meets first after the cue ball sends it off. Contacts with the
/// chosen pocket's own jaws on the way in are counted (`jaw_contacts`), not taken as
/// what it meets first: a ball that rattles in is pocketed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WholeTarget {
    /// Whether the object ball drops into the chosen pocket before anything else
    /// touches it (the pocket's own jaws aside).
    pub pocketed: bool,
    /// How many times it touches the chosen pocket's jaws before it drops or meets
    /// something else.
    pub jaw_contacts: usize,
    /// The ball in its way: the first ball it hits after the cue ball's contact (or the
    /// ball that hits it), if that comes first.
    pub in_the_way: Option<usize>,
    /// What it meets first: `pocket` (the chosen one or another), `ball`, `cushion`, or
    /// `rest` if it stops; `none` if the cue ball never touches it.
    pub first: &'static str,
}

impl WholeTarget {
    /// The verdict for `object` and `pocket` over `events` (time order).
    pub fn check(events: &[EventReport], object: usize, pocket: usize) -> Self {
        let involves = |e: &EventReport| e.balls.contains(&object);
        // The cue ball's contact with the object ball sends it off.
        let Some(start) = events
            .iter()
            .position(|e| e.kind == "ball" && involves(e) && e.balls.contains(&0))
        else {
            return Self {
                pocketed: false,
                jaw_contacts: 0,
                in_the_way: None,
                first: "none",
            };
        };
        let jaw = |e: &EventReport| e.kind == "cushion" && e.pocket == Some(pocket);
        let mut after = events[start + 1..].iter().filter(|e| involves(e));
        let jaw_contacts = after.clone().take_while(|e| jaw(e)).count();
        let next = after.find(|e| !jaw(e));
        let (pocketed, in_the_way, first) = match next {
            Some(e) if e.kind == "pocket" => (e.pocket == Some(pocket), None, "pocket"),
            // Turned away by the jaws: they are what it met first.
            _ if jaw_contacts > 0 => (false, None, "cushion"),
            Some(e) if e.kind == "ball" => (
                false,
                e.balls.iter().copied().find(|&b| b != object),
                "ball",
            ),
            Some(e) => (false, None, e.kind),
            None => (false, None, "rest"),
        };
        Self {
            pocketed,
            jaw_contacts,
            in_the_way,
            first,
        }
    }
}

/// One stretch of a ball's path: from simulation time `since`, `motion`, until `until`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Start (s).
    pub since: f32,
    /// End (s): the next event that changes the ball, its drop, or its stop.
    pub until: f32,
    /// The motion from `since` (times relative to it).
    pub motion: Motion,
}

/// The whole table after the shot.
#[derive(Clone, Debug, PartialEq)]
pub struct TableOutcome {
    /// Where each ball ends, scene order; `None` if pocketed.
    pub final_positions: Vec<Option<[f32; 2]>>,
    /// Every event in time order.
    pub events: Vec<EventReport>,
    /// Each ball's path, scene order.
    pub paths: Vec<Vec<Segment>>,
    /// Time until the last ball stops or drops (s).
    pub time: f32,
    /// The scoring check, on a carom table with three balls.
    pub three_cushion: Option<ThreeCushion>,
    /// The chosen object ball and pocket on the whole table, if a pocket was chosen.
    pub target: Option<WholeTarget>,
}

/// Simulate the whole table for `request` played with `stroke`; `cue_launch` is the cue
/// ball's motion from the strike (the shot chain's, the same as the simulation's).
pub fn simulate(
    request: &Request,
    stroke: &Stroke,
    cue_launch: &Motion,
) -> Result<TableOutcome, ShotError> {
    let setup = sim::Setup {
        shot: request.setup,
        cushion: cushion_for(request)?,
        jaws: match request.table_name {
            "snooker" => sim::Jaws::SNOOKER,
            _ => sim::Jaws::POOL,
        },
        ..sim::Setup::POOL
    };
    let scene = &request.scene;
    let mut paths: Vec<Vec<Segment>> = scene.balls().iter().map(|_| Vec::new()).collect();
    if let Some(cue) = paths.first_mut() {
        cue.push(Segment {
            since: 0.0,
            until: f32::INFINITY,
            motion: *cue_launch,
        });
    }
    let mut events = Vec::new();
    let finish = sim::play(scene, stroke, &setup, |event, now| {
        let balls: Vec<usize> = std::iter::once(event.ball).chain(event.other).collect();
        for &ball in &balls {
            let Some(path) = paths.get_mut(ball) else {
                continue;
            };
            if let Some(last) = path.last_mut() {
                last.until = last.until.min(event.time);
            }
            if let Some((since, motion)) = now.motion(ball) {
                if since == event.time {
                    path.push(Segment {
                        since,
                        until: f32::INFINITY,
                        motion: *motion,
                    });
                }
            }
        }
        events.push(EventReport {
            time: event.time,
            kind: match event.kind {
                EventKind::Ball => "ball",
                EventKind::Cushion => "cushion",
                EventKind::Pocket(_) => "pocket",
                EventKind::Rest => "rest",
            },
            balls,
            position: [event.position.x, event.position.y],
            pocket: match event.kind {
                EventKind::Pocket(p) => Some(p),
                _ => event.jaw,
            },
        });
    })
    .map_err(|e| ShotError::invalid(format!("whole table: {e}")))?;
    for path in &mut paths {
        if let Some(last) = path.last_mut() {
            if last.until == f32::INFINITY {
                last.until = last.since + last.motion.stop_time();
            }
        }
    }
    let three_cushion = (request.table_name == "carom" && scene.balls().len() == 3)
        .then(|| ThreeCushion::check(&events));
    let target = request
        .pocket
        .map(|pocket| WholeTarget::check(&events, request.object.unwrap_or(1), pocket));
    Ok(TableOutcome {
        target,
        final_positions: finish
            .positions()
            .iter()
            .map(|p| p.map(|p: Vec3| [p.x, p.y]))
            .collect(),
        events,
        paths,
        time: finish.time,
        three_cushion,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn event(kind: &'static str, balls: &[usize]) -> EventReport {
        EventReport {
            time: 0.0,
            kind,
            balls: balls.to_vec(),
            position: [0.0, 0.0],
            pocket: None,
        }
    }

    /// A ball that rattles off its pocket's jaws and drops is pocketed; one the jaws
    /// turn away is not, and the jaws are what it met; another pocket's jaw is a
    /// cushion like any.
    #[test]
    fn the_chosen_pockets_jaws_are_counted_not_taken_as_the_first_contact() {
        let jaw = |pocket: usize| EventReport {
            pocket: Some(pocket),
            ..event("cushion", &[1])
        };
        let drop = |pocket: usize| EventReport {
            pocket: Some(pocket),
            ..event("pocket", &[1])
        };
        let hit = event("ball", &[0, 1]);
        let rattled_in = [hit.clone(), jaw(3), jaw(3), drop(3)];
        assert_eq!(
            WholeTarget::check(&rattled_in, 1, 3),
            WholeTarget {
                pocketed: true,
                jaw_contacts: 2,
                in_the_way: None,
                first: "pocket"
            }
        );
        let turned_away = [
            hit.clone(),
            jaw(3),
            event("cushion", &[1]),
            event("rest", &[1]),
        ];
        assert_eq!(
            WholeTarget::check(&turned_away, 1, 3),
            WholeTarget {
                pocketed: false,
                jaw_contacts: 1,
                in_the_way: None,
                first: "cushion"
            }
        );
        let other_jaw = [hit, jaw(2), drop(3)];
        assert_eq!(
            WholeTarget::check(&other_jaw, 1, 3),
            WholeTarget {
                pocketed: false,
                jaw_contacts: 0,
                in_the_way: None,
                first: "cushion"
            }
        );
    }

    #[test]
    fn three_cushions_before_the_second_ball_score_and_two_do_not() {
        let cushion = || event("cushion", &[0]);
        // Cushions before the first ball count; the object balls' own cushions do not.
        let scoring = [
            cushion(),
            event("ball", &[0, 2]),
            event("cushion", &[2]),
            cushion(),
            cushion(),
            event("ball", &[1, 0]),
        ];
        assert_eq!(
            ThreeCushion::check(&scoring),
            ThreeCushion {
                scored: true,
                first: Some(2),
                second: Some(1),
                cushions: 3
            }
        );
        let two = [
            event("ball", &[0, 1]),
            cushion(),
            event("cushion", &[1]),
            cushion(),
            event("ball", &[0, 2]),
            cushion(),
        ];
        assert_eq!(
            ThreeCushion::check(&two),
            ThreeCushion {
                scored: false,
                first: Some(1),
                second: Some(2),
                cushions: 2
            }
        );
        // The first ball twice, or a kiss between the object balls, is not the second.
        let one = [
            event("ball", &[0, 1]),
            cushion(),
            cushion(),
            cushion(),
            event("ball", &[1, 2]),
            event("ball", &[0, 1]),
        ];
        assert_eq!(
            ThreeCushion::check(&one),
            ThreeCushion {
                scored: false,
                first: Some(1),
                second: None,
                cushions: 3
            }
        );
    }
}
