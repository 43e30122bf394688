//! Run time against error of the stiffness fields: the global
//! influence field each contact grid's stiffness file holds, against the
//! next finer grid's, and the reduced-order mesh's against the medium
//! mesh's on the same grid, where its files exist.
//!
//! A point load's compliance at its own point depends on the grid (the
//! load patch scales with the cell), so the fields are compared through a
//! grid-independent quantity: the loaded tooth's displacement under a
//! uniform unit pressure on the flank, u(p) = (1/N) Σᵢ C(i, p) (a cell-area
//! weighted integral of the global field, every grid's cells being equal).
//! The finer grid's u is interpolated bilinearly (in the normalised face
//! and profile parameters ξ, η) to the coarser grid's points; the error is
//! max |u_coarse − u_fine| / max |u_fine|, pinion and wheel, the larger.
//!
//! Cost: the stiffness stage's recorded time for the member's file
//! (`<stem>.stiffness.json`, `total_s`: assembly, factorisation, unit
//! loads, local fields; wall time of that run, as thread CPU of a
//! multi-threaded factorisation cannot be re-measured from a cached file),
//! both members summed. Meshing is not counted.

use crate::studies::grid_scenes::{member_fields, GridScene};
use crate::studies::tradeoff_stage::{StageTradeoff, TradeoffPoint};
use formats::paths::MeshLevel;
use formats::stiffness_file::StiffnessData;
use geometry::design::Member;

const GRID: &str = "contact grid (profile × face)";
const LEVEL: &str = "mesh level (same grid)";

/// The loaded tooth's displacement under a uniform unit pressure, per grid
/// point (index i_face · profile + i_profile).
pub fn uniform_pressure_displacement(d: &StiffnessData) -> anyhow::Result<Vec<f64>> {
    let o = d.offsets.iter().position(|&o| o == 0).ok_or_else(|| {
        anyhow::anyhow!(
            "stiffness file of the {} has no loaded tooth (offset 0)",
            d.member
        )
    })?;
    let np = d.points();
    Ok((0..np)
        .map(|p| (0..np).map(|i| d.global_at(0, o, i, p)).sum::<f64>() / np as f64)
        .collect())
}

/// Bilinear interpolation of `u` on `d`'s grid at (ξ, η), clamped to the
/// grid points' hull.
fn at(d: &StiffnessData, u: &[f64], xi: f64, eta: f64) -> f64 {
    let cell = |v: &[f64], x: f64| {
        let k = v.partition_point(|a| *a < x).clamp(1, v.len().max(2) - 1);
        if v.len() < 2 {
            return (0, 0, 0.0);
        }
        let t = ((x - v[k - 1]) / (v[k] - v[k - 1])).clamp(0.0, 1.0);
        (k - 1, k, t)
    };
    let (f0, f1, tf) = cell(&d.xi, xi);
    let (p0, p1, tp) = cell(&d.eta, eta);
    let n = d.grid_profile;
    let v = |f: usize, p: usize| u[f * n + p];
    (1.0 - tf) * ((1.0 - tp) * v(f0, p0) + tp * v(f0, p1))
        + tf * ((1.0 - tp) * v(f1, p0) + tp * v(f1, p1))
}

/// max |u_coarse − u_fine| / max |u_fine| at the coarse grid's points, %.
pub fn field_error_pct(coarse: &StiffnessData, fine: &StiffnessData) -> anyhow::Result<f64> {
    let uc = uniform_pressure_displacement(coarse)?;
    let uf = uniform_pressure_displacement(fine)?;
    let scale = uf.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let n = coarse.grid_profile;
    let mut worst = 0.0f64;
    for (k, &u) in uc.iter().enumerate() {
        let (f, p) = (k / n, k % n);
        worst = worst.max((u - at(fine, &uf, coarse.xi[f], coarse.eta[p])).abs());
    }
    Ok(worst / scale * 100.0)
}

/// Both members' fields of a grid scene at `level`, and their summed cost.
fn fields(s: &GridScene, level: MeshLevel) -> anyhow::Result<([StiffnessData; 2], Option<f64>)> {
    let (p, tp) = member_fields(&s.scene, &s.g, &s.dir, Member::Pinion, level)?;
    let (w, tw) = member_fields(&s.scene, &s.g, &s.dir, Member::Wheel, level)?;
    Ok(([p, w], tp.zip(tw).map(|(a, b)| a + b)))
}

/// The study over `grids` (the scene itself among them, marked default),
/// finest last.
pub fn run(grids: &[GridScene], default_grid: [u32; 2]) -> StageTradeoff {
    let mut st = StageTradeoff::new(
        "stiffness",
        "Stiffness fields: stiffness-stage time against the change to the next finer grid / mesh",
        "stiffness-stage time, both members (s): recorded wall time of the stage",
        "max |u − u_finer| / max |u_finer| of the loaded tooth's displacement under uniform pressure (global field), larger of pinion and wheel, against the next finer contact grid, or the medium mesh on the same grid",
    );
    let mut sorted: Vec<&GridScene> = grids.iter().collect();
    sorted.sort_by_key(|s| s.grid[0] * s.grid[1]);
    let mut loaded = Vec::new();
    for s in sorted {
        match fields(s, MeshLevel::Reduced) {
            Ok(f) => loaded.push((s, f)),
            Err(e) => st.skip(GRID, &s.label(), format!("{e:#}")),
        }
    }
    for w in loaded.windows(2) {
        let ((s, (c, cost)), (_, (f, _))) = (&w[0], &w[1]);
        let err = (|| -> anyhow::Result<f64> {
            Ok(field_error_pct(&c[0], &f[0])?.max(field_error_pct(&c[1], &f[1])?))
        })();
        match (err, cost) {
            (Ok(e), Some(t)) => st.push(TradeoffPoint {
                parameter: GRID.into(),
                setting: s.label(),
                value: (s.grid[0] * s.grid[1]) as f64,
                cpu_s: *t,
                error_pct: e,
                secondary_error_pct: None,
                is_default: s.grid == default_grid,
            }),
            (Err(e), _) => st.skip(GRID, &s.label(), format!("{e:#}")),
            (_, None) => st.skip(
                GRID,
                &s.label(),
                "no stiffness-stage report beside the file (a checked-in fixture): its cost is unknown".into(),
            ),
        }
    }
    if let Some((s, _)) = loaded.last() {
        st.skip(
            GRID,
            &s.label(),
            "the finest grid run: nothing finer to compare with".into(),
        );
    }
    // Mesh level on the scene's own grid: reduced against medium.
    if let Some((s, (c, cost))) = loaded.iter().find(|(s, _)| s.grid == default_grid) {
        match fields(s, MeshLevel::Medium) {
            Err(e) => st.skip(
                LEVEL,
                "reduced",
                format!("no medium-level stiffness files to compare with: {e:#}"),
            ),
            Ok((f, fcost)) => {
                let err = (|| -> anyhow::Result<f64> {
                    Ok(field_error_pct(&c[0], &f[0])?.max(field_error_pct(&c[1], &f[1])?))
                })();
                match (err, cost) {
                    (Ok(e), Some(t)) => st.push(TradeoffPoint {
                        parameter: LEVEL.into(),
                        setting: format!("reduced ({})", s.label()),
                        value: 0.0,
                        cpu_s: *t,
                        error_pct: e,
                        secondary_error_pct: None,
                        is_default: true,
                    }),
                    (Err(e), _) => st.skip(LEVEL, "reduced", format!("{e:#}")),
                    (_, None) => st.skip(LEVEL, "reduced", "no stiffness-stage report".into()),
                }
                let m = s.scene.scene.mesh.medium();
                st.skip(
                    LEVEL,
                    &format!("medium ({} × {} elements)", m.profile, m.face),
                    format!(
                        "nothing finer with stiffness files (the reference level's would need ~16 GB); its stage time {} s",
                        fcost.map_or("unknown".into(), |t| format!("{t:.1}"))
                    ),
                );
            }
        }
    }
    st.finish();
    st
}
