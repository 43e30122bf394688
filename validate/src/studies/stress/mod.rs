//! `validate stress <scene>`: the stress matrix on cached meshes
//! and stiffness files. For the scene's design and every seed pair (the
//! chain scenes `seed<NNN>_<z1>x<z2>.toml` beside the scene), standard
//! blanks, drive flanks:
//!
//! - loads: the pinion torques of [`LOADS_NM`] over the scene's sweep, then
//!   doubling from 5,000 N·m until the LTCA reports edge contact (or a
//!   refusal), at most [`DOUBLINGS`] times;
//! - slices per tooth pair [`SLICES`] at [`PROBE_NM`];
//! - the stiffness grid of the cached files, and of any `--grid-scene`
//!   whose design is the same (`make stress`: the white-paper pair at
//!   6 × 10 … 24 × 40, `reference/scenes/grids/`), over the design's sweep;
//!   a grid scene without stiffness files is skipped, naming why;
//! - the coast flanks at [`PROBE_NM`], from the design's own coast
//!   stiffness files or a `--coast-scene` of the design (`make stress`:
//!   `reference/scenes/coast/`);
//! - multibody, both members free with constant torques ([`PROBE_NM`] on
//!   the pinion, the balancing torque on the wheel), undamped, without
//!   friction, the energy-conserving scheme, from the quasi-static state,
//!   over one mesh cycle or [`MAX_RUN_S`], the shorter: maximum step [`MAX_STEPS_S`] at
//!   [`STEP_STUDY_RPM`], TE tolerance [`TOLERANCES_RAD`] at the same
//!   speed, and pinion speed [`SPEEDS_RPM`]. One mesh cycle keeps the
//!   1e-6 s run at 1,000 rpm to a few thousand steps; the 0.1 s cap keeps
//!   the 10 rpm runs (an undamped mesh vibration resolved to 1e-9 rad
//!   needs steps of a few µs: a whole cycle of seed 002 at 10 rpm would
//!   take some 500,000 steps) to the matrix's 20 min;
//! - multibody loads [`MB_LOADS_NM`] (0 N·m: the wheel free to cross the
//!   backlash) at [`STEP_STUDY_RPM`] imposed on the pinion, with the
//!   wheel's impulse balance (see [`loaded_run`]).
//!
//! Every cell records its outcome (converged, refused with the refusal's
//! message, failed with the error, or skipped where its inputs are not
//! cached), non-finite values in any output, the torque balance, whether
//! every slice force is compressive, whether the TE grows with the load at
//! every position, the energy drift of the undamped runs and the CPU time.
//! Written as one result set to `<out>/<scene>/stress/` (`summary.json`,
//! [`StressSummary`], and `outcomes.svg`).
use solver::stage::context::LoadedPair;

mod cell;
mod ltca_cells;
mod multibody_cells;

pub use cell::{
    cell, classify, deflection_to_thickness, ltca_record, row_label, Cell, DesignSummary, Outcome,
    StressSummary, Study,
};
pub use multibody_cells::{loaded_run, probe_table};

use ltca_cells::{coast_of, grid_scene_cell, load_cells};
use multibody_cells::{multibody_cells, multibody_load_cells};

use charts::{outcome_grid, GridCell};
use formats::output::write_json;
use formats::result_set::ResultSet;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::roll_surface;
use indicatif::{ProgressBar, ProgressStyle};
use solver::element::compliance::PairCompliance;
use solver::ltca::{run as run_sweep, Sweep};
use solver::stage::context::{coast_sweep, scene_sweep};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Pinion torques of the load study, N·m.
pub const LOADS_NM: [f64; 9] = [0.0, 1e-3, 0.1, 1.0, 10.0, 100.0, 1000.0, 3000.0, 5000.0];
/// Doublings of the largest load at most, looking for edge contact.
pub const DOUBLINGS: usize = 8;
/// Pinion torque of the discretization, flank and multibody cells, N·m.
pub const PROBE_NM: f64 = 300.0;
/// Slices per tooth pair.
pub const SLICES: [usize; 6] = [5, 10, 20, 40, 80, 160];
/// Multibody maximum steps, s.
pub const MAX_STEPS_S: [f64; 5] = [1e-6, 1e-5, 1e-4, 1e-3, 1e-2];
/// Multibody local error tolerances on the TE, rad (1e-6 … 1 µrad).
pub const TOLERANCES_RAD: [f64; 4] = [1e-12, 1e-10, 1e-8, 1e-6];
/// Pinion speeds, rpm.
pub const SPEEDS_RPM: [f64; 5] = [10.0, 100.0, 1000.0, 3000.0, 10000.0];
/// Pinion torques of the multibody load study, N·m (0: no load, the
/// wheel free to cross the backlash).
pub const MB_LOADS_NM: [f64; 6] = [0.0, 1.0, 10.0, 100.0, 1000.0, 3000.0];
/// Pinion speed of the step and tolerance studies, rpm.
pub const STEP_STUDY_RPM: f64 = 1000.0;
/// Maximum step of the tolerance and speed studies, s.
const STUDY_MAX_STEP_S: f64 = 1e-5;
/// TE tolerance of the step and speed studies, rad.
const STUDY_TOLERANCE_RAD: f64 = 1e-9;
/// Longest simulated time of one multibody cell, s.
pub const MAX_RUN_S: f64 = 0.1;
/// Steps at most of one multibody cell (a run needing more fails).
pub const MAX_RUN_STEPS: usize = 200_000;
/// Largest plausible loaded deflection, as a share of the thinner member's
/// normal tooth thickness: beyond it the linear, small-deflection model
/// (influence coefficients of the unloaded geometry, contact on the
/// unloaded flanks) no longer describes the teeth, and its TE is flagged.
pub const DEFLECTION_LIMIT: f64 = 0.1;
/// A TE lower than the lighter load's by more than this is a decrease, rad.
const TE_DECREASE_TOL: f64 = 1e-13;

/// The cached inputs of one design.
struct Design {
    scene: LoadedScene,
    g: PairGeometry,
    dir: PathBuf,
}

impl Design {
    fn name(&self) -> &str {
        &self.scene.scene.name
    }
    fn pair(&self) -> anyhow::Result<(PairCompliance, [f64; 2])> {
        let (s, g, dir) = (&self.scene, &self.g, &self.dir);
        let pair = LoadedPair::load(s, g, dir, [Blank::Standard; 2])?;
        let [(j1, _), (j2, _)] = pair.inertia(s, g, dir)?;
        Ok((pair.pc, [j1, j2]))
    }
}

/// The seed chain scenes beside `scene` (`seed<digits>_<z1>x<z2>.toml`).
pub fn seed_scenes(scene: &Path) -> Vec<PathBuf> {
    let dir = scene.parent().unwrap_or(Path::new("."));
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let Some(stem) = p.file_stem().and_then(|s| s.to_str()) else {
                return false;
            };
            let Some(rest) = stem.strip_prefix("seed") else {
                return false;
            };
            let mut parts = rest.splitn(2, '_');
            let (Some(n), Some(z)) = (parts.next(), parts.next()) else {
                return false;
            };
            let mut zs = z.splitn(2, 'x');
            p.extension().is_some_and(|e| e == "toml")
                && !n.is_empty()
                && n.chars().all(|c| c.is_ascii_digit())
                && matches!((zs.next(), zs.next()), (Some(a), Some(b))
                    if !a.is_empty() && !b.is_empty()
                    && a.chars().chain(b.chars()).all(|c| c.is_ascii_digit()))
        })
        .collect();
    v.sort();
    v
}

/// Runs the matrix for `scene` and the seed scenes beside it; `grid_scenes`
/// are scenes of the same designs at other stiffness grids, `coast_scenes`
/// scenes of the same designs with coast-flank stiffness files (each with
/// its meshes in a `meshes/` folder beside it, or in `meshes`).
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    grid_scenes: &[PathBuf],
    coast_scenes: &[PathBuf],
) -> anyhow::Result<StressSummary> {
    let t0 = Instant::now();
    let name = scene.scene.name.clone();
    let set = ResultSet::begin(
        &out.join(&name).join("stress"),
        &format!("validate stress {}", scene.path.display()),
    )?;
    let mut scenes: Vec<PathBuf> = vec![scene.path.clone()];
    scenes.extend(seed_scenes(&scene.path));
    let per_design = LOADS_NM.len()
        + SLICES.len()
        + 2
        + MAX_STEPS_S.len()
        + TOLERANCES_RAD.len()
        + SPEEDS_RPM.len()
        + MB_LOADS_NM.len();
    let bar = ProgressBar::new((scenes.len() * per_design) as u64);
    bar.set_style(
        ProgressStyle::with_template("stress {bar:40} {pos}/{len} cells, {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut cells = Vec::new();
    let mut designs = Vec::new();
    for path in &scenes {
        let label = path
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        bar.set_message(label.clone());
        match Scene::load(path) {
            Err(e) => {
                // Refused at load: one cell naming the check.
                let mut c = cell(&label, Study::Load, f64::NAN, "", "design".into());
                c.outcome = Outcome::Refused(format!("{e:#}"));
                cells.push(c);
                bar.inc(per_design as u64);
            }
            Ok(s) => {
                let (d, c) = design_cells(s, meshes, grid_scenes, coast_scenes, &bar)?;
                designs.extend(d);
                cells.extend(c);
            }
        }
    }
    bar.finish_and_clear();
    let summary = StressSummary {
        scene: name.clone(),
        designs,
        cells,
        wall_s: t0.elapsed().as_secs_f64(),
    };
    write_json(&set.path().join("summary.json"), &summary)?;
    chart(&set.path().join("outcomes.svg"), &summary)?;
    set.commit()?;
    Ok(summary)
}

/// Every cell of one design.
fn design_cells(
    scene: LoadedScene,
    meshes: &Path,
    grid_scenes: &[PathBuf],
    coast_scenes: &[PathBuf],
    bar: &ProgressBar,
) -> anyhow::Result<(Option<DesignSummary>, Vec<Cell>)> {
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = meshes.join(&scene.scene.name);
    let d = Design { scene, g, dir };
    let name = d.name().to_string();
    let grid = d.scene.scene.mesh.reduced_order;
    let grid = [grid.profile, grid.face];
    let (pc, inertia) = match d.pair() {
        Ok(p) => p,
        Err(e) => {
            // No cached stiffness files: every cell skipped, with the reason.
            let why = format!("{e:#}");
            let mut v = Vec::new();
            for study in Study::ALL {
                let mut c = cell(&name, study, f64::NAN, "", "not cached".into());
                c.outcome = Outcome::Skipped(why.clone());
                v.push(c);
            }
            bar.inc(
                (LOADS_NM.len()
                    + SLICES.len()
                    + 2
                    + MAX_STEPS_S.len()
                    + TOLERANCES_RAD.len()
                    + SPEEDS_RPM.len()
                    + MB_LOADS_NM.len()) as u64,
            );
            return Ok((None, v));
        }
    };
    let sc = &d.scene.scene;
    let fp = d.g.side(sc.loaded_flank);
    let rs = roll_surface(fp, &sc.utca)?;
    let sweep = scene_sweep(&d.scene, &d.g, Blank::Standard);
    let mut cells = Vec::new();

    // Loads.
    let (loads, edge_at, largest) = load_cells(&name, &d.g.data, fp, &rs, &pc, &sweep, bar);
    loads.iter().for_each(|c| log_cell(bar, c));
    cells.extend(loads);

    // Slices.
    for n in SLICES {
        let mut c = cell(&name, Study::Slices, n as f64, "", format!("{n}"));
        let sw = Sweep { slices: n, ..sweep };
        match run_sweep(fp, &rs, &pc, &sw, &[PROBE_NM]) {
            Ok(res) => ltca_record(&mut c, &res, 0, PROBE_NM),
            Err(e) => c.outcome = classify(&e),
        }
        log_cell(bar, &c);
        cells.push(c);
        bar.inc(1);
    }

    // Stiffness grids: the cached files', and the grid scenes' of this design.
    let mut c = cell(
        &name,
        Study::Grid,
        (grid[0] * grid[1]) as f64,
        "",
        format!("{} × {}", grid[0], grid[1]),
    );
    match run_sweep(fp, &rs, &pc, &sweep, &[PROBE_NM]) {
        Ok(res) => ltca_record(&mut c, &res, 0, PROBE_NM),
        Err(e) => c.outcome = classify(&e),
    }
    cells.push(c);
    for gs in grid_scenes {
        if let Some(c) = grid_scene_cell(&d, gs, meshes)? {
            cells.push(c);
        }
    }
    bar.inc(1);

    // Coast flanks.
    let mut c = cell(&name, Study::Flank, 1.0, "", "coast".into());
    match coast_of(&d, meshes, coast_scenes)? {
        Err(e) => c.outcome = Outcome::Skipped(format!("{e:#}")),
        Ok(cpc) => {
            let side = sc.loaded_flank.other();
            let cfp = d.g.side(side);
            match roll_surface(cfp, &sc.utca) {
                Err(e) => c.outcome = Outcome::Failed(e.to_string()),
                Ok(crs) => match run_sweep(
                    cfp,
                    &crs,
                    &cpc,
                    &coast_sweep(&sweep, &d.g, sc.loaded_flank),
                    &[PROBE_NM],
                ) {
                    Ok(res) => ltca_record(&mut c, &res, 0, PROBE_NM),
                    Err(e) => c.outcome = classify(&e),
                },
            }
        }
    }
    log_cell(bar, &c);
    cells.push(c);
    bar.inc(1);

    // Multibody.
    cells.extend(multibody_cells(&d, fp, &rs, &pc, inertia, bar));
    cells.extend(multibody_load_cells(&d, fp, &rs, &pc, inertia, bar));

    Ok((
        Some(DesignSummary {
            design: name,
            scene: d.scene.path.clone(),
            grid,
            positions: sweep.positions,
            edge_contact_torque_nm: edge_at.map(|e| e.0),
            edge_contact: edge_at.map(|e| e.1),
            largest_load_nm: largest,
        }),
        cells,
    ))
}

/// One line per finished cell (above the progress bar).
fn log_cell(bar: &ProgressBar, c: &Cell) {
    bar.suspend(|| {
        eprintln!(
            "stress {} · {} {}: {} ({:.2} s CPU{})",
            c.design,
            c.study.name(),
            c.label,
            Outcome::CLASSES[c.outcome.class()],
            c.cpu_s,
            c.steps.map_or(String::new(), |n| format!(", {n} steps"))
        )
    });
}

/// The outcome grid: one row per design and study.
fn chart(path: &Path, s: &StressSummary) -> anyhow::Result<()> {
    let mut rows: Vec<String> = Vec::new();
    let mut grid = Vec::new();
    for c in &s.cells {
        let label = row_label(&c.design, c.study);
        let row = match rows.iter().position(|r| *r == label) {
            Some(k) => k,
            None => {
                rows.push(label);
                rows.len() - 1
            }
        };
        let col = grid.iter().filter(|g: &&GridCell| g.row == row).count();
        grid.push(GridCell {
            row,
            col,
            class: c.outcome.class(),
            // Loads whose contact reaches an edge of the flank are marked.
            text: if c.edge_contact.is_some() {
                format!("{} · edge", c.label)
            } else {
                c.label.clone()
            },
        });
    }
    outcome_grid(
        path,
        &format!(
            "Stress matrix of {} and the seed pairs: outcome per cell (\"edge\": contact reaches an edge of the flank)",
            s.scene
        ),
        &rows,
        &Outcome::CLASSES,
        &grid,
    )?;
    Ok(())
}
