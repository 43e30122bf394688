//! What the study tests share: the project's programs (built once), the
//! mesh root shared with the other packages' tests (the white-paper pair
//! at 6 × 10 elements per flank, under `<target>/tmp/shared_meshes/`), a
//! base scene and study files written into the test's folder.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The folder of the project's programs (`study`'s own folder).
pub fn bin_dir() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_study"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Builds preprocess, solver and validate beside `study` (a no-op when
/// `cargo test` built them already), once per test binary.
pub fn build_programs() {
    static BUILT: OnceLock<()> = OnceLock::new();
    BUILT.get_or_init(|| {
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args([
            "build",
            "--bins",
            "-p",
            "preprocess",
            "-p",
            "solver",
            "-p",
            "validate",
        ])
        .current_dir(workspace());
        if bin_dir().ends_with("release") {
            cmd.arg("--release");
        }
        let out = cmd.output().unwrap();
        assert!(
            out.status.success(),
            "cargo build of the programs failed:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    });
}

pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The mesh root shared with the other tests of the same pair.
pub fn meshes_root() -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR")).join("shared_meshes")
}

/// The small scene (`reference/scenes/small.toml`, the white-paper pair,
/// 6 × 10 reduced meshes, one torque, 19 positions) as `study_small`, its
/// design path made absolute, written into `dir`.
pub fn base_scene(dir: &Path) -> PathBuf {
    let ws = workspace();
    let text = std::fs::read_to_string(ws.join("reference/scenes/small.toml")).unwrap();
    let design = ws.join("reference/white_paper_20x43.toml");
    let text = text
        .replace("name = \"small\"", "name = \"study_small\"")
        .replace(
            "design = \"../white_paper_20x43.toml\"",
            &format!("design = \"{}\"", design.display()),
        );
    assert!(text.contains("study_small") && text.contains(&design.display().to_string()));
    let path = dir.join("study_small.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// A study file of the base scene over the offsets `offsets`.
pub fn study_file(
    dir: &Path,
    name: &str,
    scene: &Path,
    analyses: &str,
    offsets: &str,
    shards: usize,
) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "name = \"{name}\"\nscenes = [\"{}\"]\nanalyses = {analyses}\n\n[grid]\noffset_mm = {offsets}\n\n[reference]\nlevel = \"reduced\"\nshards = {shards}\n\n[slurm]\ncpus_per_task = 1\n",
            scene.display()
        ),
    )
    .unwrap();
    path
}

/// Runs `study` with `args`; returns its output (not checked).
pub fn study(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_study"))
        .args(args)
        .env("RUST_BACKTRACE", "0")
        .output()
        .unwrap()
}

/// Runs `study` with `args` and returns its stdout; panics with both
/// streams when it fails.
pub fn study_ok(args: &[&str]) -> String {
    let out = study(args);
    assert!(
        out.status.success(),
        "study {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A path as a `&str` argument.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
