//! The low-speed limit of the impulsive approximation, measured: the time-domain solver
//! (`cuesight_host::timed`: Hertz contact with hysteresis, gravity, table contacts)
//! against the impulsive reference for speeds from 1 mm/s to 2 m/s (log-spaced) and
//! representative spins, cuts and friction coefficients.
//!
//!     cargo run --release -p cuesight-host --example low_speed_sweep
//!
//! prints the tables of `docs/low-speed-limit.md`, records its figures
//! (`cuesight_figures::record!`), writes the full sweep to
//! `target/tmp/low-speed-sweep.csv` and draws `target/docs/low-speed-limit.svg`;
//! `cargo xtask docs` writes both into the page and `docs/low-speed-limit.svg`, and
//! `cargo xtask test` runs it (dev profile: the solver's crate is optimised there too,
//! about 20 s on two cores) so that CI's `cargo xtask docs --check` sees any drift.
use cuesight_figures::record;
use cuesight_host::reference::BallState;
use cuesight_host::timed::{
    limit_speed, log_speeds, Comparison, Geometry, Material, Scenario, SpinKind, TimedConfig,
    TimedParams, GRAVITY, POOL_MASS, POOL_RADIUS,
};
use glam::DVec3;
use std::fmt::Write as _;

mod mechanisms;

const THRESHOLD: f64 = 0.01;
use cuesight_host::timed::{CUTS, MUS, SPINS};

/// Final rolling velocity on the cloth (TP A.4): `v − (2/7) u`, `u` the table-contact
/// slip; unchanged by any friction at the table contact.
fn rolling_velocity(b: &BallState) -> DVec3 {
    let v = DVec3::new(b.velocity.x, b.velocity.y, 0.0);
    let r_omega = DVec3::new(b.spin.y, -b.spin.x, 0.0) * POOL_RADIUS;
    v * (5.0 / 7.0) + r_omega * (2.0 / 7.0)
}

/// The error measures of one comparison (fractions of U).
#[derive(Clone, Copy, Default)]
struct Measures {
    /// `max(|Δv|/U, R|Δω|/U)`, full 3-vectors (the measure).
    full: f64,
    /// The same without the vertical velocities (hop).
    in_plane: f64,
    /// Largest change of a ball's final rolling velocity.
    rolling: f64,
}

fn measures(c: &Comparison, speed: f64) -> Measures {
    let t = [&c.timed.cue_ball, &c.timed.object_ball];
    let r = [&c.reference.cue_ball, &c.reference.object_ball];
    let mut m = Measures {
        full: c.deviation.max(),
        ..Default::default()
    };
    for i in 0..2 {
        let dv = t[i].velocity - r[i].velocity;
        let dw = POOL_RADIUS * (t[i].spin - r[i].spin).length();
        m.in_plane = m.in_plane.max(dv.truncate().length()).max(dw);
        m.rolling = m
            .rolling
            .max(rolling_velocity(t[i]).distance(rolling_velocity(r[i])));
    }
    m.in_plane /= speed;
    m.rolling /= speed;
    m
}

/// Name of the largest single component difference (velocity or R·spin).
fn dominant(c: &Comparison) -> String {
    let t = [&c.timed.cue_ball, &c.timed.object_ball];
    let r = [&c.reference.cue_ball, &c.reference.object_ball];
    let mut best = (0.0, String::new());
    for (i, ball) in ["cue", "object"].iter().enumerate() {
        let dv = (t[i].velocity - r[i].velocity).to_array();
        let dw = ((t[i].spin - r[i].spin) * POOL_RADIUS).to_array();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            if dv[k].abs() > best.0 {
                best = (dv[k].abs(), format!("{ball} v_{axis}"));
            }
            if dw[k].abs() > best.0 {
                best = (dw[k].abs(), format!("{ball} Rω_{axis}"));
            }
        }
    }
    best.1
}

fn run(s: &Scenario, p: &TimedParams, u: f64, cfg: &TimedConfig) -> Comparison {
    s.compare_with(p, u, cfg).expect("valid scenario")
}

fn fmt_limit(l: Option<f64>, top: f64) -> String {
    match l {
        Some(u) if u >= top => format!("> 1 % at {top}"),
        Some(u) => format!("{u:.3}"),
        None => "< 0.001".to_string(),
    }
}

/// Lowest speed at which an error that grows with speed reaches `threshold`
/// (bisection on log U between the sampled speeds that bracket it).
fn crossing_up(speeds: &[f64], threshold: f64, mut error: impl FnMut(f64) -> f64) -> Option<f64> {
    let i = speeds.iter().position(|&u| error(u) > threshold)?;
    if i == 0 {
        return Some(speeds[0]);
    }
    let (mut lo, mut hi) = (speeds[i - 1], speeds[i]);
    while hi / lo > 1.001 {
        let mid = (lo * hi).sqrt();
        if error(mid) > threshold {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Some((lo * hi).sqrt())
}

/// A number in a figure key: `0.001` → `0-001`.
fn key_number(x: f64) -> String {
    x.to_string().replace('.', "-")
}

/// The figures of docs/low-speed-limit.md §4 and of its summary (`cargo xtask test` runs
/// this example; `cargo xtask docs --check` compares them).
fn record_sweep(rows: &[Row], top: f64) {
    let limit = |r: &Row| r.full.filter(|&u| u < top);
    let largest = |f: &dyn Fn(&Row) -> Option<f64>, keep: &dyn Fn(&Row) -> bool| {
        rows.iter()
            .filter(|r| keep(r))
            .filter_map(f)
            .filter(|&u| u < top)
            .fold(0.0f64, f64::max)
    };
    for r in rows {
        let s = &r.scenario;
        let key = format!("low-speed-limit-sweep-{}-{:.0}", s.spin.label(), s.cut_deg);
        if s.mu == 0.05 {
            record!(
                &key,
                "{} | {} | {} | {} | {:.3} %",
                fmt_limit(r.full, top),
                r.at_limit.replace("Rω", "R ω"),
                fmt_limit(r.in_plane, top),
                fmt_limit(r.rolling, top),
                100.0 * r.at_2[0]
            );
            let by_mu: Vec<String> = [0.02, 0.05, 0.1]
                .iter()
                .map(|&mu| {
                    let other = rows
                        .iter()
                        .find(|o| {
                            o.scenario.mu == mu
                                && o.scenario.spin == s.spin
                                && o.scenario.cut_deg == s.cut_deg
                        })
                        .expect("every scenario at every μ");
                    fmt_limit(other.full, top)
                })
                .collect();
            record!(&format!("{key}-by-mu"), "{}", by_mu.join(" | "));
        }
    }
    let by_mu: Vec<String> = [0.02, 0.05, 0.1]
        .iter()
        .map(|&mu| format!("**{:.3}**", largest(&|r| r.full, &|r| r.scenario.mu == mu)))
        .collect();
    record!(
        "low-speed-limit-sweep-largest-by-mu",
        "{}",
        by_mu.join(" | ")
    );
    let all = |_: &Row| true;
    let full = largest(&|r| r.full, &all);
    record!("low-speed-limit-sweep-largest", "{full:.3}");
    record!(
        "low-speed-limit-sweep-largest-up",
        "{:.2}",
        (100.0 * full).ceil() / 100.0
    );
    let to_60 = largest(&|r| r.full, &|r| r.scenario.cut_deg <= 60.0);
    record!("low-speed-limit-sweep-largest-to-60", "{to_60:.3}");
    record!(
        "low-speed-limit-sweep-largest-to-60-up",
        "{:.2}",
        (100.0 * to_60).ceil() / 100.0
    );
    record!(
        "low-speed-limit-sweep-largest-in-plane",
        "{:.3}",
        largest(&|r| r.in_plane, &all)
    );
    let rolling = largest(&|r| r.rolling, &all);
    record!("low-speed-limit-sweep-largest-rolling", "{rolling:.3}");
    record!("low-speed-limit-sweep-largest-rolling-2", "{rolling:.2}");
    let smallest = rows.iter().filter_map(limit).fold(f64::INFINITY, f64::min);
    record!("low-speed-limit-sweep-smallest", "{smallest:.2}");
    record!("low-speed-limit-sweep-largest-2", "{full:.2}");
    let moving_shift = rows
        .iter()
        .filter_map(|r| Some((r.moving? - r.full?).abs()))
        .fold(0.0f64, f64::max);
    record!("low-speed-limit-sweep-moving-shift", "{moving_shift:.3}");
}

struct Row {
    scenario: Scenario,
    full: Option<f64>,
    in_plane: Option<f64>,
    rolling: Option<f64>,
    moving: Option<f64>,
    at_limit: String,
    at_2: [f64; 2],
    curve: Vec<f64>,
}

fn main() {
    let speeds = log_speeds(0.001, 2.0, 10);
    let fixed = TimedConfig::default();
    let moving = TimedConfig {
        geometry: Geometry::Moving,
        ..fixed
    };
    let m = Material::PHENOLIC;
    let mut out = String::new();

    // Model constants and contact duration versus speed.
    let _ = writeln!(
        out,
        "E = {:.1} GPa, ν = {}, E* = {:.3} GPa, R_eff = R/2 = {:.4} mm, k = {:.4e} N/m^1.5, g = {GRAVITY} m/s²\n",
        m.youngs_modulus / 1e9,
        m.poisson_ratio,
        m.effective_modulus() / 1e9,
        0.5 * POOL_RADIUS * 1e3,
        m.stiffness(POOL_RADIUS)
    );
    let _ = writeln!(
        out,
        "| U (m/s) | duration, solver (μs) | Hertz formula (μs) | δ_m (μm) | peak force (N) | e* measured |\n|---|---|---|---|---|---|"
    );
    let frictionless = Scenario {
        mu: 0.0,
        mu_s: 0.0,
        ..Scenario::pool(SpinKind::Stun, 0.0, 0.0)
    };
    for u in [0.001, 0.01, 0.1, 0.5, 1.0, 1.5, 2.0] {
        let c = run(&frictionless, &frictionless.params(), u, &fixed);
        let e = (c.timed.object_ball.velocity.x - c.timed.cue_ball.velocity.x) / u;
        // docs/low-speed-limit.md §1 (by hand: the solver's durations at 0.01, 1 and
        // 2 m/s are also the CI test's).
        let key = format!("low-speed-limit-sweep-duration-{}", key_number(u));
        record!(&format!("{key}-solver"), "{:.1}", c.timed.duration * 1e6);
        record!(
            &key,
            "{:.1} | {:.3} | {:.3} | {:.6}",
            m.duration(POOL_RADIUS, POOL_MASS, 0.95, u) * 1e6,
            c.timed.max_indentation * 1e6,
            c.timed.peak_force,
            e
        );
        let _ = writeln!(
            out,
            "| {u} | {:.1} | {:.1} | {:.3} | {:.3} | {:.6} |",
            c.timed.duration * 1e6,
            m.duration(POOL_RADIUS, POOL_MASS, 0.95, u) * 1e6,
            c.timed.max_indentation * 1e6,
            c.timed.peak_force,
            e
        );
    }

    // The sweep: one scenario per task, on every core (`sweep_scenario`); the results
    // are assembled in the scenarios' order, so the output does not depend on the
    // number of threads.
    let scenarios: Vec<Scenario> = MUS
        .iter()
        .flat_map(|&mu| {
            SPINS
                .iter()
                .flat_map(move |&spin| CUTS.iter().map(move |&cut| Scenario::pool(spin, cut, mu)))
        })
        .collect();
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut swept: Vec<Option<Swept>> = (0..scenarios.len()).map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|w| {
                let (scenarios, speeds) = (&scenarios, &speeds);
                scope.spawn(move || {
                    (w..scenarios.len())
                        .step_by(workers)
                        .map(|i| (i, sweep_scenario(scenarios[i], speeds, &fixed, &moving)))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for handle in handles {
            for (i, result) in handle.join().expect("a sweep thread panicked") {
                swept[i] = Some(result);
            }
        }
    });
    let mut rows = Vec::new();
    let mut csv =
        String::from("spin,cut_deg,mu,speed,full,in_plane,rolling,moving_full,duration_us\n");
    let mut convergence = 0.0f64;
    let mut without_gravity = 0.0f64;
    for result in swept.into_iter().flatten() {
        csv.push_str(&result.csv);
        convergence = convergence.max(result.convergence);
        without_gravity = without_gravity.max(result.without_gravity);
        rows.push(result.row);
    }

    let _ = writeln!(
        out,
        "\nSweep: {} speeds, {:.3}–{} m/s; e* = 0.95, μ_s = 0.3. U_1% = the speed below which the error exceeds 1 %.\n",
        speeds.len(),
        speeds[0],
        speeds.last().unwrap()
    );
    let _ = writeln!(
        out,
        "| scenario | U_1% (m/s) | largest component there | U_1% without v_z | U_1% rolling velocity | U_1% moving normal | error at 2 m/s | moving normal at 2 m/s |\n|---|---|---|---|---|---|---|---|"
    );
    let top = *speeds.last().unwrap();
    for r in &rows {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {:.3} % | {:.3} % |",
            r.scenario.label(),
            fmt_limit(r.full, top),
            r.at_limit,
            fmt_limit(r.in_plane, top),
            fmt_limit(r.rolling, top),
            fmt_limit(r.moving, top),
            100.0 * r.at_2[0],
            100.0 * r.at_2[1]
        );
    }
    let worst = |f: &dyn Fn(&Row) -> Option<f64>, mu: Option<f64>| {
        rows.iter()
            .filter(|r| mu.is_none_or(|m| r.scenario.mu == m))
            .filter_map(f)
            .filter(|&u| u < top)
            .fold(0.0f64, f64::max)
    };
    record_sweep(&rows, top);
    mechanisms::record_mechanisms(&rows, &speeds, &fixed);
    let _ = writeln!(out, "\nOverall (largest U_1% over the scenarios):\n");
    for (name, mu) in [
        ("μ = 0.05", Some(0.05)),
        ("μ = 0.02", Some(0.02)),
        ("μ = 0.1", Some(0.1)),
        ("all", None),
    ] {
        let _ = writeln!(
            out,
            "- {name}: full {:.3} m/s, without v_z {:.3} m/s, rolling velocity {:.3} m/s, moving normal {:.3} m/s",
            worst(&|r: &Row| r.full, mu),
            worst(&|r: &Row| r.in_plane, mu),
            worst(&|r: &Row| r.rolling, mu),
            worst(&|r: &Row| r.moving, mu)
        );
    }
    let _ = writeln!(
        out,
        "- largest error at 2 m/s: fixed normal {:.3} %, moving normal {:.3} %",
        100.0 * rows.iter().map(|r| r.at_2[0]).fold(0.0, f64::max),
        100.0 * rows.iter().map(|r| r.at_2[1]).fold(0.0, f64::max)
    );
    record!(
        "low-speed-limit-sweep-moving-largest-at-2",
        "{:.3}",
        100.0 * rows.iter().map(|r| r.at_2[1]).fold(0.0, f64::max)
    );
    record!("low-speed-limit-sweep-step-halving", "{convergence:.1e}");
    let _ = writeln!(
        out,
        "- step halving ({} → {} steps per contact), largest change over the sweep: {convergence:.2e} U",
        fixed.steps,
        2 * fixed.steps
    );
    let _ = writeln!(
        out,
        "- g = 0 (at 0.001 and 2 m/s), largest difference from the reference: {without_gravity:.2e} U"
    );

    // The line of centres turns during a cut (moving normal), an error that grows with
    // speed: where it reaches 1 % and 0.5 %, gravity off so that it is alone.
    let _ = writeln!(
        out,
        "\nMoving normal, g = 0 (stun, μ = 0.05): speed above which it differs from the reference by more than\n\n| cut | error at 2 m/s | 0.5 % above (m/s) | 1 % above (m/s) |\n|---|---|---|---|"
    );
    let fast = log_speeds(0.5, 32.0, 10);
    for cut in [30.0, 45.0, 60.0, 85.0] {
        let s = Scenario::pool(SpinKind::Stun, cut, 0.05);
        let p = TimedParams {
            gravity: 0.0,
            ..s.params()
        };
        let err = |u: f64| run(&s, &p, u, &moving).deviation.max();
        let show = |l: Option<f64>| l.map_or(String::from("> 32"), |u| format!("{u:.2}"));
        let (half, one) = (
            show(crossing_up(&fast, 0.005, err)),
            show(crossing_up(&fast, 0.01, err)),
        );
        let _ = writeln!(
            out,
            "| {cut}° | {:.3} % | {half} | {one} |",
            100.0 * err(2.0)
        );
        let key = format!("low-speed-limit-sweep-moving-{cut:.0}");
        record!(&format!("{key}-at-2"), "{:.3}", 100.0 * err(2.0));
        let show = |l: Option<f64>| l.map_or(String::from("> 32"), |u| format!("{u:.1}"));
        record!(
            &key,
            "{} m/s | {} m/s",
            show(crossing_up(&fast, 0.005, err)),
            show(crossing_up(&fast, 0.01, err))
        );
    }

    // Sensitivity of the overall limit (μ = 0.05 scenarios) to E and μ_s.
    let _ = writeln!(
        out,
        "\nSensitivity (μ = 0.05, the 16 scenarios; overall U_1%, full measure):\n\n| variant | duration at 1 m/s (μs) | overall U_1% (m/s) |\n|---|---|---|"
    );
    let variants: [(&str, f64, f64, f64); 6] = [
        ("base: E = 11 GPa, μ_s = 0.3", 1.0, 0.3, 0.0),
        ("E / 2", 0.5, 0.3, 0.0),
        ("E × 2", 2.0, 0.3, 0.0),
        ("μ_s = 0.2", 1.0, 0.2, 0.0),
        ("μ_s = 0.4", 1.0, 0.4, 0.0),
        ("cue-ball/table friction 0.2 (both solvers)", 1.0, 0.3, 0.2),
    ];
    let mut limits = Vec::new();
    for (name, e_factor, mu_s, cue_table) in variants {
        let material = Material {
            youngs_modulus: m.youngs_modulus * e_factor,
            ..m
        };
        let mut overall = 0.0f64;
        for &spin in &SPINS {
            for &cut in &CUTS {
                let s = Scenario {
                    mu_s,
                    ..Scenario::pool(spin, cut, 0.05)
                };
                let mut p = TimedParams {
                    material,
                    ..s.params()
                };
                p.contact.cue_table_friction = cue_table;
                let (l, _) = limit_speed(&speeds, THRESHOLD, |u| {
                    run(&s, &p, u, &fixed).deviation.max()
                });
                overall = overall.max(l.unwrap_or(0.0));
            }
        }
        let duration = material.duration(POOL_RADIUS, POOL_MASS, 0.95, 1.0) * 1e6;
        let _ = writeln!(out, "| {name} | {duration:.0} | {overall:.3} |");
        limits.push(overall);
        record!(
            &format!("low-speed-limit-sweep-sensitivity-{}", limits.len()),
            "{duration:.0} | {overall:.3}"
        );
    }
    record!("low-speed-limit-sweep-mu-s-0-2", "{:.3}", limits[3]);
    record!(
        "low-speed-limit-sweep-cue-table-change",
        "{:.3}",
        (limits[5] - limits[0]).abs()
    );
    print!("{out}");

    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let tmp = root.join("target/tmp");
    std::fs::create_dir_all(&tmp).expect("target/tmp");
    std::fs::write(tmp.join("low-speed-sweep.csv"), csv).expect("write csv");
    std::fs::write(tmp.join("low-speed-limit.txt"), &out).expect("write report");
    let drawings = root.join("target/docs");
    std::fs::create_dir_all(&drawings).expect("target/docs");
    std::fs::write(drawings.join("low-speed-limit.svg"), svg(&speeds, &rows)).expect("write svg");
    eprintln!("wrote target/tmp/low-speed-sweep.csv, target/tmp/low-speed-limit.txt, target/docs/low-speed-limit.svg (cargo xtask docs copies it into docs/)");
}

/// Log–log plots of the error against speed for the μ = 0.05 scenarios: one panel per
/// spin (stun, roll, draw, side), one line per cut angle, the 1 % threshold dashed and
/// each line's last crossing of it marked.
fn svg(speeds: &[f64], rows: &[Row]) -> String {
    let (panel_w, panel_h) = (330.0, 220.0);
    let (left, top, gap_x, gap_y, legend_h) = (70.0, 64.0, 90.0, 70.0, 40.0);
    let (w, h) = (
        left + 2.0 * panel_w + gap_x + 20.0,
        top + 2.0 * panel_h + gap_y + legend_h + 40.0,
    );
    let (x0, x1) = (speeds[0].log10(), speeds.last().unwrap().log10());
    let (y0, y1) = (-4.0f64, 0.0f64);
    let colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    let _ = writeln!(
        s,
        "<text x=\"{left}\" y=\"20\" font-size=\"14\">Impulsive model against the time-domain (Hertzian) solver, μ = 0.05: max(|Δv|, R|Δω|) / U</text>"
    );
    for (k, spin) in SPINS.iter().enumerate() {
        let (ox, oy) = (
            left + (k % 2) as f64 * (panel_w + gap_x),
            top + (k / 2) as f64 * (panel_h + gap_y),
        );
        let px = |u: f64| ox + (u.log10() - x0) / (x1 - x0) * panel_w;
        let py = |e: f64| oy + (y1 - e.max(1e-4).log10()) / (y1 - y0) * panel_h;
        let _ = writeln!(s, "<g id=\"panel-{}\">", spin.label());
        let _ = writeln!(
            s,
            "<rect x=\"{ox}\" y=\"{oy}\" width=\"{panel_w}\" height=\"{panel_h}\" fill=\"none\" stroke=\"#999\"/><text x=\"{:.1}\" y=\"{:.1}\" font-size=\"13\" font-weight=\"bold\">{}</text>",
            ox,
            oy - 8.0,
            spin.label()
        );
        for d in -3..=0 {
            let u = 10f64.powi(d);
            let x = px(u);
            let _ = writeln!(s, "<line x1=\"{x:.1}\" y1=\"{oy}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#e4e4e4\"/><text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\" font-size=\"11\">{u}</text>", oy + panel_h, oy + panel_h + 18.0);
        }
        for d in -4..=0 {
            let e = 10f64.powi(d);
            let y = py(e);
            let _ = writeln!(s, "<line x1=\"{ox}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#e4e4e4\"/><text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\" font-size=\"11\">{}%</text>", ox + panel_w, ox - 5.0, y + 4.0, 100.0 * e);
        }
        let y = py(THRESHOLD);
        let _ = writeln!(s, "<line x1=\"{ox}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"black\" stroke-dasharray=\"4 3\"/>", ox + panel_w);
        for r in rows
            .iter()
            .filter(|r| r.scenario.mu == 0.05 && r.scenario.spin == *spin)
        {
            let ci = CUTS.iter().position(|c| *c == r.scenario.cut_deg).unwrap();
            let points: Vec<String> = speeds
                .iter()
                .zip(&r.curve)
                .map(|(&u, &e)| format!("{:.1},{:.1}", px(u), py(e)))
                .collect();
            let _ = writeln!(
                s,
                "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.8\" points=\"{}\"/>",
                colours[ci],
                points.join(" ")
            );
            // The limit speed the sweep found (the table's "full" column).
            if let Some(u) = r.full {
                let _ = writeln!(
                    s,
                    "<circle cx=\"{:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"{}\"/>",
                    px(u),
                    colours[ci]
                );
            }
        }
        let _ = writeln!(s, "</g>");
    }
    let bottom = top + 2.0 * panel_h + gap_y;
    let _ = writeln!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">cue-ball speed U (m/s); dashed: 1 %, dots: the speed above which each line stays under it</text>",
        left + panel_w + 0.5 * gap_x,
        bottom + 34.0
    );
    let ly = bottom + 58.0;
    let _ = writeln!(
        s,
        "<g id=\"legend\"><text x=\"{left}\" y=\"{:.1}\">cut angle:</text>",
        ly + 4.0
    );
    for (ci, cut) in CUTS.iter().enumerate() {
        let lx = left + 80.0 + 110.0 * ci as f64;
        let _ = writeln!(s, "<line x1=\"{lx}\" y1=\"{ly}\" x2=\"{:.1}\" y2=\"{ly}\" stroke=\"{}\" stroke-width=\"2\"/><text x=\"{:.1}\" y=\"{:.1}\">{cut}°</text>", lx + 28.0, colours[ci], lx + 34.0, ly + 4.0);
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, "<text transform=\"translate(16 {:.1}) rotate(-90)\" text-anchor=\"middle\">max(|Δv|, R|Δω|) / U</text>", top + panel_h + 0.5 * gap_y);
    s.push_str("</svg>\n");
    s
}

/// One scenario's sweep: its [`Row`], its lines of the CSV, and its largest step-halving
/// change and gravity effect.
struct Swept {
    row: Row,
    csv: String,
    convergence: f64,
    without_gravity: f64,
}

fn sweep_scenario(s: Scenario, speeds: &[f64], fixed: &TimedConfig, moving: &TimedConfig) -> Swept {
    let (fixed, moving) = (*fixed, *moving);
    let p = s.params();
    let (spin, cut, mu) = (s.spin, s.cut_deg, s.mu);
    let mut csv = String::new();
    let mut convergence = 0.0f64;
    let mut without_gravity = 0.0f64;
    let mut curve = Vec::new();
    for &u in speeds {
        let c = run(&s, &p, u, &fixed);
        let me = measures(&c, u);
        let mv = run(&s, &p, u, &moving).deviation.max();
        let _ = writeln!(
            csv,
            "{},{cut},{mu},{u:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.2}",
            spin.label(),
            me.full,
            me.in_plane,
            me.rolling,
            mv,
            c.timed.duration * 1e6
        );
        curve.push(me.full);
        let fine = run(
            &s,
            &p,
            u,
            &TimedConfig {
                steps: 2 * fixed.steps,
                ..fixed
            },
        );
        let change = cuesight_host::timed::Deviation::between(
            [&c.timed.cue_ball, &c.timed.object_ball],
            [&fine.timed.cue_ball, &fine.timed.object_ball],
            u,
            POOL_RADIUS,
        );
        convergence = convergence.max(change.max());
        if u == speeds[0] || u == *speeds.last().unwrap() {
            let flat = TimedParams { gravity: 0.0, ..p };
            without_gravity = without_gravity.max(run(&s, &flat, u, &fixed).deviation.max());
        }
    }
    let (full, _) = limit_speed(speeds, THRESHOLD, |u| {
        measures(&run(&s, &p, u, &fixed), u).full
    });
    let (in_plane, _) = limit_speed(speeds, THRESHOLD, |u| {
        measures(&run(&s, &p, u, &fixed), u).in_plane
    });
    let (rolling, _) = limit_speed(speeds, THRESHOLD, |u| {
        measures(&run(&s, &p, u, &fixed), u).rolling
    });
    let (mov, _) = limit_speed(speeds, THRESHOLD, |u| {
        run(&s, &p, u, &moving).deviation.max()
    });
    let at_limit = full.map_or(String::from("—"), |u| dominant(&run(&s, &p, u, &fixed)));
    let at_2 = [
        run(&s, &p, 2.0, &fixed).deviation.max(),
        run(&s, &p, 2.0, &moving).deviation.max(),
    ];
    Swept {
        row: Row {
            scenario: s,
            full,
            in_plane,
            rolling,
            moving: mov,
            at_limit,
            at_2,
            curve,
        },
        csv,
        convergence,
        without_gravity,
    }
}
