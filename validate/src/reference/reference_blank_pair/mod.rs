//! One blank pair of `validate reference` ([`super::reference_stage`]): its
//! meshes checked, its sweep's inputs hashed, its positions from the cache
//! or solved (the bodies factored at the first position solved), its
//! files and summary; a cache comparison or a shard writes no result.

mod results;
mod sweep;

use results::{body_stats, print_summary, write_pattern};

use super::reference_options::{utca_at, StageOptions, REFERENCE_SCHEMA};
use super::reference_outputs::{copy_files, load_summaries, unloaded_check, write_te_csv};
use super::reference_root_stress::write_root_stress_csv;
use super::reference_summary::{BlankSummary, CacheComparison};
use crate::reference::reference_ltca::{Member, PositionResult};
use anyhow::Context;
use formats::output::write_json;
use formats::paths::MeshLevel;
use formats::result_set::{ResultSet, RunLock};
use formats::stiffness_plan;
use geometry::design::Member as Which;
use geometry::pair::{teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use preprocess::stiffness_stage::sha256_file;
use sha2::{Digest, Sha256};

/// What every blank pair of one `validate reference` run shares.
pub(super) struct Run<'a> {
    pub(super) scene: &'a LoadedScene,
    pub(super) opt: &'a StageOptions,
    /// The pair placed with the scene's misalignment.
    pub(super) g: PairGeometry,
    pub(super) side: geometry::generation::Side,
    /// Pinion's driving direction (±1) and the sweep's step, rad.
    pub(super) direction: f64,
    pub(super) step: f64,
    /// The scene's mesh folder and the results folder of the level.
    pub(super) dir: std::path::PathBuf,
    pub(super) ref_dir: std::path::PathBuf,
    /// The command, for locks and memory messages.
    pub(super) what: String,
    /// Pinion teeth in contact over every wheel blank's sweep.
    pub(super) pinion_teeth: Vec<usize>,
    /// The lock of a cache comparison or of a shard.
    pub(super) lock: Option<RunLock>,
}

/// The two body meshes of a blank pair, checked against the manifest.
struct PairMeshes {
    paths: [std::path::PathBuf; 2],
    sha256: [String; 2],
    /// Degrees of freedom of each body (0 when the manifest predates them).
    dofs: [usize; 2],
}

/// What the sweep over the positions gave.
struct Swept {
    res: Vec<PositionResult>,
    reused: usize,
    comparison: CacheComparison,
    /// Whether a position was solved (the bodies in [`Bodies`] served it).
    solved: bool,
    /// Each body's right-hand sides and solve time before this sweep.
    before: [(usize, f64); 2],
    sweep_s: f64,
}

/// What a factored body was made from: the same key, the same factor and
/// flank faces (its pose is the scene's, applied at each position).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BodyKey {
    pub(crate) blank: Blank,
    mesh_sha256: String,
    teeth: Vec<usize>,
    side: geometry::generation::Side,
    block: usize,
}

/// The factored bodies held between blank pairs and between the scenes of
/// one run (see [`super::reference_stage::run_scenes`]), each with its key.
#[derive(Default)]
pub(crate) struct Bodies {
    pub(crate) pinion: Option<(BodyKey, Member)>,
    pub(crate) wheel: Option<(BodyKey, Member)>,
}

impl BodyKey {
    fn teeth(&self) -> &[usize] {
        &self.teeth
    }
}

impl Bodies {
    fn member(&self, k: usize) -> Option<&Member> {
        [&self.pinion, &self.wheel][k].as_ref().map(|(_, m)| m)
    }
}

impl Run<'_> {
    fn fp(&self) -> &geometry::pair::FlankPair {
        self.g.side(self.side)
    }

    /// The pinion angles of wheel blank `wb`'s sweep at its stride.
    fn positions(&self, wb: Blank) -> (Vec<f64>, usize) {
        let opt = self.opt;
        let stride = match wb {
            Blank::Lightweight => opt.stride_lightweight.unwrap_or(opt.stride),
            _ => opt.stride,
        }
        .max(1);
        let cycles = self.scene.scene.rotation.mesh_cycles(wb);
        let n_pos = (cycles * self.g.data.mesh_cycle() / self.step).round() as usize + 1;
        let start = self.fp().roll_range[0];
        let positions = (0..n_pos)
            .step_by(stride)
            .map(|i| start + self.direction * self.step * i as f64)
            .collect();
        (positions, stride)
    }

    /// The blank pair's meshes: present, the mesh stage's for the scene's
    /// current inputs and unchanged since; recorded in `set`.
    fn meshes(
        &self,
        [pb, wb]: [Blank; 2],
        mut set: Option<&mut ResultSet>,
    ) -> anyhow::Result<PairMeshes> {
        let (scene, opt) = (self.scene, self.opt);
        let sc = &scene.scene;
        let msh = |m: Which, b: Blank| {
            formats::paths::msh(&self.dir, &formats::paths::stem_named(m, b, &opt.level))
        };
        let paths = [msh(Which::Pinion, pb), msh(Which::Wheel, wb)];
        for p in &paths {
            if !p.exists() {
                anyhow::bail!(
                    "scene {}: no mesh {}; run `preprocess mesh {} --level {}`",
                    sc.name,
                    p.display(),
                    scene.path.display(),
                    opt.level
                );
            }
        }
        let sha256 = [sha256_file(&paths[0])?, sha256_file(&paths[1])?];
        let level = MeshLevel::FINEST_FIRST
            .into_iter()
            .find(|l| l.name() == opt.level)
            .with_context(|| format!("unknown mesh level {}", opt.level))?;
        let mut dofs = [0usize; 2];
        for (k, (m, b)) in [(Which::Pinion, pb), (Which::Wheel, wb)]
            .into_iter()
            .enumerate()
        {
            let (path, hash) = (&paths[k], &sha256[k]);
            let stem = formats::paths::mesh_stem(m, b, level);
            let entry = stiffness_plan::check_mesh(scene, &self.g, &self.dir, &stem, m, b, level)
                .with_context(|| {
                    format!(
                        "scene {}: the {} mesh {} does not serve the scene; run `preprocess mesh {} --level {}`",
                        sc.name,
                        m.name(),
                        path.display(),
                        scene.path.display(),
                        opt.level
                    )
                })?;
            if &entry.msh_sha256 != hash {
                return Err(stiffness_plan::CheckError::MeshChanged {
                    path: path.to_path_buf(),
                    found: hash.clone(),
                    listed: entry.msh_sha256,
                }
                .into());
            }
            dofs[k] = 3 * entry.body.nodes;
            if let Some(set) = set.as_deref_mut() {
                set.record_input("design", &entry.inputs.design_sha256)?;
                set.record_input(&format!("mesh:{stem}"), hash)?;
            }
        }
        Ok(PairMeshes {
            paths,
            sha256,
            dofs,
        })
    }

    /// The key of one position's result (what determines it, not the
    /// stride), and the hash of the sweep's inputs (the key and the
    /// positions).
    fn keys(&self, m: &PairMeshes, positions: &[f64]) -> (String, String) {
        let sc = &self.scene.scene;
        let digest =
            |key: serde_json::Value| format!("{:x}", Sha256::digest(key.to_string().as_bytes()));
        let mut key = serde_json::json!({
            "schema": REFERENCE_SCHEMA,
            "pinion_mesh": m.sha256[0],
            "wheel_mesh": m.sha256[1],
            "level": self.opt.level,
            "settings": self.opt.settings,
            "torques": sc.pinion_torque_nm,
            "flank": self.side.flank_name(Which::Pinion),
        });
        // Only a misaligned pair adds its pose: the aligned pair's
        // cached positions keep their keys.
        if !sc.misalignment.is_zero() {
            key["misalignment"] = serde_json::json!(sc.misalignment);
        }
        let position_key = digest(key);
        let hash = digest(serde_json::json!({
            "position_key": position_key,
            "positions": positions,
        }));
        (position_key, hash)
    }

    /// One blank pair: reused whole when its inputs are unchanged, else its
    /// positions from the cache or solved, then its files and summary
    /// (None for a cache comparison or a shard, which write no result).
    pub(super) fn blank_pair(
        &self,
        [pb, wb]: [Blank; 2],
        bodies: &mut Bodies,
        set: Option<&mut ResultSet>,
    ) -> anyhow::Result<Option<BlankSummary>> {
        let (scene, opt) = (self.scene, self.opt);
        let sc = &scene.scene;
        let t0 = std::time::Instant::now();
        let name = format!("{}_{}", blank_name(pb), blank_name(wb));
        // The previous results and the position cache; this run's
        // results go to `sdir` in the staging directory (a full run).
        let odir = self.ref_dir.join(&name);
        let sdir = set.as_ref().map(|s| s.path().join(&name));
        let (positions, stride) = self.positions(wb);
        let meshes = self.meshes([pb, wb], set)?;
        let (position_key, hash) = self.keys(&meshes, &positions);
        let summary_path = odir.join("summary.json");
        let partial = opt.compare_cache || opt.shard.is_some();
        if let (false, Ok(text)) = (partial, std::fs::read_to_string(&summary_path)) {
            if let Ok(s) = serde_json::from_str::<BlankSummary>(&text) {
                // A summary from before the check-penalty statistics is
                // rebuilt from the position cache (nothing is solved).
                let complete = s.loads.iter().all(|l| l.te_check_mean_urad.is_some());
                if s.input_hash == hash && complete {
                    eprintln!(
                        "reference {name}: inputs unchanged, reusing {}",
                        summary_path.display()
                    );
                    if let Some(sdir) = &sdir {
                        copy_files(&odir, sdir)?;
                    }
                    return Ok(Some(s));
                }
            }
        }
        // The UTCA TE at the same positions, for the unloaded check.
        let fp = self.fp();
        let utca = utca_at(
            scene,
            fp,
            fp.roll_range[0],
            self.step * stride as f64,
            positions.len(),
            self.direction,
        )?;
        if let Some((a, b)) = utca
            .pinion_angle
            .iter()
            .zip(&positions)
            .find(|(a, b)| (*a - *b).abs() > 1e-12)
        {
            anyhow::bail!(
                "internal: UTCA position {a} rad differs from reference position {b} rad"
            );
        }
        let cache_dir = odir.join("positions").join(&position_key[..16]);
        std::fs::create_dir_all(&cache_dir)?;
        let wheel_teeth =
            teeth_in_contact(&self.g, self.side, sc.rotation.mesh_cycles(wb), self.step).1;
        let keys = [(pb, &self.pinion_teeth[..]), (wb, &wheel_teeth[..])]
            .into_iter()
            .zip(&meshes.sha256)
            .map(|((blank, teeth), sha)| BodyKey {
                blank,
                mesh_sha256: sha.clone(),
                teeth: teeth.to_vec(),
                side: self.side,
                block: opt.block,
            })
            .collect::<Vec<_>>();
        let swept = self.sweep(&name, &positions, &cache_dir, &meshes, bodies, &keys)?;
        if opt.compare_cache {
            self.report_comparison(&name, &swept.comparison, &odir)?;
            return Ok(None);
        }
        if let Some((k, n)) = opt.shard {
            eprintln!(
                "reference {name}: shard {k}/{n} solved; a run without --shard collects every shard's positions from {}",
                cache_dir.display()
            );
            return Ok(None);
        }
        let res = &swept.res;
        let sdir = sdir.expect("a run without --shard or --compare-cache has a result set");
        std::fs::create_dir_all(&sdir)?;
        write_te_csv(
            &sdir.join("te.csv"),
            res,
            &utca.te,
            &fp.pinion,
            fp.roll_range[0],
            self.direction,
        )?;
        let (start, direction) = (fp.roll_range[0], self.direction);
        let rotation = move |phi: f64| ((phi - start) * direction).to_degrees();
        write_root_stress_csv(&sdir.join("root_stress.csv"), res, &rotation)?;
        write_pattern(
            &sdir,
            res,
            fp,
            sc.pinion_torque_nm.last().copied().unwrap_or(0.0),
        )?;
        // The bodies' statistics count this sweep's solves only (a body
        // held from another scene or blank pair has solved before).
        let used = |k: usize| bodies.member(k).filter(|_| swept.solved);
        let (dofs, factor_s) = body_stats(&cache_dir, used(0), used(1))?;
        let (pinion, wheel) = (used(0), used(1));
        let [(rhs0, s0), (rhs1, s1)] = swept.before;
        let cpu: f64 = res.iter().map(|r| r.cpu_s).sum();
        let n = res.len().max(1) as f64;
        let summary = BlankSummary {
            input_hash: hash,
            pinion_blank: blank_name(pb),
            wheel_blank: blank_name(wb),
            level: opt.level.clone(),
            penalty_factor: opt.settings.penalty_factor,
            penalty_factor_check: opt.settings.penalty_factor_check,
            positions: res.len(),
            step_deg: sc.rotation.step_deg * stride as f64,
            mesh_cycles: sc.rotation.mesh_cycles(wb),
            dofs,
            factor_s,
            right_hand_sides: [
                pinion.map_or(0, |m| m.compliance.solves - rhs0),
                wheel.map_or(0, |m| m.compliance.solves - rhs1),
            ],
            solve_s: [
                pinion.map_or(0.0, |m| m.compliance.solve_s - s0),
                wheel.map_or(0.0, |m| m.compliance.solve_s - s1),
            ],
            positions_reused: swept.reused,
            searched_mean: res.iter().map(|r| r.searched as f64).sum::<f64>() / n,
            constraints_mean: res.iter().map(|r| r.constraints as f64).sum::<f64>() / n,
            wall_s: t0.elapsed().as_secs_f64(),
            sweep_s: swept.sweep_s,
            total_cpu_s: cpu + factor_s.iter().sum::<f64>(),
            cpu_s_per_position: cpu / n,
            loads: load_summaries(
                res,
                &sc.pinion_torque_nm,
                [
                    opt.settings.penalty_factor,
                    opt.settings.penalty_factor_check,
                ],
                &rotation,
            ),
            unloaded: unloaded_check(res, &utca.te),
        };
        write_json(&sdir.join("summary.json"), &summary)?;
        print_summary(&summary);
        Ok(Some(summary))
    }
}

fn blank_name(b: Blank) -> String {
    b.name().to_string()
}
