//! Local minimisation in two parameters: Newton with central-difference
//! gradient and Hessian, Levenberg-damped, each step accepted only where the
//! function is defined and decreases.

/// Minimises `f` from `x` (with `f(x) = f0`), step `h0` for the differences,
/// at most `iters` Newton steps. Returns the last accepted point and value.
pub fn newton_2d(
    f: impl Fn([f64; 2]) -> Option<f64>,
    mut x: [f64; 2],
    mut f0: f64,
    h0: f64,
    iters: usize,
) -> ([f64; 2], f64) {
    let mut h = h0;
    for _ in 0..iters {
        let at = |du: f64, dv: f64| f([x[0] + du, x[1] + dv]);
        let (Some(fu1), Some(fu0), Some(fv1), Some(fv0)) =
            (at(h, 0.0), at(-h, 0.0), at(0.0, h), at(0.0, -h))
        else {
            // Next to the edge of the domain: shrink the stencil, up to 1000×.
            if h > 2e-3 * h0 {
                h *= 0.1;
                continue;
            }
            break;
        };
        let fuv = match (at(h, h), at(h, -h), at(-h, h), at(-h, -h)) {
            (Some(a), Some(b), Some(c), Some(d)) => a - b - c + d,
            _ => 0.0,
        };
        let g = [(fu1 - fu0) / (2.0 * h), (fv1 - fv0) / (2.0 * h)];
        let hs = [
            (fu1 - 2.0 * f0 + fu0) / (h * h),
            fuv / (4.0 * h * h),
            (fv1 - 2.0 * f0 + fv0) / (h * h),
        ];
        match damped_step(&f, x, f0, g, hs) {
            Some((c, fc)) => {
                let moved = (c[0] - x[0]).hypot(c[1] - x[1]);
                x = c;
                f0 = fc;
                if moved < 1e-12 {
                    break;
                }
            }
            None => break,
        }
    }
    (x, f0)
}

/// One Levenberg-damped Newton step on f at x (value f0, gradient g, Hessian
/// [h_uu, h_uv, h_vv]) that decreases f and stays where f is defined.
pub fn damped_step(
    f: impl Fn([f64; 2]) -> Option<f64>,
    x: [f64; 2],
    f0: f64,
    g: [f64; 2],
    hs: [f64; 3],
) -> Option<([f64; 2], f64)> {
    let scale = hs[0].abs() + hs[2].abs() + 1e-300;
    let mut lambda = 1e-9 * scale;
    for _ in 0..25 {
        let (a, b, c) = (hs[0] + lambda, hs[1], hs[2] + lambda);
        let det = a * c - b * b;
        if det > 0.0 {
            let s = [-(c * g[0] - b * g[1]) / det, -(a * g[1] - b * g[0]) / det];
            let cand = [x[0] + s[0], x[1] + s[1]];
            if let Some(fc) = f(cand) {
                if fc <= f0 {
                    return Some((cand, fc));
                }
            }
        }
        lambda = lambda * 10.0 + 1e-3 * scale;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rosenbrock_like_quadratic_valley_is_found() {
        // f = (x − 1)² + 100 (y − x)²: minimum 0 at (1, 1).
        let f = |p: [f64; 2]| Some((p[0] - 1.0).powi(2) + 100.0 * (p[1] - p[0]).powi(2));
        let (x, v) = newton_2d(f, [-1.0, 2.0], f([-1.0, 2.0]).unwrap(), 1e-4, 50);
        assert!(
            (x[0] - 1.0).abs() < 1e-6 && (x[1] - 1.0).abs() < 1e-6 && v < 1e-10,
            "{x:?} {v}"
        );
    }

    #[test]
    fn minimum_on_the_edge_of_the_domain_is_approached_from_inside() {
        // f = x on x >= 0.5 (undefined below): the search stops near the edge, never outside.
        let f = |p: [f64; 2]| (p[0] >= 0.5).then_some(p[0] + p[1] * p[1]);
        let (x, _) = newton_2d(f, [2.0, 1.0], f([2.0, 1.0]).unwrap(), 1e-4, 100);
        assert!(x[0] >= 0.5 && x[0] < 2.0 && x[1].abs() < 1.0, "{x:?}");
    }
}
