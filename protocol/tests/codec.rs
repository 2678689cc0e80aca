//! Host tests of the codec: round trips through both JSON libraries, one case per error
//! kind, answer sizes, session state, and seeded fuzzing of the whole line path.

use cuesight::{Model, Params};
use cuesight_protocol::{
    decode, json, Answer, AnswerLine, Collide, Control, ErrorKind, Event, Identity, LineReader,
    ModelName, Overrides, Problem, Request, Session, Spin, Stroke, Summary, MAX_ANSWER, MAX_LINE,
    MAX_SAMPLES, STROKE_CAPACITY,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const IDENTITY: Identity = Identity {
    firmware: "test 0.0.0",
    board: "host",
};

/// Serve one line and parse the answer back with serde_json.
fn serve(session: &mut Session, line: &[u8]) -> (Answer, String) {
    let mut out = AnswerLine::new();
    session
        .serve_line(line, &mut out)
        .expect("a non-blank line gets an answer");
    let text = std::str::from_utf8(&out).expect("answers are UTF-8");
    assert!(text.ends_with('\n'), "{text}");
    assert_eq!(text.matches('\n').count(), 1, "one line: {text}");
    let answer: Answer = serde_json::from_str(text.trim_end()).expect("answers parse");
    (answer, text.trim_end().to_owned())
}

fn error_of(line: &str) -> (ErrorKind, Option<String>, String) {
    let mut session = Session::new(IDENTITY);
    match serve(&mut session, line.as_bytes()).0 {
        Answer::Error(e) => (
            e.kind,
            e.field.map(|f| f.as_str().to_owned()),
            e.message.as_str().to_owned(),
        ),
        other => panic!("{line}: expected an error, got {other:?}"),
    }
}

fn random_request(rng: &mut ChaCha8Rng) -> Request {
    let maybe = |rng: &mut ChaCha8Rng, lo: f32, hi: f32| {
        rng.random_bool(0.4).then(|| rng.random_range(lo..=hi))
    };
    let with = |rng: &mut ChaCha8Rng| Overrides {
        mu: maybe(rng, 0.01, 0.1),
        mu_b: maybe(rng, 0.0, 0.1),
        mu_c: maybe(rng, 0.0, 2.0),
        restitution: maybe(rng, 0.9, 1.0),
        mu_s: maybe(rng, 0.0, 0.4),
        radius: maybe(rng, 0.02, 0.04),
        mass: maybe(rng, 0.1, 0.3),
        model: rng
            .random_bool(0.5)
            .then(|| ModelName::from(Model::ALL[rng.random_range(0..Model::ALL.len())])),
    };
    match rng.random_range(0..5) {
        0 | 1 => Request::Collide(Collide {
            speed: rng.random_range(0.1..8.0),
            cut: rng.random_range(-89.0..89.0),
            spin: if rng.random_bool(0.3) {
                Spin::Roll
            } else {
                Spin::Given([0.0; 3].map(|_: f32| rng.random_range(-300.0..300.0)))
            },
            with: with(rng),
        }),
        2 => Request::Params(with(rng)),
        3 => {
            let samples = (0..rng.random_range(0..50)).map(|_| rng.random()).collect();
            if rng.random_bool(0.5) {
                Request::Stroke(Stroke::chunk(samples))
            } else {
                Request::Stroke(Stroke {
                    scale: maybe(rng, 0.001, 0.01),
                    tip_offset: rng
                        .random_bool(0.5)
                        .then(|| [rng.random_range(-0.01..0.01), 0.005]),
                    cue_mass: maybe(rng, 0.4, 0.6),
                    tip_restitution: maybe(rng, 0.7, 0.8),
                    ..Stroke::last(samples, rng.random_range(1000.0..7000.0))
                })
            }
        }
        _ => [Request::Version, Request::Shutdown][rng.random_range(0..2)].clone(),
    }
}

#[test]
fn requests_round_trip_through_both_serializers() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..2000 {
        let request = random_request(&mut rng);
        let host = serde_json::to_string(&request).unwrap();
        assert_eq!(decode(host.as_bytes()), Ok(request.clone()), "{host}");
        let mut buf = [0u8; MAX_LINE];
        let n = serde_json_core::to_slice(&request, &mut buf).unwrap();
        assert_eq!(&buf[..n], host.as_bytes(), "both serializers agree");
    }
}

#[test]
fn wire_forms() {
    assert_eq!(
        serde_json::to_string(&Request::Version).unwrap(),
        r#"{"version":{}}"#
    );
    assert_eq!(
        serde_json::to_string(&Request::Collide(Collide {
            spin: Spin::Roll,
            ..Collide::new(2.0, 30.0)
        }))
        .unwrap(),
        r#"{"collide":{"speed":2.0,"cut":30.0,"roll":true}}"#
    );
    let parsed = decode(br#" { "collide" : { "cut" : -5 , "speed" : 1e0 , "roll" : false } } "#);
    assert_eq!(parsed, Ok(Request::Collide(Collide::new(1.0, -5.0))));
}

#[test]
fn answers_are_the_same_text_from_both_serializers() {
    let mut session = Session::new(IDENTITY);
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let mut seen = 0;
    for _ in 0..500 {
        let request = random_request(&mut rng);
        if request == Request::Shutdown {
            continue;
        }
        let line = serde_json::to_string(&request).unwrap();
        let (answer, text) = serve(&mut session, line.as_bytes());
        assert_eq!(serde_json::to_string(&answer).unwrap(), text);
        if let Answer::Collide(c) = &answer {
            // The answer carries the same numbers as a direct call of the core.
            let Request::Collide(req) = &request else {
                unreachable!()
            };
            let prepared = req.prepare(session.defaults()).unwrap();
            let outcome = cuesight::collide(
                &prepared.params,
                &prepared.impact,
                prepared.model.core().unwrap(),
            )
            .unwrap();
            assert_eq!(
                c.object.v,
                outcome.object_ball.velocity.to_array().map(|x| x + 0.0)
            );
            assert_eq!(c.throw_deg, outcome.throw_angle_deg() + 0.0);
            seen += 1;
        }
    }
    assert!(seen > 100);
}

/// The longest answers fit [`MAX_ANSWER`]: every number of a collide answer at its
/// longest (`-1.2345678e-38`-like), and the longest error message.
#[test]
fn answers_fit_the_buffer() {
    let mut answer: cuesight_protocol::CollideAnswer = {
        let mut session = Session::new(IDENTITY);
        match serve(&mut session, br#"{"collide":{"speed":2,"cut":30}}"#).0 {
            Answer::Collide(c) => c,
            other => panic!("{other:?}"),
        }
    };
    let long = -1.234_567_8e-37_f32;
    let i = &mut answer.input;
    for x in [
        &mut i.speed,
        &mut i.cut_deg,
        &mut i.mu,
        &mut i.mu_b,
        &mut i.mu_c,
        &mut i.restitution,
        &mut i.mu_s,
        &mut i.radius,
        &mut i.mass,
        &mut answer.throw_deg,
        &mut answer.cue_deflection_deg,
        &mut answer.separation_deg,
        &mut answer.impulses.normal,
        &mut answer.impulses.table_friction,
    ] {
        *x = long;
    }
    for v in [
        &mut answer.input.spin,
        &mut answer.cue.v,
        &mut answer.cue.w,
        &mut answer.object.v,
        &mut answer.object.w,
        &mut answer.impulses.friction,
    ] {
        *v = [long; 3];
    }
    let text = serde_json::to_string(&Answer::Collide(answer)).unwrap();
    println!("longest collide answer: {} bytes", text.len());
    assert!(
        text.len() < 1000 && text.len() < MAX_ANSWER - 1,
        "{}",
        text.len()
    );

    // A field name at the longest kept, in the longest message.
    let (_, _, message) = error_of(&format!(r#"{{"collide":{{"{}":1}}}}"#, "x".repeat(100)));
    assert!(message.len() <= cuesight_protocol::MESSAGE_LEN);
}

#[test]
fn every_error_kind_is_named() {
    use ErrorKind::*;
    let long = "x".repeat(MAX_LINE + 1);
    let cases: &[(&str, ErrorKind, Option<&str>, &str)] = &[
        (
            r#"{"collide":{"speed":2,"cut":30}"#,
            MalformedJson,
            None,
            "unexpected end of line",
        ),
        (
            r#"{"collide":{"speed":NaN,"cut":30}}"#,
            MalformedJson,
            None,
            "expected a value",
        ),
        (
            r#"{"collide":{"speed":Infinity,"cut":30}}"#,
            MalformedJson,
            None,
            "at byte 20",
        ),
        (r#"{"collide" {}}"#, MalformedJson, None, "expected ':'"),
        ("\u{1}", MalformedJson, None, "expected a value"),
        ("[1,2]", NotARequest, None, "expected a JSON object"),
        ("{}", NotARequest, None, "empty"),
        (
            r#"{"version":{},"shutdown":{}}"#,
            NotARequest,
            None,
            "several keys",
        ),
        (
            r#"{"explode":{}}"#,
            UnknownRequest,
            Some("explode"),
            "unknown request",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"sped":1}}"#,
            UnknownField,
            Some("sped"),
            "expected speed, cut",
        ),
        (
            r#"{"version":{"verbose":true}}"#,
            UnknownField,
            Some("verbose"),
            "unknown field",
        ),
        (
            r#"{"params":{"mu":0.1,"mu":0.2}}"#,
            DuplicateField,
            Some("mu"),
            "twice",
        ),
        (
            r#"{"collide":{"cut":30}}"#,
            MissingField,
            Some("speed"),
            "missing field",
        ),
        (
            r#"{"stroke":{"rate_hz":3333}}"#,
            MissingField,
            Some("samples"),
            "missing",
        ),
        (
            r#"{"stroke":{"samples":[1,2]}}"#,
            MissingField,
            Some("rate_hz"),
            "missing",
        ),
        (
            r#"{"collide":{"speed":"fast","cut":30}}"#,
            WrongType,
            Some("speed"),
            "expected a number",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"spin":[1,2]}}"#,
            WrongType,
            Some("spin"),
            "three numbers",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"spin":[1,2,3,4]}}"#,
            WrongType,
            Some("spin"),
            "three numbers",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"roll":1}}"#,
            WrongType,
            Some("roll"),
            "true or false",
        ),
        (
            r#"{"collide":[2,30]}"#,
            WrongType,
            Some("collide"),
            "an object",
        ),
        (
            r#"{"version":null}"#,
            WrongType,
            Some("version"),
            "empty object",
        ),
        (
            r#"{"stroke":{"rate_hz":3333,"samples":[1,2,70000]}}"#,
            WrongType,
            Some("samples"),
            "-32768",
        ),
        (
            r#"{"stroke":{"rate_hz":3333,"samples":[[1,2,3]]}}"#,
            WrongType,
            Some("samples"),
            "integers",
        ),
        (
            r#"{"stroke":{"samples":[1],"more":true,"rate_hz":3333}}"#,
            Conflict,
            Some("rate_hz"),
            "rate_hz and more",
        ),
        (
            r#"{"params":{"model":"kimgrip"}}"#,
            InvalidValue,
            Some("model"),
            "expected ideal, kim, kim-grip",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"spin":[0,0,0],"roll":true}}"#,
            Conflict,
            Some("roll"),
            "cannot both",
        ),
        (
            r#"{"collide":{"speed":null,"cut":30}}"#,
            NotFinite,
            Some("speed"),
            "speed must be a finite number",
        ),
        (
            r#"{"collide":{"speed":1e39,"cut":30}}"#,
            NotFinite,
            Some("speed"),
            "finite",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"spin":[0,-1e300,0]}}"#,
            NotFinite,
            Some("spin.y"),
            "finite",
        ),
        (
            r#"{"collide":{"speed":-1,"cut":30}}"#,
            OutOfRange,
            Some("speed"),
            "speed = -1 is outside (0, 100] m/s",
        ),
        (
            r#"{"collide":{"speed":2,"cut":90}}"#,
            OutOfRange,
            Some("cut"),
            "outside (-90, 90)",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"mu":-0.1}}"#,
            OutOfRange,
            Some("mu"),
            "mu = -0.1 is outside [0, 1]",
        ),
        (
            r#"{"params":{"mass":1000}}"#,
            OutOfRange,
            Some("mass"),
            "mass = 1000",
        ),
        (
            r#"{"params":{"mu":0.5,"mu_b":0.6}}"#,
            OutOfRange,
            Some("mu_b"),
            "a + b <= 1",
        ),
        (
            r#"{"collide":{"speed":2,"cut":30,"model":"reference"}}"#,
            Unsupported,
            Some("model"),
            "host only",
        ),
        (
            r#"{"stroke":{"rate_hz":3333,"samples":[]}}"#,
            StrokeRejected,
            Some("samples"),
            "at least",
        ),
        (
            r#"{"stroke":{"rate_hz":50,"samples":[1]}}"#,
            OutOfRange,
            Some("rate_hz"),
            "[500, 100000]",
        ),
        (
            r#"{"stroke":{"rate_hz":1000,"scale":0.0001,"samples":[1]}}"#,
            OutOfRange,
            Some("scale"),
            "full scale",
        ),
        (
            r#"{"stroke":{"rate_hz":1000,"scale":0,"samples":[1]}}"#,
            OutOfRange,
            Some("scale"),
            "non-zero",
        ),
        (
            r#"{"stroke":{"rate_hz":1000,"cue_mass":5,"samples":[1]}}"#,
            OutOfRange,
            Some("cue_mass"),
            "cue_mass = 5",
        ),
        (&long, LineTooLong, None, "the limit is 3072"),
    ];
    for (line, kind, field, needle) in cases {
        let (k, f, message) = error_of(line);
        let shown = &line[..line.len().min(80)];
        assert_eq!(k, *kind, "{shown}: {message}");
        assert_eq!(f.as_deref(), *field, "{shown}: {message}");
        assert!(
            message.contains(needle),
            "{shown}: {message:?} lacks {needle:?}"
        );
    }
    // Too many samples.
    let samples = vec!["-32768"; MAX_SAMPLES + 1].join(",");
    let line = format!(r#"{{"stroke":{{"rate_hz":3333,"samples":[{samples}]}}}}"#);
    assert!(line.len() <= MAX_LINE);
    let (k, f, message) = error_of(&line);
    assert_eq!(
        (k, f.as_deref()),
        (OutOfRange, Some("samples")),
        "{message}"
    );
}

#[test]
fn params_persist_and_collide_overrides_do_not() {
    let mut session = Session::new(IDENTITY);
    let (answer, _) = serve(&mut session, br#"{"params":{"mu":0.07,"model":"kim"}}"#);
    let Answer::Params(p) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!((p.mu, p.model), (0.07, ModelName::from(Model::Kim)));
    let (answer, _) = serve(
        &mut session,
        br#"{"collide":{"speed":2,"cut":30,"mu":0.02}}"#,
    );
    let Answer::Collide(c) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!((c.input.mu, c.model.name()), (0.02, "kim"));
    let (answer, _) = serve(&mut session, br#"{"collide":{"speed":2,"cut":30}}"#);
    let Answer::Collide(c) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!(c.input.mu, 0.07);
    // A refused params request changes nothing.
    let (answer, _) = serve(&mut session, br#"{"params":{"restitution":0.5,"mass":-1}}"#);
    assert!(matches!(answer, Answer::Error(_)));
    assert_eq!(
        session.defaults().params.restitution(),
        Params::POOL.restitution()
    );
    // Speed-dependent friction, echoed component by component.
    let (answer, _) = serve(
        &mut session,
        br#"{"params":{"mu":0.00995,"mu_b":0.108,"mu_c":1.088}}"#,
    );
    let Answer::Params(p) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!((p.mu, p.mu_b, p.mu_c), (0.00995, 0.108, 1.088));
    assert!(Summary(&Answer::Params(p))
        .to_string()
        .contains("exp(-1.088 v)"));
}

#[test]
fn shutdown_reports_the_session() {
    let mut session = Session::new(IDENTITY);
    let mut out = AnswerLine::new();
    assert_eq!(session.serve_line(b"", &mut out), None);
    assert_eq!(session.serve_line(b" \t", &mut out), None);
    assert!(out.is_empty());
    serve(&mut session, br#"{"version":{}}"#);
    serve(&mut session, b"oops");
    let served = session.serve_line(br#"{"shutdown":{}}"#, &mut out).unwrap();
    assert_eq!(served.control, Control::Shutdown);
    assert_eq!(served.request, Some("shutdown"));
    assert_eq!(
        std::str::from_utf8(&out).unwrap(),
        "{\"shutdown\":{\"requests\":3,\"errors\":1}}\n"
    );
}

#[test]
fn version_names_the_limits() {
    let mut session = Session::new(IDENTITY);
    let (answer, text) = serve(&mut session, br#"{"version":{}}"#);
    assert_eq!(
        text,
        format!(
            r#"{{"version":{{"protocol":1,"firmware":"test 0.0.0","board":"host","max_line":{MAX_LINE},"max_samples":{MAX_SAMPLES},"stroke_capacity":{STROKE_CAPACITY}}}}}"#
        )
    );
    assert!(Summary(&answer)
        .to_string()
        .starts_with("protocol 1, test 0.0.0 on host"));
}

/// Lines through a [`LineReader`]: an overlong line is one error and the next line is
/// served normally.
#[test]
fn reader_and_session_resync_after_an_overlong_line() {
    let mut reader = LineReader::<MAX_LINE>::new();
    let mut session = Session::new(IDENTITY);
    let mut out = AnswerLine::new();
    let mut stream = vec![b'{'; MAX_LINE + 100];
    stream.extend_from_slice(b"\n{\"version\":{}}\r\n");
    let mut answers = Vec::new();
    for b in stream {
        if let Some(event) = reader.push(b) {
            if session.serve(event, &mut out).is_some() {
                answers.push(String::from_utf8(out.to_vec()).unwrap());
            }
        }
    }
    assert_eq!(answers.len(), 2);
    assert!(
        answers[0].starts_with(r#"{"error":{"kind":"line_too_long""#),
        "{}",
        answers[0]
    );
    assert!(answers[1].starts_with(r#"{"version":"#), "{}", answers[1]);
    assert_eq!(reader.push(b'\n'), Some(Event::Line(b"")));
}

/// The strict checker agrees with serde_json on what is JSON, over seeded mutations of
/// valid requests (truncations, byte flips, insertions) and random bytes.
#[test]
fn syntax_check_agrees_with_serde_json() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let alphabet = b"{}[]\":,.-+0123456789eEtrufalsn \\u/x\t";
    let (mut valid, mut invalid) = (0, 0);
    for _ in 0..20_000 {
        let mut line = serde_json::to_vec(&random_request(&mut rng)).unwrap();
        match rng.random_range(0..4) {
            0 => line.truncate(rng.random_range(0..=line.len())),
            1 => {
                let i = rng.random_range(0..line.len());
                line[i] = alphabet[rng.random_range(0..alphabet.len())];
            }
            2 => {
                let i = rng.random_range(0..=line.len());
                line.insert(i, alphabet[rng.random_range(0..alphabet.len())]);
            }
            _ => line = (0..rng.random_range(0..20)).map(|_| rng.random()).collect(),
        }
        let ours = json::check(&line).is_ok();
        let theirs = serde_json::from_slice::<serde::de::IgnoredAny>(&line).is_ok();
        assert_eq!(ours, theirs, "{:?}", String::from_utf8_lossy(&line));
        if ours {
            valid += 1;
        } else {
            invalid += 1;
        }
    }
    assert!(
        valid > 1000 && invalid > 1000,
        "{valid} valid, {invalid} invalid"
    );
}

/// Whatever the bytes, one line gets exactly one answer that parses, and the session
/// keeps serving.
#[test]
fn fuzzed_lines_always_get_one_parseable_answer() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let mut session = Session::new(IDENTITY);
    let mut errors = 0;
    for i in 0..20_000 {
        let mut line = serde_json::to_vec(&random_request(&mut rng)).unwrap();
        for _ in 0..rng.random_range(0..4) {
            if line.is_empty() {
                break;
            }
            let j = rng.random_range(0..line.len());
            match rng.random_range(0..3) {
                0 => line[j] = rng.random(),
                1 => {
                    line.remove(j);
                }
                _ => line.truncate(j),
            }
        }
        if line.contains(&b'\n') || line.iter().all(|b| matches!(b, b' ' | b'\t')) {
            continue;
        }
        if line == br#"{"shutdown":{}}"# {
            continue;
        }
        let (answer, _) = serve(&mut session, &line);
        if matches!(answer, Answer::Error(_)) {
            errors += 1;
        }
        if i % 1000 == 0 {
            let (answer, _) = serve(&mut session, br#"{"version":{}}"#);
            assert!(matches!(answer, Answer::Version(_)));
        }
    }
    assert!(errors > 5000, "{errors}");
    let _ = Problem::MissingField("x"); // the type is public for hosts that match on it
}

/// A clean synthetic stroke in raw words (LSM6DSOX ±16 g scale): 0.25 s at rest, a
/// half-sine acceleration to `speed` over 0.3 s, a 20 g impact (clipped at full scale),
/// 20 ms after it.
fn clean_stroke(rate_hz: f32, speed: f32) -> Vec<i16> {
    let scale = cuesight_sensors::ACCEL_MPS2_PER_LSB;
    let n = |seconds: f32| (seconds * rate_hz) as usize;
    let bias = 100i16; // offset plus gravity along a slightly raised cue
    let (duration, steps) = (0.3, n(0.3));
    // a = A sin(π t / T) reaches v = 2 A T / π at t = T.
    let peak = std::f32::consts::PI * speed / (2.0 * duration);
    let mut samples = vec![bias; n(0.25)];
    samples.extend((0..steps).map(|i| {
        let t = (i as f32 + 0.5) / rate_hz;
        let a = peak * (std::f32::consts::PI * t / duration).sin();
        bias + (a / scale).round() as i16
    }));
    samples.extend(std::iter::repeat_n(i16::MIN, 3));
    samples.extend(std::iter::repeat_n(bias, n(0.02)));
    samples
}

fn stroke_chunks(samples: &[i16], rate_hz: f32) -> Vec<Request> {
    let chunks: Vec<_> = samples.chunks(MAX_SAMPLES).collect();
    chunks
        .iter()
        .enumerate()
        .map(|(i, chunk)| {
            let chunk = chunk.iter().copied().collect();
            if i + 1 < chunks.len() {
                Request::Stroke(Stroke::chunk(chunk))
            } else {
                Request::Stroke(Stroke::last(chunk, rate_hz))
            }
        })
        .collect()
}

#[test]
fn a_stroke_in_chunks_gets_the_estimators_answer() {
    let mut session = Session::new(IDENTITY);
    for (rate, speed) in [(1000.0f32, 2.0f32), (6667.0, 3.5)] {
        let samples = clean_stroke(rate, speed);
        let requests = stroke_chunks(&samples, rate);
        let mut last = None;
        for (i, request) in requests.iter().enumerate() {
            let line = serde_json::to_string(request).unwrap();
            assert!(line.len() <= MAX_LINE);
            let (answer, _) = serve(&mut session, line.as_bytes());
            if i + 1 < requests.len() {
                let Answer::StrokeChunk(c) = answer else {
                    panic!("{answer:?}")
                };
                assert_eq!(c.samples as usize, (i + 1) * MAX_SAMPLES);
            } else {
                last = Some(answer);
            }
        }
        let Some(Answer::Stroke(s)) = last else {
            panic!("{last:?}")
        };
        // The same numbers as the estimator and the strike model called directly.
        let scale = cuesight_sensors::ACCEL_MPS2_PER_LSB;
        let mut config = cuesight_sensors::StrokeConfig::new(rate);
        config.full_scale = 32768.0 * scale;
        let direct = cuesight_sensors::estimate_raw(&samples, scale, &config).unwrap();
        assert_eq!(s.cue_speed, direct.cue_speed);
        assert_eq!(s.samples as usize, samples.len());
        assert!((s.cue_speed - speed).abs() < 0.01 * speed, "{s:?}");
        let hit = direct
            .strike(
                &Params::POOL,
                &cuesight::strike::Cue::TYPICAL,
                cuesight::strike::TipOffset::CENTRE,
            )
            .unwrap();
        assert_eq!(s.ball_speed, hit.speed);
        assert_eq!(s.ball_spin, [0.0; 3]);
        assert!(Summary(&Answer::Stroke(s)).to_string().starts_with("cue "));
    }
}

#[test]
fn stroke_errors_name_the_problem_and_drop_the_capture() {
    let mut session = Session::new(IDENTITY);
    let samples = clean_stroke(6667.0, 2.0);
    let line_of = |request: &Request| serde_json::to_string(request).unwrap();
    // No rest: the window starts in the middle of the stroke.
    let tail = &samples[samples.len() - 1000..];
    let mut answer = None;
    for middle in stroke_chunks(tail, 6667.0) {
        answer = Some(serve(&mut session, line_of(&middle).as_bytes()).0);
    }
    let answer = answer.unwrap();
    let Answer::Error(e) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!(e.kind, ErrorKind::StrokeRejected, "{}", e.message);
    // A bad line between chunks abandons the stroke: the last chunk alone is too short.
    let requests = stroke_chunks(&samples, 6667.0);
    assert!(requests.len() > 1);
    serve(&mut session, line_of(&requests[0]).as_bytes());
    serve(&mut session, b"{oops");
    let (answer, _) = serve(&mut session, line_of(requests.last().unwrap()).as_bytes());
    assert!(
        matches!(answer, Answer::Error(ref e) if e.kind == ErrorKind::StrokeRejected),
        "{answer:?}"
    );
    // Over capacity.
    let chunk = Request::Stroke(Stroke::chunk([0i16; MAX_SAMPLES].into_iter().collect()));
    let mut answer = None;
    for _ in 0..=STROKE_CAPACITY / MAX_SAMPLES {
        answer = Some(serve(&mut session, line_of(&chunk).as_bytes()).0);
    }
    let Some(Answer::Error(e)) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!(
        (e.kind, e.field.unwrap().as_str()),
        (ErrorKind::OutOfRange, "samples")
    );
    // A hit 2R/5 above centre rolls the ball; a tip beyond half a radius is refused.
    let short = clean_stroke(1000.0, 2.0);
    let mut chunks = stroke_chunks(&short, 1000.0);
    let Some(Request::Stroke(mut last)) = chunks.pop() else {
        unreachable!()
    };
    let send_all_but_last = |session: &mut Session| {
        for chunk in &chunks {
            serve(session, line_of(chunk).as_bytes());
        }
    };
    send_all_but_last(&mut session);
    last.tip_offset = Some([0.0, 0.4 * 0.028575]);
    let (answer, _) = serve(
        &mut session,
        line_of(&Request::Stroke(last.clone())).as_bytes(),
    );
    let Answer::Stroke(s) = answer else {
        panic!("{answer:?}")
    };
    let roll = s.ball_speed / 0.028575;
    assert!((s.ball_spin[1] - roll).abs() < 1e-3 * roll, "{s:?}");
    last.tip_offset = Some([0.02, 0.0]);
    send_all_but_last(&mut session);
    let (answer, _) = serve(&mut session, line_of(&Request::Stroke(last)).as_bytes());
    let Answer::Error(e) = answer else {
        panic!("{answer:?}")
    };
    assert_eq!(e.field.unwrap().as_str(), "tip_offset", "{}", e.message);
}
