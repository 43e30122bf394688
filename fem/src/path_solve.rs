//! Pruned triangular solves on a supernodal Cholesky factor L Lᵀ = P K Pᵀ.
//!
//! The compliance between two dofs is
//!
//!   C_ij = e_iᵀ K⁻¹ e_j = (L⁻¹ P e_i)ᵀ (L⁻¹ P e_j) = y_iᵀ y_j,
//!
//! and y_j = L⁻¹ P e_j is nonzero only on the supernodes of the elimination
//! tree's path from the supernode holding row (P e_j) to the root. So a
//! unit load needs only the forward half of a solve, and only along its path
//! ([`Factor::forward_units`]); a compliance is a dot product over the part
//! two paths share ([`gram`]). A displacement field u = K⁻¹ f is wanted at a
//! few dofs only: with z = L⁻¹ P f known on its paths, u at a dof needs the
//! backward solve x = L⁻ᵀ z on the path of that dof alone
//! ([`Factor::backward_at`]: a supernode's rows of x depend only on z there
//! and on x at its ancestors).
//!
//! A supernode's parent is the supernode holding the first row of its
//! off-diagonal pattern (faer does not expose the tree; its patterns give it).
//! Vectors on whole supernodes are [`PathVec`]s.
//!
//! Solves that start at a given set of dofs (a body's contact nodes) never
//! read the supernodes off their paths, so [`PathFactor`] keeps only those
//! of L's values (a supernodal factor of a gear body whose contact teeth are
//! a few of many keeps a fraction of them).

use crate::{Factor, FemError};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;
use faer::{Accum, Mat, MatRef, Par};
use rayon::prelude::*;

const NONE: u32 = u32::MAX;

/// The supernodal elimination tree of a factor.
#[derive(Debug, Clone)]
pub struct Tree {
    /// Permuted row → its supernode.
    sn_of: Vec<u32>,
    /// Supernode → parent supernode ([`u32::MAX`] at a root).
    parent: Vec<u32>,
    /// Old (unpermuted) index → permuted row.
    inv: Vec<usize>,
}

impl Tree {
    fn new(f: &Factor) -> Result<Tree, FemError> {
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

fn raw_supernodal(
    s: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
) -> Result<&SymbolicSupernodalCholesky<usize>, FemError> {
    match s.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => Ok(s),
        SymbolicCholeskyRaw::Simplicial(_) => Err(FemError::Factorization(
            "pruned solves need a supernodal factor (Factor::new_supernodal)".into(),
        )),
    }
}

/// A vector (or `ncols` vectors) in the factor's permuted row space,
/// nonzero only on whole supernodes `sn` (ascending): supernode `sn[k]`'s
/// rows are `val[ptr[k] · ncols ..ptr[k + 1] · ncols]`, row-major.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PathVec {
    pub sn: Vec<u32>,
    pub ptr: Vec<usize>,
    pub ncols: usize,
    pub val: Vec<f64>,
}

impl PathVec {
    /// Rows stored.
    pub fn rows(&self) -> usize {
        self.ptr.last().copied().unwrap_or(0)
    }

    /// Bytes held.
    pub fn bytes(&self) -> usize {
        self.val.len() * 8 + self.sn.len() * 4 + self.ptr.len() * 8
    }
}

/// Σ_k vₖ wₖ for vectors vₖ of `ncols` columns and weights wₖ (one per
/// column): one column on the union of their supernodes.
pub fn combine(parts: &[(&PathVec, &[f64])]) -> PathVec {
    let mut sn: Vec<(u32, usize)> = parts
        .iter()
        .flat_map(|(v, _)| {
            v.sn.iter()
                .enumerate()
                .map(|(k, &s)| (s, v.ptr[k + 1] - v.ptr[k]))
        })
        .collect();
    sn.sort_unstable();
    sn.dedup();
    let mut ptr = Vec::with_capacity(sn.len() + 1);
    ptr.push(0);
    for &(_, w) in &sn {
        ptr.push(ptr.last().copied().unwrap_or(0) + w);
    }
    let mut val = vec![0.0; *ptr.last().unwrap_or(&0)];
    for (v, w) in parts {
        debug_assert_eq!(w.len(), v.ncols);
        let mut at = 0;
        for (k, &s) in v.sn.iter().enumerate() {
            while sn[at].0 != s {
                at += 1;
            }
            let dst = &mut val[ptr[at]..ptr[at + 1]];
            let src = &v.val[v.ptr[k] * v.ncols..v.ptr[k + 1] * v.ncols];
            for (r, x) in dst.iter_mut().enumerate() {
                let row = &src[r * v.ncols..(r + 1) * v.ncols];
                *x += row.iter().zip(w.iter()).map(|(a, b)| a * b).sum::<f64>();
            }
        }
    }
    PathVec {
        sn: sn.into_iter().map(|(s, _)| s).collect(),
        ptr,
        ncols: 1,
        val,
    }
}

/// Dot products below which a supernode's share of [`gram`] is summed
/// directly rather than through a matrix product.
const DIRECT_FLOPS: usize = 2048;

/// G = Aᵀ B for single-column vectors: G[i][j] = aᵢ · bⱼ over the
/// supernodes they share, row-major `a.len() × b.len()`. Per supernode the
/// vectors that have it are gathered into dense blocks and multiplied.
/// Deterministic: each row of G is summed by one thread in supernode order.
pub fn gram(a: &[&PathVec], b: &[&PathVec]) -> Vec<f64> {
    let (na, nb) = (a.len(), b.len());
    let mut g = vec![0.0; na * nb];
    if na == 0 || nb == 0 {
        return g;
    }
    // (supernode, vector, offset) of B, sorted by supernode.
    let mut eb: Vec<(u32, u32, usize)> = b
        .iter()
        .enumerate()
        .flat_map(|(j, v)| {
            debug_assert_eq!(v.ncols, 1);
            v.sn.iter()
                .zip(&v.ptr)
                .map(move |(&s, &p)| (s, j as u32, p))
        })
        .collect();
    eb.sort_unstable();
    let threads = rayon::current_num_threads().max(1);
    let rows_per = na.div_ceil(4 * threads).max(1);
    g.par_chunks_mut(rows_per * nb)
        .enumerate()
        .for_each(|(chunk, out)| {
            let i0 = chunk * rows_per;
            let rows = out.len() / nb;
            let mut ea: Vec<(u32, u32, usize)> = (i0..i0 + rows)
                .flat_map(|i| {
                    let v = a[i];
                    v.sn.iter()
                        .zip(&v.ptr)
                        .map(move |(&s, &p)| (s, (i - i0) as u32, p))
                })
                .collect();
            ea.sort_unstable();
            let (mut x, mut y) = (0, 0);
            while x < ea.len() && y < eb.len() {
                let s = ea[x].0;
                match s.cmp(&eb[y].0) {
                    std::cmp::Ordering::Less => {
                        x = ea[x..].partition_point(|e| e.0 == s) + x;
                        continue;
                    }
                    std::cmp::Ordering::Greater => {
                        let t = eb[y].0;
                        y = eb[y..].partition_point(|e| e.0 == t) + y;
                        continue;
                    }
                    std::cmp::Ordering::Equal => {}
                }
                let xe = ea[x..].partition_point(|e| e.0 == s) + x;
                let ye = eb[y..].partition_point(|e| e.0 == s) + y;
                let (ga, gb) = (&ea[x..xe], &eb[y..ye]);
                let (i_any, p_any) = (ga[0].1 as usize, ga[0].2);
                let v_any = a[i0 + i_any];
                let k = v_any.sn.partition_point(|&t| t < s);
                let w = v_any.ptr[k + 1] - p_any;
                if ga.len() * gb.len() * w <= DIRECT_FLOPS {
                    for &(_, i, pa) in ga {
                        let va = &a[i0 + i as usize].val[pa..pa + w];
                        let row = &mut out[i as usize * nb..(i as usize + 1) * nb];
                        for &(_, j, pb) in gb {
                            let vb = &b[j as usize].val[pb..pb + w];
                            row[j as usize] += va.iter().zip(vb).map(|(p, q)| p * q).sum::<f64>();
                        }
                    }
                } else {
                    let za = Mat::<f64>::from_fn(w, ga.len(), |r, c| {
                        let (_, i, pa) = ga[c];
                        a[i0 + i as usize].val[pa + r]
                    });
                    let zb = Mat::<f64>::from_fn(w, gb.len(), |r, c| {
                        let (_, j, pb) = gb[c];
                        b[j as usize].val[pb + r]
                    });
                    let mut prod = Mat::<f64>::zeros(ga.len(), gb.len());
                    matmul(
                        prod.as_mut(),
                        Accum::Replace,
                        za.transpose(),
                        zb.as_ref(),
                        1.0,
                        Par::Seq,
                    );
                    for (c, &(_, i, _)) in ga.iter().enumerate() {
                        let row = &mut out[i as usize * nb..(i as usize + 1) * nb];
                        for (d, &(_, j, _)) in gb.iter().enumerate() {
                            row[j as usize] += prod[(c, d)];
                        }
                    }
                }
                x = xe;
                y = ye;
            }
        });
    g
}

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
        self.check(groups.iter().flatten().flatten().copied())?;
        let (tree, sym) = (&self.tree, self.sym());
        let out: Vec<Vec<PathVec>> = groups
            .par_chunks(block.max(1))
            .map(|chunk| self.forward_block(sym, tree, chunk))
            .collect();
        Ok(out.into_iter().flatten().collect())
    }

    fn forward_block<const K: usize>(
        &self,
        sym: &SymbolicSupernodalCholesky<usize>,
        tree: &Tree,
        groups: &[[Option<usize>; K]],
    ) -> Vec<PathVec> {
        let begin = sym.supernode_begin();
        let paths: Vec<Vec<u32>> = groups
            .iter()
            .map(|g| tree.paths(&g.iter().flatten().copied().collect::<Vec<_>>()))
            .collect();
        let mut all: Vec<u32> = paths.iter().flatten().copied().collect();
        all.sort_unstable();
        all.dedup();
        let cmp = Compact::new(sym, &all);
        let k = K * groups.len();
        let rows = cmp.rows;
        // Column-major rows × k.
        let mut x = vec![0.0; rows * k];
        for (g, dofs) in groups.iter().enumerate() {
            for (c, d) in dofs.iter().enumerate() {
                if let Some(d) = d {
                    let r = cmp.at(&tree.sn_of, begin, tree.inv[*d]);
                    x[(K * g + c) * rows + r] = 1.0;
                }
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
            let kc = K * gs.len();
            let o = cmp.off[s as usize] as usize;
            // Gather the carried columns, solve with the diagonal block.
            tmp.clear();
            tmp.resize(w * kc, 0.0);
            for (c, &g) in gs.iter().enumerate() {
                for q in 0..K {
                    let col = (K * g as usize + q) * rows + o;
                    tmp[(K * c + q) * w..(K * c + q + 1) * w].copy_from_slice(&x[col..col + w]);
                }
            }
            let (top, bot) = sn.split_at_row(w);
            let mut t = faer::MatMut::from_column_major_slice_mut(&mut tmp, w, kc);
            solve_lower_triangular_in_place(top, t.as_mut(), Par::Seq);
            for (c, &g) in gs.iter().enumerate() {
                for q in 0..K {
                    let col = (K * g as usize + q) * rows + o;
                    x[col..col + w].copy_from_slice(&tmp[(K * c + q) * w..(K * c + q + 1) * w]);
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
                for q in 0..K {
                    let col = (K * g as usize + q) * rows;
                    let src = &upd[(K * c + q) * p..(K * c + q + 1) * p];
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
                        for q in 0..K {
                            val.push(x[(K * g + q) * rows + o + r]);
                        }
                    }
                    ptr.push(ptr.last().copied().unwrap_or(0) + e - b);
                }
                PathVec {
                    sn,
                    ptr,
                    ncols: K,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cholesky::Ordering;
    use crate::structured::mapped_block;
    use crate::{assemble, Dofs, Material};

    fn body() -> (Factor, PathFactor, Dofs) {
        let b = mapped_block([3, 2, 4], |p| [p[0] * 0.03, p[1] * 0.02, p[2] * 0.04]);
        let fixed: Vec<(usize, f64)> = (0..b.mesh.nodes.len())
            .filter(|&n| b.mesh.nodes[n][2] < 1e-12)
            .flat_map(|n| (0..3).map(move |c| (3 * n + c, 0.0)))
            .collect();
        let dofs = Dofs::new(&b.mesh, &fixed).unwrap();
        let mat = Material {
            youngs_modulus_pa: 2.1e11,
            poisson_ratio: 0.3,
        };
        let sys = assemble(&b.mesh, &mat, &dofs).unwrap();
        let f = Factor::new_supernodal(&sys.matrix, &dofs.node_of_free(), Ordering::Metis).unwrap();
        let all: Vec<usize> = (0..dofs.n_free()).collect();
        let p = PathFactor::new(
            Factor::new_supernodal(&sys.matrix, &dofs.node_of_free(), Ordering::Metis).unwrap(),
            &all,
        )
        .unwrap();
        (f, p, dofs)
    }

    /// y_iᵀ y_j from pruned forward solves equals K⁻¹ from full solves.
    #[test]
    fn pruned_forward_solves_reproduce_the_inverse_stiffness() {
        let (f, pf, dofs) = body();
        let n = dofs.n_free();
        let picks: Vec<usize> = (0..n).step_by(7).collect();
        let groups: Vec<[Option<usize>; 1]> = picks.iter().map(|&d| [Some(d)]).collect();
        let y = pf.forward_units(&groups, 5).unwrap();
        let refs: Vec<&PathVec> = y.iter().collect();
        let g = gram(&refs, &refs);
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for (a, &i) in picks.iter().enumerate() {
            let mut e = vec![0.0; n];
            e[i] = 1.0;
            let x = f.solve(&e);
            for (b, &j) in picks.iter().enumerate() {
                worst = worst.max((g[a * picks.len() + b] - x[j]).abs());
                scale = scale.max(x[j].abs());
            }
        }
        assert!(worst <= 1e-12 * scale, "worst {worst:e}, scale {scale:e}");
        // Paths are shorter than the whole factor.
        let longest = y.iter().map(PathVec::rows).max().unwrap();
        assert!(longest < n, "a path holds {longest} of {n} rows");
    }

    /// The backward solve restricted to a few dofs' paths gives the full
    /// solve's displacements there, for a load combined from unit loads.
    #[test]
    fn backward_solve_on_paths_equals_full_solve_at_those_dofs() {
        let (f, pf, dofs) = body();
        let n = dofs.n_free();
        let loads = [(3usize, 1.5), (40, -0.7), (n - 2, 2.0)];
        let groups: Vec<[Option<usize>; 3]> = vec![
            [Some(loads[0].0), None, Some(loads[1].0)],
            [Some(loads[2].0), None, None],
        ];
        let y = pf.forward_units(&groups, 1).unwrap();
        let z = combine(&[(&y[0], &[1.5, 0.0, -0.7]), (&y[1], &[2.0, 0.0, 0.0])]);
        let at: Vec<usize> = (0..n).step_by(11).collect();
        let u = pf.backward_at(&[&z], &at).unwrap();
        let mut b = vec![0.0; n];
        for (d, v) in loads {
            b[d] += v;
        }
        let x = f.solve(&b);
        let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (k, &d) in at.iter().enumerate() {
            assert!(
                (u[0][k] - x[d]).abs() <= 1e-12 * scale,
                "dof {d}: {} vs {}",
                u[0][k],
                x[d]
            );
        }
    }

    /// A factor kept on the paths of a few dofs (one corner node's) gives
    /// the same compliances there as the whole factor, holds fewer values,
    /// and refuses a dof off its paths.
    #[test]
    fn factor_kept_on_a_few_paths_solves_those_alike_and_refuses_others() {
        let (_, whole, dofs) = body();
        let b = mapped_block([3, 2, 4], |p| [p[0] * 0.03, p[1] * 0.02, p[2] * 0.04]);
        let fixed: Vec<(usize, f64)> = (0..b.mesh.nodes.len())
            .filter(|&n| b.mesh.nodes[n][2] < 1e-12)
            .flat_map(|n| (0..3).map(move |c| (3 * n + c, 0.0)))
            .collect();
        let d2 = Dofs::new(&b.mesh, &fixed).unwrap();
        let sys = assemble(
            &b.mesh,
            &Material {
                youngs_modulus_pa: 2.1e11,
                poisson_ratio: 0.3,
            },
            &d2,
        )
        .unwrap();
        // The top corner node at the largest x and y.
        let corner = (0..b.mesh.nodes.len())
            .max_by(|&m, &n| {
                let s = |k: usize| b.mesh.nodes[k].iter().sum::<f64>();
                s(m).total_cmp(&s(n))
            })
            .unwrap();
        let few: Vec<usize> = (0..3)
            .filter_map(|c| dofs.free_index(3 * corner + c))
            .collect();
        let kept = PathFactor::new(
            Factor::new_supernodal(&sys.matrix, &d2.node_of_free(), Ordering::Metis).unwrap(),
            &few,
        )
        .unwrap();
        let (k, full) = kept.nnz();
        assert!(k < full, "kept {k} of {full}");
        let groups: Vec<[Option<usize>; 1]> = few.iter().map(|&d| [Some(d)]).collect();
        let (ya, yb) = (
            whole.forward_units(&groups, 2).unwrap(),
            kept.forward_units(&groups, 2).unwrap(),
        );
        let ga = gram(
            &ya.iter().collect::<Vec<_>>(),
            &ya.iter().collect::<Vec<_>>(),
        );
        let gb = gram(
            &yb.iter().collect::<Vec<_>>(),
            &yb.iter().collect::<Vec<_>>(),
        );
        let scale = ga.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (x, y) in ga.iter().zip(&gb) {
            assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
        }
        let on = kept.tree().paths(&few);
        let off = (0..dofs.n_free())
            .find(|&d| !on.contains(&kept.tree().supernode_of(d)))
            .expect("some dof lies off the kept paths");
        assert!(kept.forward_units(&[[Some(off)]], 1).is_err());
        assert!(kept.backward_at(&[&yb[0]], &[off]).is_err());
    }
}
