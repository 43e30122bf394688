//! `validate reference <scene>`: the reference loaded TCA of every pinion ×
//! wheel blank of a scene, from the meshes of one level, to
//! `<out>/<scene>/reference/<pinion>_<wheel>/`: `te.csv` (TE per position
//! and torque), `pattern_<T>nm.csv` (contact pressure on the pinion flanks at
//! the largest torque) and `summary.json`. A run whose inputs (mesh files,
//! settings, positions, torques) hash to an existing summary reuses it.
//!
//! Each blank's solved positions are cached in `<blank>/positions/<key>/`,
//! shared by the runs of one sweep (shards write into it side by side, a
//! killed run resumes from it). The results of a run are one set
//! ([`formats::result_set`]):
//! - a run without `--shard` or `--compare-cache` takes the directory's
//!   lock, writes `te.csv`, the patterns and the summaries into a staging
//!   sibling (a reused blank's files copied over), moves the position
//!   caches into it and puts it in place whole with its `run.json`; a run
//!   that fails or is killed leaves the previous results as they were and
//!   the positions it solved in the cache;
//! - `--compare-cache` takes the same lock and writes only
//!   `compare_cache.json`, in place, recorded with its checksum and the
//!   `run.json` id of the set it checked ([`formats::added_files`]);
//! - `--shard` runs write only into the cache: they share a lock with
//!   each other, and are refused while a run holds the directory's lock
//!   (as that run is refused while shards run), so that no shard writes
//!   into a cache that a finishing run is moving.

pub use super::reference_outputs::pattern_vtu;
use super::reference_outputs::{
    copy_files, load_summaries, report_factor, unloaded_check, write_te_csv,
};
pub use super::reference_summary::{BlankSummary, CacheComparison, LoadSummary, UnloadedCheck};
use crate::reference::reference_ltca::{Member, PositionResult, ReferencePair, ReferenceSettings};
use anyhow::Context;
use formats::added_files::{add_json, Dependence};
use formats::columns;
use formats::output::{write_atomic, write_json};
use formats::paths::MeshLevel;
use formats::result_set::{ResultSet, RunLock};
use formats::stiffness_plan;
use geometry::design::Member as Which;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use preprocess::stiffness_stage::sha256_file;
use serde::Serialize;
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::path::Path;

/// Version of the reference computation (constraints, solve, position
/// results); part of every cache key. A summary of another layout fails to
/// parse and is rebuilt from the cached positions.
pub const REFERENCE_SCHEMA: u32 = 6;

/// Options of the stage.
#[derive(Debug, Clone, Serialize)]
pub struct StageOptions {
    /// Mesh level ("reduced" or "reference").
    pub level: String,
    pub settings: ReferenceSettings,
    /// Solve every n-th position of the scene's sweep.
    pub stride: usize,
    /// Stride for the lightweight wheel blank (its sweep is 2.5 times
    /// longer), when given.
    pub stride_lightweight: Option<usize>,
    /// Right-hand sides per forward-solve block.
    pub block: usize,
    /// Solve every position anew and compare it with its cached result
    /// (old and new solution paths must agree within
    /// [`COMPARE_TOLERANCE`]); the cache is left as it is.
    pub compare_cache: bool,
    /// Solve only the positions i with i mod N = I (`Some((I, N))`): one
    /// shard of a sweep split among processes or machines. Shards write
    /// their positions to the shared cache; a run without a shard then
    /// finds them all there and writes the result.
    pub shard: Option<(usize, usize)>,
    /// Memory this run may use for the bodies' factors, bytes; `None`:
    /// what the system has available (`MemAvailable`). The factors a run
    /// would hold at once are estimated from the meshes before any
    /// factoring and refused above it ([`formats::memory_estimate`]).
    pub memory_bytes: Option<usize>,
}

/// Largest relative difference that `--compare-cache` accepts between a
/// position solved now and its cached result.
pub const COMPARE_TOLERANCE: f64 = 1e-6;

/// Where the reference of mesh level `level` writes its results:
/// `<out>/<scene>/reference/` for the reduced level (the meshes of the
/// reduced model), `<out>/<scene>/reference_<level>/` for a finer one.
pub fn reference_dir(out: &Path, scene: &str, level: &str) -> std::path::PathBuf {
    match level {
        "reduced" => out.join(scene).join("reference"),
        l => out.join(scene).join(format!("reference_{l}")),
    }
}

/// Mesh levels of the reference, finest first.
pub const LEVELS_FINEST_FIRST: [&str; 3] = ["reference", "medium", "reduced"];

/// The results directory of blank combination `blank` (`<pinion>_<wheel>`)
/// at the finest mesh level that has a swept `te.csv`.
pub fn finest_reference(out: &Path, scene: &str, blank: &str) -> Option<std::path::PathBuf> {
    LEVELS_FINEST_FIRST
        .iter()
        .map(|l| reference_dir(out, scene, l).join(blank))
        .find(|d| d.join("te.csv").exists())
}

/// The UTCA of the scene's generated flanks (its own UTCA settings) at `n`
/// pinion angles from `start` in steps of `step`: the unloaded check's
/// reference.
pub fn utca_at(
    scene: &LoadedScene,
    fp: &geometry::pair::FlankPair,
    start: f64,
    step: f64,
    n: usize,
    direction: f64,
) -> anyhow::Result<geometry::utca::Utca> {
    let input = preprocess::flank_stage::load_input(&scene.path)?;
    let rs = geometry::utca::roll_surface(fp, &input.utca)?;
    Ok(geometry::utca::run(fp, &rs, start, step, n, direction))
}

fn blank_name(b: Blank) -> String {
    b.name().to_string()
}

/// Runs the reference LTCA of the scene.
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    opt: &StageOptions,
) -> anyhow::Result<Vec<BlankSummary>> {
    if !scene.scene.analyses.reference {
        eprintln!(
            "scene {}: `[analyses] reference = false`, no reference FE; skipped",
            scene.scene.name
        );
        return Ok(Vec::new());
    }
    let sc = &scene.scene;
    // Taken before any work (see the module documentation): the set of a
    // full run, or the lock of a cache comparison or of a shard.
    let ref_dir = reference_dir(out, &sc.name, &opt.level);
    let what = format!(
        "validate reference {} --level {}",
        scene.path.display(),
        opt.level
    );
    let (mut set, lock) = match opt.shard {
        Some((k, n)) => (
            None,
            Some(RunLock::shared(
                &ref_dir,
                &format!("{what} --shard {k}/{n}"),
            )?),
        ),
        None if opt.compare_cache => (
            None,
            Some(RunLock::exclusive(
                &ref_dir,
                &format!("{what} --compare-cache"),
            )?),
        ),
        None => (Some(ResultSet::begin(&ref_dir, &what)?), None),
    };
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    // The pinion's nodes are placed with the scene's misalignment; the
    // meshes are body-fixed and serve every pose.
    g.misalign(&sc.misalignment);
    if let Some(set) = set.as_mut() {
        if let Some(sha) = formats::manifest::misalignment_sha256(&sc.misalignment) {
            set.record_input("misalignment", &sha)?;
        }
    }
    let side = sc.loaded_flank;
    let fp = g.side(side);
    let direction = pinion_direction(&g.data, side);
    let step = sc.rotation.step_deg.to_radians();
    let dir = meshes.join(&sc.name);
    let cycles = |wb: Blank| sc.rotation.mesh_cycles(wb);
    let msh = |m: Which, b: Blank| {
        formats::paths::msh(&dir, &formats::paths::stem_named(m, b, &opt.level))
    };
    let mut pinion_teeth = std::collections::BTreeSet::new();
    for &wb in &sc.blanks.wheel {
        pinion_teeth.extend(teeth_in_contact(&g, side, cycles(wb), step).0);
    }
    let pinion_teeth: Vec<usize> = pinion_teeth.into_iter().collect();
    let mut all = Vec::new();
    for &pb in &sc.blanks.pinion {
        let mut pinion: Option<Member> = None;
        for &wb in &sc.blanks.wheel {
            let t0 = std::time::Instant::now();
            let name = format!("{}_{}", blank_name(pb), blank_name(wb));
            // The previous results and the position cache; this run's
            // results go to `sdir` in the staging directory (a full run).
            let odir = ref_dir.join(&name);
            let sdir = set.as_ref().map(|s| s.path().join(&name));
            let stride = match wb {
                Blank::Lightweight => opt.stride_lightweight.unwrap_or(opt.stride),
                _ => opt.stride,
            }
            .max(1);
            let n_pos = (cycles(wb) * g.data.mesh_cycle() / step).round() as usize + 1;
            let positions: Vec<f64> = (0..n_pos)
                .step_by(stride)
                .map(|i| fp.roll_range[0] + direction * step * i as f64)
                .collect();
            let (pm, wm) = (msh(Which::Pinion, pb), msh(Which::Wheel, wb));
            for p in [&pm, &wm] {
                if !p.exists() {
                    anyhow::bail!(
                        "scene {}: no mesh {}; run `preprocess mesh {} --level {}`",
                        sc.name,
                        p.display(),
                        scene.path.display(),
                        opt.level
                    );
                }
            }
            let (pm_hash, wm_hash) = (sha256_file(&pm)?, sha256_file(&wm)?);
            // The meshes are the mesh stage's for the scene's current
            // inputs, unchanged since; the set records what it read.
            let level = MeshLevel::FINEST_FIRST
                .into_iter()
                .find(|l| l.name() == opt.level)
                .with_context(|| format!("unknown mesh level {}", opt.level))?;
            let mut mesh_dofs = [0usize; 2];
            for (k, (m, b, path, hash)) in [
                (Which::Pinion, pb, &pm, &pm_hash),
                (Which::Wheel, wb, &wm, &wm_hash),
            ]
            .into_iter()
            .enumerate()
            {
                let stem = formats::paths::mesh_stem(m, b, level);
                let entry = stiffness_plan::check_mesh(scene, &g, &dir, &stem, m, b, level)
                    .with_context(|| {
                        format!(
                            "scene {}: the {} mesh {} does not serve the scene; run `preprocess mesh {} --level {}`",
                            sc.name,
                            m.name(),
                            path.display(),
                            scene.path.display(),
                            opt.level
                        )
                    })?;
                if &entry.msh_sha256 != hash {
                    return Err(stiffness_plan::CheckError::MeshChanged {
                        path: path.to_path_buf(),
                        found: hash.clone(),
                        listed: entry.msh_sha256,
                    }
                    .into());
                }
                mesh_dofs[k] = 3 * entry.body.nodes;
                if let Some(set) = set.as_mut() {
                    set.record_input("design", &entry.inputs.design_sha256)?;
                    set.record_input(&format!("mesh:{stem}"), hash)?;
                }
            }
            let digest = |key: serde_json::Value| {
                format!("{:x}", Sha256::digest(key.to_string().as_bytes()))
            };
            // What determines one position's result (not the stride).
            let mut key = serde_json::json!({
                "schema": REFERENCE_SCHEMA,
                "pinion_mesh": pm_hash,
                "wheel_mesh": wm_hash,
                "level": opt.level,
                "settings": opt.settings,
                "torques": sc.pinion_torque_nm,
                "flank": side.flank_name(Which::Pinion),
            });
            // Only a misaligned pair adds its pose: the aligned pair's
            // cached positions keep their keys.
            if !sc.misalignment.is_zero() {
                key["misalignment"] = serde_json::json!(sc.misalignment);
            }
            let position_key = digest(key);
            let hash = digest(serde_json::json!({
                "position_key": position_key,
                "positions": positions,
            }));
            let summary_path = odir.join("summary.json");
            let partial = opt.compare_cache || opt.shard.is_some();
            if let (false, Ok(text)) = (partial, std::fs::read_to_string(&summary_path)) {
                if let Ok(s) = serde_json::from_str::<BlankSummary>(&text) {
                    if s.input_hash == hash {
                        eprintln!(
                            "reference {name}: inputs unchanged, reusing {}",
                            summary_path.display()
                        );
                        if let Some(sdir) = &sdir {
                            copy_files(&odir, sdir)?;
                        }
                        all.push(s);
                        continue;
                    }
                }
            }
            // The UTCA TE at the same positions, for the unloaded check.
            let utca = utca_at(
                scene,
                fp,
                fp.roll_range[0],
                step * stride as f64,
                positions.len(),
                direction,
            )?;
            if let Some((a, b)) = utca
                .pinion_angle
                .iter()
                .zip(&positions)
                .find(|(a, b)| (*a - *b).abs() > 1e-12)
            {
                anyhow::bail!(
                    "internal: UTCA position {a} rad differs from reference position {b} rad"
                );
            }
            let cache_dir = odir.join("positions").join(&position_key[..16]);
            std::fs::create_dir_all(&cache_dir)?;
            let wheel_teeth = teeth_in_contact(&g, side, cycles(wb), step).1;
            let mut wheel: Option<Member> = None;
            let (mut rhs0, mut s0) = (0, 0.0);
            let bar = indicatif::ProgressBar::new(positions.len() as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "reference {msg} [{bar:30}] {pos}/{len} positions, eta {eta}",
                )?
                .progress_chars("=> "),
            );
            bar.set_message(name.clone());
            let t_sweep = std::time::Instant::now();
            let mut res = Vec::with_capacity(positions.len());
            let mut reused = 0;
            let mut comparison = CacheComparison {
                tolerance: COMPARE_TOLERANCE,
                ..Default::default()
            };
            for (i, &phi) in positions.iter().enumerate() {
                if opt.shard.is_some_and(|(k, n)| i % n != k) {
                    bar.inc(1);
                    continue;
                }
                let cached = cache_dir.join(format!(
                    "phi_{}udeg.json",
                    (phi.to_degrees() * 1e6).round() as i64
                ));
                let from_cache = std::fs::read_to_string(&cached)
                    .ok()
                    .and_then(|t| serde_json::from_str::<PositionResult>(&t).ok())
                    .filter(|r| r.loads.len() == sc.pinion_torque_nm.len());
                if opt.compare_cache && from_cache.is_none() {
                    comparison.positions_without_cache += 1;
                    bar.inc(1);
                    continue;
                }
                if let (false, Some(r)) = (opt.compare_cache, &from_cache) {
                    res.push(r.clone());
                    reused += 1;
                    bar.inc(1);
                    continue;
                }
                // Before the first factorization: the factors this run will
                // hold at once, estimated from the meshes' node counts
                // (unknown in manifests from before they were recorded).
                if pinion.is_none() || wheel.is_none() {
                    let mut parts = Vec::new();
                    if pinion.is_none() && mesh_dofs[0] > 0 {
                        parts.push(("pinion", mesh_dofs[0]));
                    }
                    if mesh_dofs[1] > 0 {
                        parts.push(("wheel", mesh_dofs[1]));
                    }
                    formats::memory_estimate::check_fits(
                        &what,
                        &parts,
                        opt.memory_bytes
                            .or_else(fem::cholesky::available_memory_bytes),
                    )?;
                }
                if pinion.is_none() {
                    eprintln!("reference: reading and factoring {}", pm.display());
                    pinion = Some(Member::load(
                        &pm,
                        &g,
                        Which::Pinion,
                        side,
                        &pinion_teeth,
                        opt.block,
                    )?);
                    report_factor("pinion", pinion.as_ref());
                }
                if wheel.is_none() {
                    eprintln!("reference: reading and factoring {}", wm.display());
                    wheel = Some(Member::load(
                        &wm,
                        &g,
                        Which::Wheel,
                        side,
                        &wheel_teeth,
                        opt.block,
                    )?);
                    report_factor("wheel", wheel.as_ref());
                    let pin = pinion.as_ref().expect("pinion factored above");
                    (rhs0, s0) = (pin.compliance.solves, pin.compliance.solve_s);
                }
                let mut pair = ReferencePair {
                    pinion: pinion.as_mut().expect("pinion factored above"),
                    wheel: wheel.as_mut().expect("wheel factored above"),
                    flanks: fp,
                    direction,
                    settings: opt.settings,
                };
                let r = pair.position(phi, &sc.pinion_torque_nm).with_context(|| {
                    format!(
                        "scene {}: reference LTCA {name} at pinion angle {:.3} deg",
                        sc.name,
                        phi.to_degrees()
                    )
                })?;
                match &from_cache {
                    Some(old) => comparison.add(&r, old),
                    None => write_json(&cached, &r)?,
                }
                if bar.is_hidden() {
                    eprintln!(
                        "reference {name}: position {}/{}: {} of {} constraints solved, {} new nodes, TE {:.2} urad at {} N m, {:.1} s",
                        i + 1,
                        positions.len(),
                        r.constraints,
                        r.searched,
                        r.new_columns,
                        r.loads.last().map_or(0.0, |l| l.te * 1e6),
                        r.loads.last().map_or(0.0, |l| l.torque_nm),
                        r.cpu_s
                    );
                }
                res.push(r);
                bar.inc(1);
            }
            bar.finish_and_clear();
            if opt.compare_cache {
                if let Some(lock) = &lock {
                    add_json(
                        lock,
                        &format!("{name}/compare_cache.json"),
                        &comparison,
                        Dependence::OnSet,
                    )?;
                }
                eprintln!(
                    "reference {name}: {} positions solved anew against the cache ({} not cached): largest relative difference {:.2e} (TE {:.2e}, check-penalty TE {:.2e}, max pressure {:.2e}, search margin {:.2e}; torque balance {:.2e}), {} with other constraint counts",
                    comparison.positions_compared,
                    comparison.positions_without_cache,
                    comparison.worst(),
                    comparison.te,
                    comparison.te_check,
                    comparison.max_pressure,
                    comparison.search_margin,
                    comparison.torque_balance_abs,
                    comparison.count_mismatches
                );
                if comparison.worst() > COMPARE_TOLERANCE || comparison.count_mismatches > 0 {
                    anyhow::bail!(
                        "reference {name}: positions solved now differ from the cache by {:.2e} (tolerance {COMPARE_TOLERANCE:e}) with {} constraint-count mismatches; see {}",
                        comparison.worst(),
                        comparison.count_mismatches,
                        odir.join("compare_cache.json").display()
                    );
                }
                continue;
            }
            if let Some((k, n)) = opt.shard {
                eprintln!(
                    "reference {name}: shard {k}/{n} solved; a run without --shard collects every shard's positions from {}",
                    cache_dir.display()
                );
                continue;
            }
            let sweep_s = t_sweep.elapsed().as_secs_f64();
            let sdir = sdir.expect("a run without --shard or --compare-cache has a result set");
            std::fs::create_dir_all(&sdir)?;
            write_te_csv(
                &sdir.join("te.csv"),
                &res,
                &utca.te,
                &fp.pinion,
                fp.roll_range[0],
                direction,
            )?;
            // Contact pattern: the envelope of the pressure at the largest
            // torque over all positions, on the pinion flank's (ξ, η).
            let mut envelope: std::collections::HashMap<[u64; 3], ([f64; 3], f64)> =
                std::collections::HashMap::new();
            for r in &res {
                for &(p, v) in &r.pattern {
                    let e = envelope.entry(p.map(f64::to_bits)).or_insert((p, 0.0));
                    e.1 = e.1.max(v);
                }
            }
            let mut pts: Vec<([f64; 3], f64)> = envelope.into_values().collect();
            pts.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
            let mut csv = format!(
                "x_m,y_m,z_m,{},{},{}\n",
                columns::XI,
                columns::ETA,
                columns::PRESSURE_MPA
            );
            for (p, v) in &pts {
                let (l, d) = fp.pinion.gen.frame.axial(p);
                let (xi, eta) = fp.pinion.bounds.to_unit(l, d);
                writeln!(csv, "{},{},{},{xi},{eta},{}", p[0], p[1], p[2], v * 1e-6)?;
            }
            let t = sc.pinion_torque_nm.last().copied().unwrap_or(0.0);
            write_atomic(&sdir.join(format!("pattern_{t}nm.csv")), csv.as_bytes())?;
            write_atomic(
                &sdir.join(format!("pattern_{t}nm.vtu")),
                pattern_vtu(&pts).as_bytes(),
            )?;
            // Sizes and factoring times of this run's bodies, or of the run
            // that solved the positions (kept beside the position cache).
            let bodies_path = cache_dir.join("bodies.json");
            let (dofs, factor_s): ([usize; 2], [f64; 2]) = match (&pinion, &wheel) {
                (Some(p), Some(w)) => {
                    let b = (
                        [p.compliance.dofs_free, w.compliance.dofs_free],
                        [p.compliance.factor_s, w.compliance.factor_s],
                    );
                    write_json(&bodies_path, &b)?;
                    b
                }
                _ => std::fs::read_to_string(&bodies_path)
                    .ok()
                    .and_then(|t| serde_json::from_str(&t).ok())
                    .unwrap_or(([0; 2], [0.0; 2])),
            };
            let summary = BlankSummary {
                input_hash: hash,
                pinion_blank: blank_name(pb),
                wheel_blank: blank_name(wb),
                level: opt.level.clone(),
                penalty_factor: opt.settings.penalty_factor,
                penalty_factor_check: opt.settings.penalty_factor_check,
                positions: res.len(),
                step_deg: sc.rotation.step_deg * stride as f64,
                mesh_cycles: cycles(wb),
                dofs,
                factor_s,
                right_hand_sides: [
                    pinion.as_ref().map_or(0, |m| m.compliance.solves - rhs0),
                    wheel.as_ref().map_or(0, |m| m.compliance.solves),
                ],
                solve_s: [
                    pinion.as_ref().map_or(0.0, |m| m.compliance.solve_s - s0),
                    wheel.as_ref().map_or(0.0, |m| m.compliance.solve_s),
                ],
                positions_reused: reused,
                searched_mean: res.iter().map(|r| r.searched as f64).sum::<f64>()
                    / res.len().max(1) as f64,
                constraints_mean: res.iter().map(|r| r.constraints as f64).sum::<f64>()
                    / res.len().max(1) as f64,
                wall_s: t0.elapsed().as_secs_f64(),
                sweep_s,
                total_cpu_s: res.iter().map(|r| r.cpu_s).sum::<f64>()
                    + factor_s.iter().sum::<f64>(),
                cpu_s_per_position: res.iter().map(|r| r.cpu_s).sum::<f64>()
                    / res.len().max(1) as f64,
                loads: load_summaries(&res, &sc.pinion_torque_nm),
                unloaded: unloaded_check(&res, &utca.te),
            };
            write_json(&sdir.join("summary.json"), &summary)?;
            let u = &summary.unloaded;
            eprintln!(
                "  unloaded ({} N·m): TE mean {:.2} µrad (UTCA {:.2}), ptp {:.2} µrad (UTCA {:.2}), largest difference {:.3} µrad",
                u.torque_nm, u.reference_te_mean_urad, u.utca_te_mean_urad, u.reference_te_ptp_urad,
                u.utca_te_ptp_urad, u.max_abs_difference_urad
            );
            for l in &summary.loads {
                eprintln!(
                    "  {:6.1} N·m: TE mean {:8.2} µrad, ptp {:7.2} µrad, penalty check {:.3} %, max pressure {:.0} MPa",
                    l.torque_nm, l.te_mean_urad, l.te_ptp_urad, l.penalty_difference_pct, l.max_pressure_mpa
                );
            }
            all.push(summary);
        }
    }
    if let Some(mut set) = set {
        write_json(&set.path().join("summary.json"), &all)?;
        // Every blank's position cache (of this scene's blanks or not)
        // outlives the run, and so does whatever this run did not write:
        // other blank pairs' results, and the studies that other commands
        // keep in this folder (`validate convergence`, `line-load`,
        // `tradeoff`). Entries this run wrote are not carried over.
        // Whole entries first (a blank pair this run did not solve keeps
        // all its files), then the caches inside the ones it did.
        let names: Vec<std::path::PathBuf> = std::fs::read_dir(&ref_dir)
            .into_iter()
            .flatten()
            .flatten()
            .map(|e| Path::new(&e.file_name()).to_path_buf())
            .filter(|n| n != Path::new(formats::result_set::RUN_FILE))
            .collect();
        for name in &names {
            set.carry_over(name);
        }
        for name in &names {
            let rel = name.join("positions");
            if ref_dir.join(&rel).is_dir() {
                set.carry_over(&rel);
            }
        }
        set.commit()?;
    }
    Ok(all)
}
