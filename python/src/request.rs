//! One `cuesight collide` request from Python's arguments, and its prediction by the
//! CLI's own functions ([`cuesight_cli::cli`]): [`parse_model`], [`tip_spin`] (`--tip`)
//! and [`collide_within`] (the link's `Collide::prepare` from the pool defaults, the
//! core's `collide` or the f64 reference solver, `select_model` for `auto`).

use std::sync::{Mutex, MutexGuard};

use cuesight_cli::cli::{collide_within, parse_model, tip_spin, AutoPick, CliError};
use cuesight_cli::report::Report;
use cuesight_link::{Collide, ModelName};

/// A `model` name, as `cuesight collide --model` reads it; the error is the CLI's, for
/// the parameter `model`.
pub(crate) fn model(name: &str) -> Result<ModelName, String> {
    parse_model(name).map_err(|e| format!("invalid value '{name}' for model: {e}"))
}

/// The contact parameters of one request (each `None`: the pool default).
#[derive(Clone, Copy, Default)]
pub(crate) struct Contact {
    pub mu: Option<f32>,
    pub mu_b: Option<f32>,
    pub mu_c: Option<f32>,
    pub restitution: Option<f32>,
    pub mu_s: Option<f32>,
    pub radius: Option<f32>,
    pub mass: Option<f32>,
}

/// The request `cuesight collide` builds from its flags; `tip` replaces the spin as
/// `--tip` does ([`tip_spin`]). Spin with roll, or tip with either, is refused (clap
/// refuses them).
pub(crate) fn request(
    speed: f32,
    cut: f32,
    spin: Option<[f32; 3]>,
    roll: bool,
    tip: Option<[f32; 2]>,
    contact: Contact,
    model: ModelName,
) -> Result<Collide, CliError> {
    if roll && spin.is_some() {
        return Err(CliError::Usage(
            "spin and roll=True are exclusive".to_owned(),
        ));
    }
    if tip.is_some() && (roll || spin.is_some()) {
        return Err(CliError::Usage(
            "tip is exclusive with spin and roll=True".to_owned(),
        ));
    }
    let mut request = Collide {
        speed,
        cut,
        spin,
        roll,
        mu: contact.mu,
        mu_b: contact.mu_b,
        mu_c: contact.mu_c,
        restitution: contact.restitution,
        mu_s: contact.mu_s,
        radius: contact.radius,
        mass: contact.mass,
        model: Some(model),
    };
    if let Some(tip) = tip {
        request.spin = Some(tip_spin(&request, tip)?);
    }
    Ok(request)
}

/// One prediction: [`collide_within`], what `cuesight collide` runs.
pub(crate) fn predict(
    request: &Collide,
    tolerance: Option<f32>,
) -> Result<(Report, Option<AutoPick>), CliError> {
    collide_within(request, tolerance)
}

/// Held around every use of the reference solver. The CLI's wrapper of it swaps the
/// process-wide panic hook during each call (it is written for a single-threaded
/// CLI); `collide_many` runs without the GIL, so two Python threads could otherwise
/// interleave the swaps and leave the hook silenced.
static REFERENCE: Mutex<()> = Mutex::new(());

/// [`REFERENCE`]'s guard if `model` is the reference solver (no lock otherwise).
pub(crate) fn reference_lock(model: ModelName) -> Option<MutexGuard<'static, ()>> {
    (model == ModelName::Reference).then(|| {
        REFERENCE
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    })
}
