//! The report's part on the mesh stiffness against the FE reference from
//! synthetic `validate mesh-stiffness` summaries: the table rows formatted
//! from the summary, the verdict on our LTCA by its distance to the finest
//! FE level (within / beyond 10 %), seed 004's published 3.5e8 N/m set
//! against the FE with the ratio computed, and an absent summary in one
//! line.

use validate::report::sections::lumped_fe_stiffness::{markdown, SCENES};
use validate::studies::mesh_stiffness::{
    FeLevelCost, MeshStiffnessSummary, ModelStiffness, TorqueStiffness, SUMMARY_FILE,
};

fn model(m: &str, level: &str, k: f64, vs: f64) -> ModelStiffness {
    ModelStiffness {
        model: m.into(),
        level: level.into(),
        elements: if level == "reduced" {
            [6, 10]
        } else {
            [35, 75]
        },
        te_urad: 800.0,
        unloaded_te_urad: 2.0,
        tangent_nm_per_rad: k * 1e-3,
        secant_nm_per_rad: 0.9 * k * 1e-3,
        tangent_n_per_m: k,
        secant_n_per_m: 0.9 * k,
        tangent_check_n_per_m: (m == "fe").then_some(1.01 * k),
        pairs_in_contact: (m == "ltca").then_some([1, 1, 1]),
        tangent_vs_finest_fe_pct: Some(vs),
    }
}

fn summary(scene: &str, k_fe: f64, k_ltca: f64) -> MeshStiffnessSummary {
    let vs = (k_ltca - k_fe) / k_fe * 100.0;
    MeshStiffnessSummary {
        scene: scene.into(),
        design: "d".into(),
        teeth: [16, 27],
        position_index: 5,
        pinion_rotation_deg: 2.5,
        position_choice: "chosen".into(),
        pairs_in_contact: vec![2, 1, 1, 1, 2],
        cycle_tangent_n_per_m: [5e7, 6e7, 7e7],
        torques: vec![TorqueStiffness {
            torque_nm: 45.63,
            tangent_torques_nm: [43.3485, 45.63, 47.9115],
            levers_m: [0.025, 0.043],
            models: vec![
                model("fe", "reduced", 0.99 * k_fe, -1.0),
                model("fe", "reference", k_fe, 0.0),
                model("ltca", "reduced", k_ltca, vs),
            ],
            fe_extrapolated_tangent_n_per_m: None,
            fe_observed_order: None,
        }],
        fe_levels: vec![FeLevelCost {
            level: "reference".into(),
            elements: [35, 75],
            dofs: [449652, 511908],
            constraints: 1087,
            factor_gb: [2.35, 2.65],
            estimated_factor_gb: [2.2, 2.6],
            factor_s: [61.0, 65.0],
            position_s: 15.0,
            unloaded_te_urad: 2.0,
            utca_te_urad: 1.92,
        }],
        fe_levels_skipped: vec![],
        ltca_levels_skipped: vec![],
        lumped_scene: None,
        reduced_meshes_match_lumped: Some(true),
        roughness: None,
        penalty_factors: [100.0, 200.0],
        peak_memory_gb: 5.3,
        wall_s: 191.0,
    }
}

#[test]
fn fe_stiffness_part_formats_the_summaries_and_judges_the_ltca_by_its_distance_to_the_fe() {
    let out = tempfile::tempdir().unwrap();
    let write = |scene: &str, s: &MeshStiffnessSummary| {
        let dir = out.path().join(scene).join("mesh_stiffness");
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join(SUMMARY_FILE), serde_json::to_string(s).unwrap()).unwrap();
    };
    let missing = markdown(out.path());
    for (scene, _) in SCENES {
        assert!(
            missing.contains(&format!("No study of `{scene}`")),
            "{missing}"
        );
    }
    write(SCENES[0].0, &summary(SCENES[0].0, 5.6457e7, 5.6175e7));
    write(SCENES[1].0, &summary(SCENES[1].0, 1.0e8, 1.2e8));
    let md = markdown(out.path());
    for row in [
        "| 45.63 | FE reference | reference | 35 × 75 | 800.0 | 5.6457e7 | 5.0811e7 | +0.00 % | 5.7022e7 | – |",
        "| 45.63 | our LTCA | reduced | 6 × 10 | 800.0 | 5.6175e7 | 5.0558e7 | -0.50 % | – | 1 1 1 |",
        "| reference | 35 × 75 | 449652 + 511908 | 1087 | 2.35 + 2.65 | 2.20 + 2.60 | 61 + 65 | 15.0 | 2.000 / 1.920 |",
        "-0.5 % from the FE reference on the reference level (35 × 75, 5.646e7 N/m): within 10 %",
        "+20.0 % from the FE reference on the reference level (35 × 75, 1.000e8 N/m): more than 10 % apart",
        // 3.5e8 / 1.0e8 from the constant and the synthetic FE value.
        "the FE reference at this position is 1.00e8 N/m, 3.5 times smaller than the published value",
        "the same (same inputs hash) as",
        // Cycle mean and largest (6e7, 7e7) scaled by FE/LTCA = 1e8/1.2e8.
        "is 5.00e7 N/m, 7.0 times smaller, and the largest value of the cycle so scaled, 5.83e7 N/m, 6.0 times",
    ] {
        assert!(md.contains(row), "{row} missing in\n{md}");
    }
    assert!(!md.contains("No study of"), "{md}");
}
