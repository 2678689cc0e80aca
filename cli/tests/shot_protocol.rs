//! The link's `shot` request gives the numbers of `cuesight shot --json`.
//!
//! Each seeded scene is written once as JSON: the `shot` request's body (a
//! [`ShotRequest`], the same keys) and the CLI's scene file. The request goes to a host
//! [`Session`] as a frame, as the firmware gets it (the end-to-end shot test shows the
//! firmware answering exactly as this session does, which closes the chain); its
//! answer, in its JSON form, is compared with the CLI's output key by key: every value
//! under a key both have must be equal (numbers to the bit as `f32`: both come from the
//! same `f32` computations). Keys only one side has are listed once, not failed: the device leaves
//! the scene echo and pocket names to the host, and the CLI's JSON is its own.

use cuesight_figures::thousands;
use std::collections::BTreeSet;
use std::process::Command;

use cuesight_device::{Identity, Session};
use cuesight_host::firmware::{open_answer, request_frame, Incoming};
use cuesight_host::shot_scenes::random_body;
use cuesight_link::frame::{FrameReader, MAX_FRAME, MAX_RAW};
use cuesight_link::{Request, Response, ShotRequest};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_cuesight");

/// Scenes compared.
const SCENES: usize = 150;

/// `cuesight shot --scene FILE --json`: the answer, or the error line.
fn cli(body: &Value, index: usize) -> Result<Value, String> {
    let path = std::env::temp_dir().join(format!(
        "cuesight-shot-link-{}-{index}.json",
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

/// What comparing two answers found.
#[derive(Default)]
struct Comparison {
    /// Values compared (numbers, strings, booleans, nulls).
    values: usize,
    /// Paths whose values differ.
    differences: Vec<String>,
    /// Key paths (without array indices) only the device's answer has.
    device_only: BTreeSet<String>,
    /// Key paths only the CLI's has.
    cli_only: BTreeSet<String>,
}

/// Compares `device` with `cli` under every key both have.
fn compare(device: &Value, cli: &Value, path: &str, keys: &str, out: &mut Comparison) {
    match (device, cli) {
        (Value::Object(d), Value::Object(c)) => {
            for (k, dv) in d {
                let (p, kp) = (format!("{path}/{k}"), format!("{keys}/{k}"));
                match c.get(k) {
                    Some(cv) => compare(dv, cv, &p, &kp, out),
                    None => {
                        out.device_only.insert(kp);
                    }
                }
            }
            for k in c.keys().filter(|k| !d.contains_key(*k)) {
                out.cli_only.insert(format!("{keys}/{k}"));
            }
        }
        (Value::Array(d), Value::Array(c)) if d.len() == c.len() => {
            for (i, (a, b)) in d.iter().zip(c).enumerate() {
                compare(a, b, &format!("{path}/{i}"), keys, out);
            }
        }
        (Value::Number(a), Value::Number(b)) => {
            out.values += 1;
            // As `f32`, the type of every number of both: serde_json widens the
            // device's to `f64` exactly, the CLI prints the shortest form.
            let single = |n: &serde_json::Number| n.as_f64().map(|x| (x as f32).to_bits());
            if single(a) != single(b) {
                out.differences.push(format!("{path}: {a} vs {b}"));
            }
        }
        (a, b) => {
            out.values += 1;
            if a != b {
                out.differences.push(format!("{path}: {a} vs {b}"));
            }
        }
    }
}

#[test]
fn shot_request_answers_as_the_cli() {
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let mut session = Box::new(Session::new(Identity {
        firmware: "test",
        board: "host",
    }));
    let mut reader = Box::new(FrameReader::new());
    let mut out = vec![0u8; MAX_FRAME];
    let (mut compared, mut both_refused, mut values, mut longest) = (0, 0, 0, 0);
    let mut table_refused = 0;
    let (mut device_only, mut cli_only) = (BTreeSet::new(), BTreeSet::new());
    for index in 0..SCENES {
        let body = random_body(&mut rng);
        let shot: ShotRequest = serde_json::from_value(body.clone())
            .unwrap_or_else(|e| panic!("scene {index} {body}: not a shot request: {e}"));
        let frame = request_frame(index as u16, &Request::Shot(shot)).expect("encodes");
        let mut answers = Vec::new();
        for &byte in &frame {
            if let Some(received) = reader.push(byte) {
                let served = session.serve(received, &mut out);
                let mut host = FrameReader::new();
                answers.extend(
                    out[..served.len]
                        .iter()
                        .filter_map(|&b| host.push(b).map(Incoming::from_received)),
                );
            }
        }
        assert_eq!(answers.len(), 1, "scene {index}: one answer");
        if let Incoming::Frame(raw) = &answers[0] {
            longest = longest.max(raw.len());
        }
        let answer = open_answer(&answers[0]).expect("a readable answer");
        assert_eq!(usize::from(answer.seq), index);
        match (answer.response, cli(&body, index)) {
            (Response::Shot(device), Ok(host)) => {
                let device = serde_json::to_value(&device).expect("the answer as JSON");
                let mut found = Comparison::default();
                compare(&device, &host, "", "", &mut found);
                assert!(
                    found.differences.is_empty(),
                    "scene {index} {body}: {:#?}",
                    found.differences
                );
                assert!(
                    found.values >= 20,
                    "scene {index}: only {} values in common",
                    found.values
                );
                values += found.values;
                device_only.extend(found.device_only);
                cli_only.extend(found.cli_only);
                compared += 1;
            }
            (Response::Error(_), Err(_)) => both_refused += 1,
            (Response::Shot(_), Err(message)) if message.contains("ghost-ball cut") => {
                // The CLI refuses a cut of 90° or more before solving (a clearer
                // message); the device lets the solver say so.
                both_refused += 1;
            }
            (Response::Shot(_), Err(message))
                if message.starts_with("error: whole table: ")
                    && message.contains(" is valid only where ") =>
            {
                // A later collision of the CLI's whole-table simulation is outside the
                // model's validity domain (Kim where a contact grips); the device plays
                // the first contact only.
                table_refused += 1;
            }
            (device, host) => {
                panic!("scene {index} {body}: device {device:?}, CLI {host:?}")
            }
        }
    }
    println!(
        "{compared} scenes answered with the same values ({values} compared), {both_refused} \
         refused by both, {table_refused} whole tables refused by the CLI; longest answer \
         frame {longest} raw bytes (limit {MAX_RAW})"
    );
    println!("keys only the device's answer has: {device_only:?}");
    println!("keys only the CLI's has: {cli_only:?}");
    assert!(compared >= 90, "only {compared} scenes compared");
    // The figures docs/protocol.md and docs/reliability.md quote.
    cuesight_figures::record!("protocol-shot-cli-equal", "{compared}");
    cuesight_figures::record!("protocol-shot-cli-values", "{}", thousands(values));
    cuesight_figures::record!("protocol-shot-cli-refused", "{both_refused}");
}
