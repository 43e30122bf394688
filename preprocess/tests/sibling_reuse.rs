//! Reuse of a sibling scene folder's mesh and stiffness files
//! (`preprocess::sibling_reuse`): copied when the inputs and the listed
//! SHA-256 agree, not when the inputs differ or the file is not the one the
//! sibling's manifest lists.

use formats::manifest::{
    sha256_file, BodyProperties, Manifest, MeshEntry, MeshInputs, StiffnessEntry,
};
use formats::paths::MeshLevel;
use geometry::design::Member;
use geometry::gear_body::Blank;
use geometry::generation::Side;
use geometry::scene::FlankElements;
use preprocess::sibling_reuse;
use std::path::Path;

const STEM: &str = "wheel_standard_reduced";

/// A sibling folder `a` holding the mesh STEM (inputs text `inputs`) and
/// its stiffness file (inputs hash "h1"), both listed in its manifest.
fn sibling(root: &Path, inputs: &str) {
    let a = root.join("a");
    std::fs::create_dir_all(&a).unwrap();
    for (ext, text) in [
        ("msh", "mesh bytes"),
        ("vtu", "vtu"),
        ("report.json", "{}"),
        ("inputs.json", inputs),
        ("stiffness.h5", "h5 bytes"),
        ("stiffness.json", "{}"),
    ] {
        std::fs::write(a.join(format!("{STEM}.{ext}")), text).unwrap();
    }
    let msh_sha256 = sha256_file(&a.join(format!("{STEM}.msh"))).unwrap();
    let h5_sha256 = sha256_file(&a.join(format!("{STEM}.stiffness.h5"))).unwrap();
    Manifest::update(&a, |m| {
        let mut e = MeshEntry {
            member: Member::Wheel,
            blank: Blank::Standard,
            level: MeshLevel::Reduced,
            inputs: MeshInputs {
                design_sha256: "d".into(),
                blank_dimensions: serde_json::Value::Null,
                flank_elements: FlankElements {
                    profile: 12,
                    face: 20,
                },
                loaded_flank: Side::Drive,
                refined_teeth: vec![0],
                opposite_refined_teeth: vec![],
                periodic_teeth: vec![],
            },
            inputs_hash: "x".into(),
            msh_sha256,
            body: BodyProperties {
                volume_m3: 1.0,
                density_kg_m3: 1.0,
                polar_moment_kgm2: 1.0,
                nodes: 1,
            },
            stiffness: Default::default(),
        };
        e.stiffness.insert(
            STEM.into(),
            StiffnessEntry {
                file: format!("{STEM}.stiffness.h5"),
                input_hash: "h1".into(),
                sha256: h5_sha256,
                solved_teeth: vec![2],
            },
        );
        m.meshes.insert(STEM.into(), e);
    })
    .unwrap();
}

#[test]
fn sibling_mesh_and_stiffness_file_are_copied_only_from_the_same_inputs_and_intact_files() {
    let root = tempfile::tempdir().unwrap();
    let (r, b) = (root.path(), root.path().join("b"));
    sibling(r, "same");
    // Other inputs: nothing copied.
    assert!(sibling_reuse::mesh(r, &b, STEM, |t, _| t == "other").is_none());
    assert!(sibling_reuse::stiffness(r, &b, STEM, STEM, "h2").is_none());
    assert!(!b.join(format!("{STEM}.msh")).exists());
    // Same inputs: the four mesh files and the two stiffness files.
    assert_eq!(
        sibling_reuse::mesh(r, &b, STEM, |t, _| t == "same").map(|(from, _)| from),
        Some(r.join("a"))
    );
    assert_eq!(
        std::fs::read_to_string(b.join(format!("{STEM}.msh"))).unwrap(),
        "mesh bytes"
    );
    assert!(b.join(format!("{STEM}.inputs.json")).is_file());
    assert!(sibling_reuse::stiffness(r, &b, STEM, STEM, "h1").is_some());
    assert_eq!(
        std::fs::read_to_string(b.join(format!("{STEM}.stiffness.h5"))).unwrap(),
        "h5 bytes"
    );
    // A sibling file that is not the one its manifest lists is not copied.
    let c = root.path().join("c");
    std::fs::write(r.join("a").join(format!("{STEM}.msh")), "changed").unwrap();
    std::fs::write(r.join("a").join(format!("{STEM}.stiffness.h5")), "changed").unwrap();
    assert!(sibling_reuse::mesh(r, &c, STEM, |t, _| t == "same").is_none());
    assert!(sibling_reuse::stiffness(r, &c, STEM, STEM, "h1").is_none());
}
