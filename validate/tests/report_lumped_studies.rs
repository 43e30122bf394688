//! Seed 004's two design studies in the report's lumped section, from
//! synthetic ease-off variants: the TE-slope rows matched by m′₂₁ with
//! seed 004's impact forces beside ours and both rises computed; the
//! contact-ratio rows (its Table 4) matched to our run of nearest measured
//! contact ratio; only the scene's base run gets a Table 3; no variants, no
//! study tables.

#[path = "support/lumped_summary.rs"]
mod lumped_summary;

use lumped_summary::{run, variant};
use validate::report::sections::lumped::{section, LUMPED_SCENE};
use validate::report::sections::lumped_studies::markdown;

#[test]
fn te_slope_and_contact_ratio_studies_sit_beside_seed004() {
    let base = || {
        let mut r = run(77.0, None, 7.0e7, 1.0);
        r.variant = String::new();
        r
    };
    let all = vec![
        base(),
        variant(base(), -0.001, 30.0, 1.84, 100.0, [1000.0, 50.0]),
        variant(base(), -0.005, 30.0, 1.41, 300.0, [2000.0, 100.0]),
        variant(base(), -0.010, 30.0, 1.25, 700.0, [4000.0, 250.0]),
        variant(base(), -0.00001, 400.0, 1.66, 800.0, [9000.0, 280.0]),
        variant(base(), -0.00001, 80.0, 1.84, 200.0, [1200.0, 70.0]),
        variant(base(), -0.00001, 10.0, 2.25, 50.0, [600.0, 35.0]),
    ];
    let mut s = String::new();
    markdown(&mut s, &all);
    for row in [
        "| -0.001 | 9.33 | 1.840 | 7.0000e7 | 100 | 26356.5 | 1000.0 | 50.0 |",
        "| -0.010 | 93.30 | 1.250 | 7.0000e7 | 700 | 30321.3 | 4000.0 | 250.0 |",
        "| 1.65 | 400 / 4 | 1.660 | 7.0000e7 | 3.3097e8 | 800 | 5977.3 | 9000.0 | 280.0 | 2418.19 |",
        "| 1.85 | 80 / 4 | 1.840 | 7.0000e7 | 3.7518e8 | 200 | 5515.1 | 1200.0 | 70.0 | 922.54 |",
        "| 2.25 | 10 / 4 | 2.250 | 7.0000e7 | 4.3281e8 | 50 | 5156.8 | 600.0 | 35.0 | 467.38 |",
    ] {
        assert!(s.contains(row), "row {row} missing in\n{s}");
    }
    // 700/100 − 1 = +600 %; 30321.3/26356.5 − 1 = +15.0 %; RMS +300 % and +400 %.
    assert!(
        s.contains("our impact force +600 %, seed 004's +15.0 %"),
        "{s}"
    );
    assert!(s.contains("+300 % (λ̈) and +400 % (v·q̈)"));
    // 100/26356.5 = 0.4 %, 700/30321.3 = 2.3 %.
    assert!(s.contains("Our impact forces are 0.4–2.3 % of seed 004's"));
    // Table 4: 50/800 − 1 = −94 %; 600/9000 − 1 = −93 %; seed 004's stiffness 4.7–6.2 times ours.
    assert!(
        s.contains("impact force -94 % (-14 %), RMS λ̈ -93 % (-81 %)"),
        "{s}"
    );
    assert!(s.contains("Seed 004's stiffness is 4.7–6.2 times ours"));

    let mut none = String::new();
    markdown(&mut none, &all[..1]);
    assert!(none.is_empty());

    // In the section, only the base run gets seed 004's Table 3.
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join(LUMPED_SCENE).join("lumped");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("summary.json"),
        serde_json::to_string(&all).unwrap(),
    )
    .unwrap();
    let md = section(Some(out.path()), reports.path()).markdown;
    assert_eq!(md.matches("| Pinion X (axial) |").count(), 1, "{md}");
    assert!(md.contains("### Seed 004's TE-slope study"));
    assert!(md.contains("### Seed 004's contact-ratio study (its Table 4)"));
}
