//! `validate reference <scene>`: the reference loaded TCA of every pinion ×
//! wheel blank of a scene, from the meshes of one level, to
//! `<out>/<scene>/reference/<pinion>_<wheel>/`: `te.csv` (TE per position
//! and torque), `pattern_<T>nm.csv` (contact pressure on the pinion flanks at
//! the largest torque) and `summary.json`. A run whose inputs (mesh files,
//! settings, positions, torques) hash to an existing summary reuses it.
//!
//! With `--contact pinion-slave` (only the pinion's nodes against the
//! wheel's faces) the results go to `<out>/<scene>/reference_<level>_
//! pinion_slave/` instead ([`reference_dir_with`]), with their own cache.
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

use super::reference_blank_pair::Bodies;
pub use super::reference_outputs::pattern_vtu;
pub use super::reference_summary::{BlankSummary, CacheComparison, LoadSummary, UnloadedCheck};
use crate::reference::reference_ltca::ContactPasses;
use formats::output::write_json;
use formats::result_set::{ResultSet, RunLock};
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use std::path::Path;

use super::reference_options::StageOptions;

pub use formats::paths::reference_dir;

/// Where the reference of mesh level `level` with the contact passes
/// `passes` writes its results: [`reference_dir`] for the two-pass
/// contact, `<out>/<scene>/reference_<level>_pinion_slave/` for the
/// pinion-slave one.
pub fn reference_dir_with(
    out: &Path,
    scene: &str,
    level: &str,
    passes: ContactPasses,
) -> std::path::PathBuf {
    match passes {
        ContactPasses::TwoPass => reference_dir(out, scene, level),
        ContactPasses::PinionSlave => out
            .join(scene)
            .join(format!("reference_{level}_pinion_slave")),
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

/// Runs the reference LTCA of the scene.
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    opt: &StageOptions,
) -> anyhow::Result<Vec<BlankSummary>> {
    Ok(run_scenes(&[(scene, out)], meshes, opt)?
        .pop()
        .unwrap_or_default())
}

/// Runs the reference LTCA of several scenes that share their meshes (the
/// cases of one design at several misalignments): blank pair by blank
/// pair, each body factored once and kept for every scene whose sweep
/// needs it (the meshes are body-fixed; only the placement differs), so
/// that the factors held at once are those of one scene. Each scene's
/// results are its own set under its own output root, as from a run of
/// that scene alone. Two scenes of one name may not share an output root.
/// Returns the summaries of each scene that runs the reference (a scene
/// with `[analyses] reference = false` is skipped, as by [`run`]), in the
/// scenes' order.
pub fn run_scenes(
    scenes: &[(&LoadedScene, &Path)],
    meshes: &Path,
    opt: &StageOptions,
) -> anyhow::Result<Vec<Vec<BlankSummary>>> {
    for (i, (a, out)) in scenes.iter().enumerate() {
        if let Some((b, _)) = scenes[..i]
            .iter()
            .find(|(b, o)| b.scene.name == a.scene.name && o == out)
        {
            anyhow::bail!(
                "scenes {} and {} are both named {} and would write into one output root {}: give each its own --out",
                b.path.display(),
                a.path.display(),
                a.scene.name,
                out.display()
            );
        }
    }
    let mut runs = Vec::new();
    let mut sets = Vec::new();
    for &(scene, out) in scenes {
        let Some((run, set)) = begin(scene, meshes, out, opt)? else {
            continue;
        };
        runs.push(run);
        sets.push(set);
    }
    // Blank pairs in the order the scenes list them.
    let mut pairs: Vec<[Blank; 2]> = Vec::new();
    for r in &runs {
        for &pb in &r.scene.scene.blanks.pinion {
            for &wb in &r.scene.scene.blanks.wheel {
                if !pairs.contains(&[pb, wb]) {
                    pairs.push([pb, wb]);
                }
            }
        }
    }
    let mut all: Vec<Vec<BlankSummary>> = vec![Vec::new(); runs.len()];
    let mut bodies = Bodies::default();
    for [pb, wb] in pairs {
        // The wheel of the last pair is not this one's: let it go before
        // this pair factors its own (one scene's factors at a time).
        bodies.wheel = None;
        if bodies.pinion.as_ref().is_some_and(|(k, _)| k.blank != pb) {
            bodies.pinion = None;
        }
        for (k, run) in runs.iter().enumerate() {
            let sc = &run.scene.scene;
            if !(sc.blanks.pinion.contains(&pb) && sc.blanks.wheel.contains(&wb)) {
                continue;
            }
            if let Some(s) = run.blank_pair([pb, wb], &mut bodies, sets[k].as_mut())? {
                all[k].push(s);
            }
        }
    }
    for ((set, run), summaries) in sets.into_iter().zip(&runs).zip(&all) {
        if let Some(set) = set {
            commit(set, &run.ref_dir, summaries)?;
        }
    }
    Ok(all)
}

/// A scene's run: its lock or result set taken before any work (see the
/// module documentation), its pair placed; None when the scene has no
/// reference analysis.
fn begin<'a>(
    scene: &'a LoadedScene,
    meshes: &Path,
    out: &Path,
    opt: &'a StageOptions,
) -> anyhow::Result<Option<(super::reference_blank_pair::Run<'a>, Option<ResultSet>)>> {
    if !solver::stage::context::analysis_enabled(
        scene,
        scene.scene.analyses.reference,
        "reference",
        "no reference FE",
    ) {
        return Ok(None);
    }
    let sc = &scene.scene;
    let ref_dir = reference_dir_with(out, &sc.name, &opt.level, opt.settings.passes);
    let what = format!(
        "validate reference {} --level {}{}",
        scene.path.display(),
        opt.level,
        match opt.settings.passes {
            ContactPasses::TwoPass => String::new(),
            p => format!(" --contact {}", p.name()),
        }
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
    let step = sc.rotation.step_deg.to_radians();
    let mut pinion_teeth = std::collections::BTreeSet::new();
    for &wb in &sc.blanks.wheel {
        pinion_teeth.extend(teeth_in_contact(&g, side, sc.rotation.mesh_cycles(wb), step).0);
    }
    let run = super::reference_blank_pair::Run {
        scene,
        opt,
        direction: pinion_direction(&g.data, side),
        side,
        step,
        dir: meshes.join(&sc.name),
        ref_dir,
        what,
        pinion_teeth: pinion_teeth.into_iter().collect(),
        lock,
        g,
    };
    Ok(Some((run, set)))
}

/// Writes the run's summary and puts the set in place. Every blank's
/// position cache (of this scene's blanks or not) outlives the run, and so
/// does whatever this run did not write: other blank pairs' results, and
/// the studies that other commands keep in this folder (`validate
/// convergence`, `line-load`, `tradeoff`). Entries this run wrote are not
/// carried over. Whole entries first (a blank pair this run did not solve
/// keeps all its files), then the caches inside the ones it did.
fn commit(mut set: ResultSet, ref_dir: &Path, all: &[BlankSummary]) -> anyhow::Result<()> {
    write_json(&set.path().join("summary.json"), &all)?;
    let names: Vec<std::path::PathBuf> = std::fs::read_dir(ref_dir)
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
    Ok(())
}
