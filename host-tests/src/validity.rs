//! The core's declared validity domains (`cuesight::validity`) as the host suites meet
//! them: a refusal ([`cuesight::Error::OutsideValidity`]) is an answer of its own, to be
//! checked for consistency, not a failure.

use cuesight::validity::{
    Reason, Tier, KIM_GRIP_MAX_MU, KIM_GRIP_MAX_MU_MU_CT, KIM_GRIP_MAX_MU_MU_S,
    KIM_GRIP_MIN_RESTITUTION,
};
use cuesight::{collide, Error, Impact, Model, Outcome, Params};

/// Whether `error` is a refusal `model` may give for `params`: the model the reason
/// belongs to, and the reported value past the reason's limit (`Kim`'s gripping index
/// above 1; `KimGrip`'s μ, μ·μ_s or μ·μ_ct, exactly the parameters', above its limit;
/// e* below its limit with μ_ct > 0 and μ > 0).
pub fn declared(params: &Params, model: Model, error: &Error) -> bool {
    let Error::OutsideValidity {
        model: tier,
        reason,
        value,
    } = *error
    else {
        return false;
    };
    let named = matches!(
        (model, tier),
        (Model::Kim, Tier::Kim) | (Model::KimGrip, Tier::KimGrip)
    );
    let past = match reason {
        Reason::Grips => value >= 1.0, // an index just above 1 may round to 1.0 in f32
        Reason::Friction => value == params.mu() && value > KIM_GRIP_MAX_MU,
        Reason::TableFriction => {
            value == params.mu() * params.mu_s() && value > KIM_GRIP_MAX_MU_MU_S
        }
        Reason::CueTableFriction => {
            value == params.mu() * params.cue_table_friction() && value > KIM_GRIP_MAX_MU_MU_CT
        }
        Reason::NearlyPlastic => {
            params.cue_table_friction() > 0.0
                && params.mu() > 0.0
                && value == params.restitution()
                && value < KIM_GRIP_MIN_RESTITUTION
        }
    };
    named && reason.model() == tier && past
}

/// `collide`, with a declared refusal as `None`; any other error panics, naming `what`.
pub fn answer(params: &Params, impact: &Impact, model: Model, what: &str) -> Option<Outcome> {
    match collide(params, impact, model) {
        Ok(out) => Some(out),
        Err(e) if declared(params, model, &e) => None,
        Err(e) => panic!("{what}: {model:?} -> {e} ({params:?} {impact:?})"),
    }
}
