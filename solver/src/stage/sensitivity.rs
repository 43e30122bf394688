//! `solver sensitivity <scene>`: the classic V–H-style sensitivity study.
//! Each misalignment E, P, G, ΔΣ is swept alone over the scene's
//! `[sensitivity]` range (on top of the scene's own `[misalignment]`), and
//! at every value the loaded TCA of the first pinion × wheel blank runs at
//! the scene's loads over the scene's sweep: TE peak-to-peak and mean, the
//! loaded pattern's centre and extent on the pinion flank (L along the face,
//! d in height), the largest pressure and, where the stiffness files hold
//! root-stress coefficients, the largest tooth root (fillet) tension of
//! pinion and wheel with where it sits. The stiffness files are read once:
//! they are body-fixed and serve every pose.
//!
//! Writes `<out>/<scene>/sensitivity/` as one result set: `summary.json`
//! ([`formats::sensitivity_summary`]), `summary.csv` (one row per
//! misalignment × value × torque), the charts of [`CHART_FILES`] and, with
//! root stress, those of [`ROOT_STRESS_CHART_FILES`].

use crate::ltca::{mean_ptp, run_with_root_stress, PositionResult};
use crate::stage::context::{record_stiffness_inputs, LoadedPair};
use anyhow::Context;
use charts::{te_curve, Series};
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use formats::root_stress::RootStressSummary;
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

/// The root-stress chart files (written when the stiffness files hold
/// root-stress coefficients) and the quantity each shows.
pub const ROOT_STRESS_CHART_FILES: [(&str, &str); 2] = [
    (
        "pinion_root_stress.svg",
        "largest pinion root tension (MPa)",
    ),
    ("wheel_root_stress.svg", "largest wheel root tension (MPa)"),
];

/// One chart's quantity of a load: the charts of [`CHART_FILES`], then
/// those of [`ROOT_STRESS_CHART_FILES`] (NaN without root stress).
fn quantity(l: &SensitivityLoad, chart: usize) -> f64 {
    let tension = |f: fn(&RootStressSummary) -> f64| l.root_stress.as_ref().map_or(f64::NAN, f);
    match chart {
        0 => l.te_ptp_urad,
        1 => l.te_mean_urad,
        2 => l.pattern_centre_l_mm,
        3 => l.pattern_centre_d_mm,
        4 => l.pattern_length_mm,
        5 => l.max_pressure_mpa,
        6 => tension(|r| r.pinion.tension_mpa),
        _ => tension(|r| r.wheel.tension_mpa),
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
        root_stress: formats::root_stress::summarize(
            res.iter()
                .map(|p| (p.rotation.to_degrees(), p.loads[i].root_stress.as_ref())),
        ),
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
            let res = run_with_root_stress(fp, &rs, &pc, &sweep, torques).with_context(|| {
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
        "misalignment,unit,value,torque_nm,te_ptp_urad,te_mean_urad,pattern_centre_l_mm,pattern_centre_d_mm,pattern_length_mm,pattern_height_mm,max_pressure_mpa,pinion_root_tension_mpa,pinion_root_tension_xi,wheel_root_tension_mpa,wheel_root_tension_xi\n",
    );
    // Empty cells where the stiffness files hold no root stress.
    let root = |l: &SensitivityLoad| match &l.root_stress {
        Some(r) => format!(
            "{:.3},{:.4},{:.3},{:.4}",
            r.pinion.tension_mpa,
            r.pinion.tension_at.xi,
            r.wheel.tension_mpa,
            r.wheel.tension_at.xi
        ),
        None => ",,,".into(),
    };
    for c in &s.curves {
        for p in &c.points {
            for l in &p.loads {
                writeln!(
                    csv,
                    "{},{},{},{},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.3},{}",
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
                    l.max_pressure_mpa,
                    root(l)
                )?;
            }
        }
    }
    Ok(csv)
}

/// The charts of [`CHART_FILES`] (and of [`ROOT_STRESS_CHART_FILES`] when
/// every load has root stress): the quantity against the misalignment as a
/// fraction of its range, one curve per misalignment and torque.
pub fn write_charts(dir: &Path, s: &SensitivitySummary) -> Result<(), charts::PlotError> {
    let ranges: Vec<String> = s
        .curves
        .iter()
        .map(|c| format!("{} ±{} {}", c.symbol, c.range, c.unit))
        .collect();
    let x_label = format!("misalignment / its range ({})", ranges.join(", "));
    let with_root_stress = s.has_root_stress();
    let files = CHART_FILES
        .iter()
        .chain(ROOT_STRESS_CHART_FILES.iter().filter(|_| with_root_stress));
    for (k, (file, y_label)) in files.enumerate() {
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
