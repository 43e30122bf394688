//! Run time against error of the loaded TCA: slices per tooth
//! pair and the stiffness files' contact grid, against the finest FE
//! reference computed for the scene: the penalty-contact reference at the
//! white paper's 35 × 75 elements per flank (`<out>/<scene>/
//! reference_reference/`) where it exists, else the reduced-level
//! reference (`reference/`). Standard blanks, frictionless (as the
//! reference), at exactly the reference's positions and loads.
//!
//! Error: the largest |mean TE − reference| / reference over the loads
//! from [`FROM_NM`] up (secondary: the same of the peak-to-peak TE), %.
//! Cost: thread CPU of the sweep (geometry, assembly, every load's solve),
//! summed over the positions.

use crate::reference::reference_stage::BlankSummary as Reference;
use crate::studies::grid_scenes::GridScene;
use crate::studies::tradeoff_stage::{rel_pct, StageTradeoff, TradeoffPoint};
use anyhow::Context;
use geometry::pair::{pinion_direction, FlankPair, PairGeometry};
use geometry::scene::LoadedScene;
use geometry::utca::{roll_surface, RollSurface};
use solver::element::compliance::PairCompliance;
use solver::ltca::{mean_ptp, run as run_sweep, Sweep};
use std::path::Path;

/// Slices per tooth pair.
pub const SLICES: [usize; 7] = [5, 10, 15, 20, 30, 45, 60];
/// Loads compared, from this pinion torque up, N·m (the lightest load's
/// TE is the unloaded TE, limited by the table of the UTCA, not by the
/// reduced model).
pub const FROM_NM: f64 = 100.0;

const SLICE: &str = "slices per tooth pair";
const GRID: &str = "stiffness grid (profile × face)";

/// The finest standard-blank reference of the scene and its folder name.
fn reference(out: &Path, scene: &str) -> anyhow::Result<(Reference, &'static str)> {
    for folder in ["reference_reference", "reference"] {
        let p = out.join(scene).join(folder).join("summary.json");
        let Ok(text) = std::fs::read_to_string(&p) else {
            continue;
        };
        // The sweep's files as its run wrote them.
        formats::result_set::verify_files(&out.join(scene).join(folder))?;
        let all: Vec<Reference> =
            serde_json::from_str(&text).with_context(|| format!("reading {}", p.display()))?;
        if let Some(r) = all
            .into_iter()
            .find(|r| r.pinion_blank == "standard" && r.wheel_blank == "standard")
        {
            return Ok((r, folder));
        }
    }
    anyhow::bail!(
        "no reference results for the standard blanks in {}/{scene}/reference*/; run `make validate`",
        out.display()
    )
}

struct Case<'a> {
    fp: &'a FlankPair,
    rs: &'a RollSurface,
    sweep: Sweep,
    r: &'a Reference,
}

/// (cost, mean error, ptp error) of one sweep.
fn point(c: &Case, pc: &PairCompliance, slices: usize) -> anyhow::Result<(f64, f64, f64)> {
    let torques: Vec<f64> = c.r.loads.iter().map(|l| l.torque_nm).collect();
    let sweep = Sweep { slices, ..c.sweep };
    let res = run_sweep(c.fp, c.rs, pc, &sweep, &torques)?;
    let cpu = res
        .iter()
        .map(|p| p.geometry_s + p.assembly_s + p.loads.iter().map(|l| l.solve_s).sum::<f64>())
        .sum();
    let (mut em, mut ep) = (0.0f64, 0.0f64);
    for (i, l) in c.r.loads.iter().enumerate() {
        if l.torque_nm < FROM_NM {
            continue;
        }
        let te: Vec<f64> = res.iter().map(|p| p.loads[i].te * 1e6).collect();
        let (m, p) = mean_ptp(&te);
        em = em.max(rel_pct(m, l.te_mean_urad).abs());
        ep = ep.max(rel_pct(p, l.te_ptp_urad).abs());
    }
    Ok((cpu, em, ep))
}

/// The study; `grids` are the scenes of the same design at other contact
/// grids (the scene's own grid is the default).
pub fn run(
    scene: &LoadedScene,
    out: &Path,
    pc: &PairCompliance,
    grids: &[GridScene],
) -> anyhow::Result<StageTradeoff> {
    let sc = &scene.scene;
    let (r, folder) = reference(out, &sc.name)?;
    let mut st = StageTradeoff::new(
        "ltca",
        "Loaded TCA: thread CPU against the error to the FE reference",
        "thread CPU of the sweep, all loads (s)",
        &format!(
            "largest |mean TE − reference| / reference over the loads from {FROM_NM} N·m (secondary: peak-to-peak TE), standard blanks, against `{folder}` ({} level, {} × {} elements per flank; {} positions at {}°)",
            r.level,
            if r.level == "reference" { sc.mesh.reference.profile } else { sc.mesh.reduced_order.profile },
            if r.level == "reference" { sc.mesh.reference.face } else { sc.mesh.reduced_order.face },
            r.positions,
            r.step_deg
        ),
    );
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = sc.loaded_flank;
    let fp = g.side(side);
    let rs = roll_surface(fp, &sc.utca)?;
    let case = Case {
        fp,
        rs: &rs,
        sweep: Sweep {
            start: fp.roll_range[0],
            step: r.step_deg.to_radians(),
            direction: pinion_direction(&g.data, side),
            positions: r.positions,
            slices: sc.ltca.slices,
            friction: 0.0,
        },
        r: &r,
    };
    let mut slices = SLICES.to_vec();
    if !slices.contains(&sc.ltca.slices) {
        slices.push(sc.ltca.slices);
        slices.sort_unstable();
    }
    for n in slices {
        match point(&case, pc, n) {
            Ok((cpu, em, ep)) => st.push(TradeoffPoint {
                parameter: SLICE.into(),
                setting: format!("{n}"),
                value: n as f64,
                cpu_s: cpu,
                error_pct: em,
                secondary_error_pct: Some(ep),
                is_default: n == sc.ltca.slices,
            }),
            Err(e) => st.skip(SLICE, &format!("{n}"), format!("{e:#}")),
        }
    }
    let own = sc.mesh.reduced_order;
    for gs in grids {
        let is_default = gs.grid == [own.profile, own.face];
        let res = if is_default {
            point(&case, pc, sc.ltca.slices)
        } else {
            gs.compliance()
                .and_then(|gpc| point(&case, &gpc, sc.ltca.slices))
        };
        match res {
            Ok((cpu, em, ep)) => st.push(TradeoffPoint {
                parameter: GRID.into(),
                setting: gs.label(),
                value: (gs.grid[0] * gs.grid[1]) as f64,
                cpu_s: cpu,
                error_pct: em,
                secondary_error_pct: Some(ep),
                is_default,
            }),
            Err(e) => st.skip(GRID, &gs.label(), format!("{e:#}")),
        }
    }
    st.finish();
    Ok(st)
}
