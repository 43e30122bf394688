//! A supernodal factor kept on some dofs' paths ([`PathFactor`]), with the
//! forward solves of unit loads and the backward solves at a few dofs.

use super::tree::raw_supernodal;
use super::{PathVec, Tree, NONE};
use crate::{Factor, FemError};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::{Accum, MatRef, Par};
use rayon::prelude::*;

/// Compact storage of whole supernodes: supernode → first row.
struct Compact {
    off: Vec<u32>,
    rows: usize,
}

impl Compact {
    fn new(sym: &SymbolicSupernodalCholesky<usize>, sns: &[u32]) -> Compact {
        let mut off = vec![NONE; sym.n_supernodes()];
        let mut rows = 0;
        for &s in sns {
            off[s as usize] = rows as u32;
            rows += sym.supernode_end()[s as usize] - sym.supernode_begin()[s as usize];
        }
        Compact { off, rows }
    }

    /// Compact index of permuted row `r` of supernode `s`.
    fn at(&self, sn_of: &[u32], begin: &[usize], r: usize) -> usize {
        let s = sn_of[r] as usize;
        self.off[s] as usize + r - begin[s]
    }
}

/// A supernodal Cholesky factor kept only on the elimination-tree paths of
/// some dofs, for the pruned solves that start there.
pub struct PathFactor {
    symbolic: faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
    tree: Tree,
    /// Supernode → start of its values in `values` ([`usize::MAX`]: dropped).
    offset: Vec<usize>,
    values: Vec<f64>,
    /// Stored values of the whole factor.
    full_nnz: usize,
}

impl PathFactor {
    /// Keeps the supernodes of `factor` (from [`Factor::new_supernodal`]) on
    /// the paths of the free dofs `dofs`, and drops the rest.
    pub fn new(factor: Factor, dofs: &[usize]) -> Result<PathFactor, FemError> {
        let tree = Tree::new(&factor)?;
        let keep = tree.paths(dofs);
        let full_nnz = factor.values.len();
        let Factor {
            symbolic,
            mut values,
        } = factor;
        let sym = raw_supernodal(&symbolic)?;
        let cp = sym.col_ptr_for_val();
        let mut offset = vec![usize::MAX; sym.n_supernodes()];
        // Compacted in place (kept supernodes ascending, so every block moves
        // towards the front): no second copy of the factor at any time.
        let mut at = 0;
        for &s in &keep {
            let s = s as usize;
            offset[s] = at;
            values.copy_within(cp[s]..cp[s + 1], at);
            at += cp[s + 1] - cp[s];
        }
        values.truncate(at);
        values.shrink_to_fit();
        Ok(PathFactor {
            symbolic,
            tree,
            offset,
            values,
            full_nnz,
        })
    }

    /// The supernodal tree.
    pub fn tree(&self) -> &Tree {
        &self.tree
    }

    /// Values kept, and those of the whole factor.
    pub fn nnz(&self) -> (usize, usize) {
        (self.values.len(), self.full_nnz)
    }

    fn sym(&self) -> &SymbolicSupernodalCholesky<usize> {
        raw_supernodal(&self.symbolic).expect("checked in PathFactor::new")
    }

    /// Errors unless the paths of `dofs` lie in the kept supernodes.
    fn check(&self, dofs: impl Iterator<Item = usize>) -> Result<(), FemError> {
        for d in dofs {
            if self.offset[self.tree.supernode_of(d) as usize] == usize::MAX {
                return Err(FemError::Factorization(format!(
                    "dof {d} lies off the paths this factor keeps"
                )));
            }
        }
        Ok(())
    }

    /// y = L⁻¹ P e_d for unit loads at free dofs, `ncols` per group (None:
    /// a zero column), each group's columns on the union of its dofs' paths.
    /// Groups are solved `block` at a time (blocks in parallel), each block
    /// over the union of its groups' paths; at each supernode only the
    /// columns whose path passes through it are carried. Groups are best
    /// given in the order of their supernodes, so that a block's paths share
    /// most of their length.
    pub fn forward_units<const K: usize>(
        &self,
        groups: &[[Option<usize>; K]],
        block: usize,
    ) -> Result<Vec<PathVec>, FemError> {
        let cols: Vec<Vec<(usize, f64)>> = groups
            .iter()
            .flatten()
            .map(|d| d.iter().map(|&d| (d, 1.0)).collect())
            .collect();
        self.forward(K, &cols, block)
    }

    /// y = L⁻¹ P f for sparse loads f given as (free dof, value) pairs (a
    /// dof may repeat; its values add): one single-column [`PathVec`] per
    /// load, on the union of its dofs' paths. Solved `block` loads at a
    /// time like [`PathFactor::forward_units`]; loads are best given in
    /// the order of their supernodes.
    pub fn forward_sparse(
        &self,
        loads: &[Vec<(usize, f64)>],
        block: usize,
    ) -> Result<Vec<PathVec>, FemError> {
        self.forward(1, loads, block)
    }

    /// Forward solves of `cols`, `k` consecutive columns per group.
    fn forward(
        &self,
        k: usize,
        cols: &[Vec<(usize, f64)>],
        block: usize,
    ) -> Result<Vec<PathVec>, FemError> {
        self.check(cols.iter().flatten().map(|&(d, _)| d))?;
        let (tree, sym) = (&self.tree, self.sym());
        let out: Vec<Vec<PathVec>> = cols
            .par_chunks(k * block.max(1))
            .map(|chunk| self.forward_block(sym, tree, k, chunk))
            .collect();
        Ok(out.into_iter().flatten().collect())
    }

    fn forward_block(
        &self,
        sym: &SymbolicSupernodalCholesky<usize>,
        tree: &Tree,
        kk: usize,
        cols: &[Vec<(usize, f64)>],
    ) -> Vec<PathVec> {
        let begin = sym.supernode_begin();
        let paths: Vec<Vec<u32>> = cols
            .chunks(kk)
            .map(|g| tree.paths(&g.iter().flatten().map(|&(d, _)| d).collect::<Vec<_>>()))
            .collect();
        let mut all: Vec<u32> = paths.iter().flatten().copied().collect();
        all.sort_unstable();
        all.dedup();
        let cmp = Compact::new(sym, &all);
        let k = cols.len();
        let rows = cmp.rows;
        // Column-major rows × k.
        let mut x = vec![0.0; rows * k];
        for (c, col) in cols.iter().enumerate() {
            for &(d, v) in col {
                let r = cmp.at(&tree.sn_of, begin, tree.inv[d]);
                x[c * rows + r] += v;
            }
        }
        // Groups whose path passes through each supernode of `all`.
        let mut through: Vec<Vec<u32>> = vec![Vec::new(); all.len()];
        for (g, p) in paths.iter().enumerate() {
            for s in p {
                let at = all.partition_point(|t| t < s);
                through[at].push(g as u32);
            }
        }
        let mut tmp: Vec<f64> = Vec::new();
        let mut upd: Vec<f64> = Vec::new();
        for (at, &s) in all.iter().enumerate() {
            let gs = &through[at];
            if gs.is_empty() {
                continue;
            }
            let sn = self.supernode_values(sym, s as usize);
            let w = sn.ncols();
            let pattern = sym.supernode(s as usize).pattern();
            let kc = kk * gs.len();
            let o = cmp.off[s as usize] as usize;
            // Gather the carried columns, solve with the diagonal block.
            tmp.clear();
            tmp.resize(w * kc, 0.0);
            for (c, &g) in gs.iter().enumerate() {
                for q in 0..kk {
                    let col = (kk * g as usize + q) * rows + o;
                    tmp[(kk * c + q) * w..(kk * c + q + 1) * w].copy_from_slice(&x[col..col + w]);
                }
            }
            let (top, bot) = sn.split_at_row(w);
            let mut t = faer::MatMut::from_column_major_slice_mut(&mut tmp, w, kc);
            solve_lower_triangular_in_place(top, t.as_mut(), Par::Seq);
            for (c, &g) in gs.iter().enumerate() {
                for q in 0..kk {
                    let col = (kk * g as usize + q) * rows + o;
                    x[col..col + w].copy_from_slice(&tmp[(kk * c + q) * w..(kk * c + q + 1) * w]);
                }
            }
            let p = pattern.len();
            if p == 0 {
                continue;
            }
            upd.clear();
            upd.resize(p * kc, 0.0);
            let mut u = faer::MatMut::from_column_major_slice_mut(&mut upd, p, kc);
            let t = MatRef::from_column_major_slice(&tmp, w, kc);
            matmul(u.as_mut(), Accum::Replace, bot, t, 1.0, Par::Seq);
            let dst: Vec<usize> = pattern
                .iter()
                .map(|&r| cmp.at(&tree.sn_of, begin, r))
                .collect();
            for (c, &g) in gs.iter().enumerate() {
                for q in 0..kk {
                    let col = (kk * g as usize + q) * rows;
                    let src = &upd[(kk * c + q) * p..(kk * c + q + 1) * p];
                    for (&r, v) in dst.iter().zip(src) {
                        x[col + r] -= v;
                    }
                }
            }
        }
        paths
            .into_iter()
            .enumerate()
            .map(|(g, sn)| {
                let mut ptr = Vec::with_capacity(sn.len() + 1);
                ptr.push(0);
                let mut val = Vec::new();
                for &s in &sn {
                    let (b, e) = (begin[s as usize], sym.supernode_end()[s as usize]);
                    let o = cmp.off[s as usize] as usize;
                    for r in 0..e - b {
                        for q in 0..kk {
                            val.push(x[(kk * g + q) * rows + o + r]);
                        }
                    }
                    ptr.push(ptr.last().copied().unwrap_or(0) + e - b);
                }
                PathVec {
                    sn,
                    ptr,
                    ncols: kk,
                    val,
                }
            })
            .collect()
    }

    fn supernode_values<'a>(
        &'a self,
        sym: &SymbolicSupernodalCholesky<usize>,
        s: usize,
    ) -> MatRef<'a, f64> {
        let w = sym.supernode_end()[s] - sym.supernode_begin()[s];
        let p = sym.supernode(s).pattern().len();
        let o = self.offset[s];
        MatRef::from_column_major_slice(&self.values[o..o + (w + p) * w], w + p, w)
    }

    /// x = L⁻ᵀ z for each single-column `z` (= L⁻¹ P f, e.g. a [`combine`]
    /// of unit-load vectors), evaluated at the free dofs `dofs` only:
    /// `out[j][i]` = (K⁻¹ f_j) at `dofs[i]`. The backward solve runs over
    /// the supernodes on the paths of `dofs` alone.
    pub fn backward_at(&self, z: &[&PathVec], dofs: &[usize]) -> Result<Vec<Vec<f64>>, FemError> {
        self.check(dofs.iter().copied())?;
        let (tree, sym) = (&self.tree, self.sym());
        let begin = sym.supernode_begin();
        let need = tree.paths(dofs);
        let cmp = Compact::new(sym, &need);
        let (rows, k) = (cmp.rows, z.len());
        let mut x = vec![0.0; rows * k];
        for (j, v) in z.iter().enumerate() {
            for (q, &s) in v.sn.iter().enumerate() {
                let o = cmp.off[s as usize];
                if o != NONE {
                    let o = o as usize;
                    let w = v.ptr[q + 1] - v.ptr[q];
                    x[j * rows + o..j * rows + o + w]
                        .copy_from_slice(&v.val[v.ptr[q]..v.ptr[q + 1]]);
                }
            }
        }
        let mut gat: Vec<f64> = Vec::new();
        let mut tmp: Vec<f64> = Vec::new();
        for &s in need.iter().rev() {
            let sn = self.supernode_values(sym, s as usize);
            let w = sn.ncols();
            let pattern = sym.supernode(s as usize).pattern();
            let o = cmp.off[s as usize] as usize;
            let (top, bot) = sn.split_at_row(w);
            tmp.clear();
            tmp.resize(w * k, 0.0);
            for j in 0..k {
                tmp[j * w..(j + 1) * w].copy_from_slice(&x[j * rows + o..j * rows + o + w]);
            }
            let mut t = faer::MatMut::from_column_major_slice_mut(&mut tmp, w, k);
            let p = pattern.len();
            if p > 0 {
                let src: Vec<usize> = pattern
                    .iter()
                    .map(|&r| cmp.at(&tree.sn_of, begin, r))
                    .collect();
                gat.clear();
                for j in 0..k {
                    gat.extend(src.iter().map(|&r| x[j * rows + r]));
                }
                let g = MatRef::from_column_major_slice(&gat, p, k);
                matmul(t.as_mut(), Accum::Add, bot.transpose(), g, -1.0, Par::Seq);
            }
            solve_upper_triangular_in_place(top.transpose(), t.as_mut(), Par::Seq);
            for j in 0..k {
                x[j * rows + o..j * rows + o + w].copy_from_slice(&tmp[j * w..(j + 1) * w]);
            }
        }
        Ok((0..k)
            .map(|j| {
                dofs.iter()
                    .map(|&d| x[j * rows + cmp.at(&tree.sn_of, begin, tree.inv[d])])
                    .collect()
            })
            .collect())
    }
}
