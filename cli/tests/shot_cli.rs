//! `cuesight shot`, run as a process: the JSON answer's keys, the inverse-aim round trip
//! (the printed aim, played, pockets the ball), the SVG drawing, the example scenes, and
//! one stderr line with the right exit code for each kind of invalid input.

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_cuesight");

fn scene(name: &str) -> String {
    format!("{}/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .arg("shot")
        .args(args)
        .output()
        .expect("run cuesight")
}

fn stdout(output: &Output) -> String {
    String::from_utf8(output.stdout.clone()).expect("utf-8 stdout")
}

fn stderr(output: &Output) -> String {
    String::from_utf8(output.stderr.clone()).expect("utf-8 stderr")
}

/// Run and expect success; the JSON answer.
fn json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.push("--json");
    let output = run(&all);
    assert!(
        output.status.success(),
        "{args:?}: exit {:?}: {}",
        output.status.code(),
        stderr(&output)
    );
    let text = stdout(&output);
    assert_eq!(text.lines().count(), 1, "one line of JSON: {text}");
    serde_json::from_str(&text).expect("valid JSON")
}

fn number(value: &Value, path: &str) -> f64 {
    value
        .pointer(path)
        .and_then(Value::as_f64)
        .unwrap_or_else(|| panic!("{path} is not a number in {value}"))
}

/// A file in the temp directory, unique to this process and test.
fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("cuesight-shot-{}-{name}", std::process::id()))
}

#[test]
fn json_has_the_documented_keys() {
    let v = json(&["--scene", &scene("cut_to_corner.toml")]);
    // docs/shot-cli.md: the solved aim to play back, and the cue ball's hop.
    cuesight_figures::record!("shot-cli-aim", "{:.3}", number(&v, "/stroke/aim_deg"));
    cuesight_figures::record!(
        "shot-cli-hop",
        "{:.1} mm lasts {:.0} ms",
        number(&v, "/cue_ball/hop_height") * 1e3,
        number(&v, "/cue_ball/air_time") * 1e3
    );
    for key in [
        "mode",
        "table",
        "balls",
        "mu_cloth",
        "mu_roll",
        "stroke",
        "solve",
        "contact",
        "cue_ball",
        "object_ball",
        "target",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["mode"], "solve");
    for key in ["name", "length", "width", "radius", "mass", "pockets"] {
        assert!(v["table"].get(key).is_some(), "missing table.{key}");
    }
    assert_eq!(v["table"]["pockets"].as_array().unwrap().len(), 6);
    for key in [
        "cue_speed",
        "tip",
        "aim_deg",
        "aim",
        "launch_speed",
        "launch_spin",
    ] {
        assert!(v["stroke"].get(key).is_some(), "missing stroke.{key}");
    }
    for key in [
        "object",
        "pocket",
        "pocket_name",
        "aim_deg",
        "naive_aim_deg",
        "correction_deg",
        "correction_offset",
        "thinner",
        "cut_deg",
        "ghost_ball",
        "naive_ghost_ball",
        "evaluations",
        "residual",
    ] {
        assert!(v["solve"].get(key).is_some(), "missing solve.{key}");
    }
    for key in [
        "ball",
        "time",
        "cue_position",
        "line_of_centres",
        "cut_deg",
        "speed",
        "spin",
        "model",
        "model_used",
        "error_estimate",
        "regime",
        "throw_deg",
    ] {
        assert!(v["contact"].get(key).is_some(), "missing contact.{key}");
    }
    assert_eq!(v["contact"]["model"], "auto");
    let used = v["contact"]["model_used"].as_str().unwrap();
    assert!(
        cuesight::Model::ALL.iter().any(|m| m.name() == used),
        "{used}"
    );
    for ball in ["cue_ball", "object_ball"] {
        for key in [
            "ball",
            "start",
            "velocity",
            "spin",
            "hop_height",
            "air_time",
            "landing",
            "sliding_time",
            "rolling_start",
            "rolling_velocity",
            "rolling_speed",
            "rolling_direction_deg",
            "stop_time",
            "rest",
            "end",
            "end_time",
            "end_position",
            "pocket",
            "pocket_name",
        ] {
            assert!(v[ball].get(key).is_some(), "missing {ball}.{key}");
        }
    }
    assert_eq!(v["object_ball"]["end"], "pocket");
    assert_eq!(v["object_ball"]["pocket"], 3);
    assert_eq!(v["target"]["pocketed"], true);
    assert_eq!(v["target"]["pocket_name"], "top-right");
    // SI units: the solved correction is a few millimetres, given in metres.
    assert!(number(&v, "/solve/correction_offset").abs() < 0.01);
    // The ghost ball of the solution is the cue ball's centre at contact.
    for i in 0..2 {
        let path = |p: &str| format!("{p}/{i}");
        assert!(
            (number(&v, &path("/solve/ghost_ball")) - number(&v, &path("/contact/cue_position")))
                .abs()
                < 1e-6
        );
    }
}

/// The aim `--solve` reports, played with `--aim`, pockets the ball: the full-precision
/// JSON aim within 1 mm of the pocket centre, and the three-decimal aim the guidance
/// prints still in the pocket.
#[test]
fn solved_aim_played_back_reaches_the_pocket() {
    let scenes: [Vec<String>; 4] = [
        vec!["--scene".into(), scene("cut_to_corner.toml")],
        vec!["--scene".into(), scene("snooker_draw_to_middle.toml")],
        // Flags only: right english and draw into a side pocket, exact collision.
        [
            "--cue", "0.6,0.4", "--ball", "1.1,0.9", "--pocket", "top-side", "--speed", "2",
            "--tip", "0.2,-0.3", "--model", "exact",
        ]
        .map(String::from)
        .to_vec(),
        // Thin cut with a blocker elsewhere and a different cloth.
        [
            "--cue",
            "1.8,0.3",
            "--ball",
            "0.5,0.55",
            "--ball",
            "1.0,1.0",
            "--pocket",
            "0",
            "--speed",
            "4",
            "--mu-cloth",
            "0.25",
            "--mu-roll",
            "0.015",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for args in &scenes {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let solved = json(&[args.as_slice(), &["--solve"]].concat());
        assert_eq!(solved["mode"], "solve", "{args:?}");
        assert_eq!(solved["target"]["pocketed"], true, "{args:?}");
        let pocket = solved["solve"]["pocket"].clone();

        let aim = number(&solved, "/solve/aim_deg").to_string();
        let played = json(&[args.as_slice(), &["--aim", &aim]].concat());
        assert_eq!(played["mode"], "play");
        assert!(played["solve"].is_null());
        assert_eq!(played["target"]["pocketed"], true, "{args:?}: {played}");
        assert_eq!(played["object_ball"]["pocket"], pocket);
        let miss = number(&played, "/target/miss");
        assert!(miss.abs() < 1e-3, "{args:?}: miss {miss} m");

        // The guidance line "aim 12.345° (ghost ball ...": play that rounded aim.
        let text = stdout(&run(&[args.as_slice(), &["--solve"]].concat()));
        let printed = text
            .lines()
            .find_map(|l| l.strip_prefix("aim "))
            .and_then(|l| l.split('°').next())
            .unwrap_or_else(|| panic!("no aim line in {text}"));
        assert!(text.contains("than the ghost-ball aim; cut "), "{text}");
        let played = json(&[args.as_slice(), &["--aim", printed]].concat());
        assert_eq!(
            played["target"]["pocketed"], true,
            "{args:?}: aim {printed}"
        );
    }
}

#[test]
fn guidance_names_the_correction_cut_pocket_and_cue_ball() {
    let output = run(&["--scene", &scene("cut_to_corner.toml")]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    let guidance = text
        .lines()
        .find(|l| l.starts_with("aim "))
        .expect("guidance line");
    for part in [
        " mm thinner (",
        "° clockwise) than the ghost-ball aim; cut ",
        "°; object ball pockets in the top-right corner (pocket 3); cue ball ",
    ] {
        assert!(guidance.contains(part), "{guidance}");
    }
    assert!(text.contains("collision: model auto -> "), "{text}");
    assert!(text.contains("throw "), "{text}");
    assert!(text.contains("cue ball: leaves at "), "{text}");
    assert!(text.contains("ball 1: leaves at "), "{text}");
    assert!(text.contains("rolls toward "), "{text}");
}

#[test]
fn flags_override_the_scene_file() {
    let v = json(&[
        "--scene",
        &scene("cut_to_corner.json"),
        "--cue",
        "0.8,0.7",
        "--speed",
        "4",
        "--model",
        "kim-grip",
        "--mu",
        "0.06",
        "--aim",
        "10",
    ]);
    assert_eq!(v["mode"], "play");
    assert!((number(&v, "/balls/0/0") - 0.8).abs() < 1e-6);
    assert!((number(&v, "/balls/0/1") - 0.7).abs() < 1e-6);
    assert!(
        (number(&v, "/balls/1/0") - 1.9).abs() < 1e-6,
        "file's balls kept"
    );
    assert_eq!(number(&v, "/stroke/cue_speed"), 4.0);
    assert_eq!(number(&v, "/stroke/aim_deg"), 10.0);
    assert_eq!(v["contact"]["model_used"], "kim-grip");
    // --ball replaces the file's balls.
    let v = json(&["--scene", &scene("cut_to_corner.toml"), "--ball", "2.0,1.0"]);
    assert_eq!(v["balls"].as_array().unwrap().len(), 2);
}

#[test]
fn toml_and_json_scenes_give_the_same_answer() {
    let a = json(&["--scene", &scene("cut_to_corner.toml")]);
    let b = json(&["--scene", &scene("cut_to_corner.json")]);
    assert_eq!(a, b);
}

#[test]
fn every_example_scene_parses_and_plays() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if !matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("toml" | "json")
        ) {
            continue;
        }
        let v = json(&["--scene", path.to_str().unwrap()]);
        assert!(v["contact"].is_object(), "{}", path.display());
        count += 1;
    }
    assert!(count >= 3, "{count} scenes");
}

#[test]
fn a_miss_and_a_pocketless_table_are_answers() {
    // Aimed away from every ball: no contact, the cue ball's own path.
    let v = json(&["--cue", "1.0,0.6", "--ball", "2.0,0.6", "--aim", "180"]);
    assert!(v["contact"].is_null());
    assert!(v["object_ball"].is_null());
    assert_eq!(v["cue_ball"]["ball"], 0);
    assert!(["rest", "cushion", "pocket"].contains(&v["cue_ball"]["end"].as_str().unwrap()));
    // Carom: no pockets, a played aim.
    let v = json(&[
        "--table", "carom", "--cue", "0.7,0.7", "--ball", "1.5,0.8", "--aim", "7",
    ]);
    assert_eq!(v["table"]["name"], "carom");
    assert!(v["table"]["pockets"].as_array().unwrap().is_empty());
    assert!(v["target"].is_null());
    assert_eq!(v["contact"]["ball"], 1);
}

/// Element by `id` in the parsed SVG.
fn by_id<'a>(doc: &'a roxmltree::Document, id: &str) -> Option<roxmltree::Node<'a, 'a>> {
    doc.descendants().find(|n| n.attribute("id") == Some(id))
}

fn polyline(node: roxmltree::Node) -> Vec<(f64, f64)> {
    node.attribute("points")
        .unwrap()
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

#[test]
fn svg_is_well_formed_with_the_expected_elements() {
    let path = temp("cut.svg");
    let path_text = path.to_str().unwrap();
    // The cut-to-corner shot: the collision gives the cue ball a hop.
    let v = json(&["--scene", &scene("cut_to_corner.toml"), "--svg", path_text]);
    let text = std::fs::read_to_string(&path).expect("svg written");
    std::fs::remove_file(&path).ok();
    let doc = roxmltree::Document::parse(&text).expect("well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    let width: f64 = root.attribute("width").unwrap().parse().unwrap();
    assert!((800.0..=1400.0).contains(&width), "{width}");

    for id in [
        "cloth",
        "rail",
        "ball-0",
        "ball-1",
        "ball-2",
        "ghost-ball",
        "naive-ghost-ball",
        "cue-path-before",
        "cue-path-after",
        "object-path",
        "caption",
    ] {
        assert!(by_id(&doc, id).is_some(), "no #{id}");
    }
    for i in 0..6 {
        let pocket = by_id(&doc, &format!("pocket-{i}")).expect("pocket group");
        assert!(pocket
            .descendants()
            .any(|n| n.attribute("class") == Some("pocket-target")));
        let chosen = pocket.attribute("class").unwrap().contains("chosen");
        assert_eq!(chosen, i == 3, "pocket {i}");
    }
    // The hop: a dashed segment from the contact to the landing point.
    assert!(number(&v, "/cue_ball/air_time") > 0.0);
    let hop = by_id(&doc, "cue-hop").expect("cue hop drawn");
    assert!(hop.attribute("stroke-dasharray").is_some());
    assert_eq!(polyline(hop).len(), 2);
    // The post-impact cue-ball path is sampled, and curved (follow on a cut).
    let after = polyline(by_id(&doc, "cue-path-after").unwrap());
    assert!(after.len() > 50, "{} points", after.len());
    let (a, b, c) = (after[0], after[after.len() / 4], after[after.len() - 1]);
    let bend = ((b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)).abs();
    assert!(bend > 100.0, "path looks straight: {bend}");
    // The ghost ball sits where the cue-ball path before the contact ends.
    let before = polyline(by_id(&doc, "cue-path-before").unwrap());
    let ghost = by_id(&doc, "ghost-ball").unwrap();
    let (gx, gy): (f64, f64) = (
        ghost.attribute("cx").unwrap().parse().unwrap(),
        ghost.attribute("cy").unwrap().parse().unwrap(),
    );
    let end = before[before.len() - 1];
    assert!((end.0 - gx).abs() < 0.2 && (end.1 - gy).abs() < 0.2);
    // The caption repeats the guidance.
    let caption: String = by_id(&doc, "caption")
        .unwrap()
        .descendants()
        .filter_map(|n| n.text())
        .collect();
    assert!(caption.contains("than the ghost-ball aim"), "{caption}");
}

#[test]
fn svg_of_a_miss_has_no_ghost_ball() {
    let path = temp("miss.svg");
    let output = run(&[
        "--cue",
        "1.0,0.6",
        "--ball",
        "2.0,0.6",
        "--aim",
        "90",
        "--svg",
        path.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(stdout(&output).contains("drawing: "));
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();
    let doc = roxmltree::Document::parse(&text).expect("well-formed XML");
    assert!(by_id(&doc, "ghost-ball").is_none());
    assert!(by_id(&doc, "cue-path-before").is_some());
    assert!(by_id(&doc, "object-path").is_none());
}

/// Expect failure with `code` and exactly one stderr line, `error: ...` containing
/// `needle`, and nothing on stdout.
fn fails(args: &[&str], code: i32, needle: &str) {
    let output = run(args);
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(code), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(err.starts_with("error: "), "{args:?}: {err}");
    assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    assert!(output.stdout.is_empty(), "{args:?}");
}

fn write_temp(name: &str, text: &str) -> PathBuf {
    let path = temp(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// `--tolerance` (or `tolerance` in the file) reaches auto: the tier it reports is the
/// cheapest within it, and a looser one is never dearer. Never `Ideal` here, however
/// loose: the contact has friction (μ = 0.05), and `Auto` picks `Ideal` only where no
/// friction impulse acts and e* = 1 (issue 16, item 5).
#[test]
fn auto_tolerance_reaches_the_contact() {
    let scene_file = scene("cut_to_corner.toml");
    let aim = ["--scene", &scene_file, "--aim", "4.381"];
    let tiers = ["ideal", "kim", "kim-grip", "seed-exact", "exact"];
    let rank = |v: &Value| {
        let used = v["contact"]["model_used"].as_str().unwrap();
        tiers.iter().position(|&t| t == used).unwrap()
    };
    let default = json(&aim);
    assert_eq!(default["contact"]["model"], "auto");
    let mut last = usize::MAX;
    for tolerance in ["1e-5", "1e-3", "0.01", "0.1", "1"] {
        let v = json(&[&aim[..], &["--tolerance", tolerance]].concat());
        let t: f64 = tolerance.parse().unwrap();
        let estimate = number(&v, "/contact/error_estimate");
        assert!(
            estimate <= t || v["contact"]["model_used"] == "exact",
            "{tolerance}: {estimate}"
        );
        assert!(rank(&v) <= last, "{tolerance}");
        last = rank(&v);
        if tolerance == "1e-3" {
            assert_eq!(v["contact"], default["contact"]);
        }
    }
    assert_eq!(last, 2, "tolerance 1: kim-grip");
    // From the file; the flag overrides it.
    let text = std::fs::read_to_string(&scene_file).unwrap();
    let file = write_temp("tolerance.toml", &format!("tolerance = 1.0\n{text}"));
    let file = file.to_str().unwrap();
    let v = json(&["--scene", file, "--aim", "4.381"]);
    assert_eq!(v["contact"]["model_used"], "kim-grip");
    let v = json(&["--scene", file, "--aim", "4.381", "--tolerance", "1e-3"]);
    assert_eq!(v["contact"], default["contact"]);
    // Checked by the core, solving or playing; only for auto.
    for bad in ["0", "-1", "2", "NaN"] {
        fails(&[&aim[..], &["--tolerance", bad]].concat(), 1, "tolerance");
        fails(
            &["--scene", &scene_file, "--tolerance", bad],
            1,
            "tolerance",
        );
    }
    fails(
        &[&aim[..], &["--model", "exact", "--tolerance", "0.1"]].concat(),
        2,
        "tolerance is for model auto, not exact",
    );
}

#[test]
fn bad_scene_files_are_usage_errors() {
    let cases = [
        (
            "unknown.toml",
            "cue = [1, 0.5]\npower = 3\n",
            "line 2: unknown field `power`",
        ),
        (
            "unknown.json",
            "{\"cue\": [1, 0.5], \"power\": 3}",
            "unknown field `power`",
        ),
        ("syntax.toml", "cue = [1, 0.5\n", "line "),
        ("syntax.json", "{\"cue\": [1, 0.5]", "EOF"),
        ("number.toml", "cue = [1, \"x\"]\n", "invalid type"),
        ("number.json", "{\"speed\": \"fast\"}", "invalid type"),
        ("pair.json", "{\"cue\": [1]}", "invalid length"),
        (
            "table.toml",
            "table = { length = 2, width = 1, pockets = 6 }\n",
            "unknown field `pockets`",
        ),
        ("index.toml", "object = -1\n", "invalid value"),
    ];
    for (name, text, needle) in cases {
        let path = write_temp(name, text);
        fails(&["--scene", path.to_str().unwrap()], 2, needle);
        std::fs::remove_file(&path).ok();
    }
    fails(
        &["--scene", "/nonexistent/scene.toml"],
        2,
        "scene file /nonexistent/scene.toml",
    );
    let path = write_temp("scene.yaml", "cue: [1, 0.5]\n");
    fails(&["--scene", path.to_str().unwrap()], 2, ".toml or .json");
    std::fs::remove_file(&path).ok();
    let path = write_temp(
        "table.json",
        "{\"table\": \"billiards\", \"cue\": [1, 0.5]}",
    );
    fails(
        &["--scene", path.to_str().unwrap(), "--aim", "0"],
        2,
        "unknown table 'billiards'",
    );
    std::fs::remove_file(&path).ok();
}

#[test]
fn invalid_scenes_name_the_problem() {
    let base = ["--cue", "0.9,0.8", "--ball", "1.5,0.5"];
    let with = |extra: &[&'static str]| [base.as_slice(), extra].concat();
    // Usage errors (exit 2).
    fails(&["--cue", "0.9,x", "--aim", "0"], 2, "'x' is not a number");
    fails(
        &["--cue", "0.9", "--aim", "0"],
        2,
        "two comma-separated numbers",
    );
    fails(&with(&["--speed", "fast"]), 2, "--speed");
    fails(&with(&["--model", "kimgrip"]), 2, "unknown model 'kimgrip'");
    fails(&with(&["--pocket", "middle"]), 2, "unknown pocket 'middle'");
    fails(&with(&[]), 2, "no aim");
    fails(&["--ball", "1.5,0.5", "--pocket", "3"], 2, "no cue ball");
    fails(&with(&["--aim", "3", "--solve"]), 2, "cannot be used with");
    fails(&with(&["--table", "billiards"]), 2, "billiards");
    // Invalid values (exit 1).
    fails(
        &["--cue", "0.9,0.8", "--ball", "0.93,0.81", "--aim", "0"],
        1,
        "ball 1 at (0.93, 0.81) overlaps cue ball",
    );
    fails(
        &["--cue", "2.53,0.8", "--aim", "0"],
        1,
        "cue ball at (2.53, 0.8) is off the table",
    );
    fails(
        &with(&["--ball", "1.0,-0.2", "--aim", "0"]),
        1,
        "ball 2 at (1, -0.2) is off the table",
    );
    let mut crowd = vec!["--cue", "0.1,0.1", "--aim", "0"];
    let positions: Vec<String> = (0..16)
        .map(|i| format!("{:.2},0.5", 0.2 + 0.14 * i as f32))
        .collect();
    for p in &positions {
        crowd.extend(["--ball", p.as_str()]);
    }
    fails(
        &crowd,
        1,
        "17 balls (cue ball included): a scene holds at most 16",
    );
    fails(
        &with(&["--pocket", "6"]),
        1,
        "pocket 6 does not exist: the pool table has pockets 0..=5",
    );
    fails(
        &with(&["--object", "2", "--pocket", "3"]),
        1,
        "object 2 does not exist",
    );
    fails(
        &with(&["--object", "0", "--pocket", "3"]),
        1,
        "object 0 is the cue ball",
    );
    fails(
        &with(&["--table", "carom", "--pocket", "0"]),
        1,
        "no pockets",
    );
    fails(
        &with(&["--pocket", "3", "--mu", "2"]),
        1,
        "mu = 2 is outside [0, 1]",
    );
    fails(&with(&["--pocket", "3", "--mu-cloth", "0"]), 1, "mu_cloth");
    fails(
        &with(&["--pocket", "3", "--restitution", "-0.5"]),
        1,
        "restitution",
    );
    fails(
        &with(&["--pocket", "3", "--tip", "0.4,0.4"]),
        1,
        "tip = (0.4, 0.4) R is outside",
    );
    fails(
        &with(&["--pocket", "3", "--speed", "25"]),
        1,
        "speed = 25 is outside",
    );
    fails(&with(&["--aim", "nan"]), 1, "aim must be a finite number");
    // No aim exists: the pocket is behind the object ball.
    fails(
        &with(&["--pocket", "0"]),
        1,
        "no aim: ball 1 cannot be cut into the bottom-left corner",
    );
    // The SVG cannot be written.
    fails(
        &with(&["--pocket", "3", "--svg", "/nonexistent/dir/shot.svg"]),
        1,
        "svg file",
    );
}

/// Issue 17: the whole table. `"final"` has one entry per ball, cue ball first, `null`
/// for a pocketed one; `"events"` are in time order with the documented shape; the
/// pocketed balls are exactly those with a `pocket` event; every rest position is on the
/// cloth.
#[test]
fn the_whole_table_is_reported_in_final_and_events() {
    let v = json(&[
        "--cue",
        "0.635,0.635",
        "--ball",
        "1.905,0.5",
        "--ball",
        "1.2,1.0",
        "--pocket",
        "3",
    ]);
    let finals = v["final"].as_array().expect("final is an array");
    assert_eq!(finals.len(), 3);
    let events = v["events"].as_array().expect("events is an array");
    let mut last = 0.0;
    for event in events {
        let time = event["time"].as_f64().unwrap();
        assert!(time >= last, "{event}");
        last = time;
        let kind = event["kind"].as_str().unwrap();
        assert!(
            ["ball", "cushion", "pocket", "rest"].contains(&kind),
            "{event}"
        );
        let balls = event["balls"].as_array().unwrap();
        assert_eq!(balls.len(), if kind == "ball" { 2 } else { 1 }, "{event}");
        // `pocket` names the pocket of a drop, and of a cushion that is its jaw: a
        // centre beyond the rails' lines (R = 0.028575 m in from the cushions).
        let outside = {
            let (x, y) = (
                event["position"][0].as_f64().unwrap(),
                event["position"][1].as_f64().unwrap(),
            );
            // A rail's contact is on its line, within rounding.
            let r = 0.028575 - 1e-6;
            x < r || x > 2.54 - r || y < r || y > 1.27 - r
        };
        let jaw = kind == "cushion" && outside;
        assert_eq!(
            event.get("pocket").is_some(),
            kind == "pocket" || jaw,
            "{event}"
        );
    }
    for (i, end) in finals.iter().enumerate() {
        let dropped = events
            .iter()
            .any(|e| e["kind"] == "pocket" && e["balls"][0].as_u64() == Some(i as u64));
        assert_eq!(end.is_null(), dropped, "ball {i}: {end}");
        if let Some(xy) = end.as_array() {
            let (x, y) = (xy[0].as_f64().unwrap(), xy[1].as_f64().unwrap());
            assert!(
                x > 0.0 && x < 2.54 && y > 0.0 && y < 1.27,
                "ball {i} at {x}, {y}"
            );
        }
    }
    // The solved shot pockets ball 1 in the whole table too.
    assert_eq!(v["target"]["pocketed"], true);
    assert!(finals[1].is_null(), "{}", v["final"]);
    assert!(
        v["three_cushion"].is_null(),
        "only on a carom table with three balls"
    );
}

/// A three-cushion point found by scanning aims (3° steps at 5 m/s with running side
/// and follow): two cushions, ball 1, a third cushion, ball 2. The check counts the
/// cushions before the second ball; the same table two degrees off scores nothing.
#[test]
fn a_carom_shot_plays_end_to_end_with_the_three_cushion_check() {
    let shot = |aim: &str| {
        json(&[
            "--table", "carom", "--cue", "0.7,0.4", "--ball", "1.4,0.9", "--ball", "2.2,1.1",
            "--aim", aim, "--speed", "5", "--tip", "0.3,0.2",
        ])
    };
    let v = shot("84");
    assert_eq!(v["three_cushion"]["scored"], true, "{}", v["three_cushion"]);
    assert_eq!(v["three_cushion"]["first"], 1);
    assert_eq!(v["three_cushion"]["second"], 2);
    assert!(v["three_cushion"]["cushions"].as_u64().unwrap() >= 3);
    assert!(v["final"].as_array().unwrap().iter().all(|p| !p.is_null()));
    let v = shot("86");
    assert_eq!(
        v["three_cushion"]["scored"], false,
        "{}",
        v["three_cushion"]
    );
    let output = run(&[
        "--table", "carom", "--cue", "0.7,0.4", "--ball", "1.4,0.9", "--ball", "2.2,1.1", "--aim",
        "84", "--speed", "5", "--tip", "0.3,0.2",
    ]);
    let text = stdout(&output);
    assert!(
        text.contains(
            "three-cushion: scores (the cue ball touches ball 1, then ball 2 after 3 cushions)"
        ),
        "{text}"
    );
}

/// Issue 17: the inverse aim's verdict on the whole table. The solved aim pockets ball 1
/// on an open table; with ball 2 on its line to the pocket, the guidance's first path
/// still reaches the pocket, but the whole table names ball 2 in the way.
#[test]
fn the_whole_table_names_a_ball_in_the_way_of_the_solved_shot() {
    let open = json(&[
        "--cue",
        "0.635,0.635",
        "--ball",
        "1.905,0.5",
        "--pocket",
        "3",
    ]);
    assert_eq!(
        open["target_whole_table"]["pocketed"], true,
        "{}",
        open["target_whole_table"]
    );
    assert!(open["target_whole_table"]["in_the_way"].is_null());
    let blocked = json(&[
        "--cue",
        "0.635,0.635",
        "--ball",
        "1.905,0.5",
        "--ball",
        "2.2,0.85",
        "--pocket",
        "3",
    ]);
    assert_eq!(blocked["target"]["pocketed"], true, "the first path alone");
    let whole = &blocked["target_whole_table"];
    assert_eq!(whole["pocketed"], false, "{whole}");
    assert_eq!(whole["first"], "ball", "{whole}");
    assert_eq!(whole["in_the_way"], 2, "{whole}");
}
