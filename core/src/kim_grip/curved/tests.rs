extern crate std;

use super::*;
use crate::kim_grip::nu;

/// The slip's path length under sliding friction, `S = ∫₀^∞ |u(t)| dt` with `u_i(t) =
/// u_i0 e^{−k_i t}` (the slip obeys `du/dS = −K û`; with `dt = dS/|u|` each component
/// decays on its own), by composite Simpson on `[0, 40/k_min]` (the rest is below
/// `e^{−40}`).
fn sliding_path_length(k: [f64; 2], u0: [f64; 2]) -> f64 {
    const INTERVALS: usize = 4000;
    let end = 40.0 / k[0].min(k[1]);
    let h = end / INTERVALS as f64;
    let speed = |t: f64| {
        let (y, z) = (u0[0] * (-k[0] * t).exp(), u0[1] * (-k[1] * t).exp());
        (y * y + z * z).sqrt()
    };
    (0..INTERVALS)
        .map(|i| {
            let a = i as f64 * h;
            h / 6.0 * (speed(a) + 4.0 * speed(a + h / 2.0) + speed(a + h))
        })
        .sum()
}

/// The largest relative error of the grip threshold `s* = |K⁻¹ u₀|` against the
/// sliding path's length over slip directions 0°–90° (1° apart), for `K = diag(k_y,
/// k_z)`.
fn worst_grip_threshold_error(k_z: f64) -> f64 {
    let k = [k_y::<f64>(), k_z];
    (0..=90)
        .map(|degrees| {
            let angle = f64::from(degrees).to_radians();
            let u0 = [angle.cos(), angle.sin()];
            let s_star = (u0[0] / k[0]).hypot(u0[1] / k[1]);
            (s_star / sliding_path_length(k, u0) - 1.0).abs()
        })
        .fold(0.0, f64::max)
}

/// docs/physics.md §4 item 3: `s* = |j_stick|` is the friction budget that stops the
/// slip exactly for an isotropic `K`, and within a stated error for the anisotropic
/// one of a pressed object ball (`k_z = (2+ν−μ_s)/ν`, `k_y/k_z` from 7/6 at μ_s = 0 to
/// 1.4 at μ_s = 0.4).
#[test]
fn grip_threshold_is_the_sliding_path_length_within_its_stated_error() {
    let nu = nu::<f64>();
    let k_z = |mu_s: f64| (2.0 + nu - mu_s) / nu;
    let isotropic = worst_grip_threshold_error(k_y::<f64>());
    assert!(isotropic < 1e-9, "isotropic K: {isotropic:e}");
    let at_0 = worst_grip_threshold_error(k_z(0.0));
    let at_0_4 = worst_grip_threshold_error(k_z(0.4));
    // The error grows with the anisotropy, and stays within 1.3 % at k_y/k_z = 1.4.
    assert!(isotropic < at_0 && at_0 < at_0_4, "{at_0} {at_0_4}");
    assert!(at_0_4 <= 0.013, "μ_s = 0.4: {at_0_4}");
    cuesight_figures::record!(
        "physics-kimgrip-grip-threshold-error-mu-s-0",
        "{:.2}",
        at_0 * 100.0
    );
    cuesight_figures::record!(
        "physics-kimgrip-grip-threshold-error-mu-s-0-4",
        "{:.2}",
        at_0_4 * 100.0
    );
}

/// The exact slide `du/dS = −K û` from `u0`, `K = diag(k_y, k_z)`, tabulated: with
/// `dt = dS/|u|` each slip component decays on its own, `u_i(t) = u_i0 e^{−k_i t}`, so the
/// impulse is `J(t) = K⁻¹(u(t) − u0)` exactly and only the budget `S(t) = ∫₀^t |u|` needs
/// quadrature (Simpson on each of `INTERVALS` steps of `[0, 40/k_min]`). Independent of
/// the pieces: no mid-point direction, no stick budget.
struct ExactSlide {
    k: [f64; 2],
    u0: [f64; 2],
    step: f64,
    /// `S` at the end of each step.
    budgets: std::vec::Vec<f64>,
}

impl ExactSlide {
    const INTERVALS: usize = 20_000;

    fn new(k: [f64; 2], u0: [f64; 2]) -> Self {
        let step = 40.0 / k[0].min(k[1]) / Self::INTERVALS as f64;
        let speed = |t: f64| (u0[0] * (-k[0] * t).exp()).hypot(u0[1] * (-k[1] * t).exp());
        let mut budget = 0.0;
        let budgets = (0..Self::INTERVALS)
            .map(|i| {
                let a = i as f64 * step;
                budget += step / 6.0 * (speed(a) + 4.0 * speed(a + step / 2.0) + speed(a + step));
                budget
            })
            .collect();
        Self {
            k,
            u0,
            step,
            budgets,
        }
    }

    /// The budget that stops the slip: the sliding path's length.
    fn stop_budget(&self) -> f64 {
        self.budgets[Self::INTERVALS - 1]
    }

    /// `J(S)` for a budget `S` below [`Self::stop_budget`] (`t` interpolated linearly
    /// between the tabulated steps).
    fn impulse(&self, budget: f64) -> [f64; 2] {
        let i = self.budgets.partition_point(|&b| b < budget);
        let (before, after) = (
            if i == 0 { 0.0 } else { self.budgets[i - 1] },
            self.budgets[i],
        );
        let t = (i as f64 + (budget - before) / (after - before)) * self.step;
        let slip = |c: usize| self.u0[c] * (-self.k[c] * t).exp();
        [
            (slip(0) - self.u0[0]) / self.k[0],
            (slip(1) - self.u0[1]) / self.k[1],
        ]
    }
}

/// A pressed object ball's `k_z` at `μ_s` (seed eq. (23), erratum E1).
fn pressed_k_z(mu_s: f64) -> f64 {
    (2.0 + nu::<f64>() - mu_s) / nu::<f64>()
}

/// Slip directions with `u_z > 0` (pressed), 2° apart from 1° to 179°.
fn pressed_directions() -> impl Iterator<Item = [f64; 2]> {
    (0..90).map(|i| {
        let angle = (1.0 + 2.0 * f64::from(i)).to_radians();
        [angle.cos(), angle.sin()]
    })
}

/// The pieces against the exact slide at `μ_s` 0.4–1 (`k_y/k_z` 1.4–2), every pressed
/// slip direction, budgets from a tenth of the stopping budget up to the stop: the
/// impulse within 0.5 % of `|K⁻¹u₀|` (measured 0.06 %; 0.33 % with four halves), where
/// the fast path's single mid-point direction (one piece) is up to 3.4 % off (both
/// recorded for `docs/physics.md` §4).
#[test]
fn curved_slide_follows_the_exact_slide() {
    let (mut pieces_worst, mut single_worst) = (0.0f64, 0.0f64);
    for mu_s in [0.4, 0.6, 0.8, 1.0] {
        let k_z = pressed_k_z(mu_s);
        for u0 in pressed_directions() {
            let exact = ExactSlide::new([7.0, k_z], u0);
            let curved = CurvedSlide::new(u0[0], u0[1], 1.0, 0.0, k_z);
            // The single mid-point direction (the fast path's) is one piece spending it all.
            let stick = curved.stick_budget((u0[0], u0[1]));
            let stick_impulse = curved.inverse((u0[0], u0[1]));
            for tenth in 1..=10 {
                let budget = exact.stop_budget() * f64::from(tenth) / 10.0 * (1.0 - 1e-9);
                let want = exact.impulse(budget);
                let (j_y, j_z) = curved.impulse(budget);
                pieces_worst = pieces_worst.max((j_y - want[0]).hypot(j_z - want[1]) / stick);
                let (y, z) = if budget >= stick {
                    (-stick_impulse.0, -stick_impulse.1)
                } else {
                    curved.piece((u0[0], u0[1]), u0[0].hypot(u0[1]), stick, budget)
                };
                single_worst = single_worst.max((y - want[0]).hypot(z - want[1]) / stick);
            }
        }
    }
    assert!(pieces_worst <= 0.005, "pieces: {pieces_worst}");
    assert!(single_worst > 5.0 * pieces_worst, "single: {single_worst}");
    cuesight_figures::record!(
        "physics-kimgrip-curved-impulse-error",
        "{:.2}",
        pieces_worst * 100.0
    );
    cuesight_figures::record!(
        "physics-kimgrip-single-direction-impulse-error",
        "{:.1}",
        single_worst * 100.0
    );
}

/// The pieces' stopping budget (the grip threshold of the curved slide) against the
/// sliding path's length: within 1 % at `μ_s` 0.4–1 (measured 0.23 %; 0.79 % with four
/// halves), where `s* = |K⁻¹u₀|` is up to 4.3 % short.
#[test]
fn curved_stop_budget_is_the_sliding_path_length() {
    let mut worst = 0.0f64;
    for mu_s in [0.4, 0.6, 0.8, 1.0] {
        let k_z = pressed_k_z(mu_s);
        for u0 in pressed_directions() {
            let curved = CurvedSlide::new(u0[0], u0[1], 1.0, 0.0, k_z);
            let length = sliding_path_length([7.0, k_z], u0);
            worst = worst.max((curved.stop_budget() / length - 1.0).abs());
        }
    }
    assert!(worst <= 0.01, "{worst}");
    cuesight_figures::record!(
        "physics-kimgrip-curved-stop-budget-error",
        "{:.2}",
        worst * 100.0
    );
}

/// At the stopping budget the pieces add up to the stick impulse `−K⁻¹v₀` (no jump
/// across the grip), in any scale, and a zero budget gives no impulse.
#[test]
fn curved_slide_meets_the_stick_impulse_at_its_stop() {
    for (y, z, scale) in [(-0.7f64, 0.5, 2.0), (1.0, 0.02, 0.3), (0.01, 1.0, 5.0)] {
        let k_z = pressed_k_z(0.9);
        let curved = CurvedSlide::new(y, z, scale, 0.0, k_z);
        let stop = curved.stop_budget();
        let stick = [-y / 7.0 * scale, -z / k_z * scale];
        let below = curved.impulse(stop * (1.0 - 1e-9));
        let above = curved.impulse(stop * (1.0 + 1e-9));
        for (j_y, j_z) in [below, above] {
            assert!(
                (j_y - stick[0]).abs() <= 1e-7 * scale,
                "{j_y} vs {}",
                stick[0]
            );
            assert!(
                (j_z - stick[1]).abs() <= 1e-7 * scale,
                "{j_z} vs {}",
                stick[1]
            );
        }
        assert_eq!(curved.impulse(0.0), (0.0, 0.0));
    }
}
