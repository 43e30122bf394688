//! Nothing stale, nothing damaged is used: on the checked-in
//! stiffness fixture of example 02, a reader refuses a stiffness file whose
//! bytes changed since the stiffness stage listed it, whose numbers make no
//! physical sense (a flipped diagonal, a NaN), or whose mesh was made from
//! a design edited since; and the mesh stage does not reuse a damaged mesh.

use formats::manifest::{Manifest, StiffnessEntry};
use formats::paths::MeshLevel;
use formats::stiffness_plan::{check, plan, CheckError};
use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use std::path::{Path, PathBuf};

const SCENE: &str = "ltca_fixture";

/// A copy of example 02 (scene, manifest, stiffness files) in `dir`, its
/// scene naming `design` (the white-paper design by default).
fn fixture(dir: &Path, design: Option<&Path>) -> (LoadedScene, PathBuf) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let ex = root.join("examples/02_ltca_fixture");
    let wp = root.join("reference/white_paper_20x43.toml");
    let design = design.unwrap_or(&wp);
    let text = std::fs::read_to_string(ex.join("scene.toml"))
        .unwrap()
        .replace(
            "design = \"../../reference/white_paper_20x43.toml\"",
            &format!("design = {:?}", design.to_str().unwrap()),
        );
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    let meshes = dir.join("meshes");
    let folder = meshes.join(SCENE);
    std::fs::create_dir_all(&folder).unwrap();
    for e in std::fs::read_dir(ex.join("meshes").join(SCENE)).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, folder.join(p.file_name().unwrap())).unwrap();
    }
    (Scene::load(&dir.join("scene.toml")).unwrap(), meshes)
}

fn check_pinion(scene: &LoadedScene, meshes: &Path) -> Result<(), CheckError> {
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let dir = meshes.join(SCENE);
    let (m, b, l) = (Member::Pinion, Blank::Standard, MeshLevel::Reduced);
    let p = plan(scene, &g, &dir, m, b, l, scene.scene.loaded_flank).unwrap();
    check(scene, &g, &dir, &p, m, b, l).map(|_| ())
}

/// The fixture's pinion stiffness file under `meshes`.
fn pinion_h5(meshes: &Path) -> PathBuf {
    meshes
        .join(SCENE)
        .join("pinion_standard_reduced.stiffness.h5")
}

/// Grid points, the loaded tooth's offset index and the offset count of
/// the file `h5`: element `o0 · np²` starts the first solved tooth's own
/// block.
fn own_block(h5: &Path) -> (usize, usize, usize) {
    let d = formats::stiffness_file::read(h5, None).unwrap();
    let o0 = d.offsets.iter().position(|&o| o == 0).unwrap();
    (d.points(), o0, d.offsets.len())
}

/// Overwrites element `k` of the loaded tooth's total compliance with `f(value)`.
fn tamper(h5: &Path, k: usize, f: impl Fn(f64) -> f64) {
    tamper_in(h5, "compliance/total", k, f)
}

/// Overwrites element `k` of dataset `name` with `f(value)`.
fn tamper_in(h5: &Path, name: &str, k: usize, f: impl Fn(f64) -> f64) {
    let file = formats::stiffness_file::h5().append(h5).unwrap();
    let ds = file.dataset(name).unwrap();
    let mut v: Vec<f64> = ds.read_raw().unwrap();
    v[k] = f(v[k]);
    ds.write_raw(&v).unwrap();
    file.close().unwrap();
}

/// The manifest lists the file's present bytes (as if the stiffness stage
/// had written it so): only the physical-sense check can catch it then.
fn relist(meshes: &Path, h5: &Path) {
    let dir = meshes.join(SCENE);
    let sha = formats::manifest::sha256_file(h5).unwrap();
    Manifest::update(&dir, |m| {
        for e in m.meshes.values_mut() {
            for s in e.stiffness.values_mut() {
                if h5.ends_with(&s.file) {
                    *s = StiffnessEntry {
                        sha256: sha.clone(),
                        ..s.clone()
                    };
                }
            }
        }
    })
    .unwrap();
}

#[test]
fn untouched_fixture_passes_every_check() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, meshes) = fixture(tmp.path(), None);
    check_pinion(&scene, &meshes).unwrap();
}

#[test]
fn flipped_compliance_value_is_refused_by_checksum_then_by_sense() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, meshes) = fixture(tmp.path(), None);
    let h5 = pinion_h5(&meshes);
    // The first diagonal entry of the first solved tooth's own block.
    let (np, o0, _) = own_block(&h5);
    tamper(&h5, o0 * np * np, |c| -c);
    let e = check_pinion(&scene, &meshes).unwrap_err();
    assert!(matches!(e, CheckError::Changed { .. }), "{e}");
    relist(&meshes, &h5);
    let e = check_pinion(&scene, &meshes).unwrap_err();
    assert!(
        matches!(&e, CheckError::Nonsense { problem, .. } if problem.contains("diagonal")),
        "{e}"
    );
}

#[test]
fn nan_and_broken_reciprocity_are_refused_by_sense() {
    let tmp = tempfile::tempdir().unwrap();
    let (scene, meshes) = fixture(tmp.path(), None);
    let h5 = pinion_h5(&meshes);
    let (np, o0, _) = own_block(&h5);
    // C_01 halved: no longer equal to C_10.
    tamper(&h5, o0 * np * np + 1, |c| 0.5 * c);
    relist(&meshes, &h5);
    let e = check_pinion(&scene, &meshes).unwrap_err().to_string();
    assert!(e.contains("not reciprocal"), "{e}");
    tamper(&h5, o0 * np * np + 1, |_| f64::NAN);
    relist(&meshes, &h5);
    let e = check_pinion(&scene, &meshes).unwrap_err().to_string();
    assert!(e.contains("not finite"), "{e}");
}

#[test]
fn sign_flipped_global_value_is_refused_by_sense_naming_the_split() {
    // The block the contact element interpolates: global = total - local on
    // the loaded tooth, total on its neighbours. A value flipped there (the
    // manifest relisted, so the checksum passes) changes no total or local
    // number, so only the split check can catch it: on the loaded tooth's
    // block and on a neighbour's.
    let tmp = tempfile::tempdir().unwrap();
    let (scene, meshes) = fixture(tmp.path(), None);
    let h5 = pinion_h5(&meshes);
    let (np, o0, offsets) = own_block(&h5);
    let neighbour = (o0 + 1) % offsets;
    for k in [o0 * np * np + np + 2, neighbour * np * np + 3] {
        let fresh = tempfile::tempdir().unwrap();
        let (scene, meshes) = fixture(fresh.path(), None);
        let h5 = pinion_h5(&meshes);
        tamper_in(&h5, "compliance/global", k, |c| -c);
        relist(&meshes, &h5);
        let e = check_pinion(&scene, &meshes).unwrap_err().to_string();
        assert!(
            e.contains("compliance/global") && e.contains("total - local"),
            "{e}"
        );
    }
    check_pinion(&scene, &meshes).unwrap();
}

#[test]
fn design_edited_between_stages_is_refused_naming_the_design() {
    let tmp = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let text = std::fs::read_to_string(root.join("reference/white_paper_20x43.toml")).unwrap();
    // The geometry only (its published tables are named relative to it).
    let geometry = geometry::design::geometry_text(&text);
    let edited = geometry.replace("edge_radius_mm = 0.8", "edge_radius_mm = 0.7");
    assert_ne!(geometry, edited, "the design file's edge radius line");
    let design = tmp.path().join("design.toml");
    std::fs::write(&design, edited).unwrap();
    let (scene, meshes) = fixture(tmp.path(), Some(&design));
    let e = check_pinion(&scene, &meshes).unwrap_err();
    assert!(
        matches!(&e, CheckError::StaleMesh { fields, .. } if fields.iter().any(|f| f.starts_with("design_sha256"))),
        "{e}"
    );
}

#[test]
fn damaged_mesh_file_is_not_reused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let stem = "pinion_standard_reduced";
    let msh = formats::paths::msh(dir, stem);
    std::fs::write(&msh, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n").unwrap();
    // Unlisted (made before manifests): reused, and listed then.
    assert!(preprocess::mesh_stage::mesh_intact(dir, stem));
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/02_ltca_fixture/meshes")
        .join(SCENE);
    let mut m = Manifest::read(&fixture).unwrap();
    let mut e = m.meshes.remove(stem).unwrap();
    e.msh_sha256 = formats::manifest::sha256_file(&msh).unwrap();
    Manifest::update(dir, |n| {
        n.meshes.insert(stem.into(), e);
    })
    .unwrap();
    assert!(preprocess::mesh_stage::mesh_intact(dir, stem));
    // Truncated: not the listed file any more.
    std::fs::write(&msh, "$MeshFormat\n4.1 0 8\n").unwrap();
    assert!(!preprocess::mesh_stage::mesh_intact(dir, stem));
}
