//! Every `[analyses]` flag of a scene is honoured: a stage whose analysis
//! the scene does not ask for computes nothing and writes nothing, and a
//! scene that asks for the UTCA only meshes nothing.

use geometry::scene::{Analyses, MeshLevel, Scene};
use preprocess::mesh_stage::Level;
use std::path::{Path, PathBuf};
#[path = "support/reference_options.rs"]
mod reference_options;

/// The small scene with `flags` as its `[analyses]`, written into `dir`.
fn scene_with(dir: &Path, flags: Analyses) -> geometry::scene::LoadedScene {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference");
    let text = std::fs::read_to_string(root.join("scenes/small.toml")).unwrap();
    let head = text.split("[analyses]").next().unwrap();
    let design = root.join("white_paper_20x43.toml");
    let head = head.replace(
        "design = \"../white_paper_20x43.toml\"",
        &format!("design = {:?}", design.to_str().unwrap()),
    );
    let body = format!(
        "{head}[analyses]\nutca = {}\nltca = {}\nmultibody = {}\nreference = {}\n",
        flags.utca, flags.ltca, flags.multibody, flags.reference
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, body).unwrap();
    Scene::load(&path).unwrap()
}

/// Files under `dir`, recursively.
fn files(dir: &Path) -> Vec<PathBuf> {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    rd.flat_map(|e| {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p)
        } else {
            vec![p]
        }
    })
    .collect()
}

const NONE: Analyses = Analyses {
    utca: false,
    ltca: false,
    multibody: false,
    reference: false,
};

#[test]
fn utca_only_scene_meshes_nothing_and_runs_no_loaded_stage() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = scene_with(tmp.path(), Analyses { utca: true, ..NONE });
    let (meshes, out) = (tmp.path().join("meshes"), tmp.path().join("out"));
    for level in [Level::Reduced, Level::Medium, Level::Reference, Level::Both] {
        assert!(preprocess::mesh_stage::run(&scene, &meshes, level)
            .unwrap()
            .is_empty());
    }
    assert!(preprocess::stiffness_stage::run(&scene, &meshes)
        .unwrap()
        .is_empty());
    assert!(solver::stage::ltca::run(&scene, &meshes, &out)
        .unwrap()
        .is_empty());
    assert!(solver::stage::dynamic::run(&scene, &meshes, &out)
        .unwrap()
        .is_empty());
    assert!(validate::reference::reference_stage::run(
        &scene,
        &meshes,
        &out,
        &reference_options::options(1, None)
    )
    .unwrap()
    .is_empty());
    assert!(
        validate::studies::tradeoff::run(&scene, &meshes, &out, &[4])
            .unwrap()
            .is_empty()
    );
    assert!(files(tmp.path()).iter().all(|f| f.ends_with("scene.toml")));
    // The flank stage runs.
    let input = preprocess::flank_stage::load_input(&tmp.path().join("scene.toml")).unwrap();
    let s = preprocess::flank_stage::run(&input, &tmp.path().join("flanks")).unwrap();
    assert!(s.is_some_and(|s| s.utca.te_ptp_urad > 0.0));
}

#[test]
fn utca_false_writes_no_flank_files() {
    let tmp = tempfile::tempdir().unwrap();
    scene_with(tmp.path(), Analyses { ltca: true, ..NONE });
    let input = preprocess::flank_stage::load_input(&tmp.path().join("scene.toml")).unwrap();
    assert!(!input.wanted);
    let flanks = tmp.path().join("flanks");
    assert!(preprocess::flank_stage::run(&input, &flanks)
        .unwrap()
        .is_none());
    assert!(!flanks.exists());
}

#[test]
fn each_flag_asks_for_exactly_its_meshes_and_stiffness_files() {
    let table = [
        // (flags, reduced meshes, reference meshes, stiffness files)
        (Analyses { ltca: true, ..NONE }, true, false, true),
        (
            Analyses {
                multibody: true,
                ..NONE
            },
            true,
            false,
            true,
        ),
        (
            Analyses {
                reference: true,
                ..NONE
            },
            true,
            true,
            false,
        ),
        (Analyses { utca: true, ..NONE }, false, false, false),
    ];
    for (flags, reduced, fine, stiffness) in table {
        assert_eq!(flags.needs_mesh(MeshLevel::Reduced), reduced, "{flags:?}");
        assert_eq!(flags.needs_mesh(MeshLevel::Medium), fine, "{flags:?}");
        assert_eq!(flags.needs_mesh(MeshLevel::Reference), fine, "{flags:?}");
        assert_eq!(flags.needs_stiffness(), stiffness, "{flags:?}");
    }
}

#[test]
fn ltca_false_and_multibody_false_skip_their_stages_with_meshes_present() {
    // Reference only: reduced meshes are made (the reduced-level reference
    // needs them), stiffness files and the reduced model's stages are not.
    let tmp = tempfile::tempdir().unwrap();
    let scene = scene_with(
        tmp.path(),
        Analyses {
            reference: true,
            ..NONE
        },
    );
    let (meshes, out) = (tmp.path().join("meshes"), tmp.path().join("out"));
    assert!(preprocess::stiffness_stage::run(&scene, &meshes)
        .unwrap()
        .is_empty());
    assert!(solver::stage::ltca::run(&scene, &meshes, &out)
        .unwrap()
        .is_empty());
    assert!(solver::stage::dynamic::run(&scene, &meshes, &out)
        .unwrap()
        .is_empty());
    assert!(!out.exists());
}

#[test]
fn removed_mesh_and_stiffness_flags_are_rejected_by_name() {
    let tmp = tempfile::tempdir().unwrap();
    scene_with(tmp.path(), Analyses { utca: true, ..NONE });
    let path = tmp.path().join("scene.toml");
    let text = std::fs::read_to_string(&path).unwrap() + "mesh = true\n";
    std::fs::write(&path, text).unwrap();
    let err = Scene::load(&path).unwrap_err().to_string();
    assert!(err.contains("mesh"), "{err}");
}
