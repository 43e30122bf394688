//! Vectors on whole supernodes ([`PathVec`]), their weighted sums and their
//! Gram matrices (the compliances between unit loads).

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use rayon::prelude::*;

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
