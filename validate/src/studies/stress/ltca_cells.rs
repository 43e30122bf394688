//! The LTCA cells of one design: the load study (with the doubling up to
//! edge contact), a grid scene's stiffness grid, and the coast flanks'
//! compliance.

use super::cell::{
    cell, classify, deflection_to_thickness, ltca_record, te_decreases, Cell, Outcome, Study,
};
use super::{Design, DOUBLINGS, LOADS_NM, PROBE_NM};
use crate::studies::grid_scenes::GridScene;
use formats::summaries::EdgeContact;
use geometry::design::PairData;
use geometry::scene::Blank;
use geometry::utca::{roll_surface, RollSurface};
use indicatif::ProgressBar;
use solver::element::compliance::PairCompliance;
use solver::ltca::{run as run_sweep, Sweep};
use solver::stage::context::{coast_compliance, scene_sweep};
use std::path::{Path, PathBuf};

type EdgeAt = Option<(f64, EdgeContact)>;

/// The standard blanks' coast-flank compliance of `d`'s design: from its own
/// stiffness files, else from the first of `coast_scenes` with its design
/// (an outer error: a coast scene that does not load).
pub(super) fn coast_of(
    d: &Design,
    meshes: &Path,
    coast_scenes: &[PathBuf],
) -> anyhow::Result<anyhow::Result<PairCompliance>> {
    let own = coast_compliance(&d.scene, &d.g, &d.dir, Blank::Standard, Blank::Standard);
    let Err(own_err) = own else {
        return Ok(own.map(|c| c.0));
    };
    for p in coast_scenes {
        let s = GridScene::load(p, meshes)?;
        if s.same_design(&d.scene) {
            return Ok(
                coast_compliance(&s.scene, &s.g, &s.dir, Blank::Standard, Blank::Standard)
                    .map(|c| c.0),
            );
        }
    }
    Ok(Err(own_err))
}

/// The load study: [`LOADS_NM`] in one sweep (each load warm-started from
/// the lighter one), then doubling. Returns the cells, the first load with
/// edge contact and the largest load run.
pub(super) fn load_cells(
    name: &str,
    pair: &PairData,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    bar: &ProgressBar,
) -> (Vec<Cell>, EdgeAt, f64) {
    let label = |t: f64| format!("{t} N·m");
    let mut cells: Vec<Cell> = LOADS_NM
        .iter()
        .map(|&t| cell(name, Study::Load, t, "N·m", label(t)))
        .collect();
    match run_sweep(fp, rs, pc, sweep, &LOADS_NM) {
        Ok(res) => {
            for (i, c) in cells.iter_mut().enumerate() {
                ltca_record(c, &res, i, LOADS_NM[i]);
                c.deflection_to_thickness = Some(deflection_to_thickness(&res, i, pair));
                if i > 0 {
                    c.te_monotonic = Some(!te_decreases(&res, i));
                }
            }
        }
        Err(_) => {
            // One load's error stops the sweep: each load alone, to name it.
            for c in cells.iter_mut() {
                match run_sweep(fp, rs, pc, sweep, &[c.value]) {
                    Ok(res) => {
                        ltca_record(c, &res, 0, c.value);
                        c.deflection_to_thickness = Some(deflection_to_thickness(&res, 0, pair));
                    }
                    Err(e) => c.outcome = classify(&e),
                }
            }
        }
    }
    bar.inc(LOADS_NM.len() as u64);
    let first_edge = |cells: &[Cell]| {
        cells
            .iter()
            .find_map(|c| c.edge_contact.map(|e| (c.value, e)))
    };
    let mut largest = *LOADS_NM.last().unwrap_or(&0.0);
    let mut t = largest;
    for _ in 0..DOUBLINGS {
        if first_edge(&cells).is_some() || cells.iter().any(|c| c.outcome != Outcome::Converged) {
            break;
        }
        t *= 2.0;
        let mut c = cell(name, Study::Load, t, "N·m", label(t));
        match run_sweep(fp, rs, pc, sweep, &[t / 2.0, t]) {
            Ok(res) => {
                ltca_record(&mut c, &res, 1, t);
                c.deflection_to_thickness = Some(deflection_to_thickness(&res, 1, pair));
                c.te_monotonic = Some(!te_decreases(&res, 1));
            }
            Err(e) => c.outcome = classify(&e),
        }
        largest = t;
        cells.push(c);
    }
    let e = first_edge(&cells);
    (cells, e, largest)
}

/// The LTCA at [`PROBE_NM`] over `d`'s sweep on the stiffness files of
/// `path`'s scene (another contact grid) when its design is `d`'s.
pub(super) fn grid_scene_cell(
    d: &Design,
    path: &Path,
    meshes: &Path,
) -> anyhow::Result<Option<Cell>> {
    let s = GridScene::load(path, meshes)?;
    if !s.same_design(&d.scene) {
        return Ok(None);
    }
    let mut c = cell(
        d.name(),
        Study::Grid,
        (s.grid[0] * s.grid[1]) as f64,
        "",
        s.label(),
    );
    let sc = &d.scene.scene;
    let fp = d.g.side(sc.loaded_flank);
    let rs = roll_surface(fp, &sc.utca)?;
    match s.compliance() {
        Err(e) => c.outcome = Outcome::Skipped(format!("{e:#}")),
        Ok(pc) => match run_sweep(
            fp,
            &rs,
            &pc,
            &scene_sweep(&d.scene, &d.g, Blank::Standard),
            &[PROBE_NM],
        ) {
            Ok(res) => ltca_record(&mut c, &res, 0, PROBE_NM),
            Err(e) => c.outcome = classify(&e),
        },
    }
    Ok(Some(c))
}
