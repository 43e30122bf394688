//! Tests of the charts' numerical helpers: marching squares, 1-2-5 ticks
//! and equal-aspect ranges.

mod common;

use charts::*;
use common::flank_grid;

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
