//! The run-up's angle-domain order analysis (`solver::signal::runup_orders`) on a
//! synthetic run-up whose orders are known in closed form: a linear speed
//! ramp q(t) = a t²/2 and a wheel bearing force with a mesh order, its
//! per-wheel-revolution modulation (the lightweight wheel's hole family and
//! side bands) and a low order.

use solver::signal::runup_orders::marked_orders;
use solver::signal::runup_orders::{line_amplitude, windows};
use std::f64::consts::PI;

const Z: [usize; 2] = [20, 43];

/// y(q) = A₁ cos(o₁ q) (1 + m cos(n r q)) + A₀ cos(n r q + 0.3) over the
/// pinion rotation q, r = z₁/z₂, o₁ = z₁, n = 3: the side bands z₁ ± n r
/// carry A₁ m / 2 each, the hole order n r carries A₀.
fn signal(q: f64, a1: f64, m: f64, a0: f64) -> f64 {
    let r = Z[0] as f64 / Z[1] as f64;
    let o = 3.0 * r * q;
    a1 * (Z[0] as f64 * q).cos() * (1.0 + m * o.cos()) + a0 * (o + 0.3).cos()
}

#[test]
fn dft_line_of_a_sampled_cosine_is_its_amplitude() {
    let n = 43 * 32;
    let y: Vec<f64> = (0..n)
        .map(|j| 2.5 * (2.0 * PI * 86.0 * j as f64 / n as f64 - 1.1).cos())
        .collect();
    assert!((line_amplitude(&y, 86) - 2.5).abs() < 1e-10);
    assert!(line_amplitude(&y, 85) < 1e-10);
    assert!(line_amplitude(&y, 3) < 1e-10);
}

#[test]
fn ramp_runup_orders_recover_mesh_order_side_bands_and_hole_order() {
    // 0 -> 1100 rpm in 1.1 s, recorded at 1e-5 s as the multibody does.
    let a = 1100.0 * PI / 30.0 / 1.1;
    let dt = 1e-5;
    let n = (1.1 / dt) as usize + 1;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
    let q: Vec<f64> = t.iter().map(|t| 0.5 * a * t * t).collect();
    let (a1, m, a0) = (400.0, 0.2, 30.0);
    // The force along a fixed direction (3, 4, 0)/5: the resultant of the
    // components' amplitudes is the signal's.
    let force: Vec<[f64; 3]> = q
        .iter()
        .map(|&q| {
            let y = signal(q, a1, m, a0);
            [0.6 * y, 0.8 * y, 0.0]
        })
        .collect();
    let marks = marked_orders(Z[0], Z[1], 3);
    let w = windows(&t, &q, &force, Z, 32 * Z[1], &marks);
    // 10.1 pinion revolutions = 4.7 wheel revolutions: windows every half.
    assert_eq!(w.len(), 8, "windows: {}", w.len());
    // The resampling interpolates the trace linearly between steps: at
    // 1100 rpm and 1e-5 s, order 20 turns 0.023 rad per step, an error up
    // to (0.023)²/8 = 6.6e-5 of the amplitude.
    let tol = 1e-4 * a1;
    let at = |win: &formats::summaries::RunupOrderWindow, label: &str| {
        win.marked
            .iter()
            .find(|x| x.label == label)
            .unwrap()
            .wheel_bearing_force_n
    };
    for win in &w {
        // Mean speed: the ramp's speed at the window's mean time.
        let want = a * 0.5 * (win.time_s[0] + win.time_s[1]) * 30.0 / PI;
        assert!(
            (win.mean_pinion_rpm - want).abs() < 1e-3 * want,
            "mean speed {} against {want}",
            win.mean_pinion_rpm
        );
        assert!((at(win, "20") - a1).abs() < tol, "20: {}", at(win, "20"));
        for sb in ["20-1.40", "20+1.40"] {
            assert!(
                (at(win, sb) - 0.5 * a1 * m).abs() < tol,
                "{sb}: {}",
                at(win, sb)
            );
        }
        assert!((at(win, "3·20/43") - a0).abs() < tol);
        assert!(at(win, "40") < tol, "40: {}", at(win, "40"));
    }
}
