//! Writes the committed seed corpus, `fuzz/corpus/<target>/`, and checks that each seed
//! reaches what it was written for (a contact, a pocket, an outcome of every model, a
//! valid frame of every request kind, a whole session's answers, the error of each
//! hostile frame class). Run from `fuzz/` after changing a target's input layout:
//!
//! ```sh
//! cargo run --example seeds
//! ```
//!
//! The seeds are small, valid inputs; the fuzzer mutates them into invalid ones.

use std::f32::consts::PI;
use std::fs;
use std::path::Path;

use cuesight_fuzz::input::Writer;
use cuesight_fuzz::link::{self, op, Script, StrokePlan};
use cuesight_fuzz::{collide, link_frame, link_session, shot_scene};
use cuesight_link::error::{FrameFault, SequenceFault};
use cuesight_link::{LinkError, Overrides, Request, UploadFault, SCHEMA_HASH};

fn main() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus");
    let count = link_frame_seeds(&corpus.join("link_frame"))
        + link_session_seeds(&corpus.join("link_session"))
        + shot_seeds(&corpus.join("shot_scene"))
        + collide_seeds(&corpus.join("collide"));
    println!("wrote {count} seeds under {}", corpus.display());
}

/// Empties `dir` and writes `seeds` into it.
fn write_all(dir: &Path, seeds: &[(String, Vec<u8>)]) -> usize {
    if dir.exists() {
        fs::remove_dir_all(dir).expect("clearing the corpus directory");
    }
    fs::create_dir_all(dir).expect("creating the corpus directory");
    for (name, bytes) in seeds {
        fs::write(dir.join(name), bytes).expect("writing a seed");
    }
    seeds.len()
}

/// `link_frame`: every example request as one valid frame (raw mode), all of them in
/// one stream, the same as a script, and a script of each kind of damage.
fn link_frame_seeds(dir: &Path) -> usize {
    let examples = link::examples();
    let mut seeds = Vec::new();
    let mut all = vec![0u8];
    let mut script = Script::new();
    for (seq, (name, request)) in examples.iter().enumerate() {
        let wire = link::wire(SCHEMA_HASH, seq as u16, &link::body_of(request));
        seeds.push((format!("frame-{name}"), [&[0u8][..], &wire].concat()));
        all.extend_from_slice(&wire);
        script.send(request);
    }
    seeds.push(("frames-every-kind".into(), all));
    seeds.push(("script-every-kind".into(), scripted(&script)));
    let body = link::body_of(&examples[1].1);
    let stroke = link::body_of(&link::stroke_chunks(1, link::synthetic_stroke())[5]);
    for (name, code, a, b, body) in [
        ("script-truncated", op::TRUNCATE, 20, 0, &body),
        ("script-bit-flip", op::FLIP, 0x53, 0, &body),
        ("script-merged", op::MERGE, 0, 0, &body),
        ("script-oversized", op::OVERSIZED, 4, 1, &body),
        ("script-foreign-schema", op::SCHEMA, 3, 0, &body),
        ("script-stroke-chunk-flipped", op::FLIP, 0x07, 2, &stroke),
    ] {
        let mut script = Script::new();
        script.record(code, a, b, body).send(&examples[0].1);
        seeds.push((name.into(), scripted(&script)));
    }
    for (name, bytes) in &seeds {
        let report = link_frame::run(bytes);
        assert!(report.received >= 1, "{name}: {report:?}");
        if name.starts_with("frame-") {
            assert_eq!(
                (report.received, report.requests),
                (1, 1),
                "{name}: {report:?}"
            );
        }
        println!("link_frame/{name}: {report:?}");
    }
    assert_eq!(
        link_frame::run(&seeds[examples.len()].1).requests,
        examples.len()
    );
    write_all(dir, &seeds)
}

/// What a `link_session` seed must reach.
type Check = fn(&link_session::Report) -> bool;

/// A script for `link_frame` (its first byte odd).
fn scripted(script: &Script) -> Vec<u8> {
    [&[1u8][..], script.bytes()].concat()
}

/// `link_session`: a whole session (every example, a stroke upload, shutdown), and one
/// script for each hostile class, which must get its error.
fn link_session_seeds(dir: &Path) -> usize {
    let examples = link::examples();
    let example = |name: &str| {
        examples
            .iter()
            .position(|(n, _)| *n == name)
            .expect("an example") as u8
    };
    let collide = example("collide-stun");
    let mut seeds: Vec<(String, Script, Check)> = Vec::new();
    let mut whole = Script::new();
    for (name, _) in examples.iter().filter(|(n, _)| *n != "shutdown") {
        whole.record(op::EXAMPLE, example(name), 0, &[]);
    }
    whole
        .record(op::STROKE, 7, 0, &StrokePlan::default().body())
        .record(op::EXAMPLE, example("shutdown"), 0, &[]);
    seeds.push(("session-every-kind".into(), whole, |r| {
        r.errors.is_empty() && r.estimates == 1 && r.shots == 3
    }));
    let base = || {
        let mut script = Script::new();
        script.record(op::EXAMPLE, 0, 0, &[]);
        script
    };
    let body = link::body_of(&examples[usize::from(collide)].1);
    let mut hostile = |name: &str, script: Script, check: Check| {
        seeds.push((name.into(), script, check));
    };
    let mut s = base();
    s.send(&examples[usize::from(collide)].1)
        .record(op::RESEND, 0, 0, &[]);
    hostile("duplicate-frame", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::Sequence(SequenceFault::Duplicate { .. })))
    });
    let mut s = base();
    s.record_ab(op::SEQ, 2, &body)
        .send(&examples[usize::from(collide)].1);
    hostile("dropped-frame", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::Sequence(SequenceFault::Gap { .. })))
    });
    let mut s = base();
    s.record_ab(op::SEQ, 1, &body)
        .record_ab(op::SEQ, 0, &body)
        .record(op::RESEND, 1, 0, &[]);
    hostile("reordered-frames", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::Sequence(SequenceFault::Stale { .. })))
    });
    let mut s = base();
    s.record_ab(op::TRUNCATE, 17, &body)
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("truncated-frame", s, |r| {
        r.errors.iter().any(|e| matches!(e, LinkError::Frame(_))) && r.collides == 1
    });
    let mut s = base();
    s.record_ab(op::FLIP, 8 * 12 + 3, &body)
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("bit-flip", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::Frame(FrameFault::Crc { .. })))
            && r.collides == 1
    });
    let mut s = base();
    // Frame 1's zero is lost: it runs into its resend, and both are lost; then sent again.
    s.record(op::MERGE, 0, 0, &body)
        .record_ab(op::SEQ, 0, &body)
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("merged-frames", s, |r| {
        r.errors.iter().any(|e| matches!(e, LinkError::Frame(_))) && r.collides == 1
    });
    let mut s = base();
    s.record(op::OVERSIZED, 10, 3, &[0x42])
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("oversized-frame", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::Frame(FrameFault::Oversized { .. })))
    });
    let mut s = base();
    s.record(op::SCHEMA, 5, 0, &body)
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("foreign-schema", s, |r| {
        r.errors
            .iter()
            .any(|e| matches!(e, LinkError::SchemaMismatch { .. }))
            && r.collides == 1
    });
    // Defaults outside `KimGrip`'s validity domain (μ(0) = 0.05 + 0.49, the default
    // model's limit 0.15): the session answers `params`, and the target's closing
    // `collide` (with `Exact`) is answered (this target found its closing check too
    // strict with the default model).
    let mut s = base();
    s.send(&Request::Params(Overrides {
        mu_b: Some(0.49),
        ..Overrides::default()
    }));
    hostile("defaults-outside-kimgrip", s, |r| r.errors.is_empty());
    let mut s = base();
    s.record(op::RAW, 0, 0, b"{\"version\":{}}\n\x00\x01\x01\x00")
        .record(op::EXAMPLE, collide, 0, &[]);
    hostile("raw-bytes", s, |r| r.errors.len() >= 2 && r.collides == 1);
    for (name, plan, check) in [
        (
            "stroke-glitch-rail",
            StrokePlan {
                glitch: Some((100, i16::MIN)),
                ..StrokePlan::default()
            },
            (|r: &link_session::Report| {
                r.estimates == 0
                    && matches!(
                        r.errors[..],
                        [LinkError::Upload(UploadFault::Glitch {
                            chunk: 0,
                            sample: 100,
                            value: i16::MIN,
                            ..
                        })]
                    )
            }) as Check,
        ),
        (
            "stroke-duplicate-chunk",
            StrokePlan {
                fault: (1, 2),
                ..StrokePlan::default()
            },
            |r| {
                r.estimates == 0
                    && r.errors.iter().any(|e| {
                        matches!(
                            e,
                            LinkError::Upload(UploadFault::Duplicate { chunk: 2, .. })
                        )
                    })
            },
        ),
        (
            "stroke-missing-chunk",
            StrokePlan {
                fault: (2, 3),
                ..StrokePlan::default()
            },
            |r| {
                r.estimates == 0
                    && r.errors.iter().any(|e| {
                        matches!(e, LinkError::Upload(UploadFault::Missing { chunk: 4, .. }))
                    })
            },
        ),
        (
            "stroke-swapped-chunks",
            StrokePlan {
                fault: (3, 1),
                ..StrokePlan::default()
            },
            |r| {
                r.estimates == 0
                    && r.errors.iter().any(|e| {
                        matches!(e, LinkError::Upload(UploadFault::Missing { chunk: 2, .. }))
                    })
            },
        ),
        (
            "stroke-setup-every-field",
            StrokePlan {
                setup: Writer::new()
                    .real(500.0, 8000.0, 1000.0)
                    .flag(true)
                    .real(-0.01, 0.01, cuesight_sensors::ACCEL_MPS2_PER_LSB)
                    .flag(true)
                    .pair(-0.02, 0.02, [0.005, -0.01])
                    .flag(true)
                    .real(0.1, 2.0, 0.5)
                    .flag(true)
                    .real(0.0, 1.0, 0.8)
                    .bytes()
                    .to_vec(),
                ..StrokePlan::default()
            },
            |r| r.errors.is_empty() && r.estimates == 1,
        ),
        (
            "stroke-partial",
            StrokePlan {
                chunks: 3,
                ..StrokePlan::default()
            },
            |r| r.errors.is_empty() && r.estimates == 0,
        ),
    ] {
        let mut s = base();
        s.record(op::STROKE, 9, plan.chunks, &plan.body());
        seeds.push((name.into(), s, check));
    }
    let mut written = Vec::new();
    for (name, script, check) in &seeds {
        let report = link_session::run(script.bytes());
        assert!(check(&report), "{name}: {report:?}");
        println!(
            "link_session/{name}: {} answers, {} errors {:?}, {} estimates, {} shots",
            report.answers,
            report.errors.len(),
            report.errors.first(),
            report.estimates,
            report.shots
        );
        written.push((name.clone(), script.bytes().to_vec()));
    }
    write_all(dir, &written)
}

/// One shot, laid out in the order `shot_scene::run` reads it.
struct Shot {
    /// 0 pool, 1 snooker, 2 carom.
    table: u8,
    length: f32,
    width: f32,
    cue_ball: [f32; 2],
    balls: Vec<[f32; 2]>,
    /// μ, e*, μ_s, M.
    params: [f32; 4],
    /// Speed-dependent law `a, b, c`.
    law: Option<[f32; 3]>,
    mu_ct: Option<f32>,
    cue: Option<[f32; 2]>,
    cloth: Option<[f32; 2]>,
    /// 0 Ideal … 3 Exact; 4 Auto with the tolerance.
    model: (u8, f32),
    cue_speed: f32,
    /// Tip offset, fractions of R.
    tip: [f32; 2],
    /// Aimed at this ball with this offset (in R).
    aim_at: (u8, f32),
    /// Inverse aim: object ball and pocket.
    solve: (u8, u8),
    /// Guidance: 0 solve for that target; 1 play the aim (degrees) and report on the
    /// target; 2 play the aim alone.
    guide: (u8, f32),
    expect: shot_scene::Report,
}

impl Shot {
    fn bytes(&self) -> Vec<u8> {
        let mut w = Writer::new();
        let (length, width) = (self.length, self.width);
        w.choice(self.table).choice(1); // the set's radius
        w.real(-0.1, length + 0.1, self.cue_ball[0])
            .real(-0.1, width + 0.1, self.cue_ball[1]);
        w.choice(self.balls.len() as u8);
        for p in &self.balls {
            w.real(-0.1, length + 0.1, p[0])
                .real(-0.1, width + 0.1, p[1]);
        }
        let [mu, e, mu_s, mass] = self.params;
        w.choice(1) // the scene's radius
            .real(0.0, 0.2, mu)
            .real(0.5, 1.0, e)
            .real(0.0, 0.5, mu_s)
            .real(0.05, 1.0, mass);
        w.flag(self.law.is_some());
        if let Some([a, b, c]) = self.law {
            w.real(1e-6, 0.05, a).real(0.0, 0.2, b).real(0.0, 5.0, c);
        }
        w.flag(self.mu_ct.is_some());
        if let Some(mu_ct) = self.mu_ct {
            w.real(0.0, 0.3, mu_ct);
        }
        w.flag(self.cue.is_some());
        if let Some([mass, e_t]) = self.cue {
            w.real(0.1, 2.0, mass).real(0.0, 1.0, e_t);
        }
        w.flag(self.cloth.is_some());
        if let Some([sliding, rolling]) = self.cloth {
            w.real(0.0, 1.0, sliding).real(0.0, 0.5, rolling);
        }
        w.choice(self.model.0);
        if self.model.0 == 4 {
            w.real(1e-4, 0.1, self.model.1);
        }
        w.real(0.0, 8.0, self.cue_speed).flag(true);
        w.pair(-0.6, 0.6, self.tip);
        w.choice(2)
            .choice(self.aim_at.0)
            .real(-2.0, 2.0, self.aim_at.1);
        // Probes of the cue ball's and the object ball's motions.
        w.real(0.0, 10.0, 0.5).real(0.0, 3.0, 0.3);
        w.real(0.0, 10.0, 1.0).real(0.0, 3.0, 0.5);
        // A free motion: a rolling ball with side spin.
        w.pair(-1e3, 1e3, [1.0, 0.5])
            .triple(-1e3, 1e3, [1.5, 0.5, 0.0])
            .triple(-1e6, 1e6, [-17.5, 52.5, 30.0])
            .real(0.001, 1.0, 0.028575)
            .real(0.0, 1.0, 0.2)
            .real(0.0, 0.5, 0.01)
            .real(0.0, 100.0, 0.7);
        w.choice(self.solve.0).choice(self.solve.1);
        w.choice(self.guide.0);
        if self.guide.0 != 0 {
            w.real(-180.0, 180.0, self.guide.1);
        }
        w.bytes().to_vec()
    }
}

fn pool_shot() -> Shot {
    Shot {
        table: 0,
        length: 2.54,
        width: 1.27,
        cue_ball: [1.0, 0.5],
        balls: vec![[2.0, 1.0]],
        params: [0.06, 0.95, 0.3, 0.17],
        law: None,
        mu_ct: None,
        cue: None,
        cloth: None,
        model: (2, 0.0),
        cue_speed: 2.0,
        tip: [0.0, 0.0],
        aim_at: (1, 0.0),
        solve: (1, 3),
        guide: (0, 0.0),
        expect: shot_scene::Report {
            balls: 2,
            played: true,
            contact: true,
            pocketed: false,
            aimed: true,
            guided: true,
        },
    }
}

/// A triangle of `rows` rows with its apex at `apex`, pointing along −x.
fn rack(apex: [f32; 2], rows: usize, radius: f32) -> Vec<[f32; 2]> {
    let pitch = 2.0 * radius * 1.0001;
    let mut balls = Vec::new();
    for row in 0..rows {
        for k in 0..=row {
            let x = apex[0] + row as f32 * pitch * (3f32).sqrt() / 2.0;
            let y = apex[1] + (k as f32 - row as f32 / 2.0) * pitch;
            balls.push([x, y]);
        }
    }
    balls
}

fn shot_seeds(dir: &Path) -> usize {
    let pool_r = 0.028575;
    let mut shots = vec![("pool-cut-kimgrip-aim".to_string(), pool_shot())];
    // Straight in: the object ball 30 cm from the corner pocket at (L, W).
    let mut straight = pool_shot();
    straight.cue_ball = [1.5, 0.5];
    straight.balls = vec![[2.2, 1.011]];
    straight.model = (4, 1e-3);
    straight.tip = [0.0, 0.3];
    straight.expect.pocketed = true;
    shots.push(("pool-straight-in-auto-follow".into(), straight));
    // Snooker draw with Marlow's friction and μ_ct, Exact.
    let mut snooker = pool_shot();
    snooker.table = 1;
    (snooker.length, snooker.width) = (3.569, 1.778);
    snooker.cue_ball = [1.0, 0.9];
    snooker.balls = vec![[2.5, 1.1], [3.0, 0.4], [0.5, 1.5]];
    snooker.params = [0.06, 0.95, 0.3, 0.142];
    snooker.law = Some([9.951e-3, 0.108, 1.088]);
    snooker.mu_ct = Some(0.2);
    snooker.model = (3, 0.0);
    snooker.tip = [0.0, -0.35];
    snooker.solve = (1, 3);
    snooker.guide = (1, 10.0);
    snooker.expect.balls = 4;
    shots.push(("snooker-draw-marlow-exact".into(), snooker));
    // Carom: no pockets, side spin, another cue and cloth, Kim.
    let mut carom = pool_shot();
    carom.table = 2;
    (carom.length, carom.width) = (2.84, 1.42);
    carom.cue_ball = [0.7, 0.7];
    carom.balls = vec![[2.0, 0.8], [2.3, 0.3]];
    carom.params = [0.05, 0.93, 0.2, 0.21];
    carom.cue = Some([0.5, 0.8]);
    carom.cloth = Some([0.25, 0.015]);
    carom.model = (1, 0.0);
    carom.tip = [0.3, 0.2];
    carom.expect.balls = 3;
    carom.expect.aimed = false;
    carom.guide = (2, 5.0);
    shots.push(("carom-side-spin-kim".into(), carom));
    // A full rack and two balls more than the scene holds; a 6 m/s break, Ideal.
    let mut rack_shot = pool_shot();
    rack_shot.cue_ball = [0.635, 0.635];
    rack_shot.balls = rack([1.905, 0.635], 5, pool_r);
    rack_shot.balls.extend([[0.3, 0.3], [0.3, 1.0]]);
    rack_shot.model = (0, 0.0);
    rack_shot.cue_speed = 6.0;
    rack_shot.expect.balls = 16;
    rack_shot.expect.aimed = false;
    rack_shot.guide = (1, 0.0);
    shots.push(("pool-rack-over-capacity-break".into(), rack_shot));
    // Thin cut with english towards a side pocket.
    let mut thin = pool_shot();
    thin.cue_ball = [0.6, 0.3];
    thin.balls = vec![[1.27, 0.15]];
    thin.tip = [-0.25, 0.1];
    thin.aim_at = (1, 1.2);
    thin.solve = (1, 4);
    thin.expect.aimed = false;
    thin.guide = (1, -12.0);
    shots.push(("pool-thin-cut-english".into(), thin));

    let mut seeds = Vec::new();
    for (name, shot) in &shots {
        let bytes = shot.bytes();
        let report = shot_scene::run(&bytes);
        let expect = &shot.expect;
        assert_eq!(
            (report.balls, report.played, report.contact),
            (expect.balls, expect.played, expect.contact),
            "{name}: {report:?}"
        );
        assert!(
            report.pocketed >= expect.pocketed
                && report.aimed >= expect.aimed
                && report.guided >= expect.guided,
            "{name}: {report:?}"
        );
        println!("shot_scene/{name}: {report:?}");
        seeds.push((name.clone(), bytes));
    }
    write_all(dir, &seeds)
}

/// One collision, laid out in the order `collide::run` reads it.
struct Collision {
    /// The whole valid domain rather than physical ranges.
    valid: bool,
    /// μ, e*, μ_s, R, M.
    params: [f32; 5],
    mu_ct: Option<f32>,
    /// 0 constant, 1 speed-dependent (a, b, c), 2 a constant that skipped validation.
    law: (u8, [f32; 3]),
    /// 0 velocity (vx, vy), 1 cut (speed, rad), 2 cut (speed, degrees), 3 rolling.
    impact: (u8, [f32; 2]),
    spin: [f32; 3],
    tolerance: f32,
}

impl Collision {
    fn bytes(&self) -> Vec<u8> {
        let mut w = Writer::new();
        w.flag(self.valid);
        let ranges: [(f32, f32); 5] = if self.valid {
            [
                (0.0, 1.0),
                (0.0, 1.0),
                (0.0, 1.0),
                (0.001, 1.0),
                (0.001, 100.0),
            ]
        } else {
            [(0.0, 0.1), (0.8, 1.0), (0.0, 0.4), (0.02, 0.04), (0.1, 0.3)]
        };
        for (value, (lo, hi)) in self.params.iter().zip(ranges) {
            w.real(lo, hi, *value);
        }
        w.flag(self.mu_ct.is_some());
        if let Some(mu_ct) = self.mu_ct {
            w.real(0.0, if self.valid { 1.0 } else { 0.3 }, mu_ct);
        }
        w.choice(self.law.0);
        let [a, b, c] = self.law.1;
        match self.law.0 {
            1 if self.valid => w.real(1e-6, 1.0, a).real(0.0, 1.0, b).real(0.0, 100.0, c),
            1 => w.real(1e-6, 0.05, a).real(0.0, 0.2, b).real(0.0, 5.0, c),
            2 => w.flag(true).real(-1.0, 2.0, a),
            _ => &mut w,
        };
        let (speed, spin) = if self.valid {
            (100.0, 10_000.0)
        } else {
            (10.0, 200.0)
        };
        let [first, second] = self.impact.1;
        w.choice(self.impact.0);
        match self.impact.0 {
            0 => w.real(0.0, speed, first).real(-speed, speed, second),
            1 => w.real(0.0, speed, first).real(-PI / 2.0, PI / 2.0, second),
            2 => w.real(0.0, speed, first).real(-90.0, 90.0, second),
            _ => w.real(-speed, speed, first).real(-speed, speed, second),
        };
        if self.impact.0 < 3 {
            w.triple(-spin, spin, self.spin);
        }
        w.real(0.0, 0.1, self.tolerance);
        w.bytes().to_vec()
    }
}

fn collide_seeds(dir: &Path) -> usize {
    let mut cases = vec![("readme-topspin-cut".to_string(), readme_collision())];
    let with = |f: &dyn Fn(&mut Collision)| {
        let mut c = readme_collision();
        f(&mut c);
        c
    };
    cases.push((
        "head-on-stun".into(),
        with(&|c| {
            c.impact = (0, [1.0, 0.0]);
            c.spin = [0.0; 3];
        }),
    ));
    cases.push((
        "draw-cut-radians-cue-table-friction".into(),
        with(&|c| {
            c.impact = (1, [2.0, 0.35]);
            c.spin = [0.0, -70.0, 0.0];
            c.mu_ct = Some(0.2);
        }),
    ));
    cases.push((
        "marlow-law".into(),
        with(&|c| c.law = (1, [9.951e-3, 0.108, 1.088])),
    ));
    cases.push((
        "gearing-no-slip".into(),
        with(&|c| {
            c.impact = (2, [1.0, 30.0]);
            c.spin = [0.0, 0.0, -17.4978];
        }),
    ));
    cases.push(("natural-roll".into(), with(&|c| c.impact = (3, [2.0, 0.5]))));
    cases.push((
        "snooker-side-spin-tight-tolerance".into(),
        with(&|c| {
            c.params = [0.05, 0.9, 0.2, 0.02625, 0.142];
            c.spin = [5.0, 20.0, 60.0];
            c.tolerance = 1e-5;
        }),
    ));
    cases.push((
        "valid-domain-corner".into(),
        with(&|c| {
            c.valid = true;
            c.params = [0.5, 0.5, 0.8, 0.01, 5.0];
            c.mu_ct = Some(0.5);
            c.impact = (0, [50.0, -40.0]);
            c.spin = [3000.0, -2000.0, 5000.0];
            c.tolerance = 0.05;
        }),
    ));
    cases.push((
        "unvalidated-constant-law".into(),
        with(&|c| c.law = (2, [-0.5, 0.0, 0.0])),
    ));
    let mut seeds = Vec::new();
    for (name, case) in &cases {
        let bytes = case.bytes();
        let report = collide::run(&bytes);
        assert!(report.valid, "{name}: {report:?}");
        // Every call answers, refuses as its model's validity domain declares (`Kim`
        // where the contact grips: the head-on stun), or errs on an input that skipped
        // validation (the unvalidated law).
        let calls = 2 * (cuesight::Model::ALL.len() + 1);
        assert_eq!(
            report.outcomes + report.refusals + report.rejected,
            calls,
            "{name}: {report:?}"
        );
        println!("collide/{name}: {report:?}");
        seeds.push((name.clone(), bytes));
    }
    // Inputs the fuzzer once failed on, kept byte for byte: μ = ∞ through the enum's
    // `Constant` variant (unvalidated) gave `KimGrip`'s fast path a NaN velocity.
    for (name, bytes) in COLLIDE_REGRESSIONS {
        let report = collide::run(bytes);
        assert!(report.valid, "{name}: {report:?}");
        println!("collide/{name}: {report:?}");
        seeds.push((name.to_string(), bytes.to_vec()));
    }
    write_all(dir, &seeds)
}

/// Crash inputs of the `collide` target, as `cargo fuzz` wrote them.
const COLLIDE_REGRESSIONS: [(&str, &[u8]); 2] = [
    (
        "unvalidated-infinite-mu-fast-path",
        &[
            0x00, 0x06, 0x39, 0x99, 0x99, 0x99, 0x06, 0xbf, 0xfe, 0xff, 0xbf, 0x06, 0x4f, 0x00,
            0x00, 0x6d, 0x06, 0x51, 0x99, 0x77, 0x77, 0x77, 0x77, 0x77, 0x77, 0x77, 0x02, 0x77,
            0x83, 0x41, 0x83, 0x54, 0xc0, 0x7f, 0xff, 0xff, 0x99, 0x59, 0xc4, 0x99, 0x9e, 0x06,
        ],
    ),
    (
        "regression-speed-path-unvalidated-law",
        &[
            0x00, 0x06, 0x39, 0x99, 0x99, 0x02, 0x01, 0xab, 0x06, 0xaa, 0xaa, 0x7e, 0x02, 0x06,
            0x33, 0x33, 0x33, 0x33, 0x06, 0xaa, 0xaa, 0xaa, 0xaa, 0x06, 0x00, 0x00, 0x00, 0x80,
            0x06, 0x99, 0x99, 0x99, 0x99, 0x06, 0x00, 0x00, 0x00, 0x2a, 0x02, 0x06, 0x33, 0x33,
            0x33, 0x33, 0x06, 0x7e, 0xaa, 0xaa, 0xaa, 0xaa, 0x06, 0x00, 0x00, 0x00, 0x80, 0x06,
            0x99, 0x99, 0x99, 0x99, 0x06, 0x00, 0x00, 0x00, 0x80, 0x11, 0xb0, 0xee, 0xd6, 0x3f,
            0x69, 0xd8, 0x3f, 0x06, 0x2a, 0x5c, 0x8f, 0x02,
        ],
    ),
];

/// The README's shot: 2 m/s, cut 30°, 40 rad/s of topspin, μ = 0.06, pool balls.
fn readme_collision() -> Collision {
    Collision {
        valid: false,
        params: [0.06, 0.95, 0.3, 0.028575, 0.17],
        mu_ct: None,
        law: (0, [0.0; 3]),
        impact: (2, [2.0, 30.0]),
        spin: [0.0, 40.0, 0.0],
        tolerance: 1e-3,
    }
}
