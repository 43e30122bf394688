//! Free vibration of the linear 8-DOF model (constant mesh stiffness, no
//! damping, no load): started in each mode shape of (K, M), the time
//! integration oscillates at that mode's frequency √λ, λ a generalized
//! eigenvalue of K φ = λ M φ (nalgebra), within 1e-6; and the energy
//! ½q̇ᵀMq̇ + ½qᵀKq stays within 1e-6 of its start over 10 mesh cycles.
//!
//! Tolerances: these checks need the integration error well below 1e-6,
//! so they run Dormand–Prince 5(4) at rtol = 1e-11 with atol = 1e-11 times
//! each component's scale (seed 004's rtol = 1e-6 is for the loaded runs;
//! its error over a run is about 1e-6 times the number of steps, too large
//! to see a 1e-6 frequency or energy error).

#[path = "support/lumped_case.rs"]
mod lumped_case;

use lumped_case::{model, K_MEAN, MESH_HZ};
use nalgebra::{DMatrix, SymmetricEigen};
use solver::lumped::excitation::{FourierSeries, MeshExcitation, StaticError};
use solver::lumped::integrate::{energy, integrate, Equations, Settings};

const RTOL: f64 = 1e-11;

fn constant_excitation() -> MeshExcitation {
    MeshExcitation {
        stiffness: FourierSeries::constant(K_MEAN, 1.0 / MESH_HZ),
        transmission_error: StaticError::Series(FourierSeries::constant(0.0, 1.0 / MESH_HZ)),
        impact: None,
        friction: None,
    }
}

/// ω² and mass-normalized shapes of K φ = λ M φ, ascending.
fn modes(k: &DMatrix<f64>, m_diag: &[f64]) -> Vec<(f64, Vec<f64>)> {
    let s: Vec<f64> = m_diag.iter().map(|m| 1.0 / m.sqrt()).collect();
    let a = DMatrix::from_fn(8, 8, |i, j| s[i] * k[(i, j)] * s[j]);
    let e = SymmetricEigen::new(a);
    let mut v: Vec<(f64, Vec<f64>)> = (0..8)
        .map(|c| {
            (
                e.eigenvalues[c],
                (0..8).map(|i| s[i] * e.eigenvectors[(i, c)]).collect(),
            )
        })
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// Root of the cubic Hermite interpolant of (t, η, η̇) between two samples
/// whose η differ in sign.
fn hermite_root(t: [f64; 2], y: [f64; 2], yd: [f64; 2]) -> f64 {
    let h = t[1] - t[0];
    let p = |s: f64| {
        let (s2, s3) = (s * s, s * s * s);
        (2.0 * s3 - 3.0 * s2 + 1.0) * y[0]
            + (s3 - 2.0 * s2 + s) * h * yd[0]
            + (-2.0 * s3 + 3.0 * s2) * y[1]
            + (s3 - s2) * h * yd[1]
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if (p(mid) > 0.0) == (p(lo) > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    t[0] + 0.5 * (lo + hi) * h
}

#[test]
fn lumped_free_vibration_frequencies_equal_the_eigenvalues_of_m_and_k() {
    let m = model();
    m.check().unwrap();
    let exc = constant_excitation();
    let eq = Equations::new(&m, &exc);
    let kmat = m.stiffness(K_MEAN);
    let k = DMatrix::from_fn(8, 8, |i, j| kmat[(i, j)]);
    let md = m.mass_diagonal();
    let all = modes(&k, &md);
    // One rigid mode (the free rotation (θ₁, θ₂) ∝ (r₂, r₁)), seven elastic.
    assert!(all[0].0.abs() < 1e-6 * all[1].0, "{:?}", all[0].0);
    assert!(all[1].0 > 1e3, "second eigenvalue {}", all[1].0);
    for (lam, phi) in &all[1..] {
        let w = lam.sqrt();
        let amp = 1e-6 / phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let mut y0 = [0.0; 16];
        for i in 0..8 {
            y0[i] = amp * phi[i];
        }
        let period = 2.0 * std::f64::consts::PI / w;
        let mut atol = [0.0; 16];
        for i in 0..8 {
            atol[i] = RTOL * 1e-6;
            atol[8 + i] = RTOL * 1e-6 * w;
        }
        let cycles = 12.0;
        let h = integrate(
            &eq,
            y0,
            &Settings {
                t_span_s: [0.0, cycles * period],
                output_step_s: period / 64.0,
                rtol: RTOL,
                atol,
                max_step_s: period / 8.0,
                max_steps: 1_000_000,
            },
        )
        .unwrap();
        // Modal coordinate η = φᵀ M q / (φᵀ M φ · amp) = cos ωt.
        let norm: f64 = (0..8).map(|i| phi[i] * md[i] * phi[i]).sum::<f64>() * amp;
        let eta = |q: &[f64; 8]| (0..8).map(|i| phi[i] * md[i] * q[i]).sum::<f64>() / norm;
        let mut crossings = Vec::new();
        for j in 1..h.t.len() {
            let (a, b) = (eta(&h.q[j - 1]), eta(&h.q[j]));
            if a != 0.0 && (a > 0.0) != (b > 0.0) {
                crossings.push(hermite_root(
                    [h.t[j - 1], h.t[j]],
                    [a, b],
                    [eta(&h.qd[j - 1]), eta(&h.qd[j])],
                ));
            }
        }
        assert_eq!(crossings.len(), 24, "zero crossings of mode ω = {w}");
        // The n-th crossing of cos ωt is at (2n − 1)π/(2ω).
        let n = crossings.len() as f64;
        let measured = (2.0 * n - 1.0) * std::f64::consts::PI / (2.0 * crossings[23]);
        let rel = (measured / w - 1.0).abs();
        eprintln!(
            "mode {:9.2} Hz: measured {:9.2} Hz, relative error {rel:.2e}",
            w / (2.0 * std::f64::consts::PI),
            measured / (2.0 * std::f64::consts::PI)
        );
        assert!(rel < 1e-6, "ω {w} rad/s, measured {measured}: {rel:e}");
        // And the shape holds: the other modes stay unexcited.
        let worst =
            h.q.iter()
                .zip(&h.t)
                .map(|(q, t)| {
                    (0..8)
                        .map(|i| (q[i] - amp * phi[i] * (w * t).cos()).abs())
                        .fold(0.0f64, f64::max)
                })
                .fold(0.0f64, f64::max);
        assert!(
            worst < 1e-4 * 1e-6,
            "departure from the mode shape {worst:e} m"
        );
    }
}

#[test]
fn lumped_undamped_energy_is_kept_within_1e_6_over_10_mesh_cycles() {
    let m = model();
    let exc = constant_excitation();
    let eq = Equations::new(&m, &exc);
    // Every coordinate and velocity displaced: all modes excited.
    let q0 = [1e-6, -2e-6, 1.5e-6, 3e-5, -0.5e-6, 1e-6, -1e-6, -1e-5];
    let qd0 = [1e-2, 2e-2, -1e-2, 0.5, -1e-2, 5e-3, 1e-2, 0.1];
    let mut y0 = [0.0; 16];
    y0[..8].copy_from_slice(&q0);
    y0[8..].copy_from_slice(&qd0);
    let mut atol = [RTOL * 1e-6; 16];
    for a in atol.iter_mut().skip(8) {
        *a = RTOL * 1e-2;
    }
    let t_end = 10.0 / MESH_HZ;
    let h = integrate(
        &eq,
        y0,
        &Settings {
            t_span_s: [0.0, t_end],
            output_step_s: 1.0 / (MESH_HZ * 100.0),
            rtol: RTOL,
            atol,
            max_step_s: t_end,
            max_steps: 1_000_000,
        },
    )
    .unwrap();
    let e0 = energy(&m, K_MEAN, &q0, &qd0);
    assert!(e0 > 0.0);
    let worst =
        h.q.iter()
            .zip(&h.qd)
            .map(|(q, qd)| (energy(&m, K_MEAN, q, qd) / e0 - 1.0).abs())
            .fold(0.0f64, f64::max);
    eprintln!(
        "energy drift {worst:.2e} over {} samples, {} steps",
        h.t.len(),
        h.steps[0]
    );
    assert!(h.t.len() >= 1000, "{} samples", h.t.len());
    assert!(worst < 1e-6, "energy drift {worst:e}");
    // With mesh damping the energy must fall: the check can tell.
    let mut md = m.clone();
    md.mesh_damping_ns_per_m = 2e3;
    let eqd = Equations::new(&md, &exc);
    let hd = integrate(
        &eqd,
        y0,
        &Settings {
            t_span_s: [0.0, t_end],
            output_step_s: t_end / 10.0,
            rtol: RTOL,
            atol,
            max_step_s: t_end,
            max_steps: 1_000_000,
        },
    )
    .unwrap();
    let last = hd.t.len() - 1;
    let el = energy(&md, K_MEAN, &hd.q[last], &hd.qd[last]);
    assert!(el < 0.99 * e0, "damped energy {el} of {e0}");
}

#[test]
fn lumped_run_at_a_crawl_is_refused_before_integrating_with_its_step_estimate() {
    // At 1e-6 of the case's mesh frequency the 10 mesh cycles span 4,400 s,
    // while the bearing and mesh modes (a few kHz) hold the step near
    // 4e-5 s: over 1e8 steps, beyond the 5e7-step budget. Refused up front
    // as an input, not after minutes of integration.
    let m = model();
    let exc = constant_excitation();
    let slow = 1e-6 * MESH_HZ;
    let e = solver::lumped::run::simulate(&m, &exc, slow, 10.0, 32, 1e-6).unwrap_err();
    assert!(matches!(e, solver::lumped::LumpedError::Input(_)), "{e}");
    let msg = e.to_string();
    for w in ["budget", "raise the pinion speed", "mesh cycles"] {
        assert!(msg.contains(w), "'{w}' not in: {msg}");
    }
    // At the case's own speed the same run passes the check.
    let s = solver::lumped::run::settings(&m, &exc, MESH_HZ, 10.0, 32, 1e-6);
    solver::lumped::run::check_step_budget(&s, MESH_HZ, 10.0).unwrap();
}
