//! cuesight bench firmware: counts the instructions of one prediction for every model
//! and precision on the first scenes of the baked set, then prints every model's
//! outcome on the whole set, as plain text on semihosting stdout. Run by
//! `cargo xtask bench` under QEMU `mps2-an386` with `-icount shift=0`.
//!
//! Output lines (fields separated by one space):
//!
//! * `bench <backend> <seed> <scenes> <counted>` — header;
//! * `calibration <instructions> <reps> <block ticks> <empty ticks> <name…>`;
//! * `count <model> <precision> <scene> <reps> <ticks> <empty ticks>`;
//! * `outcome <model> <precision> <scene> <regime> <12 hex f32>` — cue v, cue ω,
//!   object v, object ω; regime `frictionless`/`sliding`/`gripping`, or `error` with
//!   twelve zero words, or `invalid` when the core rejected the scene's inputs;
//!   (not with the `counts-only` feature);
//! * `end` — everything was printed.
#![no_std]
#![no_main]
#![deny(unsafe_code)]
#![deny(missing_docs)]

use core::fmt::Write as _;

use cuesight::Model;
use cuesight_bench::count::{self, Predict, CALIBRATIONS, CALIBRATION_REPS};
use cuesight_bench::out::Out;
use cuesight_bench::scenes::Scenes;
use cuesight_bench::{exit, timer};

#[cfg(feature = "libm")]
const BACKEND: &str = "libm";
#[cfg(feature = "micromath")]
const BACKEND: &str = "micromath";

/// Evaluation precisions, each with its entry point. `collide_f64` needs the `libm`
/// backend (software double precision on the M4F). Add new precisions here.
#[cfg(feature = "libm")]
const PRECISIONS: &[(&str, Predict)] =
    &[("f32", cuesight::collide), ("f64", cuesight::collide_f64)];
#[cfg(not(feature = "libm"))]
const PRECISIONS: &[(&str, Predict)] = &[("f32", cuesight::collide)];

/// `Auto` is measured at these tolerances (labelled `auto(<tolerance>)`).
const AUTO_TOLERANCES: [f32; 3] = [1e-2, 1e-3, 1e-4];

/// Every model of `Model::ALL` (labelled with its name), then `Auto`.
fn models() -> impl Iterator<Item = (Label, Model)> {
    let tiers = Model::ALL.into_iter().map(|m| (Label::Name(m.name()), m));
    let auto = AUTO_TOLERANCES
        .into_iter()
        .map(|tolerance| (Label::Auto(tolerance), Model::Auto { tolerance }));
    tiers.chain(auto)
}

/// How a model is named in the output (no spaces).
#[derive(Clone, Copy)]
enum Label {
    Name(&'static str),
    Auto(f32),
}

impl core::fmt::Display for Label {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Label::Name(name) => f.write_str(name),
            Label::Auto(tolerance) => write!(f, "auto({tolerance:e})"),
        }
    }
}

#[cortex_m_rt::entry]
fn main() -> ! {
    cortex_m::interrupt::disable();
    let mut out = Out::stdout();
    let Some(scenes) = Scenes::baked() else {
        exit::fail(format_args!(
            "no scene set baked into this image: build it through `cargo xtask bench`"
        ));
    };
    timer::start();
    let _ = writeln!(
        out,
        "bench {BACKEND} {} {} {}",
        scenes.seed, scenes.count, scenes.counted
    );

    for c in &CALIBRATIONS {
        let (block, empty) = c.measure(CALIBRATION_REPS);
        let _ = writeln!(
            out,
            "calibration {} {CALIBRATION_REPS} {block} {empty} {}",
            c.instructions, c.name
        );
    }
    out.flush();

    for (label, model) in models() {
        for &(precision, predict) in PRECISIONS {
            for index in 0..scenes.counted {
                let Some(scene) = scenes.get(index) else {
                    continue;
                };
                let c = count::count(predict, &scene.params, &scene.impact, model);
                let _ = writeln!(
                    out,
                    "count {label} {precision} {index} {} {} {}",
                    c.reps, c.ticks, c.empty_ticks
                );
            }
            out.flush();
        }
    }

    #[cfg(not(feature = "counts-only"))]
    print_outcomes(&mut out, &scenes);
    let _ = writeln!(out, "end");
    out.flush();
    exit::exit(true)
}

/// Every model's outcome on every scene, as `outcome` lines.
#[cfg(not(feature = "counts-only"))]
fn print_outcomes(out: &mut Out, scenes: &Scenes) {
    for (label, model) in models() {
        for &(precision, predict) in PRECISIONS {
            for index in 0..scenes.count {
                let _ = write!(out, "outcome {label} {precision} {index} ");
                let Some(scene) = scenes.get(index) else {
                    let _ = writeln!(out, "invalid");
                    continue;
                };
                let (regime, words) = match predict(&scene.params, &scene.impact, model) {
                    Ok(o) => {
                        let mut words = [0u32; 12];
                        let vectors = [
                            o.cue_ball.velocity,
                            o.cue_ball.spin,
                            o.object_ball.velocity,
                            o.object_ball.spin,
                        ];
                        for (k, v) in vectors.iter().enumerate() {
                            words[3 * k] = v.x.to_bits();
                            words[3 * k + 1] = v.y.to_bits();
                            words[3 * k + 2] = v.z.to_bits();
                        }
                        (o.regime.name(), words)
                    }
                    Err(_) => ("error", [0; 12]),
                };
                let _ = out.write_str(regime);
                for w in words {
                    let _ = out.write_str(" ");
                    out.hex(w);
                }
                let _ = out.write_str("\n");
            }
        }
    }
}
