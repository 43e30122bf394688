//! The report's order-map subsection: a present
//! `order_map.json` gives one row per wheel blank, one per speed and blank
//! with the amplitudes at the marked orders as the summary holds them, the
//! order maps copied; the whole-revolution subsection follows (one line
//! when its scene has not run; `report_lightweight_revolution.rs` tests it).

use formats::lumped_summary::{LobeFit, MarkedOrder, OrderMapSpeed, OrderMapSummary};
use formats::summaries::{RunupOrderWindow, RunupOrders};
use geometry::gear_body::Blank;
use validate::report::sections::lightweight_revolution::{self, RUNUP_SCENE};
use validate::report::sections::lumped_order_map::{subsection, ORDER_MAP_SCENE};

fn map(wheel: Blank, lobe_line_n: f64) -> OrderMapSummary {
    OrderMapSummary {
        pinion_blank: Blank::Standard,
        wheel_blank: wheel,
        pinion_teeth: 20,
        wheel_teeth: 43,
        lobes: if wheel == Blank::Lightweight { 3 } else { 0 },
        wheel_solved_teeth: if wheel == Blank::Lightweight {
            vec![0, 1, 2, 3, 4, 5, 41, 42]
        } else {
            vec![2]
        },
        ltca_span_mesh_cycles: 5,
        cycle_mean_stiffness_n_per_m: vec![9.2e7, 9.0e7],
        cycle_wheel_tooth: vec![-0.98, 0.02],
        stiffness_lobe: [0.03, -0.02, -0.04],
        deflection_lobe_m: [0.0; 3],
        stiffness_lobe_ptp_relative: 0.1093,
        stiffness_lobe_minimum_wheel_tooth: (wheel == Blank::Lightweight).then_some(2.49),
        span_fit_residual_of_ptp: [0.086, 0.109],
        mesh_harmonics: 14,
        revolution_harmonics: 623,
        revolution_series_residual_of_ptp: [0.016, 0.007],
        ltca_wall_s: 0.21,
        excitation: "lobe fitted to the span".into(),
        short_span_lobe: None,
        lobe_repeat_mismatch_of_mean: None,
        hole_wheel_teeth: if wheel == Blank::Lightweight {
            vec![3.1, 17.43, 31.76]
        } else {
            vec![]
        },
        speeds: vec![OrderMapSpeed {
            pinion_speed_rpm: 3000.0,
            mesh_frequency_hz: 1000.0,
            integration_wall_s: 0.29,
            run_wall_s: 0.56,
            order_resolution: 20.0 / 86.0,
            marked: vec![
                MarkedOrder {
                    label: "3·20/43".into(),
                    pinion_order: 60.0 / 43.0,
                    wheel_bearing_force_n: lobe_line_n,
                },
                MarkedOrder {
                    label: "20".into(),
                    pinion_order: 20.0,
                    wheel_bearing_force_n: 448.6,
                },
            ],
        }],
    }
}

#[test]
fn present_order_map_gives_rows_from_the_summary_and_the_maps_beside_the_multibody_spectrogram() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let dir = out.path().join(ORDER_MAP_SCENE).join("lumped");
    std::fs::create_dir_all(&dir).unwrap();
    let maps = vec![map(Blank::Standard, 5.3e-6), map(Blank::Lightweight, 1.502)];
    std::fs::write(
        dir.join("order_map.json"),
        serde_json::to_string(&maps).unwrap(),
    )
    .unwrap();
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"/>";
    for b in ["standard", "lightweight"] {
        std::fs::write(dir.join(format!("order_map_standard_{b}.svg")), svg).unwrap();
    }
    let (md, figs) = subsection(out.path(), reports.path());
    assert!(
        md.contains("| Lightweight | 0, 1, 2, 3, 4, 5, 41, 42 | 5 |"),
        "{md}"
    );
    assert!(md.contains("2.49 (of 14.33 per lobe)"), "{md}");
    assert!(
        md.contains("| 3000 | Lightweight | 1.502e0 | 4.486e2 |"),
        "{md}"
    );
    assert!(
        md.contains("| 3000 | Standard | 5.300e-6 | 4.486e2 |"),
        "{md}"
    );
    let files: Vec<&str> = figs.iter().map(|f| f.file.as_str()).collect();
    assert_eq!(
        files,
        [
            "lumped_order_map_standard_standard.svg",
            "lumped_order_map_standard_lightweight.svg",
        ]
    );
    // The whole-revolution scene has not run: said so.
    assert!(md.contains("No whole-revolution order map"), "{md}");
}

/// A run-up window at `rpm` with the lobe family's side bands `band` N.
fn window(rpm: f64, band: f64) -> RunupOrderWindow {
    let mk = |label: &str, o: f64, f: f64| MarkedOrder {
        label: label.into(),
        pinion_order: o,
        wheel_bearing_force_n: f,
    };
    RunupOrderWindow {
        pinion_rev: [0.0, 2.15],
        time_s: [0.0, 0.13],
        mean_pinion_rpm: rpm,
        pinion_rpm: [rpm - 60.0, rpm + 60.0],
        marked: vec![
            mk("20", 20.0, 120.0),
            mk("3·20/43", 1.395, 1.0),
            mk("20-1.40", 18.605, band),
            mk("20+1.40", 21.395, band),
        ],
    }
}

#[test]
fn whole_revolution_subsection_checks_the_lobe_and_puts_the_runup_windows_beside_the_8dof_runs() {
    let out = tempfile::tempdir().unwrap();
    let reports = tempfile::tempdir().unwrap();
    let scene = out.path().join(RUNUP_SCENE);
    std::fs::create_dir_all(scene.join("lumped")).unwrap();
    let mut light = map(Blank::Lightweight, 1.502);
    light.wheel_solved_teeth = (0..43).collect();
    light.ltca_span_mesh_cycles = 43;
    light.excitation = "solved revolution".into();
    light.stiffness_lobe_ptp_relative = 0.0812;
    light.stiffness_lobe_minimum_wheel_tooth = Some(3.6);
    light.short_span_lobe = Some(LobeFit {
        span_mesh_cycles: 5,
        stiffness_lobe: [0.0; 3],
        stiffness_lobe_ptp_relative: 0.1093,
        stiffness_lobe_minimum_wheel_tooth: Some(2.49),
    });
    light.lobe_repeat_mismatch_of_mean = Some([0.0071, 0.0032]);
    let maps = vec![map(Blank::Standard, 5.3e-6), light];
    std::fs::write(
        scene.join("lumped").join("order_map.json"),
        serde_json::to_string(&maps).unwrap(),
    )
    .unwrap();
    for (pair, band) in [("standard_standard", 0.01), ("standard_lightweight", 2.5)] {
        let dir = scene.join("multibody").join(pair);
        std::fs::create_dir_all(&dir).unwrap();
        let orders = RunupOrders {
            pinion_blank: Blank::Standard,
            wheel_blank: Blank::Standard,
            pinion_teeth: 20,
            wheel_teeth: 43,
            samples_per_window: 1376,
            order_resolution: 20.0 / 43.0,
            windows: vec![
                window(2400.0, 9.0),
                window(2950.0, band),
                window(3500.0, 9.0),
            ],
        };
        std::fs::write(
            dir.join("runup_orders.json"),
            serde_json::to_string(&orders).unwrap(),
        )
        .unwrap();
        // On compliant bearings (the lightweight wheel only): side bands
        // 2.0 N instead of 2.5 at the window shown.
        if band > 1.0 {
            let mut on_bearings = orders.clone();
            on_bearings.windows[1] = window(2950.0, 2.0);
            std::fs::write(
                dir.join("bearings_runup_orders.json"),
                serde_json::to_string(&on_bearings).unwrap(),
            )
            .unwrap();
        }
    }
    let extrapolated = vec![map(Blank::Lightweight, 1.0)];
    let (md, _) = lightweight_revolution::subsection(out.path(), reports.path(), &extrapolated);
    // Lobe rows: the whole revolution, its first 5 cycles, the 8-tooth
    // scene; least k against the nearest hole (3.1 of each 14.33-tooth lobe).
    assert!(
        md.contains("| the whole revolution | 43 | 0.0812 | 3.60 | +0.50 |"),
        "{md}"
    );
    assert!(
        md.contains("| its first mesh cycles only | 5 | 0.1093 | 2.49 | -0.60 |"),
        "{md}"
    );
    assert!(
        md.contains("| the order-map scene's 8-tooth file | 5 | 0.1093 | 2.49 | -0.60 |"),
        "{md}"
    );
    assert!(md.contains("max 0.0071 and rms 0.0032"), "{md}");
    // The nearest window (2950 rpm) beside the 8-DOF runs at 3000 rpm.
    assert!(
        md.contains("| 3000 | Lightweight | multibody run-up, 2950 rpm (2890–3010) | 1.200e2 | — | 1.000e0 | 2.500e0 | 2.500e0 |"),
        "{md}"
    );
    assert!(
        md.contains("| 3000 | Lightweight | 8-DOF, solved revolution |"),
        "{md}"
    );
    assert!(
        md.contains("| 3000 | Lightweight | 8-DOF, lobe fitted to 8 teeth |"),
        "{md}"
    );
    assert!(
        md.contains("(sum of both): 3000 rpm: 1.0 and 250.0."),
        "{md}"
    );
    // Compliant bearings: their window's row and the ratios to the rigid
    // run-up's (2.0 / 2.5 = 0.80 at each side band, 1 elsewhere; no 40).
    assert!(
        md.contains("| 3000 | Lightweight | multibody run-up, compliant bearings, 2950 rpm (2890–3010) | 1.200e2 | — | 1.000e0 | 2.000e0 | 2.000e0 |"),
        "{md}"
    );
    assert!(
        !md.contains("| Standard | multibody run-up, compliant"),
        "{md}"
    );
    assert!(
        md.contains("Lightweight at 3000 rpm: 20 1.00, 40 —, 3·20/43 1.00, 20-1.40 0.80, 20+1.40 0.80, side bands together 0.80"),
        "{md}"
    );
}

#[test]
fn hole_distance_wraps_round_the_lobe() {
    let lobe = 43.0 / 3.0;
    let d = lightweight_revolution::from_nearest_hole(14.0, &[0.5], lobe).unwrap();
    assert!((d - (14.0 - 0.5 - lobe)).abs() < 1e-12, "{d}");
    assert!(lightweight_revolution::from_nearest_hole(1.0, &[], lobe).is_none());
}
