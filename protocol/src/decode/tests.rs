//! The hand-written decoder against the serde-json-core decoder it replaced
//! ([`decode_with_serde`], the oracle): the same request or the same problem for every
//! line, over seeded valid and mutated requests of every kind; and named cases for every
//! `shot` field, every error and the extremes of number parsing.

extern crate std;

use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::decode;
use super::oracle::decode_with_serde;
use crate::problem::{ErrorKind, Problem};
use crate::request::Request;

/// Both decoders' results, compared through `Debug` (NaN fields compare equal there).
fn agree(line: &str) -> String {
    let ours = format!("{:?}", decode(line.as_bytes()));
    let theirs = format!("{:?}", decode_with_serde(line.as_bytes()));
    assert_eq!(ours, theirs, "{line}");
    ours
}

/// Values of every JSON kind, numbers at the edges of `f32` and `u32` parsing, integers
/// written as floats, escapes, nesting.
const VALUES: &[&str] = &[
    "null",
    "true",
    "false",
    "\"x\"",
    "\"pool\"",
    "\"snooker\"",
    "\"carom\"",
    "\"po\\u006fl\"",
    "\"kim\"",
    "\"auto\"",
    "\"reference\"",
    "\"a\\\"b\"",
    "[]",
    "{}",
    "{\"a\":1}",
    "[1]",
    "[1,2]",
    "[ 1 , 2 ]",
    "[1,2,3]",
    "[null,1]",
    "[true,1]",
    "[\"1\",1]",
    "[[1,2]]",
    "[[1,2],[3,4]]",
    "[[1,2],[3]]",
    "[[1,2],null]",
    "[[1,2],[3,4,5]]",
    "[[1,2],[3,\"4\"]]",
    "0",
    "-0",
    "0.0",
    "-0.0",
    "1",
    "-1",
    "0.5",
    "1.5",
    "1e2",
    "1E+2",
    "1e0",
    "2.0e1",
    "-1e-3",
    "3",
    "15",
    "16",
    "4294967295",
    "4294967296",
    "42949672950",
    "99999999999999999999",
    "1e39",
    "-1e39",
    "1e400",
    "2.5e-400",
    "3.4028235e38",
    "3.4028236e38",
    "3.40282357e38",
    "1e-46",
    "1.4e-45",
    "7.006492e-46",
    "1.17549435e-38",
    "1.1754942e-38",
    "0.000000000000000000000000000000000000000000001",
    "123456789012345678901234567890",
    "1.00000005960464477539062500000000000000001",
    "16777217",
];

/// The fields of a `shot`, and keys that are not.
const KEYS: &[&str] = &[
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
    "mu",
    "mu_b",
    "mu_c",
    "restitution",
    "mu_s",
    "mass",
    "model",
    "radius",
    "sped",
    "Speed",
    "sp\\u0065ed",
    "",
    "xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx",
    "a\\\"b",
    "\u{e9}",
];

fn pick<'a>(rng: &mut ChaCha8Rng, from: &[&'a str]) -> &'a str {
    from[rng.random_range(0..from.len())]
}

fn number(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> String {
    let x: f32 = rng.random_range(lo..hi);
    if rng.random_bool(0.5) {
        format!("{:.4}", x)
    } else {
        x.to_string()
    }
}

fn whitespace(rng: &mut ChaCha8Rng) -> &'static str {
    ["", "", "", " ", "\t", " \r ", "\n"][rng.random_range(0..7)]
}

/// A valid-looking `shot` body as `(key, value)` pairs.
fn shot_fields(rng: &mut ChaCha8Rng) -> Vec<(String, String)> {
    let table = ["pool", "snooker", "carom"][rng.random_range(0..3)];
    let point =
        |rng: &mut ChaCha8Rng| format!("[{},{}]", number(rng, 0.05, 2.5), number(rng, 0.05, 1.2));
    let mut fields = Vec::new();
    if rng.random_bool(0.9) {
        fields.push(("table".to_string(), format!("\"{table}\"")));
    }
    fields.push(("cue".to_string(), point(rng)));
    if rng.random_bool(0.9) {
        let balls: Vec<String> = (0..rng.random_range(0..17)).map(|_| point(rng)).collect();
        fields.push(("balls".to_string(), format!("[{}]", balls.join(","))));
    }
    fields.push(("speed".to_string(), number(rng, 0.1, 8.0)));
    for (key, lo, hi) in [
        ("mu", 0.0, 0.2),
        ("mu_b", 0.0, 0.1),
        ("mu_c", 0.0, 2.0),
        ("restitution", 0.8, 1.0),
        ("mu_s", 0.0, 0.5),
        ("mass", 0.1, 0.3),
        ("mu_cloth", 0.1, 0.3),
        ("mu_roll", 0.001, 0.03),
        ("cue_mass", 0.3, 0.8),
        ("tip_restitution", 0.5, 0.9),
        ("aim", -180.0, 180.0),
    ] {
        if rng.random_bool(0.3) {
            fields.push((key.to_string(), number(rng, lo, hi)));
        }
    }
    if rng.random_bool(0.6) {
        fields.push((
            "tip".to_string(),
            format!("[{},{}]", number(rng, -0.3, 0.3), number(rng, -0.3, 0.3)),
        ));
    }
    for key in ["object", "pocket"] {
        if rng.random_bool(0.4) {
            fields.push((key.to_string(), rng.random_range(0..8u32).to_string()));
        }
    }
    if rng.random_bool(0.5) {
        let model = [
            "ideal",
            "kim",
            "kim-grip",
            "seed-exact",
            "exact",
            "auto",
            "reference",
        ][rng.random_range(0..7)];
        fields.push(("model".to_string(), format!("\"{model}\"")));
    }
    // Field order is free.
    for i in (1..fields.len()).rev() {
        if rng.random_bool(0.5) {
            fields.swap(i, rng.random_range(0..=i));
        }
    }
    fields
}

/// A `shot` line, possibly with schema mutations and odd spacing.
fn shot_line(rng: &mut ChaCha8Rng) -> String {
    let mut fields = shot_fields(rng);
    for _ in 0..rng.random_range(0..3) {
        let at = rng.random_range(0..=fields.len());
        match rng.random_range(0..5) {
            0 | 1 if !fields.is_empty() => {
                let i = rng.random_range(0..fields.len());
                fields[i].1 = pick(rng, VALUES).to_string();
            }
            2 if !fields.is_empty() => {
                let i = rng.random_range(0..fields.len());
                let copy = (fields[i].0.clone(), pick(rng, VALUES).to_string());
                fields.insert(at, copy);
            }
            3 => fields.insert(
                at,
                (pick(rng, KEYS).to_string(), pick(rng, VALUES).to_string()),
            ),
            _ if !fields.is_empty() => {
                fields.remove(rng.random_range(0..fields.len()));
            }
            _ => {}
        }
    }
    let mut body = String::from("{");
    body.push_str(whitespace(rng));
    for (i, (key, value)) in fields.iter().enumerate() {
        if i > 0 {
            body.push(',');
            body.push_str(whitespace(rng));
        }
        body.push_str(&format!(
            "\"{key}\"{}:{}{value}{}",
            whitespace(rng),
            whitespace(rng),
            whitespace(rng)
        ));
    }
    body.push('}');
    match rng.random_range(0..20) {
        0 => format!("{{\"shot\":{}}}", pick(rng, VALUES)),
        1 => format!("{{\"shot\":{body},\"version\":{{}}}}"),
        2 => format!("{{\"version\":{{}},\"shot\":{body}}}"),
        3 => format!("{{\"sh\\u006ft\":{body}}}"),
        _ => format!(
            "{}{{{}\"shot\"{}:{}{body}{}}}{}",
            whitespace(rng),
            whitespace(rng),
            whitespace(rng),
            whitespace(rng),
            whitespace(rng),
            whitespace(rng)
        ),
    }
}

/// Every `shot` line gets the same request, or the same problem, from both decoders.
#[test]
fn shot_decoder_agrees_with_the_serde_decoder() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let (mut decoded, mut refused) = (0, 0);
    let mut kinds = std::collections::BTreeSet::new();
    for _ in 0..40_000 {
        let line = shot_line(&mut rng);
        let mut line = line.into_bytes();
        // Some byte-level damage too (mostly refused by the syntax check first).
        if rng.random_bool(0.05) {
            let alphabet = b"{}[]\":,.-+0123456789eEtrufalsn \\u/x";
            let at = rng.random_range(0..line.len());
            line[at] = alphabet[rng.random_range(0..alphabet.len())];
        }
        let line = String::from_utf8_lossy(&line).into_owned();
        agree(&line);
        match decode(line.as_bytes()) {
            Ok(_) => decoded += 1,
            Err(problem) => {
                refused += 1;
                kinds.insert(format!("{:?}", problem.kind()));
            }
        }
    }
    std::println!("{decoded} decoded, {refused} refused; kinds {kinds:?}");
    assert!(decoded > 5_000 && refused > 10_000, "{decoded} {refused}");
    assert!(kinds.len() >= 9, "{kinds:?}");
}

/// The other requests go through the same top level (the dispatch is hand-written).
#[test]
fn request_dispatch_agrees_with_the_serde_decoder() {
    for line in [
        "[1,2]",
        "1",
        "\"shot\"",
        "null",
        "{}",
        " { } ",
        "{\"version\":{}}",
        "{\"version\":{} }",
        "{\"version\":null}",
        "{\"version\":{\"x\":1}}",
        "{\"shutdown\":{}}",
        "{\"jump\":{}}",
        "{\"collide\":{\"speed\":2,\"cut\":30},\"params\":{}}",
        "{\"collide\":[2,30]}",
        "{\"collide\":{\"speed\":2,\"cut\":30,\"spin\":[1,2]}}",
        "{\"params\":{\"mu\":0.1,\"mu\":0.2}}",
        "{\"params\":{\"model\":\"kimgrip\"}}",
        "{\"stroke\":{\"samples\":[1,2.5],\"rate_hz\":1000}}",
        "{\"stroke\":{\"samples\":[1],\"more\":true}}",
        "{\"stroke\":{\"samples\":[1],\"more\":true},\"shot\":{}}",
        "{\"shot\":{},\"stroke\":{\"samples\":[1],\"more\":true}}",
    ] {
        agree(line);
    }
}

/// A `collide`, `params`, `stroke`, `version` or `shutdown` line, possibly mutated.
fn other_line(rng: &mut ChaCha8Rng) -> String {
    let mut fields: Vec<(String, String)> = Vec::new();
    let numbers = |rng: &mut ChaCha8Rng, fields: &mut Vec<(String, String)>, keys: &[&str]| {
        for key in keys {
            if rng.random_bool(0.25) {
                fields.push((key.to_string(), number(rng, -0.1, 2.0)));
            }
        }
    };
    let overrides = [
        "mu",
        "mu_b",
        "mu_c",
        "restitution",
        "mu_s",
        "radius",
        "mass",
    ];
    let name = match rng.random_range(0..6) {
        0 | 1 => {
            fields.push(("speed".to_string(), number(rng, 0.1, 8.0)));
            fields.push(("cut".to_string(), number(rng, -89.0, 89.0)));
            if rng.random_bool(0.4) {
                let spin: Vec<String> = (0..3).map(|_| number(rng, -50.0, 50.0)).collect();
                fields.push(("spin".to_string(), format!("[{}]", spin.join(","))));
            }
            if rng.random_bool(0.3) {
                let roll = ["true", "false"][rng.random_range(0..2)];
                fields.push(("roll".to_string(), roll.to_string()));
            }
            numbers(rng, &mut fields, &overrides);
            "collide"
        }
        2 => {
            numbers(rng, &mut fields, &overrides);
            "params"
        }
        3 | 4 => {
            let samples: Vec<String> = (0..rng.random_range(0..30))
                .map(|_| rng.random::<i16>().to_string())
                .collect();
            fields.push(("samples".to_string(), format!("[{}]", samples.join(","))));
            if rng.random_bool(0.5) {
                let more = ["true", "false"][rng.random_range(0..2)];
                fields.push(("more".to_string(), more.to_string()));
            }
            if rng.random_bool(0.7) {
                fields.push(("rate_hz".to_string(), number(rng, 100.0, 8000.0)));
            }
            numbers(rng, &mut fields, &["scale", "cue_mass", "tip_restitution"]);
            if rng.random_bool(0.2) {
                fields.push(("tip_offset".to_string(), "[0.0,0.01]".to_string()));
            }
            "stroke"
        }
        _ => ["version", "shutdown"][rng.random_range(0..2)],
    };
    if rng.random_bool(0.3) {
        let model = [
            "ideal",
            "kim",
            "kim-grip",
            "exact",
            "auto",
            "reference",
            "fast",
        ][rng.random_range(0..7)];
        fields.push(("model".to_string(), format!("\"{model}\"")));
    }
    let extra = [
        "[1,2.5]",
        "[70000]",
        "[-32769]",
        "[-32768,32767]",
        "[-0]",
        "[1e2]",
        "[0.0]",
        "[null]",
        "[[1]]",
        "[1,]",
    ];
    for _ in 0..rng.random_range(0..3) {
        let at = rng.random_range(0..=fields.len());
        match rng.random_range(0..4) {
            0 if !fields.is_empty() => {
                let i = rng.random_range(0..fields.len());
                fields[i].1 = if rng.random_bool(0.7) {
                    pick(rng, VALUES)
                } else {
                    pick(rng, &extra)
                }
                .to_string();
            }
            1 if !fields.is_empty() => {
                let i = rng.random_range(0..fields.len());
                let copy = (fields[i].0.clone(), pick(rng, VALUES).to_string());
                fields.insert(at, copy);
            }
            2 => fields.insert(
                at,
                (pick(rng, KEYS).to_string(), pick(rng, VALUES).to_string()),
            ),
            _ if !fields.is_empty() => {
                fields.remove(rng.random_range(0..fields.len()));
            }
            _ => {}
        }
    }
    let body: Vec<String> = fields
        .iter()
        .map(|(key, value)| format!("\"{key}\"{}:{}{value}", whitespace(rng), whitespace(rng)))
        .collect();
    let body = format!("{{{}}}", body.join(","));
    match rng.random_range(0..20) {
        0 => format!("{{\"{name}\":{}}}", pick(rng, VALUES)),
        1 => format!("{{\"{name}\":{body},\"{name}\":{body}}}"),
        _ => format!(
            "{}{{\"{name}\":{body}}}{}",
            whitespace(rng),
            whitespace(rng)
        ),
    }
}

/// Every other request line too.
#[test]
fn other_requests_agree_with_the_serde_decoder() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (mut decoded, mut refused) = (0, 0);
    let mut kinds = std::collections::BTreeSet::new();
    for _ in 0..40_000 {
        let line = other_line(&mut rng);
        agree(&line);
        match decode(line.as_bytes()) {
            Ok(_) => decoded += 1,
            Err(problem) => {
                refused += 1;
                kinds.insert(format!("{:?}", problem.kind()));
            }
        }
    }
    std::println!("{decoded} decoded, {refused} refused; kinds {kinds:?}");
    assert!(decoded > 10_000 && refused > 10_000, "{decoded} {refused}");
    assert!(kinds.len() >= 8, "{kinds:?}");
    // Samples at the edges of i16, and integers written otherwise.
    for samples in [
        "[-32768,32767,0,-0,1,-1]",
        "[32768]",
        "[-32769]",
        "[1.0]",
        "[1e0]",
        "[-1.5]",
        "[0.5]",
        "[00]",
        "[null]",
        "[\"1\"]",
        "[true]",
        "[[1]]",
        "[ 1 , 2 ]",
        "[]",
        "{}",
        "1",
    ] {
        agree(&format!(
            r#"{{"stroke":{{"samples":{samples},"rate_hz":1000}}}}"#
        ));
    }
    let full = std::vec!["7"; crate::MAX_SAMPLES + 1].join(",");
    agree(&format!(
        r#"{{"stroke":{{"samples":[{full}],"more":true}}}}"#
    ));
    let full = std::vec!["7"; crate::MAX_SAMPLES].join(",");
    agree(&format!(
        r#"{{"stroke":{{"samples":[{full}],"more":true}}}}"#
    ));
    agree(&format!(
        r#"{{"stroke":{{"samples":[{full},1.5],"more":true}}}}"#
    ));
}

fn problem(line: &str) -> Problem {
    let got = agree(line);
    decode(line.as_bytes()).expect_err(&got)
}

fn shot(line: &str) -> crate::shot::Shot {
    agree(line);
    match decode(line.as_bytes()) {
        Ok(Request::Shot(shot)) => shot,
        other => panic!("{line}: {other:?}"),
    }
}

#[test]
fn every_shot_field_is_read() {
    use crate::names::ModelName;
    use crate::shot::TableName;
    let s = shot(
        r#"{"shot":{"table":"snooker","cue":[0.5,0.25],"balls":[[1,0.5],[2,1]],"speed":3,"tip":[0.1,-0.2],"aim":-45.5,"object":2,"pocket":4,"mu_cloth":0.21,"mu_roll":0.011,"cue_mass":0.6,"tip_restitution":0.7,"mu":0.06,"mu_b":0.01,"mu_c":1.5,"restitution":0.93,"mu_s":0.25,"mass":0.15,"model":"exact"}}"#,
    );
    assert_eq!(s.table, TableName::Snooker);
    assert_eq!(s.cue, [0.5, 0.25]);
    assert_eq!(s.balls.as_slice(), &[[1.0, 0.5], [2.0, 1.0]]);
    assert_eq!((s.speed, s.tip, s.aim), (3.0, [0.1, -0.2], Some(-45.5)));
    assert_eq!((s.object, s.pocket), (Some(2), Some(4)));
    assert_eq!(
        (s.mu_cloth, s.mu_roll, s.cue_mass, s.tip_restitution),
        (Some(0.21), Some(0.011), Some(0.6), Some(0.7))
    );
    let w = s.with;
    assert_eq!(
        (
            w.mu,
            w.mu_b,
            w.mu_c,
            w.restitution,
            w.mu_s,
            w.radius,
            w.mass
        ),
        (
            Some(0.06),
            Some(0.01),
            Some(1.5),
            Some(0.93),
            Some(0.25),
            None,
            Some(0.15)
        )
    );
    assert_eq!(w.model, ModelName::from_name("exact"));
    // The defaults: pool, no balls, centre tip, nothing else given.
    let s = shot(r#"{"shot":{"cue":[1,0.5],"speed":2}}"#);
    assert_eq!(
        (s.table, s.balls.len(), s.tip),
        (TableName::Pool, 0, [0.0; 2])
    );
    assert_eq!(
        (s.aim, s.object, s.pocket, s.with.model),
        (None, None, None, None)
    );
    // Whitespace anywhere, `null` as NaN, a zero index.
    let s = shot("\t{ \"shot\" :\r{ \"cue\" : [ 1 , null ] ,\n\"speed\":null, \"object\" : 0 } } ");
    assert!(s.cue[1].is_nan() && s.speed.is_nan());
    assert_eq!(s.object, Some(0));
}

/// Numbers are parsed exactly as serde-json-core parsed them: correctly rounded, ±inf
/// beyond the f32 range, ±0 below it, subnormals kept.
#[test]
fn numbers_at_the_extremes_of_f32() {
    let speed = |text: &str| shot(&format!(r#"{{"shot":{{"cue":[1,0.5],"speed":{text}}}}}"#)).speed;
    for (text, bits) in [
        ("3.4028235e38", f32::MAX.to_bits()),
        ("-3.4028235e38", f32::MIN.to_bits()),
        ("3.40282357e38", f32::INFINITY.to_bits()), // past the halfway point to 2^128
        ("3.40282356e38", f32::MAX.to_bits()),
        ("3.4028236e38", f32::INFINITY.to_bits()),
        ("1e39", f32::INFINITY.to_bits()),
        ("-1e39", f32::NEG_INFINITY.to_bits()),
        ("1e400", f32::INFINITY.to_bits()),
        ("1.17549435e-38", f32::MIN_POSITIVE.to_bits()),
        ("1.1754942e-38", 0x007f_ffff),
        ("1.4e-45", 1),
        ("7.0064924e-46", 1), // just above half the smallest subnormal
        ("7.006492e-46", 0),
        ("7.006492321624085e-46", 0),
        ("1e-46", 0),
        ("-1e-46", (-0.0f32).to_bits()),
        ("2.5e-400", 0),
        ("-0", (-0.0f32).to_bits()),
        ("16777217", 16_777_216.0f32.to_bits()),
        ("16777219", 16_777_220.0f32.to_bits()),
        ("0.1", 0.1f32.to_bits()),
        (
            "123456789012345678901234567890",
            1.234_567_9e29f32.to_bits(),
        ),
    ] {
        assert_eq!(speed(text).to_bits(), bits, "{text}");
        // And as the standard library reads it, but for `1e400`/`2.5e-400`-style
        // inputs it reads too (it saturates the same way).
        let std_bits = text.parse::<f32>().map(f32::to_bits);
        assert_eq!(std_bits, Ok(bits), "{text}");
    }
}

#[test]
fn malformed_shots_get_the_same_typed_errors() {
    use ErrorKind::*;
    let cases: &[(&str, ErrorKind, Option<&str>)] = &[
        (r#"{"shot":[1]}"#, WrongType, Some("shot")),
        (r#"{"shot":null}"#, WrongType, Some("shot")),
        (r#"{"shot":{"speed":2}}"#, MissingField, Some("cue")),
        (r#"{"shot":{"cue":[1,1]}}"#, MissingField, Some("speed")),
        (
            r#"{"shot":{"cue":[1,1],"speed":"2"}}"#,
            WrongType,
            Some("speed"),
        ),
        (r#"{"shot":{"cue":[1],"speed":2}}"#, WrongType, Some("cue")),
        (
            r#"{"shot":{"cue":[1,2,3],"speed":2}}"#,
            WrongType,
            Some("cue"),
        ),
        (
            r#"{"shot":{"cue":[1,"2"],"speed":2}}"#,
            WrongType,
            Some("cue"),
        ),
        (r#"{"shot":{"cue":{},"speed":2}}"#, WrongType, Some("cue")),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"tip":[0]}}"#,
            WrongType,
            Some("tip"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"table":1}}"#,
            WrongType,
            Some("table"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"table":"pol"}}"#,
            InvalidValue,
            Some("table"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"table":"po\u006fl"}}"#,
            InvalidValue,
            Some("table"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"model":"fast"}}"#,
            InvalidValue,
            Some("model"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"model":["kim"]}}"#,
            WrongType,
            Some("model"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"balls":[1,2]}}"#,
            WrongType,
            Some("balls"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"balls":[[1,2],[3]]}}"#,
            WrongType,
            Some("balls"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"balls":{}}}"#,
            WrongType,
            Some("balls"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"balls":[],"balls":[]}}"#,
            DuplicateField,
            Some("balls"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"speed":3}}"#,
            DuplicateField,
            Some("speed"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"mu":0,"mu":"x"}}"#,
            DuplicateField,
            Some("mu"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"radius":0.03}}"#,
            UnknownField,
            Some("radius"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"sp\u0065ed":2}}"#,
            UnknownField,
            Some("sp\\u0065ed"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"object":-1}}"#,
            WrongType,
            Some("object"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"object":4294967296}}"#,
            WrongType,
            Some("object"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"pocket":"1"}}"#,
            WrongType,
            Some("pocket"),
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"pocket":null}}"#,
            WrongType,
            Some("pocket"),
        ),
        // serde-json-core read `0` of `0.5` and then failed on `.5` with an error that
        // named nothing: kept, so the answers stay the same.
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"pocket":0.5}}"#,
            NotARequest,
            None,
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2,"pocket":1e2}}"#,
            NotARequest,
            None,
        ),
        (
            r#"{"shot":{"cue":[1,1],"speed":2},"version":{}}"#,
            NotARequest,
            None,
        ),
        (r#"{"sh\u006ft":{}}"#, UnknownRequest, Some("sh\\u006ft")),
    ];
    for (line, kind, field) in cases {
        let p = problem(line);
        assert_eq!(p.kind(), *kind, "{line}: {p:?}");
        assert_eq!(
            p.field().as_ref().map(|f| f.as_str()),
            *field,
            "{line}: {p:?}"
        );
    }
    // Too many balls: the 16th is read, then refused.
    let balls = ["[0.5,0.5]"; 16].join(",");
    let p = problem(&format!(
        r#"{{"shot":{{"cue":[1,1],"speed":2,"balls":[{balls}]}}}}"#
    ));
    assert_eq!(
        p,
        Problem::TooMany {
            field: "balls",
            limit: 15
        }
    );
    // ... unless it is malformed.
    let balls = ["[0.5,0.5]"; 15].join(",");
    let p = problem(&format!(
        r#"{{"shot":{{"cue":[1,1],"speed":2,"balls":[{balls},[1]]}}}}"#
    ));
    assert_eq!(p.kind(), ErrorKind::WrongType);
    // Which problem comes first: the first bad field in line order, then the model,
    // the table, `cue`, `speed`.
    let p = problem(r#"{"shot":{"model":"x","table":"y","speed":"z"}}"#);
    assert_eq!(p.kind(), ErrorKind::WrongType);
    let p = problem(r#"{"shot":{"model":"x","table":"y"}}"#);
    assert_eq!(p.kind(), ErrorKind::InvalidValue);
    assert_eq!(p.field().unwrap().as_str(), "model");
    let p = problem(r#"{"shot":{"table":"y"}}"#);
    assert_eq!(p.field().unwrap().as_str(), "table");
    assert_eq!(
        problem(r#"{"shot":{"cue":[1,1],"speed":2},"version":{}}"#),
        Problem::NotARequest(crate::problem::NotARequest::SeveralKeys)
    );
}
