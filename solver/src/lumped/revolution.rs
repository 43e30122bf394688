//! The mesh excitation over one wheel revolution, for a wheel whose mesh
//! stiffness changes from tooth to tooth (the lightweight blank's web
//! holes): k(t) and the loaded deflection δ(t) then repeat only every z₂
//! mesh cycles, and a one-mesh-cycle Fourier fit
//! ([`super::from_ltca::fit_series`]) cannot carry the per-revolution lobes
//! nor the side bands they put round the mesh orders.
//!
//! A stiffness file holds the influence data of a few wheel teeth only (the
//! white paper's lightweight wheel: 8 of 43), so the LTCA can sweep only the
//! mesh cycles whose loaded teeth are among them, not the whole revolution.
//! The per-revolution variation is derived from that span:
//!
//! ```text
//! k(t) = k̃(p) (1 + c₀ + a cos nψ + b sin nψ)
//! δ(t) = δ̃(p) + d₀ + d_a cos nψ + d_b sin nψ
//! ```
//!
//! with p the position within the mesh cycle, k̃, δ̃ the cycle shape, n
//! the number of web holes (the lobes per revolution) and ψ
//! the wheel angle of the loaded teeth, 2π w/z₂ with w the force-weighted
//! wheel tooth of the loaded pairs (pinion tooth j meshes wheel tooth −j),
//! advanced one tooth per mesh cycle. c₀, a, b and d₀, d_a, d_b are the
//! least-squares fit over the span's positions, alternated with k̃, δ̃ as
//! the span's mean at p of k/(1 + c₀ + a cos nψ + b sin nψ) and
//! δ − (d₀ + …), until the coefficients settle: k̃ is then the cycle
//! without the lobe and joins up across the cycle's end (the span's plain
//! mean at p would carry the lobe's drift over the cycle, a jump at its
//! end). The lobe is the lowest harmonic of the n-lobe family, all that a span shorter than one lobe can tell; the
//! residual it leaves is reported. For an axisymmetric wheel (n = 0) the
//! excitation is k̃, δ̃ repeated.
//!
//! The revolution's z₂·P samples (P positions per mesh cycle) are turned
//! into a series of period z₂T by a direct DFT ([`direct_series`]), kept up
//! to the harmonics the one-cycle fit needed plus half a mesh order.

use super::excitation::{FittedSeries, FourierSeries};
use super::from_ltca::MeshSamples;
use super::response::ptp;
use super::LumpedError;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::f64::consts::PI;

/// Most alternations of the lobe fit and the cycle shape.
const LOBE_ITERATIONS: usize = 50;

/// The per-revolution excitation derived from an LTCA span.
#[derive(Debug, Clone, Serialize)]
pub struct Revolution {
    /// Positions per mesh cycle P.
    pub per_cycle: usize,
    /// Wheel teeth z₂ (mesh cycles per wheel revolution).
    pub wheel_teeth: usize,
    /// Lobes per revolution n (0: axisymmetric wheel).
    pub lobes: usize,
    /// Whole mesh cycles of the LTCA span.
    pub span_cycles: usize,
    /// k̃ over the mesh cycle, N/m.
    pub stiffness_cycle_n_per_m: Vec<f64>,
    /// δ̃ over the mesh cycle, m.
    pub deflection_cycle_m: Vec<f64>,
    /// c₀, a, b (relative to k̃).
    pub stiffness_lobe: [f64; 3],
    /// d₀, d_a, d_b, m.
    pub deflection_lobe_m: [f64; 3],
    /// Wheel tooth w at t = 0 and its advance per mesh cycle (±1).
    pub wheel_tooth_start: f64,
    pub wheel_tooth_per_cycle: f64,
    /// Per span cycle: mean k (N/m) and mean loaded wheel tooth.
    pub cycle_mean_stiffness_n_per_m: Vec<f64>,
    pub cycle_wheel_tooth: Vec<f64>,
    /// Largest residual of the model above at the LTCA positions over the
    /// samples' peak-to-peak: stiffness, deflection.
    pub max_residual_of_ptp: [f64; 2],
    /// The revolution's own LTCA samples k (N/m), δ (m) when the span
    /// covers a whole revolution ([`Revolution::from_revolution`]): they,
    /// not the lobe model, are the excitation.
    pub solved: Option<[Vec<f64>; 2]>,
}

/// Least squares of `y` on the columns `cols`.
fn least_squares(cols: &[Vec<f64>], y: &[f64]) -> Result<Vec<f64>, LumpedError> {
    let a = DMatrix::from_fn(y.len(), cols.len(), |i, j| cols[j][i]);
    let x = a
        .svd(true, true)
        .solve(&DVector::from_column_slice(y), 1e-12)
        .map_err(|e| LumpedError::Input(format!("revolution fit: {e}")))?;
    Ok(x.iter().copied().collect())
}

impl Revolution {
    /// From span samples (`samples.time_s` from the sweep start, evenly
    /// `step_rad` of pinion rotation apart), the force-weighted wheel tooth
    /// of each position, z₂ and the lobe count n.
    pub fn from_span(
        samples: &MeshSamples,
        wheel_tooth: &[f64],
        mesh_cycle_rad: f64,
        step_rad: f64,
        wheel_teeth: usize,
        lobes: usize,
    ) -> Result<Self, LumpedError> {
        let n = samples.time_s.len();
        if wheel_tooth.len() != n || wheel_teeth < 2 {
            return Err(LumpedError::Input(format!(
                "revolution: {n} samples, {} wheel teeth of positions, z2 = {wheel_teeth}",
                wheel_tooth.len()
            )));
        }
        let pf = mesh_cycle_rad / step_rad;
        let per_cycle = pf.round() as usize;
        if per_cycle < 3 || (pf - per_cycle as f64).abs() > 1e-6 * pf {
            return Err(LumpedError::Input(format!(
                "revolution: the sweep step must divide the mesh cycle into ≥ 3 positions ({pf} positions per cycle)"
            )));
        }
        let span_cycles = n / per_cycle;
        if span_cycles == 0 || (lobes > 0 && span_cycles < 3) {
            return Err(LumpedError::Input(format!(
                "revolution: {n} positions hold {span_cycles} whole mesh cycles, need ≥ {}",
                if lobes > 0 { 3 } else { 1 }
            )));
        }
        let m = span_cycles * per_cycle;
        let period = samples.period_s;
        let cyc: Vec<f64> = samples.time_s[..m].iter().map(|t| t / period).collect();
        for (i, c) in cyc.iter().enumerate() {
            if (c * per_cycle as f64 - i as f64).abs() > 1e-6 {
                return Err(LumpedError::Input(format!(
                    "revolution: position {i} is at {c} mesh cycles, not on the {per_cycle}-per-cycle grid"
                )));
            }
        }
        let k = &samples.tangent_n_per_m[..m];
        let d = &samples.deflection_m[..m];
        let mean_at = |v: &[f64], p: usize| {
            (0..span_cycles).map(|c| v[c * per_cycle + p]).sum::<f64>() / span_cycles as f64
        };
        let mut kc: Vec<f64> = (0..per_cycle).map(|p| mean_at(k, p)).collect();
        let mut dc: Vec<f64> = (0..per_cycle).map(|p| mean_at(d, p)).collect();
        // Wheel tooth, linear in time at ±1 tooth per mesh cycle.
        let w = &wheel_tooth[..m];
        let (cm, wm) = (
            cyc.iter().sum::<f64>() / m as f64,
            w.iter().sum::<f64>() / m as f64,
        );
        let slope = cyc
            .iter()
            .zip(w)
            .map(|(c, x)| (c - cm) * (x - wm))
            .sum::<f64>()
            / cyc
                .iter()
                .map(|c| (c - cm) * (c - cm))
                .sum::<f64>()
                .max(1e-300);
        let per = slope.signum();
        if span_cycles > 1 && (slope.abs() - 1.0).abs() > 0.5 {
            return Err(LumpedError::Input(format!(
                "revolution: the loaded wheel tooth moves {slope} teeth per mesh cycle, not ±1"
            )));
        }
        let w0 = wm - per * cm;
        let psi = |c: f64| 2.0 * PI * (w0 + per * c) / wheel_teeth as f64;
        let (mut kl, mut dl) = ([0.0; 3], [0.0; 3]);
        if lobes > 0 {
            let nl = lobes as f64;
            let cols = vec![
                vec![1.0; m],
                cyc.iter().map(|c| (nl * psi(*c)).cos()).collect(),
                cyc.iter().map(|c| (nl * psi(*c)).sin()).collect(),
            ];
            let term = |x: &[f64; 3], i: usize| x[0] + x[1] * cols[1][i] + x[2] * cols[2][i];
            // Alternately: the lobe fitted to k/k̃ − 1 (δ − δ̃), then k̃ (δ̃)
            // the span's mean of k/(1 + lobe) (δ − lobe) at each position
            // of the cycle, until the lobe's coefficients settle.
            for _ in 0..LOBE_ITERATIONS {
                let rk: Vec<f64> = (0..m).map(|i| k[i] / kc[i % per_cycle] - 1.0).collect();
                let rd: Vec<f64> = (0..m).map(|i| d[i] - dc[i % per_cycle]).collect();
                let xk = least_squares(&cols, &rk)?;
                let xd = least_squares(&cols, &rd)?;
                let next = [xk[0], xk[1], xk[2]];
                let change = (0..3).map(|j| (next[j] - kl[j]).abs()).fold(0.0, f64::max);
                kl = next;
                dl = [xd[0], xd[1], xd[2]];
                let ku: Vec<f64> = (0..m).map(|i| k[i] / (1.0 + term(&kl, i))).collect();
                let du: Vec<f64> = (0..m).map(|i| d[i] - term(&dl, i)).collect();
                let (kn, dn): (Vec<f64>, Vec<f64>) = (0..per_cycle)
                    .map(|p| (mean_at(&ku, p), mean_at(&du, p)))
                    .unzip();
                kc = kn;
                dc = dn;
                if change < 1e-12 {
                    break;
                }
            }
        }
        let mut r = Self {
            per_cycle,
            wheel_teeth,
            lobes,
            span_cycles,
            stiffness_cycle_n_per_m: kc,
            deflection_cycle_m: dc,
            stiffness_lobe: kl,
            deflection_lobe_m: dl,
            wheel_tooth_start: w0,
            wheel_tooth_per_cycle: per,
            cycle_mean_stiffness_n_per_m: (0..span_cycles)
                .map(|c| {
                    k[c * per_cycle..(c + 1) * per_cycle].iter().sum::<f64>() / per_cycle as f64
                })
                .collect(),
            cycle_wheel_tooth: (0..span_cycles)
                .map(|c| {
                    w[c * per_cycle..(c + 1) * per_cycle].iter().sum::<f64>() / per_cycle as f64
                })
                .collect(),
            max_residual_of_ptp: [0.0; 2],
            solved: None,
        };
        let (mut ek, mut ed) = (0.0f64, 0.0f64);
        for i in 0..m {
            let [kv, dv] = r.at(i % per_cycle, cyc[i]);
            ek = ek.max((kv - k[i]).abs());
            ed = ed.max((dv - d[i]).abs());
        }
        r.max_residual_of_ptp = [ek / ptp(k).max(1e-300), ed / ptp(d).max(1e-300)];
        Ok(r)
    }

    /// As [`Revolution::from_span`] on a span of at least one wheel
    /// revolution (z₂ mesh cycles: a stiffness file that holds every wheel
    /// tooth). The lobe is still fitted over the span, for comparison with
    /// a shorter span's; the excitation is the first z₂·P LTCA samples
    /// themselves (k and δ repeat after z₂ mesh cycles: the pinion is
    /// axisymmetric and the wheel has turned once).
    pub fn from_revolution(
        samples: &MeshSamples,
        wheel_tooth: &[f64],
        mesh_cycle_rad: f64,
        step_rad: f64,
        wheel_teeth: usize,
        lobes: usize,
    ) -> Result<Self, LumpedError> {
        let mut r = Self::from_span(
            samples,
            wheel_tooth,
            mesh_cycle_rad,
            step_rad,
            wheel_teeth,
            lobes,
        )?;
        if r.span_cycles < wheel_teeth {
            return Err(LumpedError::Input(format!(
                "revolution: the LTCA span holds {} mesh cycles, a wheel revolution {wheel_teeth}",
                r.span_cycles
            )));
        }
        let n = wheel_teeth * r.per_cycle;
        r.solved = Some([
            samples.tangent_n_per_m[..n].to_vec(),
            samples.deflection_m[..n].to_vec(),
        ]);
        Ok(r)
    }

    /// k and δ at cycle position `p` of the mesh cycle `c` (in cycles from
    /// the sweep start).
    fn at(&self, p: usize, c: f64) -> [f64; 2] {
        let psi = 2.0 * PI * (self.wheel_tooth_start + self.wheel_tooth_per_cycle * c)
            / self.wheel_teeth as f64;
        let (s, co) = (self.lobes as f64 * psi).sin_cos();
        let [c0, a, b] = self.stiffness_lobe;
        let [d0, da, db] = self.deflection_lobe_m;
        [
            self.stiffness_cycle_n_per_m[p] * (1.0 + c0 + a * co + b * s),
            self.deflection_cycle_m[p] + d0 + da * co + db * s,
        ]
    }

    /// Peak-to-peak of the lobe of k over its revolution mean,
    /// 2√(a² + b²)/(1 + c₀).
    pub fn stiffness_lobe_ptp(&self) -> f64 {
        let [c0, a, b] = self.stiffness_lobe;
        2.0 * a.hypot(b) / (1.0 + c0)
    }

    /// Wheel tooth (in [0, z₂/n)) where the fitted lobe term of k is least:
    /// a cos nψ + b sin nψ is least at nψ = atan2(b, a) + π. None for an
    /// axisymmetric wheel.
    pub fn stiffness_lobe_minimum_wheel_tooth(&self) -> Option<f64> {
        if self.lobes == 0 {
            return None;
        }
        let [_, a, b] = self.stiffness_lobe;
        let psi = (b.atan2(a) + PI) / self.lobes as f64;
        let lobe = self.wheel_teeth as f64 / self.lobes as f64;
        Some((psi * self.wheel_teeth as f64 / (2.0 * PI)).rem_euclid(lobe))
    }

    /// The z₂·P samples of one wheel revolution: k (N/m), δ (m): the
    /// LTCA's own when it covered the revolution, else the lobe model's.
    pub fn samples(&self) -> [Vec<f64>; 2] {
        if let Some(s) = &self.solved {
            return s.clone();
        }
        let n = self.wheel_teeth * self.per_cycle;
        let mut k = Vec::with_capacity(n);
        let mut d = Vec::with_capacity(n);
        for j in 0..n {
            let [kv, dv] = self.at(j % self.per_cycle, j as f64 / self.per_cycle as f64);
            k.push(kv);
            d.push(dv);
        }
        [k, d]
    }

    /// k(t), δ(t) as series over one wheel revolution at mesh period
    /// `mesh_period_s`, up to `mesh_harmonics` + ½ mesh orders, each with
    /// its residual at the revolution's samples against `tolerance` × ptp.
    pub fn series(
        &self,
        mesh_period_s: f64,
        mesh_harmonics: usize,
        tolerance: f64,
    ) -> Result<[FittedSeries; 2], LumpedError> {
        let period = mesh_period_s * self.wheel_teeth as f64;
        let n = self.wheel_teeth * self.per_cycle;
        let harmonics = (self.wheel_teeth * mesh_harmonics + self.wheel_teeth / 2).min(n / 2 - 1);
        let times: Vec<f64> = (0..n).map(|j| period * j as f64 / n as f64).collect();
        let [k, d] = self.samples();
        let fitted = |v: &[f64]| -> Result<FittedSeries, LumpedError> {
            let s = direct_series(v, period, harmonics)?;
            let r = s.max_residual(&times, v);
            let p = ptp(v);
            let rel = if p > 0.0 { r / p } else { 0.0 };
            Ok(FittedSeries {
                series: s,
                max_residual: r,
                max_residual_of_ptp: rel,
                tolerance_of_ptp: tolerance,
                met: rel <= tolerance,
            })
        };
        Ok([fitted(&k)?, fitted(&d)?])
    }
}

/// How far a per-tooth sequence (one value per mesh cycle over a whole
/// revolution, `values[c]` at wheel tooth c) is from repeating `lobes`
/// times per revolution: with s = z₂/n (not a whole number of teeth for
/// 43/3), v(c + s) by linear interpolation between its neighbours on the
/// periodic sequence, the mismatch e_c = v(c + s) − v(c). Returns
/// (max |e_c|, rms e_c) over the sequence's mean.
pub fn lobe_repeat_mismatch(values: &[f64], lobes: usize) -> Result<[f64; 2], LumpedError> {
    let z = values.len();
    if lobes == 0 || z < 2 * lobes {
        return Err(LumpedError::Input(format!(
            "lobe repeat: {z} values for {lobes} lobes"
        )));
    }
    let mean = values.iter().sum::<f64>() / z as f64;
    let s = z as f64 / lobes as f64;
    let (mut max, mut sq) = (0.0f64, 0.0);
    for c in 0..z {
        let x = c as f64 + s;
        let i = x.floor();
        let f = x - i;
        let i = i as usize;
        let v = (1.0 - f) * values[i % z] + f * values[(i + 1) % z];
        let e = v - values[c];
        max = max.max(e.abs());
        sq += e * e;
    }
    Ok([max / mean, (sq / z as f64).sqrt() / mean])
}

/// The series of period `period_s` with `harmonics` harmonics from samples
/// at t_j = j·period/N (j = 0..N−1) by the direct DFT:
/// a₀ = Σf/N, aₗ = (2/N) Σ f cos(2πlj/N), bₗ = (2/N) Σ f sin(2πlj/N);
/// harmonics < N/2 (interpolating the samples exactly when N is odd and
/// harmonics = (N − 1)/2).
pub fn direct_series(
    values: &[f64],
    period_s: f64,
    harmonics: usize,
) -> Result<FourierSeries, LumpedError> {
    let n = values.len();
    if n == 0 || 2 * harmonics >= n || !(period_s > 0.0 && period_s.is_finite()) {
        return Err(LumpedError::Input(format!(
            "direct DFT: {n} samples, {harmonics} harmonics (needs 2·harmonics < samples), period {period_s} s"
        )));
    }
    if values.iter().any(|v| !v.is_finite()) {
        return Err(LumpedError::Input(
            "direct DFT: a sample is not finite".into(),
        ));
    }
    let nf = n as f64;
    let mut cos = Vec::with_capacity(harmonics);
    let mut sin = Vec::with_capacity(harmonics);
    for l in 1..=harmonics {
        let (mut a, mut b) = (0.0, 0.0);
        for (j, v) in values.iter().enumerate() {
            // l·j mod N keeps the angle small and exact.
            let x = 2.0 * PI * ((l * j) % n) as f64 / nf;
            let (s, c) = x.sin_cos();
            a += v * c;
            b += v * s;
        }
        cos.push(2.0 * a / nf);
        sin.push(2.0 * b / nf);
    }
    Ok(FourierSeries {
        period_s,
        mean: values.iter().sum::<f64>() / nf,
        cos,
        sin,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lobe_repeat_mismatch_is_small_for_a_three_lobe_sequence_and_large_otherwise() {
        // 43 teeth, k = 1 + 0.05 cos(3ψ − 0.4): repeats every 43/3 teeth;
        // linear interpolation between teeth leaves at most
        // (1/8)(3·2π/43)²·0.05 = 1.2e-3.
        let three: Vec<f64> = (0..43)
            .map(|c| 1.0 + 0.05 * (3.0 * 2.0 * PI * c as f64 / 43.0 - 0.4).cos())
            .collect();
        let [max, rms] = lobe_repeat_mismatch(&three, 3).unwrap();
        assert!(max < 1.2e-3 && rms <= max, "{max} {rms}");
        // One lobe per revolution of the same size does not repeat every
        // third of it: 2·0.05·sin(π/3) = 0.087 at most.
        let one: Vec<f64> = (0..43)
            .map(|c| 1.0 + 0.05 * (2.0 * PI * c as f64 / 43.0).cos())
            .collect();
        let [max, _] = lobe_repeat_mismatch(&one, 3).unwrap();
        assert!((max - 0.0866).abs() < 2e-3, "{max}");
    }

    #[test]
    fn direct_dft_recovers_the_harmonics_of_sampled_cosines() {
        let n = 86;
        let period = 2.0;
        let v: Vec<f64> = (0..n)
            .map(|j| {
                let x = 2.0 * PI * j as f64 / n as f64;
                3.0 + 0.5 * (3.0 * x).cos() - 0.25 * (43.0 * x - 0.3).cos()
            })
            .collect();
        let s = direct_series(&v, period, 42).unwrap();
        assert!((s.mean - 3.0).abs() < 1e-12);
        let amp = s.amplitudes();
        for (l, a) in amp.iter().enumerate() {
            let want = match l + 1 {
                3 => 0.5,
                _ => 0.0,
            };
            assert!((a - want).abs() < 1e-12, "harmonic {}: {a}", l + 1);
        }
        // 43 = N/2 is the Nyquist line: left out, not folded in.
        assert!(direct_series(&v, period, 43).is_err());
    }
}
