//! The web part of the calibration: the lightweight wheel's axial web
//! thickness such that the reduced model's LTCA of the standard pinion
//! with the lightweight wheel gives the published NLFEA mean TE at
//! [`super::WEB_FIT_LOAD_NM`]. Every thickness tried is a scene of its
//! own (the calibrated design, the lightweight wheel only), meshed and
//! its stiffness files solved by the preprocess stages, so each trial
//! costs a few minutes; the search is a secant on ln(mean TE) against
//! ln(thickness), which a plate-like web makes nearly straight.

use super::ease_off_fit::ltca_te;
use super::write;
use geometry::gear_body::BlankDimensions;
use geometry::scene::{Blank, LoadedScene, Scene};
use preprocess::mesh_stage::Level;
use solver::stage::context::{LoadedPair, StageContext};
use std::path::Path;

/// Stop when the mean TE is within this (relative) of the target.
pub const TOLERANCE: f64 = 2e-3;

/// At most this many thicknesses are meshed.
pub const MAX_TRIALS: usize = 6;

/// Thickness bounds, fractions of the base design's web thickness.
pub const BOUNDS: [f64; 2] = [0.3, 3.0];

/// The fitted web.
#[derive(Debug, Clone)]
pub struct WebFit {
    pub base_thickness_mm: f64,
    pub thickness_mm: f64,
    /// The model's lightweight mean TE at the fitted thickness, µrad.
    pub mean_urad: f64,
    /// Every thickness tried: [mm, mean TE µrad].
    pub trials: Vec<[f64; 2]>,
}

/// The next thickness of the secant on ln(mean) − ln(target) over ln(t),
/// from the last two trials (or, after one, with the slope `slope0`),
/// kept inside `[lo, hi]`.
pub fn secant_step(trials: &[[f64; 2]], target: f64, slope0: f64, lo: f64, hi: f64) -> f64 {
    let [t1, m1] = trials[trials.len() - 1];
    let slope = if trials.len() >= 2 {
        let [t0, m0] = trials[trials.len() - 2];
        let s = (m1.ln() - m0.ln()) / (t1.ln() - t0.ln());
        if s.is_finite() && s < 0.0 {
            s
        } else {
            slope0
        }
    } else {
        slope0
    };
    (t1.ln() + (target.ln() - m1.ln()) / slope)
        .exp()
        .clamp(lo, hi)
}

/// Fits the web thickness of `base`'s scene with the calibrated `design`;
/// the trial scenes are written to `work`, their meshes and stiffness
/// files to `meshes`.
pub fn fit(
    base: &LoadedScene,
    design: &Path,
    meshes: &Path,
    work: &Path,
    target_mean_urad: f64,
) -> anyhow::Result<WebFit> {
    let dims = BlankDimensions::resolve(&base.scene.blank_dimensions, &base.pair);
    let base_mm = dims.wheel_lightweight_web_thickness * 1e3;
    let (lo, hi) = (BOUNDS[0] * base_mm, BOUNDS[1] * base_mm);
    std::fs::create_dir_all(work)?;
    let mut trials: Vec<[f64; 2]> = Vec::new();
    let mut t = base_mm;
    loop {
        // Micrometre steps: the scene names and the meshes' inputs stay
        // reproducible.
        t = (t * 1e3).round() / 1e3;
        let mean = trial(base, design, meshes, work, t)?;
        eprintln!(
            "  web {t:.3} mm: lightweight mean TE {mean:.2} urad (target {target_mean_urad:.2})"
        );
        trials.push([t, mean]);
        if (mean / target_mean_urad - 1.0).abs() < TOLERANCE || trials.len() >= MAX_TRIALS {
            break;
        }
        // Before a second trial: a plate web's compliance goes as t⁻³ and
        // it carries about half of the lightweight pair's mean TE.
        let next = secant_step(&trials, target_mean_urad, -1.5, lo, hi);
        if (next - t).abs() < 1e-3 {
            break;
        }
        t = next;
    }
    let best = trials
        .iter()
        .copied()
        .min_by(|a, b| {
            (a[1] / target_mean_urad - 1.0)
                .abs()
                .total_cmp(&(b[1] / target_mean_urad - 1.0).abs())
        })
        .expect("at least one trial");
    Ok(WebFit {
        base_thickness_mm: base_mm,
        thickness_mm: best[0],
        mean_urad: best[1],
        trials,
    })
}

/// One thickness: its scene written, meshed, stiffness files solved, the
/// lightweight pair's LTCA mean TE at the fitted load, µrad.
fn trial(
    base: &LoadedScene,
    design: &Path,
    meshes: &Path,
    work: &Path,
    t_mm: f64,
) -> anyhow::Result<f64> {
    let name = format!("{}_web_{:.0}um", write::CALIBRATED_SCENE_NAME, t_mm * 1e3);
    let path = work.join(format!("{name}.toml"));
    let text = write::web_trial_scene_text(base, design, &name, t_mm)?;
    write::atomic(&path, &text)?;
    let scene = Scene::load(&path)?;
    preprocess::mesh_stage::run(&scene, meshes, Level::Reduced)?;
    preprocess::stiffness_stage::run_level(&scene, meshes, Level::Reduced)?;
    let ctx = StageContext::new(&scene, meshes)?;
    let pair = LoadedPair::load(
        &scene,
        &ctx.g,
        &ctx.dir,
        [Blank::Standard, Blank::Lightweight],
    )?;
    let te = ltca_te(
        &scene,
        &scene.pair.ease_off,
        &pair.pc,
        &pair.sweep,
        &[super::WEB_FIT_LOAD_NM],
    )?;
    Ok(te[0].mean_urad)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn secant_on_a_power_law_lands_on_the_target_in_one_step() {
        // mean = 500 (t / 2)^-3: ln-ln straight, slope −3; from two trials
        // the secant finds t = 2 (500/400)^(1/3) for the target 400.
        let m = |t: f64| 500.0 * (t / 2.0f64).powi(-3);
        let trials = [[2.0, m(2.0)], [2.5, m(2.5)]];
        let t = secant_step(&trials, 400.0, -1.0, 0.1, 10.0);
        assert!((t - 2.0 * 1.25f64.powf(1.0 / 3.0)).abs() < 1e-12, "{t}");
    }

    #[test]
    fn secant_keeps_the_thickness_inside_its_bounds() {
        let t = secant_step(&[[2.0, 100.0]], 1e6, -1.5, 1.0, 4.0);
        assert_eq!(t, 1.0);
    }
}
