//! The report's seed 003 part from synthetic `solver lumped` summaries (the
//! smooth pair and one roughness grade at both loads): our velocities
//! formatted beside the test rig's measured 4.195 / 4.384 mm/s and seed
//! 003's simulated 4.06 / 4.116, the runs matched to the loads by the
//! pinion torque T₂ × 16/27, the stiffness change against the smooth
//! flanks, the roughness the model carries; an absent summary in one line.

#[path = "support/lumped_summary.rs"]
mod lumped_summary;

use lumped_summary::run;
use validate::report::sections::lumped_seed003::{markdown, SEED003_SCENE};

#[test]
fn seed003_part_puts_our_velocities_beside_the_test_rig_and_says_what_the_roughness_is() {
    let out = tempfile::tempdir().unwrap();
    let dir = out.path().join(SEED003_SCENE).join("lumped");
    std::fs::create_dir_all(&dir).unwrap();
    let runs = vec![
        run(77.0, None, 6.0e7, 1.5),
        run(105.0, None, 6.2e7, 1.8),
        run(77.0, Some(0.8), 6.03e7, 2.1),
        run(105.0, Some(0.8), 6.31e7, 2.4),
    ];
    std::fs::write(
        dir.join("summary.json"),
        serde_json::to_string(&runs).unwrap(),
    )
    .unwrap();
    let md = markdown(out.path());
    for row in [
        "| 77 | 45.63 | 1.500 | 2.100 | 4.195 / 4.123 | 4.060 / 4.055 |",
        "| 105 | 62.22 | 1.800 | 2.400 | 4.384 / 4.413 | 4.116 / 4.135 |",
        // Seed 003's Table 2 against its two fits of D.
        "| 0.2 | 1.65 | 1.746 (+0.096) | 1.635 (-0.015) |",
        "| 45.63 | smooth | 0.600 | 6.0000e7 | +0.00 | 1.500 / 1.000 | 150.0 |",
        "| 45.63 | Ra 0.8 µm | 0.611 | 6.0300e7 | +0.50 | 2.100 / 1.000 | 150.0 |",
        "| 62.22 | Ra 0.8 µm | 0.611 | 6.3100e7 | +1.77 | 2.400 / 1.000 | 150.0 |",
        "| 0.8 | 1.131 | 1.545 | 4.50e-9 | 2 / 15 | 1.000 / 1.400 (71 %) | 0.533 | 0.189 | 1.258 | 0.241 |",
    ] {
        assert!(md.contains(row), "row {row} missing in\n{md}");
    }
    // 1.5 / 4.195 = 36 %, 2.4 / 4.384 = 55 %; smooth rise 1.8 / 1.5 = +20 %, measured +4.5 %.
    assert!(
        md.contains("Ours are 36–55 % of the measured values"),
        "{md}"
    );
    assert!(md.contains("ours +20 % from 77 to 105 N·m"));
    assert!(md.contains("measured +4.5 %"));
    assert!(md.contains("neither a calibration nor a validation"));
    assert!(md.contains("the two do not agree; the comparison below uses the text's"));
    assert!(
        md.contains("from the smooth flanks through Ra 0.8 µm, the mean stiffness rises with every grade at 45.63 N·m and rises with every grade at 62.22 N·m"),
        "{md}"
    );
    // Eq. (31) with Table 2's L and D is no roughness in µm: 823 at Ra 0.8.
    assert!(md.contains("823 at Ra 0.8"), "{md}");
    assert!(md.contains("R = √2 Ra, the composite roughness of two flanks of roughness Ra (our choice, not the seed's)"));
    assert!(md.contains("1200 rpm (mesh frequency 320.0 Hz)"));
}

#[test]
fn absent_seed003_summary_is_one_line() {
    let out = tempfile::tempdir().unwrap();
    let md = markdown(out.path());
    let body: Vec<&str> = md
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .collect();
    assert_eq!(body.len(), 1, "{md}");
    assert!(body[0].starts_with("No seed 003 run:"));
    assert!(!md.contains('|'));
}
