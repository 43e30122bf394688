//! The mesh excitations over the mesh cycle: the mesh stiffness k(t) and
//! the static transmission error e(t) as Fourier series, and the meshing
//! impact as a pulse once per mesh cycle.
//!
//! A series of period T (ω = 2π/T) with N harmonics:
//!
//! ```text
//! f(t) = a₀ + Σₗ₌₁ᴺ (aₗ cos lωt + bₗ sin lωt)
//! ```
//!
//! (seed 004's k_m + Σ A cos(lωt + φ) + B sin(lωt + φ) with the phases
//! folded into aₗ, bₗ; amplitude √(aₗ² + bₗ²)). The coefficients are the
//! least-squares fit to samples at arbitrary times inside one period (the
//! LTCA's positions need not be evenly spaced nor span the period exactly).
//! N is the smallest count whose largest residual at the samples is within
//! `tolerance` × (peak-to-peak of the samples); the residual is reported.

use super::LumpedError;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::f64::consts::PI;

/// A truncated Fourier series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FourierSeries {
    /// Period T, s.
    pub period_s: f64,
    /// a₀.
    pub mean: f64,
    /// aₗ, l = 1..N.
    pub cos: Vec<f64>,
    /// bₗ, l = 1..N.
    pub sin: Vec<f64>,
}

impl FourierSeries {
    /// A constant.
    pub fn constant(value: f64, period_s: f64) -> Self {
        Self {
            period_s,
            mean: value,
            cos: Vec::new(),
            sin: Vec::new(),
        }
    }

    pub fn harmonics(&self) -> usize {
        self.cos.len()
    }

    /// Amplitudes √(aₗ² + bₗ²).
    pub fn amplitudes(&self) -> Vec<f64> {
        self.cos
            .iter()
            .zip(&self.sin)
            .map(|(a, b)| a.hypot(*b))
            .collect()
    }

    /// f, f′ and f″ at `t` (s).
    pub fn eval(&self, t: f64) -> [f64; 3] {
        let w = 2.0 * PI / self.period_s;
        let (s1, c1) = (w * t).sin_cos();
        // cos/sin of lωt by the recurrence of the angle sum.
        let (mut s, mut c) = (s1, c1);
        let mut out = [self.mean, 0.0, 0.0];
        for (l, (a, b)) in self.cos.iter().zip(&self.sin).enumerate() {
            let lw = (l + 1) as f64 * w;
            out[0] += a * c + b * s;
            out[1] += lw * (b * c - a * s);
            out[2] -= lw * lw * (a * c + b * s);
            let sn = s * c1 + c * s1;
            c = c * c1 - s * s1;
            s = sn;
        }
        out
    }

    pub fn value(&self, t: f64) -> f64 {
        self.eval(t)[0]
    }

    /// Least-squares fit with `harmonics` (N) harmonics to samples (tᵢ, fᵢ);
    /// needs at least 2N + 1 samples.
    pub fn fit(
        times: &[f64],
        values: &[f64],
        period_s: f64,
        harmonics: usize,
    ) -> Result<Self, LumpedError> {
        let n = times.len();
        let unknowns = 2 * harmonics + 1;
        if values.len() != n || n < unknowns || !(period_s > 0.0 && period_s.is_finite()) {
            return Err(LumpedError::Input(format!(
                "Fourier fit: {n} times, {} values, period {period_s} s, {harmonics} harmonics (needs ≥ {unknowns} samples and a period > 0)",
                values.len()
            )));
        }
        if times.iter().chain(values).any(|v| !v.is_finite()) {
            return Err(LumpedError::Input(
                "Fourier fit: a sample is not finite".into(),
            ));
        }
        let w = 2.0 * PI / period_s;
        let a = DMatrix::from_fn(n, unknowns, |i, j| {
            if j == 0 {
                1.0
            } else {
                let l = j.div_ceil(2) as f64;
                if j % 2 == 1 {
                    (l * w * times[i]).cos()
                } else {
                    (l * w * times[i]).sin()
                }
            }
        });
        let y = DVector::from_column_slice(values);
        let x = a
            .svd(true, true)
            .solve(&y, 1e-12)
            .map_err(|e| LumpedError::Input(format!("Fourier fit: {e}")))?;
        Ok(Self {
            period_s,
            mean: x[0],
            cos: (0..harmonics).map(|l| x[1 + 2 * l]).collect(),
            sin: (0..harmonics).map(|l| x[2 + 2 * l]).collect(),
        })
    }

    /// Largest |f(tᵢ) − fᵢ| over the samples.
    pub fn max_residual(&self, times: &[f64], values: &[f64]) -> f64 {
        times
            .iter()
            .zip(values)
            .map(|(t, v)| (self.value(*t) - v).abs())
            .fold(0.0, f64::max)
    }
}

/// A series fitted to samples with the harmonic count chosen by its error.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FittedSeries {
    pub series: FourierSeries,
    /// Largest residual at the samples, in the samples' unit.
    pub max_residual: f64,
    /// The same over the samples' peak-to-peak (0 for constant samples).
    pub max_residual_of_ptp: f64,
    /// The requested bound on `max_residual_of_ptp`.
    pub tolerance_of_ptp: f64,
    /// Whether the bound was met (else the series has the most harmonics
    /// the samples allow, ⌊(n − 1)/2⌋).
    pub met: bool,
}

/// The fit with the fewest harmonics whose largest residual at the samples
/// is ≤ `tolerance` × (max − min of the samples).
pub fn fit_to_tolerance(
    times: &[f64],
    values: &[f64],
    period_s: f64,
    tolerance: f64,
) -> Result<FittedSeries, LumpedError> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(LumpedError::Input(format!(
            "Fourier tolerance {tolerance}: must be finite and > 0"
        )));
    }
    if values.is_empty() {
        return Err(LumpedError::Input("Fourier fit: no samples".into()));
    }
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let ptp = hi - lo;
    let most = (values.len() - 1) / 2;
    let mut last = None;
    for n in 0..=most {
        let s = FourierSeries::fit(times, values, period_s, n)?;
        let r = s.max_residual(times, values);
        let rel = if ptp > 0.0 { r / ptp } else { 0.0 };
        let met = rel <= tolerance;
        last = Some(FittedSeries {
            series: s,
            max_residual: r,
            max_residual_of_ptp: rel,
            tolerance_of_ptp: tolerance,
            met,
        });
        if met {
            break;
        }
    }
    last.ok_or_else(|| LumpedError::Input("Fourier fit: no samples".into()))
}

/// The meshing impact: a half-sine force pulse along the mesh normal,
/// F(t) = F_s sin(π s/d) for s = (t − t₀) mod T in [0, d), once per mesh
/// period T (seed 004 gives the peak F_s and d = 0.05 T but not the shape;
/// the half sine is chosen here as the usual shape of an impact force).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ImpactPulse {
    /// Peak F_s, N.
    pub peak_n: f64,
    /// Pulse length d, s.
    pub duration_s: f64,
    /// Start t₀ within the mesh period, s.
    pub start_s: f64,
    /// Mesh period T, s.
    pub period_s: f64,
}

impl ImpactPulse {
    pub fn force(&self, t: f64) -> f64 {
        let s = (t - self.start_s).rem_euclid(self.period_s);
        if s < self.duration_s {
            self.peak_n * (PI * s / self.duration_s).sin()
        } else {
            0.0
        }
    }
}

/// Seed 004's peak impact force
/// F_s = v_s √(b J₁J₂ / ((J₁ r′_b2² + J₂ r_b1²) q_s)), with q_s = b/k_s the
/// compliance of the entering pair per face width (m²/N), i.e.
/// F_s = v_s √(k_s mₑ′), mₑ′ = J₁J₂/(J₁r′_b2² + J₂r_b1²) the equivalent mass
/// at the levers of the impact point.
pub fn seed004_impact_force(
    impact_velocity_m_s: f64,
    entering_pair_stiffness_n_per_m: f64,
    inertias_kgm2: [f64; 2],
    levers_at_impact_m: [f64; 2],
) -> f64 {
    let [j1, j2] = inertias_kgm2;
    let [rb1, rb2] = levers_at_impact_m;
    let me = j1 * j2 / (j1 * rb2 * rb2 + j2 * rb1 * rb1);
    impact_velocity_m_s.abs() * (entering_pair_stiffness_n_per_m * me).sqrt()
}

/// The static transmission error e(t) along the normal, m.
#[derive(Debug, Clone, PartialEq)]
pub enum StaticError {
    /// e(t) as its own series.
    Series(FourierSeries),
    /// e(t) = δ(t) − F/k(t) from a series of the loaded static deflection
    /// δ(t) (the LTCA's loaded TE times r₂) at the mesh force F = T₁/r₁:
    /// the model's quasi-static deflection δ = e + F/k is then the series
    /// of δ whatever the error of the series of k. Derivatives:
    /// e′ = δ′ + F k′/k², e″ = δ″ + F (k″/k² − 2k′²/k³).
    LoadedDeflection {
        deflection: FourierSeries,
        force_n: f64,
    },
}

/// The mesh excitation: k(t) (N/m), e(t) (m, along the normal), the
/// impact pulse and sliding friction.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshExcitation {
    pub stiffness: FourierSeries,
    pub transmission_error: StaticError,
    pub impact: Option<ImpactPulse>,
    pub friction: Option<super::friction::FrictionExcitation>,
}

impl MeshExcitation {
    /// e, e′, e″ at `t`.
    pub fn te(&self, t: f64) -> [f64; 3] {
        match &self.transmission_error {
            StaticError::Series(s) => s.eval(t),
            StaticError::LoadedDeflection {
                deflection,
                force_n,
            } => {
                let [d, d1, d2] = deflection.eval(t);
                let [k, k1, k2] = self.stiffness.eval(t);
                let f = *force_n;
                [
                    d - f / k,
                    d1 + f * k1 / (k * k),
                    d2 + f * (k2 / (k * k) - 2.0 * k1 * k1 / (k * k * k)),
                ]
            }
        }
    }
}
