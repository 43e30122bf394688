//! Tests of the SVG plots: well-formed output written atomically, errors
//! instead of panics on bad input, and the numerical helpers (marching
//! squares, 1-2-5 ticks, equal-aspect ranges).
//!
//! Longer than 700 lines on purpose: every chart's tests and the ignored
//! demo share the sample data and the SVG-reading helpers at the top.

use charts::*;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------
// Sample data (also used by the ignored demo test)
// ---------------------------------------------------------------------------

/// Transmission error of 3 tooth pairs (dashed) and their upper envelope
/// (solid), µrad over pinion rotation in deg.
fn te_series() -> Vec<Series> {
    let pitch = 18.0;
    let phi: Vec<f64> = (0..=400).map(|j| -12.0 + 0.1 * j as f64).collect();
    let pair = |c: f64| -> Vec<f64> {
        phi.iter()
            .map(|&p| {
                let d = p - c;
                if d.abs() <= 14.0 {
                    -0.1 * d * d - 1.5
                } else {
                    f64::NAN
                }
            })
            .collect()
    };
    let pairs: Vec<Vec<f64>> = (0..3).map(|j| pair(j as f64 * pitch)).collect();
    let env: Vec<f64> = (0..phi.len())
        .map(|i| {
            pairs
                .iter()
                .map(|p| p[i])
                .filter(|v| v.is_finite())
                .fold(f64::NAN, f64::max)
        })
        .collect();
    let mut out = vec![Series {
        name: "loaded envelope".into(),
        x: phi.clone(),
        y: env,
        dashed: false,
    }];
    for (j, p) in pairs.into_iter().enumerate() {
        out.push(Series {
            name: format!("tooth pair {}", j + 1),
            x: phi.clone(),
            y: p,
            dashed: true,
        });
    }
    out
}

/// Curvilinear flank grid, x = cone distance 60..90 mm, y = height -4..4 mm,
/// with `f(x, y)` as value.
fn flank_grid(n_face: usize, n_profile: usize, f: impl Fn(f64, f64) -> f64) -> FlankMap {
    let (mut x, mut y, mut value) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..n_face {
        let u = i as f64 / (n_face - 1) as f64;
        for k in 0..n_profile {
            let v = k as f64 / (n_profile - 1) as f64;
            let h = -4.0 + 8.0 * v + 0.6 * (u - 0.5); // profile lines rise along the face
            let cd = 60.0 + 30.0 * u + 2.5 * (v - 0.5) + 1.0 * (v - 0.5) * (v - 0.5);
            x.push(cd);
            y.push(h);
            value.push(f(cd, h));
        }
    }
    FlankMap {
        n_face,
        n_profile,
        x,
        y,
        value,
    }
}

fn ease_off(x: f64, y: f64) -> f64 {
    let (u, v) = ((x - 75.0) / 15.0, y / 4.0);
    22.0 * u * u + 9.0 * v * v - 6.0 * u * v + 2.0 * u
}

fn flank_outline() -> Vec<(f64, f64)> {
    vec![(60.0, -4.3), (90.0, -3.7), (91.2, 4.3), (61.2, 3.7)]
}

fn contact_paths() -> Vec<PathSeries> {
    vec![
        PathSeries {
            name: "path of contact (drive)".into(),
            points: (0..=12)
                .map(|j| {
                    let t = j as f64 / 12.0;
                    (
                        64.0 + 23.0 * t,
                        -2.5 + 5.0 * t + 0.8 * (t - 0.5) * (t - 0.5),
                    )
                })
                .collect(),
        },
        PathSeries {
            name: "path of contact (coast)".into(),
            points: (0..=12)
                .map(|j| {
                    let t = j as f64 / 12.0;
                    (66.0 + 20.0 * t, 2.2 - 4.0 * t)
                })
                .collect(),
        },
    ]
}

fn contact_ellipses() -> Vec<Ellipse> {
    (0..=4)
        .map(|j| {
            let t = j as f64 / 4.0;
            Ellipse {
                center: (
                    64.0 + 23.0 * t,
                    -2.5 + 5.0 * t + 0.8 * (t - 0.5) * (t - 0.5),
                ),
                semi_axes: (7.0 + 2.0 * t, 0.45),
                angle_rad: -0.55,
            }
        })
        .collect()
}

fn section_curves() -> Vec<PathSeries> {
    let prof = |sign: f64| -> Vec<(f64, f64)> {
        (0..=20)
            .map(|j| {
                let h = -4.5 + 9.0 * j as f64 / 20.0;
                (sign * (2.4 - 0.36 * h + 0.012 * h * h), h)
            })
            .collect()
    };
    vec![
        PathSeries {
            name: "concave flank".into(),
            points: prof(-1.0),
        },
        PathSeries {
            name: "convex flank".into(),
            points: prof(1.0),
        },
        PathSeries {
            name: "root".into(),
            points: vec![(-4.6, -4.5), (4.6, -4.5)],
        },
        PathSeries {
            name: "tip".into(),
            points: vec![(-0.86, 4.5), (0.86, 4.5)],
        },
    ]
}

// ---------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------

fn read_svg(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn assert_well_formed(svg: &str, must_contain: &[&str]) {
    let t = svg.trim();
    assert!(
        t.starts_with("<svg"),
        "does not start with <svg: {:?}",
        &t[..t.len().min(80)]
    );
    assert!(t.ends_with("</svg>"), "does not end with </svg>");
    assert_eq!(t.matches("<svg").count(), 1);
    for s in must_contain {
        assert!(svg.contains(s), "SVG lacks the text {s:?}");
    }
}

fn no_tmp_files(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".tmp"))
        .collect()
}

/// Width and height of the SVG page, px.
fn svg_size(svg: &str) -> (f64, f64) {
    let attr = |name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let start = svg.find(&key).unwrap() + key.len();
        let end = start + svg[start..].find('"').unwrap();
        svg[start..end].parse().unwrap()
    };
    (attr("width"), attr("height"))
}

/// All `points="..."` lists of the SVG, as pixel coordinates.
fn svg_point_lists(svg: &str) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(pos) = rest.find("points=\"") {
        rest = &rest[pos + 8..];
        let end = rest.find('"').unwrap();
        let pts = rest[..end]
            .split_whitespace()
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                (x.parse().unwrap(), y.parse().unwrap())
            })
            .collect();
        out.push(pts);
        rest = &rest[end..];
    }
    out
}

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
// Marching squares
// ---------------------------------------------------------------------------

/// For v = x on a skewed grid, the iso-line at c is the vertical line x = c
/// from the bottom to the top boundary of the grid.
#[test]
fn iso_line_of_linear_field_is_the_vertical_line_x_equals_level() {
    let (nf, np) = (5, 4);
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for i in 0..nf {
        for k in 0..np {
            x.push(10.0 + 2.5 * i as f64 + 0.4 * k as f64);
            y.push(-3.0 + 1.7 * k as f64 + 0.3 * i as f64);
        }
    }
    let g = FlankMap {
        n_face: nf,
        n_profile: np,
        value: x.clone(),
        x,
        y,
    };
    for c in [12.1, 13.37, 16.05, 19.9] {
        let segs = iso_segments(&g, c);
        assert!(!segs.is_empty(), "level {c}");
        for &(a, b) in &segs {
            assert!(
                (a.0 - c).abs() <= 1e-12 && (b.0 - c).abs() <= 1e-12,
                "{a:?} {b:?} at {c}"
            );
        }
        // bottom boundary k = 0: x = 10 + 2.5 i, y = -3 + 0.3 i
        let y_bottom = -3.0 + 0.3 * (c - 10.0) / 2.5;
        // top boundary k = 3: x = 11.2 + 2.5 i, y = 2.1 + 0.3 i
        let y_top = 2.1 + 0.3 * (c - 11.2) / 2.5;
        let ys: Vec<f64> = segs.iter().flat_map(|&(a, b)| [a.1, b.1]).collect();
        let ymin = ys.iter().cloned().fold(f64::MAX, f64::min);
        let ymax = ys.iter().cloned().fold(f64::MIN, f64::max);
        assert!((ymin - y_bottom).abs() <= 1e-12, "{ymin} vs {y_bottom}");
        assert!((ymax - y_top).abs() <= 1e-12, "{ymax} vs {y_top}");
        // the segments tile the line without gaps or overlaps
        let len: f64 = segs.iter().map(|&(a, b)| (b.1 - a.1).abs()).sum();
        assert!((len - (y_top - y_bottom)).abs() <= 1e-12, "{len}");
    }
}

/// A closed contour of v = x² + y² is a closed chain (every end point is
/// shared by exactly two segments) close to the circle r = √level.
#[test]
fn iso_line_of_radial_field_is_a_closed_chain_near_the_circle() {
    let n = 41;
    let (mut x, mut y, mut v) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..n {
        for k in 0..n {
            let (px, py) = (-2.0 + 4.0 * i as f64 / 40.0, -2.0 + 4.0 * k as f64 / 40.0);
            x.push(px);
            y.push(py);
            v.push(px * px + py * py);
        }
    }
    let g = FlankMap {
        n_face: n,
        n_profile: n,
        x,
        y,
        value: v,
    };
    let segs = iso_segments(&g, 1.0);
    assert!(segs.len() > 40);
    let mut ends: Vec<(u64, u64)> = segs
        .iter()
        .flat_map(|&(a, b)| {
            [
                (a.0.to_bits(), a.1.to_bits()),
                (b.0.to_bits(), b.1.to_bits()),
            ]
        })
        .collect();
    ends.sort();
    for chunk in ends.chunk_by(|p, q| p == q) {
        assert_eq!(
            chunk.len(),
            2,
            "end point shared by {} segments",
            chunk.len()
        );
    }
    for &(a, b) in &segs {
        for p in [a, b] {
            let r = (p.0 * p.0 + p.1 * p.1).sqrt();
            assert!((r - 1.0).abs() < 5e-3, "r = {r}");
        }
    }
}

#[test]
fn iso_segments_are_empty_outside_the_range_or_for_a_bad_grid() {
    let g = flank_grid(5, 4, |x, _| x);
    assert!(iso_segments(&g, 0.0).is_empty());
    assert!(iso_segments(&g, 1000.0).is_empty());
    assert!(iso_segments(&g, f64::NAN).is_empty());
    let mut bad = g.clone();
    bad.y.pop();
    assert!(iso_segments(&bad, 75.0).is_empty());
}

/// On a saddle v = x·y the four crossings of the centre cell are paired into
/// two segments that do not cross.
#[test]
fn iso_segments_resolve_saddle_cells() {
    let g = FlankMap {
        n_face: 2,
        n_profile: 2,
        x: vec![-1.0, -1.0, 1.0, 1.0],
        y: vec![-1.0, 1.0, -1.0, 1.0],
        value: vec![1.0, -1.0, -1.0, 1.0],
    };
    for level in [0.5, -0.5] {
        let segs = iso_segments(&g, level);
        assert_eq!(segs.len(), 2);
        for &(a, b) in &segs {
            // each segment cuts off one corner: both ends lie in the same quadrant
            assert!(
                a.0 * b.0 > 0.0 && a.1 * b.1 > 0.0,
                "level {level}: {a:?} {b:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------
// Ticks and ranges
// ---------------------------------------------------------------------------

fn assert_nice(lo: f64, hi: f64, n: usize) {
    let t = nice_ticks(lo, hi, n);
    assert!(t.len() >= 2, "{lo}..{hi}: {t:?}");
    assert!(t.len() <= n + 1, "{lo}..{hi} n={n}: {t:?}");
    let (a, b) = (lo.min(hi), lo.max(hi));
    for &v in &t {
        assert!(v >= a && v <= b, "{v} outside [{a}, {b}]");
    }
    let step = t[1] - t[0];
    for w in t.windows(2) {
        assert!(
            ((w[1] - w[0]) - step).abs() <= 1e-9 * step,
            "{t:?} not equally spaced"
        );
    }
    let mag = 10f64.powf(step.log10().floor());
    let m = step / mag;
    assert!(
        [1.0, 2.0, 5.0, 10.0].iter().any(|s| (m - s).abs() < 1e-6),
        "step {step} is not 1, 2 or 5 x 10^k"
    );
    // ticks are multiples of the step and cover the range to within one step
    for &v in &t {
        assert!(((v / step) - (v / step).round()).abs() < 1e-6);
    }
    assert!(t[0] - a < step + 1e-12 * step && b - t[t.len() - 1] < step + 1e-12 * step);
}

#[test]
fn nice_ticks_are_equally_spaced_1_2_5_steps_within_the_range() {
    assert_eq!(nice_ticks(0.0, 37.0, 5), vec![0.0, 10.0, 20.0, 30.0]);
    for (lo, hi, n) in [
        (0.0, 37.0, 5),
        (-3.2, 15.1, 8),
        (0.3, 0.9, 6),
        (-1e-6, 2.5e-6, 8),
        (1234.0, 1278.0, 4),
        (-50.0, -49.9, 3),
        (15.1, -3.2, 8),
        (0.0, 1.0, 1),
    ] {
        assert_nice(lo, hi, n);
    }
}

#[test]
fn nice_ticks_degenerate_inputs() {
    assert_eq!(nice_ticks(2.0, 2.0, 5), vec![2.0]);
    assert!(nice_ticks(f64::NAN, 1.0, 5).is_empty());
    assert!(nice_ticks(0.0, f64::INFINITY, 5).is_empty());
    assert!(!nice_ticks(0.0, 10.0, 0).is_empty());
}

#[test]
fn equal_aspect_ranges_have_equal_units_per_pixel_and_contain_the_data() {
    for (xs, ys, w, h) in [
        ((60.0, 90.0), (-4.0, 4.0), 900, 600),
        ((-5.0, 5.0), (-1.0, 30.0), 900, 600),
        ((0.0, 1.0), (0.0, 1.0), 300, 700),
        ((3.0, 3.0), (-2.0, 2.0), 500, 500),
        ((90.0, 60.0), (4.0, -4.0), 1000, 500),
    ] {
        let ((x0, x1), (y0, y1)) = equal_aspect_ranges(xs, ys, w, h);
        let (px, py) = ((x1 - x0) / w as f64, (y1 - y0) / h as f64);
        assert!(
            (px - py).abs() <= 1e-12 * px.max(py),
            "{px} vs {py} per pixel"
        );
        assert!(
            x0 <= xs.0.min(xs.1) && x1 >= xs.0.max(xs.1),
            "x {xs:?} in ({x0}, {x1})"
        );
        assert!(
            y0 <= ys.0.min(ys.1) && y1 >= ys.0.max(ys.1),
            "y {ys:?} in ({y0}, {y1})"
        );
        // the binding direction is not widened
        assert!(
            (x1 - x0 - (xs.1 - xs.0).abs()).abs() < 1e-12
                || (y1 - y0 - (ys.1 - ys.0).abs()).abs() < 1e-12
        );
        // the widened direction stays centred
        assert!((0.5 * (x0 + x1) - 0.5 * (xs.0 + xs.1)).abs() < 1e-12);
        assert!((0.5 * (y0 + y1) - 0.5 * (ys.0 + ys.1)).abs() < 1e-12);
    }
    let ((x0, x1), (y0, y1)) = equal_aspect_ranges((1.0, 1.0), (2.0, 2.0), 400, 200);
    assert!(x1 > x0 && y1 > y0 && ((x1 - x0) / 400.0 - (y1 - y0) / 200.0).abs() < 1e-15);
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
