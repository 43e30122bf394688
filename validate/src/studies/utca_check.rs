//! Cross-check of the fast UTCA against the direct contact search.

use geometry::direct::direct_te;
use geometry::error::GeometryError;
use geometry::pair::{pinion_direction, PairGeometry};
use geometry::utca::{roll_surface, sweep};
use geometry::utca::{LineGrid, RollSurface};
use preprocess::flank_stage::FlankInput;
use serde::Serialize;
use std::time::Instant;

/// One compared position.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    pub pinion_rotation_deg: f64,
    pub fast_te_urad: f64,
    pub direct_te_urad: f64,
    pub difference_urad: f64,
}

/// The comparison over one mesh cycle.
#[derive(Debug, Clone, Serialize)]
pub struct UtcaCheck {
    pub name: String,
    pub side: &'static str,
    pub rows: Vec<Row>,
    pub max_abs_difference_urad: f64,
    pub fast_te_ptp_urad: f64,
    pub fast_te_mean_urad: f64,
    pub contact_ratio: f64,
    pub fast_ms_per_position: f64,
    pub direct_ms_per_position: f64,
    /// Smallest gap over the active flank nodes at the direct TE, µm (≥ 0: no penetration).
    pub min_gap_um: f64,
}

/// Why the UTCA check could not run.
#[derive(Debug, thiserror::Error)]
pub enum UtcaCheckError {
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    #[error("{}: the direct contact search found no contact at step {step}", .design.display())]
    NoContact {
        design: std::path::PathBuf,
        step: usize,
    },
}

/// Runs the fast UTCA over the scene's sweep and the direct search at
/// `positions` equally spaced positions of the first mesh cycle.
pub fn check(input: &FlankInput, positions: usize) -> Result<UtcaCheck, UtcaCheckError> {
    let g = PairGeometry::build(&input.pair, Some(&input.design_path))?;
    let pair = &g.data;
    let fp = g.side(input.side);
    let s = &input.utca;
    let t = Instant::now();
    let rs = roll_surface(fp, s)?;
    let u = sweep(fp, pair, &rs, s);
    let fast_ms = t.elapsed().as_secs_f64() * 1e3 / u.te.len() as f64;
    let coarse = RollSurface::new(
        fp,
        LineGrid {
            n_face: 21,
            n_profile: 21,
        },
    )?;
    let dir = pinion_direction(pair, input.side);
    let per_cycle = (pair.mesh_cycle() / s.step_deg.to_radians()).round() as usize;
    let stride = (per_cycle / positions.max(1)).max(1);
    let mut rows = Vec::new();
    let mut min_gap = f64::INFINITY;
    let t = Instant::now();
    for k in (0..=per_cycle.min(u.te.len() - 1)).step_by(stride) {
        let d = direct_te(fp, &coarse, u.pinion_angle[k], dir).ok_or_else(|| {
            UtcaCheckError::NoContact {
                design: input.design_path.clone(),
                step: k,
            }
        })?;
        min_gap = min_gap.min(d.min_node_gap);
        rows.push(Row {
            pinion_rotation_deg: (u.pinion_angle[k] - u.pinion_angle[0]).abs().to_degrees(),
            fast_te_urad: u.te[k] * 1e6,
            direct_te_urad: d.te * 1e6,
            difference_urad: (u.te[k] - d.te) * 1e6,
        });
    }
    let direct_ms = t.elapsed().as_secs_f64() * 1e3 / rows.len() as f64;
    Ok(UtcaCheck {
        name: input.name.clone(),
        side: input.side.name(),
        max_abs_difference_urad: rows
            .iter()
            .map(|r| r.difference_urad.abs())
            .fold(0.0, f64::max),
        rows,
        fast_te_ptp_urad: u.te_ptp() * 1e6,
        fast_te_mean_urad: u.te.iter().sum::<f64>() / u.te.len() as f64 * 1e6,
        contact_ratio: u.contact_ratio,
        fast_ms_per_position: fast_ms,
        direct_ms_per_position: direct_ms,
        min_gap_um: min_gap * 1e6,
    })
}

/// Why the cross-check's result set could not be written.
#[derive(Debug, thiserror::Error)]
pub enum UtcaCheckWriteError {
    #[error("reading {}: {message}", .path.display())]
    Input {
        path: std::path::PathBuf,
        message: String,
    },
    #[error(transparent)]
    Set(#[from] formats::result_set::ResultSetError),
}

/// Writes `c` as one result set in `out`: `utca_check.json` and a
/// `run.json` listing its checksum and the SHA-256 of the scene (or
/// design) file `source` and of the design's geometry text, so that an
/// edited result or a changed input is detected like every other stage's.
pub fn write_set(
    c: &UtcaCheck,
    source: &std::path::Path,
    design: &std::path::Path,
    out: &std::path::Path,
) -> Result<formats::result_set::RunInfo, UtcaCheckWriteError> {
    let read = |path: &std::path::Path| {
        std::fs::read_to_string(path).map_err(|e| UtcaCheckWriteError::Input {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    };
    let mut set = formats::result_set::ResultSet::begin(out, &format!("validate utca {}", c.name))?;
    set.record_input("scene", &formats::manifest::sha256_text(&read(source)?))?;
    let geometry = geometry::design::geometry_text(&read(design)?);
    set.record_input("design", &formats::manifest::sha256_text(&geometry))?;
    formats::output::write_json(&set.path().join("utca_check.json"), c)
        .map_err(formats::result_set::ResultSetError::from)?;
    Ok(set.commit()?)
}
