//! Example 04 (`examples/04_machine_settings/`): the flank stage on a design
//! file that gives each flank's machine settings instead of an ease-off
//! (the white-paper pair's, by local synthesis), its key numbers against
//! `examples/04_machine_settings/golden.json`; and the settings it writes
//! back are the ones the design gives (within 1e-12 relative: they go
//! through SI units and back). `BLESS=1` rewrites the golden file.
//!
//! Tolerance: relative 1e-9 on every value, plus an absolute floor for
//! values that can be near zero (1e-12 m on positions, 1e-9 µm / µrad /
//! deg on ease-off, TE and angles), as example 01.

#[path = "../../examples/golden.rs"]
mod golden;

#[path = "support/flank_example.rs"]
mod flank_example;

use flank_example::{flank_quantities, num, read, summary_quantities, utca_quantities, REL};
use golden::Quantity;
use preprocess::flank_stage::{load_input, run_stage};

#[test]
fn example_04_machine_settings_matches_its_golden_output() {
    let dir = golden::example_dir(env!("CARGO_MANIFEST_DIR"), "04_machine_settings");
    let input = load_input(&dir.join("scene.toml")).unwrap();
    assert!(
        input.pair.machine_settings.is_some(),
        "the design gives settings"
    );
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("flanks");
    let summary = run_stage(&input, &out).unwrap();

    let mut q = Vec::new();
    let s = read(&out.join("summary.json"));
    assert_eq!(s["machine_settings"]["source"], "design_file");
    summary_quantities(&mut q, &s, &summary);
    utca_quantities(&mut q, &read(&out.join("utca.json")));
    flank_quantities(&mut q, &read(&out.join("flanks.json")));

    // The settings written back are the design's, and the pinion's
    // summary gives what they cut: the deviation from the conjugate flank
    // at the toe-root corner, the mean point and the heel-tip corner.
    let written: toml::Value =
        toml::from_str(&std::fs::read_to_string(out.join("machine_settings.toml")).unwrap())
            .unwrap();
    let given: toml::Value =
        toml::from_str(&std::fs::read_to_string(dir.join("design.toml")).unwrap()).unwrap();
    same_settings(
        &written["machine_settings"],
        &given["machine_settings"],
        "machine_settings",
    );
    let pinion: toml::Value =
        toml::from_str(&std::fs::read_to_string(out.join("machine_settings_pinion.toml")).unwrap())
            .unwrap();
    for flank in ["concave", "convex"] {
        let dev = &pinion[flank]["deviation"]["deviation_um"];
        for (i, j) in [(0, 0), (2, 4), (4, 8)] {
            q.push(Quantity::new(
                format!("machine_settings_pinion.{flank}.deviation_um[{i}][{j}]"),
                dev[i][j].as_float().unwrap(),
                "um",
                REL,
                1e-9,
            ));
        }
        q.push(Quantity::new(
            format!("machine_settings_pinion.{flank}.spiral_angle_deg"),
            num(
                &serde_json::json!(pinion[flank]["spiral_angle_deg"].as_float().unwrap()),
                "spiral angle",
            ),
            "deg",
            REL,
            1e-9,
        ));
    }

    golden::check(
        &dir.join("golden.json"),
        "examples/04_machine_settings: preprocess::flank_stage::run_stage on examples/04_machine_settings/scene.toml (test preprocess/tests/example_04_machine_settings.rs)",
        &q,
    );
}

/// The two settings tables hold the same keys and values (numbers within
/// 1e-12 relative: mm and degrees go through SI and back).
fn same_settings(a: &toml::Value, b: &toml::Value, at: &str) {
    match (a, b) {
        (toml::Value::Table(x), toml::Value::Table(y)) => {
            let keys = |t: &toml::value::Table| t.keys().cloned().collect::<Vec<_>>();
            assert_eq!(keys(x), keys(y), "{at}");
            for (k, v) in x {
                same_settings(v, &y[k], &format!("{at}.{k}"));
            }
        }
        (toml::Value::Float(x), toml::Value::Float(y)) => {
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(1.0),
                "{at}: {x} against {y}"
            )
        }
        _ => assert_eq!(a, b, "{at}"),
    }
}
