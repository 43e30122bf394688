//! The potential's path integral by prefix moments instead of quadrature
//! over every grid cell the path crosses.
//!
//! At table node p the torque's lag interpolant t_p(θ) (cubic Hermite,
//! [`super::interpolation::hermite_weights`]) and its first two
//! θ-derivatives are stored as prefix moments
//!
//!   M_{f,j}(p, θ_m) = ∫_{θ₀}^{θ_m} (θ' − θ₀)^j ∂_θ^f t_p(θ') dθ',  f, j ≤ 3,
//!
//! at every lag node θ_m (θ₀ the first). Along the path s ↦ (s, r s − q₂)
//! inside one q₁ cell, the Catmull–Rom weight of node a at
//! t_q(s) = c − e, e = (θ − θ')/(r h), is the cubic
//!
//!   w_a(c − e) = Σ_k (−e)^k / k! · w_a^{(k)}(c),
//!
//! so with (θ − θ')^k = Σ_j C(k, j) Θ^{k−j} (−(θ' − θ₀))^j, Θ = θ − θ₀,
//!
//!   ∫ T₁ ds = (1/r) Σ_a Σ_k w_a^{(k)}(c)/k! (−1/(r h))^k
//!             Σ_j C(k, j) Θ^{k−j} (−1)^j [M_{0,j}(p_a, ·)]_{θ_a}^{θ_b},
//!
//! and likewise ∫ ∂T₁/∂θ ds and ∫ ∂²T₁/∂θ² ds with f = 1, 2. M at a θ
//! between lag nodes is the prefix at the node below plus the rest of that
//! cell by 4-point Gauss–Legendre, exact for (θ' − θ₀)^j ∂^f t_p (degree
//! ≤ 6). The result is the same exact integral of the same interpolant as
//! the quadrature over every crossed cell ([`super::MeshTable::state`] used
//! that until 2026-11-28), in a few operations per q₁ cell crossed instead
//! of a bicubic evaluation at four points in every lag cell.

use super::interpolation::{gauss4, hermite_weights};

/// Moments per (field f, power j).
pub(super) type Moments = [[f64; 4]; 3];

/// Prefix moments of every table node's lag interpolant: `at(p, m)` holds
/// M(p, θ_m), node-major like the table's fields.
#[derive(Debug, Clone, Default)]
pub struct PathMoments {
    nu: usize,
    prefix: Vec<Moments>,
}

/// The lag interpolant's data at lag index k of a column: zero below the
/// grid, continued linearly above it (as [`super::MeshTable`]'s fields).
fn lag_value(col: &[f64], k: i64) -> f64 {
    let nu = col.len() as i64;
    if k < 0 {
        0.0
    } else if k >= nu {
        2.0 * col[(nu - 1) as usize] - col[(nu - 2) as usize]
    } else {
        col[k as usize]
    }
}

/// The Gauss rule of ∫_{x_m}^{x} (θ' − θ₀)^j ∂^f t(θ') dθ' over part of
/// lag cell m, for any column: per Gauss point the Hermite weights of the
/// cell's four lag nodes (rows f = 0..2) and the weighted powers
/// w_g · (x − x_m) · (θ' − θ₀)^j. Exact for these integrands (degree ≤ 6).
pub(super) struct PartialRule {
    m: usize,
    points: [([[f64; 4]; 3], [f64; 4]); 4],
}

impl PartialRule {
    pub(super) fn new(lags: &[f64], m: usize, x: f64) -> PartialRule {
        let (x0, len) = (lags[m], x - lags[m]);
        let points = gauss4().map(|(g, wg)| {
            let th = x0 + len * g;
            let rel = th - lags[0];
            let s = wg * len;
            (
                hermite_weights(lags, m, th),
                [s, s * rel, s * rel * rel, s * rel * rel * rel],
            )
        });
        PartialRule { m, points }
    }

    /// The integrals for the column `col` (zero below the grid, continued
    /// linearly above it, as [`super::MeshTable`]'s fields).
    pub(super) fn apply(&self, col: &[f64]) -> Moments {
        let d: [f64; 4] = std::array::from_fn(|b| lag_value(col, self.m as i64 - 1 + b as i64));
        let mut out = [[0.0; 4]; 3];
        for (w, pw) in &self.points {
            for (f, row) in out.iter_mut().enumerate() {
                let v: f64 = (0..4).map(|b| w[f][b] * d[b]).sum();
                for (o, p) in row.iter_mut().zip(pw) {
                    *o += p * v;
                }
            }
        }
        out
    }
}

impl PathMoments {
    /// The prefix moments of `data` (nodes × lag nodes, node-major) on the
    /// lag grid `lags`.
    pub(super) fn new(lags: &[f64], data: &[f64]) -> PathMoments {
        let nu = lags.len();
        let mut prefix = Vec::with_capacity(data.len());
        let cells: Vec<PartialRule> = (0..nu - 1)
            .map(|m| PartialRule::new(lags, m, lags[m + 1]))
            .collect();
        for col in data.chunks_exact(nu) {
            let mut acc = [[0.0; 4]; 3];
            prefix.push(acc);
            for rule in &cells {
                let cell = rule.apply(col);
                for f in 0..3 {
                    for j in 0..4 {
                        acc[f][j] += cell[f][j];
                    }
                }
                prefix.push(acc);
            }
        }
        PathMoments { nu, prefix }
    }

    /// Whether moments were computed (a table made without its torque has none).
    pub(super) fn is_empty(&self) -> bool {
        self.prefix.is_empty()
    }

    /// M(p, θ) for node p's column `col`, θ in the cell of `rule` (made
    /// for that θ).
    pub(super) fn at(&self, rule: &PartialRule, col: &[f64], p: usize) -> Moments {
        let base = self.prefix[p * self.nu + rule.m];
        let part = rule.apply(col);
        std::array::from_fn(|f| std::array::from_fn(|j| base[f][j] + part[f][j]))
    }
}

/// Σ_k w^{(k)}(c)/k! (−1/(r h))^k Σ_j C(k, j) Θ^{k−j} (−1)^j ΔM_{f,j}: the
/// path integral over one q₁ cell of field f given the moment differences
/// `dm` of node a's interpolant and the Catmull–Rom derivatives `w` (rows
/// k = 0..3) of that node at c. Returns the three fields' integrals
/// (before the factor 1/r).
pub(super) fn cell_integral(dm: &Moments, w: [f64; 4], big_theta: f64, rh: f64) -> [f64; 3] {
    const BINOM: [[f64; 4]; 4] = [
        [1.0, 0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0, 0.0],
        [1.0, 2.0, 1.0, 0.0],
        [1.0, 3.0, 3.0, 1.0],
    ];
    const FACT: [f64; 4] = [1.0, 1.0, 2.0, 6.0];
    let tp = [
        1.0,
        big_theta,
        big_theta * big_theta,
        big_theta * big_theta * big_theta,
    ];
    let mut out = [0.0; 3];
    for (f, o) in out.iter_mut().enumerate() {
        for k in 0..4 {
            let mut s = 0.0;
            for j in 0..=k {
                let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                s += BINOM[k][j] * tp[k - j] * sign * dm[f][j];
            }
            *o += w[k] / FACT[k] * (-1.0 / rh).powi(k as i32) * s;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::{lag_grid, Column, MeshTable, TableSpec};

    /// A table of a stiffening contact whose unloaded TE varies with q₁:
    /// T₁ = k (θ − θ₀(q₁))^1.5 above θ₀ (positions × 24 lag nodes).
    fn table(periodic: bool) -> MeshTable {
        let (positions, nu, step) = (12usize, 24usize, 0.01);
        let lead = if periodic { 0 } else { 3 };
        let te0 = |i: i64| 20e-6 + 8e-6 * (2.0 * std::f64::consts::PI * i as f64 / 12.0).sin();
        let idx: Vec<i64> = (-(lead as i64)..positions as i64).collect();
        let lags = lag_grid(12e-6, 28e-6, 1.5e-3, nu);
        let cols: Vec<Column> = idx
            .iter()
            .map(|&i| Column {
                te0: te0(i),
                torque: lags
                    .iter()
                    .map(|&th| 4e7 * (th - te0(i)).max(0.0).powf(1.5))
                    .collect(),
                force: vec![[0.0; 3]; nu],
                wrench: vec![[0.0; 6]; nu],
                friction: vec![[0.0; 2]; nu],
                tangential: vec![0.0; nu],
                root_tension: Vec::new(),
                cpu: 0.0,
            })
            .collect();
        let spec = TableSpec {
            start: 0.0,
            direction: 1.0,
            step,
            positions,
            periodic,
            slices: 10,
            lag_nodes: nu,
            torque_max_nm: 100.0,
        };
        let refs: Vec<&Column> = cols.iter().collect();
        MeshTable::from_columns(spec, lead, 0.46, lags, &refs, None)
    }

    /// The prefix moments give the potential's three path integrals of the
    /// quadrature over every crossed cell (the same exact integrals of the
    /// same interpolant) within 1e-11 of their scale, on periodic and
    /// non-periodic tables, for paths that cross q₁ grid lines (long lags)
    /// and stay in one cell.
    #[test]
    fn prefix_moments_give_the_quadrature_path_integrals() {
        for periodic in [true, false] {
            let t = table(periodic);
            let r = t.ratio;
            let mut worst = [0.0f64; 3];
            let mut scale = [0.0f64; 3];
            for k in 0..200 {
                let q1 = 0.001 + 0.1 * (k as f64 * 0.618_033_988_7).fract();
                let theta = 15e-6 + 1.4e-3 * ((k * 7 + 3) as f64 * 0.381_966).fract();
                let q2 = r * q1 - theta;
                let a = t.path_integrals(q1, q2).unwrap();
                let b = t.path_integrals_by_quadrature(q1, q2).unwrap();
                for f in 0..3 {
                    worst[f] = worst[f].max((a[f] - b[f]).abs());
                    scale[f] = scale[f].max(b[f].abs());
                }
            }
            println!(
                "periodic {periodic}: largest differences {:.1e} / {:.1e} / {:.1e} of the scale",
                worst[0] / scale[0],
                worst[1] / scale[1],
                worst[2] / scale[2]
            );
            for f in 0..3 {
                assert!(scale[f] > 0.0);
                assert!(
                    worst[f] <= 1e-11 * scale[f],
                    "periodic {periodic}, integral {f}: {:e} against scale {:e}",
                    worst[f],
                    scale[f]
                );
            }
        }
    }
}
