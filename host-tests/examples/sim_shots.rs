//! Our side of the pooltool comparison (`tools/pooltool-compare/`, issue 17): plays
//! each shot of a JSON file through the table simulation and prints the results as one
//! JSON array.
//!
//! Input: an array of `{"table": "pool" | "carom", "balls": [[x, y], ...], "velocity":
//! [vx, vy], "spin": [wx, wy, wz]}` (table frame, metres, m/s, rad/s; ball 0 is the cue
//! ball, launched with that velocity and spin). Output, per shot: `{"final": [[x, y] |
//! null, ...], "events": [{"time", "kind", "balls"}], "error": null | "...", "seconds":
//! host time per simulation}` (the mean of repeated runs, at least 20 ms of them).
//!
//! `cargo run --release -p cuesight-host --example sim_shots -- SHOTS.json [MODEL] >
//! ours.json`, MODEL a collision model's name (`kim-grip` by default; `ideal`, the
//! frictionless one, to compare with pooltool's frictionless ball–ball collisions).

use std::io::Write;
use std::time::Instant;

use cuesight::shot::ShotSetup;
use cuesight::sim::{simulate, EventKind, Launch, Setup};
use cuesight::table::{BallSet, Scene, Table};
use cuesight::{Model, Vec3};
use serde::Deserialize;
use serde_json::{json, Value};

/// Largest shots file read (bytes).
const MAX_INPUT: u64 = 16 << 20;

#[derive(Deserialize)]
struct Shot {
    table: String,
    balls: Vec<[f32; 2]>,
    velocity: [f32; 2],
    spin: [f32; 3],
}

fn play(shot: &Shot, model: Model) -> Result<Value, String> {
    let (table, balls, setup) = match shot.table.as_str() {
        "pool" => (Table::pool(), BallSet::POOL, Setup::POOL),
        "carom" => (
            Table::carom(),
            BallSet::CAROM,
            Setup::carom().map_err(|e| e.to_string())?,
        ),
        other => return Err(format!("unknown table {other:?}")),
    };
    let setup = Setup {
        shot: ShotSetup {
            model,
            ..setup.shot
        },
        ..setup
    };
    let first = shot.balls.first().ok_or("no balls")?;
    let mut scene = Scene::new(table, balls.radius, *first).map_err(|e| e.to_string())?;
    for ball in &shot.balls[1..] {
        scene.add_ball(*ball).map_err(|e| e.to_string())?;
    }
    let launch = [Launch {
        ball: 0,
        velocity: Vec3::new(shot.velocity[0], shot.velocity[1], 0.0),
        spin: Vec3::new(shot.spin[0], shot.spin[1], shot.spin[2]),
    }];
    let mut events = Vec::new();
    let finish = simulate(&scene, &launch, &setup, |event, _| {
        let kind = match event.kind {
            EventKind::Ball => "ball",
            EventKind::Cushion => "cushion",
            EventKind::Pocket(_) => "pocket",
            EventKind::Rest => "rest",
        };
        let balls: Vec<usize> = std::iter::once(event.ball).chain(event.other).collect();
        events.push(json!({"time": event.time, "kind": kind, "balls": balls}));
    })
    .map_err(|e| e.to_string())?;
    // Host time: repeat until 20 ms have passed.
    let start = Instant::now();
    let mut runs = 0u32;
    while runs == 0 || start.elapsed().as_secs_f64() < 0.02 {
        let _ = simulate(&scene, &launch, &setup, |_, _| {});
        runs += 1;
    }
    let seconds = start.elapsed().as_secs_f64() / f64::from(runs);
    let finals: Vec<Value> = finish
        .positions()
        .iter()
        .map(|p| p.map_or(Value::Null, |p| json!([p.x, p.y])))
        .collect();
    Ok(json!({"final": finals, "events": events, "error": Value::Null, "seconds": seconds}))
}

fn main() -> std::process::ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: sim_shots SHOTS.json");
        return std::process::ExitCode::from(2);
    };
    let text = match std::fs::File::open(&path).and_then(|file| {
        use std::io::Read;
        let mut text = String::new();
        file.take(MAX_INPUT + 1).read_to_string(&mut text)?;
        Ok(text)
    }) {
        Ok(text) if text.len() as u64 <= MAX_INPUT => text,
        Ok(_) => {
            eprintln!("error: {path} is over {MAX_INPUT} bytes");
            return std::process::ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("error: {path}: {e}");
            return std::process::ExitCode::from(2);
        }
    };
    let model = match std::env::args().nth(2) {
        None => Model::KimGrip,
        Some(name) => match Model::from_name(&name) {
            Some(model) => model,
            None => {
                eprintln!("error: unknown model {name:?}");
                return std::process::ExitCode::from(2);
            }
        },
    };
    let shots: Vec<Shot> = match serde_json::from_str(&text) {
        Ok(shots) => shots,
        Err(e) => {
            eprintln!("error: {path}: {e}");
            return std::process::ExitCode::from(2);
        }
    };
    let results: Vec<Value> = shots
        .iter()
        .map(|shot| {
            play(shot, model)
                .unwrap_or_else(|e| json!({"final": [], "events": [], "error": e, "seconds": 0.0}))
        })
        .collect();
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{}", Value::Array(results)).and_then(|()| out.flush()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: writing the results: {e}");
            std::process::ExitCode::from(1)
        }
    }
}
