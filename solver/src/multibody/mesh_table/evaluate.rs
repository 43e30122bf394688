//! Reading the table at (q₁, q₂): the interpolated fields, the potential with
//! its gradient and Hessian, and the friction, wrench, tangential-force and
//! impact-law states.

use super::interpolation::{catmull_rom, gauss4, hermite_weights, stencil};
use super::path_moments::{cell_integral, PartialRule};
use super::{ImpactState, MeshState, MeshTable};
use crate::SolverError;

/// The real table nodes (with their weights) that make stencil entry `k`
/// of a row of `n` nodes, as [`stencil`] continues it: the node itself,
/// its periodic image, or the linear continuation past an end.
fn node_combo(n: usize, periodic: bool, k: i64) -> [(usize, f64); 2] {
    let n_i = n as i64;
    if periodic {
        [(k.rem_euclid(n_i) as usize, 1.0), (0, 0.0)]
    } else if k < 0 {
        let m = (-k) as f64;
        [(0, 1.0 + m), (1, -m)]
    } else if k >= n_i {
        let m = (k - n_i + 1) as f64;
        [(n - 1, 1.0 + m), (n - 2, -m)]
    } else {
        [(k as usize, 1.0), (0, 0.0)]
    }
}

impl MeshTable {
    /// First lag node θ_lo (below every unloaded TE), rad.
    pub fn theta_lo(&self) -> f64 {
        self.lags[0]
    }

    /// Smallest lag step (the fine band's), rad.
    pub fn du(&self) -> f64 {
        self.lags[1] - self.lags[0]
    }

    /// Mean lag step over the table, rad (a scale for lag iterations).
    pub fn mean_lag_step(&self) -> f64 {
        (self.lags[self.lags.len() - 1] - self.lags[0]) / (self.lags.len() - 1) as f64
    }

    /// Table nodes in q₁, lead-in included.
    pub fn nodes(&self) -> usize {
        self.lead + self.spec.positions
    }

    /// Table period in q₁ (periodic tables) or range from q₁ = 0, rad.
    pub fn span(&self) -> f64 {
        let n = self.spec.positions;
        if self.spec.periodic {
            self.spec.step * n as f64
        } else {
            self.spec.step * (n - 1) as f64
        }
    }

    fn cell(&self, q1: f64) -> Result<(i64, f64), SolverError> {
        // Table node index: node `lead` is q₁ = 0.
        let s = if self.spec.periodic {
            q1.rem_euclid(self.span()) / self.spec.step
        } else {
            q1 / self.spec.step + self.lead as f64
        };
        // Non-periodic tables extrapolate linearly up to one step outside.
        if !self.spec.periodic && !(-1.0..=self.nodes() as f64).contains(&s) {
            return Err(SolverError::Table(format!(
                "pinion rotation {:.4} deg outside the table's {:.4}..{:.4} deg",
                q1.to_degrees(),
                -(self.lead as f64 * self.spec.step).to_degrees(),
                self.span().to_degrees()
            )));
        }
        let i = s.floor();
        Ok((i as i64, s - i))
    }

    /// Unloaded TE θ₀(q₁) and its first two derivatives.
    pub fn unloaded(&self, q1: f64) -> Result<[f64; 3], SolverError> {
        self.along_q1(|k| self.te0[k], q1)
    }

    /// A per-node quantity (`value(k)` at table node k, lead first)
    /// interpolated at q₁ as θ₀ is (Catmull–Rom, periodic or continued
    /// linearly), with its first two derivatives.
    pub fn along_q1(&self, value: impl Fn(usize) -> f64, q1: f64) -> Result<[f64; 3], SolverError> {
        let (i, t) = self.cell(q1)?;
        let v = stencil(self.nodes(), self.spec.periodic, i, value);
        let w = catmull_rom(t);
        let h = self.spec.step;
        let d = |r: usize| (0..4).map(|o| w[r][o] * v[o]).sum::<f64>();
        Ok([d(0), d(1) / h, d(2) / (h * h)])
    }

    /// Bicubic interpolation of a table field at (q₁, θ ≥ θ_lo): value and
    /// the derivatives [f, f_q, f_θ, f_qq, f_qθ, f_θθ]. Below θ_lo every
    /// field is zero (the flanks are open).
    fn field(
        &self,
        data: impl Fn(usize, usize) -> f64,
        q1: f64,
        theta: f64,
    ) -> Result<[f64; 6], SolverError> {
        let nu = self.spec.lag_nodes;
        let top = self.lags[nu - 1];
        if theta > top {
            return Err(SolverError::Table(format!(
                "wheel lag {:.3} µrad beyond the table's {:.3} µrad; raise the multibody table's torque",
                theta * 1e6,
                top * 1e6
            )));
        }
        let m = (self.lags.partition_point(|&x| x <= theta) as i64 - 1).clamp(0, nu as i64 - 2);
        let (i, tq) = self.cell(q1)?;
        let wq = catmull_rom(tq);
        let wu = hermite_weights(&self.lags, m as usize, theta);
        let hq = self.spec.step;
        let mut out = [0.0; 6];
        // Weights of lag node b: value, first and second derivative (per θ).
        let lag_weights = (0..4).map(|b| [wu[0][b], wu[1][b], wu[2][b]]);
        for (b, wb) in lag_weights.enumerate() {
            let k = m - 1 + b as i64;
            let col = stencil(self.nodes(), self.spec.periodic, i, |p| {
                if k < 0 {
                    0.0
                } else if k >= nu as i64 {
                    2.0 * data(p, nu - 1) - data(p, nu - 2)
                } else {
                    data(p, k as usize)
                }
            });
            for a in 0..4 {
                let v = col[a];
                out[0] += wq[0][a] * wb[0] * v;
                out[1] += wq[1][a] * wb[0] * v / hq;
                out[2] += wq[0][a] * wb[1] * v;
                out[3] += wq[2][a] * wb[0] * v / (hq * hq);
                out[4] += wq[1][a] * wb[1] * v / hq;
                out[5] += wq[0][a] * wb[2] * v;
            }
        }
        Ok(out)
    }

    /// Friction moments per unit friction coefficient (Φ₁, Φ₂) at (q₁, q₂),
    /// N·m, and their derivatives ∂Φᵢ/∂q_j (θ = r q₁ − q₂); zero where open.
    pub fn friction_state(
        &self,
        q1: f64,
        q2: f64,
    ) -> Result<([f64; 2], [[f64; 2]; 2]), SolverError> {
        let r = self.ratio;
        let theta = r * q1 - q2;
        let mut phi = [0.0; 2];
        let mut grad = [[0.0; 2]; 2];
        if theta <= self.theta_lo() || theta <= self.unloaded(q1)?[0] {
            return Ok((phi, grad));
        }
        let nu = self.spec.lag_nodes;
        for i in 0..2 {
            let [f, fq, ft, ..] = self.field(|p, m| self.friction[p * nu + m][i], q1, theta)?;
            phi[i] = f;
            grad[i] = [fq + r * ft, -ft];
        }
        Ok((phi, grad))
    }

    /// The contact's wrench on the wheel ([`MeshTable::wrench`]) at
    /// (q₁, θ), per component [value, ∂/∂q₁ at fixed θ, ∂/∂θ]; zero below
    /// the first lag node (interpolated as the torque is).
    pub fn wrench_state(&self, q1: f64, theta: f64) -> Result<[[f64; 3]; 6], SolverError> {
        let mut out = [[0.0; 3]; 6];
        if theta <= self.theta_lo() {
            return Ok(out);
        }
        let nu = self.spec.lag_nodes;
        for (c, o) in out.iter_mut().enumerate() {
            let [f, fq, ft, ..] = self.field(|p, m| self.wrench[p * nu + m][c], q1, theta)?;
            *o = [f, fq, ft];
        }
        Ok(out)
    }

    /// The tangential component of the contact force on the wheel
    /// ([`MeshTable::tangential`]) at (q₁, q₂), N; zero where the flanks
    /// are open (interpolated as the torque is).
    pub fn tangential_at(&self, q1: f64, q2: f64) -> Result<f64, SolverError> {
        let theta = self.ratio * q1 - q2;
        if theta <= self.theta_lo() {
            return Ok(0.0);
        }
        let nu = self.spec.lag_nodes;
        Ok(self.field(|p, m| self.tangential[p * nu + m], q1, theta)?[0].max(0.0))
    }

    /// The loaded teeth's largest root tension of [pinion, wheel]
    /// ([`MeshTable::root_tension`]) at (q₁, θ), Pa; None when the table
    /// has none, zero where the flanks are open (interpolated as the torque
    /// is, clamped at zero). The tabulated value is a largest over teeth:
    /// where the loaded tooth changes it has a kink, which the cubics round.
    pub fn root_tension_at(&self, q1: f64, theta: f64) -> Result<Option<[f64; 2]>, SolverError> {
        if self.root_tension.is_empty() {
            return Ok(None);
        }
        if theta <= self.theta_lo() {
            return Ok(Some([0.0; 2]));
        }
        let nu = self.spec.lag_nodes;
        let at = |i: usize| -> Result<f64, SolverError> {
            Ok(self.field(|p, m| self.root_tension[p * nu + m][i], q1, theta)?[0].max(0.0))
        };
        Ok(Some([at(0)?, at(1)?]))
    }

    /// The impact law's damping levers and slip speed at (q₁, q₂); None
    /// for the element's table, zero where the flanks are open.
    pub fn impact_state(&self, q1: f64, q2: f64) -> Result<Option<ImpactState>, SolverError> {
        let Some(imp) = &self.impact else {
            return Ok(None);
        };
        let r = self.ratio;
        let theta = r * q1 - q2;
        let mut out = ImpactState::default();
        if theta <= self.theta_lo() || theta <= self.unloaded(q1)?[0] {
            return Ok(Some(out));
        }
        let nu = self.spec.lag_nodes;
        for i in 0..4 {
            let [f, fq, ft, ..] = self.field(|p, m| imp.damping[p * nu + m][i], q1, theta)?;
            // A ≥ 0 (Hermite overshoot clipped); E takes either sign.
            out.damping[i] = if i < 2 { f.max(0.0) } else { f };
            out.damping_grad[i] = [fq + r * ft, -ft];
        }
        out.slip = self.field(|p, m| imp.slip[p * nu + m], q1, theta)?[0].max(0.0);
        Ok(Some(out))
    }

    /// Lag cell of θ on the lag grid (as [`MeshTable::field`] picks it).
    fn lag_cell(&self, theta: f64) -> usize {
        let nu = self.spec.lag_nodes as i64;
        (self.lags.partition_point(|&x| x <= theta) as i64 - 1).clamp(0, nu - 2) as usize
    }

    /// The potential's path integrals at (q₁, q₂): V = ∫ T₁ ds and
    /// ∫ ∂T₁/∂θ ds, ∫ ∂²T₁/∂θ² ds along s ↦ (s, r s − q₂) from θ = θ_lo
    /// to q₁, by the prefix moments ([`super::path_moments`]): one term per
    /// q₁ cell the path crosses.
    pub(super) fn path_integrals(&self, q1: f64, q2: f64) -> Result<[f64; 3], SolverError> {
        const W3: [f64; 4] = [-3.0, 9.0, -9.0, 3.0];
        let (r, h, nu) = (self.ratio, self.spec.step, self.spec.lag_nodes);
        let th_lo = self.theta_lo();
        let theta = r * q1 - q2;
        let s_lo = q1 - (theta - th_lo) / r;
        let mut cuts = vec![s_lo];
        let mut i = (s_lo / h).floor() + 1.0;
        while i * h < q1 {
            cuts.push(i * h);
            i += 1.0;
        }
        cuts.push(q1);
        let (big, rh, n) = (theta - th_lo, r * h, self.nodes());
        let mut out = [0.0; 3];
        for w in cuts.windows(2) {
            let (sa, sb) = (w[0], w[1]);
            if sb <= sa {
                continue;
            }
            let mid = 0.5 * (sa + sb);
            let (ic, t_mid) = self.cell(mid)?;
            let cr = catmull_rom(t_mid + (q1 - mid) / h);
            let ends = [(r * sa - q2).max(th_lo), (r * sb - q2).max(th_lo)];
            let rules = ends.map(|x| PartialRule::new(&self.lags, self.lag_cell(x), x));
            for a in 0..4 {
                let wk = [cr[0][a], cr[1][a], cr[2][a], W3[a]];
                for (p, coef) in node_combo(n, self.spec.periodic, ic - 1 + a as i64) {
                    if coef == 0.0 {
                        continue;
                    }
                    let col = &self.torque[p * nu..(p + 1) * nu];
                    let mb = self.moments.at(&rules[1], col, p);
                    let ma = self.moments.at(&rules[0], col, p);
                    let dm = std::array::from_fn(|f| std::array::from_fn(|j| mb[f][j] - ma[f][j]));
                    let v = cell_integral(&dm, wk, big, rh);
                    for (o, x) in out.iter_mut().zip(v) {
                        *o += coef * x;
                    }
                }
            }
        }
        Ok(out.map(|x| x / r))
    }

    /// [`MeshTable::path_integrals`] by 4-point Gauss–Legendre between
    /// every crossing of the path with the grid lines (q₁ nodes and lag
    /// nodes): the same exact integrals, one bicubic evaluation per Gauss
    /// point (the method before the prefix moments; kept as their check).
    pub fn path_integrals_by_quadrature(&self, q1: f64, q2: f64) -> Result<[f64; 3], SolverError> {
        let r = self.ratio;
        let theta = r * q1 - q2;
        let nu = self.spec.lag_nodes;
        let torque = |q: f64, th: f64| self.field(|p, m| self.torque[p * nu + m], q, th);
        // The path s ↦ (s, r s − q₂) from θ = θ_lo to q₁, cut where it
        // crosses the grid lines q₁ = i·step and θ = θ_m.
        let s_lo = q1 - (theta - self.theta_lo()) / r;
        let mut cuts = vec![s_lo, q1];
        let h = self.spec.step;
        let mut i = (s_lo / h).floor() + 1.0;
        while i * h < q1 {
            cuts.push(i * h);
            i += 1.0;
        }
        for &th in self.lags.iter().skip(1).take_while(|&&x| x < theta) {
            let s = (th + q2) / r;
            if s > s_lo && s < q1 {
                cuts.push(s);
            }
        }
        cuts.sort_by(f64::total_cmp);
        let (mut v, mut vt, mut vtt) = (0.0, 0.0, 0.0);
        for w in cuts.windows(2) {
            let len = w[1] - w[0];
            if len <= 0.0 {
                continue;
            }
            for (x, g) in gauss4() {
                let s = w[0] + len * x;
                let th = (r * s - q2).max(self.theta_lo());
                let f = torque(s, th)?;
                v += g * len * f[0];
                vt += g * len * f[2];
                vtt += g * len * f[5];
            }
        }
        Ok([v, vt, vtt])
    }

    /// Potential, gradient, Hessian and force at (q₁, q₂).
    pub fn state(&self, q1: f64, q2: f64) -> Result<MeshState, SolverError> {
        let r = self.ratio;
        let theta = r * q1 - q2;
        let u = theta - self.unloaded(q1)?[0];
        if theta <= self.theta_lo() {
            return Ok(MeshState {
                theta,
                u,
                ..Default::default()
            });
        }
        let nu = self.spec.lag_nodes;
        let [t, tq, tt, ..] = self.field(|p, m| self.torque[p * nu + m], q1, theta)?;
        let [v, vt, vtt] = if self.moments.is_empty() {
            self.path_integrals_by_quadrature(q1, q2)?
        } else {
            self.path_integrals(q1, q2)?
        };
        let mut force = [0.0; 3];
        if u > 0.0 {
            for (c, f) in force.iter_mut().enumerate() {
                *f = self.field(|p, m| self.force[p * nu + m][c], q1, theta)?[0];
            }
        }
        Ok(MeshState {
            theta,
            u,
            potential: v,
            grad: [t, -vt],
            hess: [[tq + r * tt, -tt], [-tt, vtt]],
            force,
        })
    }
}
