//! The loaded contact of one position: slice forces F ≥ 0 and the wheel lag θ
//! such that every slice is closed where it carries load and open elsewhere,
//! and the forces carry the pinion torque.
//!
//! Gap of slice k (m):  g_k = λ₂ₖ (lag_k − θ) + Σ_l C_kl F_l + U_k(F_k),
//! complementarity:     F_k ≥ 0, g_k ≥ 0, F_k g_k = 0,
//! torque balance:      Σ_k λ₁ₖ F_k = T₁,
//!
//! with C the bodies' global compliance, U_k the slice's Weber–Banaschek
//! approach and λ₁, λ₂ the pinion and wheel normal levers. U is handled by
//! its secant compliance u_k = U_k(F_k)/F_k, updated to a fixed point; each
//! linear problem (C + diag u) is solved exactly by an active-set method:
//! drop slices with negative force, add slices with negative gap, until
//! neither is left.

use crate::element::weber_banaschek::LineContact;
use crate::SolverError;
use nalgebra::{DMatrix, DVector};

/// One position's contact problem (n slices).
///
/// Two equal slices touching at the same lag share the torque equally, and
/// each closes its gap: θ = lag + (C F + U(F)) / λ₂.
///
/// ```
/// use geometry::Material;
/// use solver::element::contact_problem::ContactProblem;
/// use solver::element::weber_banaschek::LineContact;
/// let c = 2e-9; // m/N, no coupling between the slices
/// let line = LineContact { rho: 0.01, length: 0.004, h: [0.005; 2], bodies: [Material::STEEL; 2], edge: None };
/// let (r1, r2, torque) = (0.04, 0.09, 300.0);
/// let p = ContactProblem {
///     compliance: &[c, 0.0, 0.0, c],
///     lag: &[1e-4, 1e-4],
///     lever_wheel: &[r2, r2],
///     lever_pinion: &[r1, r1],
///     line: &[line, line],
///     torque,
/// };
/// let s = p.solve(None).unwrap();
/// let f = torque / (2.0 * r1);
/// assert!(s.force.iter().all(|x| (x / f - 1.0).abs() < 1e-9));
/// let theta = 1e-4 + (c * f + line.approach(f)) / r2;
/// assert!((s.theta / theta - 1.0).abs() < 1e-9);
/// ```
pub struct ContactProblem<'a> {
    /// Compliance C, row-major n × n, symmetric, m/N.
    pub compliance: &'a [f64],
    /// Wheel lag at which each slice touches, rad.
    pub lag: &'a [f64],
    pub lever_wheel: &'a [f64],
    pub lever_pinion: &'a [f64],
    pub line: &'a [LineContact],
    /// Pinion torque, N·m (≥ 0).
    pub torque: f64,
}

/// The solution.
#[derive(Debug, Clone)]
pub struct ContactSolution {
    /// Slice forces, N.
    pub force: Vec<f64>,
    /// Loaded wheel lag (loaded TE), rad.
    pub theta: f64,
    pub active: Vec<bool>,
    /// Fixed-point iterations on the Weber–Banaschek secant, and active-set changes in all.
    /// Each iteration solves its linear problem exactly, active set included.
    pub iterations: usize,
    pub active_set_changes: usize,
}

/// Gaps below this are violations, m.
const GAP_TOL: f64 = 1e-14;

impl ContactProblem<'_> {
    fn n(&self) -> usize {
        self.lag.len()
    }

    fn min_lag(&self) -> (usize, f64) {
        self.lag
            .iter()
            .copied()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, f64::NAN))
    }

    /// Solves the problem; `warm` is a starting active set (e.g. the previous load's).
    pub fn solve(&self, warm: Option<&[bool]>) -> Result<ContactSolution, SolverError> {
        if !(self.torque >= 0.0 && self.torque.is_finite()) {
            return Err(SolverError::Torque(self.torque));
        }
        self.fixed_point(warm, None)
    }

    /// Lag control: the slice forces when the wheel lags by `theta` (rad);
    /// the `torque` field is not used. Zero forces where no slice penetrates.
    pub fn solve_at_lag(
        &self,
        theta: f64,
        warm: Option<&[bool]>,
    ) -> Result<ContactSolution, SolverError> {
        if !theta.is_finite() {
            return Err(SolverError::NotConverged {
                what: format!("lag control: wheel lag {theta} rad is not finite"),
                iterations: 0,
            });
        }
        self.fixed_point(warm, Some(theta))
    }

    /// Pinion torque Σ λ₁ F of a force vector, N·m.
    pub fn pinion_torque(&self, force: &[f64]) -> f64 {
        force
            .iter()
            .zip(self.lever_pinion)
            .map(|(f, l)| f * l)
            .sum()
    }

    fn fixed_point(
        &self,
        warm: Option<&[bool]>,
        prescribed: Option<f64>,
    ) -> Result<ContactSolution, SolverError> {
        let n = self.n();
        if n == 0 {
            return Err(SolverError::NoContact);
        }
        let (kmin, lmin) = self.min_lag();
        let closed = |th: f64| -> Vec<bool> { self.lag.iter().map(|&l| l < th).collect() };
        if let Some(th) = prescribed {
            if th <= lmin {
                return Ok(ContactSolution {
                    force: vec![0.0; n],
                    theta: th,
                    active: vec![false; n],
                    iterations: 0,
                    active_set_changes: 0,
                });
            }
        } else if self.torque == 0.0 {
            let mut active = vec![false; n];
            active[kmin] = true;
            return Ok(ContactSolution {
                force: vec![0.0; n],
                theta: lmin,
                active,
                iterations: 0,
                active_set_changes: 0,
            });
        }
        // Nominal slice force: the torque over ~8 slices at the mean lever,
        // or under lag control the largest penetration over its own compliance.
        let f_nom = match prescribed {
            None => {
                let lever = self.lever_pinion.iter().sum::<f64>() / n as f64;
                self.torque / lever / 8.0
            }
            Some(th) => (0..n)
                .map(|k| self.lever_wheel[k] * (th - self.lag[k]) / self.compliance[k * n + k])
                .fold(0.0, f64::max),
        };
        let mut u: Vec<f64> = self.line.iter().map(|l| l.secant(f_nom)).collect();
        // The secant of an unloaded slice: at a thousandth of the nominal force.
        let u_open: Vec<f64> = self.line.iter().map(|l| l.secant(1e-3 * f_nom)).collect();
        let mut active = match (warm, prescribed) {
            (Some(w), _) if w.len() == n && w.iter().any(|&a| a) => w.to_vec(),
            (_, Some(th)) => closed(th),
            _ => {
                let mut a = vec![false; n];
                a[kmin] = true;
                a
            }
        };
        let mut force = vec![0.0; n];
        let mut theta = lmin;
        let mut changes = 0;
        for it in 1..=200 {
            let (f, th, ch) = self.linear(&u, &mut active, prescribed)?;
            changes += ch;
            let fmax = f.iter().fold(0.0f64, |a, &b| a.max(b));
            let df = f
                .iter()
                .zip(&force)
                .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
            let dth = (th - theta).abs();
            force = f;
            theta = th;
            for k in 0..n {
                u[k] = if force[k] > 0.0 {
                    self.line[k].secant(force[k])
                } else {
                    u_open[k]
                };
            }
            // Converged when another secant update moves the TE by < 1e-7 µrad
            // and the forces by < 1e-9 of the largest (round-off of the
            // ill-conditioned compliance of finely spaced slices is ~1e-11).
            if it > 1 && df <= 1e-9 * fmax && dth <= 1e-13 {
                return Ok(ContactSolution {
                    force,
                    theta,
                    active,
                    iterations: it,
                    active_set_changes: changes,
                });
            }
        }
        Err(SolverError::NotConverged {
            what: "Weber–Banaschek fixed point".into(),
            iterations: 200,
        })
    }

    /// Exact solution of the linear complementarity problem with compliance
    /// C + diag(u), by active set; returns (F, θ, active-set changes).
    fn linear(
        &self,
        u: &[f64],
        active: &mut [bool],
        prescribed: Option<f64>,
    ) -> Result<(Vec<f64>, f64, usize), SolverError> {
        let n = self.n();
        let c = self.compliance;
        let mut changes = 0;
        // Torque control: m forces + θ; lag control: m forces.
        let extra = usize::from(prescribed.is_none());
        for iter in 0..10 * n + 20 {
            let idx: Vec<usize> = (0..n).filter(|&k| active[k]).collect();
            let m = idx.len();
            let mut a = DMatrix::<f64>::zeros(m + extra, m + extra);
            let mut rhs = DVector::<f64>::zeros(m + extra);
            for (i, &k) in idx.iter().enumerate() {
                for (j, &l) in idx.iter().enumerate() {
                    a[(i, j)] = c[k * n + l];
                }
                a[(i, i)] += u[k];
                match prescribed {
                    None => {
                        a[(i, m)] = -self.lever_wheel[k];
                        a[(m, i)] = self.lever_pinion[k];
                        rhs[i] = -self.lever_wheel[k] * self.lag[k];
                    }
                    Some(th) => rhs[i] = self.lever_wheel[k] * (th - self.lag[k]),
                }
            }
            if prescribed.is_none() {
                rhs[m] = self.torque;
            }
            let x = if m + extra == 0 {
                DVector::zeros(0)
            } else {
                a.lu()
                    .solve(&rhs)
                    .ok_or(SolverError::Singular { slices: m })?
            };
            let theta = prescribed.unwrap_or_else(|| x[m]);
            let mut force = vec![0.0; n];
            for (i, &k) in idx.iter().enumerate() {
                force[k] = x[i];
            }
            let single = iter > 3 * n;
            // Drop negative forces first.
            let neg: Vec<usize> = idx.iter().copied().filter(|&k| force[k] < 0.0).collect();
            if !neg.is_empty() {
                if single {
                    let k = *neg
                        .iter()
                        .min_by(|a, b| force[**a].total_cmp(&force[**b]))
                        .unwrap();
                    active[k] = false;
                } else {
                    for &k in &neg {
                        active[k] = false;
                    }
                }
                if prescribed.is_none() && !active.iter().any(|&x| x) {
                    active[self.min_lag().0] = true;
                }
                changes += 1;
                continue;
            }
            // Then close penetrating open slices.
            let gap = |k: usize| -> f64 {
                self.lever_wheel[k] * (self.lag[k] - theta)
                    + idx.iter().map(|&l| c[k * n + l] * force[l]).sum::<f64>()
            };
            let viol: Vec<(usize, f64)> = (0..n)
                .filter(|&k| !active[k])
                .map(|k| (k, gap(k)))
                .filter(|&(_, g)| g < -GAP_TOL)
                .collect();
            if viol.is_empty() {
                return Ok((force, theta, changes));
            }
            if single {
                let k = viol.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap().0;
                active[k] = true;
            } else {
                for &(k, _) in &viol {
                    active[k] = true;
                }
            }
            changes += 1;
        }
        Err(SolverError::NotConverged {
            what: "active set".into(),
            iterations: 10 * n + 20,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geometry::Material;

    const STEEL: Material = Material::STEEL;

    fn line() -> LineContact {
        LineContact {
            rho: 0.02,
            length: 2e-3,
            h: [3e-3, 3e-3],
            bodies: [STEEL, STEEL],
            edge: None,
        }
    }

    #[test]
    fn one_slice_under_load_closes_by_the_weber_banaschek_approach() {
        // A single slice, no body compliance: the wheel lag grows by exactly
        // the closed-form approach w(F)/λ₂ with F = T/λ₁.
        let (l1, l2, t) = (0.05, 0.1, 200.0);
        let p = ContactProblem {
            compliance: &[0.0],
            lag: &[1e-5],
            lever_wheel: &[l2],
            lever_pinion: &[l1],
            line: &[line()],
            torque: t,
        };
        let s = p.solve(None).unwrap();
        let f = t / l1;
        assert!((s.force[0] - f).abs() < 1e-9 * f);
        let expected = 1e-5 + line().approach(f) / l2;
        assert!(
            (s.theta - expected).abs() < 1e-12 * expected,
            "{} vs {expected}",
            s.theta
        );
    }

    #[test]
    fn two_springs_in_parallel_share_load_by_stiffness_and_the_far_one_stays_open() {
        // Three slices with diagonal compliance (no WB): two touch at once,
        // the third is 1 µm away and must stay open under a small load.
        let c = [1e-9, 0.0, 0.0, 0.0, 2e-9, 0.0, 0.0, 0.0, 1e-9];
        let flat = LineContact {
            rho: 1.0,
            length: 1e3,
            h: [1e-9, 1e-9],
            bodies: [STEEL, STEEL],
            edge: None,
        };
        let p = ContactProblem {
            compliance: &c,
            lag: &[0.0, 0.0, 1e-5],
            lever_wheel: &[0.1; 3],
            lever_pinion: &[0.1; 3],
            line: &[flat; 3],
            torque: 30.0,
        };
        let s = p.solve(None).unwrap();
        // F = 300 N shared 2:1; approach F₀ C₀ = 200 N · 1e-9 = 2e-7 m (< 1 µm).
        assert!((s.force[0] - 200.0).abs() < 1e-3, "{:?}", s.force);
        assert!((s.force[1] - 100.0).abs() < 1e-3);
        assert_eq!(s.force[2], 0.0);
        assert!(!s.active[2]);
        let torque: f64 = s.force.iter().map(|f| f * 0.1).sum();
        assert!((torque - 30.0).abs() < 1e-9 * 30.0);
    }

    #[test]
    fn lag_control_inverts_torque_control() {
        // Three slices, coupled compliance and WB: the forces at the lag that
        // torque control found carry the same torque; below the first
        // touching lag the forces vanish.
        let c = [2e-9, 5e-10, 1e-10, 5e-10, 2e-9, 5e-10, 1e-10, 5e-10, 2e-9];
        let p = ContactProblem {
            compliance: &c,
            lag: &[1e-5, 0.0, 2e-6],
            lever_wheel: &[0.1, 0.11, 0.12],
            lever_pinion: &[0.05, 0.051, 0.052],
            line: &[line(); 3],
            torque: 150.0,
        };
        let s = p.solve(None).unwrap();
        let l = p.solve_at_lag(s.theta, None).unwrap();
        let t = p.pinion_torque(&l.force);
        assert!((t - 150.0).abs() < 1e-7 * 150.0, "{t}");
        for (a, b) in s.force.iter().zip(&l.force) {
            assert!((a - b).abs() < 1e-7 * 150.0 / 0.05, "{a} vs {b}");
        }
        let open = p.solve_at_lag(-1e-7, None).unwrap();
        assert!(open.force.iter().all(|&f| f == 0.0));
    }

    #[test]
    fn zero_torque_gives_the_unloaded_contact() {
        let p = ContactProblem {
            compliance: &[1e-9, 0.0, 0.0, 1e-9],
            lag: &[2e-5, 1e-5],
            lever_wheel: &[0.1; 2],
            lever_pinion: &[0.1; 2],
            line: &[line(); 2],
            torque: 0.0,
        };
        let s = p.solve(None).unwrap();
        assert_eq!(s.theta, 1e-5);
        assert!(s.force.iter().all(|&f| f == 0.0));
        let bad = ContactProblem { torque: -1.0, ..p };
        assert!(matches!(bad.solve(None), Err(SolverError::Torque(_))));
    }
}
