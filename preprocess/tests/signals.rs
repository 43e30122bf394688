//! `preprocess stiffness` stopped by SIGINT or SIGTERM at each phase
//! (reading the mesh, solving the unit loads, writing the stiffness file)
//! exits with 130 and leaves the mesh folder as it was: no temporary file,
//! no half-written stiffness file, the manifest unchanged. The small
//! scene's coarse (6 × 10) meshes, with the loaded TCA asked so that the
//! scene needs stiffness files.

#[path = "../../validate/tests/support/shared_meshes.rs"]
mod shared_meshes;
#[path = "support/small_scene.rs"]
mod small_scene;
#[path = "../../formats/tests/support/stop_at_phase.rs"]
mod stop_at_phase;

use geometry::scene::Scene;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;
use stop_at_phase::{check_left, stop_at, tree};

/// The small scene's reduced-level meshes (made once, shared with the
/// other tests that mesh it).
fn meshes() -> &'static Path {
    static M: OnceLock<PathBuf> = OnceLock::new();
    M.get_or_init(|| {
        shared_meshes::reduced_meshes(
            &Scene::load(&small_scene::reference().join("scenes/small.toml")).unwrap(),
        )
    })
}

/// The small scene with the loaded TCA on, written into `dir`.
fn scene(dir: &Path) -> PathBuf {
    let text = small_scene::small_scene_text().replace("ltca = false", "ltca = true");
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn stopped(phase: &str, signal: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path().join("meshes");
    let own = root.join("small");
    std::fs::create_dir_all(&own).unwrap();
    for f in std::fs::read_dir(meshes().join("small")).unwrap().flatten() {
        let name = f.file_name().to_string_lossy().into_owned();
        if f.path().is_file() && !name.contains("stiffness") {
            std::fs::copy(f.path(), own.join(&name)).unwrap();
        }
    }
    let before = tree(&root);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_preprocess"));
    cmd.arg("stiffness")
        .arg(scene(tmp.path()))
        .arg("--meshes")
        .arg(&root);
    stop_at(cmd, phase, signal, tmp.path());
    check_left(&root, Path::new("small"), phase, &before, &tree(&root));
}

#[test]
fn stiffness_stopped_while_reading_the_mesh_leaves_the_folder_as_it_was() {
    stopped("reading", "-INT");
    stopped("reading", "-TERM");
}

#[test]
fn stiffness_stopped_while_solving_leaves_the_folder_as_it_was() {
    stopped("solving", "-INT");
    stopped("solving", "-TERM");
}

#[test]
fn stiffness_stopped_while_writing_its_file_leaves_the_folder_as_it_was() {
    stopped("writing", "-INT");
    stopped("writing", "-TERM");
}
