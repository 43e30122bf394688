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
            if i >= n_nodes || on_interface[i] || (0..3).any(|c| fixed_set.contains(&(3 * i + c))) {
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

    // Constraint modes.
    let mut shapes: Vec<Vec<f64>> = Vec::new();
    for itf in interfaces {
        for c in 0..6 {
            let v = rigid_field(mesh, &itf.nodes, itf.reference, c);
            let f = full.expand(&sym_lower_mul(&k, &full.restrict(&v)));
            let rhs: Vec<f64> = interior.restrict(&f).iter().map(|x| -x).collect();
            let psi = interior.expand(&factor.solve(&rhs));
            shapes.push(v.iter().zip(&psi).map(|(a, b)| a + b).collect());
        }
    }
    // Fixed-interface modes on the same factor (σ = 0).
    let fixed_modes = if modes > 0 {
        lowest_modes_factored(&factor, &m_ii, modes, 0.0)?
    } else {
        crate::modes::Modes {
            omega2: Vec::new(),
            shapes: Vec::new(),
            steps: 0,
        }
    };
    shapes.extend(fixed_modes.shapes.iter().map(|p| interior.expand(p)));

    // Reduced matrices Tᵀ K T, Tᵀ M T.
    let t: Vec<Vec<f64>> = shapes.iter().map(|s| full.restrict(s)).collect();
    let kt: Vec<Vec<f64>> = t.iter().map(|x| sym_lower_mul(&k, x)).collect();
    let mt: Vec<Vec<f64>> = t.iter().map(|x| sym_lower_mul(&m, x)).collect();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let r = t.len();
    let stiffness = DMatrix::from_fn(r, r, |i, j| 0.5 * (dot(&t[i], &kt[j]) + dot(&t[j], &kt[i])));
    let mass = DMatrix::from_fn(r, r, |i, j| 0.5 * (dot(&t[i], &mt[j]) + dot(&t[j], &mt[i])));
    Ok(CraigBampton {
        stiffness,
        mass,
        fixed_interface_omega2: fixed_modes.omega2,
        shapes,
    })
}
