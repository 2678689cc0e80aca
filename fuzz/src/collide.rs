//! Target `collide`: parameters, a friction law and an impact decoded from the bytes,
//! through [`cuesight::collide`] and [`cuesight::collide_f64`] for every model
//! ([`Model::ALL`] and `Auto`), and the error estimates and `Auto`'s tier choice.
//!
//! Checked, whatever the input: no panic; every `Ok` outcome finite, field by field
//! (also for friction laws built from the enum's variants, bypassing validation). For
//! input that passed the constructors' validation: the outcome's throw, deflection and
//! separation angles are numbers too; every model answers `Ok` (the core
//! documents `NumericalFailure` as a guard that valid input never trips), every error
//! estimate is a number `≥ 0` (infinite is allowed: `Kim`'s and `KimGrip`'s outside
//! their calibrated domain), and `Auto` gives exactly the outcome of the tier
//! `select_model` picks.

use cuesight::{
    collide, collide_f64, error_estimate, select_model, Field, FrictionLaw, Impact, Model, Params,
};

use crate::finite;
use crate::input::Input;

/// Which ranges the numbers are drawn from (raw bit patterns are always possible).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ranges {
    /// Physical values: pool-like balls and friction, speeds to 10 m/s, spins to
    /// 200 rad/s.
    Physical,
    /// Everything the constructors accept.
    Valid,
}

/// What one input reached (for checking seeds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Report {
    /// Parameters and impact were accepted.
    pub valid: bool,
    /// Calls that returned an outcome (two precisions for each of [`Model::ALL`] and
    /// `Auto`)...
    pub outcomes: usize,
    /// ...calls refused outside the model's declared validity domain...
    pub refusals: usize,
    /// ...and calls that returned an error for an input that skipped validation.
    pub rejected: usize,
}

/// Decodes `data` and checks every model on it (see the module docs).
pub fn run(data: &[u8]) -> Report {
    let mut input = Input::new(data);
    let ranges = if input.flag() {
        Ranges::Valid
    } else {
        Ranges::Physical
    };
    let mut report = Report::default();
    let Some((params, validated)) = params(&mut input, ranges) else {
        return report;
    };
    let Some(impact) = impact(&mut input, ranges, &params) else {
        return report;
    };
    report.valid = true;
    let tolerance = input.real(0.0, 0.1);
    let models = Model::ALL.into_iter().chain([Model::Auto { tolerance }]);
    for model in models {
        for (precision, result) in [
            ("f32", collide(&params, &impact, model)),
            ("f64", collide_f64(&params, &impact, model)),
        ] {
            let what = format!("{model:?} {precision} for {params:?}, {impact:?}");
            match result {
                Ok(outcome) => {
                    finite::outcome(&what, &outcome);
                    if validated {
                        finite::angles(&what, &outcome);
                    }
                    report.outcomes += 1;
                }
                Err(error) => {
                    let bad_tolerance = matches!(model, Model::Auto { .. })
                        && error.field() == Some(Field::Tolerance);
                    // A refusal outside the model's declared validity domain: Kim where
                    // its contact grips (index above 1), KimGrip its parameters' refusal.
                    let declared = match error {
                        cuesight::Error::OutsideValidity {
                            reason: cuesight::validity::Reason::Grips,
                            value,
                            ..
                        } => model == Model::Kim && value >= 1.0, // rounded to f32
                        cuesight::Error::OutsideValidity { .. } => {
                            model == Model::KimGrip
                                && cuesight::validity::kim_grip(&params) == Err(error)
                        }
                        _ => false,
                    };
                    assert!(
                        !validated || bad_tolerance || declared,
                        "{what}: {error} for valid input {params:?}, {impact:?}"
                    );
                    report.refusals += usize::from(declared);
                    report.rejected += usize::from(!validated && !declared);
                }
            }
        }
        let estimate = error_estimate(&params, &impact, model);
        assert!(
            !validated || estimate >= 0.0,
            "error_estimate({model:?}) = {estimate} for {params:?}, {impact:?}"
        );
    }
    if validated && tolerance > 0.0 && tolerance <= 1.0 {
        let (tier, estimate) = select_model(&params, &impact, tolerance);
        assert!(estimate >= 0.0, "select_model estimate {estimate}");
        assert_eq!(
            collide(&params, &impact, Model::Auto { tolerance }),
            collide(&params, &impact, tier),
            "Auto {{ tolerance: {tolerance} }} is not {tier:?} for {params:?}, {impact:?}"
        );
    }
    report
}

/// The parameters, and whether every part went through a validating constructor.
fn params(input: &mut Input, ranges: Ranges) -> Option<(Params, bool)> {
    let physical = ranges == Ranges::Physical;
    let pick = |p: (f32, f32), v: (f32, f32)| if physical { p } else { v };
    let (lo, hi) = pick((0.0, 0.1), (0.0, 1.0));
    let mu = input.real(lo, hi);
    let (lo, hi) = pick((0.8, 1.0), (0.0, 1.0));
    let restitution = input.real(lo, hi);
    let (lo, hi) = pick((0.0, 0.4), (0.0, 1.0));
    let mu_s = input.real(lo, hi);
    let (lo, hi) = pick((0.02, 0.04), (0.001, 1.0));
    let radius = input.real(lo, hi);
    let (lo, hi) = pick((0.1, 0.3), (0.001, 100.0));
    let mass = input.real(lo, hi);
    let mut params = Params::new(mu, restitution, mu_s, radius, mass).ok()?;
    if input.flag() {
        let (lo, hi) = pick((0.0, 0.3), (0.0, 1.0));
        params = params.with_cue_table_friction(input.real(lo, hi)).ok()?;
    }
    let mut validated = true;
    match input.choice(3) {
        0 => {}
        1 => {
            let (a_hi, b_hi, c_hi) = if physical {
                (0.05, 0.2, 5.0)
            } else {
                (1.0, 1.0, 100.0)
            };
            let law = FrictionLaw::speed_dependent(
                input.real(1e-6, a_hi),
                input.real(0.0, b_hi),
                input.real(0.0, c_hi),
            )
            .ok()?;
            params = params.with_friction_law(law);
        }
        _ => {
            // The enum's variants are public: a law that skipped validation.
            validated = false;
            let law = if input.flag() {
                FrictionLaw::Constant(input.real(-1.0, 2.0))
            } else {
                FrictionLaw::SpeedDependent {
                    a: input.real(-1.0, 2.0),
                    b: input.real(-1.0, 2.0),
                    c: input.real(-10.0, 200.0),
                }
            };
            params = params.with_friction_law(law);
        }
    }
    Some((params, validated))
}

/// The impact, through one of its four constructors.
fn impact(input: &mut Input, ranges: Ranges, params: &Params) -> Option<Impact> {
    let (speed, spin) = match ranges {
        Ranges::Physical => (10.0, 200.0),
        Ranges::Valid => (100.0, 10_000.0),
    };
    let quarter = std::f32::consts::FRAC_PI_2;
    let impact = match input.choice(4) {
        0 => Impact::from_velocity(
            [input.real(0.0, speed), input.real(-speed, speed)],
            input.triple(-spin, spin),
        ),
        1 => Impact::from_cut(
            input.real(0.0, speed),
            input.real(-quarter, quarter),
            input.triple(-spin, spin),
        ),
        2 => Impact::from_cut_degrees(
            input.real(0.0, speed),
            input.real(-90.0, 90.0),
            input.triple(-spin, spin),
        ),
        _ => Impact::rolling(input.pair(-speed, speed), params.radius()),
    };
    let impact = impact.ok()?;
    finite::impact("impact", &impact);
    Some(impact)
}
