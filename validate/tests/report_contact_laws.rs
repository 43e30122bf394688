//! The report's "Contact laws" section from synthetic multibody summaries
//! in a temporary `out/`: the rows carry both runs' numbers and the seeds'
//! published values, a seed without outputs is named absent (no zeros), and
//! a summary that cannot be used is an error naming the file.

use serde_json::{json, Value};
use std::path::Path;
use validate::report::published::seed_contact_laws;
use validate::report::sections::contact_laws::{build, ContactLawsError};

/// A load run whose numbers start at `base` (distinct per run and field),
/// with statistics sampled every 2 ms when `sample` is set.
fn load_run(base: f64, sample: bool) -> Value {
    let sampled = sample.then(|| {
        json!({
            "interval_s": 0.002, "samples": 400,
            "wheel_speed_mean_deg_s": 1873.4,
            "wheel_speed_fluctuation_mean_deg_s": base + 0.5,
            "wheel_speed_fluctuation_max_deg_s": base + 0.6,
            "tangential_force_mean_n": 25001.0 + base, "tangential_force_max_n": 26900.0 + base,
            "tangential_force_fluctuation_mean_n": base + 90.0,
            "tangential_force_fluctuation_max_n": base + 1900.0
        })
    });
    json!({
        "pinion_rpm": 1283.8333333333333, "pinion_ramp_s": 0.2,
        "wheel_torque_nm": 1964.99, "wheel_torque_rise_s": 0.0, "sim_time_s": 1.0,
        "steps": 1000 + base as usize, "rejected_steps": 7, "cpu_s": 2.5,
        "cpu_s_per_step": 4.5e-5, "window_s": [0.2, 0.9996], "window_mesh_cycles": 154,
        "wheel_speed_mean_deg_s": 1873.5, "wheel_speed_kinematic_deg_s": 1873.7027027027027,
        "wheel_speed_error": -1.0e-4,
        "wheel_speed_fluctuation_mean_deg_s": base + 0.11,
        "wheel_speed_fluctuation_max_deg_s": base + 0.22,
        "wheel_mesh_torque_mean_nm": 1964.0, "torque_balance_error": 1e-6,
        "pinion_mesh_torque_mean_nm": 486.0, "mesh_efficiency": 0.9876,
        "tangential_force_mean_n": 25000.0 + base, "tangential_force_max_n": 27000.0 + base,
        "tangential_force_theory_n": 23603.6,
        "tangential_force_error": (25000.0 + base) / 23603.6 - 1.0,
        "tangential_force_error_of_mean": (25000.0 + base - 23603.6) / (25000.0 + base),
        "tangential_force_fluctuation_mean_n": base + 100.0,
        "tangential_force_fluctuation_max_n": base + 2000.0,
        "contact_radius_mm": 1964.0 / (25000.0 + base) * 1e3,
        "outer_pitch_radius_mm": 83.25,
        "sampled": sampled,
        "mesh_force_mean_n": 35000.0, "mesh_force_max_n": 38000.0,
        "mesh_force_theory_n": 36000.0, "te_mean_urad": 140.0, "te_ptp_urad": 46.0
    })
}

fn run(law: &str, scene: &str, base: f64) -> Value {
    let impact = (law == "impact").then(|| {
        json!({
            "stiffness_n_per_mm_e": 6.65e7, "stiffness_source": "scene",
            "hertz_stiffness_n_per_mm_1_5": 5.0e5, "hertz_radii_mm": [20.25, 83.25],
            "exponent": 1.5, "damping_n_s_per_mm": 50.0, "penetration_depth_mm": 0.1,
            "static_friction": 0.08, "dynamic_friction": 0.05,
            "stiction_speed_mm_s": 100.0, "friction_transition_speed_mm_s": 1000.0
        })
    });
    json!([{
        "pinion_blank": "standard", "wheel_blank": "standard",
        "inertia_kgm2": [5e-5, 6e-3], "inertia_source": "mesh",
        "damping_nm_s_per_rad": 0.0,
        "friction_coefficient": if law == "element" { 0.05 } else { 0.0 },
        "table_positions": 320, "table_lag_nodes": 96, "table_build_s": 0.2,
        "table_cpu_s_per_position": 0.001, "quasi_static": [], "runup": null,
        "backlash_urad": null, "free_play_urad": null, "rattle": null,
        "force_law": law, "impact_law": impact, "load_run": load_run(base, law == "impact"),
        "dir": format!("somewhere/else/{scene}/multibody/standard_standard")
    }])
}

fn write(out: &Path, scene: &str, text: &str) {
    let d = out.join(scene).join("multibody");
    std::fs::create_dir_all(d.join("standard_standard")).unwrap();
    std::fs::write(d.join("summary.json"), text).unwrap();
}

/// Seed 002's two runs, the impact run with a speed chart.
fn seed_002(out: &Path) {
    write(
        out,
        "seed002_impact",
        &run("impact", "seed002_impact", 10.0).to_string(),
    );
    write(
        out,
        "seed002_element",
        &run("element", "seed002_element", 30.0).to_string(),
    );
    std::fs::write(
        out.join("seed002_impact/multibody/standard_standard/load_run_speed.svg"),
        "<svg id=\"speed-chart\"></svg>",
    )
    .unwrap();
}

fn row<'a>(md: &'a str, starts: &str) -> &'a str {
    md.lines()
        .find(|l| l.starts_with(starts))
        .unwrap_or_else(|| panic!("no row starting with {starts:?} in\n{md}"))
}

#[test]
fn rows_carry_both_runs_and_the_seeds_published_values() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    seed_002(&out);
    let cl = build(&out, None, &reports).unwrap();
    let md = &cl.markdown;
    assert!(md.contains("### Seed 002 (9/37 pair, UG NX 3D contact)"));
    // The seed's fluctuations stand on the rows sampled as it sampled
    // (2 ms); the element run was not sampled.
    assert_eq!(
        row(md, "| wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s, every step"),
        "| wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s, every step | 10.11 / 10.22 | 30.11 / 30.22 |  |"
    );
    assert_eq!(
        row(md, "| wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s, samples"),
        "| wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s, samples every 2 ms (400 samples) | 10.50 / 10.60 | not sampled | 13.5 / 86.9 (Section 3.3, Figure 7) |"
    );
    assert_eq!(
        row(md, "| tangential force fluctuation \\|F_t − mean\\| mean / max, N, samples"),
        "| tangential force fluctuation \\|F_t − mean\\| mean / max, N, samples every 2 ms (400 samples) | 100.0 / 1910.0 | not sampled | 117.53 / 1741.3 (Section 3.4, Figure 9) |"
    );
    assert_eq!(
        row(md, "| mean wheel speed against kinematic"),
        "| mean wheel speed against kinematic | -0.010 % | -0.010 % | 0.054 % (Table 2) |"
    );
    // The tangential force from the contact forces, on both bases, beside
    // the seed's printed difference and the one its two values give.
    assert_eq!(
        row(md, "| mean tangential force against 2T/d, (mean − 2T/d) / mean"),
        "| mean tangential force against 2T/d, (mean − 2T/d) / mean | +5.623 % | +5.699 % | 4.82 % (Table 2) |"
    );
    assert_eq!(
        row(md, "| mean tangential force against 2T/d, mean / (2T/d) − 1"),
        "| mean tangential force against 2T/d, mean / (2T/d) − 1 | +5.958 % | +6.043 % | +5.069 % (from Table 2's two values) |"
    );
    assert_eq!(
        row(md, "| largest tangential force, N"),
        "| largest tangential force, N | 27010.0 | 27030.0 | 26498.9 (Section 3.4, Figure 8) |"
    );
    assert!(row(md, "| where the contact acts").ends_with(
        "| 78.53 | 78.47 | 79.23 (the load / Table 2's mean; d/2 = 83.25 from its 2T/d) |"
    ));
    assert!(row(md, "| mean tangential force (contact forces")
        .ends_with("| 24799.9 against 2T/d = 23603.5 (Table 2) |"));
    let para = row(md, "- Tangential force:");
    assert!(
        para.contains("at 78.53 mm (impact law) and 78.47 mm (element), inside and inside the outer pitch circle"),
        "{para}"
    );
    assert!(
        para.contains("lies 5.62 % above and 5.70 % above 2T/d"),
        "{para}"
    );
    assert!(
        para.contains("puts its contact at 79.23 mm on average"),
        "{para}"
    );
    assert!(
        para.contains("Our element's contact lies 0.77 mm inside the seed's."),
        "{para}"
    );
    assert!(!md.contains("measures its averaging"));
    assert_eq!(
        row(md, "| steps (rejected)"),
        "| steps (rejected) | 1010 (7) | 1030 (7) |  |"
    );
    // The K of the run against the Hertz value of the summary (6.65e7 /
    // 5e5), and the element's constant μ.
    assert!(row(md, "| Hertz K = 4/3").ends_with("| 5.0000e5 | printed / recomputed = 133.000 |"));
    assert!(md.contains("| element runs: constant Coulomb μ | 0.05 | |"));
    assert!(
        row(md, "| K, N/mm^e").contains(&format!("{:.4e}", seed_contact_laws()[1].stiffness.value))
    );
    assert!(md.contains("133 times the value with the pitch radii"));
    // The chart that is there is copied and linked; the missing ones are
    // left out.
    assert_eq!(cl.figures.len(), 1);
    assert_eq!(cl.figures[0].svg, "<svg id=\"speed-chart\"></svg>");
    assert!(reports
        .join("contact_laws_seed002_impact_load_run_speed.svg")
        .exists());
    assert!(md.contains("](contact_laws_seed002_impact_load_run_speed.svg)"));
}

#[test]
fn an_absent_seed_is_named_absent_not_reported_as_zeros() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    seed_002(&out);
    let md = build(&out, None, &reports).unwrap().markdown;
    let line = row(md.as_str(), "Seed 001");
    assert!(line.contains("not run"), "{line}");
    assert!(
        line.contains("seed001_impact/multibody/summary.json"),
        "{line}"
    );
    assert!(
        line.contains("seed001_element/multibody/summary.json"),
        "{line}"
    );
    assert!(!md.contains("### Seed 001"));
    assert!(!md.contains("| seed 001 |"));
    // Only seed 002's table: one row of each quantity.
    assert_eq!(
        md.matches("| mean wheel speed against kinematic").count(),
        1
    );
}

#[test]
fn a_seed_with_one_run_missing_is_absent_and_names_that_file() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    write(
        &out,
        "seed002_impact",
        &run("impact", "seed002_impact", 10.0).to_string(),
    );
    let md = build(&out, None, &reports).unwrap().markdown;
    let line = row(md.as_str(), "Seed 002");
    assert!(
        line.contains("seed002_element/multibody/summary.json"),
        "{line}"
    );
    assert!(!line.contains("seed002_impact"), "{line}");
    assert!(!md.contains("|---|"), "no table without both runs:\n{md}");
}

#[test]
fn an_unreadable_summary_is_an_error_naming_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    seed_002(&out);
    write(&out, "seed001_element", "{ not json");
    let e = build(&out, None, &reports).unwrap_err();
    assert!(matches!(e, ContactLawsError::Parse { .. }), "{e:?}");
    assert!(
        e.to_string()
            .contains("seed001_element/multibody/summary.json"),
        "{e}"
    );
}

#[test]
fn a_summary_without_a_load_run_or_of_the_other_law_is_an_error() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    let mut v = run("impact", "seed002_impact", 10.0);
    v[0]["load_run"] = Value::Null;
    write(&out, "seed002_impact", &v.to_string());
    write(
        &out,
        "seed002_element",
        &run("element", "seed002_element", 30.0).to_string(),
    );
    let e = build(&out, None, &reports).unwrap_err();
    assert!(matches!(e, ContactLawsError::NoLoadRun { .. }), "{e:?}");
    assert!(e.to_string().contains("seed002_impact"), "{e}");
    write(
        &out,
        "seed002_impact",
        &run("element", "seed002_impact", 10.0).to_string(),
    );
    let e = build(&out, None, &reports).unwrap_err();
    assert!(matches!(e, ContactLawsError::WrongLaw { .. }), "{e:?}");
}

#[test]
fn the_section_and_its_charts_go_into_the_report_figures() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    seed_002(&out);
    let mut figs = validate::report::gather::ReportFigures {
        contact_laws: Some(build(&out, None, &reports).unwrap()),
        ..Default::default()
    };
    assert!(figs
        .all()
        .any(|f| f.file == "contact_laws_seed002_impact_load_run_speed.svg"));
    figs.contact_laws = None;
    assert_eq!(figs.all().count(), 0);
}

#[test]
fn seed_001_impact_law_with_the_haversine_ramp_stands_beside_the_cubic() {
    let tmp = tempfile::tempdir().unwrap();
    let (out, reports) = (tmp.path().join("out"), tmp.path().join("reports"));
    for (law, scene, base) in [
        ("impact", "seed001_impact", 10.0),
        ("element", "seed001_element", 30.0),
        ("impact", "seed001_impact_haversine", 50.0),
    ] {
        write(&out, scene, &run(law, scene, base).to_string());
    }
    let md = build(&out, None, &reports).unwrap().markdown;
    assert!(md.contains("(scene `seed001_impact_haversine`)"), "{md}");
    // Seed 001's printed K against the Hertz value with its rounded E*.
    assert!(
        md.contains("8.4332e5 (-0.002 %: the printed value to its digits)"),
        "{md}"
    );
    assert_eq!(
        row(&md, "| wheel speed fluctuation mean, °/s"),
        "| wheel speed fluctuation mean, °/s | 10.1100 | 50.1100 | +395.648 % |"
    );
    // Without the haversine run there is no such table.
    std::fs::remove_dir_all(out.join("seed001_impact_haversine")).unwrap();
    let md = build(&out, None, &reports).unwrap().markdown;
    assert!(!md.contains("seed001_impact_haversine"));
}
