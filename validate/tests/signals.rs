//! `validate reference` stopped by SIGINT or SIGTERM at each phase (reading
//! and factoring the bodies, solving the first position, writing a
//! position's cache file, committing its result set, right after the
//! commit) exits with 130 and leaves the output folder as it was (or, once
//! committed, the new set whole), with no staging folder, old copy, lock or
//! temporary file. The position cache beside the results outlives runs by
//! design (a stopped sweep resumes from it): it is not compared, but no
//! temporary file may be left in it. The small scene's coarse (6 × 10)
//! meshes.

#[path = "support/shared_meshes.rs"]
mod shared_meshes;
#[path = "../../formats/tests/support/stop_at_phase.rs"]
mod stop_at_phase;

use formats::result_set::ResultSet;
use geometry::scene::Scene;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use stop_at_phase::{check_left, stop_at, tree};

fn scene_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference/scenes/small.toml")
}

/// The small scene's reduced-level meshes (made once, shared).
fn meshes() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| shared_meshes::reduced_meshes(&Scene::load(&scene_path()).unwrap()))
}

/// The tree without the position cache (`<blank pair>/positions/`, kept
/// by design: a stopped sweep resumes from it) and the blank pairs' folders
/// that hold it.
fn compared(out: &Path) -> BTreeMap<PathBuf, Option<Vec<u8>>> {
    let set = out.join("small/reference");
    tree(out)
        .into_iter()
        .filter(|(p, b)| {
            let in_cache = p.components().any(|c| c.as_os_str() == "positions");
            let cache_parent = b.is_none() && out.join(p).parent() == Some(set.as_path());
            !(in_cache || cache_parent)
        })
        .collect()
}

fn stopped(phase: &str, signal: &str) {
    let meshes = meshes();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let set = Path::new("small/reference");
    let previous = ResultSet::begin(&out.join(set), "previous run").unwrap();
    std::fs::write(previous.path().join("summary.json"), "[]").unwrap();
    previous.commit().unwrap();
    let before = compared(&out);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_validate"));
    cmd.arg("reference")
        .arg(scene_path())
        .arg("--meshes")
        .arg(meshes)
        .args(["--level", "reduced", "--stride", "9"])
        .arg("--out")
        .arg(&out);
    stop_at(cmd, phase, signal, tmp.path());
    let after = compared(&out);
    assert_eq!(stop_at_phase::leftovers(&tree(&out)), Vec::<PathBuf>::new());
    check_left(&out, set, phase, &before, &after);
}

#[test]
fn reference_stopped_while_factoring_leaves_the_previous_set() {
    stopped("reading", "-INT");
    stopped("reading", "-TERM");
}

#[test]
fn reference_stopped_while_solving_leaves_the_previous_set() {
    stopped("solving", "-INT");
    stopped("solving", "-TERM");
}

// The two phases beyond the three of the matrix, one signal each (the
// signal thread treats both alike; every phase takes about 9 s of
// factoring on these meshes).
#[test]
fn reference_stopped_while_writing_a_position_leaves_no_temporary_file() {
    stopped("writing", "-INT");
}

#[test]
fn reference_stopped_while_committing_leaves_the_previous_set() {
    stopped("committing", "-INT");
    stopped("committing", "-TERM");
}

#[test]
fn reference_stopped_right_after_the_commit_leaves_the_new_set_whole() {
    // SIGTERM: the signal gmsh's handlers had taken over.
    stopped("committed", "-TERM");
}
