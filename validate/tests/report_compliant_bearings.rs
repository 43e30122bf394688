//! The report's compliant-bearing section from a synthetic `solver
//! dynamic` / `solver ltca` output of `white_paper_bearings`: the bearings
//! and masses used, TE compliant against rigid, the pose and force ranges
//! read from the runs' CSV files, the 10 rpm run against the LTCA on the
//! same bearings computed at the LTCA's positions, and the spectrograms
//! copied; an absent summary is one line of text.

use formats::summaries::{
    BearingLoadSummary, BlankSummary, CompliantBodiesUsed, CompliantRunSummary, CompliantSummary,
    DynamicSummary, QuasiStaticSummary, RunupSummary,
};
use geometry::gear_body::Blank;
use geometry::scene_bearings::{BearingMm, BodyMass};
use std::fmt::Write as _;
use std::path::Path;
use validate::report::results::Stamp;
use validate::report::sections::compliant_bearings::{section, COMPLIANT_SCENE};

fn run(case: &str, csv: &str, te_mean: f64, steps: usize) -> CompliantRunSummary {
    CompliantRunSummary {
        case: case.into(),
        torque_nm: 300.0,
        steps,
        rejected_steps: 0,
        cpu_s: steps as f64 * 120e-6,
        cpu_s_per_step: 120e-6,
        te_mean_urad: te_mean,
        te_ptp_urad: 14.5,
        largest_misalignment: [54.0, 12.0, 18.0, 61.0],
        largest_linearization_urad: 76.5,
        mean_linearization_urad: 8.75,
        pinion_bearing_force_n: vec![1.0],
        wheel_bearing_force_n: vec![2.0],
        csv: csv.into(),
    }
}

fn bearing(position: f64) -> BearingMm {
    BearingMm {
        axial_position_mm: position,
        radial_stiffness_n_per_m: 1e9,
        axial_stiffness_n_per_m: 0.0,
        radial_damping_n_s_per_m: 2e3,
        axial_damping_n_s_per_m: 0.0,
    }
}

fn dynamic() -> DynamicSummary {
    DynamicSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: Blank::Standard,
        inertia_kgm2: [0.0055, 0.055],
        inertia_source: "mesh".into(),
        damping_nm_s_per_rad: 24.0,
        friction_coefficient: 0.0,
        table_positions: 144,
        table_lag_nodes: 96,
        table_build_s: 0.5,
        table_cpu_s_per_position: 0.008,
        quasi_static: vec![QuasiStaticSummary {
            torque_nm: 300.0,
            te_mean_urad: 359.25,
            te_ptp_urad: 18.5,
            steps: 2000,
            rejected_steps: 0,
            cpu_s: 0.26,
            cpu_s_per_step: 130e-6,
            root_tension_mpa: None,
        }],
        runup: Some(RunupSummary {
            pinion_torque_nm: 300.0,
            rpm: [0.0, 1000.0],
            sim_time_s: 0.15,
            max_step_s: 1e-5,
            steps: 15000,
            rejected_steps: 0,
            cpu_s: 1.0,
            cpu_s_per_step: 70e-6,
            te_dynamic_minus_static_urad: [0.0, 15.0],
            root_tension_mpa: None,
        }),
        backlash_urad: None,
        free_play_urad: None,
        rattle: None,
        force_law: "element".into(),
        impact_law: None,
        load_run: None,
        ste_dte: None,
        compliant: Some(CompliantSummary {
            lag_shift_s: 35.0,
            masses_kg: [3.685, 6.692],
            mass_source: "pinion: thin disc; wheel: thin disc".into(),
            notes: vec![],
            runs: vec![
                run("10 rpm", "bearings_quasi_static_300nm.csv", 688.75, 1593),
                run("run-up", "bearings_runup.csv", 705.5, 15034),
            ],
            used: Some(CompliantBodiesUsed {
                pinion_bearings: vec![bearing(149.65), bearing(209.65)],
                wheel_bearings: vec![bearing(71.0), bearing(171.0)],
                bodies: [
                    BodyMass {
                        mass_kg: 3.685,
                        centroid_mm: 109.65,
                        transverse_inertia_kgm2: 0.00275,
                    },
                    BodyMass {
                        mass_kg: 6.692,
                        centroid_mm: 51.0,
                        transverse_inertia_kgm2: 0.0275,
                    },
                ],
            }),
            gearbox: None,
        }),
        dir: "synthetic".into(),
    }
}

fn ltca() -> BlankSummary {
    BlankSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: Blank::Standard,
        positions: 6,
        step_deg: 0.5,
        mesh_cycles: 2.0,
        slices_per_pair: 20,
        friction_coefficient: 0.0,
        utca_te_mean_urad: 0.0,
        utca_te_ptp_urad: 0.0,
        stiffness_files: vec![],
        wall_s: 1.0,
        loads: vec![],
        dir: "synthetic".into(),
        coast: None,
        ablation: Vec::new(),
        loaded_pair_rule: None,
        bearings: Some(vec![BearingLoadSummary {
            torque_nm: 300.0,
            te_mean_urad: 671.25,
            te_ptp_urad: 17.5,
            rigid_te_mean_urad: 354.5,
            rigid_te_ptp_urad: 18.25,
            pinion_apex_displacement_um: 45.0,
            wheel_apex_displacement_um: 15.0,
            pinion_bearing_force_n: vec![1.0, 2.0],
            wheel_bearing_force_n: vec![3.0, 4.0],
            max_iterations: 10,
            max_change_nm: 0.5,
        }]),
    }
}

const FORCES: [&str; 2] = ["pinion_bearing0", "wheel_bearing1"];

/// The bearing-force columns' names and the line's end.
fn force_header(s: &mut String) {
    for b in FORCES {
        for d in ["x", "y", "z"] {
            let _ = write!(s, ",{b}_f{d}_n");
        }
    }
    s.push('\n');
}

/// Bearing i's force in direction d: 1000 (i + 1) + 100 q − 3000 d + `shift`, N.
fn force_row(s: &mut String, q: f64, shift: f64) {
    for i in 0..FORCES.len() {
        for d in 0..3 {
            let _ = write!(
                s,
                ",{}",
                1000.0 * (i + 1) as f64 + 100.0 * q - d as f64 * 3000.0 + shift
            );
        }
    }
    s.push('\n');
}

/// A multibody CSV at rotations 0, 0.3, …, 2.1°: TE 600 + 10 q, E from −54
/// to −33 µm (−54 + 10 q), P = 12, G = −18, ΔΣ = 60 + q; forces linear in q.
fn multibody_csv(path: &Path) {
    let mut s = String::from("time_s,pinion_rotation_deg,te_urad,e_um,p_um,g_um,shaft_angle_urad");
    force_header(&mut s);
    for k in 0..8 {
        let q = 0.3 * k as f64;
        let _ = write!(
            s,
            "{},{q},{},{},12,-18,{}",
            k as f64 * 0.01,
            600.0 + 10.0 * q,
            -54.0 + 10.0 * q,
            60.0 + q
        );
        force_row(&mut s, q, 0.0);
    }
    std::fs::write(path, s).unwrap();
}

/// The LTCA's `bearings.csv` at 0, 0.5, …, 2.5° (2.5 beyond the run):
/// TE 598 + 10 q (multibody − LTCA = +2 µrad), rigid 300; forces 5 N below
/// the multibody's; a 100 N·m row that must be ignored.
fn ltca_csv(path: &Path) {
    let mut s = String::from("pinion_rotation_deg,torque_nm,te_urad,te_rigid_bearings_urad");
    force_header(&mut s);
    for (k, t) in (0..6).map(|k| (k, 300.0)).chain([(1, 100.0)]) {
        let q = 0.5 * k as f64;
        let _ = write!(
            s,
            "{q},{t},{},300",
            if t == 300.0 { 598.0 + 10.0 * q } else { 0.0 }
        );
        force_row(&mut s, q, -5.0);
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn compliant_section_tabulates_runs_and_checks_the_10rpm_run_against_the_ltca() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let root = out.path().join(COMPLIANT_SCENE);
    let mb = root.join("multibody");
    let blanks = mb.join("standard_standard");
    let lt = root.join("ltca").join("standard_standard");
    std::fs::create_dir_all(&blanks).unwrap();
    std::fs::create_dir_all(&lt).unwrap();
    formats::output::write_json(&mb.join("summary.json"), &vec![dynamic()]).unwrap();
    formats::output::write_json(&root.join("ltca").join("summary.json"), &vec![ltca()]).unwrap();
    multibody_csv(&blanks.join("bearings_quasi_static_300nm.csv"));
    multibody_csv(&blanks.join("bearings_runup.csv"));
    // Rigid run-up TE 350 … 370: mean 360, ptp 20.
    std::fs::write(
        blanks.join("runup.csv"),
        "time_s,te_urad\n0,350\n1,360\n2,370\n",
    )
    .unwrap();
    ltca_csv(&lt.join("bearings.csv"));
    for f in ["runup_spectrogram.svg", "bearings_runup_spectrogram.svg"] {
        std::fs::write(blanks.join(f), format!("<svg><!-- {f} --></svg>")).unwrap();
    }
    let stamp = Stamp {
        date_utc: "2026-11-24".into(),
        commit: "abc1234".into(),
    };
    let sec = section(Some(out.path()), reports.path(), &stamp);
    let md = &sec.markdown;
    assert!(md.starts_with("## Compliant bearings (multibody)"), "{md}");
    assert!(md.contains("built 2026-11-24 at commit abc1234"), "{md}");
    assert!(md.contains("no run stamp"), "{md}");
    for row in [
        // Bearings and bodies as used.
        "| pinion 1 | 209.65 | 1.000e9 | 0.000e0 | 2.000e3 | 0.000e0 |",
        "| wheel (standard_standard) | 6.692 | 51.00 | 2.7500e-2 | 5.5000e-2 |",
        // TE: rigid from the summary / runup.csv, compliant, LTCA's.
        "| standard_standard | 10 rpm at 300 N·m | 359.25 / 18.50 | 688.75 / 14.50 | 671.25 / 17.50 | 354.50 / 18.25 | 8.75 (76.50) | 1593 | 130.0 | 120.0 |",
        "| standard_standard | run-up at 300 N·m | 360.00 / 20.00 | 705.50 / 14.50 | – | – | 8.75 (76.50) | 15034 | 70.0 | 120.0 |",
        // Pose ranges from the CSV: E −54 … −33, ΔΣ 60 … 62.1.
        "| standard_standard | 10 rpm | -54.00 … -33.00 | 12.00 … 12.00 | -18.00 … -18.00 | 60.00 … 62.10 |",
        // Forces: wheel bearing 1, x 2000 … 2210, z −4000 … −3790.
        "| standard_standard | run-up | wheel bearing1 | 2000 … 2210 | -1000 … -790 | -4000 … -3790 |",
        // Check: 5 LTCA positions inside 0 … 2.1 (0, 0.5, …, 2.0); added
        // TE mean 298 + 10·1.0 = 308; difference +2 everywhere (0.6 % of
        // 308); forces 5 N apart, largest LTCA force |−4000 + 200 − 5| = 3805 (0.1 %).
        "| standard_standard | 300 | 5 | 308.00 | +2.00 / 2.00 | 0.6 | 8.75 | 5 | 0.1 |",
        "| 1.00 | 300.00 | 608.00 | 610.00 |",
    ] {
        assert!(md.contains(row), "row {row} missing in\n{md}");
    }
    // The 100 N·m LTCA row and the position beyond the run are not compared.
    assert!(!md.contains("| 2.50 |"), "{md}");
    assert_eq!(sec.figures.len(), 2);
    for f in &sec.figures {
        assert!(
            reports.path().join(&f.file).is_file(),
            "{} not copied",
            f.file
        );
    }
    assert!(sec.figures[1].svg.contains("bearings_runup_spectrogram"));
}

#[test]
fn compliant_section_without_runs_is_one_line() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let stamp = Stamp {
        date_utc: "2026-11-24".into(),
        commit: "abc1234".into(),
    };
    let sec = section(Some(out.path()), reports.path(), &stamp);
    assert!(sec.markdown.contains("No compliant-bearing runs"));
    assert!(!sec.markdown.contains('|'));
    assert!(sec.figures.is_empty());
}
