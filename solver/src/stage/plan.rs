//! Which tooth pairs can be in contact at each position of a scene's sweep,
//! and `solver plan --out <dir>`: the plan written as one result set
//! (`<dir>/plan.json` with `run.json` listing its checksum and the scene
//! and design it was planned from).

use formats::result_set::{ResultSet, ResultSetError, RunInfo};
use geometry::error::GeometryError;
use geometry::generation::Side;
use geometry::pair::{pairs_in_contact, pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use serde::Serialize;
use std::path::Path;

/// Tooth pairs (pinion tooth j with wheel tooth −j) that can touch at one position.
#[derive(Debug, Clone, Serialize)]
pub struct Position {
    pub pinion_rotation_deg: f64,
    pub tooth_pairs: Vec<i32>,
}

/// The plan of one wheel blank.
#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    pub blank: Blank,
    pub loaded_flank: Side,
    pub mesh_cycles: f64,
    pub positions: Vec<Position>,
    /// Distinct pinion teeth (mod z₁) that ever touch: the flanks that need
    /// stiffness data ([`teeth_in_contact`], the one rule the mesh and
    /// stiffness stages use too).
    pub pinion_teeth: Vec<usize>,
    /// Distinct wheel teeth (mod z₂) that ever touch.
    pub wheel_teeth: Vec<usize>,
}

/// Plans every wheel blank of the scene.
pub fn plan(scene: &LoadedScene) -> Result<Vec<Plan>, GeometryError> {
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = scene.scene.loaded_flank;
    let fp = g.side(side);
    let tau = g.data.mesh_cycle();
    let dir = pinion_direction(&g.data, side);
    let step = scene.scene.rotation.step_deg.to_radians();
    Ok(scene
        .scene
        .blanks
        .wheel
        .iter()
        .map(|&blank| {
            let cycles = scene.scene.rotation.mesh_cycles(blank);
            let n = (cycles * tau / step).round() as usize + 1;
            let positions: Vec<Position> = (0..n)
                .map(|k| {
                    let phi = fp.roll_range[0] + dir * step * k as f64;
                    Position {
                        pinion_rotation_deg: (step * k as f64).to_degrees(),
                        tooth_pairs: pairs_in_contact(phi, fp.roll_range, tau),
                    }
                })
                .collect();
            let (pinion_teeth, wheel_teeth) = teeth_in_contact(&g, side, cycles, step);
            Plan {
                blank,
                loaded_flank: side,
                mesh_cycles: cycles,
                positions,
                pinion_teeth,
                wheel_teeth,
            }
        })
        .collect())
}

/// Why the plan could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlanWriteError {
    #[error(transparent)]
    Set(#[from] ResultSetError),
    #[error("cannot read {}: {message}", .path.display())]
    Input {
        path: std::path::PathBuf,
        message: String,
    },
    #[error(transparent)]
    Plan(#[from] GeometryError),
}

/// Plans `scene` and writes the plan into `out` as one result set:
/// `plan.json`, and `run.json` with its SHA-256 and the inputs' (`scene`:
/// the scene file's bytes; `design`: the design's geometry text, as the
/// flank stage records it). The output is taken (and refused, if another
/// run writes it or it cannot be written) before any work.
pub fn write_plan_set(scene: &LoadedScene, out: &Path) -> Result<Vec<Plan>, PlanWriteError> {
    let mut set = ResultSet::begin(out, &format!("solver plan {}", scene.scene.name))?;
    let read = |path: &Path| {
        std::fs::read_to_string(path).map_err(|e| PlanWriteError::Input {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    };
    set.record_input(
        "scene",
        &formats::manifest::sha256_text(&read(&scene.path)?),
    )?;
    set.record_input(
        "design",
        &formats::manifest::sha256_text(&geometry::design::geometry_text(&read(
            &scene.design_path,
        )?)),
    )?;
    let plans = plan(scene)?;
    formats::output::write_json(&set.path().join("plan.json"), &plans)
        .map_err(ResultSetError::from)?;
    let _: RunInfo = set.commit()?;
    Ok(plans)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_ratio_of_2_point_87_gives_two_or_three_pairs() {
        // Active range 2.87 mesh cycles wide: 2 or 3 tooth pairs at every position.
        let tau = 18f64.to_radians();
        let range = [-0.4, -0.4 + 2.87 * tau];
        for k in 0..100 {
            let phi = -0.4 + k as f64 * tau / 50.0;
            let n = pairs_in_contact(phi, range, tau).len();
            assert!((2..=3).contains(&n), "{n} pairs at step {k}");
        }
        // Exactly at the entry the entering pair counts.
        assert_eq!(pairs_in_contact(-0.4, range, tau), vec![0, 1, 2]);
    }
}
