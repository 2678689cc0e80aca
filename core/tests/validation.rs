//! Input validation of the core's collision and strike entry points, table-driven:
//! every invalid input (NaN, ±Inf, zero or negative mass, radius or speed, μ < 0,
//! e* outside [0, 1], |φ| ≥ 90°, tolerance ≤ 0, bad friction-law and strike parameters)
//! returns the typed error naming the field, with the message `Display` gives; the
//! accepted edges of every range are accepted. docs/reliability.md lists the table.

mod common;

use cuesight::strike::{strike, Cue, Strike, TipOffset};
use cuesight::{collide, collide_f64, Error, Field, FrictionLaw, Impact, Model, Params, Vec3};

const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;

/// What a row expects: `NotFinite` or `OutOfRange` for `field`.
#[derive(Clone, Copy, Debug)]
enum Expect {
    NotFinite(Field),
    OutOfRange(Field, f32),
}

type Call = Box<dyn Fn() -> Result<(), Error>>;

fn row(
    what: &'static str,
    call: impl Fn() -> Result<(), Error> + 'static,
    expect: Expect,
) -> (&'static str, Call, Expect) {
    (what, Box::new(call), expect)
}

fn ok<T>(r: cuesight::Result<T>) -> Result<(), Error> {
    r.map(|_| ())
}

fn p() -> Params {
    Params::POOL
}

fn head_on() -> Impact {
    Impact::from_velocity([1.0, 0.0], [0.0; 3]).unwrap()
}

/// Every invalid input of the collision entry points with its expected error.
fn collision_rows() -> Vec<(&'static str, Call, Expect)> {
    use Expect::{NotFinite as Nf, OutOfRange as Or};
    let mut rows = vec![
        // Params::new(mu, e, mu_s, R, M)
        row(
            "Params::new mu NaN",
            || ok(Params::new(NAN, 0.9, 0.3, 0.03, 0.17)),
            Nf(Field::Friction),
        ),
        row(
            "Params::new mu +Inf",
            || ok(Params::new(INF, 0.9, 0.3, 0.03, 0.17)),
            Nf(Field::Friction),
        ),
        row(
            "Params::new mu < 0",
            || ok(Params::new(-0.01, 0.9, 0.3, 0.03, 0.17)),
            Or(Field::Friction, -0.01),
        ),
        row(
            "Params::new mu > 1",
            || ok(Params::new(1.5, 0.9, 0.3, 0.03, 0.17)),
            Or(Field::Friction, 1.5),
        ),
        row(
            "Params::new e NaN",
            || ok(Params::new(0.05, NAN, 0.3, 0.03, 0.17)),
            Nf(Field::Restitution),
        ),
        row(
            "Params::new e < 0",
            || ok(Params::new(0.05, -0.1, 0.3, 0.03, 0.17)),
            Or(Field::Restitution, -0.1),
        ),
        row(
            "Params::new e > 1",
            || ok(Params::new(0.05, 1.0001, 0.3, 0.03, 0.17)),
            Or(Field::Restitution, 1.0001),
        ),
        row(
            "Params::new e -Inf",
            || ok(Params::new(0.05, -INF, 0.3, 0.03, 0.17)),
            Nf(Field::Restitution),
        ),
        row(
            "Params::new mu_s NaN",
            || ok(Params::new(0.05, 0.9, NAN, 0.03, 0.17)),
            Nf(Field::TableFriction),
        ),
        row(
            "Params::new mu_s < 0",
            || ok(Params::new(0.05, 0.9, -0.3, 0.03, 0.17)),
            Or(Field::TableFriction, -0.3),
        ),
        row(
            "Params::new mu_s > 1",
            || ok(Params::new(0.05, 0.9, 1.1, 0.03, 0.17)),
            Or(Field::TableFriction, 1.1),
        ),
        row(
            "Params::new R NaN",
            || ok(Params::new(0.05, 0.9, 0.3, NAN, 0.17)),
            Nf(Field::Radius),
        ),
        row(
            "Params::new R 0",
            || ok(Params::new(0.05, 0.9, 0.3, 0.0, 0.17)),
            Or(Field::Radius, 0.0),
        ),
        row(
            "Params::new R < 0",
            || ok(Params::new(0.05, 0.9, 0.3, -0.03, 0.17)),
            Or(Field::Radius, -0.03),
        ),
        row(
            "Params::new R +Inf",
            || ok(Params::new(0.05, 0.9, 0.3, INF, 0.17)),
            Nf(Field::Radius),
        ),
        row(
            "Params::new R below 1 mm",
            || ok(Params::new(0.05, 0.9, 0.3, 9e-4, 0.17)),
            Or(Field::Radius, 9e-4),
        ),
        row(
            "Params::new R above 1 m",
            || ok(Params::new(0.05, 0.9, 0.3, 1.5, 0.17)),
            Or(Field::Radius, 1.5),
        ),
        row(
            "Params::new M NaN",
            || ok(Params::new(0.05, 0.9, 0.3, 0.03, NAN)),
            Nf(Field::Mass),
        ),
        row(
            "Params::new M 0",
            || ok(Params::new(0.05, 0.9, 0.3, 0.03, 0.0)),
            Or(Field::Mass, 0.0),
        ),
        row(
            "Params::new M < 0",
            || ok(Params::new(0.05, 0.9, 0.3, 0.03, -0.17)),
            Or(Field::Mass, -0.17),
        ),
        row(
            "Params::new M -Inf",
            || ok(Params::new(0.05, 0.9, 0.3, 0.03, -INF)),
            Nf(Field::Mass),
        ),
        row(
            "Params::new M above 100 kg",
            || ok(Params::new(0.05, 0.9, 0.3, 0.03, 101.0)),
            Or(Field::Mass, 101.0),
        ),
        // with_* replacements
        row(
            "Params::with_mu NaN",
            || ok(p().with_mu(NAN)),
            Nf(Field::Friction),
        ),
        row(
            "Params::with_mu < 0",
            || ok(p().with_mu(-1e-7)),
            Or(Field::Friction, -1e-7),
        ),
        row(
            "Params::with_restitution -Inf",
            || ok(p().with_restitution(-INF)),
            Nf(Field::Restitution),
        ),
        row(
            "Params::with_restitution > 1",
            || ok(p().with_restitution(2.0)),
            Or(Field::Restitution, 2.0),
        ),
        row(
            "Params::with_mu_s +Inf",
            || ok(p().with_mu_s(INF)),
            Nf(Field::TableFriction),
        ),
        row(
            "Params::with_mu_s < 0",
            || ok(p().with_mu_s(-0.0001)),
            Or(Field::TableFriction, -0.0001),
        ),
        row(
            "Params::with_ball R NaN",
            || ok(p().with_ball(NAN, 0.17)),
            Nf(Field::Radius),
        ),
        row(
            "Params::with_ball R < 0",
            || ok(p().with_ball(-0.028, 0.17)),
            Or(Field::Radius, -0.028),
        ),
        row(
            "Params::with_ball M 0",
            || ok(p().with_ball(0.028, 0.0)),
            Or(Field::Mass, 0.0),
        ),
        row(
            "Params::with_ball M NaN",
            || ok(p().with_ball(0.028, NAN)),
            Nf(Field::Mass),
        ),
        row(
            "Params::with_cue_table_friction NaN",
            || ok(p().with_cue_table_friction(NAN)),
            Nf(Field::CueTableFriction),
        ),
        row(
            "Params::with_cue_table_friction < 0",
            || ok(p().with_cue_table_friction(-0.1)),
            Or(Field::CueTableFriction, -0.1),
        ),
        row(
            "Params::with_cue_table_friction > 1",
            || ok(p().with_cue_table_friction(1.01)),
            Or(Field::CueTableFriction, 1.01),
        ),
        // FrictionLaw
        row(
            "FrictionLaw::constant NaN",
            || ok(FrictionLaw::constant(NAN)),
            Nf(Field::Friction),
        ),
        row(
            "FrictionLaw::constant < 0",
            || ok(FrictionLaw::constant(-0.05)),
            Or(Field::Friction, -0.05),
        ),
        row(
            "FrictionLaw::constant > 1",
            || ok(FrictionLaw::constant(1.2)),
            Or(Field::Friction, 1.2),
        ),
        row(
            "speed_dependent a NaN",
            || ok(FrictionLaw::speed_dependent(NAN, 0.1, 1.0)),
            Nf(Field::Friction),
        ),
        row(
            "speed_dependent a 0",
            || ok(FrictionLaw::speed_dependent(0.0, 0.1, 1.0)),
            Or(Field::Friction, 0.0),
        ),
        row(
            "speed_dependent a below 1e-6",
            || ok(FrictionLaw::speed_dependent(5e-7, 0.1, 1.0)),
            Or(Field::Friction, 5e-7),
        ),
        row(
            "speed_dependent a < 0",
            || ok(FrictionLaw::speed_dependent(-0.01, 0.1, 1.0)),
            Or(Field::Friction, -0.01),
        ),
        row(
            "speed_dependent b NaN",
            || ok(FrictionLaw::speed_dependent(0.01, NAN, 1.0)),
            Nf(Field::FrictionAmplitude),
        ),
        row(
            "speed_dependent b < 0",
            || ok(FrictionLaw::speed_dependent(0.01, -0.1, 1.0)),
            Or(Field::FrictionAmplitude, -0.1),
        ),
        row(
            "speed_dependent a + b > 1",
            || ok(FrictionLaw::speed_dependent(0.5, 0.6, 1.0)),
            Or(Field::FrictionAmplitude, 0.6),
        ),
        row(
            "speed_dependent c -Inf",
            || ok(FrictionLaw::speed_dependent(0.01, 0.1, -INF)),
            Nf(Field::FrictionDecay),
        ),
        row(
            "speed_dependent c < 0",
            || ok(FrictionLaw::speed_dependent(0.01, 0.1, -1.0)),
            Or(Field::FrictionDecay, -1.0),
        ),
        row(
            "speed_dependent c > 100",
            || ok(FrictionLaw::speed_dependent(0.01, 0.1, 101.0)),
            Or(Field::FrictionDecay, 101.0),
        ),
        // Impact::from_velocity([vx, vy], spin)
        row(
            "from_velocity vx NaN",
            || ok(Impact::from_velocity([NAN, 0.0], [0.0; 3])),
            Nf(Field::VelocityX),
        ),
        row(
            "from_velocity vx 0 (no approach)",
            || ok(Impact::from_velocity([0.0, 1.0], [0.0; 3])),
            Or(Field::VelocityX, 0.0),
        ),
        row(
            "from_velocity vx < 0 (receding)",
            || ok(Impact::from_velocity([-1.0, 0.0], [0.0; 3])),
            Or(Field::VelocityX, -1.0),
        ),
        row(
            "from_velocity vx > 100",
            || ok(Impact::from_velocity([150.0, 0.0], [0.0; 3])),
            Or(Field::VelocityX, 150.0),
        ),
        row(
            "from_velocity vy +Inf",
            || ok(Impact::from_velocity([1.0, INF], [0.0; 3])),
            Nf(Field::VelocityY),
        ),
        row(
            "from_velocity vy < -100",
            || ok(Impact::from_velocity([1.0, -101.0], [0.0; 3])),
            Or(Field::VelocityY, -101.0),
        ),
        row(
            "from_velocity spin.x NaN",
            || ok(Impact::from_velocity([1.0, 0.0], [NAN, 0.0, 0.0])),
            Nf(Field::SpinX),
        ),
        row(
            "from_velocity spin.y -Inf",
            || ok(Impact::from_velocity([1.0, 0.0], [0.0, -INF, 0.0])),
            Nf(Field::SpinY),
        ),
        row(
            "from_velocity spin.z > 1e4",
            || ok(Impact::from_velocity([1.0, 0.0], [0.0, 0.0, 1.0e4 + 1.0])),
            Or(Field::SpinZ, 10_001.0),
        ),
        row(
            "from_velocity spin.x < -1e4",
            || ok(Impact::from_velocity([1.0, 0.0], [-2e4, 0.0, 0.0])),
            Or(Field::SpinX, -2e4),
        ),
        // Impact::from_cut(speed, φ rad, spin)
        row(
            "from_cut speed NaN",
            || ok(Impact::from_cut(NAN, 0.1, [0.0; 3])),
            Nf(Field::Speed),
        ),
        row(
            "from_cut speed 0",
            || ok(Impact::from_cut(0.0, 0.1, [0.0; 3])),
            Or(Field::Speed, 0.0),
        ),
        row(
            "from_cut speed -0",
            || ok(Impact::from_cut(-0.0, 0.1, [0.0; 3])),
            Or(Field::Speed, -0.0),
        ),
        row(
            "from_cut speed < 0",
            || ok(Impact::from_cut(-2.0, 0.1, [0.0; 3])),
            Or(Field::Speed, -2.0),
        ),
        row(
            "from_cut speed > 100",
            || ok(Impact::from_cut(100.5, 0.1, [0.0; 3])),
            Or(Field::Speed, 100.5),
        ),
        row(
            "from_cut speed +Inf",
            || ok(Impact::from_cut(INF, 0.1, [0.0; 3])),
            Nf(Field::Speed),
        ),
        row(
            "from_cut φ NaN",
            || ok(Impact::from_cut(1.0, NAN, [0.0; 3])),
            Nf(Field::CutAngle),
        ),
        row(
            "from_cut φ = π/2",
            || {
                ok(Impact::from_cut(
                    1.0,
                    core::f32::consts::FRAC_PI_2,
                    [0.0; 3],
                ))
            },
            Or(Field::CutAngle, core::f32::consts::FRAC_PI_2),
        ),
        row(
            "from_cut φ = -π/2",
            || {
                ok(Impact::from_cut(
                    1.0,
                    -core::f32::consts::FRAC_PI_2,
                    [0.0; 3],
                ))
            },
            Or(Field::CutAngle, -core::f32::consts::FRAC_PI_2),
        ),
        row(
            "from_cut φ = 2",
            || ok(Impact::from_cut(1.0, 2.0, [0.0; 3])),
            Or(Field::CutAngle, 2.0),
        ),
        row(
            "from_cut spin.z NaN",
            || ok(Impact::from_cut(1.0, 0.1, [0.0, 0.0, NAN])),
            Nf(Field::SpinZ),
        ),
        // Impact::from_cut_degrees(speed, φ°, spin)
        row(
            "from_cut_degrees φ = 90",
            || ok(Impact::from_cut_degrees(1.0, 90.0, [0.0; 3])),
            Or(Field::CutAngle, 90.0),
        ),
        row(
            "from_cut_degrees φ = -90",
            || ok(Impact::from_cut_degrees(1.0, -90.0, [0.0; 3])),
            Or(Field::CutAngle, -90.0),
        ),
        row(
            "from_cut_degrees φ = 135",
            || ok(Impact::from_cut_degrees(1.0, 135.0, [0.0; 3])),
            Or(Field::CutAngle, 135.0),
        ),
        row(
            "from_cut_degrees φ +Inf",
            || ok(Impact::from_cut_degrees(1.0, INF, [0.0; 3])),
            Nf(Field::CutAngle),
        ),
        // 89.999999° rounds to 90° in f32 (the nearest f32 below 90 is 89.999992).
        row(
            "from_cut_degrees φ = 89.999999 (f32: 90)",
            || ok(Impact::from_cut_degrees(1.0, 89.999_999, [0.0; 3])),
            Or(Field::CutAngle, 90.0),
        ),
        row(
            "from_cut_degrees speed 0",
            || ok(Impact::from_cut_degrees(0.0, 10.0, [0.0; 3])),
            Or(Field::Speed, 0.0),
        ),
        row(
            "from_cut_degrees speed NaN",
            || ok(Impact::from_cut_degrees(NAN, 10.0, [0.0; 3])),
            Nf(Field::Speed),
        ),
        // Impact::rolling(velocity, R)
        row(
            "rolling R NaN",
            || ok(Impact::rolling([1.0, 0.0], NAN)),
            Nf(Field::Radius),
        ),
        row(
            "rolling R 0",
            || ok(Impact::rolling([1.0, 0.0], 0.0)),
            Or(Field::Radius, 0.0),
        ),
        row(
            "rolling vx < 0",
            || ok(Impact::rolling([-1.0, 0.0], 0.03)),
            Or(Field::VelocityX, -1.0),
        ),
        row(
            "rolling vy NaN",
            || ok(Impact::rolling([1.0, NAN], 0.03)),
            Nf(Field::VelocityY),
        ),
        // The rolling spin v/R is derived: 20 m/s on a 1 mm ball is 2e4 rad/s > 1e4.
        row(
            "rolling derived spin > 1e4",
            || ok(Impact::rolling([20.0, 0.0], 0.001)),
            Or(Field::SpinY, 20_000.0),
        ),
    ];
    // Model::Auto { tolerance } through every collision entry point.
    for (label, tolerance) in [
        ("Auto tolerance NaN", NAN),
        ("Auto tolerance 0", 0.0),
        ("Auto tolerance < 0", -1e-3),
        ("Auto tolerance > 1", 1.5),
        ("Auto tolerance +Inf", INF),
    ] {
        let expect = if tolerance.is_finite() {
            Or(Field::Tolerance, tolerance)
        } else {
            Nf(Field::Tolerance)
        };
        rows.push(row(
            label,
            move || ok(collide(&p(), &head_on(), Model::Auto { tolerance })),
            expect,
        ));
        rows.push(row(
            label,
            move || ok(collide_f64(&p(), &head_on(), Model::Auto { tolerance })),
            expect,
        ));
        rows.push(row(
            label,
            move || {
                ok(cuesight::collide_in::<f32>(
                    &p(),
                    &head_on(),
                    Model::Auto { tolerance },
                ))
            },
            expect,
        ));
    }
    rows
}

/// Every invalid input of the strike entry points with its expected error.
fn strike_rows() -> Vec<(&'static str, Call, Expect)> {
    use Expect::{NotFinite as Nf, OutOfRange as Or};
    let r = Params::POOL.radius();
    let centre = TipOffset::CENTRE;
    vec![
        row(
            "Cue::new mass NaN",
            || ok(Cue::new(NAN, 0.75)),
            Nf(Field::CueMass),
        ),
        row(
            "Cue::new mass 0",
            || ok(Cue::new(0.0, 0.75)),
            Or(Field::CueMass, 0.0),
        ),
        row(
            "Cue::new mass < 0",
            || ok(Cue::new(-0.5, 0.75)),
            Or(Field::CueMass, -0.5),
        ),
        row(
            "Cue::new mass < 0.1 kg",
            || ok(Cue::new(0.05, 0.75)),
            Or(Field::CueMass, 0.05),
        ),
        row(
            "Cue::new mass > 2 kg",
            || ok(Cue::new(2.5, 0.75)),
            Or(Field::CueMass, 2.5),
        ),
        row(
            "Cue::new e_t NaN",
            || ok(Cue::new(0.54, NAN)),
            Nf(Field::TipRestitution),
        ),
        row(
            "Cue::new e_t < 0",
            || ok(Cue::new(0.54, -0.1)),
            Or(Field::TipRestitution, -0.1),
        ),
        row(
            "Cue::new e_t > 1",
            || ok(Cue::new(0.54, 1.1)),
            Or(Field::TipRestitution, 1.1),
        ),
        row(
            "TipOffset::new side NaN",
            || ok(TipOffset::new(NAN, 0.0)),
            Nf(Field::TipOffset),
        ),
        row(
            "TipOffset::new height -Inf",
            || ok(TipOffset::new(0.0, -INF)),
            Nf(Field::TipOffset),
        ),
        row(
            "from_radius_fraction R 0",
            || ok(TipOffset::from_radius_fraction(0.1, 0.1, 0.0)),
            Or(Field::Radius, 0.0),
        ),
        row(
            "from_radius_fraction R NaN",
            || ok(TipOffset::from_radius_fraction(0.1, 0.1, NAN)),
            Nf(Field::Radius),
        ),
        row(
            "from_radius_fraction side NaN",
            || ok(TipOffset::from_radius_fraction(NAN, 0.1, 0.03)),
            Nf(Field::TipOffset),
        ),
        row(
            "strike cue speed NaN",
            move || ok(strike(&Params::POOL, &Cue::TYPICAL, centre, NAN)),
            Nf(Field::CueSpeed),
        ),
        row(
            "strike cue speed 0",
            move || ok(strike(&Params::POOL, &Cue::TYPICAL, centre, 0.0)),
            Or(Field::CueSpeed, 0.0),
        ),
        row(
            "strike cue speed < 0",
            move || ok(strike(&Params::POOL, &Cue::TYPICAL, centre, -3.0)),
            Or(Field::CueSpeed, -3.0),
        ),
        row(
            "strike cue speed > 20",
            move || ok(strike(&Params::POOL, &Cue::TYPICAL, centre, 20.5)),
            Or(Field::CueSpeed, 20.5),
        ),
        row(
            "strike cue speed +Inf",
            move || ok(strike(&Params::POOL, &Cue::TYPICAL, centre, INF)),
            Nf(Field::CueSpeed),
        ),
        row(
            "strike tip beyond 0.5 R",
            move || {
                ok(strike(
                    &Params::POOL,
                    &Cue::TYPICAL,
                    TipOffset::new(0.0, 0.6 * r).unwrap(),
                    2.0,
                ))
            },
            Or(Field::TipOffset, 0.6 * r),
        ),
        row(
            "strike tip 3e38 m (|b| reported as inf)",
            || {
                ok(strike(
                    &Params::POOL,
                    &Cue::TYPICAL,
                    TipOffset::new(3e38, 0.0).unwrap(),
                    2.0,
                ))
            },
            Or(Field::TipOffset, INF),
        ),
        row(
            "Strike::to_impact φ NaN",
            || {
                ok(Strike {
                    speed: 1.0,
                    spin: Vec3::ZERO,
                }
                .to_impact(NAN))
            },
            Nf(Field::CutAngle),
        ),
        row(
            "Strike::to_impact φ = π/2",
            || {
                ok(Strike {
                    speed: 1.0,
                    spin: Vec3::ZERO,
                }
                .to_impact(core::f32::consts::FRAC_PI_2))
            },
            Or(Field::CutAngle, core::f32::consts::FRAC_PI_2),
        ),
        // `Strike` has public fields: a hand-built one is validated by `to_impact`.
        row(
            "Strike::to_impact speed NaN (hand-built)",
            || {
                ok(Strike {
                    speed: NAN,
                    spin: Vec3::ZERO,
                }
                .to_impact(0.0))
            },
            Nf(Field::Speed),
        ),
        row(
            "Strike::to_impact speed 0 (hand-built)",
            || {
                ok(Strike {
                    speed: 0.0,
                    spin: Vec3::ZERO,
                }
                .to_impact(0.0))
            },
            Or(Field::Speed, 0.0),
        ),
        row(
            "Strike::to_impact spin.z +Inf (hand-built)",
            || {
                ok(Strike {
                    speed: 1.0,
                    spin: Vec3::new(0.0, 0.0, INF),
                }
                .to_impact(0.0))
            },
            Nf(Field::SpinZ),
        ),
    ]
}

fn check_rows(rows: Vec<(&'static str, Call, Expect)>) -> usize {
    let mut failures = Vec::new();
    let n = rows.len();
    for (what, call, expect) in rows {
        let got = call();
        let good = match (expect, got) {
            (Expect::NotFinite(field), Err(e @ Error::NotFinite { field: f })) => {
                f == field && e.to_string() == format!("{} must be a finite number", field.name())
            }
            (
                Expect::OutOfRange(field, value),
                Err(e @ Error::OutOfRange { field: f, value: v }),
            ) => {
                f == field
                    && v.to_bits() == value.to_bits()
                    && e.to_string()
                        == format!(
                            "{} = {} is outside {}",
                            field.name(),
                            value,
                            field.valid_range()
                        )
            }
            _ => false,
        };
        if good {
            println!("{what:45} -> {}", got.unwrap_err());
        } else {
            failures.push(format!("{what}: expected {expect:?}, got {got:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    n
}

#[test]
fn every_invalid_collision_input_names_its_field() {
    let n = check_rows(collision_rows());
    assert!(n >= 90, "{n} rows");
    cuesight_figures::record!("reliability-validation-collision-rows", "{n}");
}

#[test]
fn every_invalid_strike_input_names_its_field() {
    let n = check_rows(strike_rows());
    assert!(n >= 24, "{n} rows");
    cuesight_figures::record!("reliability-validation-strike-rows", "{n}");
}

/// The edges of every accepted range are accepted (closed ends) and produce a
/// finite prediction with every model.
#[test]
fn range_edges_are_accepted() {
    let tiny = f32::from_bits(1); // smallest positive subnormal, 1.4e-45
    for (mu, e, mu_s, r, m) in [
        (0.0, 0.0, 0.0, 0.001, 0.001),
        (1.0, 1.0, 1.0, 1.0, 100.0),
        (tiny, tiny, tiny, 0.001, 100.0),
    ] {
        let params = Params::new(mu, e, mu_s, r, m)
            .unwrap()
            .with_cue_table_friction(1.0)
            .unwrap();
        for impact in [
            Impact::from_velocity([tiny, 0.0], [0.0; 3]).unwrap(),
            Impact::from_velocity([100.0, -100.0], [-1e4, 1e4, -1e4]).unwrap(),
            Impact::from_velocity([100.0, 100.0], [1e4, -1e4, 1e4]).unwrap(),
            Impact::from_cut_degrees(100.0, 89.999_99, [0.0; 3]).unwrap(),
            Impact::from_cut(tiny, 0.0, [0.0; 3]).unwrap(),
        ] {
            for model in [
                Model::Ideal,
                Model::Kim,
                Model::KimGrip,
                Model::Exact,
                Model::Auto { tolerance: 1.0 },
                Model::Auto { tolerance: tiny },
            ] {
                // Answered, or refused as the model's validity domain declares.
                if let Some(out) = common::answer(&params, &impact, model) {
                    assert!(out.is_finite());
                }
            }
        }
    }
    assert!(FrictionLaw::speed_dependent(1e-6, 0.0, 0.0).is_ok());
    assert!(FrictionLaw::speed_dependent(0.5, 0.5, 100.0).is_ok());
    assert!(FrictionLaw::speed_dependent(1.0, 0.0, 100.0).is_ok());
    assert!(Cue::new(0.1, 0.0).is_ok() && Cue::new(2.0, 1.0).is_ok());
    let edge = TipOffset::from_radius_fraction(0.3, 0.4, Params::POOL.radius()).unwrap();
    assert!(strike(&Params::POOL, &Cue::TYPICAL, edge, 20.0).is_ok());
    assert!(strike(&Params::POOL, &Cue::TYPICAL, TipOffset::CENTRE, tiny).is_ok());
}

/// A speed so small that `U cos φ` underflows is refused, naming the cut angle (the
/// cue ball would not approach at f32 resolution): documented behaviour.
#[test]
fn underflowing_approach_is_refused_as_a_cut_angle() {
    let tiny = f32::from_bits(1);
    let err = Impact::from_cut_degrees(tiny, 60.0, [0.0; 3]).unwrap_err();
    assert_eq!(
        err,
        Error::OutOfRange {
            field: Field::CutAngle,
            value: 60.0
        }
    );
}

/// Functions that take no `Result` never panic on a bad tolerance: `select_model` with
/// a NaN tolerance falls back to `Exact` (nothing meets it), and every estimate stays
/// finite whatever the tolerance.
#[test]
fn unvalidated_helpers_degrade_gracefully() {
    let (params, impact) = (Params::POOL, head_on());
    for tolerance in [NAN, -1.0, 0.0, INF] {
        let (tier, estimate) = cuesight::select_model(&params, &impact, tolerance);
        if tolerance.is_nan() {
            assert_eq!(tier, Model::Exact);
        }
        assert!(estimate.is_finite(), "{tolerance}: {tier:?} {estimate}");
        assert!(cuesight::error_estimate(&params, &impact, Model::Auto { tolerance }).is_finite());
    }
}
