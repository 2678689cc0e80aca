//! Physical invariants of one collision outcome (issue 16, item 2), checked from vector
//! mechanics alone: nothing here uses a model's own equations, only the outcome (both
//! balls' velocities and spins after the impact, the ball–ball impulses it reports), the
//! state before it ([`Impact`]) and the contact parameters ([`Params`]).
//!
//! # Frame and bookkeeping
//!
//! Collision frame (docs/physics-notes.md §1): `x̂` from the cue-ball centre to the
//! object-ball centre, `ẑ` up, `ŷ = ẑ × x̂`. Both balls have mass `M` (kg), radius `R` (m)
//! and moment of inertia `I = ν M R²`, `ν = 2/5` (solid sphere). The impact is impulsive:
//! positions do not change during it, so the line of centres stays `x̂` and both table
//! contacts stay at `−R ẑ` from the centres; gravity's impulse `M g Δt` (≈ 5e-4 N·s for
//! a pool ball over 300 µs) is neglected, as every model and the reference do.
//!
//! Impulses (N·s) acting during the impact:
//!
//! * ball–ball `J = (J_n, J_y, J_z)` on the object ball at `−R x̂` from its centre, and
//!   `−J` on the cue ball at `+R x̂` from its centre (Newton's third law). `J_n` is the
//!   normal impulse ([`cuesight::Impulses::normal`]), `J_t = (0, J_y, J_z)` the friction
//!   impulse ([`cuesight::Impulses::friction`]);
//! * table on the object ball `(T_x, T_y, N_o)` at `−R ẑ`: friction `T_o = (T_x, T_y)` and
//!   normal impulse `N_o`;
//! * table on the cue ball `(C_x, C_y, N_c)` at `−R ẑ`.
//!
//! Newton's and Euler's laws for each ball (`M ΔV = ΣJ`, `I Δω = Σ r × J`):
//!
//! ```text
//! object:  M V'            = J + (T_x, T_y, N_o)
//!          I ω'_o          = (−R x̂) × J + (−R ẑ) × (T_x, T_y, N_o)
//!                          = R (T_y, J_z − T_x, −J_y)
//! cue:     M (U' − U)      = −J + (C_x, C_y, N_c)
//!          I (ω'_c − ω)    = (R x̂) × (−J) + (−R ẑ) × (C_x, C_y, N_c)
//!                          = R (C_y, J_z − C_x, −J_y)
//! ```
//!
//! The outcome does not report the table impulses (only the size of `T_o`, as
//! `table_friction`), so they are *derived* from linear momentum with the reported `J`:
//!
//! ```text
//! (T_x, T_y) = M (V'_x, V'_y) − (J_n, J_y)          N_o = M V'_z − J_z
//! (C_x, C_y) = M (U'_x − U_x, U'_y − U_y) + (J_n, J_y)   N_c = M U'_z + J_z
//! ```
//!
//! and the six angular equations are then checked as a consistency condition
//! ([`Invariant::Impulses`]): they hold iff the outcome is what the reported ball–ball
//! impulse and *some* table impulses at the table contacts produce. Together the twelve
//! equations are the whole rigid-body bookkeeping, so every impulse checked below is
//! one that acted on the balls, not only one a model says it applied.
//!
//! # The invariants
//!
//! * [`Invariant::Energy`]: total kinetic energy
//!   `E = Σ_balls ½ M |v|² + ½ ν M R² |ω|²` (J) does not grow:
//!   `E' ≤ E (1 + 1e-6)`. The only forces are the contact forces: Coulomb friction
//!   opposes its contact's slip and so only dissipates, the ball–ball normal force
//!   returns at most the work of compression (Stronge's `e* ≤ 1`), and the table's normal
//!   force does no work (it acts only while its ball's contact point does not move
//!   vertically).
//! * [`Invariant::BallNormal`]: `J_n ≥ 0`; the contact can only push.
//! * [`Invariant::BallCone`]: `|J_t| ≤ μ_max J_n`. Coulomb: at every instant
//!   `|dJ_t| ≤ μ(s) dJ_n` with `s` the slip speed, so `|J_t| = |∫ dJ_t| ≤ ∫ μ(s) dJ_n ≤
//!   μ_max J_n` where `μ_max` is the largest μ over the slip speeds reached. The outcome
//!   does not say which slip speeds were reached, so `μ_max` is the largest value the
//!   law takes over all `s ≥ 0` (a necessary condition): the constant μ, or for
//!   `μ(s) = a + b e^{−c s}` with `b ≥ 0` (the core's constructor enforces it)
//!   `μ(0) = a + b`.
//! * [`Invariant::ObjectTableNormal`], [`Invariant::CueTableNormal`]: `N_o ≥ 0`,
//!   `N_c ≥ 0`; the table can only push.
//! * [`Invariant::ObjectTableCone`]: `|T_o| ≤ μ_s N_o`, the same Coulomb argument at the
//!   object ball's table contact with its (static) coefficient μ_s ([`Params::mu_s`]):
//!   the table friction force is at most μ_s times the table's normal force at every
//!   instant, so its impulse is at most μ_s times the normal impulse. In particular an
//!   object ball the ball–ball friction lifts (`N_o = 0`) gets no table friction.
//! * [`Invariant::CueTableCone`]: `|C| ≤ μ_ct N_c` with μ_ct
//!   ([`Params::cue_table_friction`]); with μ_ct = 0 the cue ball's horizontal momentum
//!   changes by `−(J_n, J_y)` only.
//! * [`Invariant::Approach`]: after the impact the balls do not move into each other:
//!   the object ball's centre velocity along the line of centres is at least the cue
//!   ball's, `V'_x − U'_x ≥ 0` (the normal relative velocity of the contact points is
//!   that of the centres: the spins' contribution `ω × r` at `±R x̂` is perpendicular to
//!   `x̂`).
//! * [`Invariant::ObjectIntoTable`], [`Invariant::CueIntoTable`]: a ball on the table
//!   does not move into it, `V'_z ≥ 0` and `U'_z ≥ 0` (both start on the table with
//!   zero vertical velocity).
//! * [`Invariant::Impulses`]: the angular-momentum equations above hold (the six
//!   residuals `(I Δω − Σ r × J)/R`, in N·s, vanish).
//! * [`Invariant::ReportedTableFriction`]: the reported
//!   [`Impulses::table_friction`](cuesight::Impulses::table_friction) is `|T_o|`, the
//!   size of the table friction the object ball's momentum shows.
//!
//! # Tolerances (f32 rounding only)
//!
//! The outcome is f32; the checks are evaluated in f64 from its values, so the only
//! error to allow for is the rounding of the outcome's numbers. `u = 2⁻²⁴` is the unit
//! roundoff of f32 (half an ulp, relative).
//!
//! * Energy: `1e-6` relative, the issue's bound. Each output component carries a
//!   relative rounding of a few `u`, its square twice that, so the computed `E'` is
//!   within ~`4u` ≈ 2.4e-7 of the exact one: the bound is 4× the rounding.
//! * Ball–ball cone: `|J_t| ≤ μ_max J_n (1 + 64 u)` (64 u ≈ 3.8e-6). A sliding contact
//!   whose direction does not turn sits exactly on the cone, so its rounding shows. The
//!   deepest computation in the core is `Exact`: `J_n` and `J_t` are sums of ≤ 28 step
//!   impulses (24 steps, the end refinements), each sum accruing ≤ 28 `u`; per step `μ`
//!   (an `exp` within 4 ulps) and the unit slip direction (a square root, a division)
//!   add a few `u`; the conversion to f32 and the product by `M` two more on each side.
//!   `2 × 28 + 8 = 64`.
//! * Everything derived by differences (table impulses, residuals, relative velocity,
//!   vertical velocity): an absolute tolerance of `32 u` times the sum of the
//!   magnitudes that enter (a *speed scale* `S` in m/s, times `M` for impulses). Each
//!   output is one f32 rounding of a sum of at most three terms (`core::outcome`'s
//!   assembly), i.e. ≤ 2–4 `u` of `S`; a derived quantity combines at most four of
//!   them: ≤ 16 `u S`, taken twice. `S` is `|U| + |U'| + |V'| + (|J_n| + |J_t|)/M` for the
//!   linear checks and adds `ν R (|ω| + |ω'_c| + |ω'_o|)` for the angular residuals (an
//!   f32 spin of 10⁴ rad/s is only resolved to 1e-3 rad/s). A cone or sign test on a
//!   derived impulse allows `(1 + μ) × 32 u M S`.
//!
//! Every violation carries its size (how far past its limit, in units of the scene: `E`
//! for energy, `M U` for impulses, `U` for velocities, with `U = |U|` the cue-ball speed
//! before the impact) so that worst cases can be ranked across scenes.

use cuesight::{FrictionLaw, Impact, Model, Outcome, Params, Vec3};

/// Moment-of-inertia factor of a solid sphere, `I = ν M R²`.
pub const NU: f64 = 0.4;

/// Unit roundoff of f32, `2⁻²⁴` (half an ulp of 1, relative).
pub const F32_ROUNDOFF: f64 = f32::EPSILON as f64 / 2.0;

/// Largest relative growth of the kinetic energy accepted (the issue's bound).
pub const ENERGY_RELATIVE: f64 = 1e-6;

/// Relative tolerance of the ball–ball Coulomb cone, `64 u` (module docs).
pub const CONE_RELATIVE: f64 = 64.0 * F32_ROUNDOFF;

/// Absolute tolerance of a derived quantity, in units of `u ×` its speed scale
/// (module docs).
pub const DERIVED_ROUNDOFFS: f64 = 32.0;

/// One physical invariant (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Invariant {
    /// Total kinetic energy does not grow (relative 1e-6).
    Energy,
    /// Ball–ball normal impulse `J_n ≥ 0`.
    BallNormal,
    /// Ball–ball friction impulse in its Coulomb cone, `|J_t| ≤ μ_max J_n`.
    BallCone,
    /// Table normal impulse on the object ball `N_o ≥ 0`.
    ObjectTableNormal,
    /// Table friction on the object ball in its cone, `|T_o| ≤ μ_s N_o`.
    ObjectTableCone,
    /// Table normal impulse on the cue ball `N_c ≥ 0`.
    CueTableNormal,
    /// Table friction on the cue ball in its cone, `|C| ≤ μ_ct N_c`.
    CueTableCone,
    /// The balls do not move into each other: `V'_x − U'_x ≥ 0`.
    Approach,
    /// The object ball does not move into the table: `V'_z ≥ 0`.
    ObjectIntoTable,
    /// The cue ball does not move into the table: `U'_z ≥ 0`.
    CueIntoTable,
    /// The spins are those the impulses' torques give (`I Δω = Σ r × J`).
    Impulses,
    /// The reported object-ball table friction is the one its momentum shows.
    ReportedTableFriction,
}

impl Invariant {
    /// Every invariant, in table order.
    pub const ALL: [Invariant; 12] = [
        Invariant::Energy,
        Invariant::BallNormal,
        Invariant::BallCone,
        Invariant::ObjectTableNormal,
        Invariant::ObjectTableCone,
        Invariant::CueTableNormal,
        Invariant::CueTableCone,
        Invariant::Approach,
        Invariant::ObjectIntoTable,
        Invariant::CueIntoTable,
        Invariant::Impulses,
        Invariant::ReportedTableFriction,
    ];

    /// Short name for tables.
    pub const fn name(self) -> &'static str {
        match self {
            Invariant::Energy => "energy",
            Invariant::BallNormal => "ball normal >= 0",
            Invariant::BallCone => "ball-ball cone",
            Invariant::ObjectTableNormal => "object table normal >= 0",
            Invariant::ObjectTableCone => "object table cone",
            Invariant::CueTableNormal => "cue table normal >= 0",
            Invariant::CueTableCone => "cue table cone",
            Invariant::Approach => "balls separate",
            Invariant::ObjectIntoTable => "object v_z >= 0",
            Invariant::CueIntoTable => "cue v_z >= 0",
            Invariant::Impulses => "torque consistency",
            Invariant::ReportedTableFriction => "reported table friction",
        }
    }

    /// Index in [`Invariant::ALL`].
    pub fn index(self) -> usize {
        Self::ALL
            .iter()
            .position(|&i| i == self)
            .expect("every invariant is in ALL")
    }

    /// The unit of [`Violation::size`] for this invariant.
    pub const fn unit(self) -> &'static str {
        match self {
            Invariant::Energy => "E",
            Invariant::Approach | Invariant::ObjectIntoTable | Invariant::CueIntoTable => "U",
            _ => "M U",
        }
    }
}

/// One broken invariant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Violation {
    /// Which.
    pub invariant: Invariant,
    /// The checked quantity (SI: J, N·s or m/s; see [`Measures`]).
    pub value: f64,
    /// Its limit (same unit), tolerance not included: the quantity must be at most
    /// (energy, cones, residuals) or at least (signs) this.
    pub limit: f64,
    /// How far past the limit, tolerance not subtracted, in units of the scene
    /// ([`Invariant::unit`]: `E`, `M U` or `U`); always > 0.
    pub size: f64,
}

/// Every quantity the checks use, for one outcome (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measures {
    /// Cue-ball speed before the impact `U` (m/s).
    pub speed: f64,
    /// Ball mass `M` (kg).
    pub mass: f64,
    /// Kinetic energy before (J).
    pub energy_before: f64,
    /// Kinetic energy after (J).
    pub energy_after: f64,
    /// Reported ball–ball normal impulse `J_n` (N·s).
    pub normal: f64,
    /// Reported ball–ball friction impulse size `|J_t|` (N·s).
    pub friction: f64,
    /// Largest ball–ball μ the law allows.
    pub mu_max: f64,
    /// Object-ball table friction `(T_x, T_y)` (N·s), from its linear momentum.
    pub object_table_friction: [f64; 2],
    /// Object-ball table normal impulse `N_o` (N·s).
    pub object_table_normal: f64,
    /// Cue-ball table friction `(C_x, C_y)` (N·s).
    pub cue_table_friction: [f64; 2],
    /// Cue-ball table normal impulse `N_c` (N·s).
    pub cue_table_normal: f64,
    /// Normal relative velocity after the impact `V'_x − U'_x` (m/s).
    pub separation: f64,
    /// Vertical velocities after the impact `(U'_z, V'_z)` (m/s).
    pub vertical: [f64; 2],
    /// Largest component of `(I Δω − Σ r × J)/R` over both balls (N·s).
    pub torque_residual: f64,
    /// Reported object-ball table friction size (N·s).
    pub reported_table_friction: f64,
    /// Speed scale of the linear checks (m/s).
    pub linear_scale: f64,
    /// Speed scale of the angular residuals (m/s).
    pub angular_scale: f64,
}

fn wide(v: Vec3) -> [f64; 3] {
    [v.x as f64, v.y as f64, v.z as f64]
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Largest value of the ball–ball friction law over all slip speeds `s ≥ 0`.
pub fn mu_max(law: FrictionLaw) -> f64 {
    match law {
        FrictionLaw::Constant(mu) => mu as f64,
        // a + b e^{−cs} is largest at s = 0 for b ≥ 0, and tends to a for b < 0 (not
        // accepted by the core, covered anyway).
        FrictionLaw::SpeedDependent { a, b, .. } => a as f64 + (b as f64).max(0.0),
    }
}

/// Kinetic energy (J) of a ball of mass `m` (kg), radius `r` (m), velocity `v` (m/s)
/// and spin `w` (rad/s): `½ m |v|² + ½ ν m r² |ω|²`.
pub fn kinetic_energy(m: f64, r: f64, v: [f64; 3], w: [f64; 3]) -> f64 {
    let (v, w) = (norm(&v), norm(&w));
    0.5 * m * v * v + 0.5 * NU * m * r * r * w * w
}

impl Measures {
    /// Measure `outcome`, the result of `impact` with `params`.
    pub fn of(params: &Params, impact: &Impact, outcome: &Outcome) -> Self {
        let m = params.mass() as f64;
        let r = params.radius() as f64;
        let u0 = wide(impact.velocity());
        let w0 = wide(impact.spin());
        let u1 = wide(outcome.cue_ball.velocity);
        let wc = wide(outcome.cue_ball.spin);
        let v1 = wide(outcome.object_ball.velocity);
        let wo = wide(outcome.object_ball.spin);
        let jn = outcome.impulses.normal as f64;
        let jt = wide(outcome.impulses.friction);
        // The friction impulse's x component is zero by the type's contract; a non-zero
        // one is counted in the ball–ball impulse anyway.
        let j = [jn + jt[0], jt[1], jt[2]];
        let energy_before = kinetic_energy(m, r, u0, w0);
        let energy_after = kinetic_energy(m, r, u1, wc) + kinetic_energy(m, r, v1, wo);
        // Linear momentum: the table impulses.
        let t = [m * v1[0] - j[0], m * v1[1] - j[1]];
        let n_o = m * v1[2] - j[2];
        let c = [m * (u1[0] - u0[0]) + j[0], m * (u1[1] - u0[1]) + j[1]];
        let n_c = m * (u1[2] - u0[2]) + j[2];
        // Angular momentum, divided by R: I Δω / R = ν M R Δω.
        let k = NU * m * r;
        let object_residual = [
            k * wo[0] - t[1],
            k * wo[1] - (j[2] - t[0]),
            k * wo[2] + j[1],
        ];
        let cue_residual = [
            k * (wc[0] - w0[0]) - c[1],
            k * (wc[1] - w0[1]) - (j[2] - c[0]),
            k * (wc[2] - w0[2]) + j[1],
        ];
        let torque_residual = object_residual
            .iter()
            .chain(cue_residual.iter())
            .fold(0.0f64, |a, x| a.max(x.abs()));
        let linear_scale = norm(&u0) + norm(&u1) + norm(&v1) + (jn.abs() + norm(&jt)) / m;
        let angular_scale = linear_scale + NU * r * (norm(&w0) + norm(&wc) + norm(&wo));
        Self {
            speed: norm(&u0),
            mass: m,
            energy_before,
            energy_after,
            normal: jn,
            friction: norm(&jt[1..]).hypot(jt[0]),
            mu_max: mu_max(params.friction_law()),
            object_table_friction: t,
            object_table_normal: n_o,
            cue_table_friction: c,
            cue_table_normal: n_c,
            separation: v1[0] - u1[0],
            vertical: [u1[2], v1[2]],
            torque_residual,
            reported_table_friction: outcome.impulses.table_friction as f64,
            linear_scale,
            angular_scale,
        }
    }

    /// Absolute tolerance of a derived velocity (m/s).
    pub fn velocity_tolerance(&self) -> f64 {
        DERIVED_ROUNDOFFS * F32_ROUNDOFF * self.linear_scale
    }

    /// Absolute tolerance of a derived impulse (N·s).
    pub fn impulse_tolerance(&self) -> f64 {
        self.mass * self.velocity_tolerance()
    }

    /// Absolute tolerance of a torque residual (N·s).
    pub fn residual_tolerance(&self) -> f64 {
        2.0 * DERIVED_ROUNDOFFS * F32_ROUNDOFF * self.mass * self.angular_scale
    }

    /// Every check of this outcome, broken or not, with `mu_s` and `mu_ct` the table
    /// coefficients, in [`Invariant::ALL`] order.
    pub fn checks(&self, mu_s: f64, mu_ct: f64) -> [Check; 12] {
        let momentum = self.mass * self.speed;
        let tau = self.impulse_tolerance();
        let sigma = self.velocity_tolerance();
        let check = |invariant: Invariant, value: f64, limit: f64, slack: f64, unit: f64| Check {
            invariant,
            value,
            limit,
            slack,
            unit,
        };
        let cone = self.mu_max * self.normal.max(0.0);
        [
            check(
                Invariant::Energy,
                self.energy_after,
                self.energy_before,
                self.energy_before * ENERGY_RELATIVE,
                self.energy_before,
            ),
            // Signs as upper bounds on the negated quantity.
            check(Invariant::BallNormal, -self.normal, 0.0, 0.0, momentum),
            check(
                Invariant::BallCone,
                self.friction,
                cone,
                cone * CONE_RELATIVE,
                momentum,
            ),
            check(
                Invariant::ObjectTableNormal,
                -self.object_table_normal,
                0.0,
                tau,
                momentum,
            ),
            check(
                Invariant::ObjectTableCone,
                norm(&self.object_table_friction),
                mu_s * self.object_table_normal.max(0.0),
                (1.0 + mu_s) * tau,
                momentum,
            ),
            check(
                Invariant::CueTableNormal,
                -self.cue_table_normal,
                0.0,
                tau,
                momentum,
            ),
            check(
                Invariant::CueTableCone,
                norm(&self.cue_table_friction),
                mu_ct * self.cue_table_normal.max(0.0),
                (1.0 + mu_ct) * tau,
                momentum,
            ),
            check(
                Invariant::Approach,
                -self.separation,
                0.0,
                sigma,
                self.speed,
            ),
            check(
                Invariant::ObjectIntoTable,
                -self.vertical[1],
                0.0,
                sigma,
                self.speed,
            ),
            check(
                Invariant::CueIntoTable,
                -self.vertical[0],
                0.0,
                sigma,
                self.speed,
            ),
            check(
                Invariant::Impulses,
                self.torque_residual,
                0.0,
                self.residual_tolerance(),
                momentum,
            ),
            check(
                Invariant::ReportedTableFriction,
                (self.reported_table_friction - norm(&self.object_table_friction)).abs(),
                0.0,
                2.0 * tau,
                momentum,
            ),
        ]
    }

    /// The invariants this outcome breaks (see [`Measures::checks`]).
    pub fn violations(&self, mu_s: f64, mu_ct: f64) -> Vec<Violation> {
        self.checks(mu_s, mu_ct)
            .iter()
            .filter_map(Check::violation)
            .collect()
    }
}

/// One check: `value ≤ limit + slack` must hold (a sign condition `x ≥ 0` is checked
/// as `−x ≤ 0`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Check {
    /// Which invariant.
    pub invariant: Invariant,
    /// The checked quantity (SI).
    pub value: f64,
    /// Its physical limit (SI).
    pub limit: f64,
    /// The rounding tolerance (SI, ≥ 0; module docs).
    pub slack: f64,
    /// The scene's unit of this quantity ([`Invariant::unit`], SI).
    pub unit: f64,
}

impl Check {
    /// `true` when the invariant holds within its tolerance (a NaN fails).
    pub fn holds(&self) -> bool {
        self.value <= self.limit + self.slack
    }

    /// How far past its limit, in the scene's unit (negative: inside).
    pub fn excess(&self) -> f64 {
        (self.value - self.limit) / self.unit
    }

    /// How much of the rounding tolerance is used: `(value − limit)/slack` past the
    /// limit, 0 inside it (≤ 1 holds; +∞ past a zero tolerance; NaN for a NaN).
    pub fn tolerance_used(&self) -> f64 {
        let over = self.value - self.limit;
        if over <= 0.0 {
            0.0
        } else {
            over / self.slack
        }
    }

    /// The violation, if the check fails.
    pub fn violation(&self) -> Option<Violation> {
        (!self.holds()).then(|| Violation {
            invariant: self.invariant,
            value: self.value,
            limit: self.limit,
            size: self.excess(),
        })
    }
}

/// The invariants `outcome` (the result of `impact` with `params`) breaks; empty when
/// it is physical. See the module docs for each check and its tolerance.
pub fn check(params: &Params, impact: &Impact, outcome: &Outcome) -> Vec<Violation> {
    Measures::of(params, impact, outcome)
        .violations(params.mu_s() as f64, params.cue_table_friction() as f64)
}

/// The `cuesight collide` command line (`--flag=value` form, so that negative values
/// parse) for `model` on the scene given by its speed (m/s), cut (degrees), spin
/// (rad/s) and `params`; `None` when the CLI cannot express the scene (cue-ball/table
/// friction μ_ct > 0 has no flag).
pub fn collide_command(
    speed: f32,
    cut_deg: f32,
    spin: [f32; 3],
    params: &Params,
    model: Model,
) -> Option<String> {
    if params.cue_table_friction() != 0.0 {
        return None;
    }
    let law = match params.friction_law() {
        FrictionLaw::Constant(mu) => format!("--mu={mu}"),
        FrictionLaw::SpeedDependent { a, b, c } => format!("--mu={a} --mu-b={b} --mu-c={c}"),
    };
    let model = match model {
        Model::Auto { tolerance } => format!("--model=auto --tolerance={tolerance}"),
        other => format!("--model={}", other.name()),
    };
    Some(format!(
        "cuesight collide --speed={speed} --cut={cut_deg} --spin={},{},{} {law} \
         --restitution={} --mu-s={} --radius={} --mass={} {model}",
        spin[0],
        spin[1],
        spin[2],
        params.restitution(),
        params.mu_s(),
        params.radius(),
        params.mass(),
    ))
}

/// The parameters and impact `cuesight collide` builds from the values of
/// [`collide_command`] (the link's validation, as the CLI does), so that a repro can be
/// checked to show the violation it is quoted for.
pub fn cli_inputs(
    speed: f32,
    cut_deg: f32,
    spin: [f32; 3],
    params: &Params,
) -> Option<(Params, Impact)> {
    use cuesight_link::request::{law_components, Collide, Defaults};
    if params.cue_table_friction() != 0.0 {
        return None;
    }
    let (a, b, c) = law_components(params.friction_law());
    let request = Collide {
        speed,
        cut: cut_deg,
        spin: Some(spin),
        roll: false,
        mu: Some(a),
        mu_b: Some(b),
        mu_c: Some(c),
        restitution: Some(params.restitution()),
        mu_s: Some(params.mu_s()),
        radius: Some(params.radius()),
        mass: Some(params.mass()),
        model: None,
    };
    let prepared = request.prepare(&Defaults::POOL).ok()?;
    Some((prepared.params, prepared.impact))
}
