//! `validate convergence <scene>`: mesh convergence of the reference LTCA.
//! The TE at one position and at each torque on three mesh levels (standard
//! blanks; one set of unit-load columns serves every torque), the observed
//! order of convergence and the Richardson extrapolation per torque, how
//! far each level lies from it, and the reduced model's quasi-static LTCA
//! at the same position against the extrapolated TE. Written to
//! `<out>/<scene>/reference/convergence.json`; each level's result is kept
//! under `convergence/` with the hash of its meshes and settings and reused.
//! The study holds a shared lock on the reference folder while it runs (no
//! sweep replaces the folder meanwhile) and records every file it writes
//! there with its checksum ([`formats::added_files`]); a level result is
//! reused only when it is listed there unchanged and its hash matches.

use crate::reference::reference_ltca::{Member, ReferencePair, ReferenceSettings};
use crate::reference::reference_options::REFERENCE_SCHEMA;
use anyhow::Context;
use formats::added_files::{add_json, read_added, AddedState, Dependence};
use formats::result_set::RunLock;
use geometry::design::Member as Which;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene, MeshLevel};
use preprocess::stiffness_stage::sha256_file;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::Path;

/// One mesh level's result.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LevelResult {
    pub level: String,
    /// Elements along the active profile × face width requested.
    pub profile_elements: u32,
    pub face_elements: u32,
    /// Relative element size 1/√(profile · face).
    pub h: f64,
    pub dofs: [usize; 2],
    pub constraints: usize,
    /// TE per torque of the study, µrad.
    pub te_urad: Vec<f64>,
    /// The unloaded check at this level: TE at the vanishing torque against
    /// the UTCA of the generated flanks at the same position, µrad.
    #[serde(default)]
    pub unloaded_te_urad: f64,
    #[serde(default)]
    pub utca_te_urad: f64,
    /// |TE − TE at the check penalty| / TE per torque, %.
    pub penalty_difference_pct: Vec<f64>,
    /// TE per torque at the check penalty factor, µrad (empty in results
    /// cached before it was recorded).
    #[serde(default)]
    pub te_check_urad: Vec<f64>,
    /// Bytes of the pinion's and the wheel's whole Cholesky factor (8 per
    /// value), and what [`formats::memory_estimate::factor`] expected
    /// before factoring (0 in results cached before they were recorded).
    #[serde(default)]
    pub factor_bytes: [usize; 2],
    #[serde(default)]
    pub estimated_factor_bytes: [f64; 2],
    pub factor_s: [f64; 2],
    pub position_s: f64,
    pub input_hash: String,
    /// SHA-256 of the pinion and wheel meshes it was computed on (empty in
    /// files written before they were recorded: treated as stale).
    #[serde(default)]
    pub mesh_sha256: [String; 2],
}

/// The study at one torque.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TorqueConvergence {
    pub torque_nm: f64,
    /// Observed order p of TE(h) = TE∞ + c hᵖ from the three levels (None
    /// when the differences change sign, or p < [`MIN_ORDER`]).
    pub observed_order: Option<f64>,
    pub extrapolated_te_urad: Option<f64>,
    /// (TE(level) − TE∞) / TE∞ per level, %.
    pub error_to_extrapolation_pct: Vec<Option<f64>>,
    /// The reduced model's quasi-static LTCA at the same position (the
    /// scene's slices and stiffness files, standard blanks), µrad.
    pub reduced_model_te_urad: f64,
    /// (reduced model − TE∞) / TE∞, %.
    pub reduced_model_error_pct: Option<f64>,
    /// (reduced model − TE on the finest level) / that TE, %.
    pub reduced_model_vs_finest_pct: f64,
}

/// Smallest observed order taken as convergence: below it the three levels
/// differ by nearly equal steps (not yet in the asymptotic range) and the
/// extrapolation would run off (order 0.09 at 100 N·m put TE∞ 25 % above
/// the finest level).
pub const MIN_ORDER: f64 = 0.5;

/// The study.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Convergence {
    pub pinion_rotation_deg: f64,
    pub levels: Vec<LevelResult>,
    pub torques: Vec<TorqueConvergence>,
}

impl Convergence {
    /// Levels whose meshes under `scene_meshes` (`meshes/<scene>/`) are not
    /// the ones the study was computed on (changed, missing, or not recorded).
    pub fn stale_levels(&self, scene_meshes: &Path) -> Vec<String> {
        self.levels
            .iter()
            .filter(|l| {
                let now = [Which::Pinion, Which::Wheel].map(|m| {
                    let stem = formats::paths::stem_named(m, Blank::Standard, &l.level);
                    sha256_file(&formats::paths::msh(scene_meshes, &stem)).unwrap_or_default()
                });
                now != l.mesh_sha256 || now.iter().any(|h| h.is_empty())
            })
            .map(|l| l.level.clone())
            .collect()
    }
}

/// Observed order and extrapolated value from three levels, coarse to fine
/// (h₁ > h₂ > h₃), for f(h) = f∞ + c hᵖ:
/// (f₁ − f₂)/(f₂ − f₃) = (h₁ᵖ − h₂ᵖ)/(h₂ᵖ − h₃ᵖ) is solved for p in
/// [0.05, 20] by bisection (the right side grows monotonically with p), and
/// f∞ = f₃ − (f₂ − f₃) h₃ᵖ/(h₂ᵖ − h₃ᵖ). None when the differences change
/// sign or no p in the range fits.
pub fn richardson(h: [f64; 3], f: [f64; 3]) -> Option<(f64, f64)> {
    let (d1, d2) = (f[0] - f[1], f[1] - f[2]);
    if d1 == 0.0 || d2 == 0.0 || d1.signum() != d2.signum() {
        return None;
    }
    let target = d1 / d2;
    let ratio = |p: f64| (h[0].powf(p) - h[1].powf(p)) / (h[1].powf(p) - h[2].powf(p));
    let (mut lo, mut hi) = (0.05, 20.0);
    if !(ratio(lo) <= target && target <= ratio(hi)) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let p = 0.5 * (lo + hi);
    let inf = f[2] - d2 * h[2].powf(p) / (h[1].powf(p) - h[2].powf(p));
    Some((p, inf))
}

/// What the study solves.
#[derive(Debug, Clone)]
pub struct Study {
    /// Mesh levels: reduced, medium, reference.
    pub levels: Vec<String>,
    /// Position index in the scene's sweep (its rotation steps).
    pub position: usize,
    pub torques_nm: Vec<f64>,
    pub settings: ReferenceSettings,
    /// Right-hand sides per solve block.
    pub block: usize,
}

/// One position of the scene's sweep (standard blanks), as the studies on
/// one position solve it.
pub struct StudyPosition {
    pub g: PairGeometry,
    pub side: Side,
    /// Pinion's driving direction (±1).
    pub direction: f64,
    /// The sweep's step, rad.
    pub step: f64,
    /// Position index in the sweep and its pinion angle, rad.
    pub index: usize,
    pub phi: f64,
    /// Teeth of the pinion and the wheel that the sweep brings into contact.
    pub teeth: [Vec<usize>; 2],
    /// The UTCA TE of the generated flanks at this position, µrad.
    pub utca_te_urad: f64,
}

impl StudyPosition {
    /// Position `index` of `scene`'s sweep.
    pub fn new(scene: &LoadedScene, index: usize) -> anyhow::Result<StudyPosition> {
        let sc = &scene.scene;
        let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
        let side = sc.loaded_flank;
        let fp = g.side(side);
        let direction = pinion_direction(&g.data, side);
        let step = sc.rotation.step_deg.to_radians();
        let cycles = sc.rotation.mesh_cycles(Blank::Standard);
        // The sweep's positions, as `validate reference` counts them.
        let n_pos = (cycles * g.data.mesh_cycle() / step).round() as usize + 1;
        if index >= n_pos {
            anyhow::bail!(
                "--position {index}: scene {}'s sweep (standard blanks) has {n_pos} positions, 0 to {} ({} mesh cycles every {}°)",
                sc.name,
                n_pos - 1,
                cycles,
                sc.rotation.step_deg
            );
        }
        let phi = fp.roll_range[0] + direction * step * index as f64;
        let (pinion_teeth, wheel_teeth) = teeth_in_contact(&g, side, cycles, step);
        let utca_te_urad =
            crate::reference::reference_options::utca_at(scene, fp, phi, step, 1, direction)?.te[0]
                * 1e6;
        Ok(StudyPosition {
            g,
            side,
            direction,
            step,
            index,
            phi,
            teeth: [pinion_teeth, wheel_teeth],
            utca_te_urad,
        })
    }
}

/// How one level's FE reference at a [`StudyPosition`] is solved and kept.
pub struct LevelSolve<'a> {
    pub scene: &'a LoadedScene,
    pub meshes: &'a Path,
    pub position: &'a StudyPosition,
    /// Torques, N·m, increasing.
    pub torques_nm: &'a [f64],
    pub settings: ReferenceSettings,
    /// Right-hand sides per solve block.
    pub block: usize,
    /// Memory the two factors may take together, bytes (None: what the
    /// system has available); refused before factoring above it.
    pub memory_bytes: Option<usize>,
    /// The study's shared lock on the scene's reference folder, and the
    /// folder under it that keeps the level results (`<cache>/<level>.json`).
    pub lock: &'a RunLock,
    pub cache: &'a str,
}

impl LevelSolve<'_> {
    /// The FE reference on `level`'s meshes at the position and torques:
    /// reused from `<cache>/<level>.json` when its inputs hash and meshes
    /// match, otherwise solved (after the factor-memory check) and kept.
    pub fn level_result(&self, level: &str) -> anyhow::Result<LevelResult> {
        let scene = self.scene;
        let sc = &scene.scene;
        let pos = self.position;
        let g = &pos.g;
        let Some(lv) = MeshLevel::from_name(level) else {
            anyhow::bail!("--levels: unknown level {level} (reduced, medium, reference)");
        };
        let elements = match lv {
            MeshLevel::Reduced => sc.mesh.reduced_order,
            MeshLevel::Medium => sc.mesh.medium(),
            MeshLevel::Reference => sc.mesh.reference,
        };
        let scene_meshes = self.meshes.join(&sc.name);
        let msh = |m: Which| {
            let stem = formats::paths::stem_named(m, Blank::Standard, level);
            formats::paths::msh(&scene_meshes, &stem)
        };
        let (pm, wm) = (msh(Which::Pinion), msh(Which::Wheel));
        for p in [&pm, &wm] {
            if !p.exists() {
                anyhow::bail!(
                    "scene {}: no mesh {}; run `preprocess mesh {} --level {level}`",
                    sc.name,
                    p.display(),
                    scene.path.display()
                );
            }
        }
        let mesh_sha256 = [sha256_file(&pm)?, sha256_file(&wm)?];
        let key = serde_json::json!({
            "schema": REFERENCE_SCHEMA,
            "pinion_mesh": mesh_sha256[0],
            "wheel_mesh": mesh_sha256[1],
            "settings": self.settings,
            "phi": pos.phi,
            "torques_nm": self.torques_nm,
            "flank": pos.side.flank_name(Which::Pinion),
        });
        let hash = format!("{:x}", Sha256::digest(key.to_string().as_bytes()));
        let rel = format!("{}/{level}.json", self.cache);
        if let Some(r) = self.kept_result(level, &rel, &hash, &mesh_sha256)? {
            return Ok(r);
        }
        let estimated_factor_bytes = self.factors_fit(level, lv, &scene_meshes)?;
        eprintln!(
            "{} {level}: reading and factoring {} and {}",
            self.cache,
            pm.display(),
            wm.display()
        );
        let [pinion_teeth, wheel_teeth] = &pos.teeth;
        let mut pinion = Member::load(&pm, g, Which::Pinion, pos.side, pinion_teeth, self.block)?;
        let mut wheel = Member::load(&wm, g, Which::Wheel, pos.side, wheel_teeth, self.block)?;
        let mut pair = ReferencePair {
            pinion: &mut pinion,
            wheel: &mut wheel,
            flanks: g.side(pos.side),
            direction: pos.direction,
            settings: self.settings,
        };
        let r = pair
            .position(pos.phi, self.torques_nm)
            .with_context(|| format!("scene {}: FE reference at level {level}", sc.name))?;
        let res = LevelResult {
            level: level.to_string(),
            profile_elements: elements.profile,
            face_elements: elements.face,
            h: 1.0 / (elements.profile as f64 * elements.face as f64).sqrt(),
            dofs: [pinion.compliance.dofs_free, wheel.compliance.dofs_free],
            constraints: r.constraints,
            te_urad: r.loads.iter().map(|l| l.te * 1e6).collect(),
            unloaded_te_urad: r.unloaded_te * 1e6,
            utca_te_urad: pos.utca_te_urad,
            penalty_difference_pct: r
                .loads
                .iter()
                .map(|l| ((l.te - l.te_check) / l.te).abs() * 100.0)
                .collect(),
            te_check_urad: r.loads.iter().map(|l| l.te_check * 1e6).collect(),
            factor_bytes: [
                8 * pinion.compliance.factor_nnz[1],
                8 * wheel.compliance.factor_nnz[1],
            ],
            estimated_factor_bytes,
            factor_s: [pinion.compliance.factor_s, wheel.compliance.factor_s],
            position_s: r.cpu_s,
            input_hash: hash,
            mesh_sha256,
        };
        eprintln!(
            "{} {level}: TE {:.3?} µrad at {:?} N·m, unloaded {:.4} µrad (UTCA {:.4}) ({} + {} dofs, {} constraints, factors {:.2} + {:.2} GB in {:.0} + {:.0} s, position {:.0} s)",
            self.cache,
            res.te_urad,
            self.torques_nm,
            res.unloaded_te_urad,
            res.utca_te_urad,
            res.dofs[0],
            res.dofs[1],
            res.constraints,
            res.factor_bytes[0] as f64 / 1e9,
            res.factor_bytes[1] as f64 / 1e9,
            res.factor_s[0],
            res.factor_s[1],
            res.position_s
        );
        add_json(self.lock, &rel, &res, Dependence::Beside)?;
        Ok(res)
    }

    /// The level result kept at `rel` under the lock's folder, when it is
    /// current and was computed from `hash` and the meshes `mesh_sha256`;
    /// why it is not reused otherwise, on stderr.
    fn kept_result(
        &self,
        level: &str,
        rel: &str,
        hash: &str,
        mesh_sha256: &[String; 2],
    ) -> anyhow::Result<Option<LevelResult>> {
        let dir = self.lock.dir();
        match read_added(dir, rel)? {
            AddedState::Current(bytes) => {
                if let Some(r) = serde_json::from_slice::<LevelResult>(&bytes)
                    .ok()
                    .filter(|r| r.input_hash == hash && r.mesh_sha256 == *mesh_sha256)
                {
                    eprintln!(
                        "{} {level}: inputs unchanged, reusing {}",
                        self.cache,
                        dir.join(rel).display()
                    );
                    return Ok(Some(r));
                }
            }
            AddedState::Missing => {}
            other => eprintln!(
                "{} {level}: not reusing {}: {}",
                self.cache,
                dir.join(rel).display(),
                other.why_not().unwrap_or_default()
            ),
        }
        Ok(None)
    }

    /// The factors held at once, estimated from the meshes' node counts
    /// before any factoring, refused above the memory allowed; returns the
    /// estimated factor bytes of pinion and wheel.
    fn factors_fit(
        &self,
        level: &str,
        lv: MeshLevel,
        scene_meshes: &Path,
    ) -> anyhow::Result<[f64; 2]> {
        let scene = self.scene;
        let sc = &scene.scene;
        let g = &self.position.g;
        let dofs = [Which::Pinion, Which::Wheel].map(|m| {
            let stem = formats::paths::mesh_stem(m, Blank::Standard, lv);
            formats::stiffness_plan::check_mesh(
                scene,
                g,
                scene_meshes,
                &stem,
                m,
                Blank::Standard,
                lv,
            )
            .map(|e| 3 * e.body.nodes)
        });
        let dofs = [dofs[0].as_ref(), dofs[1].as_ref()].map(|d| d.map_or(0, |&d| d));
        let estimated_factor_bytes = dofs.map(|d| formats::memory_estimate::factor(d).bytes);
        formats::memory_estimate::check_fits(
            &format!("scene {}: the FE reference at level {level}", sc.name),
            &[("pinion", dofs[0]), ("wheel", dofs[1])],
            self.memory_bytes
                .or_else(fem::cholesky::available_memory_bytes),
        )?;
        Ok(estimated_factor_bytes)
    }
}

/// Runs the study (standard blanks).
pub fn run(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    study: &Study,
) -> anyhow::Result<Convergence> {
    let Study {
        levels,
        position: index,
        torques_nm,
        settings,
        block,
    } = study.clone();
    let sc = &scene.scene;
    let pos = StudyPosition::new(scene, index)?;
    let dir = out.join(&sc.name).join("reference");
    let lock = RunLock::shared(&dir, &format!("validate convergence {}", sc.name))?;
    let solve = LevelSolve {
        scene,
        meshes,
        position: &pos,
        torques_nm: &torques_nm,
        settings,
        block,
        memory_bytes: None,
        lock: &lock,
        cache: "convergence",
    };
    let mut results = Vec::new();
    for level in &levels {
        results.push(solve.level_result(level)?);
    }
    results.sort_by(|a, b| b.h.total_cmp(&a.h));
    let reduced = reduced_model_te(
        scene,
        meshes,
        &pos.g,
        pos.phi,
        pos.step,
        pos.direction,
        &torques_nm,
    )?;
    let torques = torques_nm
        .iter()
        .enumerate()
        .map(|(i, &torque_nm)| {
            let fit = (results.len() == 3)
                .then(|| {
                    richardson(
                        [results[0].h, results[1].h, results[2].h],
                        [0, 1, 2].map(|k| results[k].te_urad[i]),
                    )
                })
                .flatten()
                .filter(|&(p, _)| p >= MIN_ORDER);
            let error = |te: f64| fit.map(|(_, inf)| (te - inf) / inf * 100.0);
            let finest = results.last().map_or(f64::NAN, |r| r.te_urad[i]);
            TorqueConvergence {
                torque_nm,
                observed_order: fit.map(|f| f.0),
                extrapolated_te_urad: fit.map(|f| f.1),
                error_to_extrapolation_pct: results.iter().map(|r| error(r.te_urad[i])).collect(),
                reduced_model_te_urad: reduced[i],
                reduced_model_error_pct: error(reduced[i]),
                reduced_model_vs_finest_pct: (reduced[i] - finest) / finest * 100.0,
            }
        })
        .collect();
    let c = Convergence {
        pinion_rotation_deg: (pos.step * index as f64).to_degrees(),
        levels: results,
        torques,
    };
    add_json(&lock, "convergence.json", &c, Dependence::Beside)?;
    Ok(c)
}

/// The reduced model's quasi-static TE (µrad) at pinion angle `phi`, per
/// torque: the scene's stiffness files for standard blanks and its slice
/// count, frictionless like the reference.
fn reduced_model_te(
    scene: &LoadedScene,
    meshes: &Path,
    g: &PairGeometry,
    phi: f64,
    step: f64,
    direction: f64,
    torques_nm: &[f64],
) -> anyhow::Result<Vec<f64>> {
    let sc = &scene.scene;
    let fp = g.side(sc.loaded_flank);
    let rs = geometry::utca::roll_surface(fp, &sc.utca)?;
    let dir = meshes.join(&sc.name);
    let pc = solver::stage::context::LoadedPair::load(scene, g, &dir, [Blank::Standard; 2])?.pc;
    let sweep = solver::ltca::Sweep {
        start: phi,
        step,
        direction,
        positions: 1,
        slices: sc.ltca.slices,
        friction: 0.0,
    };
    let r = solver::ltca::run(fp, &rs, &pc, &sweep, torques_nm)
        .context("reduced model at the convergence study's position")?;
    Ok(r[0].loads.iter().map(|l| l.te * 1e6).collect())
}

#[cfg(test)]
mod tests {
    use super::richardson;

    /// f = 1 + 0.5 h² on unequal refinement ratios: order 2 and f∞ = 1.
    #[test]
    fn richardson_recovers_a_known_quadratic() {
        let h = [0.0645, 0.0358, 0.0195];
        let f = h.map(|x| 1.0 + 0.5 * x * x);
        let (p, inf) = richardson(h, f).unwrap();
        assert!((p - 2.0).abs() < 1e-9, "order {p}");
        assert!((inf - 1.0).abs() < 1e-12, "limit {inf}");
    }

    /// Differences of opposite sign: no monotone convergence, no estimate.
    #[test]
    fn richardson_refuses_oscillating_values() {
        assert!(richardson([0.3, 0.2, 0.1], [1.0, 1.2, 1.1]).is_none());
    }

    /// A study is shown only on the meshes it was computed on.
    #[test]
    fn convergence_on_changed_or_missing_meshes_is_stale() {
        use super::{Convergence, LevelResult};
        let dir = std::env::temp_dir().join(format!("conv-stale-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let write = |m: &str, text: &str| {
            std::fs::write(dir.join(format!("{m}_standard_reduced.msh")), text).unwrap()
        };
        write("pinion", "p");
        write("wheel", "w");
        let sha = |m: &str| {
            preprocess::stiffness_stage::sha256_file(&dir.join(format!("{m}_standard_reduced.msh")))
                .unwrap()
        };
        let level = LevelResult {
            level: "reduced".into(),
            profile_elements: 12,
            face_elements: 20,
            h: 0.06,
            dofs: [1, 1],
            constraints: 1,
            te_urad: vec![1.0],
            unloaded_te_urad: 0.0,
            utca_te_urad: 0.0,
            penalty_difference_pct: vec![0.0],
            te_check_urad: vec![1.0],
            factor_bytes: [0; 2],
            estimated_factor_bytes: [0.0; 2],
            factor_s: [0.0; 2],
            position_s: 0.0,
            input_hash: String::new(),
            mesh_sha256: [sha("pinion"), sha("wheel")],
        };
        let mut c = Convergence {
            pinion_rotation_deg: 0.0,
            levels: vec![level],
            torques: Vec::new(),
        };
        assert!(c.stale_levels(&dir).is_empty());
        write("wheel", "w2");
        assert_eq!(c.stale_levels(&dir), vec!["reduced".to_string()]);
        c.levels[0].mesh_sha256[1] = sha("wheel");
        assert!(c.stale_levels(&dir).is_empty());
        std::fs::remove_file(dir.join("pinion_standard_reduced.msh")).unwrap();
        assert_eq!(c.stale_levels(&dir).len(), 1);
        c.levels[0].mesh_sha256 = Default::default();
        assert_eq!(c.stale_levels(&dir).len(), 1, "unrecorded hashes are stale");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
