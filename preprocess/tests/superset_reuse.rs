//! A scene that asks for fewer refined teeth than another scene's meshes
//! hold reuses those meshes instead of meshing again: the small scene's
//! coarse meshes serve a variant of it that turns through half a mesh
//! cycle (fewer teeth in contact). The variant's manifest keeps the
//! meshes' own inputs, its stiffness files are planned on their teeth
//! (the same files as the small scene's), and the readers' check accepts
//! them. A scene that asks for more teeth is not served.

#[path = "../../validate/tests/support/shared_meshes.rs"]
mod shared_meshes;
#[path = "support/small_scene.rs"]
mod small_scene;

use formats::manifest::Manifest;
use formats::paths::{self, MeshLevel};
use formats::stiffness_plan::{check_mesh, plan};
use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::teeth::refined_teeth;
use preprocess::mesh_stage::{self, Level};
use std::path::Path;

/// The small scene with `edit` applied to its text, named `name`, written
/// into `dir`.
fn variant(dir: &Path, name: &str, edit: impl Fn(String) -> String) -> LoadedScene {
    let text =
        small_scene::small_scene_text().replace("name = \"small\"", &format!("name = \"{name}\""));
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, edit(text)).unwrap();
    Scene::load(&path).unwrap()
}

#[test]
fn a_scene_asking_for_fewer_teeth_reuses_the_meshes_of_one_asking_for_more() {
    let small =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference/scenes/small.toml"))
            .unwrap();
    let shared = shared_meshes::reduced_meshes(&small);
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path().join("meshes");
    std::fs::create_dir_all(root.join("small")).unwrap();
    for f in std::fs::read_dir(shared.join("small")).unwrap().flatten() {
        let name = f.file_name().to_string_lossy().into_owned();
        if f.path().is_file() && !name.contains("stiffness") {
            std::fs::copy(f.path(), root.join("small").join(&name)).unwrap();
        }
    }
    let fewer = variant(tmp.path(), "fewer", |t| {
        t.replace("mesh_cycles_standard = 1.0", "mesh_cycles_standard = 0.5")
    });
    let g = PairGeometry::build(&fewer.pair, Some(&fewer.design_path)).unwrap();
    let members = [
        (Member::Pinion, Blank::Standard),
        (Member::Wheel, Blank::Standard),
    ];
    // The case: the variant asks for a strict subset of teeth on some member.
    let strict = members.iter().any(|&(m, b)| {
        refined_teeth(&g, &fewer.scene, m, b).len() < refined_teeth(&g, &small.scene, m, b).len()
    });
    assert!(strict, "the variant asks for the same teeth");
    let reports = mesh_stage::run(&fewer, &root, Level::Reduced).unwrap();
    assert!(reports.iter().all(|r| r.reused), "meshed again");
    let own = Manifest::read(&root.join("fewer")).unwrap();
    let theirs = Manifest::read(&root.join("small")).unwrap();
    for (m, b) in members {
        let stem = paths::mesh_stem(m, b, MeshLevel::Reduced);
        assert_eq!(
            own.meshes[&stem].inputs, theirs.meshes[&stem].inputs,
            "{stem}"
        );
        assert!(check_mesh(
            &fewer,
            &g,
            &root.join("fewer"),
            &stem,
            m,
            b,
            MeshLevel::Reduced
        )
        .is_ok());
        // Planned on the meshes' teeth: the small scene's stiffness files.
        let side = fewer.scene.loaded_flank;
        let a = plan(
            &fewer,
            &g,
            &root.join("fewer"),
            m,
            b,
            MeshLevel::Reduced,
            side,
        )
        .unwrap();
        let s = plan(
            &small,
            &g,
            &root.join("small"),
            m,
            b,
            MeshLevel::Reduced,
            side,
        )
        .unwrap();
        assert_eq!(
            serde_json::to_value(&a.config).unwrap(),
            serde_json::to_value(&s.config).unwrap(),
            "{stem}"
        );
    }
    // A second run reuses its own folder's meshes as they are.
    let again = mesh_stage::run(&fewer, &root, Level::Reduced).unwrap();
    assert!(again.iter().all(|r| r.reused));
    // The other way round: the small scene's teeth are not all in a
    // mesh made for fewer, so that mesh does not serve it.
    let more = variant(tmp.path(), "more", |t| t);
    for (m, b) in members {
        let stem = paths::mesh_stem(m, b, MeshLevel::Reduced);
        let fewer_inputs = formats::manifest::MeshInputs {
            refined_teeth: refined_teeth(&g, &fewer.scene, m, b),
            ..theirs.meshes[&stem].inputs.clone()
        };
        let wanted = theirs.meshes[&stem].inputs.clone();
        let d = fewer_inputs.serves(&wanted);
        let asks_more =
            refined_teeth(&g, &more.scene, m, b).len() > fewer_inputs.refined_teeth.len();
        assert_eq!(d.is_empty(), !asks_more, "{stem}: {d:?}");
    }
}
