//! The seed pairs of `reference/` through the whole chain on their scenes
//! (`reference/scenes/seed*.toml`: standard blanks, 6 × 10 flank elements,
//! one load): meshes (reused from `<target>/tmp/seed_pairs/` when the
//! preprocess crate's seed-pair tests made them with the same inputs),
//! stiffness files, loaded TCA and the multibody run.

use geometry::scene::Scene;
use std::path::PathBuf;

fn runs_flanks_to_multibody(name: &str) {
    let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../reference/scenes"))
        .join(format!("{name}.toml"));
    let scene = Scene::load(&path).unwrap();
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("seed_pairs");
    let out = root.join("out");
    preprocess::mesh_stage::run(&scene, &root, preprocess::mesh_stage::Level::Reduced)
        .unwrap_or_else(|e| panic!("{name}, meshes: {e:#}"));
    let stiffness = preprocess::stiffness_stage::run(&scene, &root)
        .unwrap_or_else(|e| panic!("{name}, stiffness files: {e:#}"));
    assert_eq!(stiffness.len(), 2, "{name}");
    let ltca = solver::stage::ltca::run(&scene, &root, &out)
        .unwrap_or_else(|e| panic!("{name}, LTCA: {e:#}"));
    let dynamic = solver::stage::dynamic::run(&scene, &root, &out)
        .unwrap_or_else(|e| panic!("{name}, multibody: {e:#}"));

    let d = &scene.pair;
    let ratio = d.members[1].teeth as f64 / d.members[0].teeth as f64;
    assert_eq!(ltca.len(), 1, "{name}: one blank pair");
    let torques = &scene.scene.pinion_torque_nm;
    let b = &ltca[0];
    assert_eq!(b.loads.len(), torques.len());
    for (l, &t) in b.loads.iter().zip(torques) {
        // The wheel takes the pinion torque times the ratio (no friction).
        assert!(
            (l.wheel_torque_mean_nm / (t * ratio) - 1.0).abs() < 1e-6,
            "{name}: wheel torque {} N·m at {t} N·m",
            l.wheel_torque_mean_nm
        );
        // Loaded TE above the unloaded, finite, with a finite stiffness.
        assert!(
            l.te_mean_urad > b.utca_te_mean_urad && l.te_mean_urad.is_finite(),
            "{name}: loaded TE {} µrad, unloaded {} µrad",
            l.te_mean_urad,
            b.utca_te_mean_urad
        );
        assert!(l.mesh_stiffness_mean_nm_per_rad > 0.0 && l.max_pressure_mpa > 0.0);
        println!(
            "{name} {t} N·m: LTCA TE mean {:.2} µrad ptp {:.2} µrad (unloaded {:.2} / {:.2}), max pressure {:.0} MPa",
            l.te_mean_urad, l.te_ptp_urad, b.utca_te_mean_urad, b.utca_te_ptp_urad, l.max_pressure_mpa
        );
    }
    // The 10 rpm multibody run follows the quasi-static LTCA.
    assert_eq!(dynamic.len(), 1, "{name}: one blank pair");
    for (q, l) in dynamic[0].quasi_static.iter().zip(&b.loads) {
        let rel = q.te_mean_urad / l.te_mean_urad - 1.0;
        println!(
            "{name} {} N·m: multibody TE mean {:.2} µrad ptp {:.2} µrad ({} steps), {rel:+.2e} from the LTCA",
            q.torque_nm, q.te_mean_urad, q.te_ptp_urad, q.steps
        );
        assert!(
            rel.abs() < 0.01,
            "{name}: multibody TE mean {} µrad, LTCA {} µrad",
            q.te_mean_urad,
            l.te_mean_urad
        );
    }
    assert_eq!(dynamic[0].quasi_static.len(), torques.len());
    // The summaries the report reads are the writer's own type: what the
    // stages wrote reads back equal (a renamed or dropped field fails here).
    let stage = out.join(&scene.scene.name);
    let read_ltca: Vec<formats::summaries::BlankSummary> =
        validate::report::comparison::read(&stage.join("ltca/summary.json"))
            .unwrap()
            .expect("ltca/summary.json written");
    assert_eq!(read_ltca, ltca, "{name}: ltca/summary.json");
    let read_dynamic: Vec<formats::summaries::DynamicSummary> =
        validate::report::comparison::read(&stage.join("multibody/summary.json"))
            .unwrap()
            .expect("multibody/summary.json written");
    assert_eq!(read_dynamic, dynamic, "{name}: multibody/summary.json");
}

#[test]
fn seed001_9x40_runs_from_flanks_to_multibody() {
    runs_flanks_to_multibody("seed001_9x40");
}

#[test]
fn seed002_9x37_runs_from_flanks_to_multibody() {
    runs_flanks_to_multibody("seed002_9x37");
}

#[test]
fn seed003_16x27_runs_from_flanks_to_multibody() {
    runs_flanks_to_multibody("seed003_16x27");
}

#[test]
fn seed004_23x86_runs_from_flanks_to_multibody() {
    runs_flanks_to_multibody("seed004_23x86");
}
