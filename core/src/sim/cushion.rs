//! Ball–cushion rebound: Han 2005, closed form, impulsive.
//!
//! I. Han, *Dynamics in carom and three cushion billiards*, J. Mech. Sci. Technol.
//! 19 (4), 976–984 (2005), eqs. (14)–(23), as pooltool 0.6 implements them
//! (`pooltool/physics/resolve/ball_cushion/han_2005/model.py`).
//!
//! The cushion's nose touches the ball at height `h` above the cloth (`R < h < 2R`), so
//! the contact normal is tilted down by `θ = asin(h/R − 1)` from the horizontal. In the
//! cushion frame (`x` the horizontal normal into the cushion, `y = ẑ × x`, `z` up) the
//! contact's slip before the impact is (eq. 14; `v_z = 0`, the ball on the cloth)
//!
//! * `s_x = v_x sin θ + R ω_y`, `s_y = −v_y − R ω_z cos θ + R ω_x sin θ`,
//! * the normal approach `c = v_x cos θ` (m/s),
//!
//! the normal impulse that ends the impact `P_zE = (1 + e) M c` (eqs. 16–17; restitution
//! `e` on the normal velocity) and the tangential impulse that would stop the slip
//! `|s| / A`, `A = 7 / (2M)` (a sphere's tangential compliance at its surface). If that is
//! within the Coulomb cone `μ P_zE` the contact grips (eq. 18: `P_xE = s_x/A`, `P_yE =
//! s_y/A`), else it slides (eq. 19: `μ P_zE` against the slip). Rotated to the cushion
//! frame (eqs. 21–22) the impulses `P_X`, `P_Y`, `P_Z` change the horizontal velocity by
//! `P/M` and the spin by `R/I` times the moment (eq. 23; `I = ν M R²`). The vertical
//! velocity the impulse would give is dropped, as in pooltool: the ball stays on the
//! cloth (a jump off the cushion is not modelled).
//!
//! The impulses are all per unit mass here (`M = 1`): the rebound does not depend on it.

use crate::error::{check, Error, Field, Result};
use crate::math;
use crate::vector::Vec3;
use crate::NU;

/// A cushion: restitution, ball–cushion friction and the nose height.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Cushion {
    restitution: f32,
    friction: f32,
    height: f32,
}

impl Cushion {
    /// Pool cushions (pooltool 0.6 `POOL_GENERIC`: `e_c` 0.85, `f_c` 0.2, nose at
    /// `0.64 × 2R` = 36.6 mm for 57.15 mm balls).
    pub const POOL: Self = Self {
        restitution: 0.85,
        friction: 0.2,
        height: 0.036576,
    };
    /// Carom cushions (pooltool 0.6 `BILLIARD_GENERIC`/`BILLIARD_WIP`: `e_c` 0.85, `f_c`
    /// 0.15, nose at 37 mm for 61.5 mm balls).
    pub const CAROM: Self = Self {
        restitution: 0.85,
        friction: 0.15,
        height: 0.037,
    };
    /// Snooker cushions: pool's restitution and friction and the same nose height in
    /// radii (`1.28 R` = 33.6 mm for 52.5 mm balls). An assumption, not a measured
    /// figure: pooltool's snooker heights (28 mm in 0.6, 39 mm since) disagree with
    /// each other.
    pub const SNOOKER: Self = Self {
        restitution: 0.85,
        friction: 0.2,
        height: 0.0336,
    };

    /// A cushion of restitution `restitution` and friction `friction` (each in `[0, 1]`)
    /// whose nose is `height` (m) above the cloth; [`Field::Cushion`] names the one out
    /// of range. The height must lie within `[R, 2R)` of the balls it meets
    /// ([`Cushion::check_height`]).
    pub fn new(restitution: f32, friction: f32, height: f32) -> Result<Self> {
        Ok(Self {
            restitution: check(Field::Cushion, restitution, 0.0, 1.0, false)?,
            friction: check(Field::Cushion, friction, 0.0, 1.0, false)?,
            height: check(Field::Cushion, height, 0.0, 2.0, true)?,
        })
    }

    /// Restitution `e_c` on the normal velocity.
    pub const fn restitution(&self) -> f32 {
        self.restitution
    }
    /// Ball–cushion friction `f_c`.
    pub const fn friction(&self) -> f32 {
        self.friction
    }
    /// Nose height above the cloth (m).
    pub const fn height(&self) -> f32 {
        self.height
    }

    /// `Ok` when the nose meets balls of `radius` (m) on their upper half: `R ≤ h < 2R`.
    pub fn check_height(&self, radius: f32) -> Result<()> {
        if self.height >= radius && self.height < 2.0 * radius {
            Ok(())
        } else {
            Err(Error::OutOfRange {
                field: Field::Cushion,
                value: self.height,
            })
        }
    }

    /// Velocity and spin after the ball hits this cushion, whose horizontal unit normal
    /// `normal` points into the cushion (away from the cloth). `velocity` (m/s, its
    /// horizontal part is used) must have a positive component along `normal`; the
    /// result's is `−e` times it times `cos² θ` plus the friction's share. Returns the
    /// velocity (horizontal) and the spin (rad/s).
    pub(crate) fn rebound(
        &self,
        radius: f32,
        velocity: Vec3,
        spin: Vec3,
        normal: Vec3,
    ) -> (Vec3, Vec3) {
        let across = Vec3::new(-normal.y, normal.x, 0.0); // ẑ × normal
        let (v_x, v_y) = (velocity.dot(normal), velocity.dot(across));
        let (w_x, w_y, w_z) = (spin.dot(normal), spin.dot(across), spin.z);
        // θ from the nose height; the caller checked R ≤ h < 2R.
        let sin_theta = self.height / radius - 1.0;
        let cos_theta = math::sqrt(1.0 - sin_theta * sin_theta);
        // Eq. 14: slip at the contact, and the normal approach (per unit mass: M = 1).
        let slip_x = v_x * sin_theta + radius * w_y;
        let slip_y = -v_y - radius * w_z * cos_theta + radius * w_x * sin_theta;
        let approach = v_x * cos_theta;
        // Eqs. 16–17: the compression-plus-restitution normal impulse and the tangential
        // compliance A = 1/M + R²/I = (1 + 1/ν)/M.
        let normal_impulse = (1.0 + self.restitution) * approach;
        let compliance = 1.0 + 1.0 / NU;
        let slip = math::sqrt(slip_x * slip_x + slip_y * slip_y);
        // Eqs. 18–19: grip if stopping the slip fits in the Coulomb cone, else slide.
        let (p_xe, p_ye) = if slip <= compliance * self.friction * normal_impulse {
            (slip_x / compliance, slip_y / compliance)
        } else {
            let scale = self.friction * normal_impulse / slip;
            (slip_x * scale, slip_y * scale)
        };
        // Eqs. 21–22: from the contact frame to the cushion frame.
        let p_x = -p_xe * sin_theta - normal_impulse * cos_theta;
        let p_y = p_ye;
        let p_z = p_xe * cos_theta - normal_impulse * sin_theta;
        // Eq. 23 (I/M = ν R²): the moment of each impulse about the centre.
        let spin_gain = 1.0 / (NU * radius);
        let v_x = v_x + p_x;
        let v_y = v_y + p_y;
        let w_x = w_x - spin_gain * p_y * sin_theta;
        let w_y = w_y + spin_gain * (p_x * sin_theta - p_z * cos_theta);
        let w_z = w_z + spin_gain * p_y * cos_theta;
        (
            normal * v_x + across * v_y,
            normal * w_x + across * w_y + Vec3::new(0.0, 0.0, w_z),
        )
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    type V = [f64; 3];
    fn add(a: V, b: V) -> V {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }
    fn scale(a: V, k: f64) -> V {
        [a[0] * k, a[1] * k, a[2] * k]
    }
    fn dot(a: V, b: V) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    fn cross(a: V, b: V) -> V {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// The same impact from vector mechanics, without Han's component equations: the
    /// nose touches the ball at `r_c = R (cos θ n̂ + sin θ ẑ)` from its centre; the
    /// contact point's velocity is `u = v + ω × r_c`; an impulse `P` there changes it
    /// by `P/M` along the normal `r̂_c` and by `(1/M + R²/I) P` across it (a sphere);
    /// the normal impulse is `(1 + e) M` times the approach `u · r̂_c`, the tangential
    /// one stops the tangential slip if that fits in the Coulomb cone, else is `μ` times
    /// the normal one against the slip; `Δv = P/M` without its vertical part (the cloth
    /// takes it), `Δω = r_c × P / I`. Per unit mass, f64.
    fn reference(cushion: &Cushion, radius: f64, v: V, w: V, n: V) -> (V, V, bool) {
        let sin_theta = f64::from(cushion.height) / radius - 1.0;
        let cos_theta = (1.0 - sin_theta * sin_theta).sqrt();
        let r_hat = add(scale(n, cos_theta), [0.0, 0.0, sin_theta]);
        let r_c = scale(r_hat, radius);
        let u = add(v, cross(w, r_c));
        let approach = dot(u, r_hat);
        assert!(approach > 0.0);
        let normal = (1.0 + f64::from(cushion.restitution)) * approach;
        let tangential = add(u, scale(r_hat, -approach));
        let slip = dot(tangential, tangential).sqrt();
        let compliance = 1.0 + 1.0 / f64::from(NU);
        let friction = f64::from(cushion.friction);
        let grips = slip <= compliance * friction * normal;
        let p_t = if grips {
            scale(tangential, -1.0 / compliance)
        } else {
            scale(tangential, -friction * normal / slip)
        };
        let p = add(scale(r_hat, -normal), p_t);
        let v_after = [v[0] + p[0], v[1] + p[1], 0.0];
        let w_after = add(
            w,
            scale(cross(r_c, p), 1.0 / (f64::from(NU) * radius * radius)),
        );
        (v_after, w_after, grips)
    }

    /// Han's components against the vector form, over incidence angles, speeds, spins
    /// (follow, draw, side, both), cushions (pool, carom, a high and a low nose, no
    /// friction, dead and perfectly elastic) and normals in every direction: gripping and
    /// sliding contacts both occur.
    #[test]
    fn han_components_agree_with_the_vector_mechanics_of_the_same_impact() {
        let radius = 0.028575f32;
        let cushions = [
            Cushion::POOL,
            Cushion::new(0.85, 0.15, 0.037 * radius / 0.03075).unwrap(),
            Cushion::new(0.5, 0.6, 1.9 * radius).unwrap(),
            Cushion::new(1.0, 0.0, 1.05 * radius).unwrap(),
            Cushion::new(0.0, 1.0, 1.28 * radius).unwrap(),
        ];
        let (mut worst, mut grips, mut slides) = (0.0f64, 0, 0);
        for cushion in &cushions {
            for normal_angle in [0.0f32, 1.0, 2.5, 4.0] {
                let n = Vec3::new(math::cos(normal_angle), math::sin(normal_angle), 0.0);
                let t = Vec3::new(-n.y, n.x, 0.0);
                for incidence in [0.0f32, 0.3, 0.8, 1.2, 1.5] {
                    for speed in [0.1f32, 1.0, 4.0] {
                        let v = (n * math::cos(incidence) + t * math::sin(incidence)) * speed;
                        for (top, side) in [
                            (0.0f32, 0.0f32),
                            (1.0, 0.0),
                            (-1.0, 0.0),
                            (0.0, 1.0),
                            (0.5, -1.5),
                        ] {
                            // Natural roll along v is ẑ × v / R; add side spin about z.
                            let roll = Vec3::new(-v.y, v.x, 0.0) * (1.0 / radius);
                            let w = roll * top + Vec3::new(0.0, 0.0, side * speed / radius);
                            let (v1, w1) = cushion.rebound(radius, v, w, n);
                            let f = |a: Vec3| [f64::from(a.x), f64::from(a.y), f64::from(a.z)];
                            let (rv, rw, gripped) =
                                reference(cushion, f64::from(radius), f(v), f(w), f(n));
                            let error_v =
                                (0..3).map(|k| (f(v1)[k] - rv[k]).abs()).fold(0.0, f64::max);
                            let error_w =
                                (0..3).map(|k| (f(w1)[k] - rw[k]).abs()).fold(0.0, f64::max);
                            let error = (error_v + f64::from(radius) * error_w) / f64::from(speed);
                            worst = worst.max(error);
                            assert!(error < 2e-6, "{cushion:?} n {n:?} v {v:?} w {w:?}: {v1:?} {w1:?} vs {rv:?} {rw:?}");
                            if gripped {
                                grips += 1
                            } else {
                                slides += 1
                            }
                        }
                    }
                }
            }
        }
        std::println!("worst {worst:.2e} of the speed; {grips} gripping, {slides} sliding");
        cuesight_figures::record!("table-han-vector-agreement", "{worst:.1e}");
        cuesight_figures::record!("table-han-impacts", "{}", grips + slides);
        cuesight_figures::record!("table-han-gripping", "{grips}");
        assert!(grips > 50 && slides > 50, "{grips} {slides}");
    }

    /// A ball straight into a frictionless cushion: the normal impulse along the tilted
    /// normal, `(1 + e) v cos θ`, has the horizontal part `(1 + e) v cos² θ` (eqs. 21–23),
    /// so it leaves at `v (1 − (1 + e) cos² θ)`: slower than `e v` because the nose
    /// pushes it partly into the cloth (θ = 16.3° on pool cushions: 0.70 v, not 0.85 v).
    #[test]
    fn a_head_on_frictionless_rebound_is_one_minus_one_plus_e_cos_squared_theta() {
        let radius = 0.028575f32;
        let cushion = Cushion::new(0.85, 0.0, 1.28 * radius).unwrap();
        let n = Vec3::new(1.0, 0.0, 0.0);
        let (v1, _) = cushion.rebound(radius, Vec3::new(2.0, 0.0, 0.0), Vec3::ZERO, n);
        let sin_theta = 0.28f32;
        let expected = 2.0 * (1.0 - 1.85 * (1.0 - sin_theta * sin_theta));
        assert!(
            (v1.x - expected).abs() < 1e-5 && v1.y.abs() < 1e-6,
            "{v1:?} vs {expected}"
        );
    }
}
