//! Order analysis of a run-up in the pinion's angle domain: the wheel
//! bearing force resampled at uniform pinion rotation and transformed over
//! windows of one wheel revolution, so that every order that repeats per
//! wheel revolution (the mesh orders z₁, 2z₁, the lightweight wheel's hole
//! family n·z₁/z₂ and its side bands z₁ ± n·z₁/z₂) falls on a line however
//! fast the speed changes (a time-domain STFT smears them by the ramp).
//!
//! Window w covers pinion rotation [q_w, q_w + Θ), Θ = 2π z₂/z₁ (one wheel
//! revolution), N samples y_j = y(q_w + jΘ/N); line k (wheel order k,
//! pinion order k z₁/z₂) has the single-sided amplitude
//!
//! ```text
//! A_k = (2/N) |Σ_j y_j e^(−2πi kj/N)|
//! ```
//!
//! per force component; the resultant √(A_x² + A_y² + A_z²) is the number
//! reported (the 8-DOF order map's definition). Rectangular window: a
//! stationary signal's lines are exact; within one window the run-up
//! changes the speed and the amplitudes, which leaks a little into the
//! neighbouring lines.

use crate::signal::spectrum::resample;
use formats::lumped_summary::MarkedOrder;
use formats::summaries::RunupOrderWindow;
use std::f64::consts::PI;

/// Wheel-order DFT line `k` of `y` (one window, N samples): (2/N)|Σ y e^(−2πikj/N)|.
pub fn line_amplitude(y: &[f64], k: usize) -> f64 {
    let n = y.len();
    let (mut re, mut im) = (0.0, 0.0);
    for (j, v) in y.iter().enumerate() {
        // k·j mod N keeps the angle small and exact.
        let x = 2.0 * PI * ((k * j) % n) as f64 / n as f64;
        let (s, c) = x.sin_cos();
        re += v * c;
        im -= v * s;
    }
    2.0 * re.hypot(im) / n as f64
}

/// The run-up's wheel-revolution windows, every half revolution from the
/// start: samples per window `per_revolution`; `marks` the (label, pinion
/// order) to report, each taken at its nearest line.
///
/// `t`, `q1` the trace's time (s) and pinion rotation (rad, non-decreasing),
/// `force` the wheel bearing force (N, fixed frame).
pub fn windows(
    t: &[f64],
    q1: &[f64],
    force: &[[f64; 3]],
    z: [usize; 2],
    per_revolution: usize,
    marks: &[(String, f64)],
) -> Vec<RunupOrderWindow> {
    let Some(&q0) = q1.first() else {
        return Vec::new();
    };
    let ratio = z[0] as f64 / z[1] as f64;
    let theta = 2.0 * PI / ratio;
    let dq = theta / per_revolution as f64;
    // Time and force at uniform pinion angle from q0.
    let time = resample(q1, t, dq);
    let comp: Vec<Vec<f64>> = (0..3)
        .map(|c| resample(q1, &force.iter().map(|f| f[c]).collect::<Vec<_>>(), dq))
        .collect();
    let half = per_revolution / 2;
    let mut out = Vec::new();
    let mut start = 0;
    while start + per_revolution < time.len() {
        let span = start..start + per_revolution;
        let (ta, tb) = (time[start], time[start + per_revolution]);
        let rpm = |a: usize| {
            let (i0, i1) = (a.saturating_sub(1), (a + 1).min(time.len() - 1));
            (i1 - i0) as f64 * dq / (time[i1] - time[i0]).max(1e-300) * 30.0 / PI
        };
        let marked = marks
            .iter()
            .map(|(label, order)| {
                let k = (order / ratio).round() as usize;
                let amp = comp
                    .iter()
                    .map(|y| line_amplitude(&y[span.clone()], k).powi(2))
                    .sum::<f64>()
                    .sqrt();
                MarkedOrder {
                    label: label.clone(),
                    pinion_order: k as f64 * ratio,
                    wheel_bearing_force_n: amp,
                }
            })
            .collect();
        out.push(RunupOrderWindow {
            pinion_rev: [
                (q0 + start as f64 * dq) / (2.0 * PI),
                (q0 + (start + per_revolution) as f64 * dq) / (2.0 * PI),
            ],
            time_s: [ta, tb],
            mean_pinion_rpm: theta / (tb - ta).max(1e-300) * 30.0 / PI,
            pinion_rpm: [rpm(start), rpm(start + per_revolution)],
            marked,
        });
        start += half.max(1);
    }
    out
}

/// The marked pinion orders: (label, order) for z₁, 2z₁, the lobe family
/// o = n z₁/z₂ and 2o, and z₁ ± o, 2z₁ ± o.
pub fn marked_orders(z1: usize, z2: usize, holes: usize) -> Vec<(String, f64)> {
    let (z, o) = (z1 as f64, holes as f64 * z1 as f64 / z2 as f64);
    vec![
        (format!("{holes}·{z1}/{z2}"), o),
        (format!("2·{holes}·{z1}/{z2}"), 2.0 * o),
        (format!("{z1}-{o:.2}"), z - o),
        (format!("{z1}"), z),
        (format!("{z1}+{o:.2}"), z + o),
        (format!("{}-{o:.2}", 2 * z1), 2.0 * z - o),
        (format!("{}", 2 * z1), 2.0 * z),
        (format!("{}+{o:.2}", 2 * z1), 2.0 * z + o),
    ]
}

/// Amplitude of `spectrum` (pinion order, amplitude) at the line nearest `order`.
pub fn amplitude_at(spectrum: &[(f64, f64)], order: f64) -> f64 {
    spectrum
        .iter()
        .min_by(|a, b| (a.0 - order).abs().total_cmp(&(b.0 - order).abs()))
        .map_or(0.0, |l| l.1)
}
