//! The contact element as a force element between two rigid gear bodies.
//!
//! Generalized coordinates: q₁ the pinion rotation from the sweep start and
//! q₂ the wheel rotation, both in their drive directions, rad, with q₂ = r q₁
//! (r = z₁/z₂) for conjugate motion. The wheel lag (TE) is θ = r q₁ − q₂.
//!
//! At each pinion position the contact element under lag control gives the
//! pinion torque T₁(q₁, θ) = Σ λ₁ F (zero while θ is below the unloaded TE
//! θ₀(q₁)). The mesh's potential is the work of that torque while the
//! pinion turns against the held wheel from first contact:
//!
//!   V(q₁, q₂) = ∫_{s*}^{q₁} T₁(s, r s − q₂) ds,
//!
//! so that ∂V/∂q₁ = T₁ (the quasi-static pinion balance is the LTCA's) and
//! ∂V/∂q₂ = −∫ ∂T₁/∂θ ds (the wheel torque, ≈ T₁/r). T₁ is tabulated on a
//! grid of q₁ × θ and interpolated by Catmull–Rom cubics in both
//! directions. Along the integration path (a straight line in q₁, θ) that
//! interpolant is a polynomial of degree 6 between grid lines, so 4-point
//! Gauss–Legendre between the crossings integrates it exactly: V, its
//! gradient and its Hessian are exact for the interpolated T₁, and the
//! element is conservative (a run without damping keeps V + kinetic energy
//! − work of the torques). The grid is in θ, not in the deflection θ − θ₀:
//! the unloaded TE has kinks where the contact passes from one tooth pair to
//! the next, and T₁ is smooth across them only at fixed θ.

use crate::compliance::PairCompliance;
use crate::contact_problem::ContactProblem;
use crate::ltca::{assemble, geometry, Assembled, Geometry};
use crate::SolverError;
use preprocess::generation::MemberFrame;
use preprocess::pair::FlankPair;
use preprocess::utca::RollSurface;
use rayon::prelude::*;

/// Where and how finely the table is computed.
#[derive(Debug, Clone, Copy)]
pub struct TableSpec {
    /// Pinion angle at q₁ = 0, rad, and its drive direction (±1).
    pub start: f64,
    pub direction: f64,
    /// q₁ step, rad, and number of positions.
    pub step: f64,
    pub positions: usize,
    /// Periodic over `positions · step` (standard blanks: one angular pitch).
    pub periodic: bool,
    pub slices: usize,
    /// Lag nodes from below the smallest unloaded TE up to the largest lag
    /// under `torque_max_nm`.
    pub lag_nodes: usize,
    pub torque_max_nm: f64,
}

/// The tabulated force element.
#[derive(Debug, Clone)]
pub struct MeshTable {
    pub spec: TableSpec,
    /// Nodes before q₁ = 0 (non-periodic tables): the potential's path
    /// integral starts at first contact, up to (θ_max − θ_lo)/r before q₁.
    pub lead: usize,
    /// r = z₁/z₂.
    pub ratio: f64,
    /// First lag node θ_lo (below every unloaded TE) and the lag step du, rad.
    pub theta_lo: f64,
    pub du: f64,
    /// Unloaded TE θ₀ per position, rad.
    pub te0: Vec<f64>,
    /// Pinion torque T₁ (N·m) and the contact force on the wheel in the
    /// fixed frame (N): row-major positions × lag nodes.
    pub torque: Vec<f64>,
    pub force: Vec<[f64; 3]>,
    /// Geometry + assembly + lag-controlled solves, s per position (one core).
    pub cpu_s_per_position: f64,
}

/// The element's state at (q₁, q₂).
#[derive(Debug, Clone, Copy, Default)]
pub struct MeshState {
    /// Wheel lag θ and its distance above the unloaded TE, rad.
    pub theta: f64,
    pub u: f64,
    /// Potential V (J), gradient ∂V/∂q (N·m), Hessian (N·m/rad).
    pub potential: f64,
    pub grad: [f64; 2],
    pub hess: [[f64; 2]; 2],
    /// Contact force on the wheel, fixed frame, N (interpolated; output only).
    pub force: [f64; 3],
}

/// Catmull–Rom weights of nodes i−1..i+2 and their first and second
/// derivatives with respect to t ∈ [0, 1] in cell i.
fn catmull_rom(t: f64) -> [[f64; 4]; 3] {
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

/// 1-D node values around a cell: periodic wrap or linear continuation past the ends.
fn stencil(n: usize, periodic: bool, i: i64, value: impl Fn(usize) -> f64) -> [f64; 4] {
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
fn gauss4() -> [(f64, f64); 4] {
    const X: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
    const W: [f64; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
    [
        (0.5 * (1.0 - X[1]), 0.5 * W[1]),
        (0.5 * (1.0 - X[0]), 0.5 * W[0]),
        (0.5 * (1.0 + X[0]), 0.5 * W[0]),
        (0.5 * (1.0 + X[1]), 0.5 * W[1]),
    ]
}

struct Column {
    te0: f64,
    torque: Vec<f64>,
    force: Vec<[f64; 3]>,
    cpu: f64,
}

impl MeshTable {
    /// Computes the table: per position the slices and compliance, then the
    /// lag-controlled contact problem at every lag node.
    pub fn build(
        fp: &FlankPair,
        rs: &RollSurface,
        pc: &PairCompliance,
        frame: &MemberFrame,
        ratio: f64,
        spec: TableSpec,
    ) -> Result<Self, SolverError> {
        if spec.positions < 4 || spec.lag_nodes < 4 {
            return Err(SolverError::Table(format!(
                "{} positions × {} lag nodes: need at least 4 of each",
                spec.positions, spec.lag_nodes
            )));
        }
        let tau = fp.pinion.gen.frame.pitch();
        let phi = |i: i64| spec.start + spec.direction * spec.step * i as f64;
        // Pass 1: geometry, compliance and the lag at the largest torque.
        let pass1 = |range: std::ops::Range<i64>| -> Result<Vec<_>, SolverError> {
            range
                .into_par_iter()
                .map(|i| {
                    let t = std::time::Instant::now();
                    let g = geometry(fp, rs, phi(i), tau, spec.slices);
                    if g.slices.is_empty() {
                        return Err(SolverError::NoContact);
                    }
                    let a = assemble(&g, pc)?;
                    let s = crate::ltca::solve(&a, spec.torque_max_nm, None)?;
                    Ok((g, a, s.theta, t.elapsed().as_secs_f64()))
                })
                .collect()
        };
        let lag_range = |p: &[(Geometry, Assembled, f64, f64)]| {
            let hi = p.iter().map(|p| p.2).fold(f64::NEG_INFINITY, f64::max);
            let lo = p.iter().map(|p| p.0.utca_te).fold(f64::INFINITY, f64::min);
            (lo, hi)
        };
        let mut columns = pass1(0..spec.positions as i64)?;
        // V at q₁ integrates T₁ from first contact, q₁ − (θ − θ_lo)/r: a
        // non-periodic table starts that far (plus two steps) before q₁ = 0.
        let lead = if spec.periodic {
            0
        } else {
            let (lo, hi) = lag_range(&columns);
            ((hi - lo) / ratio / spec.step).ceil() as usize + 2
        };
        if lead > 0 {
            let mut before = pass1(-(lead as i64)..0)?;
            before.append(&mut columns);
            columns = before;
        }
        let (lo, hi) = lag_range(&columns);
        // One node below the first contact, so that V and T₁ start from zero rows.
        let du = (hi - lo) / (spec.lag_nodes - 2) as f64;
        let theta_lo = lo - du;
        // Pass 2: the lag-controlled solves.
        let cols: Vec<Column> = columns
            .into_par_iter()
            .map(|(g, a, _, cpu0)| {
                let t = std::time::Instant::now();
                let p = ContactProblem {
                    compliance: &a.compliance,
                    lag: &a.lag,
                    lever_wheel: &a.lever_wheel,
                    lever_pinion: &a.lever_pinion,
                    line: &a.line,
                    torque: 0.0,
                };
                let mut torque = Vec::with_capacity(spec.lag_nodes);
                let mut force = Vec::with_capacity(spec.lag_nodes);
                let mut warm: Option<Vec<bool>> = None;
                for m in 0..spec.lag_nodes {
                    let s = p.solve_at_lag(theta_lo + du * m as f64, warm.as_deref())?;
                    torque.push(p.pinion_torque(&s.force));
                    // Force on the wheel: along the pinion's outward normal,
                    // slice k of pair j at pinion rotation φ + jτ.
                    let mut f = [0.0; 3];
                    for (k, sl) in g.slices.iter().enumerate() {
                        if s.force[k] > 0.0 {
                            let n = frame.to_fixed(
                                &nalgebra::Vector3::from(sl.normal),
                                g.phi + sl.pair as f64 * tau,
                            );
                            for c in 0..3 {
                                f[c] += s.force[k] * n[c];
                            }
                        }
                    }
                    force.push(f);
                    if s.active.iter().any(|&x| x) {
                        warm = Some(s.active);
                    }
                }
                Ok(Column {
                    te0: g.utca_te,
                    torque,
                    force,
                    cpu: cpu0 + t.elapsed().as_secs_f64(),
                })
            })
            .collect::<Result<_, SolverError>>()?;
        let n = cols.len();
        Ok(MeshTable {
            spec,
            lead,
            ratio,
            theta_lo,
            du,
            te0: cols.iter().map(|c| c.te0).collect(),
            torque: cols.iter().flat_map(|c| c.torque.iter().copied()).collect(),
            force: cols.iter().flat_map(|c| c.force.iter().copied()).collect(),
            cpu_s_per_position: cols.iter().map(|c| c.cpu).sum::<f64>() / n as f64,
        })
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
        let (i, t) = self.cell(q1)?;
        let v = stencil(self.nodes(), self.spec.periodic, i, |k| self.te0[k]);
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
        let s = (theta - self.theta_lo) / self.du;
        if s > (nu - 1) as f64 {
            return Err(SolverError::Table(format!(
                "wheel lag {:.3} µrad beyond the table's {:.3} µrad; raise the multibody table's torque",
                theta * 1e6,
                (self.theta_lo + self.du * (nu - 1) as f64) * 1e6
            )));
        }
        let m = (s.floor() as i64).clamp(0, nu as i64 - 2);
        let tu = s - m as f64;
        let (i, tq) = self.cell(q1)?;
        let (wq, wu) = (catmull_rom(tq), catmull_rom(tu));
        let (hq, hu) = (self.spec.step, self.du);
        let mut out = [0.0; 6];
        // Weights of lag node b: value, first and second derivative.
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
                out[2] += wq[0][a] * wb[1] * v / hu;
                out[3] += wq[2][a] * wb[0] * v / (hq * hq);
                out[4] += wq[1][a] * wb[1] * v / (hq * hu);
                out[5] += wq[0][a] * wb[2] * v / (hu * hu);
            }
        }
        Ok(out)
    }

    /// Potential, gradient, Hessian and force at (q₁, q₂).
    pub fn state(&self, q1: f64, q2: f64) -> Result<MeshState, SolverError> {
        let r = self.ratio;
        let theta = r * q1 - q2;
        let u = theta - self.unloaded(q1)?[0];
        if theta <= self.theta_lo {
            return Ok(MeshState {
                theta,
                u,
                ..Default::default()
            });
        }
        let nu = self.spec.lag_nodes;
        let torque = |q: f64, th: f64| self.field(|p, m| self.torque[p * nu + m], q, th);
        let [t, tq, tt, ..] = torque(q1, theta)?;
        // The path s ↦ (s, r s − q₂) from θ = θ_lo to q₁, cut where it
        // crosses the grid lines q₁ = i·step and θ = θ_m.
        let s_lo = q1 - (theta - self.theta_lo) / r;
        let mut cuts = vec![s_lo, q1];
        let h = self.spec.step;
        let mut i = (s_lo / h).floor() + 1.0;
        while i * h < q1 {
            cuts.push(i * h);
            i += 1.0;
        }
        let m_hi = ((theta - self.theta_lo) / self.du).ceil() as usize;
        for m in 1..m_hi {
            let th = self.theta_lo + self.du * m as f64;
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
                let th = (r * s - q2).max(self.theta_lo);
                let f = torque(s, th)?;
                v += g * len * f[0];
                vt += g * len * f[2];
                vtt += g * len * f[5];
            }
        }
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

#[cfg(test)]
mod tests {
    use super::*;

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
