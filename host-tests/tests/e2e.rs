//! End-to-end: the release firmware in QEMU, driven over its serial port.
//!
//! 1. ≥ 200 seeded `collide` requests over the grid's domain (every core model, natural
//!    roll, speed-dependent friction), each answer compared field by field with the
//!    host's own `Collide::prepare` + `cuesight::collide` (f32 against f32):
//!    `|a − b| ≤ 1e-5·max(|a|, |b|) + 1e-6`, the absolute floor of 1e-6 in the field's
//!    unit (m/s, rad/s, N·s, degrees) covering components that are zero up to rounding.
//! 2. Four synthetic strokes sent in `stroke` chunks, each answer compared with the
//!    host's own protocol session on the same lines (same tolerance).
//! 3. ≥ 1,000 seeded malformed lines (bad JSON, truncated, overlong, unknown requests
//!    and fields, NaN/inf/out-of-range values, wrong types, random bytes), streamed
//!    back to back: each must get exactly one `{"error":...}` answer of the expected
//!    kind, and a valid request sent after them must get its normal answer.
//! 4. `shutdown`: the session counters match and QEMU exits 0.
//!
//! Needs the release firmware and QEMU, so it is `#[ignore]`d in a plain `cargo test`;
//! `cargo xtask test` builds the firmware and runs it:
//! `cargo test -p cuesight-host --test e2e -- --ignored --nocapture`
//! (`CUESIGHT_FIRMWARE_ELF` overrides the ELF path).

use std::collections::BTreeMap;
use std::io::Write;
use std::time::{Duration, Instant};

use cuesight::Model;
use cuesight_host::firmware::{self, Firmware};
use cuesight_host::grid;
use cuesight_host::strokes::{stroke_requests, synthetic_stroke};
use cuesight_protocol::{
    Answer, AnswerLine, Collide, CollideAnswer, Defaults, ErrorKind, Identity, ModelName,
    Overrides, Request, Session, Spin, MAX_LINE, MAX_SAMPLES,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const RTOL: f64 = 1e-5;
const ATOL: f64 = 1e-6;
const COLLIDES: usize = 250;
const MALFORMED: usize = 1200;
const ANSWER_TIMEOUT: Duration = Duration::from_secs(30);
/// Synthetic strokes: (seed, sample rate in Hz, cue speed at impact in m/s).
/// (A 1.33 s synthetic stroke at 6.67 kHz would exceed the session's 5,000 samples.)
const STROKES: [(u64, f64, f64); 4] = [
    (11, 3333.0, 1.5),
    (12, 3333.0, 3.0),
    (13, 3333.0, 5.0),
    (14, 1000.0, 0.8),
];

/// The seeded collide requests: grid scenes as speed and cut angle, cycling through the
/// core's models; every 7th with natural roll, every 5th with TP A.14's speed-dependent
/// friction.
fn collide_requests() -> Vec<Collide> {
    grid::scenes(2024, COLLIDES)
        .iter()
        .enumerate()
        .map(|(i, scene)| {
            let [vx, vy] = scene.velocity.map(f64::from);
            let (mu_b, mu_c) = if i % 5 == 4 {
                (Some(0.108), Some(1.088))
            } else {
                (None, None)
            };
            Collide {
                speed: vx.hypot(vy) as f32,
                cut: vy.atan2(vx).to_degrees() as f32,
                spin: if i % 7 == 3 {
                    Spin::Roll
                } else {
                    Spin::Given(scene.spin)
                },
                with: Overrides {
                    mu: Some(if mu_b.is_some() { 0.00995 } else { scene.mu }),
                    mu_b,
                    mu_c,
                    restitution: Some(scene.restitution),
                    mu_s: Some(scene.mu_s),
                    radius: Some(scene.radius),
                    mass: Some(scene.mass),
                    model: Some(ModelName::from(Model::ALL[i % Model::ALL.len()])),
                },
            }
        })
        .collect()
}

/// What the host core says for `request`.
fn expected(request: &Collide) -> CollideAnswer {
    let prepared = request.prepare(&Defaults::POOL).expect("valid request");
    let model = prepared.model.core().expect("a core model");
    let outcome = cuesight::collide(&prepared.params, &prepared.impact, model).expect("solves");
    CollideAnswer::new(prepared.model, prepared.input, &outcome)
}

/// Every number of a collide answer, named.
fn numbers(a: &CollideAnswer) -> Vec<(String, f32)> {
    let mut out = Vec::new();
    let mut push3 = |name: &str, v: [f32; 3]| {
        for (axis, x) in ["x", "y", "z"].iter().zip(v) {
            out.push((format!("{name}.{axis}"), x));
        }
    };
    push3("cue.v", a.cue.v);
    push3("cue.w", a.cue.w);
    push3("object.v", a.object.v);
    push3("object.w", a.object.w);
    push3("impulses.friction", a.impulses.friction);
    push3("input.spin", a.input.spin);
    out.extend([
        ("throw_deg".to_owned(), a.throw_deg),
        ("cue_deflection_deg".to_owned(), a.cue_deflection_deg),
        ("separation_deg".to_owned(), a.separation_deg),
        ("impulses.normal".to_owned(), a.impulses.normal),
        (
            "impulses.table_friction".to_owned(),
            a.impulses.table_friction,
        ),
    ]);
    out
}

/// A malformed line and the error kinds it may get.
struct Bad {
    category: &'static str,
    line: Vec<u8>,
    kinds: &'static [ErrorKind],
}

fn is_json(line: &[u8]) -> bool {
    serde_json::from_slice::<serde::de::IgnoredAny>(line).is_ok()
}

fn valid_line(rng: &mut ChaCha8Rng) -> Vec<u8> {
    let request = Collide {
        spin: Spin::Given([0.0, rng.random_range(-100.0..100.0), 0.0]),
        ..Collide::new(rng.random_range(0.5..5.0), rng.random_range(-60.0..60.0))
    };
    serde_json::to_vec(&Request::Collide(request)).unwrap()
}

fn random_name(rng: &mut ChaCha8Rng) -> String {
    let len = rng.random_range(1..12);
    (0..len)
        .map(|_| char::from(b"abcdefghijklmnopqrstuvwxyz_"[rng.random_range(0..27)]))
        .collect()
}

/// A stun collide line with `field` set to the raw JSON text `value`.
fn collide_with(field: &str, value: &str) -> String {
    match field {
        "speed" => format!(r#"{{"collide":{{"speed":{value},"cut":30}}}}"#),
        "cut" => format!(r#"{{"collide":{{"speed":2,"cut":{value}}}}}"#),
        _ => format!(r#"{{"collide":{{"speed":2,"cut":30,"{field}":{value}}}}}"#),
    }
}

/// The seeded malformed lines, cycling through the categories.
fn malformed_lines() -> Vec<Bad> {
    use ErrorKind::*;
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    let mut out = Vec::new();
    let mut i = 0;
    while out.len() < MALFORMED {
        i += 1;
        let bad = match i % 10 {
            // A valid request with one byte replaced, inserted or deleted, kept only if
            // that made it invalid JSON.
            0 => {
                let mut line = valid_line(&mut rng);
                let at = rng.random_range(0..line.len());
                let junk = b"{}[]\":,.-+eE0x \\"[rng.random_range(0..16)];
                match rng.random_range(0..3) {
                    0 => line[at] = junk,
                    1 => line.insert(at, junk),
                    _ => {
                        line.remove(at);
                    }
                }
                Bad {
                    category: "bad JSON",
                    line,
                    kinds: &[MalformedJson],
                }
            }
            1 => {
                let mut line = valid_line(&mut rng);
                line.truncate(rng.random_range(1..line.len()));
                Bad {
                    category: "truncated",
                    line,
                    kinds: &[MalformedJson],
                }
            }
            2 if i % 100 == 2 => {
                // Overlong: a valid request padded past the line buffer.
                let mut line = b"{\"collide\":{\"speed\":2,\"cut\":30".to_vec();
                let pad = MAX_LINE + rng.random_range(1..2000);
                line.extend(std::iter::repeat_n(b' ', pad));
                line.extend_from_slice(b"}}");
                Bad {
                    category: "overlong",
                    line,
                    kinds: &[LineTooLong],
                }
            }
            2 => {
                let line = format!("{{\"{}\":{{}}}}", random_name(&mut rng));
                Bad {
                    category: "unknown request",
                    line: line.into_bytes(),
                    kinds: &[UnknownRequest],
                }
            }
            3 => {
                let name = random_name(&mut rng);
                let (line, kinds): (String, &'static [ErrorKind]) = match rng.random_range(0..3) {
                    0 => (
                        format!(r#"{{"collide":{{"speed":2,"cut":30,"{name}x":1}}}}"#),
                        &[UnknownField],
                    ),
                    1 => (
                        format!(r#"{{"params":{{"{name}x":0.1}}}}"#),
                        &[UnknownField],
                    ),
                    _ => (
                        format!(r#"{{"version":{{"{name}":true}}}}"#),
                        &[UnknownField],
                    ),
                };
                Bad {
                    category: "unknown field",
                    line: line.into_bytes(),
                    kinds,
                }
            }
            4 => {
                let field = [
                    "speed",
                    "cut",
                    "mu",
                    "restitution",
                    "mu_s",
                    "radius",
                    "mass",
                ][rng.random_range(0..7)];
                let value = ["NaN", "Infinity", "-Infinity", "nan", "inf"][rng.random_range(0..5)];
                let line = format!(r#"{{"collide":{{"speed":2,"cut":30,"{field}":{value}}}}}"#);
                // Not JSON: NaN and infinities have no JSON spelling.
                Bad {
                    category: "NaN/inf token",
                    line: line.into_bytes(),
                    kinds: &[MalformedJson],
                }
            }
            5 => {
                let field = [
                    "speed",
                    "cut",
                    "mu",
                    "restitution",
                    "mu_s",
                    "radius",
                    "mass",
                ][rng.random_range(0..7)];
                let value = ["null", "1e39", "-1e39", "3.5e38"][rng.random_range(0..4)];
                let line = collide_with(field, value);
                Bad {
                    category: "non-finite value",
                    line: line.into_bytes(),
                    kinds: &[NotFinite],
                }
            }
            6 => {
                let (field, value) = [
                    ("speed", "-1"),
                    ("speed", "0"),
                    ("speed", "150"),
                    ("cut", "90"),
                    ("cut", "-95"),
                    ("mu", "-0.01"),
                    ("mu", "1.5"),
                    ("restitution", "1.01"),
                    ("mu_s", "-1"),
                    ("radius", "0"),
                    ("mass", "1000"),
                    ("mu_b", "2"),
                    ("mu_c", "-3"),
                ][rng.random_range(0..13)];
                let line = collide_with(field, value);
                Bad {
                    category: "out of range",
                    line: line.into_bytes(),
                    kinds: &[OutOfRange],
                }
            }
            7 => {
                let line = [
                    r#"{"collide":{"speed":"2","cut":30}}"#,
                    r#"{"collide":{"speed":2,"cut":[30]}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"spin":[1,2]}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"spin":{"x":1}}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"roll":"yes"}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"model":5}}"#,
                    r#"{"params":{"mu":true}}"#,
                    r#"{"collide":"fast"}"#,
                    r#"{"version":[]}"#,
                    r#"{"stroke":{"rate_hz":3333,"samples":[[1,2]]}}"#,
                ][rng.random_range(0..10)];
                Bad {
                    category: "wrong type",
                    line: line.as_bytes().to_vec(),
                    kinds: &[WrongType],
                }
            }
            8 => {
                let line = [
                    r#"{"collide":{"cut":30}}"#,
                    r#"{"collide":{"speed":2}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"speed":3}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"spin":[0,0,0],"roll":true}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"model":"kimgrip"}}"#,
                    r#"{"collide":{"speed":2,"cut":30,"model":"reference"}}"#,
                    r#"{}"#,
                    r#"[{"version":{}}]"#,
                    r#"{"version":{},"shutdown":{}}"#,
                    r#""version""#,
                ][rng.random_range(0..10)];
                Bad {
                    category: "other schema",
                    line: line.as_bytes().to_vec(),
                    kinds: &[
                        MissingField,
                        DuplicateField,
                        Conflict,
                        InvalidValue,
                        Unsupported,
                        NotARequest,
                    ],
                }
            }
            _ => {
                // Random bytes: anything but a newline, never blank.
                let len = rng.random_range(1..200);
                let line: Vec<u8> = (0..len)
                    .map(|_| loop {
                        let b: u8 = rng.random();
                        if b != b'\n' {
                            break b;
                        }
                    })
                    .collect();
                if line.iter().all(|b| matches!(b, b' ' | b'\t' | b'\r')) {
                    continue;
                }
                Bad {
                    category: "random bytes",
                    line,
                    kinds: &[MalformedJson, NotARequest],
                }
            }
        };
        // Mutations that happen to stay valid JSON are not malformed: skip them.
        if matches!(bad.category, "bad JSON" | "truncated") && is_json(&bad.line) {
            continue;
        }
        out.push(bad);
    }
    out
}

fn parse(line: &str) -> Answer {
    serde_json::from_str(line).unwrap_or_else(|e| panic!("unparseable answer {line:?}: {e}"))
}

#[test]
#[ignore = "boots the release firmware in QEMU: run by `cargo xtask test` after the firmware build"]
fn firmware_in_qemu_agrees_with_the_host_core_and_survives_malformed_input() {
    let elf = firmware::default_elf();
    let defmt_print = firmware::find_defmt_print();
    let started = Instant::now();
    let mut fw = Firmware::boot(&elf, defmt_print.as_deref()).expect("QEMU boots the firmware");

    let version = fw.request(br#"{"version":{}}"#, ANSWER_TIMEOUT).unwrap();
    let Answer::Version(version) = parse(&version) else {
        panic!("{version}")
    };
    assert_eq!(version.protocol, cuesight_protocol::PROTOCOL_VERSION);
    assert_eq!(version.max_line as usize, MAX_LINE);
    println!(
        "e2e: {} on {}, protocol {}",
        version.firmware, version.board, version.protocol
    );

    // 1. Collide requests against the host core.
    let requests = collide_requests();
    let (mut max_rel, mut worst) = (0.0f64, String::new());
    let (mut compared, mut identical) = (0usize, 0usize);
    let mut per_model: BTreeMap<&str, usize> = BTreeMap::new();
    let t = Instant::now();
    for request in &requests {
        let line = serde_json::to_vec(&Request::Collide(*request)).unwrap();
        let answer = fw.request(&line, ANSWER_TIMEOUT).unwrap();
        let got = match parse(&answer) {
            Answer::Collide(c) => c,
            other => panic!("{}: {other:?}", String::from_utf8_lossy(&line)),
        };
        let want = expected(request);
        assert_eq!(got.model, want.model);
        assert_eq!(
            got.regime,
            want.regime,
            "{}",
            String::from_utf8_lossy(&line)
        );
        assert_eq!(got.input.roll, want.input.roll);
        *per_model.entry(want.model.name()).or_default() += 1;
        for ((name, a), (_, b)) in numbers(&got).into_iter().zip(numbers(&want)) {
            let (a, b) = (f64::from(a), f64::from(b));
            let scale = a.abs().max(b.abs());
            assert!(
                (a - b).abs() <= RTOL * scale + ATOL,
                "{name}: firmware {a} vs host {b} for {}",
                String::from_utf8_lossy(&line)
            );
            compared += 1;
            if a.to_bits() == b.to_bits() {
                identical += 1;
            }
            if scale > ATOL {
                let rel = (a - b).abs() / scale;
                if rel > max_rel {
                    max_rel = rel;
                    worst = name.clone();
                }
            }
        }
    }
    let collide_secs = t.elapsed().as_secs_f64();
    assert!(requests.len() >= 200);
    println!(
        "e2e: {} collide requests ({}), {compared} numbers compared: max relative error {max_rel:.3e}{}, \
         {identical} bit-identical; tolerance |a-b| <= {RTOL:e}*max(|a|,|b|) + {ATOL:e}; {collide_secs:.2} s",
        requests.len(),
        per_model
            .iter()
            .map(|(m, n)| format!("{m} {n}"))
            .collect::<Vec<_>>()
            .join(", "),
        if worst.is_empty() {
            String::new()
        } else {
            format!(" (in {worst})")
        }
    );

    // 2. Strokes in chunks, against the host's own protocol session (the same estimator
    //    and strike model, compiled for the host) and the speed that generated them.
    let mut host = Session::new(Identity {
        firmware: "host",
        board: "host",
    });
    let mut out = AnswerLine::new();
    let (mut stroke_lines, mut strokes, mut max_truth_error) = (0usize, 0usize, 0.0f64);
    let t = Instant::now();
    for (seed, rate, speed) in STROKES {
        let stroke = synthetic_stroke(seed, rate, speed);
        for request in stroke_requests(&stroke, MAX_SAMPLES) {
            let line = serde_json::to_vec(&request).unwrap();
            let got = parse(&fw.request(&line, ANSWER_TIMEOUT).unwrap());
            host.serve_line(&line, &mut out).unwrap();
            let want = parse(std::str::from_utf8(&out).unwrap().trim_end());
            stroke_lines += 1;
            match (&got, &want) {
                (Answer::StrokeChunk(a), Answer::StrokeChunk(b)) => assert_eq!(a, b),
                (Answer::Stroke(a), Answer::Stroke(b)) => {
                    let pairs = [
                        (a.cue_speed, b.cue_speed),
                        (a.ball_speed, b.ball_speed),
                        (a.ball_spin[1], b.ball_spin[1]),
                        (a.stroke_duration, b.stroke_duration),
                        (a.rest_noise, b.rest_noise),
                    ];
                    for (x, y) in pairs.map(|(x, y)| (f64::from(x), f64::from(y))) {
                        let scale = x.abs().max(y.abs());
                        assert!((x - y).abs() <= RTOL * scale + ATOL, "{a:?} vs {b:?}");
                        if scale > ATOL {
                            max_rel = max_rel.max((x - y).abs() / scale);
                        }
                    }
                    assert_eq!((a.samples, a.impact_index), (b.samples, b.impact_index));
                    let truth = (f64::from(a.cue_speed) - speed).abs() / speed;
                    max_truth_error = max_truth_error.max(truth);
                    strokes += 1;
                }
                _ => panic!("stroke answers differ: firmware {got:?}, host {want:?}"),
            }
        }
    }
    println!(
        "e2e: {strokes} strokes in {stroke_lines} chunk requests: firmware = host session (max relative error \
         {max_rel:.3e} over collide and stroke numbers); cue speed within {:.2} % of the generating speed; {:.2} s",
        100.0 * max_truth_error,
        t.elapsed().as_secs_f64()
    );

    // 3. Malformed lines, streamed back to back, then one valid request.
    let bad = malformed_lines();
    let sentinel = br#"{"collide":{"speed":2,"cut":30,"spin":[0,40,0],"mu":0.06}}"#;
    let mut stream = Vec::new();
    for b in &bad {
        stream.extend_from_slice(&b.line);
        stream.push(b'\n');
    }
    stream.extend_from_slice(sentinel);
    stream.push(b'\n');
    let bytes = stream.len();
    let mut port = fw.take_serial_in().expect("serial input");
    let writer = std::thread::spawn(move || port.write_all(&stream).map(|()| port));
    let t = Instant::now();
    let mut per_category: BTreeMap<&str, usize> = BTreeMap::new();
    let mut per_kind: BTreeMap<&str, usize> = BTreeMap::new();
    for (n, b) in bad.iter().enumerate() {
        let answer = fw
            .answer(ANSWER_TIMEOUT)
            .unwrap_or_else(|e| panic!("malformed line {n} ({}): {e}", b.category));
        let shown = String::from_utf8_lossy(&b.line[..b.line.len().min(120)]).into_owned();
        let Answer::Error(error) = parse(&answer) else {
            panic!("line {n} ({}) {shown:?} was answered {answer}", b.category)
        };
        assert!(
            b.kinds.contains(&error.kind),
            "line {n} ({}) {shown:?}: {:?} not in {:?}: {}",
            b.category,
            error.kind,
            b.kinds,
            error.message
        );
        *per_category.entry(b.category).or_default() += 1;
        *per_kind.entry(error.kind.name()).or_default() += 1;
    }
    let after = parse(&fw.answer(ANSWER_TIMEOUT).unwrap());
    let Answer::Collide(after) = after else {
        panic!("the request after the malformed lines got {after:?}")
    };
    assert_eq!(after.regime.name(), "sliding");
    let mut port = writer.join().unwrap().expect("the stream was written");
    let malformed_secs = t.elapsed().as_secs_f64();
    println!(
        "e2e: {} malformed lines ({:.0} KiB) -> {} error answers, one each; then a valid request answered; {malformed_secs:.2} s",
        bad.len(),
        bytes as f64 / 1024.0,
        per_kind.values().sum::<usize>(),
    );
    println!("e2e:   by category: {per_category:?}");
    println!("e2e:   by error kind: {per_kind:?}");
    assert!(bad.len() >= 1000);

    // 4. Shutdown: counters, then QEMU exits 0.
    port.write_all(b"{\"shutdown\":{}}\n").unwrap();
    drop(port);
    let Answer::Shutdown(stats) = parse(&fw.answer(ANSWER_TIMEOUT).unwrap()) else {
        panic!("no shutdown answer")
    };
    let total = 1 + requests.len() + stroke_lines + bad.len() + 1 + 1;
    assert_eq!(stats.requests as usize, total);
    assert_eq!(stats.errors as usize, bad.len());
    let ended = fw.wait(Duration::from_secs(30));
    if ended.status.is_none_or(|s| !s.success()) {
        for line in &ended.log {
            eprintln!("firmware log: {line}");
        }
        panic!("QEMU ended with {:?}", ended.status);
    }
    if let Some(last) = ended.log.last() {
        println!("e2e: firmware log ends with: {last}");
    }
    println!(
        "e2e: {} requests in {:.1} s, QEMU exited 0",
        stats.requests,
        started.elapsed().as_secs_f64()
    );
}
