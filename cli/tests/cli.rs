//! End-to-end tests of the `cuesight` binary.

use std::process::{Command, Output};

use serde_json::Value;

fn cuesight(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cuesight"))
        .args(args)
        .output()
        .expect("cuesight binary runs")
}

fn collide(extra: &[&str]) -> Output {
    let mut args = vec!["collide"];
    args.extend_from_slice(extra);
    cuesight(&args)
}

fn json(extra: &[&str]) -> Value {
    let mut args = extra.to_vec();
    args.push("--json");
    let out = collide(&args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "one line of JSON: {stdout}");
    serde_json::from_str(&stdout).expect("stdout is JSON")
}

fn vec3(value: &Value) -> [f64; 3] {
    let a = value.as_array().expect("array");
    assert_eq!(a.len(), 3, "{value}");
    [0, 1, 2].map(|i| a[i].as_f64().expect("number"))
}

/// Run an invalid command and return its single stderr line, checking the exit code
/// and that nothing went to stdout.
fn rejected(extra: &[&str], code: i32) -> String {
    let out = collide(extra);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(code), "{extra:?}: {stderr}");
    assert!(out.stdout.is_empty(), "{extra:?}");
    assert_eq!(
        stderr.lines().count(),
        1,
        "{extra:?}: exactly one stderr line, got {stderr:?}"
    );
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn json_has_every_key() {
    let v = json(&["--speed", "2", "--cut", "30"]);
    assert_eq!(v["model"], "kim-grip");
    assert!(["frictionless", "sliding", "gripping"].contains(&v["regime"].as_str().unwrap()));
    for ball in ["cue", "object"] {
        vec3(&v[ball]["v"]);
        vec3(&v[ball]["w"]);
    }
    for key in ["throw_deg", "cue_deflection_deg", "separation_deg"] {
        assert!(v[key].as_f64().unwrap().is_finite(), "{key}");
    }
    assert!(v["impulses"]["normal"].as_f64().unwrap() > 0.0);
    vec3(&v["impulses"]["friction"]);
    assert!(v["impulses"]["table_friction"].is_number());
    let input = &v["input"];
    assert_eq!(input["speed"], 2.0);
    assert_eq!(input["cut_deg"], 30.0);
    assert_eq!(vec3(&input["spin"]), [0.0; 3]);
    for key in [
        "mu",
        "mu_b",
        "mu_c",
        "restitution",
        "mu_s",
        "radius",
        "mass",
    ] {
        assert!(input[key].is_number(), "input.{key}");
    }
    // Constant friction unless --mu-b/--mu-c say otherwise.
    assert_eq!(
        (input["mu_b"].as_f64(), input["mu_c"].as_f64()),
        (Some(0.0), Some(0.0))
    );
    // A stun cut to the left throws the object ball forward (towards +y).
    assert!(v["throw_deg"].as_f64().unwrap() > 0.0);
}

/// A stun cut with every contact option set: Kim's contact grips here (gripping index
/// 1.10) unless spin is added.
const STUN_CUT: [&str; 14] = [
    "--speed",
    "1.5",
    "--cut",
    "-20",
    "--mu",
    "0.06",
    "--restitution",
    "0.9",
    "--mu-s",
    "0.2",
    "--radius",
    "0.03",
    "--mass",
    "0.2",
];

#[test]
fn options_reach_the_model() {
    let mut args = STUN_CUT.to_vec();
    args.extend_from_slice(&["--spin", "0,60,0", "--model", "kim"]);
    let v = json(&args);
    // Topspin keeps the contact sliding, inside Kim's validity domain.
    assert_eq!(v["model"], "kim");
    let input = &v["input"];
    for (key, value) in [
        ("speed", 1.5),
        ("cut_deg", -20.0),
        ("mu", 0.06),
        ("restitution", 0.9),
        ("mu_s", 0.2),
        ("radius", 0.03),
        ("mass", 0.2),
    ] {
        assert!(
            (input[key].as_f64().unwrap() - value).abs() < 1e-6,
            "input.{key}"
        );
    }
    let ideal = json(&["--speed", "2", "--cut", "30", "--model", "ideal"]);
    assert_eq!(ideal["model"], "ideal");
    assert_eq!(ideal["regime"], "frictionless");
}

#[test]
fn speed_dependent_friction_is_echoed() {
    let v = json(&[
        "--speed", "2", "--cut", "30", "--mu", "0.00995", "--mu-b", "0.108", "--mu-c", "1.088",
    ]);
    let input = &v["input"];
    for (key, value) in [("mu", 0.00995), ("mu_b", 0.108), ("mu_c", 1.088)] {
        assert!(
            (input[key].as_f64().unwrap() - value).abs() < 1e-7,
            "input.{key}"
        );
    }
    let constant = json(&["--speed", "2", "--cut", "30", "--mu", "0.00995"]);
    assert_ne!(
        v["throw_deg"], constant["throw_deg"],
        "the law reaches the model"
    );
    let line = rejected(&["--speed", "2", "--cut", "30", "--mu-b", "1.5"], 1);
    assert!(line.starts_with("error: mu_b "), "{line}");
}

#[test]
fn roll_is_topspin_head_on() {
    let v = json(&["--speed", "2", "--cut", "0", "--roll"]);
    let spin = vec3(&v["input"]["spin"]);
    assert!(spin[1] > 0.0, "{spin:?}");
    assert!(
        (spin[1] - 2.0 / 0.028575).abs() < 1e-2,
        "natural roll U/R: {spin:?}"
    );
    assert_eq!(v["input"]["roll"], true);
    // Follow: the cue ball keeps its topspin after a head-on hit.
    assert!(vec3(&v["cue"]["w"])[1] > 0.0);
}

#[test]
fn negative_spin_parses() {
    let v = json(&["--speed", "2", "--cut", "10", "--spin", "-10,0,5"]);
    assert_eq!(vec3(&v["input"]["spin"]), [-10.0, 0.0, 5.0]);
    let v = json(&["--speed", "2", "--cut", "-10", "--spin=-3,-4,-5"]);
    assert_eq!(vec3(&v["input"]["spin"]), [-3.0, -4.0, -5.0]);
}

#[test]
fn spin_and_roll_conflict() {
    let line = rejected(
        &["--speed", "2", "--cut", "0", "--spin", "0,10,0", "--roll"],
        2,
    );
    assert!(line.contains("--spin") && line.contains("--roll"), "{line}");
    let line = rejected(
        &["--speed", "2", "--cut", "0", "--roll", "--spin", "0,10,0"],
        2,
    );
    assert!(line.contains("--spin") && line.contains("--roll"), "{line}");
}

#[test]
fn invalid_physics_values_name_their_field() {
    let base = ["--speed", "2", "--cut", "30"];
    let cases: &[(&[&str], &str)] = &[
        (&["--mu", "-0.1"], "error: mu = -0.1 is outside [0, 1]"),
        (&["--mu", "NaN"], "error: mu must be a finite number"),
        (&["--restitution", "1.5"], "error: restitution "),
        (&["--mu-s", "2"], "error: mu_s "),
        (&["--radius", "0"], "error: radius "),
        (&["--mass", "inf"], "error: mass "),
        (&["--spin", "0,20000,0"], "error: spin.y "),
    ];
    for (extra, expected) in cases {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        let line = rejected(&args, 1);
        assert!(line.starts_with(expected), "{args:?}: {line}");
    }
    for (args, expected) in [
        (["--speed", "0", "--cut", "30"], "error: speed "),
        (["--speed", "-2", "--cut", "30"], "error: speed "),
        (["--speed", "2", "--cut", "90"], "error: cut "),
        (["--speed", "2", "--cut", "-95"], "error: cut "),
    ] {
        let line = rejected(&args, 1);
        assert!(line.starts_with(expected), "{args:?}: {line}");
    }
    let line = rejected(&["--speed", "2", "--cut", "90", "--roll"], 1);
    assert!(line.starts_with("error: cut "), "{line}");
}

/// Issue 16's cases outside a model's validity domain: a one-line refusal naming the
/// model, the limit and the scene's value (exit 1); `--model exact` and `auto` answer.
#[test]
fn scenes_outside_a_models_domain_are_refused() {
    let grippy = [
        "--speed",
        "1",
        "--cut",
        "30",
        "--spin",
        "-30,35,0",
        "--mu",
        "0.9",
        "--mu-s",
        "1",
        "--restitution",
        "0.6",
    ];
    let line = rejected(&grippy, 1);
    assert_eq!(
        line.trim_end(),
        "error: kim-grip is valid only where mu * mu_s <= 0.2 (a speed-dependent law: mu(0) * mu_s) (here 0.9); use exact or auto"
    );
    for model in ["exact", "auto"] {
        let mut args = grippy.to_vec();
        args.extend_from_slice(&["--model", model]);
        assert_eq!(json(&args)["model"], model);
    }
    // A stun cut at μ 0.06 grips in Kim's first order (gripping index 1.10).
    let mut args = STUN_CUT.to_vec();
    args.extend_from_slice(&["--model", "kim"]);
    let line = rejected(&args, 1);
    assert!(
        line.starts_with("error: kim is valid only where gripping index mu p0 / s* <= 1"),
        "{line}"
    );
}

#[test]
fn usage_errors_name_their_option() {
    let base = ["--speed", "2", "--cut", "30"];
    let cases: &[(&[&str], &str)] = &[
        (&["--mu", "abc"], "--mu"),
        (&["--spin", "1,2"], "--spin"),
        (&["--spin", "1,x,3"], "--spin"),
        (&["--spin", ""], "--spin"),
        (&["--model", "bogus"], "--model"),
        (&["--mass"], "--mass"),
    ];
    for (extra, option) in cases {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        let line = rejected(&args, 2);
        assert!(line.contains(option), "{args:?}: {line}");
    }
    let line = rejected(&["--cut", "30"], 2);
    assert!(line.contains("--speed"), "{line}");
    let line = rejected(&["--speed", "fast", "--cut", "30"], 2);
    assert!(line.contains("--speed"), "{line}");
    let line = rejected(&["--speed", "2", "--cut", "left"], 2);
    assert!(line.contains("--cut"), "{line}");
}

#[test]
fn human_summary() {
    let out = collide(&[
        "--speed", "2", "--cut", "30", "--spin", "0,-50,0", "--model", "kim",
    ]);
    assert!(out.status.success());
    assert!(out.stderr.is_empty());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("model kim, regime "), "{text}");
    for needle in [
        "cue:",
        "object:",
        "m/s",
        "rad/s",
        "throw",
        "cue deflection",
        "separation",
    ] {
        assert!(text.contains(needle), "{needle} missing from {text}");
    }
}

#[test]
fn help_and_version_still_work() {
    let out = cuesight(&["--version"]);
    assert!(out.status.success());
    assert!(String::from_utf8(out.stdout)
        .unwrap()
        .starts_with("cuesight "));
    let out = cuesight(&["collide", "--help"]);
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    assert!(help.contains("--spin") && help.contains("--model"));
}

/// `--model reference` runs the f64 solver; on a stun 30° cut (pure sliding along y,
/// where the closed form is exact) it agrees with kim-grip to f32 precision.
#[test]
fn reference_model_runs_and_agrees_on_a_stun_cut() {
    let reference = json(&["--speed", "2", "--cut", "30", "--model", "reference"]);
    let kim_grip = json(&["--speed", "2", "--cut", "30"]);
    assert_eq!(reference["model"], "reference");
    assert_eq!(reference["regime"], "sliding");
    let throw = |v: &serde_json::Value| v["throw_deg"].as_f64().unwrap();
    assert!((throw(&reference) - throw(&kim_grip)).abs() < 1e-4);
}

/// `--model auto --tolerance T`: the tier the core's `select_model` picks for T, its
/// estimate, and exactly that tier's outcome; a looser tolerance never picks a dearer
/// tier.
#[test]
fn auto_tolerance_picks_the_cores_tier() {
    use cuesight::{select_model, Impact, Model, Params};
    let scene = ["--speed", "2", "--cut", "30", "--spin", "0,40,0"];
    let impact = Impact::from_cut_degrees(2.0, 30.0, [0.0, 40.0, 0.0]).unwrap();
    let rank = |name: &str| Model::ALL.iter().position(|m| m.name() == name).unwrap();
    let mut last_rank = usize::MAX;
    for tolerance in ["1e-5", "1e-3", "0.01", "0.05", "0.2", "1"] {
        let mut args = scene.to_vec();
        args.extend(["--model", "auto", "--tolerance", tolerance]);
        let v = json(&args);
        let t: f32 = tolerance.parse().unwrap();
        let (tier, estimate) = select_model(&Params::POOL, &impact, t);
        assert_eq!(v["model"], "auto");
        let as_f32 = |key: &str| v[key].as_f64().map(|x| x as f32);
        assert_eq!(as_f32("tolerance"), Some(t));
        assert_eq!(v["model_used"], tier.name(), "{tolerance}");
        assert_eq!(as_f32("error_estimate"), Some(estimate));
        assert!(
            estimate <= t || tier == Model::Exact,
            "{tolerance}: {estimate}"
        );
        // The same numbers as asking for that tier.
        let mut direct = scene.to_vec();
        direct.extend(["--model", tier.name()]);
        let d = json(&direct);
        for key in ["cue", "object", "throw_deg", "impulses", "regime"] {
            assert_eq!(v[key], d[key], "{tolerance}: {key}");
        }
        let r = rank(v["model_used"].as_str().unwrap());
        assert!(
            r <= last_rank,
            "{tolerance}: a dearer tier than a tighter tolerance's"
        );
        last_rank = r;
    }
    // Without --tolerance: the link's default, 1e-3; without auto, no extra keys.
    let mut args = scene.to_vec();
    args.extend(["--model", "auto"]);
    assert_eq!(json(&args)["tolerance"].as_f64(), Some(0.001));
    let plain = json(&scene);
    for key in ["tolerance", "model_used", "error_estimate"] {
        assert!(plain.get(key).is_none(), "{key}");
    }
}

#[test]
fn auto_tolerance_in_the_summary_and_its_errors() {
    let args = ["--speed", "2", "--cut", "30", "--model", "auto"];
    let out = collide(&[&args[..], &["--tolerance", "0.05"]].concat());
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let last = text.lines().last().unwrap();
    assert!(last.starts_with("auto: "), "{text}");
    assert!(last.ends_with(", tolerance 0.05)"), "{text}");
    // The other lines are the summary as before.
    assert!(text.starts_with("model auto, regime "), "{text}");
    assert_eq!(text.lines().count(), 7, "{text}");
    let kim = collide(&["--speed", "2", "--cut", "30", "--model", "kim"]);
    assert_eq!(String::from_utf8(kim.stdout).unwrap().lines().count(), 6);
    // The core checks the tolerance: (0, 1], finite.
    for bad in ["0", "-0.1", "1.5", "NaN", "inf"] {
        let e = rejected(&[&args[..], &["--tolerance", bad]].concat(), 1);
        assert!(e.starts_with("error: tolerance "), "{bad}: {e}");
    }
    // Only auto has a tolerance.
    let e = rejected(&["--speed", "2", "--cut", "30", "--tolerance", "0.1"], 2);
    assert!(
        e.contains("--tolerance is for --model auto, not kim-grip"),
        "{e}"
    );
    let e = rejected(
        &[
            "--speed",
            "2",
            "--cut",
            "30",
            "--model",
            "reference",
            "--tolerance",
            "0.1",
        ],
        2,
    );
    assert!(e.contains("not reference"), "{e}");
    let e = rejected(&[&args[..], &["--tolerance", "x"]].concat(), 2);
    assert!(e.contains("--tolerance"), "{e}");
}

/// `--tip SIDE,HEIGHT` (shot's vocabulary): the strike's spin at the arrival speed, in
/// rad/s in the echo; `0,0.4` is natural roll, and the tip's spin played as `--spin`
/// gives the same answer.
#[test]
fn tip_offsets_are_spins_from_the_strike() {
    let scene = ["--speed", "2", "--cut", "30"];
    let with = |extra: &[&str]| json(&[&scene[..], extra].concat());
    let tip_roll = with(&["--tip", "0,0.4"]);
    let roll = with(&["--roll"]);
    let (a, b) = (
        vec3(&tip_roll["input"]["spin"]),
        vec3(&roll["input"]["spin"]),
    );
    for i in 0..3 {
        assert!((a[i] - b[i]).abs() <= 1e-5 * 70.0, "{a:?} vs {b:?}");
    }
    let close = |x: &Value, y: &Value| (x.as_f64().unwrap() - y.as_f64().unwrap()).abs() < 1e-4;
    assert!(close(&tip_roll["throw_deg"], &roll["throw_deg"]));
    assert_eq!(tip_roll["input"]["roll"], false);
    for tip in ["0.3,-0.2", "-0.25,0", "0,-0.5"] {
        let v = with(&["--tip", tip]);
        let spin = vec3(&v["input"]["spin"])
            .map(|w| (w as f32).to_string())
            .join(",");
        let direct = with(&["--spin", &spin]);
        assert_eq!(v, direct, "{tip}: --spin {spin}");
    }
    // Head on, right english throws the object ball to the left (+y), left english to
    // the right (the strike's and the collision's signs, as in the core's tests).
    let throw = |tip: &str| {
        let v = json(&["--speed", "2", "--cut", "0", "--tip", tip]);
        v["throw_deg"].as_f64().unwrap()
    };
    assert!(throw("0.3,0") > 0.5, "{}", throw("0.3,0"));
    assert!(throw("-0.3,0") < -0.5, "{}", throw("-0.3,0"));
    // Errors: beyond R/2 (the core's), the syntax, with --spin or --roll.
    let e = rejected(&[&scene[..], &["--tip", "0.4,0.4"]].concat(), 1);
    assert!(e.starts_with("error: tip_offset "), "{e}");
    let e = rejected(&[&scene[..], &["--tip", "0.1"]].concat(), 2);
    assert!(e.contains("SIDE,HEIGHT"), "{e}");
    rejected(&[&scene[..], &["--tip", "0,0.1", "--roll"]].concat(), 2);
    rejected(
        &[&scene[..], &["--tip", "0,0.1", "--spin", "0,1,0"]].concat(),
        2,
    );
}

/// `cuesight device` with requests on stdin, against the in-process device.
fn device(args: &[&str], stdin: &str) -> Output {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_cuesight"))
        .arg("device")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cuesight binary runs");
    let mut input = child.stdin.take().unwrap();
    input.write_all(stdin.as_bytes()).unwrap();
    drop(input);
    child.wait_with_output().unwrap()
}

#[test]
fn device_plays_the_demo_session_on_the_loopback() {
    let demo = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../firmware/demo/session.jsonl"
    );
    let out = device(&["--loopback", "--session", demo], "");
    let stdout = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    assert!(stdout.starts_with("connected: schema 0x"), "{stdout}");
    assert!(stdout.contains("< error: speed = -1 is outside (0, 100] m/s"));
    assert!(stdout.contains("< session over: "), "{stdout}");
}

#[test]
fn device_json_answers_one_line_each() {
    let out = device(
        &["--loopback", "--json"],
        "{\"params\":{}}\n{\"collide\":{\"speed\":2,\"cut\":30}}\n",
    );
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON"))
        .collect();
    assert_eq!(lines.len(), 2, "{stdout}");
    assert_eq!(lines[0]["params"]["model"], "kim-grip");
    assert_eq!(lines[1]["collide"]["input"]["cut_deg"], 30.0);
}

#[test]
fn device_fails_after_the_session_on_unexpected_errors() {
    let out = device(
        &["--loopback"],
        "{\"collide\":{\"speed\":-1,\"cut\":30}}\n{\"collide\":{\"speed\":2,\"cut\":NaN}}\n\
         !expect-error {\"collide\":{\"speed\":0,\"cut\":30}}\n{\"params\":{}}\n",
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    // Played to the end.
    assert!(stdout.contains("< defaults now: "), "{stdout}");
    assert!(stderr.contains("2 unexpected error(s)"), "{stderr}");
    assert!(
        stderr.contains("line 1: error: speed = -1 is outside"),
        "{stderr}"
    );
    assert!(stderr.contains("line 2: not a request: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn device_usage_errors() {
    let out = device(&[], "");
    assert_eq!(out.status.code(), Some(2));
    let out = device(&["--loopback", "--session", "/no/such/file"], "");
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.starts_with("error: cannot read /no/such/file"),
        "{stderr}"
    );
    let out = device(&["--tcp", "127.0.0.1:1"], "");
    assert_eq!(out.status.code(), Some(3), "no device there");
}
