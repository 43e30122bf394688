//! Natural modes of an FE body: the lowest eigenpairs of K φ = ω² M φ.
//!
//! Shift-invert Lanczos with full reorthogonalization in the M inner
//! product. With a shift σ below the lowest ω², the operator
//! A = (K − σM)⁻¹ M is self-adjoint and positive in ⟨x, y⟩_M = xᵀ M y, its
//! eigenvalues θ = 1/(ω² − σ) are largest for the lowest modes, and the
//! Lanczos recurrence
//!
//!   β_j q_{j+1} = A q_j − α_j q_j − β_{j−1} q_{j−1},  α_j = ⟨q_j, A q_j⟩_M,
//!
//! builds a tridiagonal T whose eigenpairs (θᵢ, sᵢ) give Ritz pairs
//! ω²ᵢ = σ + 1/θᵢ, φᵢ = Σ_j s_{j,i} q_j with residual ‖A φᵢ − θᵢ φᵢ‖_M =
//! β_j |s_{j,i}| (the last component). A pair counts as converged when that
//! residual is below `tolerance · θᵢ`. K − σM is factored once (faer's
//! Cholesky with a METIS ordering, [`crate::Factor`]); each step is one solve.
//! A free body needs σ < 0 (its rigid modes have ω² = 0).

use crate::assembly::sym_lower_mul;
use crate::cholesky::Ordering;
use crate::{Factor, FemError};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use nalgebra::{DMatrix, SymmetricEigen};

/// The lowest natural modes of a body.
#[derive(Debug, Clone)]
pub struct Modes {
    /// ω² of each mode, ascending, rad²/s².
    pub omega2: Vec<f64>,
    /// Mode shapes on the free dofs, M-orthonormal: φᵢᵀ M φⱼ = δᵢⱼ.
    pub shapes: Vec<Vec<f64>>,
    /// Lanczos steps taken (one solve each).
    pub steps: usize,
}

impl Modes {
    /// Natural frequencies f = √ω² / 2π, Hz (0 for ω² ≤ 0, rigid modes).
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega2
            .iter()
            .map(|w| w.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect()
    }
}

/// Relative residual below which a Ritz pair counts as converged.
pub const TOLERANCE: f64 = 1e-10;

/// The `count` lowest modes of K φ = ω² M φ (both lower triangles of the
/// same pattern, as [`crate::assemble`] and [`crate::assembly::assemble_mass`]
/// give them for one [`crate::Dofs`]), `node_of` as [`Factor::new`] takes it,
/// `shift` σ (rad²/s²) below the lowest ω².
pub fn lowest_modes(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    node_of: &[usize],
    count: usize,
    shift: f64,
) -> Result<Modes, FemError> {
    let shifted = shifted_matrix(k, m, shift)?;
    let factor = match Factor::new(&shifted, node_of, Ordering::Metis) {
        Err(FemError::NotPositiveDefinite(_)) => {
            return Err(FemError::Invalid {
                field: "shift",
                value: shift.to_string(),
                limit: "must lie below the lowest ω² (K − σM is not positive definite)".into(),
            })
        }
        f => f?,
    };
    lowest_modes_factored(&factor, m, count, shift)
}

/// K − σ M of two lower triangles with the same pattern.
fn shifted_matrix(
    k: &SparseColMat<usize, f64>,
    m: &SparseColMat<usize, f64>,
    shift: f64,
) -> Result<SparseColMat<usize, f64>, FemError> {
    if k.col_ptr() != m.col_ptr() || k.row_idx() != m.row_idx() {
        return Err(FemError::Invalid {
            field: "mass matrix",
            value: format!("{} stored values", m.val().len()),
            limit: format!(
                "must have the stiffness matrix's pattern ({} stored values)",
                k.val().len()
            ),
        });
    }
    if !shift.is_finite() {
        return Err(FemError::Invalid {
            field: "shift",
            value: shift.to_string(),
            limit: "must be finite".into(),
        });
    }
    let values = k
        .val()
        .iter()
        .zip(m.val())
        .map(|(a, b)| a - shift * b)
        .collect();
    let n = k.ncols();
    let symbolic =
        SymbolicSparseColMat::new_checked(n, n, k.col_ptr().to_vec(), None, k.row_idx().to_vec());
    Ok(SparseColMat::new(symbolic, values))
}

/// [`lowest_modes`] with K − σM already factored (σ = 0: the stiffness's
/// own factor, as the Craig–Bampton reduction has it).
pub fn lowest_modes_factored(
    factor: &Factor,
    m: &SparseColMat<usize, f64>,
    count: usize,
    shift: f64,
) -> Result<Modes, FemError> {
    lowest_modes_operator(
        factor.n(),
        |x| factor.solve(x),
        |x| sym_lower_mul(m, x),
        count,
        shift,
    )
}

/// [`lowest_modes`] for K and M given as operators on n coordinates:
/// `solve` applies (K − σM)⁻¹, `mass` applies M (e.g. a body with
/// constraints eliminated, whose K − σM is never formed).
pub fn lowest_modes_operator(
    n: usize,
    solve: impl Fn(&[f64]) -> Vec<f64>,
    mass: impl Fn(&[f64]) -> Vec<f64>,
    count: usize,
    shift: f64,
) -> Result<Modes, FemError> {
    if count == 0 || count > n {
        return Err(FemError::Invalid {
            field: "mode count",
            value: count.to_string(),
            limit: format!("must lie in 1..={n} (the free dofs)"),
        });
    }
    let max_steps = n.min(3 * count + 60);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    // Start: M times a fixed pseudo-random vector, M-normalized.
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let r: Vec<f64> = (0..n)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    let mut w = mass(&r);
    let mut q: Vec<Vec<f64>> = Vec::new();
    let (mut alpha, mut beta): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
    let norm0 = dot(&w, &mass(&w)).sqrt();
    w.iter_mut().for_each(|x| *x /= norm0);
    q.push(w);
    loop {
        let j = q.len() - 1;
        let mq = mass(&q[j]);
        let mut w = solve(&mq);
        let a = dot(&mq, &w);
        for (i, x) in w.iter_mut().enumerate() {
            *x -= a * q[j][i]
                + if j > 0 {
                    beta[j - 1] * q[j - 1][i]
                } else {
                    0.0
                };
        }
        // Full reorthogonalization, twice ("twice is enough").
        for _ in 0..2 {
            let mw = mass(&w);
            for qi in &q {
                let c = dot(qi, &mw);
                w.iter_mut().zip(qi).for_each(|(x, y)| *x -= c * y);
            }
        }
        alpha.push(a);
        let b = dot(&w, &mass(&w)).max(0.0).sqrt();
        let steps = q.len();
        // T's eigenpairs cost O(steps³): test for convergence once the
        // space could hold the modes, and then every fourth step.
        let scale = alpha.iter().fold(0.0f64, |x, y| x.max(y.abs()));
        let exhausted_now = steps == n || b <= 1e-10 * scale;
        if !exhausted_now
            && (steps < count || !(steps - count).is_multiple_of(4))
            && steps < max_steps
        {
            beta.push(b);
            w.iter_mut().for_each(|x| *x /= b);
            q.push(w);
            continue;
        }
        let (theta, s) = tridiagonal_eigen(&alpha, &beta);
        // Largest θ first: the lowest ω².
        let mut order: Vec<usize> = (0..steps).collect();
        order.sort_by(|&x, &y| theta[y].total_cmp(&theta[x]));
        let exhausted = steps == n || b <= 1e-13 * theta[order[0]].abs();
        let converged = steps >= count
            && order[..count]
                .iter()
                .all(|&i| (b * s[(steps - 1, i)]).abs() <= TOLERANCE * theta[i].abs());
        if converged || exhausted {
            if steps < count {
                return Err(FemError::NotConverged(format!(
                    "the Krylov space closed after {steps} steps, fewer than the {count} modes asked (a start vector without their components)"
                )));
            }
            let mut modes: Vec<(f64, Vec<f64>)> = order[..count]
                .iter()
                .map(|&i| {
                    let mut phi = vec![0.0; n];
                    for (jj, qj) in q.iter().enumerate() {
                        let c = s[(jj, i)];
                        phi.iter_mut().zip(qj).for_each(|(x, y)| *x += c * y);
                    }
                    (shift + 1.0 / theta[i], phi)
                })
                .collect();
            modes.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (omega2, shapes) = modes.into_iter().unzip();
            return Ok(Modes {
                omega2,
                shapes,
                steps,
            });
        }
        if steps >= max_steps {
            return Err(FemError::NotConverged(format!(
                "{count} modes not within a relative residual of {TOLERANCE:e} after {steps} Lanczos steps"
            )));
        }
        beta.push(b);
        w.iter_mut().for_each(|x| *x /= b);
        q.push(w);
    }
}

/// Eigenvalues and eigenvectors (columns) of the symmetric tridiagonal
/// matrix with diagonal `alpha` and off-diagonal `beta`.
fn tridiagonal_eigen(alpha: &[f64], beta: &[f64]) -> (Vec<f64>, DMatrix<f64>) {
    let k = alpha.len();
    let t = DMatrix::from_fn(k, k, |i, j| {
        if i == j {
            alpha[i]
        } else if i + 1 == j {
            beta[i]
        } else if j + 1 == i {
            beta[j]
        } else {
            0.0
        }
    });
    let e = SymmetricEigen::new(t);
    (e.eigenvalues.iter().copied().collect(), e.eigenvectors)
}
