//! The binary: errors, `--json`, `--params` round trips, cross-validation, CSV.

use std::process::Command;

use cuesight_cli::calibrate::read_file;
use serde_json::Value;

use super::{cuesight, shared_set, temp_file};

fn rejected(args: &[&str]) -> String {
    let out = cuesight(args);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
    assert!(out.stdout.is_empty(), "{args:?}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ") && !stderr.contains("panicked"),
        "{stderr}"
    );
    stderr
}

#[test]
fn cli_errors_are_one_line_and_exit_1() {
    let cases: [(&str, &[u8], &str); 5] = [
        (
            "missing.csv",
            b"cut_deg,speed_mps\n30,2\n",
            "missing column `throw_deg`",
        ),
        (
            "cut.csv",
            b"cut_deg,speed_mps,throw_deg\n91,2,3\n",
            "line 2: cut_deg = 91",
        ),
        (
            "nan.csv",
            b"cut_deg,speed_mps,throw_deg\n30,2,NaN\n",
            "line 2: throw_deg",
        ),
        (
            "few.csv",
            b"cut_deg,speed_mps,throw_deg\n30,2,3\n40,2,3\n",
            "2 points for 3",
        ),
        ("empty.json", b"{\"points\": []}", "no points"),
    ];
    for (name, contents, expected) in cases {
        let path = temp_file(name, contents);
        let e = rejected(&["calibrate", "--throw", path.to_str().unwrap()]);
        assert!(e.contains(expected), "{name}: {e}");
    }
    let e = rejected(&[
        "calibrate",
        "--throw",
        shared_set().to_str().unwrap(),
        "--max-evaluations",
        "50",
    ]);
    assert!(e.contains("did not converge"), "{e}");
    let e = rejected(&["calibrate", "--throw", "/nonexistent/throw.csv"]);
    assert!(e.contains("/nonexistent/throw.csv"), "{e}");
}

fn calibrate_json(extra: &[&str]) -> Value {
    let shared = shared_set();
    let mut args = vec!["calibrate", "--throw", shared.to_str().unwrap(), "--json"];
    args.extend_from_slice(extra);
    let out = cuesight(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1);
    serde_json::from_str(&stdout).unwrap()
}

#[test]
fn cli_json_has_collides_names_and_feeds_params() {
    let v = calibrate_json(&[]);
    for key in ["mu", "mu_b", "mu_c", "restitution", "rms_deg", "points"] {
        assert!(v[key].is_number(), "{key}: {v}");
    }
    assert_eq!(v["points"], 36);
    assert_eq!(v["above_ceiling"], 12);
    assert!(v["ci95"]["mu_c"].as_f64().unwrap() > 0.0);
    let path = temp_file("fit.json", v.to_string().as_bytes());
    let path = path.to_str().unwrap();
    let number = |x: &Value| format!("{}", x.as_f64().unwrap() as f32);
    let (mu, b, c) = (number(&v["mu"]), number(&v["mu_b"]), number(&v["mu_c"]));
    let shot = ["collide", "--speed", "2", "--cut", "30", "--json"];
    let with_file = cuesight(&[&shot[..], &["--params", path]].concat());
    let with_flags = cuesight(&[&shot[..], &["--mu", &mu, "--mu-b", &b, "--mu-c", &c]].concat());
    assert!(with_file.status.success());
    assert_eq!(with_file.stdout, with_flags.stdout);
    // docs/calibration.md §3: the fitted μ(v) in `collide`, and the device's `params`
    // line with the fit (four significant digits).
    let played: Value = serde_json::from_slice(&with_file.stdout).unwrap();
    cuesight_figures::record!(
        "calibration-params-collide-throw",
        "{:.3} deg ({})",
        played["throw_deg"].as_f64().unwrap(),
        played["regime"].as_str().unwrap()
    );
    let significant = |x: &Value| {
        let x = x.as_f64().unwrap();
        let decimals = (3 - x.abs().log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    };
    cuesight_figures::record!(
        "calibration-params-line",
        "`{{\"params\":{{\"mu\":{},\"mu_b\":{},\"mu_c\":{},\"restitution\":{}}}}}`",
        significant(&v["mu"]),
        significant(&v["mu_b"]),
        significant(&v["mu_c"]),
        v["restitution"]
    );
    // A flag overrides the file.
    let overridden =
        cuesight(&[&shot[..], &["--params", path, "--mu-b", "0", "--mu-c", "0"]].concat());
    let constant = cuesight(&[&shot[..], &["--mu", &mu]].concat());
    assert_eq!(overridden.stdout, constant.stdout);
    // shot reads the same file.
    let shot_args = [
        "shot",
        "--cue",
        "0.9,0.8",
        "--ball",
        "1.9,0.9",
        "--pocket",
        "top-right",
        "--json",
    ];
    let out = cuesight(&[&shot_args[..], &["--params", path]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let plain = cuesight(&shot_args);
    assert_ne!(out.stdout, plain.stdout, "the fitted μ(v) changes the aim");
}

#[test]
fn cli_params_file_errors_name_the_file_and_key() {
    let path = temp_file("typo.json", br#"{"mu": 0.05, "restituion": 0.9}"#);
    let out = cuesight(&[
        "collide",
        "--speed",
        "2",
        "--cut",
        "30",
        "--params",
        path.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("restituion") && stderr.contains("typo.json"),
        "{stderr}"
    );
    let path = temp_file("bad_mu.json", br#"{"mu": 2}"#);
    let out = cuesight(&[
        "collide",
        "--speed",
        "2",
        "--cut",
        "30",
        "--params",
        path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn cli_cross_validation_and_csv() {
    let v = calibrate_json(&["--cross-validate"]);
    let cv = &v["cross_validation"];
    assert_eq!(cv["points"], 36);
    assert_eq!(cv["folds"].as_array().unwrap().len(), 3);
    // The same points as CSV give the same fit.
    let points = read_file(&shared_set()).unwrap();
    let mut csv = String::from("id,series,cut_deg,speed_mps,spin,throw_deg\n");
    for m in &points {
        csv += &format!(
            "{},{},{},{},stun,{}\n",
            m.id, m.series, m.cut_deg, m.speed_mps, m.throw_deg
        );
    }
    let path = temp_file("shared.csv", csv.as_bytes());
    let out = cuesight(&["calibrate", "--throw", path.to_str().unwrap(), "--json"]);
    let from_csv: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(from_csv["mu_c"], v["mu_c"]);
    assert_eq!(from_csv["rms_deg"], v["rms_deg"]);
}

#[test]
fn cli_closed_stdout_is_not_a_panic() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_cuesight"))
        .args(["calibrate", "--throw", shared_set().to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}
