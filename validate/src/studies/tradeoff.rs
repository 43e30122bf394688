//! `validate tradeoff <scene>`: the reduced model's run time against its
//! error to the reference, over its discretization (slices per tooth pair).
//! For each slice count the quasi-static LTCA is run at exactly the
//! reference's positions, and its mean and peak-to-peak TE per blank and
//! load are compared with the reference's. Written to
//! `<out>/<scene>/reference/tradeoff.json` and a plot of the largest error
//! against the time per position, `tradeoff.svg`, both recorded with their
//! checksums as computed from the sweep committed there
//! ([`formats::added_files`], a shared lock held on the folder meanwhile).
//!
//! The other discretization, the stiffness grid density, needs stiffness
//! files at other grids and is not varied here.
use solver::stage::context::LoadedPair;

use crate::reference::reference_stage::BlankSummary as Reference;
use anyhow::Context;
use charts::{te_curve, Series};
use formats::added_files::{add_file, add_json, Dependence};
use formats::result_set::RunLock;
use geometry::pair::{pinion_direction, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::roll_surface;
use serde::{Deserialize, Serialize};
use solver::ltca::{mean_ptp, run as run_sweep, Sweep};
use std::path::Path;
use std::time::Instant;

/// One slice count × blank × load.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Point {
    pub wheel_blank: String,
    pub slices: usize,
    pub torque_nm: f64,
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    pub reference_te_mean_urad: f64,
    pub reference_te_ptp_urad: f64,
    pub mean_error_pct: f64,
    pub ptp_error_pct: f64,
    /// LTCA wall time per position (all torques), s.
    pub s_per_position: f64,
}

fn blank_of(name: &str) -> Option<Blank> {
    match name {
        "standard" => Some(Blank::Standard),
        "lightweight" => Some(Blank::Lightweight),
        _ => None,
    }
}

/// Runs the study for `slices` against every reference summary of the scene
/// (standard pinion).
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    slices: &[usize],
) -> anyhow::Result<Vec<Point>> {
    if !scene.scene.analyses.reference {
        eprintln!(
            "scene {}: `[analyses] reference = false`, no trade-off study; skipped",
            scene.scene.name
        );
        return Ok(Vec::new());
    }
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = sc.loaded_flank;
    let fp = g.side(side);
    let rs = roll_surface(fp, &sc.utca)?;
    let dir = meshes.join(&sc.name);
    let rdir = out.join(&sc.name).join("reference");
    let lock = RunLock::shared(&rdir, &format!("validate tradeoff {}", sc.name))?;
    let mut points = Vec::new();
    for entry in std::fs::read_dir(&rdir).with_context(|| {
        format!(
            "no reference results in {}; run `validate reference`",
            rdir.display()
        )
    })? {
        let path = entry?.path().join("summary.json");
        let Ok(text) = std::fs::read_to_string(&path) else {
            continue;
        };
        let r: Reference = match serde_json::from_str(&text) {
            Ok(r) => r,
            Err(e) => {
                // A stale summary (older layout, or a blank the scene no
                // longer has) is named and left out, not used.
                eprintln!(
                    "tradeoff: skipping {}: not a reference summary of this version ({e}); rerun `validate reference`",
                    path.display()
                );
                continue;
            }
        };
        let (Some(pb), Some(wb)) = (blank_of(&r.pinion_blank), blank_of(&r.wheel_blank)) else {
            continue;
        };
        let pc = LoadedPair::load(scene, &g, &dir, [pb, wb])?.pc;
        let torques: Vec<f64> = r.loads.iter().map(|l| l.torque_nm).collect();
        for &n in slices {
            let sweep = Sweep {
                start: fp.roll_range[0],
                step: r.step_deg.to_radians(),
                direction: pinion_direction(&g.data, side),
                positions: r.positions,
                slices: n,
                // Against the frictionless reference.
                friction: 0.0,
            };
            let t = Instant::now();
            let res = run_sweep(fp, &rs, &pc, &sweep, &torques)
                .with_context(|| format!("LTCA with {n} slices, {wb:?} wheel"))?;
            let s_per_position = t.elapsed().as_secs_f64() / res.len().max(1) as f64;
            for (i, l) in r.loads.iter().enumerate() {
                let te: Vec<f64> = res.iter().map(|p| p.loads[i].te).collect();
                let (m, p) = mean_ptp(&te);
                let (m, p) = (m * 1e6, p * 1e6);
                points.push(Point {
                    wheel_blank: r.wheel_blank.clone(),
                    slices: n,
                    torque_nm: l.torque_nm,
                    te_mean_urad: m,
                    te_ptp_urad: p,
                    reference_te_mean_urad: l.te_mean_urad,
                    reference_te_ptp_urad: l.te_ptp_urad,
                    mean_error_pct: (m - l.te_mean_urad) / l.te_mean_urad * 100.0,
                    ptp_error_pct: (p - l.te_ptp_urad) / l.te_ptp_urad * 100.0,
                    s_per_position,
                });
            }
        }
    }
    add_json(&lock, "tradeoff.json", &points, Dependence::OnSet)?;
    let svg = rdir.join("tradeoff.svg");
    plot(&svg, &points)?;
    add_file(
        &lock,
        "tradeoff.svg",
        &std::fs::read(&svg)?,
        Dependence::OnSet,
    )?;
    Ok(points)
}

/// Largest |mean TE error| over the loads from 100 N·m up, against the time
/// per position, one curve per blank (points in slice order).
fn plot(path: &Path, points: &[Point]) -> anyhow::Result<()> {
    let mut blanks: Vec<&str> = points.iter().map(|p| p.wheel_blank.as_str()).collect();
    blanks.sort_unstable();
    blanks.dedup();
    let mut series = Vec::new();
    for b in blanks {
        let mut slices: Vec<usize> = points.iter().map(|p| p.slices).collect();
        slices.sort_unstable();
        slices.dedup();
        let (mut x, mut ym, mut yp) = (Vec::new(), Vec::new(), Vec::new());
        for n in slices {
            let sel: Vec<&Point> = points
                .iter()
                .filter(|p| p.wheel_blank == b && p.slices == n && p.torque_nm >= 100.0)
                .collect();
            if sel.is_empty() {
                continue;
            }
            x.push(sel[0].s_per_position * 1e3);
            ym.push(
                sel.iter()
                    .map(|p| p.mean_error_pct.abs())
                    .fold(0.0, f64::max),
            );
            yp.push(
                sel.iter()
                    .map(|p| p.ptp_error_pct.abs())
                    .fold(0.0, f64::max),
            );
        }
        series.push(Series {
            name: format!("{b}: mean TE"),
            x: x.clone(),
            y: ym,
            dashed: false,
        });
        series.push(Series {
            name: format!("{b}: ptp TE"),
            x,
            y: yp,
            dashed: true,
        });
    }
    te_curve(
        path,
        "Reduced model against the reference (100-700 N·m): error vs LTCA time, over slices per pair",
        "LTCA wall time per position, all torques (ms)",
        "largest |error| to the reference (%)",
        &series,
    )?;
    Ok(())
}
