//! The total influence blocks C_pq = w_pᵀ K⁻¹ w_q of a body, by one of two
//! solve paths over the same Cholesky factor K = L Lᵀ:
//!
//! - [`Solves::Pruned`] (the default): y_p = L⁻¹ P w_p by forward solves
//!   along the elimination-tree paths of w_p's dofs only, and
//!   C_pq = y_pᵀ y_q as Gram products ([`fem::path_solve`]); no backward
//!   solve. One forward vector per grid point of every tooth that loads or
//!   responds, each solved once however many loaded teeth it responds to.
//! - [`Solves::Full`]: u_p = K⁻¹ w_p by full forward and backward solves,
//!   C_pq = w_qᵀ u_p gathered from the whole field.
//!
//! The two differ only by rounding; the pruned path also checks itself
//! against a backward solve (one grid point per loaded tooth, see
//! [`InfluenceStats::backward_check`]).

use super::root::RootTargets;
use super::{gather, InfluenceError, InfluenceRequest, InfluenceStats, Weights};
use fem::path_solve::{gram, PathFactor, PathVec};
use fem::{Dofs, Factor};
use std::collections::BTreeMap;
use std::time::Instant;

/// How the unit-load fields are solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Solves {
    /// Forward solves along elimination-tree paths and Gram products.
    #[default]
    Pruned,
    /// Full forward and backward solves per unit load (the slower path the
    /// pruned one is checked against).
    Full,
}

impl Solves {
    /// The factorization each path needs (pruned solves read the
    /// supernodal tree).
    pub fn factorization(self) -> fem::Factorization {
        match self {
            Solves::Pruned => fem::Factorization::Supernodal,
            Solves::Full => fem::Factorization::Auto,
        }
    }
}

/// The teeth loaded (`solved`) and responding (`solved + offsets`, modulo z).
pub(super) fn tooth_of(req: &InfluenceRequest, k: usize, o: i32) -> usize {
    (k as i64 + o as i64).rem_euclid(req.teeth as i64) as usize
}

fn free(w: &Weights, dofs: &Dofs) -> Vec<(usize, f64)> {
    w.iter()
        .filter_map(|&(d, c)| dofs.free_index(d).map(|f| (f, c)))
        .collect()
}

/// `total[s][o][i][q]` by full solves, `req.block` right-hand sides at a time.
pub(super) fn full(
    req: &InfluenceRequest,
    dofs: &Dofs,
    factor: &Factor,
    weights: &BTreeMap<usize, Vec<Weights>>,
    stats: &mut InfluenceStats,
    targets: &mut Option<RootTargets>,
) -> Vec<f64> {
    let (np, no, ns) = (req.grid.len(), req.offsets.len(), req.solved_teeth.len());
    let mut total = vec![0.0; ns * no * np * np];
    let n = dofs.n_free();
    let batch = (2 * req.block).max(1);
    let t = Instant::now();
    for (s, &k) in req.solved_teeth.iter().enumerate() {
        let wk = &weights[&k];
        for start in (0..np).step_by(batch) {
            let cols: Vec<usize> = (start..(start + batch).min(np)).collect();
            let mut rhs = vec![0.0; n * cols.len()];
            for (c, &i) in cols.iter().enumerate() {
                for (f, v) in free(&wk[i], dofs) {
                    rhs[c * n + f] += v;
                }
            }
            factor.solve_many(&mut rhs, req.block);
            stats.right_hand_sides += cols.len();
            for (c, &i) in cols.iter().enumerate() {
                let u = &rhs[c * n..(c + 1) * n];
                if let Some(t) = targets.as_mut() {
                    let lap = Instant::now();
                    let at = |node: usize| {
                        [0, 1, 2].map(|d| dofs.free_index(3 * node + d).map_or(0.0, |f| u[f]))
                    };
                    t.fill(req, s, k, i, &at);
                    stats.root_stress_s += lap.elapsed().as_secs_f64();
                }
                for (oi, &o) in req.offsets.iter().enumerate() {
                    let row = ((s * no + oi) * np + i) * np;
                    for (q, w) in weights[&tooth_of(req, k, o)].iter().enumerate() {
                        total[row + q] = gather(w, dofs, u);
                    }
                }
            }
        }
    }
    stats.solve_s = t.elapsed().as_secs_f64() - stats.root_stress_s;
    total
}

/// Forward vectors of every grid point of tooth `j`, solved in the order of
/// their supernodes (neighbouring loads share most of their paths).
fn forward_tooth(
    pf: &PathFactor,
    loads: &[Vec<(usize, f64)>],
    block: usize,
) -> Result<Vec<PathVec>, InfluenceError> {
    let mut order: Vec<usize> = (0..loads.len()).collect();
    let key = |l: &[(usize, f64)]| l.iter().map(|&(d, _)| pf.tree().supernode_of(d)).min();
    order.sort_by_key(|&i| key(&loads[i]));
    let sorted: Vec<Vec<(usize, f64)>> = order.iter().map(|&i| loads[i].clone()).collect();
    let y = pf.forward_sparse(&sorted, block)?;
    let mut out = vec![PathVec::default(); loads.len()];
    for (y, &i) in y.into_iter().zip(&order) {
        out[i] = y;
    }
    Ok(out)
}

/// `total[s][o][i][q]` by pruned forward solves and Gram products. Each
/// tooth's forward vectors are kept while a loaded tooth still to come
/// responds on it, then dropped.
pub(super) fn pruned(
    req: &InfluenceRequest,
    dofs: &Dofs,
    factor: Factor,
    weights: &BTreeMap<usize, Vec<Weights>>,
    stats: &mut InfluenceStats,
    targets: &mut Option<RootTargets>,
) -> Result<Vec<f64>, InfluenceError> {
    let (np, no, ns) = (req.grid.len(), req.offsets.len(), req.solved_teeth.len());
    // Every tooth's loads on the free dofs, once.
    let loads: BTreeMap<usize, Vec<Vec<(usize, f64)>>> = weights
        .iter()
        .map(|(&j, w)| (j, w.iter().map(|w| free(w, dofs)).collect()))
        .collect();
    let mut keep: Vec<usize> = loads
        .values()
        .flatten()
        .flatten()
        .map(|&(f, _)| f)
        .collect();
    if let Some(t) = targets.as_ref() {
        keep.extend(
            t.support_nodes(None)
                .iter()
                .flat_map(|&n| (0..3).filter_map(move |c| dofs.free_index(3 * n + c))),
        );
    }
    keep.sort_unstable();
    keep.dedup();
    let pf = PathFactor::new(factor, &keep)?;
    let mut uses: BTreeMap<usize, usize> = BTreeMap::new();
    for &k in &req.solved_teeth {
        for &o in &req.offsets {
            *uses.entry(tooth_of(req, k, o)).or_default() += 1;
        }
    }
    let mut held: BTreeMap<usize, Vec<PathVec>> = BTreeMap::new();
    let mut total = vec![0.0; ns * no * np * np];
    let (mut forward_s, mut gram_s, mut check) = (0.0, 0.0, 0.0f64);
    for (s, &k) in req.solved_teeth.iter().enumerate() {
        let t = Instant::now();
        for &o in &req.offsets {
            let j = tooth_of(req, k, o);
            if let std::collections::btree_map::Entry::Vacant(e) = held.entry(j) {
                e.insert(forward_tooth(&pf, &loads[&j], req.block)?);
                stats.right_hand_sides += np;
            }
        }
        let bytes: usize = held.values().flatten().map(PathVec::bytes).sum();
        stats.path_vectors_gb = stats.path_vectors_gb.max(bytes as f64 / 1e9);
        forward_s += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let yk: Vec<&PathVec> = held[&k].iter().collect();
        for (oi, &o) in req.offsets.iter().enumerate() {
            let yj: Vec<&PathVec> = held[&tooth_of(req, k, o)].iter().collect();
            let g = gram(&yk, &yj);
            let at = (s * no + oi) * np * np;
            total[at..at + np * np].copy_from_slice(&g);
        }
        gram_s += t.elapsed().as_secs_f64();
        check = check.max(backward_check(req, &pf, &loads, &held, s, &total)?);
        if let Some(t) = targets.as_mut() {
            let lap = Instant::now();
            t.fill_pruned(req, &pf, dofs, s, &held[&k])?;
            stats.root_stress_s += lap.elapsed().as_secs_f64();
        }
        for &o in &req.offsets {
            let j = tooth_of(req, k, o);
            let left = uses.get_mut(&j).expect("counted above");
            *left -= 1;
            if *left == 0 {
                held.remove(&j);
            }
        }
    }
    stats.solve_s = forward_s;
    stats.gram_s = gram_s;
    stats.backward_check = Some(check);
    Ok(total)
}

/// Largest relative difference between loaded tooth `s`'s influence row of
/// its middle grid point from the Gram products and from the backward solve
/// u = L⁻ᵀ y at the responding teeth's weight dofs (gathered like the full
/// path's fields), relative to the row's largest value.
fn backward_check(
    req: &InfluenceRequest,
    pf: &PathFactor,
    loads: &BTreeMap<usize, Vec<Vec<(usize, f64)>>>,
    held: &BTreeMap<usize, Vec<PathVec>>,
    s: usize,
    total: &[f64],
) -> Result<f64, InfluenceError> {
    let (np, no) = (req.grid.len(), req.offsets.len());
    let k = req.solved_teeth[s];
    let i = np / 2;
    let mut at: Vec<usize> = req
        .offsets
        .iter()
        .flat_map(|&o| loads[&tooth_of(req, k, o)].iter().flatten())
        .map(|&(f, _)| f)
        .collect();
    at.sort_unstable();
    at.dedup();
    let u = pf.backward_at(&[&held[&k][i]], &at)?.remove(0);
    let value = |d: usize| at.binary_search(&d).map_or(0.0, |p| u[p]);
    let (mut worst, mut scale) = (0.0f64, 0.0f64);
    for (oi, &o) in req.offsets.iter().enumerate() {
        let row = &total[((s * no + oi) * np + i) * np..((s * no + oi) * np + i + 1) * np];
        for (q, w) in loads[&tooth_of(req, k, o)].iter().enumerate() {
            let approach: f64 = w.iter().map(|&(d, c)| c * value(d)).sum();
            worst = worst.max((approach - row[q]).abs());
            scale = scale.max(row[q].abs());
        }
    }
    Ok(if scale > 0.0 { worst / scale } else { worst })
}
