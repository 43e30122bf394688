//! Reduced-level meshes shared by the tests that mesh the same pair (the
//! white-paper pair at 6 × 10 elements per flank: `reference_sweep.rs` and
//! example 03), under `<target>/tmp/shared_meshes/`: a scene whose manifest
//! inputs equal another scene's finds that scene's meshes copied into its own
//! folder, and the mesh stage reuses them after its own checks (inputs
//! hash, the `.msh` SHA-256 in the manifest). Meshing once instead of twice
//! saves about a minute of `make test`.

use formats::manifest::Manifest;
use geometry::scene::LoadedScene;
use preprocess::mesh_stage::{self, Level};
use std::path::{Path, PathBuf};

/// The mesh root holding `scene`'s reduced-level meshes, made or reused.
pub fn reduced_meshes(scene: &LoadedScene) -> PathBuf {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("shared_meshes");
    let own = root.join(&scene.scene.name);
    if !own.join("manifest.json").exists() {
        adopt_twin(&root, &own);
    }
    mesh_stage::run(scene, &root, Level::Reduced).unwrap();
    root
}

/// Copies into `own` the mesh files of a sibling folder (another scene),
/// when one exists; the mesh stage then decides whether they serve.
fn adopt_twin(root: &Path, own: &Path) {
    let Ok(dirs) = std::fs::read_dir(root) else {
        return;
    };
    for d in dirs.flatten().map(|e| e.path()) {
        if d == own || Manifest::read(&d).is_err() {
            continue;
        }
        std::fs::create_dir_all(own).unwrap();
        for f in std::fs::read_dir(&d).unwrap().flatten().map(|e| e.path()) {
            let name = f.file_name().unwrap().to_string_lossy().into_owned();
            let mesh_file = [".msh", ".vtu", ".inputs.json", ".report.json"]
                .iter()
                .any(|s| name.ends_with(s))
                || name == "manifest.json";
            if f.is_file() && mesh_file && !name.contains("stiffness") {
                std::fs::copy(&f, own.join(&name)).unwrap();
            }
        }
        return;
    }
}
