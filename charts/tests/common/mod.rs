//! What the chart tests share: sample data (also used by the ignored demo
//! test) and the helpers that read the written SVG.
#![allow(dead_code)]

use charts::*;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------
// Sample data (also used by the ignored demo test)
// ---------------------------------------------------------------------------

/// Transmission error of 3 tooth pairs (dashed) and their upper envelope
/// (solid), µrad over pinion rotation in deg.
pub fn te_series() -> Vec<Series> {
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
pub fn flank_grid(n_face: usize, n_profile: usize, f: impl Fn(f64, f64) -> f64) -> FlankMap {
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

pub fn ease_off(x: f64, y: f64) -> f64 {
    let (u, v) = ((x - 75.0) / 15.0, y / 4.0);
    22.0 * u * u + 9.0 * v * v - 6.0 * u * v + 2.0 * u
}

pub fn flank_outline() -> Vec<(f64, f64)> {
    vec![(60.0, -4.3), (90.0, -3.7), (91.2, 4.3), (61.2, 3.7)]
}

pub fn contact_paths() -> Vec<PathSeries> {
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

pub fn contact_ellipses() -> Vec<Ellipse> {
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

pub fn section_curves() -> Vec<PathSeries> {
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

pub fn read_svg(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

pub fn assert_well_formed(svg: &str, must_contain: &[&str]) {
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

pub fn no_tmp_files(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.to_string_lossy().ends_with(".tmp"))
        .collect()
}

/// Width and height of the SVG page, px.
pub fn svg_size(svg: &str) -> (f64, f64) {
    let attr = |name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let start = svg.find(&key).unwrap() + key.len();
        let end = start + svg[start..].find('"').unwrap();
        svg[start..end].parse().unwrap()
    };
    (attr("width"), attr("height"))
}

/// All `points="..."` lists of the SVG, as pixel coordinates.
pub fn svg_point_lists(svg: &str) -> Vec<Vec<(f64, f64)>> {
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
