//! Levenberg–Marquardt for small least-squares fits (a handful of
//! parameters, residuals that cost a model run each): the Jacobian by
//! forward differences, the step from the damped normal equations
//!
//! (JᵀJ + λ diag(JᵀJ)) δ = −Jᵀr,
//!
//! λ divided by 3 after a step that lowers ½|r|², multiplied by 4 and the
//! step retried after one that does not (Marquardt's scaling). Parameters
//! are kept inside their box by clamping each trial point.

use nalgebra::{DMatrix, DVector};

/// What the fit needs to know about each parameter.
#[derive(Debug, Clone, Copy)]
pub struct Bounds {
    pub lower: f64,
    pub upper: f64,
    /// Forward-difference step of the Jacobian, in the parameter's unit.
    pub step: f64,
}

/// The fit's result.
#[derive(Debug, Clone)]
pub struct Fit {
    pub x: Vec<f64>,
    pub residuals: Vec<f64>,
    /// Model runs, Jacobian columns included.
    pub evaluations: usize,
    pub iterations: usize,
}

/// Minimises ½|r(x)|² from `x0` within `bounds`, at most `max_iterations`
/// Jacobians; stops when a step changes the cost by less than `tol`
/// (relative) or |r|∞ falls below `tol`.
pub fn fit<E>(
    mut residual: impl FnMut(&[f64]) -> Result<Vec<f64>, E>,
    x0: &[f64],
    bounds: &[Bounds],
    max_iterations: usize,
    tol: f64,
) -> Result<Fit, E> {
    let n = x0.len();
    let clamp = |x: &mut [f64]| {
        for (v, b) in x.iter_mut().zip(bounds) {
            *v = v.clamp(b.lower, b.upper);
        }
    };
    let cost = |r: &[f64]| 0.5 * r.iter().map(|v| v * v).sum::<f64>();
    let mut x = x0.to_vec();
    clamp(&mut x);
    let mut r = residual(&x)?;
    let mut evaluations = 1;
    let mut lambda = 1e-2;
    let mut iterations = 0;
    while iterations < max_iterations && r.iter().fold(0.0f64, |a, v| a.max(v.abs())) > tol {
        iterations += 1;
        let m = r.len();
        let mut jac = DMatrix::zeros(m, n);
        for j in 0..n {
            let mut xj = x.clone();
            // Step away from the nearer bound so that the column stays inside.
            let h = if x[j] + bounds[j].step > bounds[j].upper {
                -bounds[j].step
            } else {
                bounds[j].step
            };
            xj[j] += h;
            let rj = residual(&xj)?;
            evaluations += 1;
            for i in 0..m {
                jac[(i, j)] = (rj[i] - r[i]) / h;
            }
        }
        let jtj = jac.transpose() * &jac;
        let jtr = jac.transpose() * DVector::from_column_slice(&r);
        let c0 = cost(&r);
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for k in 0..n {
                a[(k, k)] += lambda * jtj[(k, k)].max(1e-12);
            }
            let Some(delta) = a.lu().solve(&(-&jtr)) else {
                lambda *= 4.0;
                continue;
            };
            let mut xt: Vec<f64> = x.iter().zip(delta.iter()).map(|(a, d)| a + d).collect();
            clamp(&mut xt);
            let rt = residual(&xt)?;
            evaluations += 1;
            let ct = cost(&rt);
            if ct < c0 {
                let change = (c0 - ct) / c0.max(f64::MIN_POSITIVE);
                x = xt;
                r = rt;
                lambda = (lambda / 3.0).max(1e-9);
                improved = true;
                if change < tol {
                    return Ok(Fit {
                        x,
                        residuals: r,
                        evaluations,
                        iterations,
                    });
                }
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    Ok(Fit {
        x,
        residuals: r,
        evaluations,
        iterations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn free(step: f64) -> Bounds {
        Bounds {
            lower: -1e9,
            upper: 1e9,
            step,
        }
    }

    #[test]
    fn rosenbrock_residuals_reach_the_minimum_at_one_one() {
        // r = (10 (y − x²), 1 − x): the Rosenbrock valley, minimum (1, 1).
        let f = fit(
            |x: &[f64]| Ok::<_, ()>(vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]]),
            &[-1.2, 1.0],
            &[free(1e-7), free(1e-7)],
            200,
            1e-12,
        )
        .unwrap();
        assert!(
            (f.x[0] - 1.0).abs() < 1e-5 && (f.x[1] - 1.0).abs() < 1e-5,
            "{f:?}"
        );
    }

    #[test]
    fn overdetermined_line_fit_equals_the_normal_equations() {
        // y = a + b t through four points: the least-squares line
        // b = Sty / Stt = 6.25 / 5 = 1.25, a = ȳ − b t̄ = 2.625 − 1.875 = 0.75
        // (closed form of the normal equations).
        let (t, y) = ([0.0, 1.0, 2.0, 3.0], [1.0, 1.5, 3.5, 4.5]);
        let f = fit(
            |x: &[f64]| Ok::<_, ()>(t.iter().zip(&y).map(|(t, y)| x[0] + x[1] * t - y).collect()),
            &[0.0, 0.0],
            &[free(1e-6), free(1e-6)],
            50,
            1e-14,
        )
        .unwrap();
        assert!(
            (f.x[0] - 0.75).abs() < 1e-6 && (f.x[1] - 1.25).abs() < 1e-6,
            "{f:?}"
        );
    }

    #[test]
    fn a_bound_holds_the_parameter_where_the_free_minimum_lies_outside() {
        // r = x − 2 with x ≤ 1: the fit stops at the bound.
        let f = fit(
            |x: &[f64]| Ok::<_, ()>(vec![x[0] - 2.0]),
            &[0.0],
            &[Bounds {
                lower: 0.0,
                upper: 1.0,
                step: 1e-6,
            }],
            50,
            1e-12,
        )
        .unwrap();
        assert_eq!(f.x[0], 1.0);
    }
}
