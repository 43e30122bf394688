//! Fill-reducing nested-dissection ordering by METIS on the node graph.
//!
//! The three dofs of a node share their sparsity, so METIS orders the node
//! graph (nine times fewer edges) and each node's dofs stay together.

use crate::FemError;
use faer::sparse::SparseColMat;
use std::sync::Mutex;

/// One ordering at a time: METIS's support library (GKlib) traps SIGTERM
/// and SIGABRT around each ordering and puts back the handlers it found;
/// two orderings at once on two threads would each put back what the
/// other had installed, leaving GKlib's handler in place after both.
static ORDERING: Mutex<()> = Mutex::new(());

/// Forward permutation (new position → free dof) for the lower-triangle
/// matrix `k`; `node_of[i]` is the node of free dof i, nondecreasing in i.
pub fn nested_dissection(
    k: &SparseColMat<usize, f64>,
    node_of: &[usize],
) -> Result<Vec<usize>, FemError> {
    let n = k.ncols();
    assert_eq!(node_of.len(), n);
    // Compressed node numbering: group g = run of equal node_of.
    let mut group = vec![0usize; n];
    let mut first = Vec::new();
    for i in 0..n {
        if i == 0 || node_of[i] != node_of[i - 1] {
            first.push(i);
        }
        group[i] = first.len() - 1;
    }
    let ng = first.len();
    let mut adj: Vec<Vec<i32>> = vec![Vec::new(); ng];
    let (cp, ri) = (k.col_ptr(), k.row_idx());
    for (g, &j) in first.iter().enumerate() {
        for &i in &ri[cp[j]..cp[j + 1]] {
            let h = group[i];
            if h != g {
                adj[g].push(h as i32);
                adj[h].push(g as i32);
            }
        }
    }
    let mut xadj = Vec::with_capacity(ng + 1);
    let mut adjncy = Vec::new();
    xadj.push(0i32);
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
        adjncy.extend_from_slice(a);
        let len = i32::try_from(adjncy.len())
            .map_err(|_| FemError::Ordering("graph too large for 32-bit METIS".into()))?;
        xadj.push(len);
    }
    drop(adj);
    let mut nv = ng as i32;
    let mut perm = vec![0i32; ng];
    let mut iperm = vec![0i32; ng];
    let one_at_a_time = ORDERING.lock().unwrap_or_else(|e| e.into_inner());
    // SAFETY: xadj/adjncy form a valid CSR graph of `ng` vertices; perm and
    // iperm have `ng` entries; null weights and options select METIS defaults.
    let status = unsafe {
        metis_sys::METIS_NodeND(
            &mut nv,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            perm.as_mut_ptr(),
            iperm.as_mut_ptr(),
        )
    };
    drop(one_at_a_time);
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(FemError::Ordering(format!(
            "METIS_NodeND returned {status}"
        )));
    }
    let mut fwd = Vec::with_capacity(n);
    for &g in &perm {
        let g = g as usize;
        let end = if g + 1 < ng { first[g + 1] } else { n };
        fwd.extend(first[g]..end);
    }
    Ok(fwd)
}
