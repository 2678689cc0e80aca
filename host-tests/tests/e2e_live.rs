//! The live cue in QEMU (issue 15): the shipped IMU traces (`firmware/traces/`) played
//! through the `live` image's emulated LSM6DSOX, its driver and the streaming estimator,
//! with a planned shot (two object balls) set first; every stroke report checked
//! against the trace's truth file, and its guidance against the host's computation of
//! the same plan at the same cue speed.
//!
//! `#[ignore]`d in plain `cargo test`: it needs the live image. `cargo xtask test` builds
//! it and runs this with `CUESIGHT_LIVE_ELF` set; by hand:
//! `cd firmware && cargo build --release --features live --target-dir target/live`, then
//! `CUESIGHT_LIVE_ELF=firmware/target/live/thumbv7em-none-eabihf/release/cuesight-firmware
//! cargo test -p cuesight-host --test e2e_live -- --ignored --nocapture`.

use std::path::{Path, PathBuf};
use std::time::Duration;

use cuesight_device::{Identity, Session};
use cuesight_host::compare::thousands;
use cuesight_host::firmware::find_defmt_print;
use cuesight_host::live::{csv_samples, play, trace_binary};
use cuesight_link::live::{FollowThrough, LiveReport, LiveStroke};
use cuesight_link::{Request, ShotRequest};
use cuesight_sensors::StreamFault;
use serde_json::Value;

/// Impact located within this many samples of the truth (issue 15).
const IMPACT_SAMPLES: u64 = 2;
/// Impact detected → guidance composed, with two object balls (issue 15): 1 ms at 64 MHz.
const LATENCY_BUDGET: u32 = 64_000;
/// Mean per-sample work (the sampling interrupt and the deferred work it pends, the
/// emulation excluded; issue 15).
const WORK_MEAN_BUDGET: f64 = 250.0;
/// The most of one sampling interrupt (the estimator's step; its deferred work runs
/// one priority below, `firmware/src/live/sampler.rs`; issue 15).
const WORK_MAX_BUDGET: u32 = 400;
/// Follow-through against the model's motion: length within 2.5 mm, time within 10 ms,
/// the estimator's own limits (`sensors/tests/follow_through.rs`, where they are
/// derived: the contact's own travel, up to 1.8 mm at 6 m/s, is not measured, and the
/// stop is interpolated between 25 ms blocks).
const FOLLOW_LENGTH_M: f64 = 2.5e-3;
const FOLLOW_TIME_S: f64 = 10e-3;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn live_elf() -> PathBuf {
    std::env::var_os("CUESIGHT_LIVE_ELF").map_or_else(
        || repo().join("firmware/target/live/thumbv7em-none-eabihf/release/cuesight-firmware"),
        PathBuf::from,
    )
}

/// The follow-through report of stroke number `stroke` (1-based, as reported).
fn follow_through(reports: &[LiveReport], stroke: u32) -> Option<&FollowThrough> {
    reports.iter().find_map(|r| match r {
        LiveReport::FollowThrough(f) if f.stroke == stroke => Some(f),
        _ => None,
    })
}

/// The shipped plan (`firmware/traces/plan-cut-to-corner.json`: two object balls, as
/// the latency budget is for), and a host session with it set.
fn planned_host() -> (ShotRequest, Session) {
    let plan_text = std::fs::read(repo().join("firmware/traces/plan-cut-to-corner.json")).unwrap();
    let plan: ShotRequest = serde_json::from_slice(&plan_text).unwrap();
    assert_eq!(
        plan.balls.len(),
        2,
        "the latency budget is for two object balls"
    );
    let mut host = Session::new(Identity {
        firmware: "host",
        board: "host",
    });
    let mut answer = [0u8; cuesight_link::frame::MAX_FRAME];
    let set =
        cuesight_host::firmware::request_frame(0, &Request::Plan(Some(plan.clone()))).unwrap();
    let mut reader = cuesight_link::frame::FrameReader::new();
    for &byte in &set {
        if let Some(frame) = reader.push(byte) {
            assert!(host.serve(frame, &mut answer).outcome.is_ok());
        }
    }
    (plan, host)
}

/// The stroke reports among `reports`.
fn stroke_reports(reports: &[LiveReport]) -> Vec<&LiveStroke> {
    reports
        .iter()
        .filter_map(|r| match r {
            LiveReport::Stroke(s) => Some(s),
            _ => None,
        })
        .collect()
}

/// One trace: its file, the speed tolerance (relative; 1 % at 6.66 kHz, 1.5 % at
/// 3.33 kHz as `sensors/tests/trace.rs` holds the estimator to).
const TRACES: [(&str, f64); 3] = [
    ("three-strokes-6667", 0.01),
    ("five-strokes-3333", 0.015),
    ("faults-6667", 0.01),
];

#[test]
#[ignore = "needs the live firmware image (cargo xtask test)"]
fn the_live_cue_reports_every_stroke_of_the_shipped_traces_with_the_hosts_guidance() {
    let elf = live_elf();
    let defmt_print = find_defmt_print();
    let (plan, host) = planned_host();
    let (mut worst_latency, mut worst_speed, mut worst_impact, mut strokes) = (0, 0.0f64, 0, 0);
    let (mut worst_follow_m, mut worst_follow_s, mut follows) = (0.0f64, 0.0f64, 0);
    for (name, speed_tolerance) in TRACES {
        let dir = repo().join("firmware/traces");
        let csv = std::fs::read(dir.join(format!("{name}.csv"))).unwrap();
        let truth: Value =
            serde_json::from_slice(&std::fs::read(dir.join(format!("{name}.truth.json"))).unwrap())
                .unwrap();
        let rate = truth["odr_hz"].as_f64().unwrap().round() as u16;
        let samples = csv_samples(&csv).unwrap();
        let played = play(
            &elf,
            defmt_print.as_deref(),
            &trace_binary(&samples, rate),
            Some(&plan),
            Duration::from_secs(300),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(
            played.ended.status.is_some_and(|s| s.success()),
            "{name}: the firmware did not exit cleanly\n{}",
            played.ended.log.join("\n")
        );
        let reported = stroke_reports(&played.reports);
        let faults: Vec<_> = played
            .reports
            .iter()
            .filter_map(|r| match r {
                LiveReport::Fault(f) => Some(*f),
                _ => None,
            })
            .collect();
        let mut expected_strokes = 0;
        for stroke in truth["strokes"].as_array().unwrap() {
            let impact = stroke["impact_sample"].as_u64().unwrap();
            let speed = stroke["cue_speed_mps"].as_f64().unwrap();
            if stroke.get("saturated_from_sample").is_some() {
                assert!(
                    faults.iter().any(|f| matches!(f, StreamFault::Saturated { impact: i, .. } if i.abs_diff(impact) <= IMPACT_SAMPLES)),
                    "{name}: the saturated stroke at {impact} is not reported saturated: {faults:?}"
                );
                assert!(
                    reported
                        .iter()
                        .all(|s| s.impact_sample.abs_diff(impact) > IMPACT_SAMPLES),
                    "{name}: a saturated stroke reported a speed"
                );
                continue;
            }
            expected_strokes += 1;
            let Some(found) = reported
                .iter()
                .find(|s| s.impact_sample.abs_diff(impact) <= IMPACT_SAMPLES)
            else {
                panic!("{name}: stroke at sample {impact} missed; reported {reported:?}");
            };
            let error = (f64::from(found.cue_speed) - speed).abs() / speed;
            assert!(
                error <= speed_tolerance,
                "{name}: stroke at {impact}: {} m/s against {speed} ({:.3} %)",
                found.cue_speed,
                error * 100.0
            );
            let follow = follow_through(&played.reports, found.stroke);
            if let Some(second) = stroke.get("second_impact_sample").and_then(Value::as_u64) {
                assert!(
                    faults.iter().any(|f| matches!(f, StreamFault::DoubleHit { second: s, .. } if s.abs_diff(second) <= 8)),
                    "{name}: the double hit at {second} is not reported: {faults:?}"
                );
                // A second contact ends the measurement: no follow-through.
                assert_eq!(follow, None, "{name}: stroke at {impact}: double hit");
            } else {
                let Some(follow) = follow else {
                    panic!("{name}: stroke at {impact}: no follow-through");
                };
                let length = stroke["follow_through_m"].as_f64().unwrap();
                let time = stroke["follow_through_s"].as_f64().unwrap();
                let (dl, dt) = (
                    (f64::from(follow.length) - length).abs(),
                    (f64::from(follow.time) - time).abs(),
                );
                assert!(
                    dl <= FOLLOW_LENGTH_M && dt <= FOLLOW_TIME_S,
                    "{name}: stroke at {impact}: follow-through {} m in {} s against {length} m in {time} s",
                    follow.length,
                    follow.time
                );
                worst_follow_m = worst_follow_m.max(dl);
                worst_follow_s = worst_follow_s.max(dt);
                follows += 1;
            }
            // The same guidance as the host's, for the same plan at the same speed.
            let hosts = host.plan_guidance(found.cue_speed);
            assert_eq!(
                found.guidance, hosts,
                "{name}: stroke at {impact}: guidance differs from the host's"
            );
            // A plan is set: every stroke is guided (a slow one may be refused, e.g.
            // the ball cannot reach the pocket: the host refuses it alike).
            assert!(
                found.guidance.is_some(),
                "{name}: stroke at {impact}: no guidance"
            );
            worst_latency = worst_latency.max(found.latency_instructions);
            worst_speed = worst_speed.max(error);
            worst_impact = worst_impact.max(found.impact_sample.abs_diff(impact));
        }
        assert_eq!(
            reported.len(),
            expected_strokes,
            "{name}: phantom strokes: {reported:?}"
        );
        assert!(
            played.reports.iter().all(|r| match r {
                LiveReport::FollowThrough(f) => reported.iter().any(|s| s.stroke == f.stroke),
                _ => true,
            }),
            "{name}: a follow-through of no reported stroke"
        );
        strokes += expected_strokes;
        let Some(LiveReport::TraceEnd(end)) = played.reports.last() else {
            panic!("{name}: no trace end");
        };
        assert_eq!(end.samples, samples.len() as u64, "{name}: samples lost");
        assert!(!end.truncated);
        assert!(
            end.work_mean_instructions() <= WORK_MEAN_BUDGET,
            "{name}: {} instructions per sample (mean)",
            end.work_mean_instructions()
        );
        assert!(
            end.work_max_instructions <= WORK_MAX_BUDGET,
            "{name}: {} instructions in one sampling interrupt",
            end.work_max_instructions
        );
        let peak = played.ended.log.iter().find_map(|line| {
            line.split("peak stack ")
                .nth(1)?
                .split(' ')
                .next()?
                .parse::<u32>()
                .ok()
        });
        println!("{name}: peak stack {peak:?} bytes");
        println!(
            "{name}: {} strokes, {} faults, {} samples; per sample {:.0} instructions mean, {} max (sampling interrupt), {} resolving a sample's deferred work (max; 40-instruction resolution)",
            reported.len(),
            faults.len(),
            end.samples,
            end.work_mean_instructions(),
            end.work_max_instructions,
            end.resolve_max_instructions
        );
        // README's "The live cue": each trace's row.
        let key = |what: &str| format!("live-{name}-{what}");
        cuesight_figures::record!(&key("strokes"), "{}", reported.len());
        cuesight_figures::record!(&key("faults"), "{}", faults.len());
        cuesight_figures::record!(&key("samples"), "{}", thousands(end.samples as usize));
        cuesight_figures::record!(&key("work-mean"), "{:.0}", end.work_mean_instructions());
        cuesight_figures::record!(&key("work-max"), "{}", end.work_max_instructions);
        cuesight_figures::record!(&key("resolve-max"), "{}", end.resolve_max_instructions);
    }
    cuesight_figures::record!("live-strokes", "{strokes}");
    cuesight_figures::record!("live-impact-within", "{worst_impact}");
    cuesight_figures::record!("live-speed-within", "{:.3}", worst_speed * 100.0);
    cuesight_figures::record!("live-latency-max", "{}", thousands(worst_latency as usize));
    cuesight_figures::record!("live-follow-throughs", "{follows}");
    cuesight_figures::record!("live-follow-length", "{:.2}", worst_follow_m * 1e3);
    cuesight_figures::record!("live-follow-time", "{:.1}", worst_follow_s * 1e3);
    println!(
        "{strokes} strokes: impact within {worst_impact} samples, cue speed within {:.3} %, guidance equal to the host's, latency at most {worst_latency} instructions; {follows} follow-throughs within {:.2} mm and {:.1} ms",
        worst_speed * 100.0,
        worst_follow_m * 1e3,
        worst_follow_s * 1e3
    );
    assert!(
        worst_latency <= LATENCY_BUDGET,
        "impact → guidance took {worst_latency} instructions"
    );
}

/// Issue 15's acceptance streams: 100 synthetic strokes (50 at 3 mg RMS noise, 50 at
/// 8 mg; bias ±50 mg, tilt 0.5–2° with the gyro, address 0.25–3 s, pause 0–1.5 s,
/// 0.5–3 s still between strokes, 0.5–6 m/s; `cuesight_host::live_trace`'s defaults)
/// streamed through the live image at 6.66 kHz with the shipped plan set: no missed and
/// no phantom stroke, every impact within 2 samples, every cue speed within 1 %, every
/// guidance the host's for the same plan at the same speed, within the latency budget.
#[test]
#[ignore = "needs the live firmware image (cargo xtask test); about a minute"]
fn the_live_cue_detects_100_synthetic_strokes() {
    use cuesight_host::live_trace::{generate, TraceConfig};
    let elf = live_elf();
    let defmt_print = find_defmt_print();
    let (mut worst_speed, mut worst_impact, mut total, mut seconds) = (0.0f64, 0u64, 0, 0.0);
    let (mut worst_follow_m, mut worst_follow_s) = (0.0f64, 0.0f64);
    let (mut work, mut samples, mut work_max, mut resolve_max) = (0, 0, 0, 0);
    let (plan, host) = planned_host();
    let mut worst_latency = 0;
    // The two halves in two QEMUs at once (the machine's two cores).
    let runs = std::thread::scope(|scope| {
        let halves = [(15, 3.0), (16, 8.0)].map(|(seed, noise_mg)| {
            let (elf, defmt_print, plan) = (&elf, defmt_print.as_deref(), &plan);
            scope.spawn(move || {
                let trace = generate(&TraceConfig {
                    seed,
                    strokes: 50,
                    noise_mg,
                    ..TraceConfig::default()
                });
                let played = play(
                    elf,
                    defmt_print,
                    &trace_binary(&trace.samples, 6667),
                    Some(plan),
                    Duration::from_secs(900),
                )
                .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
                (seed, trace, played)
            })
        });
        halves.map(|half| half.join().expect("a half of the run panicked"))
    });
    for (seed, trace, played) in runs {
        seconds += trace.samples.len() as f64 / 6667.0;
        let Some(end) = played.reports.iter().find_map(|r| match r {
            LiveReport::TraceEnd(end) => Some(*end),
            _ => None,
        }) else {
            panic!("seed {seed}: no trace end");
        };
        work += end.work_instructions;
        samples += end.samples;
        work_max = work_max.max(end.work_max_instructions);
        resolve_max = resolve_max.max(end.resolve_max_instructions);
        let reported = stroke_reports(&played.reports);
        let faults: Vec<_> = played
            .reports
            .iter()
            .filter(|r| matches!(r, LiveReport::Fault(_) | LiveReport::Sensor(_)))
            .collect();
        assert_eq!(
            reported.len(),
            trace.strokes.len(),
            "seed {seed}: {faults:?}"
        );
        for (truth, found) in trace.strokes.iter().zip(&reported) {
            let impact = found.impact_sample.abs_diff(truth.impact_sample as u64);
            let error =
                (f64::from(found.cue_speed) - truth.cue_speed_mps).abs() / truth.cue_speed_mps;
            assert!(
                impact <= IMPACT_SAMPLES && error <= 0.01,
                "seed {seed}, stroke {}: impact {} against {}, {} m/s against {}",
                truth.stroke,
                found.impact_sample,
                truth.impact_sample,
                found.cue_speed,
                truth.cue_speed_mps
            );
            // The same guidance as the host's, for the same plan at the same speed.
            assert_eq!(
                found.guidance,
                host.plan_guidance(found.cue_speed),
                "seed {seed}, stroke {}: guidance differs from the host's",
                truth.stroke
            );
            assert!(
                found.guidance.is_some(),
                "seed {seed}, stroke {}: no guidance",
                truth.stroke
            );
            worst_latency = worst_latency.max(found.latency_instructions);
            worst_speed = worst_speed.max(error);
            worst_impact = worst_impact.max(impact);
            let Some(follow) = follow_through(&played.reports, found.stroke) else {
                panic!("seed {seed}, stroke {}: no follow-through", truth.stroke);
            };
            let (dl, dt) = (
                (f64::from(follow.length) - truth.follow_through_m).abs(),
                (f64::from(follow.time) - truth.follow_through_s).abs(),
            );
            assert!(
                dl <= FOLLOW_LENGTH_M && dt <= FOLLOW_TIME_S,
                "seed {seed}, stroke {}: follow-through {} m in {} s against {} m in {} s",
                truth.stroke,
                follow.length,
                follow.time,
                truth.follow_through_m,
                truth.follow_through_s
            );
            worst_follow_m = worst_follow_m.max(dl);
            worst_follow_s = worst_follow_s.max(dt);
        }
        assert!(faults.is_empty(), "seed {seed}: {faults:?}");
        total += reported.len();
    }
    let work_mean = work as f64 / samples as f64;
    println!(
        "{total} strokes in {seconds:.0} s of IMU trace: none missed, none phantom; impact within {worst_impact} samples, cue speed within {:.3} %, guidance equal to the host's, impact to guidance at most {worst_latency} instructions; follow-through within {:.2} mm and {:.1} ms; per sample {work_mean:.0} instructions mean, {work_max} max (sampling interrupt), {resolve_max} resolving a sample's deferred work (max)",
        worst_speed * 100.0,
        worst_follow_m * 1e3,
        worst_follow_s * 1e3
    );
    assert!(
        work_mean <= WORK_MEAN_BUDGET,
        "{work_mean} instructions per sample (mean)"
    );
    assert!(
        work_max <= WORK_MAX_BUDGET,
        "{work_max} instructions in one sampling interrupt"
    );
    assert!(
        worst_latency <= LATENCY_BUDGET,
        "impact to guidance {worst_latency} instructions"
    );
    // README's "The live cue": the acceptance stream's row.
    cuesight_figures::record!("live-100-strokes", "{total}");
    cuesight_figures::record!("live-100-seconds", "{seconds:.0}");
    cuesight_figures::record!("live-100-impact-within", "{worst_impact}");
    cuesight_figures::record!("live-100-speed-within", "{:.3}", worst_speed * 100.0);
    cuesight_figures::record!(
        "live-100-latency-max",
        "{}",
        thousands(worst_latency as usize)
    );
    cuesight_figures::record!("live-100-work-mean", "{work_mean:.0}");
    cuesight_figures::record!("live-100-work-max", "{work_max}");
    cuesight_figures::record!("live-100-resolve-max", "{resolve_max}");
}

/// Issue 15's bad inputs, each a defined report with sampling going on: a stalled
/// sensor (300 samples without data-ready from sample 2,000, in the first stroke's
/// address), a failed bus (100 samples from 12,000, between strokes), a trace that ends
/// mid-stroke (the first 21,999 samples of `three-strokes-6667.csv`: stroke 1's contact
/// is at 22,603), no plan set (every stroke reported without guidance); the double hit
/// and the saturated stroke are `faults-6667.csv`'s, checked above.
#[test]
#[ignore = "needs the live firmware image (cargo xtask test)"]
fn the_live_cue_reports_bad_inputs_and_samples_on() {
    use cuesight_host::live::{trace_binary_with_faults, FaultWindow};
    use cuesight_link::live::SensorFault;
    let csv = std::fs::read(repo().join("firmware/traces/three-strokes-6667.csv")).unwrap();
    let samples = &csv_samples(&csv).unwrap()[..21_999];
    let windows = [
        FaultWindow {
            from: 2_000,
            count: 300,
            bus_failing: false,
            stalled: true,
        },
        FaultWindow {
            from: 12_000,
            count: 100,
            bus_failing: true,
            stalled: false,
        },
    ];
    let played = play(
        &live_elf(),
        find_defmt_print().as_deref(),
        &trace_binary_with_faults(samples, 6667, &windows),
        None,
        Duration::from_secs(300),
    )
    .unwrap();
    let reports = &played.reports;
    println!("{reports:#?}");
    assert!(matches!(
        reports[0],
        LiveReport::Sensor(SensorFault::Stalled { sample: 2_000 })
    ));
    let LiveReport::Stroke(stroke) = &reports[1] else {
        panic!("no stroke after the stall: {reports:?}");
    };
    // The stroke at 8,030 is found where the trace has it, the 300 lost samples counted.
    assert_eq!(stroke.impact_sample, 8_030);
    assert_eq!(stroke.guidance, None, "no plan: no guidance");
    // Its follow-through (the cue stops about 10,000) before the bus fails.
    assert!(matches!(
        reports[2],
        LiveReport::FollowThrough(FollowThrough { stroke: 1, .. })
    ));
    assert!(matches!(
        reports[3],
        LiveReport::Sensor(SensorFault::ReadFailed { sample: 12_000 })
    ));
    assert!(matches!(
        reports[4],
        LiveReport::Fault(StreamFault::EndedMidStroke { .. })
    ));
    let LiveReport::TraceEnd(end) = &reports[5] else {
        panic!("no trace end: {reports:?}");
    };
    assert_eq!(
        (end.samples, end.truncated, reports.len()),
        (21_999, false, 6)
    );
    assert!(played.ended.status.is_some_and(|s| s.success()));
}
