//! Multibody with compliant bearings: each member turns about its own axis
//! (q₁, q₂ as in [`crate::multibody::model`]) and moves on its bearings by five
//! small coordinates dₖ (translations along e₁, e₂, a and tilts about e₁,
//! e₂ of [`crate::bearings::support::Support::basis`], about its pitch apex), 12
//! coordinates x = (q₁, q₂, d₁, d₂) in all.
//!
//! The contact sees the members' displacements through the constant map
//! of [`crate::bearings::relative_twist`]: the contact coordinates
//!
//!   c = L x = (q₁ + δq₁, q₂ + δq₂, E, P, G, ΔΣ),  (δq₁, δq₂, m) = J d,
//!
//! and the element is the rigid-bearing table ([`crate::multibody::mesh_table`]) read
//! at the equivalent lag ([`crate::multibody::lag_shift`]): with s(q₁) = ∂θ₀/∂m the
//! unloaded TE's shift per misalignment, the pair at misalignment m and
//! lag θ is the aligned pair at θ − s(q₁)·m, i.e. at wheel rotation
//! q₂' = q₂ + s(q₁)·m. With g = ∇V₀ and H its Hessian at (q₁, q₂'), the
//! element's forces on c are
//!
//!   F = (g₁, g₂, g₂ s₁, …, g₂ s₄),
//!
//! the pinion torque T₁(q₁, θ − s·m) exactly as the table gives it, the
//! wheel torque, and on each misalignment the wheel torque times the lag it
//! shifts (virtual work: for one contact point this is the normal force
//! along its line of action, the mesh stiffness acting on the bearings).
//! Its tangent ∂F/∂c (∂q₂'/∂q₁ = s'·m, ∂q₂'/∂mᵢ = sᵢ):
//!
//!   ∂F₁/∂c = (H₁₁ + H₁₂ s'·m, H₁₂, H₁₂ s),
//!   ∂F₂/∂c = (H₂₁ + H₂₂ s'·m, H₂₂, H₂₂ s),
//!   ∂F_{mᵢ}/∂c = sᵢ ∂F₂/∂c + (g₂ sᵢ', 0, 0).
//!
//! F is the gradient of V₀(q₁, q₂ + s(q₁)·m) but for the term
//! g₂ s'(q₁)·m in F₁, left out so that the pinion torque is the table's at
//! the equivalent lag (the potential's path integral runs over q₁ at the
//! endpoint's s, which would add a torque of relative size s'·m); the
//! tangent above is therefore slightly unsymmetric and the scheme is
//! generalized-α only. The mesh damping c_m acts on the equivalent lag's
//! rate, θ̇' = ℓ·ċ with ℓ = (r, −1, −s), as the rigid model's on θ̇.
//!
//! Equations of motion, M ẍ + C_b ẋ + K_b x = f_ext − Lᵀ (F + c_m θ̇' ℓ),
//! with M the polar moments on (q₁, q₂) and each member's rigid-body mass
//! matrix about its apex on dₖ, K_b and C_b its bearings' stiffness and
//! damping (Qₖᵀ K Qₖ), f_ext the drive's torques on (q₁, q₂). Gyroscopic
//! coupling of the spin with the tilts is not modelled. The shaft TE is
//! r q₁ − q₂: the rotations of the shafts, as the LTCA on a displaced pose
//! ([`crate::bearings::system_deflection`]) reports it.

use crate::bearings::relative_twist::TwistMap;
use crate::bearings::support::Support;
use crate::multibody::lag_shift::LagShift;
use crate::multibody::model::Model;
use crate::multibody::time_step::{lag_error_ratio, run_until, StepControl, StepHistory};
use crate::SolverError;
use nalgebra::{Matrix3, SMatrix, SVector, Vector3, Vector6};

/// Coordinates of the compliant model: (q₁, q₂, d₁ (5), d₂ (5)).
pub type X = SVector<f64, 12>;
type M12 = SMatrix<f64, 12, 12>;
type M6 = SMatrix<f64, 6, 6>;

/// One member's body on its bearings.
#[derive(Debug, Clone)]
pub struct MemberBody {
    pub support: Support,
    /// Viscous damping per bearing (radial, axial), N·s/m, in the order of
    /// the support's bearings.
    pub damping: Vec<(f64, f64)>,
    pub mass_kg: f64,
    /// Centre of mass along the axis from the pitch apex, m.
    pub centroid_m: f64,
    /// Moment of inertia about an axis ⊥ the shaft through the centre of
    /// mass, kg·m².
    pub transverse_inertia_kgm2: f64,
}

impl MemberBody {
    /// The 6 × 6 mass matrix of [u; θ] about the apex:
    /// [[m I, −m [c]ₓ], [m [c]ₓ, I_c + m [c]ₓᵀ [c]ₓ]], c the centre of
    /// mass, I_c = J_t (I − a aᵀ) + J_p a aᵀ (J_p the `polar` moment).
    pub fn mass_matrix(&self, polar: f64) -> M6 {
        let a = self.support.axis();
        let c = a * self.centroid_m;
        let cx = Matrix3::new(0.0, -c.z, c.y, c.z, 0.0, -c.x, -c.y, c.x, 0.0);
        let aat = a * a.transpose();
        let ic = (Matrix3::identity() - aat) * self.transverse_inertia_kgm2 + aat * polar;
        let m = self.mass_kg;
        let mut out = M6::zeros();
        out.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&(Matrix3::identity() * m));
        out.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-cx * m));
        out.fixed_view_mut::<3, 3>(3, 0).copy_from(&(cx * m));
        out.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(ic + cx.transpose() * cx * m));
        out
    }
}

/// Where the element's forces on the misalignments come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BearingLoad {
    /// F_m = g₂ s(q₁): the wheel torque times the unloaded TE's shift, the
    /// normal force of the first contact point along its line of action.
    UnloadedShift,
    /// F_m from the LTCA's wrench on the wheel at the equivalent lag
    /// ([`crate::multibody::mesh_table::MeshTable::wrench`]): F_c = T⁻ᵀ W (T the twist
    /// map), the load shared among the slices and tooth pairs as loaded.
    LoadedWrench,
}

/// The compliant-bearing model.
#[derive(Debug, Clone)]
pub struct CompliantModel<'a> {
    /// Table, polar moments, mesh damping and drive (no friction, no coast
    /// flanks, the element's table).
    pub rigid: Model<'a>,
    pub shift: &'a LagShift,
    pub members: [MemberBody; 2],
    pub bearing_load: BearingLoad,
    twist: TwistMap,
    /// T⁻ᵀ: the contact coordinates' forces of a wrench on the wheel.
    wrench_map: M6,
    /// c = L x.
    l: SMatrix<f64, 6, 12>,
    mass: M12,
    stiffness: M12,
    damping: M12,
}

/// State at time t.
#[derive(Debug, Clone, Copy, Default)]
pub struct CState {
    pub t: f64,
    pub x: X,
    pub v: X,
    pub a: X,
}

/// The element's forces on the contact coordinates c and on x.
#[derive(Debug, Clone, Copy)]
pub struct CompliantMesh {
    /// Contact coordinates c = (q₁ + δq₁, q₂ + δq₂, E, P, G, ΔΣ).
    pub c: Vector6<f64>,
    /// F (potential part) + c_m θ̇' ℓ on c, N·m and N.
    pub force_c: Vector6<f64>,
    /// Generalized forces on x, −Lᵀ force_c.
    pub force: X,
    /// −∂force/∂x and −∂force/∂ẋ.
    pub stiffness: M12,
    pub damping: M12,
    /// Equivalent lag θ' = r c₁ − c₂ − s·m and its distance above θ₀, rad.
    pub lag: f64,
    pub u: f64,
}

/// Generalized-α parameters (Chung & Hulbert 1993) of ρ∞.
pub(crate) fn alpha_parameters(rho: f64) -> [f64; 4] {
    let am = (2.0 * rho - 1.0) / (rho + 1.0);
    let af = rho / (rho + 1.0);
    let gamma = 0.5 - am + af;
    let beta = 0.25 * (1.0 - am + af).powi(2);
    [am, af, gamma, beta]
}

impl<'a> CompliantModel<'a> {
    /// The model of `rigid` (its table, polar moments, mesh damping and
    /// drive) with the members on `members`; `hand` is the trace sign of
    /// the pinion's hand ([`geometry::generation::trace_sign`]).
    pub fn new(
        rigid: Model<'a>,
        shift: &'a LagShift,
        members: [MemberBody; 2],
        hand: f64,
    ) -> Result<Self, SolverError> {
        if rigid.friction != 0.0 || rigid.coast.is_some() || rigid.table.impact.is_some() {
            return Err(SolverError::Table(
                "the compliant-bearing multibody takes the element's table without friction or coast flanks (multibody.friction = 0, no coast contact, force_law = \"element\")".into(),
            ));
        }
        if shift.slope.len() != rigid.table.nodes() {
            return Err(SolverError::Table(format!(
                "lag shift of {} nodes for a table of {}",
                shift.slope.len(),
                rigid.table.nodes()
            )));
        }
        let twist = TwistMap::new(
            members[0].support.axis(),
            members[1].support.axis(),
            rigid.table.spec.direction,
            hand,
        );
        let (q1, q2) = (members[0].support.basis(), members[1].support.basis());
        let j = twist.matrix(&q1, &q2);
        let mut l = SMatrix::<f64, 6, 12>::zeros();
        l[(0, 0)] = 1.0;
        l[(1, 1)] = 1.0;
        l.fixed_view_mut::<6, 10>(0, 2).copy_from(&j);
        let mut mass = M12::zeros();
        let mut stiffness = M12::zeros();
        let mut damping = M12::zeros();
        mass[(0, 0)] = rigid.inertia[0];
        mass[(1, 1)] = rigid.inertia[1];
        for (k, (mb, q)) in members.iter().zip([q1, q2]).enumerate() {
            let o = 2 + 5 * k;
            let m6 = mb.mass_matrix(rigid.inertia[k]);
            mass.fixed_view_mut::<5, 5>(o, o)
                .copy_from(&(q.transpose() * m6 * q));
            stiffness
                .fixed_view_mut::<5, 5>(o, o)
                .copy_from(&(q.transpose() * mb.support.stiffness() * q));
            damping
                .fixed_view_mut::<5, 5>(o, o)
                .copy_from(&(q.transpose() * mb.support.damping(&mb.damping) * q));
        }
        let mut t = M6::zeros();
        for k in 0..6 {
            let mut e = Vector6::zeros();
            e[k] = 1.0;
            t.set_column(k, &twist.of_displacements(&e, &Vector6::zeros()));
        }
        let wrench_map = t
            .try_inverse()
            .ok_or_else(|| SolverError::Table("singular twist map".into()))?
            .transpose();
        Ok(CompliantModel {
            rigid,
            shift,
            members,
            bearing_load: BearingLoad::LoadedWrench,
            twist,
            wrench_map,
            l,
            mass,
            stiffness,
            damping,
        })
    }

    /// The map c = L x.
    pub fn contact_map(&self) -> &SMatrix<f64, 6, 12> {
        &self.l
    }

    /// The twist map of the pair.
    pub fn twist(&self) -> &TwistMap {
        &self.twist
    }

    /// Mass, bearing stiffness and bearing damping matrices on x.
    pub fn matrices(&self) -> (&M12, &M12, &M12) {
        (&self.mass, &self.stiffness, &self.damping)
    }

    /// Member `k`'s displacement [u; θ] about its apex (fixed frame).
    pub fn displacement(&self, x: &X, k: usize) -> Vector6<f64> {
        self.members[k].support.basis() * x.fixed_rows::<5>(2 + 5 * k)
    }

    /// The element at (x, v).
    pub fn mesh(&self, x: &X, v: &X) -> Result<CompliantMesh, SolverError> {
        let table = self.rigid.table;
        let r = table.ratio;
        let c = self.l * x;
        let cd = self.l * v;
        let m = [c[2], c[3], c[4], c[5]];
        let (s, ds) = self.shift.at(table, c[0])?;
        let sm: f64 = (0..4).map(|i| s[i] * m[i]).sum();
        let dsm: f64 = (0..4).map(|i| ds[i] * m[i]).sum();
        let ms = table.state(c[0], c[1] + sm)?;
        let (g, h) = (ms.grad, ms.hess);
        let mut f = Vector6::new(
            g[0],
            g[1],
            g[1] * s[0],
            g[1] * s[1],
            g[1] * s[2],
            g[1] * s[3],
        );
        // ∂F/∂c.
        let mut df = M6::zeros();
        let row = |a: f64, b: f64| {
            Vector6::new(a + b * dsm, b, b * s[0], b * s[1], b * s[2], b * s[3]).transpose()
        };
        let r1 = row(h[0][0], h[0][1]);
        let r2 = row(h[1][0], h[1][1]);
        df.set_row(0, &r1);
        df.set_row(1, &r2);
        match self.bearing_load {
            BearingLoad::UnloadedShift => {
                for i in 0..4 {
                    let mut ri = r2 * s[i];
                    ri[0] += g[1] * ds[i];
                    df.set_row(2 + i, &ri);
                }
            }
            BearingLoad::LoadedWrench => {
                // W(q₁, θ'), θ' = r c₁ − c₂ − s(c₁)·m.
                let w = table.wrench_state(c[0], ms.theta)?;
                let value = Vector6::from_fn(|k, _| w[k][0]);
                let dq = Vector6::from_fn(|k, _| w[k][1]);
                let dt = Vector6::from_fn(|k, _| w[k][2]);
                let lag_grad = Vector6::new(r - dsm, -1.0, -s[0], -s[1], -s[2], -s[3]).transpose();
                let fc = self.wrench_map * value;
                let dfc = self.wrench_map * (dq * Vector6::x().transpose() + dt * lag_grad);
                for i in 2..6 {
                    f[i] = fc[i];
                    df.set_row(i, &dfc.row(i));
                }
            }
        }
        // Mesh damping on the equivalent lag's rate.
        let (step, _) = crate::multibody::model::smoothstep(ms.u / table.du());
        let cm = self.rigid.damping * step;
        let ell = Vector6::new(r, -1.0, -s[0], -s[1], -s[2], -s[3]);
        let rate = ell.dot(&cd);
        f += ell * (cm * rate);
        let lt_ell = self.l.transpose() * ell;
        Ok(CompliantMesh {
            c,
            force_c: f,
            force: -(self.l.transpose() * f),
            stiffness: self.l.transpose() * df * self.l,
            damping: lt_ell * lt_ell.transpose() * cm,
            lag: ms.theta,
            u: ms.u,
        })
    }

    /// Residual of the equations of motion at (x, v, a) and time t
    /// (M a + C_b v + K_b x − f_ext − mesh forces), with the mesh state.
    pub fn residual(&self, t: f64, x: &X, v: &X, a: &X) -> Result<(X, CompliantMesh), SolverError> {
        let mesh = self.mesh(x, v)?;
        let ext = self.rigid.drive.torques(t);
        let mut res = self.mass * a + self.damping * v + self.stiffness * x - mesh.force;
        res[0] -= ext[0];
        res[1] -= ext[1];
        Ok((res, mesh))
    }

    /// The bearings' forces on member `k` at (x, v), N, in the support's
    /// order: stiffness and damping.
    pub fn bearing_forces(&self, x: &X, v: &X, k: usize) -> Vec<Vector3<f64>> {
        let mb = &self.members[k];
        let d = self.displacement(x, k);
        let dv = self.displacement(v, k);
        let el = mb
            .support
            .reactions(&crate::bearings::support::Displacement {
                translation: Vector3::new(d[0], d[1], d[2]),
                rotation: Vector3::new(d[3], d[4], d[5]),
            });
        let dm = mb.support.damping_reactions(&dv, &mb.damping);
        el.iter().zip(&dm).map(|(a, b)| a + b).collect()
    }

    /// The mesh's wrench on the pinion about the apex, [N; N·m], fixed
    /// frame: −Tᵀ F_c with T the twist map (the wheel's is its opposite).
    pub fn pinion_mesh_wrench(&self, mesh: &CompliantMesh) -> Vector6<f64> {
        let mut w = Vector6::zeros();
        for k in 0..6 {
            let mut e = Vector6::zeros();
            e[k] = 1.0;
            let col = self.twist.of_displacements(&e, &Vector6::zeros());
            w[k] = -col.dot(&mesh.force_c);
        }
        w
    }

    /// Quasi-static state at pinion rotation q₁: the rigid model's static
    /// state (its speeds), then Newton on the static balance
    /// K_b x − mesh forces = f_ext over the free coordinates (the member
    /// with imposed speed held), the bearing rates zero.
    pub fn static_state(&self, q1: f64) -> Result<CState, SolverError> {
        let rs = self.rigid.static_state(q1)?;
        let mut x = X::zeros();
        let mut v = X::zeros();
        x[0] = rs.q[0];
        x[1] = rs.q[1];
        v[0] = rs.v[0];
        v[1] = rs.v[1];
        let free = self.free();
        let scale = self.rigid.table.mean_lag_step();
        for _ in 0..200 {
            let (res, mesh) = self.residual(0.0, &x, &X::zeros(), &X::zeros())?;
            let jac = self.stiffness + mesh.stiffness;
            let mut dx = solve_free(jac, -res, &free)?;
            // Keep the equivalent lag's change within a mean lag step.
            let r = self.rigid.table.ratio;
            let dc = self.l * dx;
            let (s, _) = self.shift.at(self.rigid.table, mesh.c[0])?;
            let dlag = r * dc[0] - dc[1] - (0..4).map(|i| s[i] * dc[2 + i]).sum::<f64>();
            if dlag.abs() > scale {
                dx *= scale / dlag.abs();
            }
            x += dx;
            if converged(&dx, &x) {
                return Ok(CState {
                    t: 0.0,
                    x,
                    v,
                    a: X::zeros(),
                });
            }
        }
        Err(SolverError::NotConverged {
            what: "compliant-bearing quasi-static start".into(),
            iterations: 200,
        })
    }

    /// Free coordinates: the bearings' all, and the rotations the drive
    /// leaves free.
    pub fn free(&self) -> [bool; 12] {
        let f = self.rigid.drive.free();
        std::array::from_fn(|i| if i < 2 { f[i] } else { true })
    }
}

/// Solves J dx = b on the free coordinates (the others' dx = 0).
fn solve_free(mut jac: M12, mut b: X, free: &[bool; 12]) -> Result<X, SolverError> {
    for i in 0..12 {
        if !free[i] {
            for j in 0..12 {
                jac[(i, j)] = 0.0;
                jac[(j, i)] = 0.0;
            }
            jac[(i, i)] = 1.0;
            b[i] = 0.0;
        }
    }
    jac.lu()
        .solve(&b)
        .ok_or(SolverError::Singular { slices: 0 })
}

/// Newton's update a few ulps of the rotations (and of 1 m or 1 rad for
/// the bearing coordinates).
fn converged(dx: &X, x: &X) -> bool {
    let q = x[0].abs().max(x[1].abs());
    dx.amax() <= 1e-15 * (1.0 + q)
}

const NEWTON_MAX: usize = 40;

/// One generalized-α step of the compliant model from `s` over `h`,
/// Newton on x_{n+1}; returns the new state, the α-point (x, v, a and time
/// at which the balance holds) and the Newton iterations.
#[allow(clippy::type_complexity)]
pub fn alpha_step(
    m: &CompliantModel,
    s: &CState,
    h: f64,
    rho: f64,
) -> Result<(CState, CState, usize), SolverError> {
    let [am, af, gamma, beta] = alpha_parameters(rho);
    let free = m.free();
    let t1 = s.t + h;
    let ta = t1 - af * h;
    let mut x = s.x + s.v * h + s.a * (0.5 * h * h);
    let fixed = m.rigid.imposed(t1).map(|(i, [ang, w, acc])| {
        let ang_now = m.rigid.imposed(s.t).unwrap().1[0];
        (i, [s.x[i] + ang - ang_now, w, acc])
    });
    if let Some((i, [q, _, _])) = fixed {
        x[i] = q;
    }
    let kin = |x: &X| -> (X, X) {
        let mut a = (x - s.x - s.v * h - s.a * (h * h * (0.5 - beta))) / (beta * h * h);
        let mut v = s.v + (s.a * (1.0 - gamma) + a * gamma) * h;
        if let Some((i, [_, w, acc])) = fixed {
            a[i] = acc;
            v[i] = w;
        }
        (v, a)
    };
    for it in 1..=NEWTON_MAX {
        let (v, a) = kin(&x);
        let xm = x * (1.0 - af) + s.x * af;
        let vm = v * (1.0 - af) + s.v * af;
        let amid = a * (1.0 - am) + s.a * am;
        let (res, mesh) = m.residual(ta, &xm, &vm, &amid)?;
        let jac =
            (m.stiffness + mesh.stiffness + (m.damping + mesh.damping) * (gamma / (beta * h)))
                * (1.0 - af)
                + m.mass * ((1.0 - am) / (beta * h * h));
        let dx = solve_free(jac, -res, &free)?;
        x += dx;
        if converged(&dx, &x) {
            let (v, a) = kin(&x);
            let mid = CState {
                t: ta,
                x: x * (1.0 - af) + s.x * af,
                v: v * (1.0 - af) + s.v * af,
                a: a * (1.0 - am) + s.a * am,
            };
            return Ok((CState { t: t1, x, v, a }, mid, it));
        }
    }
    Err(SolverError::NotConverged {
        what: "compliant-bearing generalized-α Newton".into(),
        iterations: NEWTON_MAX,
    })
}

/// Integrator of the compliant model: generalized-α with the step control
/// of [`crate::multibody::time_step`] (the local error on the shaft lag r q₁ − q₂).
#[derive(Debug, Clone, Copy)]
pub struct CompliantIntegrator {
    pub rho_inf: f64,
    pub control: StepControl,
    pub h: f64,
    pub rejected: usize,
    pub newton_iterations: usize,
    pub history: StepHistory,
}

impl CompliantIntegrator {
    pub fn new(rho_inf: f64, control: StepControl) -> Self {
        CompliantIntegrator {
            rho_inf,
            control,
            h: control.max_step,
            rejected: 0,
            newton_iterations: 0,
            history: StepHistory::default(),
        }
    }

    /// One accepted step (retrying smaller ones), not past `t_end`; returns
    /// the new state and its α-point.
    pub fn step(
        &mut self,
        m: &CompliantModel,
        s: &CState,
        t_end: f64,
    ) -> Result<(CState, CState), SolverError> {
        let r = m.rigid.table.ratio;
        loop {
            let h = self.h.min(t_end - s.t).max(0.0);
            if h <= 0.0 {
                return Ok((*s, *s));
            }
            let judged = alpha_step(m, s, h, self.rho_inf).map(|(next, mid, iters)| {
                self.newton_iterations += iters;
                let turns = |x: &X| [x[0], x[1]];
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
/// own α-point) and after every accepted step with the state and the
/// α-point of that step; returns the final state and the number of steps.
pub fn integrate(
    m: &CompliantModel,
    s: CState,
    integ: &mut CompliantIntegrator,
    t_end: f64,
    record: impl FnMut(&CState, &CState) -> Result<(), SolverError>,
) -> Result<(CState, usize), SolverError> {
    run_until(s, |s| s.t, t_end, |s| integ.step(m, s, t_end), record)
}
