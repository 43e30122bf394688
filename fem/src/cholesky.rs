//! Factor once, solve many: faer's sparse Cholesky (supernodal when it pays)
//! with a METIS nested-dissection ordering.

use crate::{ordering, FemError};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SparseColMat;
use faer::{Conj, MatMut, Par, Side};
use rayon::prelude::*;

/// Fill-reducing ordering of the factorization.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordering {
    /// METIS nested dissection on the node graph (default).
    Metis,
    /// faer's approximate minimum degree.
    Amd,
}

/// Memory the system can give this process now (`MemAvailable` of
/// `/proc/meminfo`), bytes; `None` where that is not known.
pub fn available_memory_bytes() -> Option<usize> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Refuses a factor of `dofs` rows that needs `needed` bytes when only
/// `available` are free (no check when that is unknown): an error with the
/// estimate instead of the operating system killing the run part way.
pub fn fits_in_memory(
    dofs: usize,
    needed: usize,
    available: Option<usize>,
) -> Result<(), FemError> {
    match available {
        Some(a) if needed > a => Err(FemError::OutOfMemory {
            dofs,
            needed_gb: needed as f64 / 1e9,
            available_gb: a as f64 / 1e9,
        }),
        _ => Ok(()),
    }
}

/// A Cholesky factor L Lᵀ = P K Pᵀ of a symmetric positive definite matrix.
pub struct Factor {
    pub(crate) symbolic: SymbolicCholesky<usize>,
    pub(crate) values: Vec<f64>,
}

impl Factor {
    /// Factors the symmetric matrix `k` given by its lower triangle.
    /// `node_of[i]` (free dof → node, nondecreasing) lets METIS order nodes.
    pub fn new(
        k: &SparseColMat<usize, f64>,
        node_of: &[usize],
        ordering: Ordering,
    ) -> Result<Factor, FemError> {
        Factor::new_with(k, node_of, ordering, SupernodalThreshold::AUTO)
    }

    /// As [`Factor::new`], always supernodal: for the pruned solves of
    /// [`crate::path_solve::PathFactor`].
    pub fn new_supernodal(
        k: &SparseColMat<usize, f64>,
        node_of: &[usize],
        ordering: Ordering,
    ) -> Result<Factor, FemError> {
        Factor::new_with(k, node_of, ordering, SupernodalThreshold::FORCE_SUPERNODAL)
    }

    fn new_with(
        k: &SparseColMat<usize, f64>,
        node_of: &[usize],
        ordering: Ordering,
        threshold: SupernodalThreshold,
    ) -> Result<Factor, FemError> {
        let n = k.ncols();
        let (fwd, mut inv);
        let ord = match ordering {
            Ordering::Amd => SymmetricOrdering::Amd,
            Ordering::Metis => {
                fwd = ordering::nested_dissection(k, node_of)?;
                inv = vec![0usize; n];
                for (new, &old) in fwd.iter().enumerate() {
                    inv[old] = new;
                }
                SymmetricOrdering::Custom(PermRef::new_checked(&fwd, &inv, n))
            }
        };
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: threshold,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(k.symbolic(), Side::Lower, ord, params)
            .map_err(|e| FemError::Factorization(format!("{e:?}")))?;
        let par = Par::rayon(0);
        let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        fits_in_memory(
            n,
            symbolic.len_val() * std::mem::size_of::<f64>() + scratch.size_bytes(),
            available_memory_bytes(),
        )?;
        let mut values = vec![0.0; symbolic.len_val()];
        let mut mem = MemBuffer::try_new(scratch)
            .map_err(|e| FemError::Factorization(format!("scratch memory: {e:?}")))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                k.as_ref(),
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| FemError::NotPositiveDefinite(format!("{e:?}")))?;
        Ok(Factor { symbolic, values })
    }

    /// Number of rows.
    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Number of stored values of L.
    pub fn factor_nnz(&self) -> usize {
        self.values.len()
    }

    /// Solves K X = B in place for a column-major block (n × k), sequentially.
    pub fn solve_block(&self, rhs: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let par = Par::Seq;
        let mut mem = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), par),
        );
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
    }

    /// Solves K xⱼ = bⱼ for many right-hand sides stored column after column
    /// in `rhs` (n values each), in blocks of `block` columns solved in
    /// parallel, each block sequentially.
    pub fn solve_many(&self, rhs: &mut [f64], block: usize) {
        let n = self.n();
        assert_eq!(rhs.len() % n.max(1), 0);
        let k = rhs.len() / n.max(1);
        if k == 0 {
            return;
        }
        // Blocks of at most `block` columns, as many as a multiple of the
        // threads and as even as possible: 15 columns on two threads are
        // 8 + 7, not 15 on one thread while the other waits.
        let threads = rayon::current_num_threads().max(1);
        let blocks = k.div_ceil(block.max(1)).div_ceil(threads) * threads;
        let width = k.div_ceil(blocks.min(k));
        rhs.par_chunks_mut(n * width).for_each(|chunk| {
            let k = chunk.len() / n;
            let m = faer::MatMut::from_column_major_slice_mut(chunk, n, k);
            self.solve_block(m);
        });
    }

    /// Solves K x = b for one right-hand side.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut x = b.to_vec();
        let n = self.n();
        self.solve_block(faer::MatMut::from_column_major_slice_mut(&mut x, n, 1));
        x
    }
}

#[cfg(test)]
mod memory_tests {
    use super::*;

    #[test]
    fn factor_larger_than_the_free_memory_is_refused_with_its_estimate() {
        let e = fits_in_memory(1_348_188, 7_890_000_000, Some(4_000_000_000)).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("7.89 GB") && m.contains("4.00 GB") && m.contains("1348188"),
            "{m}"
        );
        assert!(fits_in_memory(10, 1000, Some(2000)).is_ok());
        assert!(fits_in_memory(10, usize::MAX, None).is_ok());
        assert!(available_memory_bytes().is_some_and(|b| b > 0));
    }
}
