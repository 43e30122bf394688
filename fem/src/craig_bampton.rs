//! Craig–Bampton reduction of a tet10 body onto rigid interfaces (a
//! housing's bearing seats).
//!
//! Each interface's nodes follow a reference point rigidly (the seat as a
//! rigid spider): u(x) = u_r + θ_r × (x − x_r). The body's displacement is
//! written in the reduced coordinates q = (6 per interface; modal η):
//!
//!   u = Σ_c Ψ_c q_c + Σ_k φ_k η_k,
//!
//! - constraint modes Ψ_c: interface c's rigid motion R_c e with the
//!   interior statically condensed, K_II Ψ_I = −K_IS R_c (one solve each);
//! - fixed-interface modes φ_k: the lowest of K_II φ = ω² M_II φ with every
//!   interface node held ([`crate::modes`], on the same factor of K_II).
//!
//! The reduced matrices are K_r = Tᵀ K T and M_r = Tᵀ M T over the columns
//! T = [Ψ, φ] (K and M of the body with only its `fixed` dofs held). The
//! constraint block of K_r is the Guyan (static) condensation onto the
//! reference points; K_r is block-diagonal (Ψᵀ K φ = 0, since K Ψ vanishes
//! in the interior and φ on the interfaces), with ω²_k on the modal
//! diagonal. The reduced model's frequencies bound the full constrained
//! model's from above and reach them as modes are added.

use crate::assembly::{assemble_mass, sym_lower_mul};
use crate::cholesky::Ordering;
use crate::modes::lowest_modes_factored;
use crate::{assemble, Dofs, Factor, FemError, Material, TetMesh};
use faer::sparse::SparseColMat;
use nalgebra::DMatrix;

/// One interface: nodes that move rigidly with a reference point.
#[derive(Debug, Clone)]
pub struct RigidInterface {
    /// Mesh nodes of the interface (a bearing seat's surface nodes).
    pub nodes: Vec<usize>,
    /// The reference point x_r, m.
    pub reference: [f64; 3],
}

/// A body reduced onto its interfaces' reference points and modes.
#[derive(Debug, Clone)]
pub struct CraigBampton {
    /// Reduced stiffness: 6 coordinates per interface (u_x, u_y, u_z in m,
    /// θ_x, θ_y, θ_z in rad of its reference point, in interface order),
    /// then one per fixed-interface mode.
    pub stiffness: DMatrix<f64>,
    /// Reduced mass, same coordinates.
    pub mass: DMatrix<f64>,
    /// ω² of the fixed-interface modes, ascending, rad²/s².
    pub fixed_interface_omega2: Vec<f64>,
    /// Each reduced coordinate's displacement field (3 per node): the
    /// recovery of the body's displacement from q.
    pub shapes: Vec<Vec<f64>>,
}

impl CraigBampton {
    /// Number of interface coordinates (6 per interface).
    pub fn interface_dofs(&self) -> usize {
        self.stiffness.nrows() - self.fixed_interface_omega2.len()
    }
}

/// Displacement (3 per node) of interface `nodes` under a unit value of
/// rigid coordinate `c` (0–2 translation, 3–5 rotation) about `reference`.
fn rigid_field(mesh: &TetMesh, nodes: &[usize], reference: [f64; 3], c: usize) -> Vec<f64> {
    let mut u = vec![0.0; 3 * mesh.nodes.len()];
    for &i in nodes {
        let r: [f64; 3] = std::array::from_fn(|a| mesh.nodes[i][a] - reference[a]);
        let d = match c {
            0..=2 => std::array::from_fn(|a| f64::from(u8::from(a == c))),
            // e_k × r
            3 => [0.0, -r[2], r[1]],
            4 => [r[2], 0.0, -r[0]],
            _ => [-r[1], r[0], 0.0],
        };
        u[3 * i..3 * i + 3].copy_from_slice(&d);
    }
    u
}

/// Reduces the body (`fixed` global dofs held at zero besides the
/// interfaces) onto `interfaces` and its `modes` lowest fixed-interface
/// modes.
pub fn craig_bampton(
    mesh: &TetMesh,
    material: &Material,
    density: f64,
    fixed: &[usize],
    interfaces: &[RigidInterface],
    modes: usize,
) -> Result<CraigBampton, FemError> {
    Reduction::new(mesh, material, density, fixed, interfaces)?.reduce(modes)
}

/// A body ready to be reduced: K and M assembled, the interior (every
/// interface node held) factored once, the constraint modes solved. Any
/// number of fixed-interface modes ([`Reduction::reduce`]) and the whole
/// body's modes ([`Reduction::full_omega2`]) then reuse the factor.
pub struct Reduction<'a> {
    mesh: &'a TetMesh,
    interfaces: &'a [RigidInterface],
    full: Dofs,
    interior: Dofs,
    k: SparseColMat<usize, f64>,
    m: SparseColMat<usize, f64>,
    m_ii: SparseColMat<usize, f64>,
    factor: Factor,
    /// Constraint modes Ψ (3 per node), 6 per interface.
    constraint: Vec<Vec<f64>>,
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

impl<'a> Reduction<'a> {
    /// Assembles, factors K_II and solves the constraint modes.
    pub fn new(
        mesh: &'a TetMesh,
        material: &Material,
        density: f64,
        fixed: &[usize],
        interfaces: &'a [RigidInterface],
    ) -> Result<Self, FemError> {
        let n_nodes = mesh.nodes.len();
        let mut on_interface = vec![false; n_nodes];
        let fixed_set: std::collections::HashSet<usize> = fixed.iter().copied().collect();
        for (s, itf) in interfaces.iter().enumerate() {
            if itf.nodes.is_empty() {
                return Err(FemError::Invalid {
                    field: "interface nodes",
                    value: format!("interface {s}: none"),
                    limit: "each interface needs at least one node".into(),
                });
            }
            for &i in &itf.nodes {
                if i >= n_nodes
                    || on_interface[i]
                    || (0..3).any(|c| fixed_set.contains(&(3 * i + c)))
                {
                    return Err(FemError::Invalid {
                        field: "interface nodes",
                        value: format!("interface {s}: node {i}"),
                        limit: format!(
                            "must be a node of the mesh (< {n_nodes}), on one interface only, and not fixed"
                        ),
                    });
                }
                on_interface[i] = true;
            }
        }
        let held: Vec<(usize, f64)> = fixed.iter().map(|&d| (d, 0.0)).collect();
        let full = Dofs::new(mesh, &held)?;
        let k = assemble(mesh, material, &full)?.matrix;
        let m = assemble_mass(mesh, density, &full)?;
        let mut held_interior = held.clone();
        for (i, _) in on_interface.iter().enumerate().filter(|(_, &o)| o) {
            held_interior.extend((0..3).map(|c| (3 * i + c, 0.0)));
        }
        let interior = Dofs::new(mesh, &held_interior)?;
        let k_ii = assemble(mesh, material, &interior)?.matrix;
        let m_ii = assemble_mass(mesh, density, &interior)?;
        let factor = Factor::new(&k_ii, &interior.node_of_free(), Ordering::Metis)?;
        let mut constraint: Vec<Vec<f64>> = Vec::new();
        for itf in interfaces {
            for c in 0..6 {
                let v = rigid_field(mesh, &itf.nodes, itf.reference, c);
                let f = full.expand(&sym_lower_mul(&k, &full.restrict(&v)));
                let rhs: Vec<f64> = interior.restrict(&f).iter().map(|x| -x).collect();
                let psi = interior.expand(&factor.solve(&rhs));
                constraint.push(v.iter().zip(&psi).map(|(a, b)| a + b).collect());
            }
        }
        Ok(Reduction {
            mesh,
            interfaces,
            full,
            interior,
            k,
            m,
            m_ii,
            factor,
            constraint,
        })
    }

    /// Tᵀ A T over `shapes` (symmetrized).
    fn project(&self, a: &SparseColMat<usize, f64>, shapes: &[Vec<f64>]) -> DMatrix<f64> {
        let t: Vec<Vec<f64>> = shapes.iter().map(|s| self.full.restrict(s)).collect();
        let at: Vec<Vec<f64>> = t.iter().map(|x| sym_lower_mul(a, x)).collect();
        let r = t.len();
        DMatrix::from_fn(r, r, |i, j| 0.5 * (dot(&t[i], &at[j]) + dot(&t[j], &at[i])))
    }

    /// The reduced model with the `modes` lowest fixed-interface modes.
    pub fn reduce(&self, modes: usize) -> Result<CraigBampton, FemError> {
        // Fixed-interface modes on the same factor (σ = 0).
        let fixed_modes = if modes > 0 {
            lowest_modes_factored(&self.factor, &self.m_ii, modes, 0.0)?
        } else {
            crate::modes::Modes {
                omega2: Vec::new(),
                shapes: Vec::new(),
                steps: 0,
            }
        };
        let mut shapes = self.constraint.clone();
        shapes.extend(fixed_modes.shapes.iter().map(|p| self.interior.expand(p)));
        Ok(CraigBampton {
            stiffness: self.project(&self.k, &shapes),
            mass: self.project(&self.m, &shapes),
            fixed_interface_omega2: fixed_modes.omega2,
            shapes,
        })
    }

    /// The `count` lowest ω² of the whole body with its interfaces rigid
    /// and free (no modal truncation): the reduced model's yardstick. Its
    /// coordinates are y = (u_I, q), the interior dofs and the interfaces'
    /// rigid motions, u = E_I u_I + R q, K̃ = Tᵀ K T, M̃ = Tᵀ M T
    /// (T = [E_I, R]). Eliminating u_I,
    ///
    ///   q = S⁻¹ (f_q + ψᵀ f_I),  u_I = K_II⁻¹ f_I + ψ q,
    ///
    /// with ψ the constraint modes' interior part and S = Ψᵀ K Ψ the Guyan
    /// block, so K̃⁻¹ costs one solve on the factor of K_II; Lanczos
    /// ([`crate::modes::lowest_modes_operator`]) runs on that.
    pub fn full_omega2(&self, count: usize) -> Result<Vec<f64>, FemError> {
        let nc = self.constraint.len();
        let ni = self.interior.n_free();
        let psi: Vec<Vec<f64>> = self
            .constraint
            .iter()
            .map(|s| self.interior.restrict(s))
            .collect();
        let rigid: Vec<Vec<f64>> = self
            .interfaces
            .iter()
            .flat_map(|itf| (0..6).map(|c| rigid_field(self.mesh, &itf.nodes, itf.reference, c)))
            .collect();
        let s_inv = self
            .project(&self.k, &self.constraint)
            .cholesky()
            .ok_or_else(|| FemError::Invalid {
                field: "interfaces",
                value: format!("{} interfaces", self.interfaces.len()),
                limit: "the body's fixed dofs must stop its rigid motion".into(),
            })?;
        let solve = |f: &[f64]| -> Vec<f64> {
            let (f_i, f_q) = f.split_at(ni);
            let g = nalgebra::DVector::from_fn(nc, |c, _| f_q[c] + dot(&psi[c], f_i));
            let q = s_inv.solve(&g);
            let mut out = self.factor.solve(f_i);
            for (c, p) in psi.iter().enumerate() {
                out.iter_mut().zip(p).for_each(|(x, y)| *x += q[c] * y);
            }
            out.extend(q.iter());
            out
        };
        let mass = |y: &[f64]| -> Vec<f64> {
            let (u_i, q) = y.split_at(ni);
            let mut u = self.interior.expand(u_i);
            for (c, rf) in rigid.iter().enumerate() {
                u.iter_mut().zip(rf).for_each(|(x, v)| *x += q[c] * v);
            }
            let g = self
                .full
                .expand(&sym_lower_mul(&self.m, &self.full.restrict(&u)));
            let mut out = self.interior.restrict(&g);
            out.extend(rigid.iter().map(|rf| dot(rf, &g)));
            out
        };
        Ok(crate::modes::lowest_modes_operator(ni + nc, solve, mass, count, 0.0)?.omega2)
    }
}
