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

use crate::studies::grid_scenes::GridScene;
use anyhow::Context;
use charts::{outcome_grid, GridCell};
use formats::output::write_json;
use formats::result_set::ResultSet;
use formats::summaries::EdgeContact;
use geometry::design::{Member, PairData};
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::{roll_surface, RollSurface};
use indicatif::{ProgressBar, ProgressStyle};
use serde::{Deserialize, Serialize};
use solver::cpu_clock::{thread_cpu_s, timed};
use solver::element::compliance::PairCompliance;
use solver::ltca::{run as run_sweep, PositionResult, Sweep};
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{Drive, Model};
use solver::multibody::time_step::{discrete_gradient, integrate, Integrator, Scheme, StepControl};
use solver::stage::context::{coast_compliance, coast_sweep, scene_sweep};
use solver::stage::ltca::first_edge_contact;
use solver::SolverError;
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

/// What a cell varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Study {
    Load,
    Slices,
    Grid,
    Flank,
    MaxStep,
    Tolerance,
    Speed,
    MultibodyLoad,
}

impl Study {
    pub const ALL: [Study; 8] = [
        Study::Load,
        Study::Slices,
        Study::Grid,
        Study::Flank,
        Study::MaxStep,
        Study::Tolerance,
        Study::Speed,
        Study::MultibodyLoad,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Study::Load => "load",
            Study::Slices => "slices",
            Study::Grid => "stiffness grid",
            Study::Flank => "flank",
            Study::MaxStep => "multibody max step",
            Study::Tolerance => "multibody tolerance",
            Study::Speed => "pinion speed",
            Study::MultibodyLoad => "multibody load",
        }
    }
}

/// A cell's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "message", rename_all = "snake_case")]
pub enum Outcome {
    Converged,
    /// Refused by a check of the input, naming field, value and limit.
    Refused(String),
    /// An error in the run itself (no convergence, a singular system, ...).
    Failed(String),
    /// Not run: its inputs (meshes, stiffness files) are not cached.
    Skipped(String),
}

impl Outcome {
    pub fn class(&self) -> usize {
        match self {
            Outcome::Converged => 0,
            Outcome::Refused(_) => 1,
            Outcome::Failed(_) => 2,
            Outcome::Skipped(_) => 3,
        }
    }
    pub const CLASSES: [&'static str; 4] =
        ["converged", "refused", "failed", "skipped (not cached)"];
}

/// One cell of the matrix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// Scene name of the design.
    pub design: String,
    pub study: Study,
    /// The varied value, in `unit`.
    pub value: f64,
    pub unit: String,
    pub label: String,
    pub outcome: Outcome,
    /// LTCA: largest fixed-point iteration count over the positions;
    /// multibody: Newton iterations of the run.
    pub iterations: Option<usize>,
    /// LTCA: largest number of active-set changes over the positions.
    pub active_set_changes: Option<usize>,
    /// Multibody: accepted and rejected steps.
    pub steps: Option<usize>,
    pub rejected_steps: Option<usize>,
    /// Multibody: simulated time, s.
    #[serde(default)]
    pub sim_time_s: Option<f64>,
    /// A NaN or an infinity in any output of the cell.
    pub non_finite: bool,
    /// LTCA: largest |Σ λ₁F − T| / T over the positions (N·m at T = 0).
    pub torque_balance: Option<f64>,
    /// LTCA: every slice force ≥ 0.
    pub compressive_only: Option<bool>,
    /// Load study: TE at this load ≥ at the next lighter one, every
    /// position (None for the lightest).
    pub te_monotonic: Option<bool>,
    pub te_mean_urad: Option<f64>,
    /// Undamped multibody runs: largest |E(t) − E(0)| over the kinetic
    /// energy at the start plus the work the pinion torque does in the run.
    pub energy_drift: Option<f64>,
    /// LTCA: the first position whose contact reaches an edge of the flank.
    pub edge_contact: Option<EdgeContact>,
    /// Load study: the largest loaded deflection over the positions, as an
    /// arc at the wheel's mean pitch radius, (TE − unloaded TE) r₂ₘ, over
    /// the thinner member's mean normal tooth thickness (above
    /// [`DEFLECTION_LIMIT`]: implausible, see there).
    #[serde(default)]
    pub deflection_to_thickness: Option<f64>,
    /// CPU time of the cell, s (LTCA: all positions' threads).
    pub cpu_s: f64,
}

/// Per design.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DesignSummary {
    pub design: String,
    pub scene: PathBuf,
    /// Contact grid (profile × face) of its cached stiffness files.
    pub grid: [u32; 2],
    pub positions: usize,
    /// Smallest load of the load study with edge contact, and where.
    pub edge_contact_torque_nm: Option<f64>,
    pub edge_contact: Option<EdgeContact>,
    /// Largest load run.
    pub largest_load_nm: f64,
}

/// `summary.json` of the stress set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StressSummary {
    pub scene: String,
    pub designs: Vec<DesignSummary>,
    pub cells: Vec<Cell>,
    pub wall_s: f64,
}

impl StressSummary {
    /// Reads `<out>/<scene>/stress/summary.json`; None where absent.
    pub fn read(out: &Path, scene: &str) -> anyhow::Result<Option<StressSummary>> {
        let p = out.join(scene).join("stress").join("summary.json");
        match std::fs::read_to_string(&p) {
            Ok(t) => Ok(Some(
                serde_json::from_str(&t).with_context(|| format!("reading {}", p.display()))?,
            )),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(e).with_context(|| format!("reading {}", p.display())),
        }
    }
}

/// A refusal (a check of the input) or a failure of the run.
pub fn classify(e: &SolverError) -> Outcome {
    match e {
        SolverError::Torque(_) | SolverError::Table(_) | SolverError::ToothNotSolved { .. } => {
            Outcome::Refused(e.to_string())
        }
        _ => Outcome::Failed(e.to_string()),
    }
}

/// A converged cell of `design` with nothing measured yet.
pub fn cell(design: &str, study: Study, value: f64, unit: &str, label: String) -> Cell {
    Cell {
        design: design.to_string(),
        study,
        value,
        unit: unit.to_string(),
        label,
        outcome: Outcome::Converged,
        iterations: None,
        active_set_changes: None,
        steps: None,
        rejected_steps: None,
        sim_time_s: None,
        non_finite: false,
        torque_balance: None,
        compressive_only: None,
        te_monotonic: None,
        te_mean_urad: None,
        energy_drift: None,
        edge_contact: None,
        deflection_to_thickness: None,
        cpu_s: 0.0,
    }
}

/// Fills `c` from the sweep `res` at torque index `i` (torque `t`).
pub fn ltca_record(c: &mut Cell, res: &[PositionResult], i: usize, t: f64) {
    let loads = res.iter().map(|p| &p.loads[i]);
    c.iterations = loads.clone().map(|l| l.iterations).max();
    c.active_set_changes = loads.clone().map(|l| l.active_set_changes).max();
    c.non_finite = loads.clone().any(|l| {
        !l.finite
            || !l.max_pressure_pa.is_finite()
            || !l.wheel_torque_nm.is_finite()
            || l.slices.iter().any(|s| !s.half_width_m.is_finite())
    });
    let scale = if t > 0.0 { t } else { 1.0 };
    c.torque_balance = Some(
        loads
            .clone()
            .map(|l| l.torque_residual_nm.abs() / scale)
            .fold(
                0.0,
                |a: f64, b| if b.is_nan() { f64::NAN } else { a.max(b) },
            ),
    );
    c.compressive_only = Some(loads.clone().all(|l| l.min_force_n >= 0.0));
    c.te_mean_urad = Some(loads.clone().map(|l| l.te).sum::<f64>() / res.len().max(1) as f64 * 1e6);
    c.edge_contact = first_edge_contact(res, i);
    let n_t = res.first().map_or(1, |p| p.loads.len()) as f64;
    c.cpu_s = res
        .iter()
        .map(|p| p.loads[i].solve_s + (p.geometry_s + p.assembly_s) / n_t)
        .sum();
}

/// The largest loaded deflection at torque index `i` over the thinner
/// member's normal tooth thickness (see [`Cell::deflection_to_thickness`]).
pub fn deflection_to_thickness(res: &[PositionResult], i: usize, pair: &PairData) -> f64 {
    let r2 = pair.mean_cone_distance * pair.members[1].pitch_angle.sin();
    let s = pair
        .normal_thickness(Member::Pinion)
        .min(pair.normal_thickness(Member::Wheel));
    res.iter()
        .map(|p| (p.loads[i].te - p.utca_te) * r2)
        .fold(0.0, f64::max)
        / s
}

/// Where TE at torque index `i` < TE at `i − 1` anywhere (beyond rounding).
fn te_decreases(res: &[PositionResult], i: usize) -> bool {
    res.iter()
        .any(|p| p.loads[i].te < p.loads[i - 1].te - TE_DECREASE_TOL)
}

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

type EdgeAt = Option<(f64, EdgeContact)>;

/// The standard blanks' coast-flank compliance of `d`'s design: from its own
/// stiffness files, else from the first of `coast_scenes` with its design
/// (an outer error: a coast scene that does not load).
fn coast_of(
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
fn load_cells(
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
fn grid_scene_cell(d: &Design, path: &Path, meshes: &Path) -> anyhow::Result<Option<Cell>> {
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

/// The multibody cells of a design (see the module's notes).
fn multibody_cells(
    d: &Design,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    inertia: [f64; 2],
    bar: &ProgressBar,
) -> Vec<Cell> {
    let name = d.name();
    let tau = d.g.data.mesh_cycle();
    let mut specs: Vec<(Study, f64, &str, String, f64, f64, f64)> = Vec::new();
    for h in MAX_STEPS_S {
        specs.push((
            Study::MaxStep,
            h,
            "s",
            format!("{h:e} s"),
            STEP_STUDY_RPM,
            h,
            STUDY_TOLERANCE_RAD,
        ));
    }
    for tol in TOLERANCES_RAD {
        specs.push((
            Study::Tolerance,
            tol * 1e6,
            "µrad",
            format!("{:e} µrad", tol * 1e6),
            STEP_STUDY_RPM,
            STUDY_MAX_STEP_S,
            tol,
        ));
    }
    for rpm in SPEEDS_RPM {
        specs.push((
            Study::Speed,
            rpm,
            "rpm",
            format!("{rpm} rpm"),
            rpm,
            STUDY_MAX_STEP_S,
            STUDY_TOLERANCE_RAD,
        ));
    }
    let (table, build_s) = timed(|| probe_table(&d.scene, &d.g, fp, rs, pc, PROBE_NM));
    let mut cells = Vec::new();
    for (study, value, unit, label, rpm, max_step, tol) in specs {
        let mut c = cell(name, study, value, unit, label);
        match &table {
            Err(e) => c.outcome = classify(e),
            Ok(table) => {
                let cpu0 = thread_cpu_s();
                if let Err(e) = free_run(&mut c, table, inertia, tau, rpm, max_step, tol) {
                    c.outcome = classify(&e);
                }
                c.cpu_s = thread_cpu_s() - cpu0 + build_s / 14.0;
            }
        }
        log_cell(bar, &c);
        cells.push(c);
        bar.inc(1);
    }
    cells
}

/// The scene's contact-element table over one mesh cycle (periodic, the
/// scene's table step, lag nodes and slices), standard blanks, covering
/// `torque_nm` × `multibody.table_torque_factor`.
pub fn probe_table(
    scene: &LoadedScene,
    g: &PairGeometry,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    torque_nm: f64,
) -> Result<MeshTable, SolverError> {
    let sc = &scene.scene;
    let mb = &sc.multibody;
    let tau = g.data.mesh_cycle();
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    let sweep = scene_sweep(scene, g, Blank::Standard);
    let per_cycle = (tau / mb.table_step_deg.to_radians()).round().max(8.0) as usize;
    MeshTable::build(
        fp,
        rs,
        pc,
        &g.frames[0],
        ratio,
        TableSpec {
            start: sweep.start,
            direction: sweep.direction,
            step: tau / per_cycle as f64,
            positions: per_cycle,
            periodic: true,
            slices: sc.ltca.slices,
            lag_nodes: mb.table_lag_nodes,
            torque_max_nm: torque_nm * mb.table_torque_factor,
        },
    )
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

/// One undamped free run over a mesh cycle at `rpm` (see the module).
fn free_run(
    c: &mut Cell,
    table: &MeshTable,
    inertia: [f64; 2],
    tau: f64,
    rpm: f64,
    max_step: f64,
    tolerance: f64,
) -> Result<(), SolverError> {
    let r = table.ratio;
    let m = Model {
        table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::Free {
            pinion_torque: PROBE_NM,
            wheel_torque: PROBE_NM / r,
        },
    };
    let w1 = rpm * std::f64::consts::PI / 30.0;
    let mut s = m.static_state(0.0)?;
    s.v = [w1, r * w1];
    let t_end = (tau / w1).min(MAX_RUN_S);
    let e0 = m.energy(&s)?;
    let scale = 0.5 * (inertia[0] * w1 * w1 + inertia[1] * (r * w1).powi(2)) + PROBE_NM * tau;
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step,
            min_step: max_step * 1e-6,
            tolerance,
        },
    );
    let (mut drift, mut finite, mut te_sum, mut n) = (0.0f64, true, 0.0, 0usize);
    let (_, steps) = integrate(&m, s, &mut integ, t_end, |s| {
        if n > MAX_RUN_STEPS {
            return Err(SolverError::NotConverged {
                what: format!(
                    "the run of {t_end:.3e} s at t = {:.3e} s, more than {MAX_RUN_STEPS} steps",
                    s.t
                ),
                iterations: n,
            });
        }
        let e = m.energy(s)?;
        finite &= e.is_finite() && s.q.iter().chain(&s.v).chain(&s.a).all(|x| x.is_finite());
        drift = drift.max((e - e0).abs());
        te_sum += r * s.q[0] - s.q[1];
        n += 1;
        Ok(())
    })?;
    c.steps = Some(steps);
    c.sim_time_s = Some(t_end);
    c.rejected_steps = Some(integ.rejected);
    c.iterations = Some(integ.newton_iterations);
    c.non_finite = !finite;
    c.energy_drift = Some(drift / scale);
    c.te_mean_urad = Some(te_sum / n.max(1) as f64 * 1e6);
    Ok(())
}

/// The multibody load cells: the pinion at [`STEP_STUDY_RPM`] (imposed),
/// the wheel resisting each torque of [`MB_LOADS_NM`] (as a pinion torque),
/// undamped, frictionless, over one mesh cycle from the static state, on a
/// table covering the largest load. Without coast flanks a torque below the
/// holding torque (the wheel would run ahead at the tooth changes and leave
/// the mesh across the backlash, a rattle the model cannot follow) is
/// refused, naming the limit. Torque balance: the wheel's angular impulse
/// over the run, |Σ h (−ḡ₂) − T₂ t − J₂ Δω₂| / (max(T₂, 1 N·m) t), with
/// ḡ₂ the scheme's discrete gradient of the element's potential in each
/// accepted step ([`discrete_gradient`], the torque the integrator
/// applied; it is the element's pointwise torque −∂V/∂q₂ at the step's
/// midpoint to second order in the step).
fn multibody_load_cells(
    d: &Design,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    inertia: [f64; 2],
    bar: &ProgressBar,
) -> Vec<Cell> {
    let top = MB_LOADS_NM.iter().copied().fold(0.0, f64::max);
    let (table, build_s) = timed(|| probe_table(&d.scene, &d.g, fp, rs, pc, top));
    let mut cells = Vec::new();
    for t in MB_LOADS_NM {
        let mut c = cell(d.name(), Study::MultibodyLoad, t, "N·m", format!("{t} N·m"));
        match &table {
            Err(e) => c.outcome = classify(e),
            Ok(table) => {
                let cpu0 = thread_cpu_s();
                if let Err(e) = loaded_run(&mut c, table, inertia, d.g.data.mesh_cycle(), t) {
                    c.outcome = classify(&e);
                }
                c.cpu_s = thread_cpu_s() - cpu0 + build_s / MB_LOADS_NM.len() as f64;
            }
        }
        log_cell(bar, &c);
        cells.push(c);
        bar.inc(1);
    }
    cells
}

/// One run of [`multibody_load_cells`] into `c` (its torque balance, steps,
/// TE); a refusal or failure as the error.
pub fn loaded_run(
    c: &mut Cell,
    table: &MeshTable,
    inertia: [f64; 2],
    tau: f64,
    torque: f64,
) -> Result<(), SolverError> {
    let r = table.ratio;
    let w1 = STEP_STUDY_RPM * std::f64::consts::PI / 30.0;
    let wheel_torque = torque / r;
    let m = Model {
        table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::PinionSpeed {
            speed: solver::multibody::model::Ramp {
                from: w1,
                to: w1,
                duration: 0.0,
            },
            wheel_torque,
        },
    };
    let holding = m.holding_torque()?;
    if torque < holding {
        return Err(SolverError::Table(format!(
            "pinion torque {torque} N·m is below {holding:.3e} N·m, the torque that holds the wheel (inertia {:.4e} kg·m²) on the drive flanks at {STEP_STUDY_RPM} rpm; without coast flanks it would leave the mesh across the backlash (rattle), which this element cannot follow",
            inertia[1]
        )));
    }
    let s = m.static_state(0.0)?;
    let t_end = (tau / w1).min(MAX_RUN_S);
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step: STUDY_MAX_STEP_S,
            min_step: STUDY_MAX_STEP_S * 1e-6,
            tolerance: STUDY_TOLERANCE_RAD,
        },
    );
    let w2_0 = s.v[1];
    // The scheme's own wheel balance per step: J₂ (v⁺ − v) = −h T₂ − h ḡ₂,
    // ḡ the scheme's discrete gradient of V between the step's ends.
    let (mut impulse, mut last): (f64, Option<(f64, [f64; 2])>) = (0.0, None);
    let (mut finite, mut te_sum, mut n) = (true, 0.0, 0usize);
    let (end, steps) = integrate(&m, s, &mut integ, t_end, |s| {
        if let Some((t0, q0)) = last {
            let mid = [0.5 * (s.q[0] + q0[0]), 0.5 * (s.q[1] + q0[1])];
            let g = discrete_gradient(&m, q0, s.q, m.mesh(mid)?.0.grad)?[1];
            impulse -= g * (s.t - t0);
        }
        last = Some((s.t, s.q));
        finite &= s.q.iter().chain(&s.v).chain(&s.a).all(|x| x.is_finite());
        te_sum += r * s.q[0] - s.q[1];
        n += 1;
        Ok(())
    })?;
    let residual = impulse - wheel_torque * t_end - inertia[1] * (end.v[1] - w2_0);
    c.steps = Some(steps);
    c.sim_time_s = Some(t_end);
    c.rejected_steps = Some(integ.rejected);
    c.iterations = Some(integ.newton_iterations);
    c.non_finite = !finite;
    c.torque_balance = Some(residual.abs() / (wheel_torque.max(1.0) * t_end));
    c.te_mean_urad = Some(te_sum / n.max(1) as f64 * 1e6);
    Ok(())
}

/// Row label of a design's study.
pub fn row_label(design: &str, study: Study) -> String {
    format!("{design} · {}", study.name())
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
