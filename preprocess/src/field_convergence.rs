//! Mesh convergence of the influence fields: two stiffness files of one
//! member × blank on the same contact grid, made from meshes of two levels,
//! compared on the loaded tooth's diagonal C(p, p) (the compliance a unit
//! load at grid point p meets at p) for the total, local and global fields:
//!
//!   r(p) = (C_fine(p, p) − C_coarse(p, p)) / C_fine(p, p).
//!
//! The global field should change by less than 3 % between the
//! reduced-order mesh and a mesh twice as fine while the total field changes
//! much more.

use formats::stiffness_file::StiffnessData;
use serde::Serialize;

/// Why two stiffness files cannot be compared.
#[derive(Debug, thiserror::Error)]
pub enum FieldConvergenceError {
    #[error("stiffness files differ in {what}: {coarse} (coarse) against {fine} (fine)")]
    Mismatch {
        what: &'static str,
        coarse: String,
        fine: String,
    },
    #[error("stiffness file of {member} {blank} has no response on the loaded tooth (offset 0)")]
    NoLoadedTooth { member: String, blank: String },
}

/// The relative change of one field's diagonal.
#[derive(Debug, Clone, Serialize)]
pub struct DiagonalChange {
    /// "total", "local" or "global".
    pub field: &'static str,
    /// r(p) at every grid point (point index = i_face · profile + i_profile).
    pub relative: Vec<f64>,
    /// Largest and mean |r|, and mean r.
    pub max_abs: f64,
    pub mean_abs: f64,
    pub mean: f64,
    /// Largest |r| without the root row (η index 0) and the toe and heel
    /// columns, where the local model's clamped cut lies closest to the load.
    pub interior_max_abs: f64,
    /// Share of the points with |r| below `bound`.
    pub share_within: f64,
    pub bound: f64,
    /// Mean |r| per profile row, root first.
    pub row_mean_abs: Vec<f64>,
}

fn check<T: PartialEq + std::fmt::Debug>(
    what: &'static str,
    a: T,
    b: T,
) -> Result<(), FieldConvergenceError> {
    if a == b {
        Ok(())
    } else {
        Err(FieldConvergenceError::Mismatch {
            what,
            coarse: format!("{a:?}"),
            fine: format!("{b:?}"),
        })
    }
}

/// Diagonal of the loaded tooth's block of a field stored as
/// [solved][offset][i][j] (`offsets` None: stored as [solved][i][j]).
fn loaded_diagonal(d: &StiffnessData, field: &[f64], offset0: Option<usize>) -> Vec<f64> {
    let np = d.points();
    let block = match offset0 {
        Some(o) => &field[o * np * np..(o + 1) * np * np],
        None => &field[..np * np],
    };
    (0..np).map(|i| block[i * np + i]).collect()
}

/// Relative change of the total, local and global diagonals on the first
/// solved tooth from `coarse` to `fine`; `bound` is the share's threshold.
pub fn diagonal_change(
    coarse: &StiffnessData,
    fine: &StiffnessData,
    bound: f64,
) -> Result<Vec<DiagonalChange>, FieldConvergenceError> {
    check("member", &coarse.member, &fine.member)?;
    check("blank", &coarse.blank, &fine.blank)?;
    check(
        "grid size (profile, face)",
        (coarse.grid_profile, coarse.grid_face),
        (fine.grid_profile, fine.grid_face),
    )?;
    check("grid ξ", &coarse.xi, &fine.xi)?;
    check("grid η", &coarse.eta, &fine.eta)?;
    check(
        "first solved tooth",
        coarse.solved_teeth.first(),
        fine.solved_teeth.first(),
    )?;
    let o0 = |d: &StiffnessData| {
        d.offsets
            .iter()
            .position(|&o| o == 0)
            .ok_or(FieldConvergenceError::NoLoadedTooth {
                member: d.member.clone(),
                blank: d.blank.clone(),
            })
    };
    let (oc, of) = (o0(coarse)?, o0(fine)?);
    let (npf, nf) = (coarse.grid_profile, coarse.grid_face);
    let fields: [(&'static str, Vec<f64>, Vec<f64>); 3] = [
        (
            "total",
            loaded_diagonal(coarse, &coarse.total, Some(oc)),
            loaded_diagonal(fine, &fine.total, Some(of)),
        ),
        (
            "local",
            loaded_diagonal(coarse, &coarse.local, None),
            loaded_diagonal(fine, &fine.local, None),
        ),
        (
            "global",
            loaded_diagonal(coarse, &coarse.global, Some(oc)),
            loaded_diagonal(fine, &fine.global, Some(of)),
        ),
    ];
    Ok(fields
        .into_iter()
        .map(|(field, c, f)| {
            let r: Vec<f64> = c.iter().zip(&f).map(|(c, f)| (f - c) / f).collect();
            let n = r.len() as f64;
            let interior = (0..r.len()).filter(|&p| {
                let (face, prof) = (p / npf, p % npf);
                prof > 0 && face > 0 && face + 1 < nf
            });
            DiagonalChange {
                field,
                max_abs: r.iter().fold(0.0, |a, x| a.max(x.abs())),
                mean_abs: r.iter().map(|x| x.abs()).sum::<f64>() / n,
                mean: r.iter().sum::<f64>() / n,
                interior_max_abs: interior.fold(0.0, |a, p| a.max(r[p].abs())),
                share_within: r.iter().filter(|x| x.abs() < bound).count() as f64 / n,
                bound,
                row_mean_abs: (0..npf)
                    .map(|i| (0..nf).map(|k| r[k * npf + i].abs()).sum::<f64>() / nf as f64)
                    .collect(),
                relative: r,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 4 grid, one solved tooth, offsets −1..1, diagonal `diag(p)`
    /// in the total field, a tenth of it in the local one.
    fn data(diag: impl Fn(usize) -> f64) -> StiffnessData {
        let (npf, nf, no) = (3, 4, 3);
        let np = npf * nf;
        let mut total = vec![1e-12; no * np * np];
        let mut local = vec![0.0; np * np];
        for p in 0..np {
            total[(np + p) * np + p] = diag(p);
            local[p * np + p] = 0.1 * diag(p);
        }
        let global = total
            .iter()
            .enumerate()
            .map(|(k, t)| match k / (np * np) {
                1 => t - local[k % (np * np)],
                _ => *t,
            })
            .collect();
        StiffnessData {
            input_hash: String::new(),
            config: String::new(),
            member: "pinion".into(),
            blank: "standard".into(),
            level: "reduced".into(),
            teeth: 20,
            axisymmetric: true,
            grid_profile: npf,
            grid_face: nf,
            xi: vec![0.1, 0.4, 0.6, 0.9],
            eta: vec![0.2, 0.5, 0.8],
            position: vec![0.0; 3 * np],
            normal: vec![0.0; 3 * np],
            lever: vec![0.0; np],
            solved_teeth: vec![0],
            offsets: vec![-1, 0, 1],
            depth_h: vec![3e-3; np],
            total,
            local,
            global,
            root_stress: None,
        }
    }

    #[test]
    fn a_uniformly_softer_fine_mesh_changes_every_field_by_the_same_share() {
        let coarse = data(|p| 1e-9 * (1.0 + p as f64));
        let fine = data(|p| 1.02e-9 * (1.0 + p as f64));
        for c in diagonal_change(&coarse, &fine, 0.03).unwrap() {
            let r = 1.0 - 1.0 / 1.02;
            assert!((c.max_abs - r).abs() < 1e-12, "{}: {}", c.field, c.max_abs);
            assert!((c.mean - r).abs() < 1e-12 && c.share_within == 1.0);
        }
    }

    #[test]
    fn only_the_interior_is_in_the_interior_maximum() {
        // Point 4 = face column 1, profile row 1: interior. Point 0: root row, toe.
        let coarse = data(|_| 1e-9);
        let fine = data(|p| match p {
            0 => 2e-9,
            4 => 1.1e-9,
            _ => 1e-9,
        });
        let c = &diagonal_change(&coarse, &fine, 0.03).unwrap()[0];
        assert!((c.max_abs - 0.5).abs() < 1e-12);
        assert!((c.interior_max_abs - 0.1 / 1.1).abs() < 1e-12);
        assert!((c.share_within - 10.0 / 12.0).abs() < 1e-12);
        assert!((c.row_mean_abs[0] - 0.5 / 4.0).abs() < 1e-12);
    }

    #[test]
    fn files_on_different_grids_are_not_compared() {
        let coarse = data(|_| 1e-9);
        let mut fine = data(|_| 1e-9);
        fine.eta[1] = 0.55;
        let e = diagonal_change(&coarse, &fine, 0.03).unwrap_err();
        assert!(e.to_string().contains("grid η"), "{e}");
    }
}
