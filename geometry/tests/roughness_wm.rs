//! The W–M roughness generator against what a surface metrologist would
//! measure: Ra over an ISO evaluation length, the PSD's log–log slope
//! (β = −(5 − 2D), seed 003's Eq. (2)), and reproducibility by seed.

use geometry::roughness::{
    seed003_fractal, RoughnessError, WmProfile, WmSpec, ROUGHNESS_CUTOFF_M, SEED003_GAMMA,
};
use std::f64::consts::PI;

/// Seed 003's grades, Ra in µm (its Tables 1–2).
const GRADES_UM: [f64; 3] = [0.8, 0.4, 0.2];

/// Ra of samples about their mean line.
fn ra(z: &[f64]) -> f64 {
    let mean = z.iter().sum::<f64>() / z.len() as f64;
    z.iter().map(|v| (v - mean).abs()).sum::<f64>() / z.len() as f64
}

#[test]
fn seed003_relations_give_its_eqs_33_34_41_values_and_eq_41_its_table_2() {
    // Hand-evaluated Eqs. (33), (34) and (41); Table 2's D = 1.55/1.60/1.65
    // agree with Eq. (41) within 0.016 and with Eq. (33) only at 0.8 µm.
    let expected = [
        (0.8, 1.5450, 1.5424, 4.903e-6, 1.55),
        (0.4, 1.6422, 1.5880, 3.417e-6, 1.60),
        (0.2, 1.7455, 1.6349, 2.356e-6, 1.65),
    ];
    for (ra_um, d33, d41, g, table) in expected {
        let f = seed003_fractal(ra_um).unwrap();
        assert!(
            (f.dimension_eq33 - d33).abs() < 1e-4,
            "Eq. (33) D({ra_um}) = {}",
            f.dimension_eq33
        );
        assert!(
            (f.dimension - d41).abs() < 1e-4,
            "Eq. (41) D({ra_um}) = {}",
            f.dimension
        );
        assert!((f.dimension - table).abs() < 0.016, "Table 2 at {ra_um}");
        assert!(
            (f.scale_mm / g - 1.0).abs() < 1e-3,
            "G({ra_um}) = {}",
            f.scale_mm
        );
    }
    assert!((seed003_fractal(0.2).unwrap().dimension_eq33 - 1.65).abs() > 0.09);
}

#[test]
fn measured_ra_over_the_evaluation_length_matches_the_requested_ra() {
    // ISO 4288: evaluation length 5 λc; sampled every 0.5 µm (5 points per
    // shortest wavelength); the mean over 32 phase draws, and every single
    // draw within 20 %.
    let length = 5.0 * ROUGHNESS_CUTOFF_M;
    let dx = 0.5e-6;
    let n = (length / dx) as usize;
    for ra_um in GRADES_UM {
        let mut sum = 0.0;
        for seed in 0..32u64 {
            let p = WmProfile::seed003(ra_um, seed).unwrap();
            let z: Vec<f64> = (0..n).map(|i| p.height_m(i as f64 * dx)).collect();
            let r = ra(&z) * 1e6;
            assert!(
                (r / ra_um - 1.0).abs() < 0.2,
                "seed {seed}: Ra {r} µm for {ra_um}"
            );
            sum += r;
        }
        let mean = sum / 32.0;
        println!("Ra requested {ra_um} µm: mean measured {mean:.4} µm over 32 seeds");
        assert!(
            (mean / ra_um - 1.0).abs() < 0.05,
            "mean Ra {mean} µm for requested {ra_um} µm"
        );
    }
}

/// In-place radix-2 FFT of (re, im); the length must be a power of two.
fn fft(re: &mut [f64], im: &mut [f64]) {
    let n = re.len();
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let ang = -2.0 * PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (ang * k as f64).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let tr = re[b] * c - im[b] * s;
                let ti = re[b] * s + im[b] * c;
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
            }
        }
        len <<= 1;
    }
}

#[test]
fn psd_slope_and_level_give_the_requested_dimension_and_scale() {
    // γ = 1.5 = 3/2: over a record of 2^10 λ_l every line ω_n = 3ⁿ/2ⁿ/λ_l
    // (n ≤ 10) falls on DFT bin 3ⁿ·2^(10−n), so no window is needed. The
    // one-sided periodogram's power is summed over each line's logarithmic
    // bin [ω_n/√γ, ω_n·√γ) and spread over ω_n ln γ (Eq. (2)); log S against
    // log ω is fitted by least squares.
    let lambda_l = 1e-3;
    for ra_um in GRADES_UM {
        let d = seed003_fractal(ra_um).unwrap().dimension;
        let spec = WmSpec {
            dimension: d,
            scale_m: 1e-9,
            gamma: SEED003_GAMMA,
            longest_wavelength_m: lambda_l,
            shortest_wavelength_m: lambda_l / SEED003_GAMMA.powi(10) * 0.999,
        };
        let p = WmProfile::with_ra(spec, ra_um * 1e-6, 7).unwrap();
        assert_eq!(p.frequencies_per_m().len(), 11);
        let record = 1024.0 * lambda_l;
        let n = 1usize << 17;
        let dx = record / n as f64;
        let mut re: Vec<f64> = (0..n).map(|i| p.height_m(i as f64 * dx)).collect();
        let mut im = vec![0.0; n];
        fft(&mut re, &mut im);
        let gamma = SEED003_GAMMA;
        let (mut xs, mut ys) = (vec![], vec![]);
        for line in 0..=10i32 {
            let w = gamma.powi(line) / lambda_l;
            let lo = (w / gamma.sqrt() * record).ceil() as usize;
            let hi = ((w * gamma.sqrt() * record).ceil() as usize).min(n / 2);
            // Mean square of the bins' components: 2|X_k|²/N² per one-sided bin.
            let power: f64 = (lo..hi)
                .map(|k| 2.0 * (re[k] * re[k] + im[k] * im[k]) / (n as f64 * n as f64))
                .sum();
            xs.push(w.ln());
            ys.push((power / (w * gamma.ln())).ln());
        }
        let m = xs.len() as f64;
        let (mx, my) = (xs.iter().sum::<f64>() / m, ys.iter().sum::<f64>() / m);
        let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
        let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let expected_slope = -(5.0 - 2.0 * d);
        assert!(
            (slope / expected_slope - 1.0).abs() < 0.05,
            "Ra {ra_um}: slope {slope}, expected {expected_slope}"
        );
        let d_measured = (5.0 + slope) / 2.0;
        println!("Ra {ra_um} µm: PSD slope {slope:.4} (expected {expected_slope:.4}), D {d_measured:.4} vs {d:.4}");
        assert!((d_measured / d - 1.0).abs() < 0.05, "D {d_measured} vs {d}");
        // Level: S = G^(2(D−1)) / (2 ln γ) ω^β → G.
        let g = ((intercept + (2.0 * gamma.ln()).ln()) / (2.0 * (d_measured - 1.0))).exp();
        let g_req = p.spec().scale_m;
        assert!((g / g_req - 1.0).abs() < 0.05, "G {g} m vs {g_req} m");
    }
}

#[test]
fn same_seed_gives_the_same_profile_and_another_seed_another() {
    let a = WmProfile::seed003(0.4, 42).unwrap();
    let b = WmProfile::seed003(0.4, 42).unwrap();
    let c = WmProfile::seed003(0.4, 43).unwrap();
    let xs: Vec<f64> = (0..500).map(|i| i as f64 * 1.3e-6).collect();
    let za: Vec<f64> = xs.iter().map(|&x| a.height_m(x)).collect();
    let zb: Vec<f64> = xs.iter().map(|&x| b.height_m(x)).collect();
    let zc: Vec<f64> = xs.iter().map(|&x| c.height_m(x)).collect();
    assert_eq!(za, zb);
    let diff = za
        .iter()
        .zip(&zc)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(diff > 0.1e-6, "seeds 42 and 43 differ by only {diff} m");
}

#[test]
fn flank_topography_is_in_um_along_the_profile_and_band_limited_to_the_grid() {
    // Long wavelengths so the 101-node grid over 10 mm carries every term:
    // the nodes then hold the profile itself, in µm, constant along the face.
    let spec = WmSpec {
        dimension: 1.6,
        scale_m: 1e-9,
        gamma: SEED003_GAMMA,
        longest_wavelength_m: 10e-3,
        shortest_wavelength_m: 0.5e-3,
    };
    let p = WmProfile::with_ra(spec, 1e-6, 3).unwrap();
    let t = p.topography(10e-3, 101, 4).unwrap();
    assert_eq!((t.profile.len(), t.face.len()), (101, 4));
    for (i, eta) in t.profile.iter().enumerate() {
        let z_um = p.height_m(eta * 10e-3) * 1e6;
        for v in &t.deviation_um[i] {
            assert!((v - z_um).abs() < 1e-9);
        }
    }
    let ra_grid = ra(&t.deviation_um.iter().map(|r| r[0]).collect::<Vec<_>>());
    assert!(ra_grid > 0.3 && ra_grid < 3.0, "grid Ra {ra_grid} µm");
    // An 11-node grid (1 mm spacing) keeps only λ ≥ 2 mm: the same phases
    // (drawn in order) and scale with λ_s = 2 mm give the same node values.
    let coarse = p.topography(10e-3, 11, 2).unwrap();
    let long_only = WmProfile::new(
        WmSpec {
            shortest_wavelength_m: 2e-3,
            ..*p.spec()
        },
        3,
    )
    .unwrap();
    assert_eq!(long_only.frequencies_per_m().len(), 4);
    for (i, eta) in coarse.profile.iter().enumerate() {
        let z_um = long_only.height_m(eta * 10e-3) * 1e6;
        assert!((coarse.deviation_um[i][1] - z_um).abs() < 1e-9, "node {i}");
    }
}

#[test]
fn bad_roughness_input_is_refused_with_the_field() {
    assert!(matches!(
        seed003_fractal(-0.4),
        Err(RoughnessError::Invalid { field: "ra_um", .. })
    ));
    let spec = WmSpec {
        dimension: 2.1,
        scale_m: 1e-9,
        gamma: 1.5,
        longest_wavelength_m: 1e-3,
        shortest_wavelength_m: 1e-6,
    };
    assert!(matches!(
        WmProfile::new(spec, 0),
        Err(RoughnessError::Invalid {
            field: "dimension",
            ..
        })
    ));
    let spec = WmSpec {
        dimension: 1.5,
        ..spec
    };
    assert!(matches!(
        WmProfile::with_ra(spec, f64::NAN, 0),
        Err(RoughnessError::Invalid { field: "ra_m", .. })
    ));
    let p = WmProfile::new(spec, 0).unwrap();
    assert!(p.topography(0.0, 10, 10).is_err());
    assert!(p.topography(1e-2, 1, 10).is_err());
}
