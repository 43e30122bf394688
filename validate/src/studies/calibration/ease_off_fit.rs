//! The ease-off part of the calibration: the pinion's ease-off (motion
//! error, lengthwise and profile crowning, bias) fitted so that the reduced
//! model's LTCA of the standard pair gives the published NLFEA mean and
//! peak-to-peak TE at the fitted loads.
//!
//! Inside the fit the body compliance is the default design's stiffness
//! files (the ease-off changes the pinion flank by micrometres on a tooth
//! some 9 mm thick; the calibrated design's own files are made and used
//! afterwards, and the rows are recomputed with them): each evaluation is
//! the surface of roll angles and the LTCA sweep, about a second.

use super::levenberg_marquardt::{self, Bounds};
use geometry::design::EaseOffDesign;
use geometry::pair::PairGeometry;
use geometry::scene::LoadedScene;
use geometry::utca::roll_surface;
use serde::Serialize;
use solver::element::compliance::PairCompliance;
use solver::ltca::Sweep;

/// A fitted parameter: its name in the design's `[ease_off]`, start, bounds.
pub const PARAMETERS: [(&str, f64, f64, f64); 4] = [
    // name, lower, upper, finite-difference step
    ("motion_error_urad", 0.0, 80.0, 0.25),
    ("lengthwise_crowning_um", 0.0, 100.0, 0.5),
    ("profile_crowning_um", 0.0, 40.0, 0.25),
    ("bias_um", -40.0, 40.0, 0.5),
];

/// The four ease-off values in [`PARAMETERS`] order.
pub fn values(e: &EaseOffDesign) -> [f64; 4] {
    [
        e.motion_error_urad,
        e.lengthwise_crowning_um,
        e.profile_crowning_um,
        e.bias_um,
    ]
}

/// `base` with the four values of `x` ([`PARAMETERS`] order); the
/// topography, if any, kept.
pub fn with_values(base: &EaseOffDesign, x: &[f64]) -> EaseOffDesign {
    EaseOffDesign {
        motion_error_urad: x[0],
        lengthwise_crowning_um: x[1],
        profile_crowning_um: x[2],
        bias_um: x[3],
        topography: base.topography.clone(),
    }
}

/// Mean and peak-to-peak TE at one load, µrad.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Te {
    pub load_nm: f64,
    pub mean_urad: f64,
    pub ptp_urad: f64,
}

/// The reduced model's LTCA of `scene`'s pair with the pinion ease-off `e`
/// over `sweep` with compliance `pc`, at `loads_nm`.
pub fn ltca_te(
    scene: &LoadedScene,
    e: &EaseOffDesign,
    pc: &PairCompliance,
    sweep: &Sweep,
    loads_nm: &[f64],
) -> anyhow::Result<Vec<Te>> {
    let mut data = scene.pair.clone();
    data.ease_off = e.clone();
    let mut g = PairGeometry::build(&data, Some(&scene.design_path))?;
    g.misalign(&scene.scene.misalignment);
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca)?;
    let res = solver::ltca::run(fp, &rs, pc, sweep, loads_nm)?;
    Ok(solver::stage::ltca::load_summaries(&res, loads_nm)
        .into_iter()
        .map(|l| Te {
            load_nm: l.torque_nm,
            mean_urad: l.te_mean_urad,
            ptp_urad: l.te_ptp_urad,
        })
        .collect())
}

/// Relative residuals (model − target) / target of mean and ptp per load.
pub fn residuals(model: &[Te], target: &[Te]) -> Vec<f64> {
    model
        .iter()
        .zip(target)
        .flat_map(|(m, t)| {
            [
                (m.mean_urad - t.mean_urad) / t.mean_urad,
                (m.ptp_urad - t.ptp_urad) / t.ptp_urad,
            ]
        })
        .collect()
}

/// The fitted ease-off and the fit's record.
#[derive(Debug, Clone, Serialize)]
pub struct EaseOffFit {
    pub start: [f64; 4],
    pub fitted: [f64; 4],
    /// The model's rows at the fitted ease-off (default stiffness files).
    pub rows: Vec<Te>,
    pub evaluations: usize,
    pub iterations: usize,
}

/// Fits the ease-off from `scene`'s own towards `target` (mean and ptp per
/// load, loads in `target` order).
pub fn fit(
    scene: &LoadedScene,
    pc: &PairCompliance,
    sweep: &Sweep,
    target: &[Te],
) -> anyhow::Result<EaseOffFit> {
    let base = &scene.pair.ease_off;
    let loads: Vec<f64> = target.iter().map(|t| t.load_nm).collect();
    let bounds: Vec<Bounds> = PARAMETERS
        .iter()
        .map(|&(_, lower, upper, step)| Bounds { lower, upper, step })
        .collect();
    let start = values(base);
    let f = levenberg_marquardt::fit(
        |x: &[f64]| {
            let te = ltca_te(scene, &with_values(base, x), pc, sweep, &loads)?;
            let r = residuals(&te, target);
            eprintln!(
                "  ease-off {:?}: residuals {:?} %",
                x.iter()
                    .map(|v| (v * 1e3).round() / 1e3)
                    .collect::<Vec<_>>(),
                r.iter()
                    .map(|v| (v * 1e4).round() / 1e2)
                    .collect::<Vec<_>>()
            );
            Ok::<_, anyhow::Error>(r)
        },
        &start,
        &bounds,
        20,
        1e-4,
    )?;
    let fitted = [f.x[0], f.x[1], f.x[2], f.x[3]];
    let rows = ltca_te(scene, &with_values(base, &fitted), pc, sweep, &loads)?;
    Ok(EaseOffFit {
        start,
        fitted,
        rows,
        evaluations: f.evaluations + 1,
        iterations: f.iterations,
    })
}
