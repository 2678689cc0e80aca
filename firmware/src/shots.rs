//! The built-in shots and the checks every outcome must pass.

use cuesight::{collide, Impact, Model, Outcome, Params};

/// Table and ball parameters used for every shot.
const PARAMS: Params = Params::POOL;
/// Ball radius (m).
const R: f32 = PARAMS.radius();

/// How the cue ball arrives at the object ball.
#[derive(Clone, Copy)]
enum Setup {
    /// Speed (m/s), cut angle (degrees) and spin `[ω_x, ω_y, ω_z]` (rad/s).
    Cut {
        speed: f32,
        cut_deg: f32,
        spin: [f32; 3],
    },
    /// Natural roll at `[v_x, v_y]` (m/s).
    Rolling { velocity: [f32; 2] },
}

/// One named shot. The name is a defmt-interned string (its text lives in the ELF's
/// `.defmt` section, not in flash; the host's decoder prints it), behind a function
/// because interning is not a constant expression.
pub struct Shot {
    name: fn() -> defmt::Str,
    setup: Setup,
}

/// A shot's name: a function returning the interned literal.
macro_rules! name {
    ($text:literal) => {{
        fn name() -> defmt::Str {
            defmt::intern!($text)
        }
        name
    }};
}

/// A shot at `speed` (m/s) and cut angle `cut_deg` (degrees) with `spin` (rad/s).
const fn cut(name: fn() -> defmt::Str, speed: f32, cut_deg: f32, spin: [f32; 3]) -> Shot {
    Shot {
        name,
        setup: Setup::Cut {
            speed,
            cut_deg,
            spin,
        },
    }
}

/// A naturally rolling cue ball at `velocity` (m/s).
const fn rolling(name: fn() -> defmt::Str, velocity: [f32; 2]) -> Shot {
    Shot {
        name,
        setup: Setup::Rolling { velocity },
    }
}

/// `sin 30°`, for the gearing spin of a 30° cut.
const SIN_30: f32 = 0.5;

/// The shots, each evaluated with every [`Model`]. Spin is `[ω_x, ω_y, ω_z]`:
/// `ω_y < 0` is draw, `ω_z > 0` counter-clockwise seen from above (side spin).
pub const SHOTS: [Shot; 5] = [
    cut(name!("stun, 30 deg cut, 2 m/s"), 2.0, 30.0, [0.0, 0.0, 0.0]),
    rolling(name!("natural roll, head-on, 2 m/s"), [2.0, 0.0]),
    // One "reverse roll" of backspin: ω_y = −U/R.
    cut(
        name!("draw, 20 deg cut, 2 m/s"),
        2.0,
        20.0,
        [0.0, -2.0 / R, 0.0],
    ),
    // ω_z = −U sin φ / R cancels the contact slip (seed eq. (11)): friction has
    // nothing to throw with, which only a model that grips gets right.
    cut(
        name!("gearing outside english, 30 deg cut, 1 m/s"),
        1.0,
        30.0,
        [0.0, 0.0, -SIN_30 / R],
    ),
    // ω_z = +U/R adds to the slip of the cut.
    cut(
        name!("inside english, 30 deg cut, 1 m/s"),
        1.0,
        30.0,
        [0.0, 0.0, 1.0 / R],
    ),
];

impl Shot {
    fn impact(&self) -> cuesight::Result<Impact> {
        match self.setup {
            Setup::Cut {
                speed,
                cut_deg,
                spin,
            } => Impact::from_cut_degrees(speed, cut_deg, spin),
            Setup::Rolling { velocity } => Impact::rolling(velocity, R),
        }
    }
}

/// Models this image evaluates ([`Model::built`]).
const BUILT_MODELS: usize = {
    let mut count = 0;
    let mut i = 0;
    while i < Model::ALL.len() {
        if Model::ALL[i].built() {
            count += 1;
        }
        i += 1;
    }
    count
};

/// Runs every shot with every model, logs the outcomes and returns how many failed.
pub fn run_all() -> u32 {
    // The image leaves `SeedExact` and `Kim` out (`Cargo.toml`): every other model is
    // checked.
    let mut failures = 0;
    for shot in &SHOTS {
        let impact = match shot.impact() {
            Ok(impact) => impact,
            Err(_) => {
                // The shots are constants inside every range: this is a broken build.
                defmt::error!("{=istr}: invalid impact", (shot.name)());
                failures += BUILT_MODELS as u32;
                continue;
            }
        };
        for model in Model::ALL.into_iter().filter(|model| model.built()) {
            match collide(&PARAMS, &impact, model) {
                Ok(out) => {
                    log(shot, model, &out);
                    if !check(shot, model, &out) {
                        failures += 1;
                    }
                }
                Err(_) => {
                    // `collide`'s only error for valid inputs: a non-finite result.
                    defmt::error!(
                        "{=istr} [{=str}]: collide failed (numerical failure)",
                        (shot.name)(),
                        model.name()
                    );
                    failures += 1;
                }
            }
        }
    }
    if failures == 0 {
        defmt::info!(
            "boot self-test: all {=usize} outcomes finite and sane",
            SHOTS.len() * BUILT_MODELS
        );
    } else {
        defmt::error!("{=u32} outcome(s) failed their checks", failures);
    }
    failures
}

fn log(shot: &Shot, model: Model, out: &Outcome) {
    defmt::info!(
        "{=istr} [{=str}]: {=str}, throw {=f32} deg, cue deflection {=f32} deg",
        (shot.name)(),
        model.name(),
        out.regime.name(),
        out.throw_angle_deg(),
        out.cue_deflection_deg(),
    );
    defmt::debug!(
        "  cue    v {} m/s, w {} rad/s",
        out.cue_ball.velocity.to_array(),
        out.cue_ball.spin.to_array()
    );
    defmt::debug!(
        "  object v {} m/s, w {} rad/s",
        out.object_ball.velocity.to_array(),
        out.object_ball.spin.to_array()
    );
}

/// Every number finite (velocities, spins, impulses, both angles), and the object
/// ball driven forward along the line of centres.
fn check(shot: &Shot, model: Model, out: &Outcome) -> bool {
    let finite = out.is_finite()
        && out.throw_angle_deg().is_finite()
        && out.cue_deflection_deg().is_finite();
    if !finite {
        defmt::error!(
            "{=istr} [{=str}]: non-finite output",
            (shot.name)(),
            model.name()
        );
        return false;
    }
    if out.object_ball.velocity.x <= 0.0 {
        defmt::error!(
            "{=istr} [{=str}]: object ball not driven forward (v.x {=f32} m/s)",
            (shot.name)(),
            model.name(),
            out.object_ball.velocity.x
        );
        return false;
    }
    true
}
