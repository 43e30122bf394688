//! Run time against error of the UTCA: the surface of roll
//! angles' sampling (face × profile samples) and the rotation step, against
//! the direct contact search ([`geometry::direct::direct_te`], Newton on
//! the flanks themselves) at [`DIRECT_POSITIONS`] positions of one mesh
//! cycle, placed off every studied step's grid so that the UTCA's curve is
//! interpolated (linearly) between its positions as a user's would be.
//!
//! Error: max |TE_UTCA − TE_direct| over the positions / the direct TE's
//! peak-to-peak, %. Cost: thread CPU of the roll surface plus one mesh
//! cycle of UTCA positions.

use crate::studies::tradeoff_stage::{StageTradeoff, TradeoffPoint};
use geometry::direct::direct_te;
use geometry::pair::{pinion_direction, FlankPair, PairGeometry};
use geometry::scene::LoadedScene;
use geometry::utca::{run as utca_run, LineGrid, RollSurface};
use solver::cpu_clock::timed;
use solver::multibody::model::interpolate;

/// Direct-search positions over one mesh cycle.
pub const DIRECT_POSITIONS: usize = 48;
/// Roll-surface samples (face = profile).
pub const SAMPLES: [usize; 5] = [11, 21, 31, 41, 81];
/// Rotation steps, degrees.
pub const STEPS_DEG: [f64; 5] = [0.5, 0.25, 0.1, 0.05, 0.025];

const GRID: &str = "roll-surface samples (face × profile)";
const STEP: &str = "rotation step (deg)";

/// One UTCA run: its cost and its error to `direct` (pinion rotations
/// from the sweep's start, TEs in rad).
fn point(
    fp: &FlankPair,
    samples: [usize; 2],
    step: f64,
    direction: f64,
    direct: &[(f64, f64)],
) -> anyhow::Result<(f64, f64)> {
    let tau = fp.pinion.gen.frame.pitch();
    let n = (tau / step).ceil() as usize + 2;
    let (te, cpu) = timed(|| -> anyhow::Result<Vec<f64>> {
        let rs = RollSurface::new(
            fp,
            LineGrid {
                n_face: samples[0],
                n_profile: samples[1],
            },
        )?;
        Ok(utca_run(fp, &rs, fp.roll_range[0], step, n, direction).te)
    });
    let te = te?;
    let rot: Vec<f64> = (0..te.len()).map(|k| step * k as f64).collect();
    let (lo, hi) = direct
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), d| {
            (a.min(d.1), b.max(d.1))
        });
    let worst = direct
        .iter()
        .map(|&(r, d)| (interpolate(&rot, &te, r) - d).abs())
        .fold(
            0.0,
            |a: f64, b| if b.is_nan() { f64::NAN } else { a.max(b) },
        );
    Ok((cpu, worst / (hi - lo) * 100.0))
}

pub fn run(scene: &LoadedScene) -> anyhow::Result<StageTradeoff> {
    let mut st = StageTradeoff::new(
        "utca",
        "UTCA: thread CPU against the error to the direct contact search",
        "thread CPU, roll surface + one mesh cycle (s)",
        "max |TE_UTCA − TE_direct| over one mesh cycle / peak-to-peak of the direct TE (unloaded, loaded flank)",
    );
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let fp = g.side(sc.loaded_flank);
    let dir = pinion_direction(&g.data, sc.loaded_flank);
    let tau = fp.pinion.gen.frame.pitch();
    let nodes = RollSurface::new(
        fp,
        LineGrid {
            n_face: 21,
            n_profile: 21,
        },
    )?;
    let mut direct = Vec::with_capacity(DIRECT_POSITIONS);
    for k in 0..DIRECT_POSITIONS {
        // 0.37 of a spacing off: on no studied step's grid.
        let r = (k as f64 + 0.37) * tau / DIRECT_POSITIONS as f64;
        let d = direct_te(fp, &nodes, fp.roll_range[0] + dir * r, dir).ok_or_else(|| {
            anyhow::anyhow!(
                "direct contact search found no contact at {:.3}°",
                r.to_degrees()
            )
        })?;
        direct.push((r, d.te));
    }
    let u = &sc.utca;
    let default_samples = [u.face_samples, u.profile_samples];
    let mut samples: Vec<usize> = SAMPLES.to_vec();
    if u.face_samples == u.profile_samples && !samples.contains(&u.face_samples) {
        samples.push(u.face_samples);
        samples.sort_unstable();
    }
    let mut grids: Vec<[usize; 2]> = samples.iter().map(|&n| [n, n]).collect();
    if !grids.contains(&default_samples) {
        grids.push(default_samples);
    }
    for s in grids {
        let label = format!("{} × {}", s[0], s[1]);
        match point(fp, s, u.step_deg.to_radians(), dir, &direct) {
            Ok((cpu, e)) => st.push(TradeoffPoint {
                parameter: GRID.into(),
                setting: label,
                value: (s[0] * s[1]) as f64,
                cpu_s: cpu,
                error_pct: e,
                secondary_error_pct: None,
                is_default: s == default_samples,
            }),
            Err(e) => st.skip(GRID, &label, format!("{e:#}")),
        }
    }
    let mut steps: Vec<f64> = STEPS_DEG.to_vec();
    if !steps.contains(&u.step_deg) {
        steps.push(u.step_deg);
        steps.sort_by(|a, b| b.total_cmp(a));
    }
    for h in steps {
        let label = format!("{h}°");
        match point(fp, default_samples, h.to_radians(), dir, &direct) {
            Ok((cpu, e)) => st.push(TradeoffPoint {
                parameter: STEP.into(),
                setting: label,
                value: h,
                cpu_s: cpu,
                error_pct: e,
                secondary_error_pct: None,
                is_default: h == u.step_deg,
            }),
            Err(e) => st.skip(STEP, &label, format!("{e:#}")),
        }
    }
    st.finish();
    Ok(st)
}
