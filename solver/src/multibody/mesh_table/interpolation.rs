//! The table's interpolation and integration weights: Catmull–Rom in q₁,
//! cubic Hermite on the lag grid, the node stencils, 4-point Gauss–Legendre,
//! and the lag grid itself.

/// Catmull–Rom weights of nodes i−1..i+2 and their first and second
/// derivatives with respect to t ∈ [0, 1] in cell i.
pub(super) fn catmull_rom(t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ],
        [
            0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
            0.5 * (9.0 * t2 - 10.0 * t),
            0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
            0.5 * (3.0 * t2 - 2.0 * t),
        ],
        [-3.0 * t + 2.0, 9.0 * t - 5.0, -9.0 * t + 4.0, 3.0 * t - 1.0],
    ]
}

/// Lag nodes for a table whose unloaded TEs lie in [lo, te0_max] and whose
/// largest lag is hi: a third of the n nodes uniform from one step below lo
/// over twice the unloaded band (where light loads act: T₁ rises from zero
/// at θ₀(q₁), which moves across that band), the rest growing
/// geometrically up to hi (T₁ nearly linear in θ there).
/// At least 3 band nodes (one spacing and the node below `lo`), so that
/// any n ≥ 4 gives a finite grid (n = 8 made the spacing band / 0).
pub fn lag_grid(lo: f64, te0_max: f64, hi: f64, n: usize) -> Vec<f64> {
    let band = (2.0 * (te0_max - lo))
        .max(1e-3 * (hi - lo))
        .min(0.5 * (hi - lo));
    let n_band = (n / 3).max(3).min(n - 1);
    let d0 = band / (n_band - 2) as f64;
    let mut out: Vec<f64> = (0..n_band).map(|m| lo - d0 + d0 * m as f64).collect();
    let rest = n - n_band;
    let start = *out.last().unwrap();
    let need = hi - start;
    // d0 (q + q² + … + q^rest) = need, q ≥ 1 by bisection.
    let sum = |q: f64| (1..=rest).map(|k| d0 * q.powi(k as i32)).sum::<f64>();
    let q = if sum(1.0) >= need {
        need / (d0 * rest as f64)
    } else {
        let (mut a, mut b) = (1.0, 2.0);
        while sum(b) < need {
            b *= 2.0;
        }
        for _ in 0..200 {
            let c = 0.5 * (a + b);
            if sum(c) < need {
                a = c;
            } else {
                b = c;
            }
        }
        0.5 * (a + b)
    };
    let mut x = start;
    for k in 1..=rest {
        x += if q < 1.0 {
            d0 * q
        } else {
            d0 * q.powi(k as i32)
        };
        out.push(x);
    }
    *out.last_mut().unwrap() = hi.max(start + f64::EPSILON);
    out
}

/// Cubic Hermite weights on a non-uniform grid x, cell [x_m, x_{m+1}], at
/// `at`: slopes from central differences, d_m = (f_{m+1} − f_{m−1}) /
/// (x_{m+1} − x_{m−1}); outside the grid the nodes continue with the end
/// spacing. Returns the weights of f_{m−1..m+2} for the value and its first
/// and second derivatives in x. On a uniform grid these are Catmull–Rom's.
pub(super) fn hermite_weights(x: &[f64], m: usize, at: f64) -> [[f64; 4]; 3] {
    let n = x.len();
    let node = |k: i64| -> f64 {
        if k < 0 {
            x[0] + (x[0] - x[1]) * (-k) as f64
        } else if k >= n as i64 {
            x[n - 1] + (x[n - 1] - x[n - 2]) * (k - n as i64 + 1) as f64
        } else {
            x[k as usize]
        }
    };
    let m = m as i64;
    let (xa, x0, x1, xb) = (node(m - 1), node(m), node(m + 1), node(m + 2));
    let h = x1 - x0;
    let t = (at - x0) / h;
    let (a, b) = (h / (x1 - xa), h / (xb - x0));
    let (t2, t3) = (t * t, t * t * t);
    // Hermite basis and its t-derivatives.
    let h00 = [
        2.0 * t3 - 3.0 * t2 + 1.0,
        6.0 * t2 - 6.0 * t,
        12.0 * t - 6.0,
    ];
    let h10 = [t3 - 2.0 * t2 + t, 3.0 * t2 - 4.0 * t + 1.0, 6.0 * t - 4.0];
    let h01 = [-2.0 * t3 + 3.0 * t2, -6.0 * t2 + 6.0 * t, -12.0 * t + 6.0];
    let h11 = [t3 - t2, 3.0 * t2 - 2.0 * t, 6.0 * t - 2.0];
    let scale = [1.0, 1.0 / h, 1.0 / (h * h)];
    std::array::from_fn(|r| {
        [
            -h10[r] * a * scale[r],
            (h00[r] - h11[r] * b) * scale[r],
            (h01[r] + h10[r] * a) * scale[r],
            h11[r] * b * scale[r],
        ]
    })
}

/// 1-D node values around a cell: periodic wrap or linear continuation past the ends.
pub(super) fn stencil(n: usize, periodic: bool, i: i64, value: impl Fn(usize) -> f64) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (o, v) in out.iter_mut().enumerate() {
        let k = i - 1 + o as i64;
        *v = if periodic {
            value(k.rem_euclid(n as i64) as usize)
        } else if k < 0 {
            let (a, b) = (value(0), value(1));
            a + (a - b) * (-k) as f64
        } else if k >= n as i64 {
            let (a, b) = (value(n - 1), value(n - 2));
            a + (a - b) * (k - n as i64 + 1) as f64
        } else {
            value(k as usize)
        };
    }
    out
}

/// Gauss–Legendre nodes and weights on [0, 1], 4 points (exact to degree 7).
pub(super) fn gauss4() -> [(f64, f64); 4] {
    const X: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
    const W: [f64; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
    [
        (0.5 * (1.0 - X[1]), 0.5 * W[1]),
        (0.5 * (1.0 - X[0]), 0.5 * W[0]),
        (0.5 * (1.0 + X[0]), 0.5 * W[0]),
        (0.5 * (1.0 + X[1]), 0.5 * W[1]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hermite_weights_are_catmull_rom_on_a_uniform_grid_and_reproduce_lines_on_any() {
        let uniform: Vec<f64> = (0..8).map(|k| 0.5 * k as f64).collect();
        let graded = [0.0, 0.1, 0.2, 0.35, 0.6, 1.0, 1.7, 3.0];
        for t in [0.0, 0.3, 0.77, 1.0] {
            let w = hermite_weights(&uniform, 3, 1.5 + 0.5 * t);
            let c = catmull_rom(t);
            for r in 0..3 {
                for k in 0..4 {
                    let scaled = c[r][k] / 0.5f64.powi(r as i32);
                    assert!((w[r][k] - scaled).abs() < 1e-12, "{r} {k}");
                }
            }
        }
        // f(x) = 2 + 3x on the graded grid, every cell incl. the end ones.
        for m in 0..graded.len() - 1 {
            for t in [0.0, 0.4, 1.0] {
                let at = graded[m] + t * (graded[m + 1] - graded[m]);
                let w = hermite_weights(&graded, m, at);
                let node = |k: i64| {
                    let n = graded.len() as i64;
                    if k < 0 {
                        graded[0] - (graded[1] - graded[0])
                    } else if k >= n {
                        2.0 * graded[7] - graded[6]
                    } else {
                        graded[k as usize]
                    }
                };
                let f: Vec<f64> = (0..4).map(|b| 2.0 + 3.0 * node(m as i64 - 1 + b)).collect();
                let v: f64 = (0..4).map(|b| w[0][b] * f[b]).sum();
                let d: f64 = (0..4).map(|b| w[1][b] * f[b]).sum();
                let dd: f64 = (0..4).map(|b| w[2][b] * f[b]).sum();
                assert!((v - (2.0 + 3.0 * at)).abs() < 1e-12, "value at {at}");
                assert!((d - 3.0).abs() < 1e-10 && dd.abs() < 1e-9, "slopes at {at}");
            }
        }
    }

    #[test]
    fn lag_grid_is_fine_over_twice_the_unloaded_band_and_ends_at_the_largest_lag() {
        let (lo, te0_max, hi, n) = (10e-6, 40e-6, 2.5e-3, 96);
        let g = lag_grid(lo, te0_max, hi, n);
        assert_eq!(g.len(), n);
        assert!(g.windows(2).all(|w| w[1] > w[0]));
        assert!(g[0] < lo && (g[n - 1] - hi).abs() < 1e-15);
        let d0 = g[1] - g[0];
        // Uniform up to lo + 2 (te0_max − lo), then growing.
        let band_end = g
            .iter()
            .position(|&x| x >= lo + 2.0 * (te0_max - lo) - 1e-15)
            .unwrap();
        for w in g[..=band_end].windows(2) {
            assert!((w[1] - w[0] - d0).abs() < 1e-12 * hi);
        }
        // 32 of 96 nodes over 60 µrad.
        assert!((d0 - 60e-6 / 30.0).abs() < 1e-12, "band step {d0}");
        let steps: Vec<f64> = g[band_end..].windows(2).map(|w| w[1] - w[0]).collect();
        assert!(steps.windows(2).all(|s| s[1] >= s[0] * (1.0 - 1e-9)));
    }

    #[test]
    fn catmull_rom_weights_sum_to_one_and_reproduce_lines() {
        for t in [0.0, 0.3, 0.77, 1.0] {
            let w = catmull_rom(t);
            assert!((w[0].iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(w[1].iter().sum::<f64>().abs() < 1e-14);
            assert!(w[2].iter().sum::<f64>().abs() < 1e-14);
            // Nodes at −1, 0, 1, 2: a line x ↦ x gives t and slope 1.
            let x = [-1.0, 0.0, 1.0, 2.0];
            let v: f64 = (0..4).map(|k| w[0][k] * x[k]).sum();
            let d: f64 = (0..4).map(|k| w[1][k] * x[k]).sum();
            assert!((v - t).abs() < 1e-14 && (d - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn gauss4_integrates_degree_7_exactly() {
        let s: f64 = gauss4().iter().map(|(x, w)| w * x.powi(7)).sum();
        assert!((s - 1.0 / 8.0).abs() < 1e-15);
    }
}
