//! Statistics of a lumped run over its kept window (the first mesh cycles
//! dropped): RMS accelerations, peak-to-peak displacements, the dynamic
//! mesh force, bearing forces and their spectrum at mesh orders.
//!
//! RMS of a signal x over the window: √(mean (x − x̄)²). Along the mesh
//! normal: λ = v·q − e and λ̈ = v·q̈ − ë (seed 004's λₙ). Spectrum: the
//! discrete Fourier amplitude 2|Σ xᵢ e^{−iωtᵢ}|/n of the fluctuation at
//! ω = 2π f, f at multiples of 1/(window length), listed in mesh orders
//! f/f_mesh (the window holds a whole number of mesh cycles, so the mesh
//! harmonics fall on bins).

use super::excitation::MeshExcitation;
use super::integrate::History;
use super::model::Model;

/// The seven directions: pinion X, Y, Z, wheel X, Y, Z, mesh normal.
pub type Seven = [f64; 7];

/// Statistics of the kept window.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    pub rms_acceleration: Seven,
    /// RMS of the fluctuating velocities (mesh normal: λ̇), m/s.
    pub rms_velocity: Seven,
    /// RMS of each member's resultant translational velocity fluctuation,
    /// √(Σ_d RMS_d²), m/s.
    pub member_velocity_rms: [f64; 2],
    /// RMS of v·q̈, m/s².
    pub relative_normal_rms: f64,
    pub peak_to_peak: Seven,
    /// Fₙ mean, min, max, N.
    pub mesh_force: [f64; 3],
    /// Bearing-force fluctuation RMS, N: pinion X, Y, Z, wheel X, Y, Z.
    pub bearing_rms: [f64; 6],
    /// (mesh order, amplitude N) of the resultant bearing-force fluctuation
    /// of both members, the strongest first.
    pub bearing_peaks: Vec<(f64, f64)>,
    /// The full spectrum: mesh order, pinion amplitude, wheel amplitude (N).
    pub bearing_spectrum: Vec<[f64; 3]>,
}

const TRANSLATIONS: [usize; 6] = [0, 1, 2, 4, 5, 6];

fn rms(x: &[f64]) -> f64 {
    let n = x.len().max(1) as f64;
    let m = x.iter().sum::<f64>() / n;
    (x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / n).sqrt()
}

/// Peak-to-peak (max − min) of `x`.
pub fn ptp(x: &[f64]) -> f64 {
    let (lo, hi) = x
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    hi - lo
}

/// Amplitude of the fluctuation of `x` (samples at `t`) at frequency `f` (Hz).
fn amplitude(t: &[f64], x: &[f64], f: f64) -> f64 {
    let n = x.len().max(1) as f64;
    let m = x.iter().sum::<f64>() / n;
    let w = 2.0 * std::f64::consts::PI * f;
    let (re, im) = t.iter().zip(x).fold((0.0, 0.0), |(re, im), (ti, xi)| {
        let (s, c) = (w * ti).sin_cos();
        (re + (xi - m) * c, im - (xi - m) * s)
    });
    2.0 * re.hypot(im) / n
}

/// Statistics of `h` from sample `first` on; `mesh_hz` the mesh
/// frequency, spectrum up to `max_order` mesh orders.
pub fn response(
    model: &Model,
    exc: &MeshExcitation,
    h: &History,
    first: usize,
    mesh_hz: f64,
    max_order: f64,
) -> Response {
    // The last sample closes the window (t = the run's end, a whole number
    // of mesh cycles after the first kept sample): left out, so the window
    // is n Δt long and the mesh orders fall on bins.
    let end = h.t.len().saturating_sub(1).max(first);
    let t = &h.t[first..end];
    let v = model.mesh_vector();
    let lam_dd: Vec<f64> = (first..end)
        .map(|i| (0..8).map(|j| v[j] * h.qdd[i][j]).sum::<f64>() - exc.te(h.t[i])[2])
        .collect();
    let rel: Vec<f64> = (first..end)
        .map(|i| (0..8).map(|j| v[j] * h.qdd[i][j]).sum::<f64>())
        .collect();
    let lam: Vec<f64> = h.mesh[first..end].iter().map(|m| m.lambda_m).collect();
    let col =
        |k: usize, of: &[[f64; 8]]| -> Vec<f64> { of[first..end].iter().map(|r| r[k]).collect() };
    let mut rms_acc = [0.0; 7];
    let mut rms_vel = [0.0; 7];
    let mut p2p = [0.0; 7];
    for (d, &k) in TRANSLATIONS.iter().enumerate() {
        rms_acc[d] = rms(&col(k, &h.qdd));
        rms_vel[d] = rms(&col(k, &h.qd));
        p2p[d] = ptp(&col(k, &h.q));
    }
    rms_acc[6] = rms(&lam_dd);
    let lam_d: Vec<f64> = (first..end)
        .map(|i| (0..8).map(|j| v[j] * h.qd[i][j]).sum::<f64>() - exc.te(h.t[i])[1])
        .collect();
    rms_vel[6] = rms(&lam_d);
    let member_velocity_rms =
        [0, 3].map(|o| (0..3).map(|d| rms_vel[o + d].powi(2)).sum::<f64>().sqrt());
    p2p[6] = ptp(&lam);
    let force: Vec<f64> = h.mesh[first..end].iter().map(|m| m.force_n).collect();
    let fmean = force.iter().sum::<f64>() / force.len().max(1) as f64;
    let fmin = force.iter().cloned().fold(f64::INFINITY, f64::min);
    let fmax = force.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    // Bearing forces k q + c q̇ per member and direction.
    let bearing: Vec<Vec<f64>> = (0..6)
        .map(|d| {
            let i = d / 3;
            (first..end)
                .map(|s| model.bearing_force(i, &h.q[s], &h.qd[s])[d % 3])
                .collect()
        })
        .collect();
    let bearing_rms = std::array::from_fn(|d| rms(&bearing[d]));
    let span = t.last().copied().unwrap_or(0.0) - t.first().copied().unwrap_or(0.0);
    let dt = if t.len() > 1 {
        span / (t.len() - 1) as f64
    } else {
        0.0
    };
    let window = span + dt;
    let mut spectrum = Vec::new();
    if window > 0.0 {
        let df = 1.0 / window;
        let bins = (max_order * mesh_hz / df).floor() as usize;
        for b in 1..=bins {
            let f = b as f64 * df;
            let member = |i: usize| {
                (0..3)
                    .map(|d| amplitude(t, &bearing[3 * i + d], f).powi(2))
                    .sum::<f64>()
                    .sqrt()
            };
            spectrum.push([f / mesh_hz, member(0), member(1)]);
        }
    }
    let mut peaks: Vec<(f64, f64)> = spectrum.iter().map(|s| (s[0], s[1].hypot(s[2]))).collect();
    peaks.sort_by(|a, b| b.1.total_cmp(&a.1));
    peaks.truncate(8);
    Response {
        rms_acceleration: rms_acc,
        rms_velocity: rms_vel,
        member_velocity_rms,
        relative_normal_rms: rms(&rel),
        peak_to_peak: p2p,
        mesh_force: [fmean, fmin, fmax],
        bearing_rms,
        bearing_peaks: peaks,
        bearing_spectrum: spectrum,
    }
}
