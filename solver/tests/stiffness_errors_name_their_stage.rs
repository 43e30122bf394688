//! When a stiffness file cannot be used, the first line of the error names
//! what mends it: the meshes (no manifest, an old schema), the mesh folder
//! itself (`--meshes` a file), or the stiffness stage (the file missing
//! from the manifest). On a copy of the example-02 fixture's mesh folder.

use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, Scene};
use solver::stage::context::member_compliance_on;
use std::path::{Path, PathBuf};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

/// The first line of the error of loading the pinion's compliance from
/// `dir` (after `damage` was done to a copy of the fixture's folder).
fn first_line(case: &str, damage: impl Fn(&Path) -> PathBuf) -> String {
    let scene = Scene::load(&example().join("scene.toml")).unwrap();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("stiffness_errors_{case}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let dir = tmp.join("ltca_fixture");
    std::fs::create_dir_all(&dir).unwrap();
    let src = example().join("meshes").join(&scene.scene.name);
    for e in std::fs::read_dir(&src).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
    }
    let dir = damage(&dir);
    let r = member_compliance_on(
        &scene,
        &g,
        &dir,
        Member::Pinion,
        Blank::Standard,
        scene.scene.loaded_flank,
    );
    let _ = std::fs::remove_dir_all(&tmp);
    let Err(e) = r else {
        panic!("the damaged folder must be refused")
    };
    format!("{e}")
}

#[test]
fn deleted_manifest_points_to_the_mesh_stage() {
    let e = first_line("manifest", |d| {
        std::fs::remove_file(d.join("manifest.json")).unwrap();
        d.to_path_buf()
    });
    assert!(
        e.contains("cannot be used") && e.contains("run `preprocess mesh"),
        "{e}"
    );
}

#[test]
fn meshes_option_naming_a_file_points_to_the_folder() {
    let e = first_line("file", |d| d.join("manifest.json"));
    assert!(e.contains("check the mesh folder"), "{e}");
    assert!(!e.contains("preprocess stiffness"), "{e}");
}

#[test]
fn stiffness_file_missing_from_the_manifest_points_to_the_stiffness_stage() {
    let e = first_line("entry", |d| {
        let m = d.join("manifest.json");
        let text = std::fs::read_to_string(&m).unwrap();
        let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
        for (_, mesh) in v["meshes"].as_object_mut().unwrap() {
            mesh["stiffness"] = serde_json::json!({});
        }
        std::fs::write(&m, serde_json::to_string(&v).unwrap()).unwrap();
        d.to_path_buf()
    });
    assert!(e.contains("run `preprocess stiffness"), "{e}");
    assert!(!e.contains("preprocess mesh"), "{e}");
}

#[test]
fn commands_the_message_gives_write_where_the_run_reads() {
    // The copy's root is a scratch folder, not the default `meshes`: the
    // commands must name it, or they would write into ./meshes.
    let e = first_line("root", |d| {
        std::fs::remove_file(d.join("manifest.json")).unwrap();
        d.to_path_buf()
    });
    let r = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("stiffness_errors_root_{}", std::process::id()))
        .display()
        .to_string();
    assert!(
        e.contains(&format!("--out {r}`")) && e.contains(&format!("--meshes {r}`")),
        "{e}"
    );
    assert!(!e.contains("no mesh folder"), "{e}");
}

#[test]
fn a_mesh_root_that_does_not_exist_is_named_as_such() {
    let e = first_line("no_root", |d| {
        d.parent().unwrap().join("not_there/ltca_fixture")
    });
    assert!(
        e.contains("no mesh folder") && e.contains("not_there"),
        "{e}"
    );
    assert!(e.contains("run `preprocess mesh"), "{e}");
}
