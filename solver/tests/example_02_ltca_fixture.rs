//! Example 02 (`examples/02_ltca_fixture/`): the loaded TCA of the reduced
//! model run by the solver alone, from a checked-in stiffness fixture (the
//! mesh folder's `manifest.json` and the two `*.stiffness.h5` files; no
//! meshes, no gmsh, no FE), against `examples/02_ltca_fixture/golden.json`.
//! `BLESS=1` rewrites the golden file; `regenerate.sh` in the example
//! remakes the fixture with the preprocess stages.
//!
//! Tolerance: relative 1e-9 (absolute 1e-9 on the torque balance, which is
//! zero to rounding). Two runs on the same machine agree bit for bit.

#[path = "../../examples/golden.rs"]
mod golden;

use geometry::scene::Scene;
use golden::Quantity;
use std::path::{Path, PathBuf};

const REL: f64 = 1e-9;

/// A scratch folder under the target directory, removed when dropped.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Every file of the fixture folder with its bytes.
fn fixture_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn example_02_ltca_from_the_stiffness_fixture_matches_its_golden_output() {
    let dir = golden::example_dir(env!("CARGO_MANIFEST_DIR"), "02_ltca_fixture");
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let meshes = dir.join("meshes");
    let fixture = meshes.join(&scene.scene.name);

    // The fixture holds the manifest and stiffness files only, well under 2 MB.
    let before = fixture_files(&fixture);
    let names: Vec<&str> = before.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"manifest.json"), "{names:?}");
    assert!(
        names
            .iter()
            .all(|n| *n == "manifest.json" || n.ends_with(".stiffness.h5")),
        "only manifest.json and *.stiffness.h5 belong in {}: {names:?}",
        fixture.display()
    );
    let bytes: usize = before.iter().map(|(_, b)| b.len()).sum();
    assert!(bytes < 2_000_000, "fixture is {bytes} bytes");

    let scratch = Scratch(
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("example_02_{}", std::process::id())),
    );
    let res = solver::stage::ltca::run(&scene, &meshes, &scratch.0).unwrap_or_else(|e| {
        panic!(
            "{e:#}\n(if the stiffness fixture is stale, run examples/02_ltca_fixture/regenerate.sh)"
        )
    });
    assert_eq!(
        fixture_files(&fixture),
        before,
        "the solver changed its input fixture"
    );
    assert_eq!(res.len(), 1, "one pinion x wheel blank");
    let b = &res[0];
    for f in [
        "te.csv",
        "pairs.csv",
        "slices.csv",
        "wheel_torque.csv",
        "ltca.h5",
        "summary.json",
    ] {
        assert!(
            b.dir.join(f).is_file(),
            "{f} missing in {}",
            b.dir.display()
        );
    }

    let ratio = scene.pair.members[0].teeth as f64 / scene.pair.members[1].teeth as f64;
    let mut q = vec![
        Quantity::new("positions", b.positions as f64, "", 0.0, 0.0),
        Quantity::new("utca_te_mean_urad", b.utca_te_mean_urad, "urad", REL, 1e-9),
        Quantity::new("utca_te_ptp_urad", b.utca_te_ptp_urad, "urad", REL, 1e-9),
    ];
    for l in &b.loads {
        let t = l.torque_nm;
        q.push(Quantity::new(
            format!("{t}nm.te_mean_urad"),
            l.te_mean_urad,
            "urad",
            REL,
            1e-9,
        ));
        q.push(Quantity::new(
            format!("{t}nm.te_ptp_urad"),
            l.te_ptp_urad,
            "urad",
            REL,
            1e-9,
        ));
        q.push(Quantity::new(
            format!("{t}nm.max_pressure_mpa"),
            l.max_pressure_mpa,
            "MPa",
            REL,
            0.0,
        ));
        q.push(Quantity::new(
            format!("{t}nm.mesh_stiffness_mean_nm_per_rad"),
            l.mesh_stiffness_mean_nm_per_rad,
            "N m/rad",
            REL,
            0.0,
        ));
        q.push(Quantity::new(
            format!("{t}nm.max_pair_share"),
            l.max_pair_share,
            "",
            REL,
            0.0,
        ));
        q.push(Quantity::new(
            format!("{t}nm.wheel_torque_mean_nm"),
            l.wheel_torque_mean_nm,
            "N m",
            REL,
            0.0,
        ));
        // Frictionless: the wheel torque is the pinion torque times z2/z1.
        let balance = l.wheel_torque_mean_nm * ratio / t - 1.0;
        q.push(Quantity::new(
            format!("{t}nm.wheel_torque_balance"),
            balance,
            "",
            0.0,
            1e-9,
        ));
    }

    // The balance at every position (wheel_torque.csv, 6 decimals).
    let csv = std::fs::read_to_string(b.dir.join("wheel_torque.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        for (l, w) in b.loads.iter().zip(&v[1..]) {
            let off = (w * ratio / l.torque_nm - 1.0).abs();
            assert!(
                off < 1e-6,
                "wheel torque balance {off:e} at {} deg, {} N m",
                v[0],
                l.torque_nm
            );
        }
    }

    golden::check(
        &dir.join("golden.json"),
        "examples/02_ltca_fixture: solver::stage::ltca::run on examples/02_ltca_fixture/scene.toml from the stiffness fixture in its meshes/ (test solver/tests/example_02_ltca_fixture.rs)",
        &q,
    );
}
