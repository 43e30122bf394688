//! `solver sensitivity <scene>`: the classic V–H-style sensitivity study.
//! Each misalignment E, P, G, ΔΣ is swept alone over the scene's
//! `[sensitivity]` range (on top of the scene's own `[misalignment]`), and
//! at every value the loaded TCA of the first pinion × wheel blank runs at
//! the scene's loads over the scene's sweep: TE peak-to-peak and mean, the
//! loaded pattern's centre and extent on the pinion flank (L along the face,
//! d in height) and the largest pressure. The stiffness files are read once:
//! they are body-fixed and serve every pose.
//!
//! Writes `<out>/<scene>/sensitivity/` as one result set: `summary.json`
//! ([`formats::sensitivity_summary`]), `summary.csv` (one row per
//! misalignment × value × torque) and the charts of [`CHART_FILES`].

use crate::ltca::{mean_ptp, run as run_sweep, PositionResult};
use crate::stage::context::{record_stiffness_inputs, LoadedPair};
use anyhow::Context;
use charts::{te_curve, Series};
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use formats::sensitivity_summary::{
    SensitivityCurve, SensitivityLoad, SensitivityPoint, SensitivitySummary,
};
use geometry::misalignment::Component;
use geometry::pair::{FlankPair, PairGeometry};
use geometry::scene::LoadedScene;
use geometry::utca::roll_surface;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// The chart files and the quantity each shows (against the misalignment
/// as a fraction of its range, one curve per misalignment and torque).
pub const CHART_FILES: [(&str, &str); 6] = [
    ("te_ptp.svg", "TE peak-to-peak (µrad)"),
    ("te_mean.svg", "mean TE (µrad)"),
    (
        "pattern_centre_l.svg",
        "pattern centre along the face, L (mm)",
    ),
    ("pattern_centre_d.svg", "pattern centre in height, d (mm)"),
    ("pattern_length.svg", "pattern length along the face (mm)"),
    ("max_pressure.svg", "largest pressure (MPa)"),
];

/// One chart's quantity of a load.
fn quantity(l: &SensitivityLoad, chart: usize) -> f64 {
    match chart {
        0 => l.te_ptp_urad,
        1 => l.te_mean_urad,
        2 => l.pattern_centre_l_mm,
        3 => l.pattern_centre_d_mm,
        4 => l.pattern_length_mm,
        _ => l.max_pressure_mpa,
    }
}

/// The statistics of one LTCA sweep at torque index `i`.
pub fn load_statistics(
    fp: &FlankPair,
    res: &[PositionResult],
    i: usize,
    torque: f64,
) -> SensitivityLoad {
    let te: Vec<f64> = res.iter().map(|p| p.loads[i].te).collect();
    let (mean, ptp) = mean_ptp(&te);
    let (mut l0, mut l1, mut d0, mut d1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for s in res.iter().flat_map(|p| &p.loads[i].slices) {
        let (l, d) = fp.pinion.bounds.from_unit(s.xi, s.eta);
        (l0, l1, d0, d1) = (l0.min(l), l1.max(l), d0.min(d), d1.max(d));
    }
    SensitivityLoad {
        torque_nm: torque,
        te_ptp_urad: ptp * 1e6,
        te_mean_urad: mean * 1e6,
        pattern_centre_l_mm: 0.5 * (l0 + l1) * 1e3,
        pattern_centre_d_mm: 0.5 * (d0 + d1) * 1e3,
        pattern_length_mm: (l1 - l0) * 1e3,
        pattern_height_mm: (d1 - d0) * 1e3,
        max_pressure_mpa: res
            .iter()
            .map(|p| p.loads[i].max_pressure_pa)
            .fold(0.0, f64::max)
            * 1e-6,
    }
}

/// Runs the study of `scene` (stiffness files from `meshes`) into `out`.
pub fn run(scene: &LoadedScene, meshes: &Path, out: &Path) -> anyhow::Result<SensitivitySummary> {
    let t0 = Instant::now();
    let sc = &scene.scene;
    let ranges = sc.sensitivity_settings();
    if let Err(e) = ranges.check(&scene.path, &sc.misalignment, &scene.pair) {
        if sc.sensitivity.is_none() {
            anyhow::bail!(
                "scene {}: the study's default ranges do not fit: {e}; the scene has no [sensitivity] table, so write one with smaller ranges",
                sc.name
            );
        }
        return Err(e.into());
    }
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("sensitivity"),
        &format!("solver sensitivity {}", scene.path.display()),
    )?;
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = meshes.join(&sc.name);
    // The first pinion × wheel blank, loaded from the aligned geometry
    // (each point of the study places the pair itself).
    let pair = LoadedPair::load(scene, &g, &dir, [sc.blanks.pinion[0], sc.blanks.wheel[0]])?;
    record_stiffness_inputs(&mut set, scene, &g, &dir, pair.blanks, false)?;
    let LoadedPair {
        blanks: [pb, wb],
        pc,
        plans: [pin_plan, whl_plan],
        sweep,
    } = pair;
    let torques = &sc.pinion_torque_nm;
    let mut curves = Vec::new();
    for c in Component::ALL {
        let mut points = Vec::new();
        for value in ranges.sweep(c) {
            let m = sc.misalignment.with(c, sc.misalignment.get(c) + value);
            g.misalign(&m);
            let fp = g.side(sc.loaded_flank);
            let rs = roll_surface(fp, &sc.utca)?;
            let res = run_sweep(fp, &rs, &pc, &sweep, torques).with_context(|| {
                format!(
                    "scene {}: sensitivity, {} = {value} {} (misalignment {m:?})",
                    sc.name,
                    c.symbol(),
                    c.unit()
                )
            })?;
            let loads = torques
                .iter()
                .enumerate()
                .map(|(i, &t)| load_statistics(fp, &res, i, t))
                .collect();
            points.push(SensitivityPoint {
                value,
                misalignment: m,
                loads,
            });
        }
        eprintln!(
            "sensitivity {}: {} values over ±{} {}",
            c.symbol(),
            points.len(),
            ranges.range(c),
            c.unit()
        );
        curves.push(SensitivityCurve {
            component: c,
            symbol: c.symbol().into(),
            unit: c.unit().into(),
            range: ranges.range(c),
            points,
        });
    }
    let summary = SensitivitySummary {
        scene: sc.name.clone(),
        pinion_blank: pb,
        wheel_blank: wb,
        base: sc.misalignment,
        torques_nm: torques.clone(),
        positions: sweep.positions,
        step_deg: sc.rotation.step_deg,
        curves,
        stiffness_files: vec![pin_plan.path, whl_plan.path],
        wall_s: t0.elapsed().as_secs_f64(),
    };
    write_json(&set.path().join("summary.json"), &summary)?;
    write_atomic(
        &set.path().join("summary.csv"),
        summary_csv(&summary)?.as_bytes(),
    )?;
    write_charts(set.path(), &summary)?;
    set.commit()?;
    Ok(summary)
}

/// One row per misalignment × value × torque.
pub fn summary_csv(s: &SensitivitySummary) -> Result<String, std::fmt::Error> {
    let mut csv = String::from(
        "misalignment,unit,value,torque_nm,te_ptp_urad,te_mean_urad,pattern_centre_l_mm,pattern_centre_d_mm,pattern_length_mm,pattern_height_mm,max_pressure_mpa\n",
    );
    for c in &s.curves {
        for p in &c.points {
            for l in &p.loads {
                writeln!(
                    csv,
                    "{},{},{},{},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.3}",
                    c.component.field(),
                    c.unit,
                    p.value,
                    l.torque_nm,
                    l.te_ptp_urad,
                    l.te_mean_urad,
                    l.pattern_centre_l_mm,
                    l.pattern_centre_d_mm,
                    l.pattern_length_mm,
                    l.pattern_height_mm,
                    l.max_pressure_mpa
                )?;
            }
        }
    }
    Ok(csv)
}

/// The charts of [`CHART_FILES`]: the quantity against the misalignment as
/// a fraction of its range, one curve per misalignment and torque.
pub fn write_charts(dir: &Path, s: &SensitivitySummary) -> Result<(), charts::PlotError> {
    let ranges: Vec<String> = s
        .curves
        .iter()
        .map(|c| format!("{} ±{} {}", c.symbol, c.range, c.unit))
        .collect();
    let x_label = format!("misalignment / its range ({})", ranges.join(", "));
    for (k, (file, y_label)) in CHART_FILES.iter().enumerate() {
        let mut series = Vec::new();
        for c in &s.curves {
            for (i, t) in s.torques_nm.iter().enumerate() {
                series.push(Series {
                    name: format!("{}, {t} N·m", c.symbol),
                    x: c.points.iter().map(|p| p.value / c.range).collect(),
                    y: c.points.iter().map(|p| quantity(&p.loads[i], k)).collect(),
                    dashed: i + 1 < s.torques_nm.len(),
                });
            }
        }
        te_curve(
            &dir.join(file),
            &format!("Misalignment sensitivity, {}: {y_label}", s.scene),
            &x_label,
            y_label,
            &series,
        )?;
    }
    Ok(())
}
