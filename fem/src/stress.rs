//! Stresses of a displacement field: per element from the strain, recovered
//! at the nodes by averaging, and their principal values.
//!
//! Hooke's law for an isotropic body,
//!
//!   σ = λ tr(ε) I + 2 μ ε,
//!
//! with ε = sym(∇u) of the element's quadratic displacement ([`tet10::strain`]):
//! linear in each straight-sided element, so its value at a node is the
//! element's own field there (no extrapolation from Gauss points needed).
//! Nodal recovery: the volume-weighted mean of the values of the elements
//! that hold the node. Where the exact stress is linear (pure bending) every
//! element reproduces it and so does the mean; elsewhere the mean removes
//! the jumps between elements to the order of the mesh's stress error.

use crate::{tet10, Material, TetMesh};

/// Symmetric stress in Voigt order [σxx, σyy, σzz, σyz, σxz, σxy], Pa.
pub type Stress = [f64; 6];

/// σ = λ tr(ε) I + 2 μ ε for a strain tensor ε.
pub fn hooke(eps: [[f64; 3]; 3], lambda: f64, mu: f64) -> Stress {
    let tr = eps[0][0] + eps[1][1] + eps[2][2];
    [
        lambda * tr + 2.0 * mu * eps[0][0],
        lambda * tr + 2.0 * mu * eps[1][1],
        lambda * tr + 2.0 * mu * eps[2][2],
        2.0 * mu * eps[1][2],
        2.0 * mu * eps[0][2],
        2.0 * mu * eps[0][1],
    ]
}

/// The stress of element `e` at its reference point `xi` for the nodal
/// displacements `u` (3 per mesh node).
pub fn element_stress(
    mesh: &TetMesh,
    material: &Material,
    u: &[f64],
    e: usize,
    xi: [f64; 3],
) -> Stress {
    let x = mesh.element(e);
    let ue = mesh.tets[e].map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
    let (lambda, mu) = material.lame();
    hooke(tet10::strain(&x, &ue, xi), lambda, mu)
}

/// Recovered stress at every node: the volume-weighted mean over the
/// elements holding the node of each element's stress at that node
/// (nodes of no element get zeros).
pub fn nodal_stress(mesh: &TetMesh, material: &Material, u: &[f64]) -> Vec<Stress> {
    let refs = tet10::reference_nodes();
    let mut sum = vec![[0.0; 6]; mesh.nodes.len()];
    let mut weight = vec![0.0; mesh.nodes.len()];
    for (e, tet) in mesh.tets.iter().enumerate() {
        let v = tet10::volume(&mesh.element(e)).abs();
        for (l, &n) in tet.iter().enumerate() {
            let s = element_stress(mesh, material, u, e, refs[l]);
            for c in 0..6 {
                sum[n][c] += v * s[c];
            }
            weight[n] += v;
        }
    }
    sum.iter()
        .zip(&weight)
        .map(|(s, &w)| if w > 0.0 { s.map(|c| c / w) } else { [0.0; 6] })
        .collect()
}

/// One stress component as a linear functional of the nodal
/// displacements: (global dof 3·node + direction, coefficient) pairs, each
/// dof once.
pub type Functional = Vec<(usize, f64)>;

/// The recovered stress at each of `nodes` ([`nodal_stress`]) as six
/// linear functionals of u, so that Σ c u[dof] over row k is component k
/// of `nodal_stress(u)` at that node, for every u. An element holding the
/// node contributes its stress there, σ(ξ_l) = Σ_a,i hooke(sym(e_i ⊗ ∇N_a))
/// u_ai, weighted by its share of the holding elements' volume. With a
/// factor's forward solves, gᵀ K⁻¹ f = (L⁻¹ P g) · (L⁻¹ P f): a stress
/// at a node per unit load without solving for the whole field.
pub fn nodal_stress_functionals(
    mesh: &TetMesh,
    material: &Material,
    nodes: &[usize],
) -> Vec<[Functional; 6]> {
    let at: std::collections::HashMap<usize, usize> =
        nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
    let refs = tet10::reference_nodes();
    let (lambda, mu) = material.lame();
    let mut rows: Vec<[Functional; 6]> = vec![Default::default(); nodes.len()];
    let mut weight = vec![0.0; nodes.len()];
    for (e, tet) in mesh.tets.iter().enumerate() {
        let holds: Vec<(usize, usize)> = tet
            .iter()
            .enumerate()
            .filter_map(|(l, n)| at.get(n).map(|&k| (l, k)))
            .collect();
        if holds.is_empty() {
            continue;
        }
        let x = mesh.element(e);
        let v = tet10::volume(&x).abs();
        for (l, k) in holds {
            weight[k] += v;
            for (a, &node) in tet.iter().enumerate() {
                for i in 0..3 {
                    let mut unit = [[0.0; 3]; 10];
                    unit[a][i] = 1.0;
                    let s = hooke(tet10::strain(&x, &unit, refs[l]), lambda, mu);
                    for c in 0..6 {
                        rows[k][c].push((3 * node + i, v * s[c]));
                    }
                }
            }
        }
    }
    for (row, w) in rows.iter_mut().zip(&weight) {
        for f in row.iter_mut() {
            f.sort_by_key(|&(d, _)| d);
            let mut merged: Functional = Vec::with_capacity(f.len());
            for &(d, c) in f.iter() {
                match merged.last_mut() {
                    Some((last, sum)) if *last == d => *sum += c,
                    _ => merged.push((d, c)),
                }
            }
            for (_, c) in merged.iter_mut() {
                *c /= w;
            }
            *f = merged;
        }
    }
    rows
}

/// The recovered stress ([`nodal_stress`]) at a few nodes only, from the
/// displacements of the elements that hold them: what a body whose field
/// is known only where asked for (pruned backward solves) needs. Built
/// once per node set; [`NodalStressAt::support`] names the nodes whose
/// displacements [`NodalStressAt::eval`] reads.
#[derive(Debug, Clone)]
pub struct NodalStressAt {
    nodes: Vec<usize>,
    /// Per node: (element, the node's local index in it, element volume).
    holders: Vec<Vec<(usize, usize, f64)>>,
}

impl NodalStressAt {
    /// The holding elements of each of `nodes` in `mesh`.
    pub fn new(mesh: &TetMesh, nodes: &[usize]) -> NodalStressAt {
        let at: std::collections::HashMap<usize, usize> =
            nodes.iter().enumerate().map(|(k, &n)| (n, k)).collect();
        let mut holders = vec![Vec::new(); nodes.len()];
        for (e, tet) in mesh.tets.iter().enumerate() {
            for (l, n) in tet.iter().enumerate() {
                if let Some(&k) = at.get(n) {
                    holders[k].push((e, l, tet10::volume(&mesh.element(e)).abs()));
                }
            }
        }
        NodalStressAt {
            nodes: nodes.to_vec(),
            holders,
        }
    }

    /// The nodes asked for, in their order.
    pub fn nodes(&self) -> &[usize] {
        &self.nodes
    }

    /// The distinct nodes of every holding element, ascending.
    pub fn support(&self, mesh: &TetMesh) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .holders
            .iter()
            .flatten()
            .flat_map(|&(e, _, _)| mesh.tets[e])
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// The recovered stress at each node, `u(n)` the displacement of
    /// support node n (zeros for a node of no element).
    pub fn eval(
        &self,
        mesh: &TetMesh,
        material: &Material,
        u: impl Fn(usize) -> [f64; 3],
    ) -> Vec<Stress> {
        let refs = tet10::reference_nodes();
        let (lambda, mu) = material.lame();
        self.holders
            .iter()
            .map(|hs| {
                let mut sum = [0.0; 6];
                let mut w = 0.0;
                for &(e, l, v) in hs {
                    let ue = mesh.tets[e].map(&u);
                    let s = hooke(tet10::strain(&mesh.element(e), &ue, refs[l]), lambda, mu);
                    for c in 0..6 {
                        sum[c] += v * s[c];
                    }
                    w += v;
                }
                if w > 0.0 {
                    sum.map(|c| c / w)
                } else {
                    [0.0; 6]
                }
            })
            .collect()
    }
}

/// Principal stresses σ₁ ≥ σ₂ ≥ σ₃ (eigenvalues of the stress tensor).
pub fn principal(s: Stress) -> [f64; 3] {
    let m = nalgebra::Matrix3::new(s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]);
    let mut ev: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
    ev.sort_by(|a, b| b.total_cmp(a));
    [ev[0], ev[1], ev[2]]
}

/// Von Mises equivalent stress √(½[(σxx−σyy)² + (σyy−σzz)² + (σzz−σxx)²] + 3(σyz² + σxz² + σxy²)).
pub fn von_mises(s: Stress) -> f64 {
    (0.5 * ((s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2))
        + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A uniaxial stress σ and a pure shear τ: principal values (σ, 0, 0)
    /// and (τ, 0, −τ); von Mises σ and √3 τ.
    #[test]
    fn principal_and_von_mises_of_uniaxial_stress_and_pure_shear() {
        let p = principal([5.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((p[0] - 5.0).abs() < 1e-12 && p[1].abs() < 1e-12 && p[2].abs() < 1e-12);
        let q = principal([0.0, 0.0, 0.0, 0.0, 0.0, 2.0]);
        assert!((q[0] - 2.0).abs() < 1e-12 && q[1].abs() < 1e-12 && (q[2] + 2.0).abs() < 1e-12);
        assert!((von_mises([5.0, 0.0, 0.0, 0.0, 0.0, 0.0]) - 5.0).abs() < 1e-12);
        assert!((von_mises([0.0, 0.0, 0.0, 0.0, 0.0, 2.0]) - 2.0 * 3f64.sqrt()).abs() < 1e-12);
    }

    /// Hooke's law under uniaxial stress: the strain (σ/E, −νσ/E, −νσ/E)
    /// gives back (σ, 0, 0).
    #[test]
    fn hooke_gives_back_uniaxial_stress_from_its_strain() {
        let m = Material::STEEL;
        let (e, nu) = (m.youngs_modulus_pa, m.poisson_ratio);
        let (l, mu) = m.lame();
        let sigma = 100e6;
        let eps = [
            [sigma / e, 0.0, 0.0],
            [0.0, -nu * sigma / e, 0.0],
            [0.0, 0.0, -nu * sigma / e],
        ];
        let s = hooke(eps, l, mu);
        assert!((s[0] - sigma).abs() < 1e-6 * sigma);
        for (c, v) in s.iter().enumerate().skip(1) {
            assert!(v.abs() < 1e-6 * sigma, "component {c}: {v}");
        }
    }
}
