//! The `preprocess stiffness` stage: FE influence fields of every member ×
//! blank of a scene at the reduced-order mesh level, written to
//! `meshes/<scene>/<member>_<blank>_<level>.stiffness.h5` and reused while
//! their inputs are unchanged.

use crate::body_mesh;
use crate::influence::{compute, FlankGrid, Influence, InfluenceRequest, InfluenceStats, Solves};
use crate::mesh_stage::Level;
use anyhow::Context;
use formats::manifest::{Manifest, StiffnessEntry};
use formats::output::write_json;
use formats::paths::{self, MeshLevel};
use formats::stiffness_file::{
    self, StiffnessConfig, StiffnessData, StiffnessFileError, STIFFNESS_SCHEMA,
};
use formats::stiffness_plan;
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// What one member × blank produced.
#[derive(Debug, Clone, Serialize)]
pub struct StiffnessReport {
    pub member: String,
    pub blank: String,
    pub level: String,
    pub path: PathBuf,
    pub reused: bool,
    /// Why an existing file was not reused, if one was there.
    pub replaced_because: Option<String>,
    pub input_hash: String,
    pub stats: Option<InfluenceStats>,
    pub total_s: f64,
}

/// Largest relative difference the stage accepts between an influence row
/// from the pruned solves' Gram products and from a backward solve
/// ([`InfluenceStats::backward_check`]); the two differ by rounding only
/// (1e-15 measured on the default scene's bodies).
pub const BACKWARD_CHECK_LIMIT: f64 = 1e-9;

/// SHA-256 of a file's bytes, hex.
pub fn sha256_file(path: &Path) -> anyhow::Result<String> {
    formats::manifest::sha256_file(path).with_context(|| format!("reading {}", path.display()))
}

/// Computes (or reuses) the stiffness files of the scene at the reduced level.
pub fn run(scene: &LoadedScene, root: &Path) -> anyhow::Result<Vec<StiffnessReport>> {
    run_level(scene, root, Level::Reduced)
}

/// As [`run`] on the meshes of another level (same contact grid): the
/// finer levels serve the mesh-convergence study of the influence fields.
pub fn run_level(
    scene: &LoadedScene,
    root: &Path,
    level: Level,
) -> anyhow::Result<Vec<StiffnessReport>> {
    if !scene.scene.analyses.needs_stiffness() {
        eprintln!(
            "scene {}: neither ltca nor multibody asked, no stiffness files; skipped",
            scene.scene.name
        );
        return Ok(Vec::new());
    }
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = root.join(&sc.name);
    let level = match level {
        Level::Reduced => MeshLevel::Reduced,
        Level::Medium => MeshLevel::Medium,
        Level::Reference => MeshLevel::Reference,
        Level::Both => {
            anyhow::bail!("stiffness files are made one mesh level at a time, not `both`")
        }
    };
    let mut out = Vec::new();
    for member in [Member::Pinion, Member::Wheel] {
        let blanks = match member {
            Member::Pinion => &sc.blanks.pinion,
            Member::Wheel => &sc.blanks.wheel,
        };
        for &blank in blanks {
            for side in stiffness_sides(sc) {
                out.push(run_one(scene, &g, &dir, member, blank, level, side)?);
            }
        }
    }
    Ok(out)
}

/// The flanks that get stiffness files: the loaded one, and the opposite
/// one when the scene asks for coast-side contact.
pub fn stiffness_sides(sc: &geometry::scene::Scene) -> Vec<Side> {
    if sc.multibody.coast_contact {
        vec![sc.loaded_flank, sc.loaded_flank.other()]
    } else {
        vec![sc.loaded_flank]
    }
}

/// Where a member × blank's stiffness file lives and what it must hold: the
/// producing configuration, its JSON and hash, the flank grid.
pub struct Planned {
    pub stem: String,
    pub msh: PathBuf,
    pub path: PathBuf,
    pub config: StiffnessConfig,
    pub config_json: String,
    pub hash: String,
    pub grid: FlankGrid,
}

/// The groups a stiffness file's `config` clamps, as [`compute`] takes them.
pub(crate) fn clamped_groups(config: &StiffnessConfig) -> Vec<&str> {
    config.clamped_groups.iter().map(String::as_str).collect()
}

/// The influence request that a stiffness file's `config` on grid `fg` asks
/// for, on `body`.
pub fn request<'a>(
    config: &'a StiffnessConfig,
    fg: &'a FlankGrid,
    body: &'a body_mesh::BodyMesh,
    g: &PairGeometry,
    member: Member,
    side: Side,
    block: usize,
) -> InfluenceRequest<'a> {
    let md = g.data.member(member);
    InfluenceRequest {
        body,
        material: crate::influence::fe_material(md.material()),
        teeth: md.teeth as usize,
        loaded: &config.loaded_flank,
        opposite: side.other().flank_name(member),
        grid: fg,
        solved_teeth: config.solved_teeth.clone(),
        offsets: config.offsets.clone(),
        load_radius: config.load_radius_m,
        fillet_rise: crate::influence::FILLET_RISE,
        block,
        solves: Solves::default(),
        root: None,
    }
}

/// The stiffness file of `member` × `blank` for loads on its `side` flank
/// that `scene` needs ([`formats::stiffness_plan::plan`]), its config
/// completed with the mesh's hashes and the local model (the mesh must
/// exist, since its SHA-256 is part of the hash).
pub fn planned(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
    side: Side,
) -> anyhow::Result<Planned> {
    let sc = &scene.scene;
    let plan = stiffness_plan::plan(scene, g, dir, member, blank, level, side)?;
    let msh = paths::msh(dir, &plan.mesh_stem);
    let inputs = dir.join(format!("{}.inputs.json", plan.mesh_stem));
    if !msh.exists() {
        if !sc.analyses.needs_mesh(level) {
            // `preprocess mesh --level <level>` skips this level for this
            // scene: pointing the user there would send them in a circle.
            anyhow::bail!(
                "scene {}: no mesh {} for the {} ({} blank): `preprocess mesh` makes {} meshes only for a scene whose [analyses] has reference = true, and this scene's has not; set it (the stiffness files of that level serve the influence-field convergence study) or use the reduced level",
                sc.name,
                msh.display(),
                member.name(),
                blank.name(),
                level.name()
            );
        }
        // The command writes where this run reads.
        let [out, _, missing_root] = stiffness_plan::mesh_root_advice(dir);
        anyhow::bail!(
            "scene {}: no mesh {} for the {} ({} blank){missing_root}; run `preprocess mesh {}{}{out}` first",
            sc.name,
            msh.display(),
            member.name(),
            blank.name(),
            scene.path.display(),
            level.option()
        );
    }
    let mesh_inputs: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(&inputs)
            .with_context(|| format!("reading {}", inputs.display()))?,
    )?;
    // The mesh must be the scene's current one, and intact: what the mesh
    // stage recorded for it in the manifest.
    let mesh_sha256 = sha256_file(&msh)?;
    let manifest = Manifest::read(dir)?;
    let entry = manifest.mesh(dir, &plan.mesh_stem)?;
    let design_text = geometry::design::geometry_text(
        &std::fs::read_to_string(&scene.design_path)
            .with_context(|| format!("reading {}", scene.design_path.display()))?,
    );
    let wanted = formats::manifest::MeshInputs::of_scene(
        scene,
        g,
        &design_text,
        member,
        blank,
        sc.mesh.elements(level),
    );
    let changed = entry.inputs.serves(&wanted);
    if !changed.is_empty() {
        anyhow::bail!(
            "scene {}: the mesh {} was made from other inputs ({}); run `preprocess mesh {}` first",
            sc.name,
            msh.display(),
            changed.join("; "),
            scene.path.display()
        );
    }
    if entry.msh_sha256 != mesh_sha256 {
        anyhow::bail!(
            "scene {}: {} changed since the mesh stage wrote it (SHA-256 {mesh_sha256}, the manifest lists {}); run `preprocess mesh {}` again",
            sc.name,
            msh.display(),
            entry.msh_sha256,
            scene.path.display()
        );
    }
    let config = StiffnessConfig {
        local_model: crate::influence::local_model(crate::influence::FILLET_RISE),
        mesh_inputs_hash: mesh_inputs["hash"].as_str().unwrap_or_default().to_string(),
        mesh_file_sha256: mesh_sha256,
        ..plan.config
    };
    let (config_json, hash) = config.json_and_hash();
    Ok(Planned {
        path: plan.path,
        stem: plan.stem,
        msh,
        config,
        config_json,
        hash,
        grid: plan.grid,
    })
}

/// The content of a stiffness file holding influence fields `inf` on grid
/// `fg`; the header strings (hash, config, member, blank, level) are left
/// empty for the caller to fill.
pub fn stiffness_data(
    fg: &FlankGrid,
    inf: Influence,
    teeth: usize,
    axisymmetric: bool,
) -> StiffnessData {
    StiffnessData {
        input_hash: String::new(),
        config: String::new(),
        member: String::new(),
        blank: String::new(),
        level: String::new(),
        teeth,
        axisymmetric,
        grid_profile: fg.size.profile,
        grid_face: fg.size.face,
        xi: fg.xi.clone(),
        eta: fg.eta.clone(),
        position: fg.position.iter().flatten().copied().collect(),
        normal: fg.normal.iter().flatten().copied().collect(),
        lever: fg.lever.clone(),
        solved_teeth: inf.solved_teeth.iter().map(|&k| k as u32).collect(),
        offsets: inf.offsets,
        depth_h: inf.depth.iter().flatten().copied().collect(),
        total: inf.total,
        local: inf.local,
        global: inf.global,
        root_stress: inf.root_stress,
    }
}

fn run_one(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
    side: Side,
) -> anyhow::Result<StiffnessReport> {
    let t0 = std::time::Instant::now();
    let sc = &scene.scene;
    let md = g.data.member(member);
    let st = &sc.stiffness;
    let blank_name = blank.name().to_string();
    let Planned {
        stem,
        msh,
        path,
        config,
        config_json,
        hash,
        grid: fg,
    } = planned(scene, g, dir, member, blank, level, side)?;
    let axisymmetric = config.axisymmetric;
    let mut replaced_because = None;
    // A file that no manifest lists, or lists with other bytes, is not
    // opened at all (a damaged HDF5 file can crash the HDF5 library
    // itself): it is replaced.
    let listed = Manifest::read(dir).ok().and_then(|m| {
        m.meshes
            .get(&paths::mesh_stem(member, blank, level))
            .and_then(|e| e.stiffness.get(&stem).map(|s| s.sha256.clone()))
    });
    let not_openable = path
        .exists()
        .then(|| formats::manifest::not_openable(&path, listed.as_deref()))
        .flatten();
    if let Some(why) = not_openable {
        eprintln!(
            "{stem}: {} is not opened ({why}); recomputing",
            path.display()
        );
        replaced_because = Some(why);
    } else if path.exists() {
        // A full read also catches truncated data, not only a stale header.
        let read = stiffness_file::read(&path, Some(&hash)).and_then(|d| {
            match formats::stiffness_sense::first_problem(&d) {
                None => Ok(d),
                Some(problem) => Err(StiffnessFileError::Hdf5 {
                    path: path.clone(),
                    message: problem,
                }),
            }
        });
        match read {
            Ok(d) => {
                eprintln!("{stem}: inputs unchanged, reusing {}", path.display());
                record(dir, level, member, blank, &stem, &hash, &d.solved_teeth)?;
                return Ok(reused_report(member, blank_name, level, path, hash, t0));
            }
            Err(StiffnessFileError::Schema { found, .. }) => {
                replaced_because = Some(format!("schema {found}, current {STIFFNESS_SCHEMA}"))
            }
            Err(StiffnessFileError::Hash { .. }) => {
                replaced_because = Some("made from other inputs (hash differs)".into())
            }
            Err(e) => replaced_because = Some(format!("unreadable: {e}")),
        }
        eprintln!(
            "{stem}: existing {} not used ({}), recomputing",
            path.display(),
            replaced_because.as_deref().unwrap_or("")
        );
    }
    let mesh_stem = paths::mesh_stem(member, blank, level);
    let root = dir.parent().unwrap_or(Path::new("."));
    if let Some(from) = crate::sibling_reuse::stiffness(root, dir, &mesh_stem, &stem, &hash) {
        if let Ok(d) = stiffness_file::read(&path, Some(&hash)) {
            eprintln!(
                "{stem}: same inputs as {}, copied",
                paths::stiffness_h5(&from, &stem).display()
            );
            record(dir, level, member, blank, &stem, &hash, &d.solved_teeth)?;
            return Ok(reused_report(member, blank_name, level, path, hash, t0));
        }
    }
    eprintln!("{stem}: reading {}", msh.display());
    let body = body_mesh::read(&msh).map_err(anyhow::Error::msg)?;
    formats::stop_point::at("reading");
    let mut req = request(&config, &fg, &body, g, member, side, st.solve_block);
    let root_asked = config.root_stress;
    // The fillets of every tooth whose root stress a loaded tooth's grid
    // loads reach.
    let mut root_teeth: Vec<usize> = req
        .solved_teeth
        .iter()
        .flat_map(|&k| {
            formats::stiffness_file::ROOT_STRESS_OFFSETS
                .into_iter()
                .filter(|o| req.offsets.contains(o))
                .map(move |o| (k as i64 + o as i64).rem_euclid(req.teeth as i64) as usize)
        })
        .collect();
    root_teeth.sort_unstable();
    root_teeth.dedup();
    let root = if root_asked {
        Some(
            crate::root_stress::RootStressPoints::new(
                &body,
                g,
                member,
                side,
                &root_teeth,
                req.material,
            )
            .with_context(|| format!("{stem}: root fillets of teeth {root_teeth:?}"))?,
        )
    } else {
        None
    };
    req.root = root.as_ref();
    eprintln!(
        "{stem}: {} nodes, {} tet10; unit loads on {} tooth(s) x {} grid points",
        body.mesh.nodes.len(),
        body.mesh.tets.len(),
        req.solved_teeth.len(),
        fg.len()
    );
    // Before assembling: a factor that cannot fit here is refused with the
    // estimate (the exact size follows from the symbolic analysis).
    formats::memory_estimate::check_fits(
        &format!("preprocess stiffness ({stem})"),
        &[(member.name(), 3 * body.mesh.nodes.len())],
        fem::cholesky::available_memory_bytes(),
    )?;
    let inf = compute(&req, &clamped_groups(&config)).with_context(|| {
        format!(
            "scene {}: influence fields of the {} ({blank_name} blank)",
            sc.name,
            member.name()
        )
    })?;
    if let Some(c) = inf.stats.backward_check {
        anyhow::ensure!(
            c <= BACKWARD_CHECK_LIMIT,
            "{stem}: the influence rows from the pruned solves differ from a backward solve by {c:.1e} (limit {BACKWARD_CHECK_LIMIT:.0e}); file not written"
        );
    }
    let stats = inf.stats.clone();
    let data = StiffnessData {
        input_hash: hash.clone(),
        config: config_json,
        member: member.name().into(),
        blank: blank_name.clone(),
        level: level.name().into(),
        ..stiffness_data(&fg, inf, md.teeth as usize, axisymmetric)
    };
    std::fs::create_dir_all(dir)?;
    stiffness_file::write(&path, &data)?;
    record(dir, level, member, blank, &stem, &hash, &data.solved_teeth)?;
    let report = StiffnessReport {
        member: member.name().into(),
        blank: blank_name,
        level: level.name().into(),
        path: path.clone(),
        reused: false,
        replaced_because,
        input_hash: hash,
        stats: Some(stats),
        total_s: t0.elapsed().as_secs_f64(),
    };
    write_json(&dir.join(format!("{stem}.stiffness.json")), &report)?;
    Ok(report)
}

/// The report of a stiffness file used as it is (this folder's, or a
/// sibling's copied).
fn reused_report(
    member: Member,
    blank: String,
    level: MeshLevel,
    path: PathBuf,
    input_hash: String,
    t0: std::time::Instant,
) -> StiffnessReport {
    StiffnessReport {
        member: member.name().into(),
        blank,
        level: level.name().into(),
        path,
        reused: true,
        replaced_because: None,
        input_hash,
        stats: None,
        total_s: t0.elapsed().as_secs_f64(),
    }
}

/// Lists the stiffness file `stem` (hash `hash`) under its mesh in the
/// folder's manifest.
fn record(
    dir: &Path,
    level: MeshLevel,
    member: Member,
    blank: Blank,
    stem: &str,
    hash: &str,
    solved: &[u32],
) -> anyhow::Result<()> {
    let path = paths::stiffness_h5(dir, stem);
    let entry = StiffnessEntry {
        file: format!("{stem}.stiffness.h5"),
        input_hash: hash.into(),
        sha256: sha256_file(&path)?,
        solved_teeth: solved.iter().map(|&t| t as usize).collect(),
    };
    let mesh_stem = paths::mesh_stem(member, blank, level);
    let mut missing = false;
    Manifest::update(dir, |m| match m.meshes.get_mut(&mesh_stem) {
        Some(e) => {
            e.stiffness.insert(stem.into(), entry);
        }
        None => missing = true,
    })?;
    if missing {
        anyhow::bail!(
            "{}: no entry for the mesh {mesh_stem}; run `preprocess mesh` on the scene",
            paths::manifest(dir).display()
        );
    }
    Ok(())
}

/// Rotational symmetry of a standard blank on its own mesh: the diagonal
/// C(p, p) of the loaded tooth when the stiffness file's solved tooth is
/// loaded and when each other periodic tooth of the standard blank is (the
/// same body, factored once): relative difference |C_b − C_a|/C_a per field,
/// the largest over teeth and grid points and the mean. The periodic teeth
/// are meshed as the solved tooth's sector turned, so this is what the
/// file's reuse by rotation ignores: the freely meshed rest of the body.
/// Without periodic teeth, the solved tooth's refined neighbour is compared.
#[derive(Debug, Clone, Serialize)]
pub struct ToothToTooth {
    pub member: String,
    pub level: String,
    /// The solved tooth first, then the teeth compared with it.
    pub teeth: Vec<usize>,
    pub total_max_abs: f64,
    pub total_mean_abs: f64,
    /// Tooth and grid point (face, profile index) of the largest total difference.
    pub total_worst: [usize; 3],
    pub global_max_abs: f64,
    pub global_mean_abs: f64,
    pub global_worst: [usize; 3],
}

/// The pair's geometry and the stiffness file of `member` × `blank` for
/// the scene's loaded flank on the meshes of `level` under `root/<scene>/`.
pub(crate) fn planned_under(
    scene: &LoadedScene,
    root: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
) -> anyhow::Result<(PairGeometry, Planned)> {
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dir = root.join(&scene.scene.name);
    let p = planned(
        scene,
        &g,
        &dir,
        member,
        blank,
        level,
        scene.scene.loaded_flank,
    )?;
    Ok((g, p))
}

/// [`ToothToTooth`] of `member`'s standard blank on the meshes of `level`
/// under `root/<scene>/`.
pub fn tooth_to_tooth(
    scene: &LoadedScene,
    root: &Path,
    member: Member,
    level: MeshLevel,
) -> anyhow::Result<ToothToTooth> {
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    let (g, p) = planned_under(scene, root, member, Blank::Standard, level)?;
    let refined = geometry::teeth::refined_teeth_on(&g, sc, member, Blank::Standard, side);
    let opposite = geometry::teeth::opposite_refined_teeth(&g, sc, member, Blank::Standard);
    let a = p.config.solved_teeth[0];
    let z = g.data.member(member).teeth as usize;
    let mut teeth = geometry::teeth::periodic_teeth(Blank::Standard, &refined, &opposite);
    if teeth.len() < 2 {
        let b = [(a + 1) % z, (a + z - 1) % z]
            .into_iter()
            .find(|t| refined.contains(t))
            .with_context(|| {
                format!("no refined neighbour of tooth {a} on the {}", member.name())
            })?;
        teeth = vec![a, b];
    }
    anyhow::ensure!(
        teeth[0] == a,
        "the {}'s periodic teeth {teeth:?} do not start with the solved tooth {a}",
        member.name()
    );
    let body = body_mesh::read(&p.msh).map_err(anyhow::Error::msg)?;
    let req = InfluenceRequest {
        solved_teeth: teeth.clone(),
        offsets: vec![0],
        ..request(
            &p.config,
            &p.grid,
            &body,
            &g,
            member,
            side,
            sc.stiffness.solve_block,
        )
    };
    let inf = compute(&req, &clamped_groups(&p.config))?;
    let np = p.grid.len();
    let npf = p.grid.size.profile;
    let change = |f: &[f64]| {
        let (mut worst, mut at, mut sum) = (0.0f64, [0; 3], 0.0);
        for (s, &tooth) in teeth.iter().enumerate().skip(1) {
            for i in 0..np {
                let (ca, cb) = (f[i * np + i], f[s * np * np + i * np + i]);
                let r = ((cb - ca) / ca).abs();
                sum += r;
                if r > worst {
                    (worst, at) = (r, [tooth, i / npf, i % npf]);
                }
            }
        }
        (worst, sum / ((teeth.len() - 1) * np) as f64, at)
    };
    let (tm, ta, tw) = change(&inf.total);
    let (gm, ga, gw) = change(&inf.global);
    Ok(ToothToTooth {
        member: member.name().into(),
        level: level.name().into(),
        teeth: teeth.clone(),
        total_max_abs: tm,
        total_mean_abs: ta,
        total_worst: tw,
        global_max_abs: gm,
        global_mean_abs: ga,
        global_worst: gw,
    })
}
