//! Writes a six-axis IMU trace of a stroke session for the live cue (format:
//! `cuesight_sensors::trace`, `firmware/traces/README.md`) and its truth file:
//!
//!     cargo run --release -p cuesight-host --example live_trace -- --out FILE.csv [options]
//!
//! The truth goes to `FILE.truth.json` (or `--truth`): per stroke the 0-based index of
//! the first contact sample and the cue speed just before contact. The model and its
//! ranges: `cuesight_host::live_trace`.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use cuesight_host::live_trace::{generate, truth_json, write_csv, TraceConfig};

/// A range `LOW,HIGH` (or one value).
fn range(text: &str) -> Result<(f64, f64), String> {
    let parse = |t: &str| {
        t.trim()
            .parse::<f64>()
            .map_err(|_| format!("{t:?} is not a number"))
    };
    match text.split_once(',') {
        Some((lo, hi)) => Ok((parse(lo)?, parse(hi)?)),
        None => parse(text).map(|v| (v, v)),
    }
}

#[derive(Parser, Debug)]
#[command(about = "Write a synthetic six-axis stroke-session trace and its truth file")]
struct Args {
    /// Trace file to write (CSV).
    #[arg(long)]
    out: PathBuf,
    /// Truth file to write (JSON); default: the trace's name with `.truth.json`.
    #[arg(long)]
    truth: Option<PathBuf>,
    /// Seed (ChaCha8).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Strokes in the trace.
    #[arg(long, default_value_t = 3)]
    strokes: usize,
    /// Output data rate (Hz).
    #[arg(long, default_value_t = 6667.0)]
    odr: f64,
    /// Accelerometer noise (mg RMS).
    #[arg(long, default_value_t = 3.0)]
    noise_mg: f64,
    /// Still at address before each backswing (s), LOW,HIGH.
    #[arg(long, value_parser = range, default_value = "0.25,3")]
    address_s: (f64, f64),
    /// Pause at the back of the backswing (s), LOW,HIGH.
    #[arg(long, value_parser = range, default_value = "0,1.5")]
    pause_s: (f64, f64),
    /// Still after each follow-through (s), LOW,HIGH.
    #[arg(long, value_parser = range, default_value = "0.5,3")]
    gap_s: (f64, f64),
    /// Pendulum tilt at the back of the backswing (degrees), LOW,HIGH.
    #[arg(long, value_parser = range, default_value = "0.5,2")]
    tilt_deg: (f64, f64),
    /// Give stroke I (0-based) a second tip contact 20 ms after the first (repeatable).
    #[arg(long = "double-hit", value_name = "I")]
    double_hits: Vec<usize>,
    /// Put stroke I's `ax` at the +16 g rail for 2 ms, 40 ms before contact (repeatable).
    #[arg(long = "saturate", value_name = "I")]
    saturated: Vec<usize>,
}

fn run(args: Args) -> Result<(), String> {
    let config = TraceConfig {
        seed: args.seed,
        strokes: args.strokes,
        odr_hz: args.odr,
        noise_mg: args.noise_mg,
        address_s: args.address_s,
        pause_s: args.pause_s,
        gap_s: args.gap_s,
        tilt_deg: args.tilt_deg,
        double_hits: args.double_hits,
        saturated: args.saturated,
    };
    config.check()?;
    let trace = generate(&config);
    let truth_path = args.truth.unwrap_or_else(|| {
        let stem = args.out.file_stem().unwrap_or_default().to_string_lossy();
        args.out.with_file_name(format!("{stem}.truth.json"))
    });
    let name = args.out.file_name().unwrap_or_default().to_string_lossy();
    // The command, without the program path, for the truth file.
    let command = std::iter::once("cargo run --release -p cuesight-host --example live_trace --")
        .map(String::from)
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    let write = |path: &PathBuf, f: &dyn Fn(&mut BufWriter<File>) -> std::io::Result<()>| {
        let file = File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut out = BufWriter::new(file);
        f(&mut out)
            .and_then(|()| out.flush())
            .map_err(|e| format!("{}: {e}", path.display()))
    };
    write(&args.out, &|out| write_csv(&trace.samples, out))?;
    write(&truth_path, &|out| {
        out.write_all(truth_json(&trace, &name, &command).as_bytes())
    })?;
    eprintln!(
        "{}: {} samples ({:.2} s at {} Hz), {} strokes; truth in {}",
        args.out.display(),
        trace.samples.len(),
        trace.samples.len() as f64 / config.odr_hz,
        config.odr_hz,
        trace.strokes.len(),
        truth_path.display()
    );
    for s in &trace.strokes {
        eprintln!(
            "  stroke {}: impact sample {}, cue speed {:.4} m/s",
            s.stroke, s.impact_sample, s.cue_speed_mps
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(Args::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
