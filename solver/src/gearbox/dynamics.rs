//! The flexible gearbox in time: the contact element of the
//! compliant-bearing model ([`CompliantModel::mesh`], on the first 12
//! coordinates) on the gearbox's linear structure,
//!
//!   M ẍ + C ẋ + K x = f_ext − Lᵀ (F + c_m θ̇′ ℓ)  (embedded in x),
//!
//! integrated by generalized-α with Newton on x_{n+1} and the step control
//! of [`crate::multibody::time_step`], as [`crate::multibody::compliant`]
//! does on its 12 coordinates. With rigid shafts and no housing the
//! structure's M, C, K are that model's and so are the runs.

use super::structure::{BearingLink, GearboxStructure, Part};
use crate::multibody::compliant::{alpha_parameters, CompliantMesh, CompliantModel, X};
use crate::multibody::time_step::{lag_error_ratio, run_until, StepControl, StepHistory};
use crate::SolverError;
use nalgebra::{DMatrix, DVector, Vector3};

/// State at time t.
#[derive(Debug, Clone, PartialEq)]
pub struct GState {
    pub t: f64,
    pub x: DVector<f64>,
    pub v: DVector<f64>,
    pub a: DVector<f64>,
}

/// The contact element on the gearbox structure.
#[derive(Debug, Clone)]
pub struct GearboxModel<'a> {
    /// The contact element, the drive and the member supports' bases (its
    /// own bearing matrices are not used: the structure holds them).
    pub contact: &'a CompliantModel<'a>,
    pub structure: &'a GearboxStructure,
    /// The structure's M, C, K by rows of nonzeros (shafts banded, the
    /// housing's stiffness block-diagonal): the residual at O(nonzeros).
    sparse: [RowSparse; 3],
}

/// A matrix's nonzero entries, row by row.
#[derive(Debug, Clone)]
struct RowSparse {
    ptr: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl RowSparse {
    /// The entries of `m` but those below 1e-14 √|m_ii m_jj| (the
    /// rounding a reduction leaves where theory has zeros: the
    /// Craig–Bampton stiffness between constraint and fixed-interface
    /// modes, the modes' mass off the diagonal).
    fn of(m: &DMatrix<f64>) -> RowSparse {
        let (mut ptr, mut col, mut val) = (vec![0], Vec::new(), Vec::new());
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                let drop = 1e-14 * (m[(i, i)] * m[(j, j)]).abs().sqrt();
                if m[(i, j)].abs() > drop {
                    col.push(j);
                    val.push(m[(i, j)]);
                }
            }
            ptr.push(col.len());
        }
        RowSparse { ptr, col, val }
    }

    /// out += A x.
    fn mul_add(&self, x: &DVector<f64>, out: &mut DVector<f64>) {
        for (i, o) in out.iter_mut().enumerate() {
            let mut acc = 0.0;
            for k in self.ptr[i]..self.ptr[i + 1] {
                acc += self.val[k] * x[self.col[k]];
            }
            *o += acc;
        }
    }
}

fn head(x: &DVector<f64>) -> X {
    X::from_fn(|i, _| x[i])
}

impl<'a> GearboxModel<'a> {
    /// Checks that the structure's first 12 coordinates are the contact
    /// element's (q₁, q₂, d₁, d₂).
    pub fn new(
        contact: &'a CompliantModel<'a>,
        structure: &'a GearboxStructure,
    ) -> Result<Self, SolverError> {
        let p = &structure.parts;
        let ok = p.len() >= 12
            && p[0] == Part::Spin(0)
            && p[1] == Part::Spin(1)
            && p[2..7].iter().all(|&x| x == Part::Body(0))
            && p[7..12].iter().all(|&x| x == Part::Body(1));
        if !ok {
            return Err(SolverError::Table(
                "the gearbox structure must start with q₁, q₂, d₁ (5), d₂ (5)".into(),
            ));
        }
        Ok(GearboxModel {
            contact,
            structure,
            sparse: [
                RowSparse::of(&structure.mass),
                RowSparse::of(&structure.damping),
                RowSparse::of(&structure.stiffness),
            ],
        })
    }

    /// The structure's forces M a + C v + K x.
    pub fn linear(&self, x: &DVector<f64>, v: &DVector<f64>, a: &DVector<f64>) -> DVector<f64> {
        let mut out = DVector::zeros(x.len());
        let [m, c, k] = &self.sparse;
        m.mul_add(a, &mut out);
        c.mul_add(v, &mut out);
        k.mul_add(x, &mut out);
        out
    }

    /// Number of coordinates.
    pub fn dofs(&self) -> usize {
        self.structure.parts.len()
    }

    /// Free coordinates: all but the turn the drive imposes.
    pub fn free(&self) -> Vec<bool> {
        let f = self.contact.free();
        (0..self.dofs()).map(|i| i >= 2 || f[i]).collect()
    }

    /// Residual M a + C v + K x − f_ext − mesh forces at (t, x, v, a), with
    /// the mesh state.
    pub fn residual(
        &self,
        t: f64,
        x: &DVector<f64>,
        v: &DVector<f64>,
        a: &DVector<f64>,
    ) -> Result<(DVector<f64>, CompliantMesh), SolverError> {
        let mesh = self.contact.mesh(&head(x), &head(v))?;
        let mut res = self.linear(x, v, a);
        let ext = self.contact.rigid.drive.torques(t);
        for i in 0..12 {
            res[i] -= mesh.force[i];
        }
        res[0] -= ext[0];
        res[1] -= ext[1];
        Ok((res, mesh))
    }

    /// The bearings' forces on their seats at (x, v), N, in the
    /// structure's bearing order.
    pub fn bearing_forces(&self, x: &DVector<f64>, v: &DVector<f64>) -> Vec<Vector3<f64>> {
        self.structure
            .bearings
            .iter()
            .map(|b: &BearingLink| b.force_on_seat(x.as_slice(), v.as_slice()))
            .collect()
    }

    /// Quasi-static state at pinion rotation q₁: the rigid model's static
    /// turns and speeds, then Newton on K x − mesh forces = f_ext over the
    /// free coordinates, every structure rate zero.
    pub fn static_state(&self, q1: f64) -> Result<GState, SolverError> {
        let rigid = &self.contact.rigid;
        let rs = rigid.static_state(q1)?;
        let n = self.dofs();
        let mut x = DVector::zeros(n);
        let mut v = DVector::zeros(n);
        x[0] = rs.q[0];
        x[1] = rs.q[1];
        v[0] = rs.v[0];
        v[1] = rs.v[1];
        let free = self.free();
        let scale = rigid.table.mean_lag_step();
        let zero = DVector::zeros(n);
        for _ in 0..200 {
            let (res, mesh) = self.residual(0.0, &x, &zero, &zero)?;
            let mut jac = self.structure.stiffness.clone();
            add_corner(&mut jac, &mesh.stiffness, 1.0);
            let mut dx = solve_free(jac, -res, &free)?;
            let r = rigid.table.ratio;
            let dc = self.contact.contact_map() * head(&dx);
            let (s, _) = self.contact.shift.at(rigid.table, mesh.c[0])?;
            let dlag = r * dc[0] - dc[1] - (0..4).map(|i| s[i] * dc[2 + i]).sum::<f64>();
            if dlag.abs() > scale {
                dx *= scale / dlag.abs();
            }
            x += &dx;
            if converged(&dx, &x) {
                return Ok(GState {
                    t: 0.0,
                    x,
                    v,
                    a: DVector::zeros(n),
                });
            }
        }
        Err(SolverError::NotConverged {
            what: "flexible-gearbox quasi-static start".into(),
            iterations: 200,
        })
    }
}

/// J[0..12, 0..12] += w · m.
fn add_corner(j: &mut DMatrix<f64>, m: &nalgebra::SMatrix<f64, 12, 12>, w: f64) {
    for r in 0..12 {
        for c in 0..12 {
            j[(r, c)] += w * m[(r, c)];
        }
    }
}

/// Solves J dx = b on the free coordinates (the others' dx = 0).
fn solve_free(
    mut jac: DMatrix<f64>,
    mut b: DVector<f64>,
    free: &[bool],
) -> Result<DVector<f64>, SolverError> {
    let n = b.len();
    for i in 0..n {
        if !free[i] {
            jac.row_mut(i).fill(0.0);
            jac.column_mut(i).fill(0.0);
            jac[(i, i)] = 1.0;
            b[i] = 0.0;
        }
    }
    jac.lu()
        .solve(&b)
        .ok_or(SolverError::Singular { slices: 0 })
}

/// Newton's update a few ulps of the rotations (and of 1 m or 1 rad for
/// the structure's coordinates).
fn converged(dx: &DVector<f64>, x: &DVector<f64>) -> bool {
    let q = x[0].abs().max(x[1].abs());
    dx.amax() <= 1e-15 * (1.0 + q)
}

const NEWTON_MAX: usize = 40;

/// The structure's part of the Newton matrix for one step size h,
/// J₀ = (1 − α_f)(K + γ/(βh) C) + (1 − α_m)/(βh²) M, split at the contact
/// element's 12 coordinates: [[A₀, B], [Bᵀ, D]]. Only A changes with the
/// element, so D is factored once per h and each Newton iteration solves
/// the 12 × 12 Schur complement (A₀ + A_mesh − B D⁻¹ Bᵀ) x₁ = r₁ − B D⁻¹ r₂,
/// then x₂ = D⁻¹ r₂ − (D⁻¹ Bᵀ) x₁: the same solution as the whole matrix
/// (tested), at O(n²) instead of O(n³) per iteration.
#[derive(Debug, Clone)]
pub struct StepMatrix {
    h: f64,
    a0: nalgebra::SMatrix<f64, 12, 12>,
    b: DMatrix<f64>,
    d: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    /// D⁻¹ Bᵀ and B D⁻¹ Bᵀ.
    d_bt: DMatrix<f64>,
    b_d_bt: nalgebra::SMatrix<f64, 12, 12>,
}

impl StepMatrix {
    /// J₀ of `st` for step `h` and the generalized-α parameters.
    fn new(
        st: &GearboxStructure,
        h: f64,
        [am, af, gamma, beta]: [f64; 4],
    ) -> Result<StepMatrix, SolverError> {
        let j0 = &st.stiffness * (1.0 - af)
            + &st.damping * ((1.0 - af) * gamma / (beta * h))
            + &st.mass * ((1.0 - am) / (beta * h * h));
        let n = j0.nrows();
        let a0 = nalgebra::SMatrix::<f64, 12, 12>::from_fn(|i, j| j0[(i, j)]);
        if n == 12 {
            return Ok(StepMatrix {
                h,
                a0,
                b: DMatrix::zeros(12, 0),
                d: None,
                d_bt: DMatrix::zeros(0, 12),
                b_d_bt: nalgebra::SMatrix::zeros(),
            });
        }
        let b = j0.view((0, 12), (12, n - 12)).into_owned();
        let d = j0.view((12, 12), (n - 12, n - 12)).into_owned().lu();
        let d_bt = d
            .solve(&j0.view((12, 0), (n - 12, 12)).into_owned())
            .ok_or(SolverError::Singular { slices: 0 })?;
        let bdb = &b * &d_bt;
        Ok(StepMatrix {
            h,
            a0,
            b_d_bt: nalgebra::SMatrix::<f64, 12, 12>::from_fn(|i, j| bdb[(i, j)]),
            b,
            d: Some(d),
            d_bt,
        })
    }

    /// J₀'s first 12 rows times `dx`.
    fn top_rows(&self, dx: &DVector<f64>) -> nalgebra::SVector<f64, 12> {
        let d1 = nalgebra::SVector::<f64, 12>::from_fn(|i, _| dx[i]);
        let mut out = self.a0 * d1;
        if self.b.ncols() > 0 {
            out += &self.b * dx.rows(12, dx.len() - 12);
        }
        out
    }

    /// Solves (J₀ + corner) dx = r with the coordinates not `free` held
    /// (those are among the first 12).
    fn solve(
        &self,
        corner: &nalgebra::SMatrix<f64, 12, 12>,
        r: &DVector<f64>,
        free: &[bool],
    ) -> Result<DVector<f64>, SolverError> {
        let n = r.len();
        let r1 = nalgebra::SVector::<f64, 12>::from_fn(|i, _| r[i]);
        let r2_zero = r.rows(12, n - 12).iter().all(|&v| v == 0.0);
        let (y, mut rhs) = match &self.d {
            Some(_) if r2_zero => (None, r1),
            Some(d) => {
                let r2 = r.rows(12, n - 12).into_owned();
                let y = d.solve(&r2).ok_or(SolverError::Singular { slices: 0 })?;
                let by = &self.b * &y;
                (
                    Some(y),
                    r1 - nalgebra::SVector::<f64, 12>::from_fn(|i, _| by[i]),
                )
            }
            None => (None, r1),
        };
        let mut s = self.a0 + corner - self.b_d_bt;
        for i in 0..12 {
            if !free[i] {
                s.row_mut(i).fill(0.0);
                s.column_mut(i).fill(0.0);
                s[(i, i)] = 1.0;
                rhs[i] = 0.0;
            }
        }
        let x1 = s
            .lu()
            .solve(&rhs)
            .ok_or(SolverError::Singular { slices: 0 })?;
        let mut x = DVector::zeros(n);
        x.rows_mut(0, 12).copy_from(&x1);
        if self.d.is_some() {
            let mut x2 = -(&self.d_bt * x1);
            if let Some(y) = y {
                x2 += y;
            }
            x.rows_mut(12, n - 12).copy_from(&x2);
        }
        Ok(x)
    }
}

/// Step sizes the integrator takes: the largest step times 2^(−k/8)
/// (steps 9 % apart), so that a few Newton matrices serve a whole run.
pub fn quantized_step(h: f64, max_step: f64) -> f64 {
    // A step on the grid stays itself despite the logarithm's rounding.
    let k = (8.0 * (max_step / h).log2() - 1e-9).ceil().max(0.0);
    max_step * (-k / 8.0).exp2()
}

/// Most Newton matrices kept (one per step size in use).
const MATRICES_KEPT: usize = 32;

/// The Newton matrices of the step sizes in use, and how many were built.
#[derive(Debug, Clone, Default)]
pub struct StepMatrices {
    kept: Vec<StepMatrix>,
    /// Matrices built over the run (a new step size each).
    pub built: usize,
}

impl StepMatrices {
    /// The matrix of step `h`, built (and the oldest let go beyond
    /// [`MATRICES_KEPT`]) when no kept one has it.
    fn of(
        &mut self,
        st: &GearboxStructure,
        h: f64,
        params: [f64; 4],
    ) -> Result<&StepMatrix, SolverError> {
        let at = match self.kept.iter().position(|j| j.h == h) {
            Some(i) => i,
            None => {
                if self.kept.len() == MATRICES_KEPT {
                    self.kept.remove(0);
                }
                self.kept.push(StepMatrix::new(st, h, params)?);
                self.built += 1;
                self.kept.len() - 1
            }
        };
        Ok(&self.kept[at])
    }
}

/// One generalized-α step from `s` over `h`: the new state, the α-point and
/// the Newton iterations. `matrices` keeps the Newton matrices of the step
/// sizes used.
pub fn alpha_step(
    m: &GearboxModel,
    s: &GState,
    h: f64,
    rho: f64,
    matrices: &mut StepMatrices,
) -> Result<(GState, GState, usize), SolverError> {
    let params = alpha_parameters(rho);
    let [am, af, gamma, beta] = params;
    let free = m.free();
    let rigid = &m.contact.rigid;
    let t1 = s.t + h;
    let ta = t1 - af * h;
    let mut x = &s.x + &s.v * h + &s.a * (0.5 * h * h);
    let fixed = rigid.imposed(t1).map(|(i, [ang, w, acc])| {
        let ang_now = rigid.imposed(s.t).expect("the same drive").1[0];
        (i, [s.x[i] + ang - ang_now, w, acc])
    });
    if let Some((i, [q, _, _])) = fixed {
        x[i] = q;
    }
    let kin = |x: &DVector<f64>| -> (DVector<f64>, DVector<f64>) {
        let mut a = (x - &s.x - &s.v * h - &s.a * (h * h * (0.5 - beta))) / (beta * h * h);
        let mut v = &s.v + (&s.a * (1.0 - gamma) + &a * gamma) * h;
        if let Some((i, [_, w, acc])) = fixed {
            a[i] = acc;
            v[i] = w;
        }
        (v, a)
    };
    let jm = matrices.of(m.structure, h, params)?;
    let ext = rigid.drive.torques(ta);
    // The structure's forces at the α-point of the current x: computed at
    // the predictor, then carried: they are linear in x with J₀ their
    // exact Jacobian, so a Newton step changes them by J₀ dx, and rows 12
    // on (no mesh force there) then vanish: the step solved them exactly.
    let mut linear: Option<DVector<f64>> = None;
    for it in 1..=NEWTON_MAX {
        let (v, a) = kin(&x);
        let xm = &x * (1.0 - af) + &s.x * af;
        let vm = &v * (1.0 - af) + &s.v * af;
        let mesh = m.contact.mesh(&head(&xm), &head(&vm))?;
        let lin = match linear.take() {
            Some(l) => l,
            None => {
                let amid = &a * (1.0 - am) + &s.a * am;
                m.linear(&xm, &vm, &amid)
            }
        };
        let mut res = lin.clone();
        for i in 0..12 {
            res[i] -= mesh.force[i];
        }
        res[0] -= ext[0];
        res[1] -= ext[1];
        let corner = mesh.stiffness * (1.0 - af) + mesh.damping * ((1.0 - af) * gamma / (beta * h));
        let dx = jm.solve(&corner, &-res, &free)?;
        x += &dx;
        let mut next = lin;
        let top = jm.top_rows(&dx);
        for i in 0..12 {
            next[i] += top[i];
        }
        let n = next.len();
        next.rows_mut(12, n - 12).fill(0.0);
        linear = Some(next);
        if converged(&dx, &x) {
            let (v, a) = kin(&x);
            let mid = GState {
                t: ta,
                x: &x * (1.0 - af) + &s.x * af,
                v: &v * (1.0 - af) + &s.v * af,
                a: &a * (1.0 - am) + &s.a * am,
            };
            return Ok((GState { t: t1, x, v, a }, mid, it));
        }
    }
    Err(SolverError::NotConverged {
        what: "flexible-gearbox generalized-α Newton".into(),
        iterations: NEWTON_MAX,
    })
}

/// Integrator of the gearbox: generalized-α with the step control on the
/// shaft lag r q₁ − q₂, as the compliant-bearing model's, each step cut
/// down to [`quantized_step`].
#[derive(Debug, Clone)]
pub struct GearboxIntegrator {
    pub rho_inf: f64,
    pub control: StepControl,
    pub h: f64,
    pub rejected: usize,
    pub newton_iterations: usize,
    pub history: StepHistory,
    /// Newton matrices per step size.
    pub matrices: StepMatrices,
}

impl GearboxIntegrator {
    pub fn new(rho_inf: f64, control: StepControl) -> Self {
        GearboxIntegrator {
            rho_inf,
            control,
            h: control.max_step,
            rejected: 0,
            newton_iterations: 0,
            history: StepHistory::default(),
            matrices: StepMatrices::default(),
        }
    }

    /// One accepted step (retrying smaller ones), not past `t_end`: the new
    /// state and its α-point.
    pub fn step(
        &mut self,
        m: &GearboxModel,
        s: &GState,
        t_end: f64,
    ) -> Result<(GState, GState), SolverError> {
        let r = m.contact.rigid.table.ratio;
        loop {
            let left = (t_end - s.t).max(0.0);
            if left <= 0.0 {
                return Ok((s.clone(), s.clone()));
            }
            let h = if self.h < left {
                quantized_step(self.h, self.control.max_step).max(self.control.min_step)
            } else {
                left
            };
            let judged =
                alpha_step(m, s, h, self.rho_inf, &mut self.matrices).map(|(next, mid, iters)| {
                    self.newton_iterations += iters;
                    let turns = |x: &DVector<f64>| [x[0], x[1]];
                    let ratio = lag_error_ratio(
                        r,
                        [turns(&s.x), turns(&s.v), turns(&s.a)],
                        turns(&next.x),
                        h,
                        self.control.tolerance,
                    );
                    ((next, mid), ratio)
                });
            if let Some(accepted) = self.control.judge(
                &mut self.h,
                &mut self.rejected,
                &mut self.history,
                h,
                judged,
            )? {
                return Ok(accepted);
            }
        }
    }
}

/// Integrates from `s` to `t_end`, calling `record` with the start (its
/// own α-point) and after every accepted step with the state and its
/// α-point; returns the final state and the number of steps.
pub fn integrate(
    m: &GearboxModel,
    s: GState,
    integ: &mut GearboxIntegrator,
    t_end: f64,
    record: impl FnMut(&GState, &GState) -> Result<(), SolverError>,
) -> Result<(GState, usize), SolverError> {
    run_until(s, |s| s.t, t_end, |s| integ.step(m, s, t_end), record)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bearings::flexible_shaft::{Shaft, ShaftSegment};
    use crate::bearings::support::{Bearing, Support};
    use crate::gearbox::{assemble, MemberParts};
    use crate::multibody::compliant::MemberBody;

    fn member(axis: Vector3<f64>) -> MemberBody {
        let b = |at: f64, axial: f64| Bearing {
            axial_position_m: at,
            radial_stiffness_n_per_m: 5e8,
            axial_stiffness_n_per_m: axial,
        };
        let bearings = [b(0.05, 2e8), b(0.15, 0.0)];
        MemberBody {
            support: Support::new("pinion.bearings", axis, Vector3::zeros(), &bearings).unwrap(),
            damping: vec![(2e3, 1e3); 2],
            mass_kg: 2.0,
            centroid_m: 0.02,
            transverse_inertia_kgm2: 3e-3,
        }
    }

    /// Steps are cut down onto the grid max·2^(−k/8): never above the
    /// controller's step, less than 9 % below it, and a step on the grid
    /// stays itself.
    #[test]
    fn quantized_steps_lie_on_the_grid_just_below_the_asked_step() {
        let max = 1e-5;
        for i in 0..400 {
            let h = max * (0.001f64).powf(i as f64 / 399.0);
            let q = quantized_step(h, max);
            assert!(
                q <= h * (1.0 + 1e-12) && q > h * 0.5f64.powf(1.0 / 8.0) * (1.0 - 1e-12),
                "{h} -> {q}"
            );
            let k = 8.0 * (max / q).log2();
            assert!((k - k.round()).abs() < 1e-9, "{q} off the grid");
            assert_eq!(quantized_step(q, max), q);
        }
        assert_eq!(quantized_step(2.0 * max, max), max);
    }

    /// The Schur complement's solution equals the whole Newton matrix's
    /// (LU of J₀ + corner with the held coordinate's row and column
    /// replaced), for an unsymmetric corner as the element's tangent is.
    #[test]
    fn schur_complement_solve_equals_the_whole_newton_matrix() {
        let members = [
            member(Vector3::new(0.0, 0.6, 0.8)),
            member(Vector3::new(1.0, 0.0, 0.0)),
        ];
        let shaft = Shaft {
            segments: vec![ShaftSegment {
                from_m: 0.0,
                to_m: 0.18,
                outer_diameter_m: 0.04,
                inner_diameter_m: 0.0,
            }],
            seat_m: 0.01,
            youngs_modulus_pa: 206e9,
            poisson_ratio: 0.3,
        };
        let parts: [MemberParts; 2] = std::array::from_fn(|k| MemberParts {
            body: &members[k],
            polar_inertia_kgm2: 1e-2,
            shaft: Some((&shaft, 7850.0)),
        });
        let st = assemble(parts, None, 0.02).unwrap();
        let n = st.parts.len();
        let params = alpha_parameters(0.8);
        let h = 3e-5;
        let jm = StepMatrix::new(&st, h, params).unwrap();
        let corner = nalgebra::SMatrix::<f64, 12, 12>::from_fn(|i, j| {
            1e7 * (((i * 7 + j * 3) % 11) as f64 - 5.0) + if i == j { 1e9 } else { 0.0 }
        });
        let r = DVector::from_fn(n, |i, _| ((i * 13) % 17) as f64 - 8.0);
        let mut free = vec![true; n];
        free[1] = false;
        let got = jm.solve(&corner, &r, &free).unwrap();
        let [am, af, gamma, beta] = params;
        let mut j = &st.stiffness * (1.0 - af)
            + &st.damping * ((1.0 - af) * gamma / (beta * h))
            + &st.mass * ((1.0 - am) / (beta * h * h));
        add_corner(&mut j, &corner, 1.0);
        let want = solve_free(j, r, &free).unwrap();
        assert!(
            (&got - &want).amax() <= 1e-10 * want.amax(),
            "{}",
            (&got - &want).amax() / want.amax()
        );
        assert_eq!(got[1], 0.0);
    }
}
