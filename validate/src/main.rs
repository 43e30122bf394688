//! `validate` command line.

use anyhow::Context;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "validate",
    version,
    about = "Independent checks and comparison reports"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// The whole validation report: loaded TE against the reference and the
    /// published tables, run times, unloaded TCA, the UTCA cross-check and
    /// the method notes (report.md, report.html, summary.json, results.md
    /// and the SVG figures), and the results table in the README.
    Report(ReportArgs),
    /// UTCA cross-check: the surface of roll angles against the direct
    /// contact search over one mesh cycle.
    Utca(UtcaArgs),
    /// Reference loaded TCA: fine FE bodies in penalty contact.
    Reference(ReferenceArgs),
    /// The reduced model's run time against its error to the reference, over
    /// the slices per tooth pair (needs `validate reference` results).
    Tradeoff(TradeoffArgs),
    /// The stress matrix (loads up to edge contact, slices, stiffness
    /// grids, flanks, multibody step, tolerance and speed) for the scene's
    /// design and the seed pairs beside it, on cached meshes and stiffness
    /// files: `<out>/<scene>/stress/summary.json` and `outcomes.svg`.
    Stress(StressArgs),
    /// Run time against error for every stage of the scene's design (UTCA,
    /// stiffness fields, LTCA, multibody, reference), as Pareto charts:
    /// `<out>/<scene>/tradeoff/` (summary.json, <stage>.json, <stage>.svg).
    StageTradeoffs(StageTradeoffsArgs),
    /// Mesh convergence of the reference LTCA: TE at one position and torque
    /// on three mesh levels (standard blanks), observed order, extrapolation.
    Convergence(ConvergenceArgs),
    /// Mesh stiffness at one position: the FE reference (smooth flanks) on
    /// the scene's mesh levels against our LTCA at the same position and
    /// torques, k = dF/dδ and F/δ; `<out>/<scene>/mesh_stiffness/summary.json`.
    MeshStiffness(MeshStiffnessArgs),
    /// The line-load check: a Hertzian line load on one pinion tooth,
    /// fine-mesh FE against the reduced model's global FE + Weber–Banaschek.
    LineLoad(LineLoadArgs),
}

#[derive(clap::Args)]
struct ReportArgs {
    /// Scene or design file.
    scene: PathBuf,
    /// Output directory of `preprocess flanks` (for the plots).
    #[arg(long)]
    flanks: PathBuf,
    /// Report directory.
    #[arg(long, default_value = "reports")]
    reports: PathBuf,
    /// Positions per mesh cycle for the direct search.
    #[arg(long, default_value_t = 12)]
    positions: usize,
    /// Output root of the solver and `validate reference`: when given, the
    /// report also compares their loaded TE (Tables 3-5).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Mesh root (for the convergence study's mesh check).
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    /// README whose text between `<!-- results:begin -->` and
    /// `<!-- results:end -->` is replaced by the results table (left
    /// alone without both markers).
    #[arg(long, default_value = "README.md")]
    readme: PathBuf,
}

#[derive(clap::Args)]
struct UtcaArgs {
    /// Scene or design file.
    scene: PathBuf,
    /// Positions per mesh cycle for the direct search.
    #[arg(long, default_value_t = 12)]
    positions: usize,
    /// Writes the comparison as one result set in this folder
    /// (`utca_check.json` and its `run.json`).
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(clap::Args)]
struct ReferenceArgs {
    /// Scene file.
    scene: PathBuf,
    /// Mesh directory (as written by `preprocess mesh`).
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    /// Output directory.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Mesh level of both bodies: reduced or reference.
    #[arg(long, default_value = "reduced")]
    level: String,
    /// Penalty ε = factor · E / (local face size).
    #[arg(long, default_value_t = 100.0)]
    penalty: f64,
    /// Second penalty factor, whose TE is compared.
    #[arg(long, default_value_t = 200.0)]
    penalty_check: f64,
    /// Constraints within this of the smallest initial gap start in the
    /// solve, um.
    #[arg(long, default_value_t = 2.0)]
    start_band_um: f64,
    /// Constraints are searched up to this initial gap and join the
    /// solve when they penetrate, um.
    #[arg(long, default_value_t = 60.0)]
    search_gap_um: f64,
    /// Solve every n-th position of the scene's sweep.
    #[arg(long, default_value_t = 1)]
    stride: usize,
    /// Stride for the lightweight wheel blank (default: --stride).
    #[arg(long)]
    stride_lightweight: Option<usize>,
    /// Right-hand sides per forward-solve block.
    #[arg(long, default_value_t = 96)]
    block: usize,
    /// Solve every cached position anew and compare it with the cache
    /// (relative tolerance 1e-6); writes compare_cache.json, exits
    /// non-zero on a difference.
    #[arg(long)]
    compare_cache: bool,
    /// Solve one shard of the sweep, I/N (positions i with i mod N = I),
    /// into the shared position cache.
    #[arg(long)]
    shard: Option<String>,
    /// Memory the bodies' factors may use, GB (default: what the system
    /// has available); the run refuses before factoring when the
    /// factors estimated from the meshes need more.
    #[arg(long)]
    memory_gb: Option<f64>,
}

#[derive(clap::Args)]
struct TradeoffArgs {
    /// Scene file.
    scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Slice counts per tooth pair.
    #[arg(long, value_delimiter = ',', default_value = "8,12,20,30,45,60")]
    slices: Vec<usize>,
}

#[derive(clap::Args)]
struct StressArgs {
    /// Scene file.
    scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Scenes of the same designs at other stiffness grids, their
    /// stiffness files in `meshes/` beside each or in `--meshes`.
    #[arg(long)]
    grid_scene: Vec<PathBuf>,
    /// Scenes of the same designs with coast-flank contact, whose
    /// coast stiffness files serve the coast cells.
    #[arg(long)]
    coast_scene: Vec<PathBuf>,
}

#[derive(clap::Args)]
struct StageTradeoffsArgs {
    /// Scene file.
    scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Scenes of the same design at other contact grids (their
    /// stiffness files in `meshes/` beside each, or in `--meshes`).
    #[arg(long)]
    grid_scene: Vec<PathBuf>,
}

#[derive(clap::Args)]
struct ConvergenceArgs {
    #[command(flatten)]
    study: LevelStudyArgs,
    /// Position index in the scene's sweep (its rotation steps).
    #[arg(long, default_value_t = 0)]
    position: usize,
    /// Pinion torques, N·m (default: the scene's loads).
    #[arg(long, value_delimiter = ',')]
    torque_nm: Vec<f64>,
}

#[derive(clap::Args)]
struct MeshStiffnessArgs {
    #[command(flatten)]
    study: LevelStudyArgs,
    /// Position index in the scene's sweep (default: the middle of the
    /// longest run with the fewest tooth pairs in contact).
    #[arg(long)]
    position: Option<usize>,
    /// Memory the two FE factors may take together, GB (default: what
    /// the system has available); a level estimated above it is skipped.
    #[arg(long)]
    memory_gb: Option<f64>,
    /// The lumped scene whose reduced meshes and roughness grades the
    /// study relates to.
    #[arg(long)]
    lumped_scene: Option<PathBuf>,
}

#[derive(clap::Args)]
struct LineLoadArgs {
    /// Scene file.
    scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Fine mesh levels.
    #[arg(long, value_delimiter = ',', default_value = "medium,reference")]
    levels: Vec<String>,
    /// Hertz half-widths, mm.
    #[arg(long, value_delimiter = ',', default_value = "0.25,0.5,1.0")]
    half_width_mm: Vec<f64>,
    /// Line load, N/mm.
    #[arg(long, default_value_t = 100.0)]
    line_load_n_per_mm: f64,
    /// Profile row of the contact grid (default: the middle one).
    #[arg(long)]
    row: Option<usize>,
    /// Grid columns at the toe and at the heel left out of the statistics.
    #[arg(long, default_value_t = 2)]
    end_columns: usize,
}

/// What the studies on one position over mesh levels share.
#[derive(clap::Args)]
struct LevelStudyArgs {
    /// Scene file.
    scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// Mesh levels, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "reduced,medium,reference"
    )]
    levels: Vec<String>,
    /// Penalty ε = factor · E / (local face size).
    #[arg(long, default_value_t = 100.0)]
    penalty: f64,
    /// Second penalty factor, whose result is compared.
    #[arg(long, default_value_t = 200.0)]
    penalty_check: f64,
    /// Right-hand sides per forward-solve block.
    #[arg(long, default_value_t = 96)]
    block: usize,
}

impl LevelStudyArgs {
    /// The scene loaded, the penalty settings and `--block`, checked.
    fn checked(
        &self,
    ) -> anyhow::Result<(
        geometry::scene::LoadedScene,
        validate::reference::reference_ltca::ReferenceSettings,
        usize,
    )> {
        Ok((
            geometry::scene::Scene::load(&self.scene)?,
            penalty_settings(self.penalty, self.penalty_check, 2.0, 60.0)?,
            check_block(self.block)?,
        ))
    }
}

/// `--block` within [1, 100000] right-hand sides.
fn check_block(block: usize) -> anyhow::Result<usize> {
    if !(1..=100_000).contains(&block) {
        anyhow::bail!("--block {block}: must lie in [1, 100000] right-hand sides");
    }
    Ok(block)
}

/// `--memory-gb` (positive) in bytes.
fn memory_bytes(memory_gb: Option<f64>) -> anyhow::Result<Option<usize>> {
    match memory_gb {
        Some(gb) if !(gb.is_finite() && gb > 0.0) => {
            anyhow::bail!("--memory-gb = {gb}: must be a positive number of GB")
        }
        gb => Ok(gb.map(|gb| (gb * 1e9) as usize)),
    }
}

/// Checks the penalty factors (positive, finite).
fn penalty_settings(
    penalty: f64,
    penalty_check: f64,
    start_band_um: f64,
    search_gap_um: f64,
) -> anyhow::Result<validate::reference::reference_ltca::ReferenceSettings> {
    for (field, v) in [
        ("--penalty", penalty),
        ("--penalty-check", penalty_check),
        ("--start-band-um", start_band_um),
        ("--search-gap-um", search_gap_um),
    ] {
        if !(v.is_finite() && v > 0.0) {
            anyhow::bail!("{field} {v}: must be a positive number");
        }
    }
    Ok(validate::reference::reference_ltca::ReferenceSettings {
        penalty_factor: penalty,
        penalty_factor_check: penalty_check,
        start_band_m: start_band_um * 1e-6,
        search_gap_m: search_gap_um * 1e-6,
    })
}

fn main() -> anyhow::Result<()> {
    // Ctrl-C / SIGTERM: remove this run's unfinished output, then exit 130.
    formats::interrupt::install();
    match Cli::parse().cmd {
        Cmd::Report(a) => report(a)?,
        Cmd::Utca(a) => utca(a)?,
        Cmd::Reference(a) => reference(a)?,
        Cmd::Stress(a) => stress(a)?,
        Cmd::StageTradeoffs(a) => stage_tradeoffs(a)?,
        Cmd::Tradeoff(a) => tradeoff(a)?,
        Cmd::Convergence(a) => convergence(a)?,
        Cmd::MeshStiffness(a) => mesh_stiffness(a)?,
        Cmd::LineLoad(a) => line_load(a)?,
    }
    Ok(())
}

/// `I/N` with N ≥ 1 and I < N.
fn parse_shard(s: &str) -> anyhow::Result<(usize, usize)> {
    let bad =
        || anyhow::anyhow!("--shard {s}: must be I/N with whole numbers N >= 1 and 0 <= I < N");
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

fn report(
    ReportArgs {
        scene,
        flanks,
        reports,
        positions,
        out,
        meshes,
        readme,
    }: ReportArgs,
) -> anyhow::Result<()> {
    let made = validate::report::run::run(&validate::report::run::ReportInputs {
        scene: &scene,
        flanks: &flanks,
        reports: &reports,
        positions,
        out: out.as_deref(),
        meshes: &meshes,
        readme: &readme,
    })?;
    println!(
        "report of scene {}: {} loaded TE rows, {} figures; reports in {}{}",
        made.scene,
        made.loaded_te_rows,
        made.figures,
        reports.display(),
        if made.readme_updated {
            format!("; results table in {}", readme.display())
        } else {
            String::new()
        }
    );
    Ok(())
}

fn utca(
    UtcaArgs {
        scene,
        positions,
        out,
    }: UtcaArgs,
) -> anyhow::Result<()> {
    let input = preprocess::flank_stage::load_input(&scene)?;
    let c = validate::studies::utca_check::check(&input, positions).context("UTCA cross-check")?;
    println!("pinion rotation, deg | fast TE, urad | direct TE, urad | difference, urad");
    for r in &c.rows {
        println!(
            "{:20.2} | {:13.4} | {:15.4} | {:+16.4}",
            r.pinion_rotation_deg, r.fast_te_urad, r.direct_te_urad, r.difference_urad
        );
    }
    println!(
        "UTCA cross-check, scene {} ({} flank): {} positions, max |fast - direct| = {:.4} urad, smallest gap {:.2e} um; TE ptp {:.2} urad, mean {:.2} urad; {:.3} ms/position (direct search {:.1} ms)",
        c.name,
        c.side,
        c.rows.len(),
        c.max_abs_difference_urad,
        c.min_gap_um,
        c.fast_te_ptp_urad,
        c.fast_te_mean_urad,
        c.fast_ms_per_position,
        c.direct_ms_per_position
    );
    if let Some(dir) = out {
        validate::studies::utca_check::write_set(&c, &scene, &input.design_path, &dir)?;
        println!("written {}", dir.join("utca_check.json").display());
    }
    Ok(())
}

fn reference(
    ReferenceArgs {
        scene,
        meshes,
        out,
        level,
        penalty,
        penalty_check,
        start_band_um,
        search_gap_um,
        stride,
        stride_lightweight,
        block,
        compare_cache,
        shard,
        memory_gb,
    }: ReferenceArgs,
) -> anyhow::Result<()> {
    if !["reduced", "medium", "reference"].contains(&level.as_str()) {
        anyhow::bail!("--level {level}: must be reduced, medium or reference");
    }
    check_block(block)?;
    let shard = shard.map(|s| parse_shard(&s)).transpose()?;
    let memory_bytes = memory_bytes(memory_gb)?;
    let settings = penalty_settings(penalty, penalty_check, start_band_um, search_gap_um)?;
    let sc = geometry::scene::Scene::load(&scene)?;
    let opt = validate::reference::reference_stage::StageOptions {
        level,
        settings,
        stride,
        stride_lightweight,
        block,
        compare_cache,
        shard,
        memory_bytes,
    };
    validate::reference::reference_stage::run(&sc, &meshes, &out, &opt)?;
    Ok(())
}

fn stress(
    StressArgs {
        scene,
        meshes,
        out,
        grid_scene,
        coast_scene,
    }: StressArgs,
) -> anyhow::Result<()> {
    let sc = geometry::scene::Scene::load(&scene)?;
    let s = validate::studies::stress::run(&sc, &meshes, &out, &grid_scene, &coast_scene)?;
    let n = |k: usize| s.cells.iter().filter(|c| c.outcome.class() == k).count();
    println!(
        "stress {}: {} cells, {} converged, {} refused, {} failed, {} skipped, {:.0} s",
        s.scene,
        s.cells.len(),
        n(0),
        n(1),
        n(2),
        n(3),
        s.wall_s
    );
    for d in &s.designs {
        match &d.edge_contact {
            Some(e) => println!(
                "  {}: edge contact from {} N·m ({}, pinion rotation {:.2}°)",
                d.design,
                d.edge_contact_torque_nm.unwrap_or(f64::NAN),
                e.edge.name(),
                e.pinion_rotation_deg
            ),
            None => println!(
                "  {}: no edge contact up to {} N·m",
                d.design, d.largest_load_nm
            ),
        }
    }
    Ok(())
}

fn stage_tradeoffs(
    StageTradeoffsArgs {
        scene,
        meshes,
        out,
        grid_scene,
    }: StageTradeoffsArgs,
) -> anyhow::Result<()> {
    let sc = geometry::scene::Scene::load(&scene)?;
    let s = validate::studies::stage_tradeoffs::run(&sc, &meshes, &out, &grid_scene)?;
    for st in &s.stages {
        println!(
            "{:24} {} points, {} not run: {}",
            st.stage,
            st.points.len(),
            st.not_run.len(),
            st.verdict()
        );
    }
    for (stage, why) in &s.missing {
        println!("{stage:24} not run: {why}");
    }
    println!("trade-off {}: {:.0} s", s.scene, s.wall_s);
    Ok(())
}

fn tradeoff(
    TradeoffArgs {
        scene,
        meshes,
        out,
        slices,
    }: TradeoffArgs,
) -> anyhow::Result<()> {
    if let Some(n) = slices.iter().find(|n| !(4..=400).contains(*n)) {
        anyhow::bail!("--slices {n}: must lie in [4, 400] (as ltca.slices)");
    }
    let sc = geometry::scene::Scene::load(&scene)?;
    let pts = validate::studies::tradeoff::run(&sc, &meshes, &out, &slices)?;
    for p in &pts {
        println!(
            "{:11} {:3} slices {:5} N m: mean {:+.3} %, ptp {:+.2} %, {:.2} ms/position",
            p.wheel_blank,
            p.slices,
            p.torque_nm,
            p.mean_error_pct,
            p.ptp_error_pct,
            p.s_per_position * 1e3
        );
    }
    Ok(())
}

fn convergence(
    ConvergenceArgs {
        study: args,
        position,
        torque_nm,
    }: ConvergenceArgs,
) -> anyhow::Result<()> {
    let (sc, settings, block) = args.checked()?;
    let torques_nm = if torque_nm.is_empty() {
        sc.scene.pinion_torque_nm.clone()
    } else {
        torque_nm
    };
    if let Some(t) = torques_nm.iter().find(|t| !(t.is_finite() && **t > 0.0)) {
        anyhow::bail!("--torque-nm {t}: must be a positive number");
    }
    let study = validate::studies::convergence::Study {
        levels: args.levels.clone(),
        position,
        torques_nm,
        settings,
        block,
    };
    let c = validate::studies::convergence::run(&sc, &args.meshes, &args.out, &study)?;
    for (i, t) in c.torques.iter().enumerate() {
        println!("{} N m:", t.torque_nm);
        for (l, e) in c.levels.iter().zip(&t.error_to_extrapolation_pct) {
            println!(
                "  {:9} {:3} x {:3}: TE {:.3} urad, {} vs extrapolation",
                l.level,
                l.profile_elements,
                l.face_elements,
                l.te_urad[i],
                e.map_or("-".into(), |e| format!("{e:+.3} %"))
            );
        }
        match (t.observed_order, t.extrapolated_te_urad) {
            (Some(p), Some(x)) => println!(
                "  observed order {p:.2}, extrapolated TE {x:.3} urad; reduced model {:.3} urad ({:+.3} %)",
                t.reduced_model_te_urad,
                t.reduced_model_error_pct.unwrap_or(f64::NAN)
            ),
            _ => println!(
                "  no monotone convergence over these levels: no extrapolation; reduced model {:.3} urad",
                t.reduced_model_te_urad
            ),
        }
    }
    Ok(())
}

fn mesh_stiffness(
    MeshStiffnessArgs {
        study: args,
        position,
        memory_gb,
        lumped_scene,
    }: MeshStiffnessArgs,
) -> anyhow::Result<()> {
    let (sc, settings, block) = args.checked()?;
    let memory_bytes = memory_bytes(memory_gb)?;
    let study = validate::studies::mesh_stiffness::StiffnessStudy {
        levels: args.levels.clone(),
        position,
        settings,
        block,
        memory_bytes,
        lumped_scene,
    };
    let s = validate::studies::mesh_stiffness::run(&sc, &args.meshes, &args.out, &study)?;
    println!(
        "mesh stiffness {}: position {} ({:.2} deg), {}",
        s.scene, s.position_index, s.pinion_rotation_deg, s.position_choice
    );
    for t in &s.torques {
        println!(
            "{} N m (levers {:.2} / {:.2} mm):",
            t.torque_nm,
            t.levers_m[0] * 1e3,
            t.levers_m[1] * 1e3
        );
        for m in &t.models {
            println!(
                "  {:4} {:9} {:2} x {:2}: k = dF/dd {:.4e} N/m, F/d {:.4e} N/m, vs finest FE {}",
                m.model,
                m.level,
                m.elements[0],
                m.elements[1],
                m.tangent_n_per_m,
                m.secant_n_per_m,
                m.tangent_vs_finest_fe_pct
                    .map_or("-".into(), |p| format!("{p:+.2} %"))
            );
        }
    }
    for (l, why) in s.fe_levels_skipped.iter().chain(&s.ltca_levels_skipped) {
        println!("  skipped {l}: {why}");
    }
    println!("{:.0} s, peak {:.2} GB", s.wall_s, s.peak_memory_gb);
    Ok(())
}

fn line_load(
    LineLoadArgs {
        scene,
        meshes,
        out,
        levels,
        half_width_mm,
        line_load_n_per_mm,
        row,
        end_columns,
    }: LineLoadArgs,
) -> anyhow::Result<()> {
    if let Some(b) = half_width_mm.iter().find(|b| !(b.is_finite() && **b > 0.0)) {
        anyhow::bail!("--half-width-mm {b}: must be a positive number");
    }
    if !(line_load_n_per_mm.is_finite() && line_load_n_per_mm > 0.0) {
        anyhow::bail!("--line-load-n-per-mm {line_load_n_per_mm}: must be a positive number");
    }
    let sc = geometry::scene::Scene::load(&scene)?;
    let study = validate::studies::line_load::LineLoadStudy {
        levels,
        half_widths: half_width_mm.iter().map(|b| b * 1e-3).collect(),
        q: line_load_n_per_mm * 1e3,
        row,
        end_columns,
    };
    let r = validate::studies::line_load::run(&sc, &meshes, &out, &study)?;
    for l in &r.levels {
        for c in &l.cases {
            println!(
                "{:9} b = {:.3} mm ({:.1} elements across): global FE + WB against FE: mean |{:.2}| %, max |{:.2}| % over columns {}..={}",
                l.level,
                c.half_width_mm,
                c.elements_across,
                c.mean_abs_difference_pct,
                c.max_abs_difference_pct,
                r.compared_columns[0],
                r.compared_columns[r.compared_columns.len() - 1]
            );
        }
    }
    Ok(())
}
