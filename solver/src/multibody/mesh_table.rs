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
//! grid of q₁ × θ and interpolated by cubics in both directions:
//! Catmull–Rom in q₁ (uniform), cubic Hermite with central-difference
//! slopes in θ, whose nodes are fine over the band of unloaded TEs (light
//! loads) and grow geometrically above it ([`lag_grid`]). Along the integration path (a straight line in q₁, θ) that
//! interpolant is a polynomial of degree 6 between grid lines, so 4-point
//! Gauss–Legendre between the crossings integrates it exactly: V, its
//! gradient and its Hessian are exact for the interpolated T₁, and the
//! element is conservative (a run without damping keeps V + kinetic energy
//! − work of the torques). The grid is in θ, not in the deflection θ − θ₀:
//! the unloaded TE has kinks where the contact passes from one tooth pair to
//! the next, and T₁ is smooth across them only at fixed θ.

use crate::element::compliance::PairCompliance;
use crate::element::contact_problem::ContactProblem;
use crate::ltca::{assemble, geometry, Assembled, Geometry};
use crate::multibody::impact_law::{Friction, ImpactLaw};
use crate::SolverError;
use geometry::generation::MemberFrame;
use geometry::pair::FlankPair;
use geometry::utca::RollSurface;
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
    /// Lag nodes θ_m, rad ([`lag_grid`]: fine over the band of unloaded TEs
    /// where light loads act, growing geometrically above it).
    pub lags: Vec<f64>,
    /// Unloaded TE θ₀ per position, rad.
    pub te0: Vec<f64>,
    /// Pinion torque T₁ (N·m) and the contact force on the wheel in the
    /// fixed frame (N): row-major positions × lag nodes.
    pub torque: Vec<f64>,
    pub force: Vec<[f64; 3]>,
    /// The contact's wrench on the wheel about the pitch apex, [N; N·m],
    /// in the frame of the wheel's bearings (the pair's relative pose
    /// applied to the pinion's points and normals): Σ F [n; x × n], same
    /// layout ([`slice_wrench`]).
    pub wrench: Vec<[f64; 6]>,
    /// Friction moments per unit friction coefficient (Φ₁, Φ₂) = (Σ F ℓ₁,
    /// Σ F ℓ₂), N·m (see [`crate::element::slices::friction_levers`]), same layout.
    pub friction: Vec<[f64; 2]>,
    /// Tangential (circumferential) component of the contact force on the
    /// wheel, Σ F λ₂ / ρ₂ (N, [`crate::element::slices::Slice::wheel_tangential`]),
    /// same layout.
    pub tangential: Vec<f64>,
    /// Geometry + assembly + lag-controlled solves, s per position (one core).
    pub cpu_s_per_position: f64,
    /// The impact law's own fields when the table holds that law instead of
    /// the element ([`crate::multibody::impact_table`]); None for the element.
    pub impact: Option<ImpactFields>,
}

/// Fields of an impact-law table ([`crate::multibody::impact_table`]), same layout as
/// the torque.
#[derive(Debug, Clone)]
pub struct ImpactFields {
    pub law: ImpactLaw,
    pub friction: Option<Friction>,
    /// Damping levers A = (Σ w λ₁ λ₂, Σ w λ₂²) and E = (Σ w λ₁ ε,
    /// Σ w λ₂ ε), ε = λ₁ − r λ₂, m²: generalized damping forces
    /// −C (A₁ θ̇ + E₁ q̇₁) on q₁ and +C (A₂ θ̇ + E₂ q̇₁) on q₂.
    pub damping: Vec<[f64; 4]>,
    /// Force-weighted mean slip speed per unit pinion speed, m/rad.
    pub slip: Vec<f64>,
}

/// The impact law's non-conservative fields at (q₁, q₂).
#[derive(Debug, Clone, Copy, Default)]
pub struct ImpactState {
    /// Damping levers (A₁, A₂, E₁, E₂) and their derivatives ∂/∂q_j.
    pub damping: [f64; 4],
    pub damping_grad: [[f64; 2]; 4],
    /// Mean slip speed per unit pinion speed, m/rad.
    pub slip: f64,
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

/// Refuses a table spec too small to interpolate (both force laws).
pub(crate) fn check_spec(spec: &TableSpec) -> Result<(), SolverError> {
    let min_lags = geometry::scene_checks::MIN_TABLE_LAG_NODES;
    if spec.positions < 4 || spec.lag_nodes < min_lags {
        return Err(SolverError::Table(format!(
            "{} positions × {} lag nodes: need at least 4 positions and {min_lags} lag nodes (multibody.table_lag_nodes)",
            spec.positions, spec.lag_nodes
        )));
    }
    Ok(())
}

/// The table's columns and lag grid, shared by both force laws: `pass1`
/// computes the columns of a range of position indices, `lags_of` gives a
/// column's unloaded TE and its lag at the largest torque. A non-periodic
/// table starts `lead` positions before q₁ = 0, (θ_hi − θ_lo)/r plus two
/// steps, since V at q₁ integrates T₁ from first contact, q₁ − (θ − θ_lo)/r.
/// Returns the columns (lead first), `lead` and the lag grid.
pub(crate) fn columns_and_lags<C>(
    spec: &TableSpec,
    ratio: f64,
    pass1: impl Fn(std::ops::Range<i64>) -> Result<Vec<C>, SolverError>,
    lags_of: impl Fn(&C) -> (f64, f64),
) -> Result<(Vec<C>, usize, Vec<f64>), SolverError> {
    let range = |c: &[C]| {
        c.iter().map(&lags_of).fold(
            (f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
            |(lo, hi, te_max), (te0, lag)| (lo.min(te0), hi.max(lag), te_max.max(te0)),
        )
    };
    let mut columns = pass1(0..spec.positions as i64)?;
    let lead = if spec.periodic {
        0
    } else {
        let (lo, hi, _) = range(&columns);
        ((hi - lo) / ratio / spec.step).ceil() as usize + 2
    };
    if lead > 0 {
        let mut before = pass1(-(lead as i64)..0)?;
        before.append(&mut columns);
        columns = before;
    }
    let (lo, hi, te0_max) = range(&columns);
    let lags = lag_grid(lo, te0_max, hi, spec.lag_nodes);
    Ok((columns, lead, lags))
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
fn hermite_weights(x: &[f64], m: usize, at: f64) -> [[f64; 4]; 3] {
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

/// The wrench on the wheel about the pitch apex, [N; N·m], of normal force
/// `f` (N) at slice `sl` with the pinion turned by `turn` (rad):
/// F [n; x × n], x and n the pinion's contact point and outward normal in
/// the fixed frame, the pair's relative `pose` (misalignment) applied.
pub fn slice_wrench(
    frame: &MemberFrame,
    pose: Option<&geometry::misalignment::Pose>,
    sl: &crate::element::slices::Slice,
    turn: f64,
    f: f64,
) -> [f64; 6] {
    let mut x = frame.to_fixed(&nalgebra::Vector3::from(sl.pos), turn);
    let mut n = frame.to_fixed(&nalgebra::Vector3::from(sl.normal), turn);
    if let Some(p) = pose {
        x = p.apply(&x);
        n = p.rotation * n;
    }
    let m = x.cross(&n) * f;
    [f * n.x, f * n.y, f * n.z, m.x, m.y, m.z]
}

/// One position's column of the table (both force laws): the unloaded TE,
/// and per lag node the pinion torque, contact force and friction moments.
pub(crate) struct Column {
    pub(crate) te0: f64,
    pub(crate) torque: Vec<f64>,
    pub(crate) force: Vec<[f64; 3]>,
    pub(crate) wrench: Vec<[f64; 6]>,
    pub(crate) friction: Vec<[f64; 2]>,
    pub(crate) tangential: Vec<f64>,
    pub(crate) cpu: f64,
}

impl MeshTable {
    /// The table from its columns (lead first), laid out position-major.
    pub(crate) fn from_columns(
        spec: TableSpec,
        lead: usize,
        ratio: f64,
        lags: Vec<f64>,
        cols: &[&Column],
        impact: Option<ImpactFields>,
    ) -> MeshTable {
        MeshTable {
            spec,
            lead,
            ratio,
            lags,
            te0: cols.iter().map(|c| c.te0).collect(),
            torque: cols.iter().flat_map(|c| c.torque.iter().copied()).collect(),
            force: cols.iter().flat_map(|c| c.force.iter().copied()).collect(),
            wrench: cols.iter().flat_map(|c| c.wrench.iter().copied()).collect(),
            friction: cols
                .iter()
                .flat_map(|c| c.friction.iter().copied())
                .collect(),
            tangential: cols
                .iter()
                .flat_map(|c| c.tangential.iter().copied())
                .collect(),
            cpu_s_per_position: cols.iter().map(|c| c.cpu).sum::<f64>() / cols.len() as f64,
            impact,
        }
    }

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
        check_spec(&spec)?;
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
                    // Normal forces only: the potential is conservative;
                    // friction is tabulated on its own.
                    let a = assemble(&g, pc, 0.0)?;
                    let s = crate::ltca::solve(&a, spec.torque_max_nm, None)?;
                    Ok((g, a, s.theta, t.elapsed().as_secs_f64()))
                })
                .collect()
        };
        let (columns, lead, lags) = columns_and_lags(
            &spec,
            ratio,
            pass1,
            |p: &(Geometry, Assembled, f64, f64)| (p.0.utca_te, p.2),
        )?;
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
                let mut wrench = Vec::with_capacity(spec.lag_nodes);
                let mut friction = Vec::with_capacity(spec.lag_nodes);
                let mut tangential = Vec::with_capacity(spec.lag_nodes);
                let mut warm: Option<Vec<bool>> = None;
                for &lag in &lags {
                    let s = p.solve_at_lag(lag, warm.as_deref())?;
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
                    let mut w = [0.0; 6];
                    for (sl, &fk) in g.slices.iter().zip(&s.force) {
                        if fk > 0.0 {
                            let turn = g.phi + sl.pair as f64 * tau;
                            let wk = slice_wrench(frame, fp.pose.as_ref(), sl, turn, fk);
                            for (a, b) in w.iter_mut().zip(wk) {
                                *a += b;
                            }
                        }
                    }
                    wrench.push(w);
                    friction.push([0, 1].map(|i| {
                        g.slices
                            .iter()
                            .zip(&s.force)
                            .map(|(sl, f)| f * sl.friction_lever[i])
                            .sum::<f64>()
                    }));
                    tangential.push(
                        g.slices
                            .iter()
                            .zip(&s.force)
                            .map(|(sl, &f)| sl.wheel_tangential(f))
                            .sum::<f64>(),
                    );
                    if s.active.iter().any(|&x| x) {
                        warm = Some(s.active);
                    }
                }
                Ok(Column {
                    te0: g.utca_te,
                    torque,
                    force,
                    wrench,
                    friction,
                    tangential,
                    cpu: cpu0 + t.elapsed().as_secs_f64(),
                })
            })
            .collect::<Result<_, SolverError>>()?;
        let cols: Vec<&Column> = cols.iter().collect();
        Ok(MeshTable::from_columns(
            spec, lead, ratio, lags, &cols, None,
        ))
    }

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
        let torque = |q: f64, th: f64| self.field(|p, m| self.torque[p * nu + m], q, th);
        let [t, tq, tt, ..] = torque(q1, theta)?;
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
