//! Writes the committed seed corpus, `fuzz/corpus/<target>/`, and checks that each seed
//! reaches what it was written for (a contact, a pocket, an outcome of every model, the
//! answers of the demo session). Run from `fuzz/` after changing a target's input layout:
//!
//! ```sh
//! cargo run --example seeds
//! ```
//!
//! The seeds are small, valid inputs; the fuzzer mutates them into invalid ones.

use std::f32::consts::PI;
use std::fs;
use std::path::{Path, PathBuf};

use cuesight_fuzz::input::Writer;
use cuesight_fuzz::{collide, protocol_line, shot_scene};

fn main() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("corpus");
    let count = protocol_seeds(&corpus.join("protocol_line"))
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

/// Every request line of the demo session alone, the two stroke chunks together, the
/// whole session as one stream, and a few framing cases.
fn protocol_seeds(dir: &Path) -> usize {
    let session: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "firmware",
        "demo",
        "session.jsonl",
    ]
    .iter()
    .collect();
    let text = fs::read_to_string(&session).expect("reading firmware/demo/session.jsonl");
    let requests: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    let mut seeds = Vec::new();
    for (i, line) in requests.iter().enumerate() {
        let name = line
            .trim_start_matches(['{', '"'])
            .split('"')
            .next()
            .unwrap_or("line");
        seeds.push((
            format!("demo-{i:02}-{name}"),
            format!("{line}\n").into_bytes(),
        ));
    }
    // The shot request (protocol feature `shot`): docs/protocol.md's solve, a played
    // aim reported on a pocket, a carom shot that misses, every optional field.
    for (name, line) in [
        (
            "shot-solve",
            r#"{"shot":{"table":"pool","cue":[0.635,0.635],"balls":[[1.9,0.9]],"speed":3.0,"tip":[0.0,0.2],"pocket":3,"model":"auto"}}"#,
        ),
        (
            "shot-aim-reported",
            r#"{"shot":{"table":"snooker","cue":[1.0,0.9],"balls":[[2.5,1.1],[3.0,0.4]],"speed":2.5,"tip":[-0.2,-0.3],"aim":7.6,"object":1,"pocket":3,"model":"exact"}}"#,
        ),
        (
            "shot-carom-miss",
            r#"{"shot":{"table":"carom","cue":[0.7,0.7],"speed":1.0,"aim":90}}"#,
        ),
        (
            "shot-every-field",
            r#"{"shot":{"table":"pool","cue":[0.5,0.3],"balls":[[1.27,0.15],[2.0,1.0]],"speed":4,"tip":[0.25,0.1],"aim":-14,"object":2,"pocket":4,"mu_cloth":0.25,"mu_roll":0.015,"cue_mass":0.5,"tip_restitution":0.8,"mu":0.00995,"mu_b":0.108,"mu_c":1.088,"restitution":0.93,"mu_s":0.2,"mass":0.16,"model":"kim"}}"#,
        ),
    ] {
        seeds.push((name.to_string(), format!("{line}\n").into_bytes()));
    }
    let stroke: String = requests
        .iter()
        .filter(|l| l.starts_with(r#"{"stroke""#))
        .map(|l| format!("{l}\n"))
        .collect();
    seeds.push(("stroke-both-chunks".into(), stroke.into_bytes()));
    let all: String = requests.iter().map(|l| format!("{l}\n")).collect();
    seeds.push(("demo-session-whole".into(), all.into_bytes()));
    let mut overlong = vec![b'{'; cuesight_protocol::MAX_LINE + 10];
    overlong.extend_from_slice(b"\n{\"version\":{}}\n");
    seeds.push(("overlong-then-version".into(), overlong));
    seeds.push((
        "crlf-blank-and-stroke-error".into(),
        b"\r\n \t\n{\"params\":{\"model\":\"auto\"}}\r\n{\"stroke\":{\"samples\":[1,2,3],\"rate_hz\":1000}}\n"
            .to_vec(),
    ));
    for (name, bytes) in &seeds {
        let report = protocol_line::run(bytes);
        let lines = bytes.iter().filter(|&&b| b == b'\n').count() as u32;
        assert!(
            report.answers >= 1 && report.answers <= lines,
            "{name}: {report:?}"
        );
    }
    let whole = protocol_line::run(&seeds[seeds.len() - 3].1);
    for (name, bytes) in seeds.iter().filter(|(name, _)| name.starts_with("shot-")) {
        let report = protocol_line::run(bytes);
        assert_eq!(report.errors, 0, "{name}: {report:?}");
    }
    assert_eq!(whole.answers as usize, requests.len(), "{whole:?}");
    write_all(dir, &seeds)
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
        let calls = 2 * (cuesight::Model::ALL.len() + 1);
        assert_eq!(report.outcomes, calls, "{name}: {report:?}");
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
const COLLIDE_REGRESSIONS: [(&str, &[u8]); 1] = [(
    "unvalidated-infinite-mu-fast-path",
    &[
        0x00, 0x06, 0x39, 0x99, 0x99, 0x99, 0x06, 0xbf, 0xfe, 0xff, 0xbf, 0x06, 0x4f, 0x00, 0x00,
        0x6d, 0x06, 0x51, 0x99, 0x77, 0x77, 0x77, 0x77, 0x77, 0x77, 0x77, 0x02, 0x77, 0x83, 0x41,
        0x83, 0x54, 0xc0, 0x7f, 0xff, 0xff, 0x99, 0x59, 0xc4, 0x99, 0x9e, 0x06,
    ],
)];

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
