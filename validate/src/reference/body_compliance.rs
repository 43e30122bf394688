//! One elastic body's compliance at its contact nodes by full solves: the
//! stiffness (supports clamped) is factored once; unit loads at a node (x, y,
//! z of the body's own frame) are solved (forward and backward) in column
//! blocks when a contact first needs that node, and the responses are kept
//! at every node of a fixed "universe".
//!
//! The reference sweeps use [`crate::reference::path_compliance`] (pruned forward
//! solves, the same C at about a hundredth of the cost); this
//! straightforward form stays as the independent check it is compared with
//! (`validate/tests/penalty_contact.rs`, `make bench`).

use crate::reference::penalty::{Compliance, ContactError};
use fem::{ClampedBody, Dofs, Factor, Factorization, Material, TetMesh};
use std::collections::HashMap;

/// A factored body and the columns computed so far.
pub struct BodyCompliance {
    factor: Factor,
    dofs: Dofs,
    slot: HashMap<usize, usize>,
    universe: usize,
    /// Node → its three columns, each restricted to the universe (3 per node).
    columns: HashMap<usize, Vec<f64>>,
    block: usize,
    /// Right-hand sides solved so far.
    pub solves: usize,
    /// Seconds spent factoring and solving.
    pub factor_s: f64,
    pub solve_s: f64,
    pub dofs_free: usize,
}

/// The distinct nodes of `nodes` that are not `known`, ascending.
pub(crate) fn missing(nodes: &[usize], known: impl Fn(usize) -> bool) -> Vec<usize> {
    let mut todo: Vec<usize> = nodes.iter().copied().filter(|&n| !known(n)).collect();
    todo.sort_unstable();
    todo.dedup();
    todo
}

pub use fem::clamp_nodes as clamped;

impl BodyCompliance {
    /// Assembles and factors the body with the `fixed` dofs (3 · node +
    /// component) held at zero; responses are kept at the `universe` nodes.
    /// Column blocks of `block` right-hand sides are solved two at a time.
    pub fn new(
        mesh: &TetMesh,
        material: &Material,
        fixed: &[usize],
        universe: &[usize],
        block: usize,
    ) -> Result<BodyCompliance, ContactError> {
        let t = std::time::Instant::now();
        let ClampedBody { dofs, factor, .. } =
            ClampedBody::new(mesh, material, fixed, Factorization::Auto)?;
        Ok(BodyCompliance {
            factor,
            dofs_free: dofs.n_free(),
            dofs,
            slot: universe.iter().enumerate().map(|(i, &n)| (n, i)).collect(),
            universe: universe.len(),
            columns: HashMap::new(),
            block: block.max(1),
            solves: 0,
            factor_s: t.elapsed().as_secs_f64(),
            solve_s: 0.0,
        })
    }

    /// Whether `node`'s columns are available.
    pub fn has(&self, node: usize) -> bool {
        self.columns.contains_key(&node)
    }

    /// Nodes with columns.
    pub fn computed(&self) -> usize {
        self.columns.len()
    }

    /// Computes the columns of the listed nodes that are missing.
    pub fn ensure(&mut self, nodes: &[usize]) -> Result<(), ContactError> {
        let todo = missing(nodes, |n| self.columns.contains_key(&n));
        if todo.is_empty() {
            return Ok(());
        }
        let t = std::time::Instant::now();
        let n = self.dofs.n_free();
        let per = 2 * self.block;
        for chunk in todo.chunks(per.div_ceil(3)) {
            let k = 3 * chunk.len();
            let mut rhs = vec![0.0; n * k];
            for (a, &node) in chunk.iter().enumerate() {
                for c in 0..3 {
                    if let Some(f) = self.dofs.free_index(3 * node + c) {
                        rhs[(3 * a + c) * n + f] = 1.0;
                    }
                }
            }
            self.factor.solve_many(&mut rhs, self.block);
            self.solves += k;
            for (a, &node) in chunk.iter().enumerate() {
                let mut col = vec![0.0; 3 * 3 * self.universe];
                for c in 0..3 {
                    let u = &rhs[(3 * a + c) * n..(3 * a + c + 1) * n];
                    for (&un, &s) in &self.slot {
                        for d in 0..3 {
                            if let Some(f) = self.dofs.free_index(3 * un + d) {
                                col[c * 3 * self.universe + 3 * s + d] = u[f];
                            }
                        }
                    }
                }
                self.columns.insert(node, col);
            }
        }
        self.solve_s += t.elapsed().as_secs_f64();
        Ok(())
    }
}

impl Compliance for BodyCompliance {
    fn block(&self, i: usize, j: usize) -> Result<[[f64; 3]; 3], ContactError> {
        let col = self
            .columns
            .get(&j)
            .ok_or(ContactError::MissingColumn { node: j })?;
        let s = *self
            .slot
            .get(&i)
            .ok_or(ContactError::MissingColumn { node: i })?;
        let u = self.universe;
        let mut m = [[0.0; 3]; 3];
        for (a, row) in m.iter_mut().enumerate() {
            for (b, v) in row.iter_mut().enumerate() {
                *v = col[b * 3 * u + 3 * s + a];
            }
        }
        Ok(m)
    }

    fn slots(&self, nodes: &[usize]) -> Result<Vec<usize>, ContactError> {
        nodes
            .iter()
            .map(|n| {
                self.slot
                    .get(n)
                    .copied()
                    .ok_or(ContactError::MissingColumn { node: *n })
            })
            .collect()
    }

    fn response(
        &self,
        j: usize,
        dir: [f64; 3],
        slots: &[usize],
    ) -> Result<Vec<[f64; 3]>, ContactError> {
        let col = self
            .columns
            .get(&j)
            .ok_or(ContactError::MissingColumn { node: j })?;
        let u3 = 3 * self.universe;
        Ok(slots
            .iter()
            .map(|&s| {
                [0, 1, 2].map(|a| {
                    dir[0] * col[3 * s + a]
                        + dir[1] * col[u3 + 3 * s + a]
                        + dir[2] * col[2 * u3 + 3 * s + a]
                })
            })
            .collect())
    }
}
