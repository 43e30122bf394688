//! Interpolation weights on the stiffness files' regular flank grids.
//!
//! One dimension: Catmull–Rom cubic on uniformly spaced nodes xᵢ; on the
//! segment [x_k, x_{k+1}] with s = (x − x_k)/Δ
//!
//!   f(x) = ½[(−s³ + 2s² − s) f_{k−1} + (3s³ − 5s² + 2) f_k + (−3s³ + 4s² + s) f_{k+1} + (s³ − s²) f_{k+2}],
//!
//! C¹, exact for quadratics inside, with ghost nodes f₋₁ = 2f₀ − f₁ and
//! f_n = 2f_{n−1} − f_{n−2} at the ends (exact for linear functions there).
//! Outside the node range the function continues linearly with the end
//! slope (f₁ − f₀)/Δ, so it stays C¹. Two dimensions: the tensor product.

/// Sparse weights: (node index, weight), weights summing to 1.
pub type Weights = Vec<(usize, f64)>;

/// Weights of the value at `x` from values at uniformly spaced `nodes`.
pub fn cubic_weights(nodes: &[f64], x: f64) -> Weights {
    let n = nodes.len();
    match n {
        0 => return Vec::new(),
        1 => return vec![(0, 1.0)],
        _ => {}
    }
    let h = nodes[1] - nodes[0];
    let t = (x - nodes[0]) / h;
    if t <= 0.0 {
        return vec![(0, 1.0 - t), (1, t)];
    }
    if t >= (n - 1) as f64 {
        let d = t - (n - 1) as f64;
        return vec![(n - 1, 1.0 + d), (n - 2, -d)];
    }
    if n == 2 {
        return vec![(0, 1.0 - t), (1, t)];
    }
    let k = (t.floor() as usize).min(n - 2);
    let s = t - k as f64;
    let (s2, s3) = (s * s, s * s * s);
    let w = [
        0.5 * (-s3 + 2.0 * s2 - s),
        0.5 * (3.0 * s3 - 5.0 * s2 + 2.0),
        0.5 * (-3.0 * s3 + 4.0 * s2 + s),
        0.5 * (s3 - s2),
    ];
    let mut out: Weights = Vec::with_capacity(4);
    let mut add = |i: usize, v: f64| match out.iter_mut().find(|e| e.0 == i) {
        Some(e) => e.1 += v,
        None => out.push((i, v)),
    };
    for (m, &wm) in w.iter().enumerate() {
        let i = k as i64 - 1 + m as i64;
        if i < 0 {
            add(0, 2.0 * wm);
            add(1, -wm);
        } else if i as usize >= n {
            add(n - 1, 2.0 * wm);
            add(n - 2, -wm);
        } else {
            add(i as usize, wm);
        }
    }
    out
}

/// Tensor-product weights on a face × profile grid (index i_face · n_profile + i_profile).
pub fn grid_weights(xi_nodes: &[f64], eta_nodes: &[f64], xi: f64, eta: f64) -> Weights {
    let np = eta_nodes.len();
    let wf = cubic_weights(xi_nodes, xi);
    let wp = cubic_weights(eta_nodes, eta);
    let mut out = Vec::with_capacity(wf.len() * wp.len());
    for &(i, a) in &wf {
        for &(j, b) in &wp {
            out.push((i * np + j, a * b));
        }
    }
    out
}

/// Σ w · values.
pub fn apply(w: &Weights, values: &[f64]) -> f64 {
    w.iter().map(|&(i, c)| c * values[i]).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn centres(n: usize) -> Vec<f64> {
        (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect()
    }

    #[test]
    fn cubic_reproduces_quadratics_inside_and_lines_everywhere() {
        let x = centres(12);
        let quad = |t: f64| 3.0 - 2.0 * t + 5.0 * t * t;
        let line = |t: f64| 0.7 + 4.0 * t;
        let fq: Vec<f64> = x.iter().map(|&t| quad(t)).collect();
        let fl: Vec<f64> = x.iter().map(|&t| line(t)).collect();
        for k in 0..=200 {
            let t = -0.1 + 1.2 * k as f64 / 200.0;
            let w = cubic_weights(&x, t);
            assert!((w.iter().map(|e| e.1).sum::<f64>() - 1.0).abs() < 1e-14);
            assert!((apply(&w, &fl) - line(t)).abs() < 1e-12, "line at {t}");
            // Interior segments (all four nodes real) are exact for quadratics.
            if t >= x[1] && t <= x[10] {
                assert!((apply(&w, &fq) - quad(t)).abs() < 1e-12, "quadratic at {t}");
            }
        }
    }

    #[test]
    fn cubic_interpolation_error_falls_with_the_cube_of_the_spacing_inside() {
        // Catmull–Rom is third-order accurate where all four nodes are real:
        // the error drops by ~8 when the spacing halves. The end segments use
        // a linearly extrapolated ghost node and are second order.
        let f = |t: f64| (3.0 * t).sin();
        let err = |n: usize, lo: usize| {
            let x = centres(n);
            let v: Vec<f64> = x.iter().map(|&t| f(t)).collect();
            let (a, b) = (x[lo], x[n - 1 - lo]);
            (0..400)
                .map(|k| a + (b - a) * k as f64 / 399.0)
                .map(|t| (apply(&cubic_weights(&x, t), &v) - f(t)).abs())
                .fold(0.0, f64::max)
        };
        let inner = (err(16, 1) / err(32, 1)).log2();
        assert!(inner > 2.8, "interior order {inner}");
        let all = (err(16, 0) / err(32, 0)).log2();
        assert!(all > 1.9, "order with the end segments {all}");
    }

    #[test]
    fn grid_weights_hit_nodes_exactly() {
        let (xf, xp) = (centres(5), centres(4));
        let w = grid_weights(&xf, &xp, xf[2], xp[1]);
        let v: Vec<f64> = (0..20).map(|i| i as f64 * 1.5).collect();
        assert!((apply(&w, &v) - v[2 * 4 + 1]).abs() < 1e-12);
    }
}
