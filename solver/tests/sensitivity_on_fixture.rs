//! `solver sensitivity` on the checked-in example-02 stiffness fixture (no
//! gmsh): four curves of the scene's 9 values, the middle value of each the
//! scene's own (aligned) LTCA, the summary's CSV and charts written as one
//! result set, and the stiffness files only read; without root-stress
//! coefficients in the files, no root stress.

use geometry::misalignment::Component;
use geometry::scene::Scene;
use std::path::{Path, PathBuf};

/// A scratch folder under the target directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        Scratch(
            Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}_{}", std::process::id())),
        )
    }
    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn sensitivity_study_sweeps_each_misalignment_around_the_aligned_ltca() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture");
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let meshes = dir.join("meshes");
    let fixture = meshes.join(&scene.scene.name);
    let before: Vec<_> = std::fs::read_dir(&fixture)
        .unwrap()
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .collect();
    let out = Scratch::new("sensitivity_study");
    let s = solver::stage::sensitivity::run(&scene, &meshes, out.path()).unwrap();
    let after: Vec<_> = std::fs::read_dir(&fixture)
        .unwrap()
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .collect();
    assert_eq!(before, after, "the study changed its stiffness files");
    let sdir = out.path().join(&scene.scene.name).join("sensitivity");
    for f in ["summary.json", "summary.csv", "run.json"]
        .into_iter()
        .chain(solver::stage::sensitivity::CHART_FILES.iter().map(|c| c.0))
    {
        assert!(sdir.join(f).is_file(), "{f} missing");
    }
    // The fixture's files hold no root-stress coefficients: no root stress,
    // no root-stress charts, empty CSV cells.
    for (f, _) in solver::stage::sensitivity::ROOT_STRESS_CHART_FILES {
        assert!(!sdir.join(f).exists(), "{f} written without root stress");
    }
    assert!(s
        .curves
        .iter()
        .flat_map(|c| &c.points)
        .flat_map(|p| &p.loads)
        .all(|l| l.root_stress.is_none()));
    let csv = std::fs::read_to_string(sdir.join("summary.csv")).unwrap();
    assert!(csv.lines().skip(1).all(|l| l.ends_with(",,,")), "{csv}");
    let torques = scene.scene.pinion_torque_nm.len();
    assert_eq!(csv.lines().count(), 1 + 4 * 9 * torques);
    // The aligned LTCA of the same scene.
    let ltca_out = Scratch::new("sensitivity_ltca");
    let ltca = solver::stage::ltca::run(&scene, &meshes, ltca_out.path()).unwrap();
    assert_eq!(s.curves.len(), 4);
    for (c, curve) in Component::ALL.iter().zip(&s.curves) {
        assert_eq!(curve.component, *c);
        assert_eq!(curve.points.len(), 9);
        let mid = &curve.points[4];
        assert_eq!(mid.value, 0.0);
        assert!(mid.misalignment.is_zero());
        for (l, a) in mid.loads.iter().zip(&ltca[0].loads) {
            assert!((l.te_ptp_urad - a.te_ptp_urad).abs() < 1e-9, "{c:?}");
            assert!((l.te_mean_urad - a.te_mean_urad).abs() < 1e-9, "{c:?}");
            assert!(
                (l.max_pressure_mpa - a.max_pressure_mpa).abs() < 1e-9,
                "{c:?}"
            );
        }
        // Every misalignment moves the mean TE (backlash and pose), the
        // more the larger it is: the ends differ from the middle most.
        let at = |k: usize| curve.points[k].loads[torques - 1].te_mean_urad;
        assert!(
            (at(0) - at(4)).abs() > (at(3) - at(4)).abs()
                && (at(8) - at(4)).abs() > (at(5) - at(4)).abs(),
            "{c:?}: mean TE {} {} {} {} {}",
            at(0),
            at(3),
            at(4),
            at(5),
            at(8)
        );
    }
}
