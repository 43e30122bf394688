//! Weierstrass–Mandelbrot (W–M) fractal roughness, seed 003's Eq. (1):
//!
//! z(x) = G^(D−1) Σ_{n=0}^{N} ω_n^(−(2−D)) cos(2π ω_n x + φ_n),  ω_n = ω_l γⁿ
//!
//! with D the profile's fractal dimension (1 < D < 2), G the characteristic
//! scale (a length), γ the frequency ratio (seed 003: 1.5), ω_l = 1/λ_l the
//! lowest spatial frequency (λ_l the longest wavelength; seed 003 writes
//! ω_n = γⁿ with n_l = 0, i.e. λ_l = 1 in its length unit), N the last term
//! below the shortest wavelength λ_s, and φ_n random phases drawn from a
//! seeded generator (same seed → same profile). The form is dimensionally
//! consistent (G^(D−1) ω^(D−2) is a length), so G converts between units as
//! any length.
//!
//! Its power spectrum, seed 003's Eq. (2), follows from spreading each line's
//! power a_n²/2 over its share ω_n ln γ of a logarithmic frequency axis:
//!
//! S(ω) = G^(2(D−1)) / (2 ln γ) · ω^(−(5−2D))
//!
//! so the log–log slope of the PSD is β = −(5 − 2D), i.e. D = (5 + β)/2.
//!
//! **Profile, not a 2D surface.** Seed 003 puts the W–M profile into the
//! involute that serves as the cutting curve, and the cut tooth surface
//! carries it along the face width (its Figures 1, 2 and 6: machining traces
//! running lengthwise). We follow that: one profile along the flank's profile
//! direction (root → tip), the same at every face position. A 2D (Ausloos–
//! Berman) surface would add ridges at other angles that the seed's cutting
//! model does not have.
//!
//! **Amplitude.** Seed 003's Eqs. (41) (D; its Eq. (33) does not
//! reproduce its Table 2) and (34) (G) give D and G from Ra
//! ([`seed003_fractal`]); with G read in mm, λ_l = 1 mm and λ_s = 2.5 µm its
//! G gives an expected Ra of 1.31 / 0.35 / 0.082 µm for the requested
//! 0.8 / 0.4 / 0.2 µm (1.64 / 0.87 / 0.41 times), so the fit does not
//! reproduce its own roughness. [`WmProfile::with_ra`]
//! therefore keeps D from Eq. (41) and sets G so that the expected Ra over the
//! random phases equals the requested Ra:
//!
//! E|z| = (2/π) ∫₀^∞ (1 − Π_n J₀(a_n t)) / t² dt,   a_n = G^(D−1) ω_n^(D−2)
//!
//! (from |z| = (2/π) ∫₀^∞ (1 − cos zt)/t² dt and E cos(a cos φ · t) = J₀(at)
//! for a uniform phase). E|z| is proportional to G^(D−1), which gives G in
//! closed form once E|z| is known for G = 1 m.
//!
//! **Into the flanks.** [`WmProfile::topography`] samples the profile as a
//! [`TopographyDesign`] (µm, normalised flank coordinates), the grid the
//! design file's `[ease_off.topography]` takes and the ease-off adds to the
//! pinion flank (bicubic between nodes). The lumped model's scenes generate
//! it (`[lumped.roughness]`, `solver::lumped::roughness`, which measures the
//! flank's profile length); a grid of at most 200 nodes over a ~10 mm
//! profile carries only wavelengths above ~0.1 mm, i.e. waviness, not the
//! 2.5 µm – 0.8 mm roughness band.

use crate::design::TopographyDesign;
use std::f64::consts::PI;
use thiserror::Error;

/// Seed 003's frequency ratio γ.
pub const SEED003_GAMMA: f64 = 1.5;
/// Longest wavelength of a roughness evaluation: ISO 4288's cutoff λc for
/// 0.1 µm < Ra ≤ 2 µm, m.
pub const ROUGHNESS_CUTOFF_M: f64 = 0.8e-3;
/// Shortest wavelength of a roughness evaluation: ISO 3274's λs for
/// λc = 0.8 mm, m.
pub const ROUGHNESS_SHORT_CUTOFF_M: f64 = 2.5e-6;
/// Largest number of W–M terms (γ = 1.5 over 100 terms spans 17 decades).
pub const MAX_TERMS: usize = 100;

/// Bad roughness input: the field, its value and the limit.
#[derive(Debug, Error, PartialEq)]
pub enum RoughnessError {
    #[error("roughness {field} = {value}: {limit}")]
    Invalid {
        field: &'static str,
        value: f64,
        limit: &'static str,
    },
}

fn invalid(field: &'static str, value: f64, limit: &'static str) -> RoughnessError {
    RoughnessError::Invalid {
        field,
        value,
        limit,
    }
}

/// D and G from seed 003's fits, Ra in µm (seed 003, Tables 1–2: "Surface
/// Roughness/µm", the contour arithmetic mean deviation). The seed gives
/// D twice:
///
/// Eq. (33): D = 1.515 / Ra^0.088,   Eq. (41): D = 1.528 / Ra^0.042,
///
/// and G = 10^(−5.26 / Ra^0.042) (Eq. (34)). Ra 0.8 / 0.4 / 0.2 µm give
/// D = 1.545 / 1.642 / 1.746 by Eq. (33) and 1.542 / 1.588 / 1.635 by
/// Eq. (41); the seed's Table 2 lists D = 1.55 / 1.60 / 1.65, which Eq. (41)
/// reproduces within 0.016 and Eq. (33) only at 0.8 µm (0.096 off at
/// 0.2 µm). `dimension` is therefore Eq. (41)'s (our choice between the
/// seed's two fits), `dimension_eq33` kept for the report. G = 4.90e-6 /
/// 3.42e-6 / 2.36e-6 against Table 2's 5e-6 / 3e-6 / 2e-6. The seed gives
/// no unit for G; read with x in mm (its Figure 1 spans mm), G is in mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed003Fractal {
    pub dimension: f64,
    pub dimension_eq33: f64,
    pub scale_mm: f64,
}

/// Seed 003's Eqs. (41), (33) and (34) for a roughness Ra in µm; Ra must lie in
/// (0, 10] µm (the fit covers 0.2–0.8 µm; beyond 10 µm D drops below 1.24).
pub fn seed003_fractal(ra_um: f64) -> Result<Seed003Fractal, RoughnessError> {
    if !(ra_um.is_finite() && ra_um > 0.0 && ra_um <= 10.0) {
        return Err(invalid("ra_um", ra_um, "must lie in (0, 10] µm"));
    }
    Ok(Seed003Fractal {
        dimension: 1.528 / ra_um.powf(0.042),
        dimension_eq33: 1.515 / ra_um.powf(0.088),
        scale_mm: 10f64.powf(-5.26 / ra_um.powf(0.042)),
    })
}

/// The W–M profile's parameters, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WmSpec {
    /// Profile fractal dimension D, 1 < D < 2.
    pub dimension: f64,
    /// Characteristic scale G, m.
    pub scale_m: f64,
    /// Frequency ratio γ > 1.
    pub gamma: f64,
    /// Longest wavelength λ_l = 1/ω_l, m.
    pub longest_wavelength_m: f64,
    /// Shortest wavelength λ_s: the terms kept have ω_n ≤ 1/λ_s, m.
    pub shortest_wavelength_m: f64,
}

impl WmSpec {
    fn check(&self) -> Result<usize, RoughnessError> {
        let d = self.dimension;
        if !(d.is_finite() && d > 1.0 && d < 2.0) {
            return Err(invalid("dimension", d, "must lie in (1, 2)"));
        }
        if !(self.scale_m.is_finite() && self.scale_m > 0.0) {
            return Err(invalid("scale_m", self.scale_m, "must be positive"));
        }
        if !(self.gamma.is_finite() && self.gamma > 1.0) {
            return Err(invalid("gamma", self.gamma, "must exceed 1"));
        }
        let (l, s) = (self.longest_wavelength_m, self.shortest_wavelength_m);
        if !(l.is_finite() && l > 0.0) {
            return Err(invalid("longest_wavelength_m", l, "must be positive"));
        }
        if !(s.is_finite() && s > 0.0 && s <= l) {
            return Err(invalid(
                "shortest_wavelength_m",
                s,
                "must be positive and at most the longest wavelength",
            ));
        }
        let terms = ((l / s).ln() / self.gamma.ln()).floor() + 1.0;
        if terms > MAX_TERMS as f64 {
            return Err(invalid(
                "shortest_wavelength_m",
                s,
                "gives more than 100 W–M terms",
            ));
        }
        Ok(terms as usize)
    }
}

/// SplitMix64: a small, seeded, reproducible generator (Steele, Lea, Flood 2014).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A W–M profile with its drawn phases.
#[derive(Debug, Clone, PartialEq)]
pub struct WmProfile {
    spec: WmSpec,
    /// Spatial frequencies ω_n, 1/m.
    frequency_per_m: Vec<f64>,
    /// Amplitudes a_n = G^(D−1) ω_n^(D−2), m.
    amplitude_m: Vec<f64>,
    /// Phases φ_n, rad.
    phase: Vec<f64>,
}

impl WmProfile {
    /// The profile of `spec` with phases drawn from `seed`.
    pub fn new(spec: WmSpec, seed: u64) -> Result<Self, RoughnessError> {
        let terms = spec.check()?;
        let mut rng = SplitMix64(seed);
        let w_l = 1.0 / spec.longest_wavelength_m;
        let frequency_per_m: Vec<f64> = (0..terms)
            .map(|n| w_l * spec.gamma.powi(n as i32))
            .collect();
        let pre = spec.scale_m.powf(spec.dimension - 1.0);
        let amplitude_m = frequency_per_m
            .iter()
            .map(|w| pre * w.powf(spec.dimension - 2.0))
            .collect();
        let phase = (0..terms).map(|_| 2.0 * PI * rng.unit()).collect();
        Ok(WmProfile {
            spec,
            frequency_per_m,
            amplitude_m,
            phase,
        })
    }

    /// The profile of dimension D whose expected Ra over the random phases
    /// is `ra_m`: G = (Ra / E|z|_{G=1 m})^(1/(D−1)) m (`spec.scale_m` is
    /// replaced).
    pub fn with_ra(spec: WmSpec, ra_m: f64, seed: u64) -> Result<Self, RoughnessError> {
        if !(ra_m.is_finite() && ra_m > 0.0) {
            return Err(invalid("ra_m", ra_m, "must be positive"));
        }
        let unit = WmProfile::new(
            WmSpec {
                scale_m: 1.0,
                ..spec
            },
            seed,
        )?;
        let ra_unit = unit.expected_ra_m();
        let scale_m = (ra_m / ra_unit).powf(1.0 / (spec.dimension - 1.0));
        WmProfile::new(WmSpec { scale_m, ..spec }, seed)
    }

    /// Seed 003's roughness grade: D from Eq. (41) for `ra_um`, γ = 1.5, the
    /// ISO roughness band λs = 2.5 µm to λc = 0.8 mm, G set for the expected
    /// Ra (see the module notes for why not Eq. (34)).
    pub fn seed003(ra_um: f64, seed: u64) -> Result<Self, RoughnessError> {
        let f = seed003_fractal(ra_um)?;
        let spec = WmSpec {
            dimension: f.dimension,
            scale_m: f.scale_mm * 1e-3,
            gamma: SEED003_GAMMA,
            longest_wavelength_m: ROUGHNESS_CUTOFF_M,
            shortest_wavelength_m: ROUGHNESS_SHORT_CUTOFF_M,
        };
        WmProfile::with_ra(spec, ra_um * 1e-6, seed)
    }

    pub fn spec(&self) -> &WmSpec {
        &self.spec
    }

    /// ω_n, 1/m.
    pub fn frequencies_per_m(&self) -> &[f64] {
        &self.frequency_per_m
    }

    /// a_n, m.
    pub fn amplitudes_m(&self) -> &[f64] {
        &self.amplitude_m
    }

    /// z(x), m, at x in m.
    pub fn height_m(&self, x_m: f64) -> f64 {
        self.height_below_m(x_m, f64::INFINITY)
    }

    /// z(x) from the terms with ω_n ≤ `max_frequency_per_m` only, m.
    fn height_below_m(&self, x_m: f64, max_frequency_per_m: f64) -> f64 {
        self.frequency_per_m
            .iter()
            .zip(&self.amplitude_m)
            .zip(&self.phase)
            .take_while(|((w, _), _)| **w <= max_frequency_per_m)
            .map(|((w, a), p)| a * (2.0 * PI * w * x_m + p).cos())
            .sum()
    }

    /// Rq = sqrt(Σ a_n² / 2), m: the RMS over a length of many λ_l (the
    /// terms are orthogonal), whatever the phases.
    pub fn rq_m(&self) -> f64 {
        (self.amplitude_m.iter().map(|a| a * a).sum::<f64>() / 2.0).sqrt()
    }

    /// Expected Ra over the random phases, m (module notes): midpoint rule
    /// on [0, T] with T = 200 / a_max and step 0.02 / Σa_n, plus the tail
    /// ∫_T^∞ dt/t² = 1/T (the product of J₀ there is below 1e-3 for two or
    /// more terms).
    pub fn expected_ra_m(&self) -> f64 {
        let a = &self.amplitude_m;
        let a_max = a.iter().cloned().fold(0.0, f64::max);
        let a_sum: f64 = a.iter().sum();
        if a.len() == 1 {
            // A single cosine: E|a cos φ| = 2a/π.
            return 2.0 * a[0] / PI;
        }
        let t_end = 200.0 / a_max;
        let h = 0.02 / a_sum;
        let steps = (t_end / h).ceil() as usize;
        let h = t_end / steps as f64;
        let integral: f64 = (0..steps)
            .map(|k| {
                let t = (k as f64 + 0.5) * h;
                let prod: f64 = a.iter().map(|an| bessel_j0(an * t)).product();
                (1.0 - prod) / (t * t)
            })
            .sum::<f64>()
            * h;
        2.0 / PI * (integral + 1.0 / t_end)
    }

    /// The profile as a flank topography in µm on `profile_nodes` ×
    /// `face_nodes` nodes evenly spread over the normalised flank (profile
    /// 0 = root limit, 1 = tip; face 0 = toe, 1 = heel), the profile running
    /// along the flank's profile direction of length `profile_length_m` and
    /// the same at every face position. Terms shorter than two node spacings
    /// are left out (a grid cannot carry them; they would alias).
    pub fn topography(
        &self,
        profile_length_m: f64,
        profile_nodes: usize,
        face_nodes: usize,
    ) -> Result<TopographyDesign, RoughnessError> {
        if !(profile_length_m.is_finite() && profile_length_m > 0.0) {
            return Err(invalid(
                "profile_length_m",
                profile_length_m,
                "must be positive",
            ));
        }
        for (field, n) in [("profile_nodes", profile_nodes), ("face_nodes", face_nodes)] {
            if !(2..=crate::design_file::MAX_TOPOGRAPHY_NODES).contains(&n) {
                return Err(invalid(field, n as f64, "must lie in 2..=200"));
            }
        }
        let spacing_m = profile_length_m / (profile_nodes - 1) as f64;
        let max_w = 1.0 / (2.0 * spacing_m);
        let profile: Vec<f64> = (0..profile_nodes)
            .map(|i| i as f64 / (profile_nodes - 1) as f64)
            .collect();
        let face = (0..face_nodes)
            .map(|j| j as f64 / (face_nodes - 1) as f64)
            .collect();
        let deviation_um = profile
            .iter()
            .map(|eta| {
                let z_um = self.height_below_m(eta * profile_length_m, max_w) * 1e6;
                vec![z_um; face_nodes]
            })
            .collect();
        Ok(TopographyDesign {
            profile,
            face,
            deviation_um,
        })
    }
}

/// Bessel function J₀(x): its power series Σ (−x²/4)^k / (k!)² for |x| < 12
/// (cancellation costs under 1e-9 there), Hankel's asymptotic expansion
/// beyond, J₀ = sqrt(2/(πx)) (P cos χ − Q sin χ), χ = x − π/4,
/// P = 1 − 9/(128x²) + 3675/(32768x⁴) − 0.572501/x⁶,
/// Q = −1/(8x) + 75/(1024x³) − 59535/(262144x⁵) + 1.727727/x⁷
/// (next terms below 2e-8 at x = 12).
pub fn bessel_j0(x: f64) -> f64 {
    let x = x.abs();
    if x < 12.0 {
        let q = -x * x / 4.0;
        let mut term = 1.0;
        let mut sum = 1.0;
        for k in 1..60 {
            let kf = k as f64;
            term *= q / (kf * kf);
            sum += term;
            if term.abs() < 1e-17 {
                break;
            }
        }
        sum
    } else {
        let x2 = x * x;
        let x4 = x2 * x2;
        let p = 1.0 - 9.0 / (128.0 * x2) + 3675.0 / (32768.0 * x4) - 0.572_501 / (x4 * x2);
        let q = -1.0 / (8.0 * x) + 75.0 / (1024.0 * x2 * x) - 59535.0 / (262144.0 * x4 * x)
            + 1.727_727 / (x4 * x2 * x);
        let chi = x - PI / 4.0;
        (2.0 / (PI * x)).sqrt() * (p * chi.cos() - q * chi.sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bessel_j0_matches_tabulated_values() {
        // Abramowitz & Stegun Table 9.1 and the first zero j₀,₁.
        for (x, j) in [
            (0.0, 1.0),
            (1.0, 0.765_197_686_557_966_6),
            (5.0, -0.177_596_771_314_338_3),
            (10.0, -0.245_935_764_451_348_3),
            (20.0, 0.167_024_664_340_583_5),
            (2.404_825_557_695_773, 0.0),
        ] {
            assert!(
                (bessel_j0(x) - j).abs() < 1e-7,
                "J0({x}) = {}",
                bessel_j0(x)
            );
        }
    }

    #[test]
    fn expected_ra_of_one_cosine_and_of_many_terms() {
        // Many equal terms tend to a Gaussian: Ra → sqrt(2/π) Rq.
        let p = WmProfile {
            spec: WmSpec {
                dimension: 1.5,
                scale_m: 1.0,
                gamma: 1.5,
                longest_wavelength_m: 1.0,
                shortest_wavelength_m: 1.0,
            },
            frequency_per_m: vec![1.0; 24],
            amplitude_m: vec![1.0; 24],
            phase: vec![0.0; 24],
        };
        let gauss = (2.0 / PI).sqrt() * p.rq_m();
        assert!((p.expected_ra_m() / gauss - 1.0).abs() < 0.01);
    }
}
