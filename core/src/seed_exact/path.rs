//! The seed's sliding path, eqs. (23)–(30) with erratum E1, and its integrals by
//! fixed-order Gauss–Legendre quadrature.
//!
//! Per unit mass (impulses in m/s; the seed's `p/m` with `m = M/2` is `2p` here). While
//! the contact slides, with the object ball's table friction along `−x` (seed eq. (7)),
//! the tangential slip obeys seed eq. (23) with E1:
//!
//! `dv_y/dp = −k_y μ v_y/|v|`, `dv_z/dp = −k_z μ v_z/|v|`,
//! `k_y = 2β_y = 2(1+ν)/ν = 7`, `k_z = 2β_z = (2+ν−μ_s)/ν` when the object ball is pressed
//! (`v_z0 > 0`, topspin), `(2+ν)/ν = 6` otherwise (dimensionless).
//!
//! Hence `d ln|v_y| / d ln|v_z| = k_y/k_z`: the invariant (24). We parametrise its curve
//! by `ρ ∈ (0, 1]` (ρ = 1 at first contact, 0 where the slip stops):
//!
//! `v_y = v_y0 ρ^{k_y}`, `v_z = v_z0 ρ^{k_z}`, `|v| = |v₀| ρ g(ρ)`,
//! `g(ρ) = √(c_y² ρ¹² + c_z² ρ^{2k_z−2})`, `(c_y, c_z) = v₀/|v₀|`.
//!
//! The seed's variables (26) are `x_k = |v_k/v̄| = x_k0 ρ^{k_k}` (with E1
//! `a_z = k_z/(2(k_y−k_z)) = (2+ν−μ_s)/(2(ν+μ_s))`, `a_y = −k_y/(2(k_y−k_z))`), and its
//! eq. (27) `√(1 + x_k^{1/a_k}) dx_k = −μ β_k dp/(m v̄)` becomes `dp = |v₀| g(ρ) dρ / μ`.
//! So the seed's integrals (29)–(30) and the `F_{2a_z}(x_z²)` term of (33) are
//!
//! * `P(ρ) = ∫_ρ^1 |v₀| g(s)/μ ds` — normal impulse (m/s) at which the slip reaches `ρ`
//!   (eq. (29): `F_{a_z}(x_z0) − F_{a_z}(x_z) = (k_z|v₀|/v̄) ∫_ρ^1 g`);
//! * `I_z(ρ) = ∫_0^{P} v_z dp = ∫_ρ^1 |v₀|² c_z s^{k_z} g(s)/μ ds` (m²/s²) — the
//!   `M v̄² [F_{2a_z}(x_z²) − F_{2a_z}(x_z0²)]/(4μβ_z)` of eqs. (33), (36).
//!
//! Why not the seed's variable `x`: `v̄` is 0 or ∞ when either slip component is zero
//! (head-on top/draw, pure side spin), and `√(1 + x^{1/a})` has an unbounded derivative at
//! `x → 0` (`1/a_z < 1`), which ruins any fixed-order rule near the stick point. In `ρ`
//! the integrand is `ρ^{k_z−1} √(c_y² ρ^{2(k_y−k_z)} + c_z²)`: bounded, smooth on
//! `(0, 1]`, every case alike.
//!
//! A speed-dependent law `μ(|v|)` (TP A.14) keeps the path — `μ` scales both rates of
//! (23) alike, so (24) holds — and only moves along it at another pace: `1/μ` becomes
//! `1/μ(|v₀| ρ g(ρ))` inside both integrals.
//!
//! **Quadrature.** Gauss–Legendre with [`NODES`] = 8 nodes on `[ρ, 1]` (exact for
//! polynomials of degree 15). Its error, against a 64-panel composite of the same rule
//! graded towards `ρ = 0` (test `quadrature_error_is_below_its_stated_bound`, f64, 181
//! slip directions including the axes, `μ_s` 0–0.4, `1 − ρ` from 1e-6 to 1):
//! `|δ∫g| ≤ 2e-8` and `|δ∫c_z ρ^{k_z} g| ≤ 1e-9`, where `∫g ≥ (1 − ρ⁷)/7`; for `μ_s`
//! up to 1 (a non-integer power `ρ^{k_z−1}` as low as `ρ^{2.5}` at the stick point)
//! `≤ 6.6e-7`. Relative to `|v₀|/μ` that is below f32 resolution in the calibrated
//! domain. A speed-dependent law needs more: [`SPEED_DEPENDENT_PANELS`] = 4 panels of 8
//! nodes, relative error ≤ 2.2e-6 for both TP A.14 fits at `c|v₀| ≤ 22` (slips up to
//! 20 m/s, measured offline against the same composite rule); the error grows with
//! `c|v₀|` beyond that.

use crate::friction::FrictionLaw;
use crate::real::Real;

/// Gauss–Legendre nodes per panel.
pub(super) const NODES: usize = 8;

/// Panels for a speed-dependent friction law (one for a constant μ).
pub(super) const SPEED_DEPENDENT_PANELS: usize = 4;

/// 8-point Gauss–Legendre rule mapped to `[0, 1]`: `(t_i, w_i)` with
/// `∫_0^1 f ≈ Σ w_i f(t_i)`; nodes `t = (1 − x)/2`, weights `w/2` of the rule on
/// `[−1, 1]`.
const RULE: [(f64, f64); NODES] = [
    (0.019_855_071_751_231_856, 0.050_614_268_145_188_39),
    (0.101_666_761_293_186_58, 0.111_190_517_226_687_23),
    (0.237_233_795_041_835_5, 0.156_853_322_938_943_7),
    (0.408_282_678_752_175_1, 0.181_341_891_689_181),
    (0.591_717_321_247_824_8, 0.181_341_891_689_181),
    (0.762_766_204_958_164_5, 0.156_853_322_938_943_7),
    (0.898_333_238_706_813_5, 0.111_190_517_226_687_23),
    (0.980_144_928_248_768_2, 0.050_614_268_145_188_39),
];

/// [`RULE`] rounded to `f32` at compile time (what `R::of_f64` gave at run time).
const RULE_F32: [(f32, f32); NODES] = {
    let mut rule = [(0.0, 0.0); NODES];
    let mut i = 0;
    while i < NODES {
        rule[i] = (RULE[i].0 as f32, RULE[i].1 as f32);
        i += 1;
    }
    rule
};

/// `k_y = 2(1+ν)/ν` for `ν = 2/5` (seed eq. (28): `2β_y`).
pub(super) const K_Y: f32 = 7.0;

/// The sliding path of one impact, normalised by the initial slip speed.
pub(super) struct SlipPath<R> {
    /// `|v₀|` (m/s).
    pub speed: R,
    /// `v_z0` (m/s).
    pub slip_z: R,
    /// `c_y² = (v_y0/|v₀|)²`, `c_z = v_z0/|v₀|`.
    cy2: R,
    cz: R,
    /// `ε = 6 − k_z = μ_s/ν` when the object ball is pressed, else 0 (then every power
    /// is an integer one and no transcendental function is needed).
    lean: R,
    /// `k_z = 2β_z` (E1).
    pub k_z: R,
    /// `κ`: the root solves' variable is `w = 1 − ρ^κ`, in which `P` and `X` are nearly
    /// linear: `κ = k_z` (`v_z` outlives `v_y`, as `k_z < k_y`, so near the stick point
    /// `P* − P ∝ ρ^{k_z}`, and `X ∝ 1 − ρ^{k_z}` exactly), `κ = k_y` for a pure side slip
    /// (then `P ∝ 1 − ρ⁷` exactly).
    pub kappa: R,
    law: FrictionLaw,
}

/// Where the slip is after the normal impulse that brings it to `ρ = 1 − q`.
#[derive(Clone, Copy)]
pub(super) struct Point<R> {
    /// `q = 1 − ρ`, in `[0, 1]`.
    pub q: R,
    /// `P`: normal impulse so far (m/s).
    pub normal: R,
    /// `I_z = ∫ v_z dp` so far (m²/s²).
    pub vertical: R,
    /// `dP/dw` (m/s), `w = 1 − ρ^κ`: finite at the stick point.
    pub slope_w: R,
    /// `ρ^{k_y} − 1`: `v_y = v_y0 (1 + this)`, so the friction impulse is
    /// `J_y = v_y0 · this / k_y` (seed eq. (57)).
    pub y_change: R,
    /// `ρ^{k_z} − 1`: `J_z = v_z0 · this / k_z`.
    pub z_change: R,
}

impl<R: Real> SlipPath<R> {
    /// The path from the initial slip `(v_y0, v_z0)` (m/s, not both zero), with the
    /// object ball's table friction `μ_s` acting when it is pressed (`v_z0 > 0`).
    pub fn new(slip_y: R, slip_z: R, mu_s: R, law: FrictionLaw) -> Self {
        let scale = R::max(R::abs(slip_y), R::abs(slip_z));
        let (y, z) = (slip_y / scale, slip_z / scale);
        let norm = R::sqrt(y * y + z * z);
        let (cy, cz) = (y / norm, z / norm);
        // ν = 2/5: k_z = (2 + ν − μ_s)/ν = 6 − μ_s/ν.
        let lean = if slip_z > R::ZERO {
            mu_s * R::of(2.5)
        } else {
            R::ZERO
        };
        let k_z = R::of(6.0) - lean;
        Self {
            speed: norm * scale,
            slip_z,
            cy2: cy * cy,
            cz,
            lean,
            k_z,
            kappa: if cz == R::ZERO { R::of(K_Y) } else { k_z },
            law,
        }
    }

    /// Largest μ on the path: at zero slip (the laws do not increase with speed).
    pub fn mu_max(&self) -> R {
        self.mu(R::ZERO)
    }

    /// Smallest μ on the path: at the initial slip speed `|v₀|`.
    pub fn mu_min(&self) -> R {
        self.mu(self.speed)
    }

    /// `|v₀|/μ_min`, the largest `dP/dq` (m/s); infinite when μ is so small that
    /// the friction cannot change the slip in this precision.
    pub fn max_pace(&self) -> R {
        self.speed / self.mu_min()
    }

    /// `μ` at slip speed `|v|` (m/s), with an accurate `exp` whatever the backend (the
    /// quadrature and the root solves need it smooth).
    fn mu(&self, slip_speed: R) -> R {
        match self.law {
            FrictionLaw::Constant(mu) => R::of(mu),
            FrictionLaw::SpeedDependent { a, b, c } => {
                R::of(a) + R::of(b) * R::exp_accurate(-R::of(c) * slip_speed)
            }
        }
    }

    /// `dP/dw = (|v₀|/μ) g dq/dw`, `dq/dw = ρ^{1−κ}/κ`, from `ρ`, `τ = ρ^ε` and
    /// `pace = |v₀|/μ` (m/s): `g ρ^{1−k_z} = √(c_y² ρ² τ² + c_z²)` for `κ = k_z`, and
    /// `g ρ^{−6} = 1` for a pure side slip.
    fn slope_w(&self, rho: R, tau: R, pace: R) -> R {
        if self.cz == R::ZERO {
            pace / self.kappa
        } else {
            let inner = self.cy2 * rho * rho * tau * tau + self.cz * self.cz;
            pace * R::sqrt(inner) / self.kappa
        }
    }

    /// `g(ρ)` and `ρ^{k_z−1}` from `ρ` and `τ = ρ^ε`.
    fn g(&self, rho: R, tau: R) -> (R, R) {
        let rho2 = rho * rho;
        let z_rate = rho2 * rho2 * rho / tau; // ρ^{5−ε} = ρ^{k_z−1}
        let inner = self.cy2 * rho2 * tau * tau + self.cz * self.cz;
        (z_rate * R::sqrt(inner), z_rate)
    }

    /// `ρ^ε` at a node, `ε = μ_s/ν`.
    fn lean_power(&self, rho: R) -> R {
        if self.lean == R::ZERO {
            R::ONE
        } else {
            R::exp_accurate(self.lean * R::ln_accurate(rho))
        }
    }

    /// `(∫ g/μ, ∫ c_z (ρ^{k_z} − z_ref) g/μ)` over `ρ ∈ [1 − to, 1 − from]`,
    /// dimensionless but for a constant `1/μ` (applied by the caller).
    fn integrals(&self, from: R, to: R, z_ref: R) -> (R, R) {
        let panels = match self.law {
            FrictionLaw::Constant(_) => 1,
            FrictionLaw::SpeedDependent { .. } => SPEED_DEPENDENT_PANELS,
        };
        let width = (to - from) / R::of(panels as f32);
        let (mut normal, mut vertical) = (R::ZERO, R::ZERO);
        for panel in 0..panels {
            // Panel k: nodes ρ = 1 − (from + (k + t) w).
            let start = R::of(panel as f32);
            let (mut n, mut v) = (R::ZERO, R::ZERO);
            for (&(t, w), &(t32, w32)) in RULE.iter().zip(RULE_F32.iter()) {
                let rho = R::ONE - (from + (start + R::of_pair(t, t32)) * width);
                let tau = self.lean_power(rho);
                let (g, z_rate) = self.g(rho, tau);
                let inverse_mu = match self.law {
                    FrictionLaw::Constant(_) => R::ONE,
                    FrictionLaw::SpeedDependent { .. } => R::ONE / self.mu(self.speed * rho * g),
                };
                let weight = R::of_pair(w, w32) * inverse_mu;
                n = n + weight * g;
                // ρ^{k_z} = ρ · ρ^{k_z−1}.
                v = v + weight * self.cz * (rho * z_rate - z_ref) * g;
            }
            normal = normal + n;
            vertical = vertical + v;
        }
        (normal * width, vertical * width)
    }

    /// `(P, ∫ (v_z − v_z,ref) dp)` (m/s, m²/s²) between `q = from` and `q = to`, with
    /// `v_z,ref = v_z0 z_ref`.
    fn impulses_between(&self, from: R, to: R, z_ref: R) -> (R, R) {
        let (normal, vertical) = self.integrals(from, to, z_ref);
        // |v₀|/μ first: at a subnormal μ the reciprocal alone would overflow.
        let pace = match self.law {
            FrictionLaw::Constant(mu) => self.speed / R::of(mu),
            FrictionLaw::SpeedDependent { .. } => self.speed,
        };
        (pace * normal, self.speed * (pace * vertical))
    }

    /// `q = 1 − ρ` for `w = 1 − ρ^κ` (both in `[0, 1]`), without cancellation near 0.
    pub fn q_of_w(&self, w: R) -> R {
        if w >= R::ONE {
            R::ONE
        } else {
            -R::exp_m1_accurate(R::ln_1p_accurate(-w) / self.kappa)
        }
    }

    /// `w = 1 − ρ^κ` where `ρ^{k_y} = 1 − ratio` (`ratio < 1`).
    pub fn w_of_y_ratio(&self, ratio: R) -> R {
        -R::exp_m1_accurate(self.kappa / R::of(K_Y) * R::ln_1p_accurate(-ratio))
    }

    /// The state after the slip has slid from contact to `ρ = 1 − q` (`q ∈ [0, 1]`).
    pub fn point(&self, q: R) -> Point<R> {
        let (normal, vertical) = self.impulses_between(R::ZERO, q, R::ZERO);
        self.at(q, normal, vertical)
    }

    /// The state at `q ≥ c.q`, with the impulses integrated from `c` (so that their
    /// differences keep their digits), and `∫_{c}^{q} (v_z − v_z(c)) dp` (m²/s²): the
    /// table term of the work since `c`, seed eq. (36).
    pub fn point_after(&self, c: &Point<R>, q: R) -> (Point<R>, R) {
        let (normal, lag) = self.impulses_between(c.q, q, R::ONE + c.z_change);
        let vertical = c.vertical + lag + self.slip_z * (R::ONE + c.z_change) * normal;
        (self.at(q, c.normal + normal, vertical), lag)
    }

    /// The slip state at `ρ = 1 − q` with the impulses given.
    fn at(&self, q: R, normal: R, vertical: R) -> Point<R> {
        if q >= R::ONE {
            // The slip has stopped: ρ = 0.
            return Point {
                q: R::ONE,
                normal,
                vertical,
                slope_w: self.slope_w(R::ZERO, R::ZERO, self.speed / self.mu_max()),
                y_change: -R::ONE,
                z_change: -R::ONE,
            };
        }
        let rho = R::ONE - q;
        // ρ^n − 1 = −q (1 + ρ + … + ρ^{n−1}): no cancellation for small q.
        let mut sum6 = R::ZERO;
        let mut power = R::ONE;
        for _ in 0..6 {
            sum6 = sum6 + power;
            power = power * rho;
        }
        let rho6_minus_1 = -q * sum6;
        // ρ⁷ − 1.
        let y_change = -q * (sum6 + power);
        // τ = ρ^ε. Near contact (q < 1/2) τ − 1 = expm1(ε ln(1 − q)) and
        // ρ^{k_z} − 1 = (ρ⁶ − 1 − (τ − 1))/τ keep their digits; nearer the stick point
        // τ itself must (it may be tiny), and ρ^{k_z} − 1 has no cancellation.
        let (tau, z_change) = if self.lean == R::ZERO {
            (R::ONE, rho6_minus_1)
        } else if q < R::of(0.5) {
            let tau_minus_1 = R::exp_m1_accurate(self.lean * R::ln_1p_accurate(-q));
            let tau = R::ONE + tau_minus_1;
            (tau, (rho6_minus_1 - tau_minus_1) / tau)
        } else {
            let tau = R::exp_accurate(self.lean * R::ln_accurate(rho));
            (tau, power / tau - R::ONE) // power = ρ⁶
        };
        let pace = match self.law {
            FrictionLaw::Constant(mu) => self.speed / R::of(mu),
            FrictionLaw::SpeedDependent { .. } => {
                let (g, _) = self.g(rho, tau);
                self.speed / self.mu(self.speed * rho * g)
            }
        };
        Point {
            q,
            normal,
            vertical,
            slope_w: self.slope_w(rho, tau, pace),
            y_change,
            z_change,
        }
    }
}

#[cfg(test)]
mod tests;
