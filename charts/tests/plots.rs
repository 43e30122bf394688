//! Tests of the SVG plots: well-formed output written atomically, and
//! errors instead of panics on bad input; the ignored demo writes one
//! example of each plot.

mod common;

use charts::*;
use common::*;
use std::path::PathBuf;

// ---------------------------------------------------------------------------
// Written files
// ---------------------------------------------------------------------------

#[test]
fn te_curve_writes_well_formed_svg_with_title_and_legend() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("te.svg");
    te_curve(
        &p,
        "Transmission error drive side",
        "pinion rotation (deg)",
        "TE (µrad)",
        &te_series(),
    )
    .unwrap();
    let svg = read_svg(&p);
    assert_well_formed(
        &svg,
        &[
            "Transmission error drive side",
            "pinion rotation (deg)",
            "TE (µrad)",
            "loaded envelope",
            "tooth pair 1",
            "tooth pair 3",
        ],
    );
    assert!(no_tmp_files(dir.path()).is_empty());
}

#[test]
fn te_curve_series_sharing_a_name_share_one_legend_entry() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("te.svg");
    let mut s = te_series();
    for x in &mut s[1..] {
        x.name = "single pair".into();
    }
    te_curve(&p, "TE", "x", "y", &s).unwrap();
    let svg = read_svg(&p);
    assert_eq!(svg.matches(">\nsingle pair\n</text>").count(), 1);
    assert_eq!(svg.matches(">\nloaded envelope\n</text>").count(), 1);
}

#[test]
fn te_curve_rejects_empty_nan_only_and_mismatched_input() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("te.svg");
    assert!(matches!(
        te_curve(&p, "t", "x", "y", &[]),
        Err(PlotError::Input { .. })
    ));
    let empty = Series {
        name: "empty".into(),
        x: vec![],
        y: vec![],
        dashed: false,
    };
    assert!(matches!(
        te_curve(&p, "t", "x", "y", &[empty]),
        Err(PlotError::Input { .. })
    ));
    let nan = Series {
        name: "nan".into(),
        x: vec![0.0, 1.0, f64::NAN],
        y: vec![f64::NAN, f64::NAN, 1.0],
        dashed: true,
    };
    assert!(matches!(
        te_curve(&p, "t", "x", "y", &[nan]),
        Err(PlotError::Input { .. })
    ));
    let inf = Series {
        name: "inf".into(),
        x: vec![f64::INFINITY, 1.0],
        y: vec![1.0, f64::NEG_INFINITY],
        dashed: false,
    };
    assert!(te_curve(&p, "t", "x", "y", &[inf]).is_err());
    let mismatch = Series {
        name: "mismatch".into(),
        x: vec![0.0, 1.0],
        y: vec![0.0],
        dashed: false,
    };
    let err = te_curve(&p, "t", "x", "y", &[mismatch]).unwrap_err();
    assert!(
        err.to_string().contains("te.svg"),
        "message names the file: {err}"
    );
    assert!(!p.exists(), "no file on error");
    assert!(no_tmp_files(dir.path()).is_empty());
}

#[test]
fn te_curve_handles_single_point_and_constant_data() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("te.svg");
    let one = Series {
        name: "one point".into(),
        x: vec![3.0],
        y: vec![0.0],
        dashed: false,
    };
    te_curve(&p, "single", "x", "y", &[one]).unwrap();
    assert_well_formed(&read_svg(&p), &["single", "one point"]);
    let flat = Series {
        name: "flat".into(),
        x: vec![0.0, 1.0, 2.0],
        y: vec![5.0, 5.0, 5.0],
        dashed: true,
    };
    te_curve(&p, "flat", "x", "y", &[flat]).unwrap();
    assert_well_formed(&read_svg(&p), &["flat"]);
}

#[test]
fn flank_map_writes_well_formed_svg_with_colorbar_label() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("ease_off.svg");
    let g = flank_grid(25, 15, ease_off);
    flank_map(&p, "Ease-off pinion drive flank", &g, "ease-off (µm)").unwrap();
    let svg = read_svg(&p);
    assert_well_formed(
        &svg,
        &[
            "Ease-off pinion drive flank",
            "ease-off (µm)",
            "max ",
            "min ",
        ],
    );
    // one filled polygon per cell
    assert!(svg.matches("<polygon").count() >= 24 * 14);
    assert!(no_tmp_files(dir.path()).is_empty());
}

#[test]
fn flank_map_skips_missing_nodes_and_handles_a_constant_field() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("map.svg");
    let mut g = flank_grid(6, 5, |x, _| x);
    g.value[7] = f64::NAN;
    g.x[20] = f64::INFINITY;
    flank_map(&p, "holes", &g, "v").unwrap();
    assert_well_formed(&read_svg(&p), &["holes"]);
    let c = flank_grid(6, 5, |_, _| 2.5);
    flank_map(&p, "constant", &c, "v").unwrap();
    assert_well_formed(&read_svg(&p), &["constant"]);
}

#[test]
fn flank_map_rejects_inconsistent_or_empty_grids() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("map.svg");
    let mut g = flank_grid(4, 3, |x, _| x);
    g.value.pop();
    assert!(matches!(
        flank_map(&p, "t", &g, "v"),
        Err(PlotError::Input { .. })
    ));
    let line = flank_grid(4, 1, |x, _| x);
    assert!(matches!(
        flank_map(&p, "t", &line, "v"),
        Err(PlotError::Input { .. })
    ));
    let mut nan = flank_grid(4, 3, |x, _| x);
    nan.value.iter_mut().for_each(|v| *v = f64::NAN);
    assert!(matches!(
        flank_map(&p, "t", &nan, "v"),
        Err(PlotError::Input { .. })
    ));
    assert!(!p.exists());
}

#[test]
fn contact_path_writes_well_formed_svg_with_legend() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("contact.svg");
    contact_path(
        &p,
        "Contact pattern gear concave",
        &flank_outline(),
        &contact_paths(),
        &contact_ellipses(),
    )
    .unwrap();
    let svg = read_svg(&p);
    assert_well_formed(
        &svg,
        &[
            "Contact pattern gear concave",
            "flank outline",
            "path of contact (drive)",
            "path of contact (coast)",
            "contact ellipses",
        ],
    );
    assert!(no_tmp_files(dir.path()).is_empty());
}

/// A circle drawn as a contact ellipse has the same width and height in
/// pixels: the plot really has equal aspect.
#[test]
fn contact_path_draws_a_circle_as_a_circle() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("circle.svg");
    let circle = Ellipse {
        center: (75.0, 0.0),
        semi_axes: (3.0, 3.0),
        angle_rad: 0.3,
    };
    contact_path(&p, "circle", &flank_outline(), &[], &[circle]).unwrap();
    let svg = read_svg(&p);
    let polys: Vec<_> = svg_point_lists(&svg)
        .into_iter()
        .filter(|l| l.len() == 72)
        .collect();
    assert_eq!(polys.len(), 1, "one 72-point ellipse polygon");
    let span = |f: fn(&(f64, f64)) -> f64| {
        let v: Vec<f64> = polys[0].iter().map(f).collect();
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    let (w, h) = (span(|p| p.0), span(|p| p.1));
    assert!(w > 20.0, "circle is visible ({w} px)");
    assert!((w - h).abs() <= 1.5, "circle is {w} x {h} px");
}

/// Ellipses with infinite or huge semi-axes are shortened and cut to the
/// visible range instead of blowing up the plot.
#[test]
fn contact_path_clips_degenerate_ellipses_to_the_canvas() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("clip.svg");
    let bad = [
        Ellipse {
            center: (75.0, 0.0),
            semi_axes: (f64::INFINITY, 0.5),
            angle_rad: 0.2,
        },
        Ellipse {
            center: (70.0, 1.0),
            semi_axes: (1e9, f64::NAN),
            angle_rad: f64::NAN,
        },
    ];
    contact_path(&p, "clipped", &flank_outline(), &contact_paths(), &bad).unwrap();
    let svg = read_svg(&p);
    assert_well_formed(&svg, &["clipped"]);
    let (w, h) = svg_size(&svg);
    let lists = svg_point_lists(&svg);
    assert!(!lists.is_empty());
    for l in lists {
        for (x, y) in l {
            assert!(
                (0.0..=w).contains(&x) && (0.0..=h).contains(&y),
                "({x}, {y})"
            );
        }
    }
}

#[test]
fn contact_path_rejects_input_without_finite_points() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("c.svg");
    assert!(matches!(
        contact_path(&p, "t", &[], &[], &[]),
        Err(PlotError::Input { .. })
    ));
    let nan = [(f64::NAN, 0.0)];
    assert!(contact_path(&p, "t", &nan, &[], &[]).is_err());
}

#[test]
fn tooth_section_writes_well_formed_svg_with_legend() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("section.svg");
    tooth_section(&p, "Pinion tooth section mean cone", &section_curves()).unwrap();
    let svg = read_svg(&p);
    assert_well_formed(
        &svg,
        &[
            "Pinion tooth section mean cone",
            "concave flank",
            "convex flank",
            "root",
            "tip",
        ],
    );
    assert!(no_tmp_files(dir.path()).is_empty());
    assert!(tooth_section(&p, "t", &[]).is_err());
}

#[test]
fn write_below_a_regular_file_is_a_write_error_and_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("file"), "not a directory").unwrap();
    let p = dir.path().join("file").join("s.svg");
    let err = tooth_section(&p, "t", &section_curves()).unwrap_err();
    assert!(matches!(err, PlotError::Write { .. }), "{err}");
    assert!(err.to_string().contains("s.svg"));
    assert!(no_tmp_files(dir.path()).is_empty());
}

#[test]
fn rewriting_a_plot_replaces_it_and_leaves_no_tmp_file() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("te.svg");
    std::fs::write(&p, "old").unwrap();
    for title in ["first", "second"] {
        te_curve(&p, title, "x", "y", &te_series()).unwrap();
        assert_well_formed(&read_svg(&p), &[title]);
    }
    let entries: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(entries.len(), 1, "only te.svg remains");
}

// ---------------------------------------------------------------------------
// Demo (writes the example plots for a visual check)
// ---------------------------------------------------------------------------

/// Renders one example of each plot to `$PLOTS_DEMO_DIR` (default
/// `<tmp>/plots-demo`). Run with `--ignored` and look at the files.
#[test]
#[ignore = "writes example plots for a visual check"]
fn demo_plots() {
    let dir = std::env::var_os("PLOTS_DEMO_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("plots-demo"));
    std::fs::create_dir_all(&dir).unwrap();
    te_curve(
        &dir.join("te.svg"),
        "Transmission error, drive side",
        "pinion rotation (deg)",
        "transmission error (µrad)",
        &te_series(),
    )
    .unwrap();
    flank_map(
        &dir.join("ease_off.svg"),
        "Ease-off, pinion convex flank",
        &flank_grid(31, 17, ease_off),
        "ease-off (µm)",
    )
    .unwrap();
    flank_map(
        &dir.join("roll.svg"),
        "Roll angles, gear concave flank",
        &flank_grid(31, 17, |x, y| 0.9 * (x - 75.0) - 2.1 * y + 0.02 * x * y),
        "roll angle (deg)",
    )
    .unwrap();
    contact_path(
        &dir.join("contact.svg"),
        "Contact pattern, gear concave flank",
        &flank_outline(),
        &contact_paths(),
        &contact_ellipses(),
    )
    .unwrap();
    tooth_section(
        &dir.join("section.svg"),
        "Pinion tooth section at mean cone distance",
        &section_curves(),
    )
    .unwrap();
}
