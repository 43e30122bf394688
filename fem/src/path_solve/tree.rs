//! The supernodal elimination tree of a factor, read off faer's patterns.

use super::NONE;
use crate::{Factor, FemError};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;

/// The supernodal elimination tree of a factor.
#[derive(Debug, Clone)]
pub struct Tree {
    /// Permuted row → its supernode.
    pub(super) sn_of: Vec<u32>,
    /// Supernode → parent supernode ([`u32::MAX`] at a root).
    parent: Vec<u32>,
    /// Old (unpermuted) index → permuted row.
    pub(super) inv: Vec<usize>,
}

impl Tree {
    pub(super) fn new(f: &Factor) -> Result<Tree, FemError> {
        let sym = supernodal(f)?;
        let n = sym.nrows();
        let ns = sym.n_supernodes();
        let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
        let mut sn_of = vec![0u32; n];
        for s in 0..ns {
            sn_of[begin[s]..end[s]].fill(s as u32);
        }
        let parent = (0..ns)
            .map(|s| {
                sym.supernode(s)
                    .pattern()
                    .first()
                    .map_or(NONE, |&r| sn_of[r])
            })
            .collect();
        let inv = match f.symbolic.perm() {
            Some(p) => p.arrays().1.to_vec(),
            None => (0..n).collect(),
        };
        Ok(Tree { sn_of, parent, inv })
    }

    /// The supernode of (unpermuted) dof `d`.
    pub fn supernode_of(&self, d: usize) -> u32 {
        self.sn_of[self.inv[d]]
    }

    /// Supernodes on the paths from those of `dofs` to the root, ascending
    /// (every supernode's ancestors included).
    pub fn paths(&self, dofs: &[usize]) -> Vec<u32> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for &d in dofs {
            let mut s = self.supernode_of(d);
            while s != NONE && seen.insert(s) {
                out.push(s);
                s = self.parent[s as usize];
            }
        }
        out.sort_unstable();
        out
    }
}

fn supernodal(f: &Factor) -> Result<&SymbolicSupernodalCholesky<usize>, FemError> {
    raw_supernodal(&f.symbolic)
}

pub(super) fn raw_supernodal(
    s: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
) -> Result<&SymbolicSupernodalCholesky<usize>, FemError> {
    match s.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => Ok(s),
        SymbolicCholeskyRaw::Simplicial(_) => Err(FemError::Factorization(
            "pruned solves need a supernodal factor (Factor::new_supernodal)".into(),
        )),
    }
}
