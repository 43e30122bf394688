//! `solver dynamic` stopped by SIGINT or SIGTERM at each phase (reading the
//! stiffness files and building the contact table, integrating, committing
//! its result set, right after the commit) exits with 130 and leaves the
//! output folder as it was (or, once committed, the new set whole), with
//! no staging folder, old copy, lock or temporary file. The checked-in
//! stiffness fixture of example 02, one short run-up.

#[path = "../../formats/tests/support/stop_at_phase.rs"]
mod stop_at_phase;

use formats::result_set::ResultSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use stop_at_phase::{check_left, stop_at, tree};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

/// The fixture's scene with multibody runs, written into `dir`.
fn scene(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(example().join("scene.toml")).unwrap();
    let design = example()
        .join("../../reference/white_paper_20x43.toml")
        .canonicalize()
        .unwrap();
    let text = text
        .replace(
            "design = \"../../reference/white_paper_20x43.toml\"",
            &format!("design = {:?}", design.display().to_string()),
        )
        .replace("multibody = false", "multibody = true")
        + "\n[multibody]\ntable_step_deg = 1.0\ntable_lag_nodes = 24\nrunup_time_s = 0.01\nrunup_rpm = [0.0, 300.0]\n";
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn stopped(phase: &str, signal: &str) {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("signals_{phase}{signal}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let scene = scene(&tmp);
    let out = tmp.join("out");
    let set = Path::new("ltca_fixture/multibody");
    let previous = ResultSet::begin(&out.join(set), "previous run").unwrap();
    std::fs::write(previous.path().join("summary.json"), "[]").unwrap();
    previous.commit().unwrap();
    let before = tree(&out);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_solver"));
    cmd.arg("dynamic")
        .arg(&scene)
        .arg("--meshes")
        .arg(example().join("meshes"))
        .arg("--out")
        .arg(&out);
    stop_at(cmd, phase, signal, &tmp);
    check_left(&out, set, phase, &before, &tree(&out));
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn dynamic_stopped_while_reading_leaves_the_previous_set() {
    stopped("reading", "-INT");
    stopped("reading", "-TERM");
}

#[test]
fn dynamic_stopped_while_integrating_leaves_the_previous_set() {
    stopped("solving", "-INT");
    stopped("solving", "-TERM");
}

#[test]
fn dynamic_stopped_while_committing_leaves_the_previous_set() {
    stopped("committing", "-INT");
    stopped("committing", "-TERM");
}

#[test]
fn dynamic_stopped_right_after_the_commit_leaves_the_new_set_whole() {
    stopped("committed", "-INT");
    stopped("committed", "-TERM");
}
