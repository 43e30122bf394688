//! `preprocess housing` on a coarse version of the white-paper gearbox's
//! housing (25 mm elements, fixed-interface modes to 10 kHz, checked to
//! 2.5 kHz): the mesh fills the CAD volume, every bearing seat has its bore
//! nodes, the reduced model's modes lie on or above the whole FE housing's
//! and within 1 % of them, a rerun reuses the file, and a changed housing
//! makes a new one.

use formats::housing_file;
use geometry::scene::Scene;
use std::path::{Path, PathBuf};

fn coarse_scene(dir: &Path, rim_mm: f64) -> PathBuf {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let text = std::fs::read_to_string(root.join("reference/scenes/white_paper_gearbox.toml"))
        .unwrap()
        .replace(
            "design = \"../white_paper_20x43.toml\"",
            &format!(
                "design = \"{}\"",
                root.join("reference/white_paper_20x43.toml").display()
            ),
        );
    let mut v: toml::Value = toml::from_str(&text).unwrap();
    let gb = v["bearings"]["gearbox"].as_table_mut().unwrap();
    gb.insert("modes_up_to_hz".into(), toml::Value::Float(2500.0));
    let h = gb["housing"].as_table_mut().unwrap();
    h.insert("element_mm".into(), toml::Value::Float(25.0));
    h.insert("modes_up_to_hz".into(), toml::Value::Float(10000.0));
    h.insert("rim_mm".into(), toml::Value::Float(rim_mm));
    let p = dir.join("coarse_gearbox.toml");
    std::fs::write(&p, toml::to_string(&v).unwrap()).unwrap();
    p
}

#[test]
fn coarse_housing_reduction_matches_the_whole_fe_housing_below_its_range() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = Scene::load(&coarse_scene(tmp.path(), 20.0)).unwrap();
    let meshes = tmp.path().join("meshes");
    let r = preprocess::housing_stage::run(&scene, &meshes)
        .unwrap()
        .expect("the scene has a housing");
    assert!(!r.reused);
    let d = &r.data;
    // The tet10 mesh fills the CAD volume (flat faces and a curved bore).
    let v = r.volume_error.unwrap();
    assert!(v.abs() < 1e-4, "mesh volume / CAD − 1 = {v}");
    // Four seats, each with nodes on its bore; seat references at the
    // bearings' centres on the members' axes.
    assert_eq!(d.seat_member, vec![0, 0, 1, 1]);
    assert!(d.seat_nodes.iter().all(|&n| n >= 20), "{:?}", d.seat_nodes);
    // The reduced model's modes bound the whole housing's from above and
    // lie within 1 % below the checked range.
    assert!(!d.reduced_hz.is_empty());
    for (x, y) in d.reduced_hz.iter().zip(&d.reference_hz) {
        assert!(
            *x >= y * (1.0 - 1e-9),
            "reduced {x} Hz below the whole housing's {y} Hz"
        );
    }
    eprintln!(
        "coarse housing: {} nodes, {} modes kept, modes {:?} Hz against {:?} Hz, truncation {:.2e}",
        d.nodes,
        d.fixed_interface_hz.len(),
        d.reduced_hz,
        d.reference_hz,
        r.truncation_error
    );
    assert!(r.truncation_error < 0.01, "{}", r.truncation_error);
    // K_r and M_r symmetric; M_r positive definite.
    let n = d.coordinates();
    let k = nalgebra::DMatrix::from_row_slice(n, n, &d.stiffness);
    let m = nalgebra::DMatrix::from_row_slice(n, n, &d.mass);
    assert!((&k - k.transpose()).norm() <= 1e-12 * k.norm());
    assert!(m.clone().cholesky().is_some());

    // A rerun reuses the file.
    let again = preprocess::housing_stage::run(&scene, &meshes)
        .unwrap()
        .unwrap();
    assert!(again.reused);
    assert_eq!(&again.data, d);

    // A wider rim is another housing: a new file with another hash.
    let thicker = Scene::load(&coarse_scene(tmp.path(), 30.0)).unwrap();
    let t = preprocess::housing_stage::run(&thicker, &meshes)
        .unwrap()
        .unwrap();
    assert!(!t.reused);
    assert_ne!(t.data.input_hash, d.input_hash);
    assert!(t.data.mass_kg > d.mass_kg);
    // The old hash no longer reads it.
    let e = housing_file::read(&t.path, Some(&d.input_hash)).unwrap_err();
    assert!(e.to_string().contains("input hash"), "{e}");
}
