//! The protocol's `shot` request gives the same answer as `cuesight shot --json`.
//!
//! Each seeded scene is written once as a `shot` body; the same JSON object is the
//! CLI's scene file (the request's keys are the scene file's). The session's answer
//! must hold exactly the CLI's keys (but the scene echo and the pocket names, which the
//! device leaves to the host) with identical values: both print `f32` with ryu's
//! shortest form, so the same numbers give the same text. The firmware's answers are
//! compared with the host session's by the end-to-end test, which closes the chain.

use std::process::Command;

use cuesight_host::shot_scenes::random_body;
use cuesight_protocol::{Identity, Session, MAX_ANSWER};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::{json, Map, Value};

const BIN: &str = env!("CARGO_BIN_EXE_cuesight");

/// Keys of the CLI's answer the device does not send.
const HOST_ONLY: [&str; 5] = ["table", "balls", "mu_cloth", "mu_roll", "pocket_name"];

/// `cuesight shot --scene FILE --json`: the answer, or the error line.
fn cli(body: &Value, index: usize) -> Result<Value, String> {
    let path = std::env::temp_dir().join(format!(
        "cuesight-shot-protocol-{}-{index}.json",
        std::process::id()
    ));
    std::fs::write(&path, body.to_string()).expect("write the scene file");
    let output = Command::new(BIN)
        .args(["shot", "--json", "--scene"])
        .arg(&path)
        .output()
        .expect("run cuesight");
    let _ = std::fs::remove_file(&path);
    if output.status.success() {
        Ok(serde_json::from_slice(&output.stdout).expect("valid JSON"))
    } else {
        Err(String::from_utf8_lossy(&output.stderr).trim().to_owned())
    }
}

/// Every key of `device` is in `host` with the same value (recursively); every key of
/// `host` but [`HOST_ONLY`] is in `device`.
fn same(device: &Value, host: &Value, path: &str, differences: &mut Vec<String>) {
    match (device, host) {
        (Value::Object(d), Value::Object(h)) => {
            let keys = |m: &Map<String, Value>| -> Vec<String> {
                m.keys()
                    .filter(|k| !HOST_ONLY.contains(&k.as_str()))
                    .cloned()
                    .collect()
            };
            let (mut dk, mut hk) = (keys(d), keys(h));
            dk.sort();
            hk.sort();
            if dk != hk {
                differences.push(format!("{path}: keys {dk:?} vs {hk:?}"));
                return;
            }
            for k in dk {
                same(&d[&k], &h[&k], &format!("{path}/{k}"), differences);
            }
        }
        (Value::Array(d), Value::Array(h)) if d.len() == h.len() => {
            for (i, (a, b)) in d.iter().zip(h).enumerate() {
                same(a, b, &format!("{path}/{i}"), differences);
            }
        }
        (Value::Number(a), Value::Number(b)) => {
            if a.as_f64() != b.as_f64() {
                differences.push(format!("{path}: {a} vs {b}"));
            }
        }
        (a, b) if a == b => {}
        (a, b) => differences.push(format!("{path}: {a} vs {b}")),
    }
}

#[test]
fn shot_request_answers_as_the_cli() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let mut session = Session::new(Identity {
        firmware: "test",
        board: "host",
    });
    let mut out = cuesight_protocol::AnswerLine::new();
    let (mut compared, mut both_refused, mut longest, mut worst) = (0, 0, 0, 0);
    for index in 0..150 {
        let body = random_body(&mut rng);
        let line = json!({ "shot": body }).to_string();
        session
            .serve_line(line.as_bytes(), &mut out)
            .expect("an answer");
        longest = longest.max(out.len());
        let answer: Value = serde_json::from_slice(&out).expect("answer JSON");
        worst = worst.max(worst_case_length(&answer, out.len()));
        match (answer.get("shot"), cli(&body, index)) {
            (Some(device), Ok(host)) => {
                let mut differences = Vec::new();
                same(device, &host, "", &mut differences);
                assert!(
                    differences.is_empty(),
                    "scene {index} {body}: {differences:#?}"
                );
                compared += 1;
            }
            (None, Err(_)) => both_refused += 1,
            (Some(_), Err(message)) if message.contains("ghost-ball cut") => {
                // The CLI refuses a cut of 90° or more before solving (a clearer
                // message); the device lets the solver say so.
                both_refused += 1;
            }
            (device, host) => {
                panic!("scene {index} {body}: device {device:?}, host {host:?} (answer {answer})")
            }
        }
    }
    println!(
        "{compared} scenes answered identically, {both_refused} refused by both; longest \
         answer {longest} bytes, {worst} with every number at its longest (buffer {MAX_ANSWER})"
    );
    assert!(compared >= 90, "only {compared} scenes compared");
    assert!(worst < MAX_ANSWER, "a shot answer could need {worst} bytes");
}

/// The length of `answer` (`length` bytes as sent) if every number took 14 characters
/// (an `f32` in ryu's shortest form is at most 14: `-1.2345678e-38`; `null` counts as
/// one) and every model
/// name were the longest (`kim-grip`).
fn worst_case_length(answer: &Value, length: usize) -> usize {
    fn walk(v: &Value, extra: &mut isize) {
        match v {
            Value::Number(n) => *extra += 14 - n.to_string().len() as isize,
            // A `null` that could have been a number (`miss`, `error_estimate`, ...).
            Value::Null => *extra += 10,
            Value::String(s) if s.len() < 8 => *extra += 8 - s.len() as isize,
            Value::Array(a) => a.iter().for_each(|x| walk(x, extra)),
            Value::Object(o) => o.values().for_each(|x| walk(x, extra)),
            _ => {}
        }
    }
    let mut extra = 0;
    walk(answer, &mut extra);
    (length as isize + extra) as usize
}
