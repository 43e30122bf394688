//! One elastic body's compliance at its contact nodes from pruned solves on
//! its Cholesky factor (`fem::path_solve`): the stiffness (supports
//! clamped) is factored once, supernodal; a node that a contact loads gets
//! Y = L⁻¹ P [e_x e_y e_z] along its elimination-tree path, kept while the
//! sweep uses it ([`PathCompliance::retain`] drops the rest: each tooth
//! engages once per sweep, so this is a sliding window).
//!
//! A constraint c's share on this body is the vector y_c = Σ_i Y_i v_ci
//! (its terms' directions), and the condensed compliance between two
//! constraints is W_cd = Σ_b y_cbᵀ y_db ([`fem::path_solve::gram`]). The
//! displacements under a set of constraint forces λ are the backward solve
//! of z = Σ_c λ_c y_c, evaluated on the paths of the nodes asked for only.
//! This is the same C = K⁻¹ as [`crate::reference::body_compliance`]'s full solves,
//! without their backward half or responses kept over every flank node.

use crate::reference::penalty::{ContactError, Term};
use fem::path_solve::{combine, PathFactor, PathVec};
use fem::{ClampedBody, Dofs, Factorization, Material, TetMesh};
use std::collections::{HashMap, HashSet};

/// A factored body and the unit-load vectors of the nodes in use.
pub struct PathCompliance {
    factor: PathFactor,
    dofs: Dofs,
    /// Node → Y (three columns: unit loads along x, y, z).
    y: HashMap<usize, PathVec>,
    /// Nodes per forward block.
    block: usize,
    /// Right-hand sides solved so far.
    pub solves: usize,
    /// Seconds spent factoring and in forward solves.
    pub factor_s: f64,
    pub solve_s: f64,
    pub dofs_free: usize,
    /// Values of the factor L kept (on the paths of the contact nodes) and
    /// of the whole factor (8 bytes each).
    pub factor_nnz: [usize; 2],
    /// Largest memory the kept vectors held, bytes.
    pub peak_bytes: usize,
    bytes: usize,
}

impl PathCompliance {
    /// Assembles and factors the body with the `fixed` dofs (3 · node +
    /// component) held at zero, and keeps the factor on the paths of the
    /// `kept` nodes only (every node a constraint can name, and the nodes
    /// whose displacements are asked for: the fillets' support). Forward
    /// solves run `block` right-hand sides (a third as many nodes) per block.
    pub fn new(
        mesh: &TetMesh,
        material: &Material,
        fixed: &[usize],
        kept: &[usize],
        block: usize,
    ) -> Result<PathCompliance, ContactError> {
        let t = std::time::Instant::now();
        let ClampedBody { dofs, factor, .. } =
            ClampedBody::new(mesh, material, fixed, Factorization::Supernodal)?;
        let keep: Vec<usize> = kept
            .iter()
            .flat_map(|&n| {
                let dofs = &dofs;
                (0..3).filter_map(move |c| dofs.free_index(3 * n + c))
            })
            .collect();
        let factor = PathFactor::new(factor, &keep)?;
        let (kept, full) = factor.nnz();
        Ok(PathCompliance {
            factor_nnz: [kept, full],
            factor,
            dofs_free: dofs.n_free(),
            dofs,
            y: HashMap::new(),
            block: block.div_ceil(3).max(1),
            solves: 0,
            factor_s: t.elapsed().as_secs_f64(),
            solve_s: 0.0,
            peak_bytes: 0,
            bytes: 0,
        })
    }

    fn free(&self, node: usize) -> [Option<usize>; 3] {
        [0, 1, 2].map(|c| self.dofs.free_index(3 * node + c))
    }

    /// Nodes with unit-load vectors.
    pub fn computed(&self) -> usize {
        self.y.len()
    }

    /// Bytes the kept vectors hold now.
    pub fn bytes(&self) -> usize {
        self.bytes
    }

    /// Computes the vectors of the listed nodes that are missing, in blocks
    /// of nodes that are neighbours in the elimination tree.
    pub fn ensure(&mut self, nodes: &[usize]) -> Result<(), ContactError> {
        let mut todo =
            crate::reference::body_compliance::missing(nodes, |n| self.y.contains_key(&n));
        if todo.is_empty() {
            return Ok(());
        }
        let t = std::time::Instant::now();
        let tree = self.factor.tree();
        let key = |n: usize| {
            self.free(n)
                .iter()
                .flatten()
                .map(|&d| tree.supernode_of(d))
                .min()
                .unwrap_or(u32::MAX)
        };
        todo.sort_by_key(|&n| (key(n), n));
        let groups: Vec<[Option<usize>; 3]> = todo.iter().map(|&n| self.free(n)).collect();
        let ys = self.factor.forward_units(&groups, self.block)?;
        self.solves += 3 * todo.len();
        for (n, y) in todo.into_iter().zip(ys) {
            self.bytes += y.bytes();
            self.y.insert(n, y);
        }
        self.peak_bytes = self.peak_bytes.max(self.bytes);
        self.solve_s += t.elapsed().as_secs_f64();
        Ok(())
    }

    /// Keeps the vectors of the nodes in `keep` only.
    pub fn retain(&mut self, keep: &HashSet<usize>) {
        self.y.retain(|n, _| keep.contains(n));
        self.bytes = self.y.values().map(PathVec::bytes).sum();
    }

    /// y_c = Σ_i Y_i v_ci over the `terms` on body `body`.
    pub fn constraint_vector(&self, terms: &[Term], body: usize) -> Result<PathVec, ContactError> {
        let parts: Vec<(&PathVec, &[f64])> = terms
            .iter()
            .filter(|t| t.body == body)
            .map(|t| {
                self.y
                    .get(&t.node)
                    .map(|y| (y, &t.dir[..]))
                    .ok_or(ContactError::MissingColumn { node: t.node })
            })
            .collect::<Result<_, _>>()?;
        Ok(combine(&parts))
    }

    /// The displacements (m) at `nodes` under each load z_j = L⁻¹ P f_j
    /// (e.g. [`combine`]d constraint vectors weighted by their forces):
    /// `out[j][i]` at `nodes[i]`; clamped dofs give zero.
    pub fn displacements(
        &self,
        z: &[&PathVec],
        nodes: &[usize],
    ) -> Result<Vec<Vec<[f64; 3]>>, ContactError> {
        let free: Vec<[Option<usize>; 3]> = nodes.iter().map(|&n| self.free(n)).collect();
        let dofs: Vec<usize> = free.iter().flatten().flatten().copied().collect();
        let x = self.factor.backward_at(z, &dofs)?;
        Ok(x.into_iter()
            .map(|xj| {
                let mut at = 0;
                free.iter()
                    .map(|f| {
                        f.map(|d| {
                            d.map_or(0.0, |_| {
                                at += 1;
                                xj[at - 1]
                            })
                        })
                    })
                    .collect()
            })
            .collect())
    }
}
