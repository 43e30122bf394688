//! `validate stage-tradeoffs <scene>` (run by `make stress`): run time
//! against error for every stage of the scene's design, each
//! stage's study in its own module:
//!
//! - UTCA ([`tradeoff_utca`]): roll-surface samples and rotation step
//!   against the direct contact search;
//! - stiffness fields ([`tradeoff_fields`]): contact grid against the next
//!   finer grid, mesh level against the medium mesh;
//! - LTCA ([`tradeoff_ltca`]): slices and stiffness grid against the finest
//!   FE reference computed;
//! - multibody ([`tradeoff_multibody`]): maximum step and tolerance against
//!   the 10 rpm LTCA and, for a run-up, against a 10× smaller step;
//! - reference ([`tradeoff_reference`]): mesh level against the Richardson
//!   extrapolation of `validate convergence`.
//!
//! Written as one result set to `<out>/<scene>/tradeoff/`: `summary.json`
//! ([`TradeoffSummary`]), `<stage>.json` and `<stage>.svg` per stage.
//!
//! [`tradeoff_utca`]: crate::studies::tradeoff_utca
//! [`tradeoff_fields`]: crate::studies::tradeoff_fields
//! [`tradeoff_ltca`]: crate::studies::tradeoff_ltca
//! [`tradeoff_multibody`]: crate::studies::tradeoff_multibody
//! [`tradeoff_reference`]: crate::studies::tradeoff_reference
use solver::stage::context::LoadedPair;

use crate::studies::grid_scenes::GridScene;
use crate::studies::tradeoff_stage::StageTradeoff;
use crate::studies::{
    tradeoff_fields, tradeoff_ltca, tradeoff_multibody, tradeoff_reference, tradeoff_utca,
};
use anyhow::Context;
use formats::output::write_json;
use formats::result_set::ResultSet;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::roll_surface;
use indicatif::{ProgressBar, ProgressStyle};
use serde::{Deserialize, Serialize};
use solver::element::compliance::PairCompliance;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `summary.json` of the trade-off set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TradeoffSummary {
    pub scene: String,
    pub stages: Vec<StageTradeoff>,
    /// Stages that could not run at all, with why.
    pub missing: Vec<(String, String)>,
    pub wall_s: f64,
}

impl TradeoffSummary {
    /// Reads `<out>/<scene>/tradeoff/summary.json`; None where absent.
    pub fn read(out: &Path, scene: &str) -> anyhow::Result<Option<TradeoffSummary>> {
        let p = out.join(scene).join("tradeoff").join("summary.json");
        match std::fs::read_to_string(&p) {
            Ok(t) => Ok(Some(
                serde_json::from_str(&t).with_context(|| format!("reading {}", p.display()))?,
            )),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(e).with_context(|| format!("reading {}", p.display())),
        }
    }
}

const STAGES: u64 = 6;

/// Runs every stage's study; `grid_scenes` are scenes of the same design at
/// other contact grids (others are ignored).
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    grid_scenes: &[PathBuf],
) -> anyhow::Result<TradeoffSummary> {
    let t0 = Instant::now();
    let sc = &scene.scene;
    let set = ResultSet::begin(
        &out.join(&sc.name).join("tradeoff"),
        &format!("validate stage-tradeoffs {}", scene.path.display()),
    )?;
    let bar = ProgressBar::new(STAGES);
    bar.set_style(
        ProgressStyle::with_template("trade-off {bar:40} {pos}/{len} stages, {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut grids = vec![GridScene::load(&scene.path, meshes)?];
    for p in grid_scenes {
        let gs = GridScene::load(p, meshes)?;
        if gs.same_design(scene) && gs.grid != grids[0].grid {
            grids.push(gs);
        }
    }
    let mut stages = Vec::new();
    let mut missing = Vec::new();
    let mut note = |stage: &str, r: anyhow::Result<Vec<StageTradeoff>>, bar: &ProgressBar| {
        match r {
            Ok(v) => stages.extend(v),
            Err(e) => missing.push((stage.to_string(), format!("{e:#}"))),
        }
        bar.inc(1);
    };
    bar.set_message("UTCA");
    note("utca", tradeoff_utca::run(scene).map(|s| vec![s]), &bar);
    bar.set_message("stiffness fields");
    let own = [sc.mesh.reduced_order.profile, sc.mesh.reduced_order.face];
    note(
        "stiffness",
        Ok(vec![tradeoff_fields::run(&grids, own)]),
        &bar,
    );
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = meshes.join(&sc.name);
    let pair = (|| -> anyhow::Result<(PairCompliance, [f64; 2])> {
        let pair = LoadedPair::load(scene, &g, &dir, [Blank::Standard; 2])?;
        let [(j1, _), (j2, _)] = pair.inertia(scene, &g, &dir)?;
        Ok((pair.pc, [j1, j2]))
    })();
    match pair {
        Err(e) => {
            let why = format!("stiffness files not cached: {e:#}");
            missing.push(("ltca".into(), why.clone()));
            missing.push(("multibody".into(), why));
            bar.inc(2);
        }
        Ok((pc, j)) => {
            bar.set_message("LTCA");
            note(
                "ltca",
                tradeoff_ltca::run(scene, out, &pc, &grids).map(|s| vec![s]),
                &bar,
            );
            bar.set_message("multibody");
            let fp = g.side(sc.loaded_flank);
            let r = roll_surface(fp, &sc.utca)
                .map_err(anyhow::Error::from)
                .and_then(|rs| tradeoff_multibody::run(scene, &g, fp, &rs, &pc, j))
                .map(|v| v.to_vec());
            note("multibody", r, &bar);
            bar.inc(1);
        }
    }
    bar.set_message("reference");
    match tradeoff_reference::run(out, &sc.name) {
        Ok(Some(s)) => stages.push(s),
        Ok(None) => missing.push((
            "reference".into(),
            "no `validate convergence` results (make convergence)".into(),
        )),
        Err(e) => missing.push(("reference".into(), format!("{e:#}"))),
    }
    bar.inc(1);
    bar.finish_and_clear();
    for s in stages.iter_mut() {
        s.draw(set.path())?;
        write_json(&set.path().join(format!("{}.json", s.stage)), &*s)?;
    }
    let summary = TradeoffSummary {
        scene: sc.name.clone(),
        stages,
        missing,
        wall_s: t0.elapsed().as_secs_f64(),
    };
    write_json(&set.path().join("summary.json"), &summary)?;
    set.commit()?;
    Ok(summary)
}
