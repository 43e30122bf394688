//! The `preprocess mesh` stage: every member × blank × mesh level of a scene
//! into `meshes/<scene>/`: `.msh` (4.1), `.vtu` (meshio) and a report.

use crate::mesh::{mesh_member, MeshError, MeshReport, MeshRequest};
use formats::manifest::{BodyProperties, Manifest, MeshEntry, MeshInputs};
use formats::output::write_json;
use formats::paths::{self, MeshLevel};
use geometry::design::Member;
use geometry::gear_body::BlankDimensions;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::teeth::{opposite_refined_teeth, periodic_teeth, refined_teeth};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// Bumped whenever the meshing changes what it produces for the same input.
pub const MESH_SCHEMA: u32 = 10;

/// What `<stem>.inputs.json` records: the hash of everything that determines a mesh.
#[derive(Debug, Serialize, Deserialize, PartialEq)]
struct Inputs {
    schema: u32,
    hash: String,
}

fn input_hash(design_text: &str, dims: &BlankDimensions, req: &MeshRequest) -> String {
    let mut h = Sha256::new();
    h.update(MESH_SCHEMA.to_le_bytes());
    h.update(design_text.as_bytes());
    h.update(serde_json::to_string(dims).unwrap_or_default().as_bytes());
    h.update(
        format!(
            "{:?}{:?}{:?}{:?}{:?}",
            req.member, req.blank, req.level, req.side, req.refined_teeth
        )
        .as_bytes(),
    );
    // Only when present, so that meshes of loaded-side-only scenes keep their hashes.
    if !req.opposite_refined_teeth.is_empty() {
        h.update(format!("opposite{:?}", req.opposite_refined_teeth).as_bytes());
    }
    if !req.periodic_teeth.is_empty() {
        h.update(format!("periodic{:?}", req.periodic_teeth).as_bytes());
    }
    format!("{:x}", h.finalize())
}

/// Which mesh levels to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Level {
    Reduced,
    Reference,
    Both,
    /// Between reduced and reference (mesh-convergence studies).
    Medium,
}

/// The project's Python (venv with meshio; override with `PROJECT_PYTHON`)
/// and its conversion script.
pub fn meshio_command() -> (PathBuf, PathBuf) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let py = std::env::var_os("PROJECT_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join(".venv/bin/python"));
    (py, root.join("scripts/msh_to_vtu.py"))
}

/// Converts a .msh into a .vtu with meshio, atomically.
pub fn convert_to_vtu(msh: &Path, vtu: &Path) -> anyhow::Result<()> {
    let (py, script) = meshio_command();
    formats::output::write_via(vtu, |tmp| {
        // Killed if the run is stopped, so that it cannot write `tmp`
        // again once the handler has removed it.
        let out = formats::interrupt::output(
            std::process::Command::new(&py)
                .arg(&script)
                .arg(msh)
                .arg(tmp),
        )
        .map_err(|e| anyhow::anyhow!("cannot run {}: {e}", py.display()))?;
        if !out.status.success() {
            anyhow::bail!(
                "meshio conversion of {} failed: {}",
                msh.display(),
                String::from_utf8_lossy(&out.stderr)
            );
        }
        Ok(())
    })
}

/// Meshes every member × blank × level of the scene into `root/<scene>/`.
pub fn run(
    scene: &LoadedScene,
    root: &Path,
    level: Level,
) -> Result<Vec<MeshReport>, anyhow::Error> {
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let dims = BlankDimensions::resolve(&sc.blank_dimensions, &g.data);
    let dir = root.join(&sc.name);
    let levels: Vec<MeshLevel> = match level {
        Level::Reduced => vec![MeshLevel::Reduced],
        Level::Reference => vec![MeshLevel::Reference],
        Level::Medium => vec![MeshLevel::Medium],
        Level::Both => vec![MeshLevel::Reduced, MeshLevel::Reference],
    };
    // Only the levels an analysis of the scene needs (`[analyses]`).
    let (levels, unasked): (Vec<MeshLevel>, Vec<MeshLevel>) =
        levels.into_iter().partition(|&l| sc.analyses.needs_mesh(l));
    for l in unasked {
        eprintln!(
            "scene {}: no analysis needs {} meshes; skipped",
            sc.name,
            l.name()
        );
    }
    // An output that cannot hold the meshes is refused before any CAD or
    // meshing work (a minute at the finer levels).
    if !levels.is_empty() {
        std::fs::create_dir_all(&dir).map_err(|e| {
            anyhow::anyhow!(
                "scene {}: cannot create the mesh folder {} (`--out`): {e}",
                sc.name,
                dir.display()
            )
        })?;
    }
    // The geometry's text: a `[published]` table does not change a mesh.
    let design_text =
        geometry::design::geometry_text(&std::fs::read_to_string(&scene.design_path)?);
    let mut reports = Vec::new();
    for member in [Member::Pinion, Member::Wheel] {
        let blanks = match member {
            Member::Pinion => &sc.blanks.pinion,
            Member::Wheel => &sc.blanks.wheel,
        };
        for &blank in blanks {
            let refined = refined_teeth(&g, sc, member, blank);
            let opposite = opposite_refined_teeth(&g, sc, member, blank);
            let periodic = periodic_teeth(blank, &refined, &opposite);
            for &level in &levels {
                let (name, lv) = (level.name(), sc.mesh.elements(level));
                let req = MeshRequest {
                    scene: &sc.name,
                    geom: &g,
                    member,
                    blank,
                    dims: &dims,
                    level: lv,
                    level_name: name,
                    side: sc.loaded_flank,
                    refined_teeth: refined.clone(),
                    opposite_refined_teeth: opposite.clone(),
                    periodic_teeth: periodic.clone(),
                };
                let stem = paths::mesh_stem(member, blank, level);
                let msh = paths::msh(&dir, &stem);
                let vtu = dir.join(format!("{stem}.vtu"));
                let report_path = dir.join(format!("{stem}.report.json"));
                let inputs_path = dir.join(format!("{stem}.inputs.json"));
                let inputs = Inputs {
                    schema: MESH_SCHEMA,
                    hash: input_hash(&design_text, &dims, &req),
                };
                let unchanged = std::fs::read_to_string(&inputs_path)
                    .ok()
                    .and_then(|t| serde_json::from_str::<Inputs>(&t).ok())
                    .is_some_and(|i| i == inputs)
                    && msh.exists()
                    && vtu.exists()
                    && mesh_intact(&dir, &stem);
                let cached = cached_report(&report_path);
                let wanted = MeshInputs::of_scene(scene, &g, &design_text, member, blank, lv);
                // Lists the mesh in the manifest with the inputs it was made
                // from (the scene's, or a mesh's refined on more teeth).
                let record = |entry: MeshInputs, hash: &str| {
                    record_mesh(&dir, &stem, member, blank, level, entry, hash, &g)
                };
                if let (true, Some(mut r)) = (unchanged, cached) {
                    eprintln!("{stem}: inputs unchanged, reusing {}", msh.display());
                    record(wanted.clone(), &inputs.hash)?;
                    r.reused = true;
                    reports.push(r);
                    continue;
                }
                // A mesh of this folder refined on more teeth than the
                // scene asks for serves it as it is (its manifest entry
                // keeps its own inputs).
                let serves = |t: &str, e: &MeshEntry| {
                    serde_json::from_str::<Inputs>(t)
                        .is_ok_and(|i| i.schema == MESH_SCHEMA && i.hash == e.inputs_hash)
                        && e.inputs.serves(&wanted).is_empty()
                };
                let own_entry = Manifest::read(&dir)
                    .ok()
                    .and_then(|m| m.meshes.get(&stem).cloned());
                let own_serves = own_entry.as_ref().is_some_and(|e| {
                    std::fs::read_to_string(&inputs_path).is_ok_and(|t| serves(&t, e))
                }) && msh.exists()
                    && vtu.exists()
                    && mesh_intact(&dir, &stem);
                if let (true, Some(mut r)) = (own_serves, cached_report(&report_path)) {
                    eprintln!(
                        "{stem}: refined on more teeth than the scene asks for, reusing {}",
                        msh.display()
                    );
                    r.reused = true;
                    reports.push(r);
                    continue;
                }
                // A sibling's mesh: the same inputs first, else one
                // refined on more teeth.
                let same_inputs = |t: &str, _: &MeshEntry| {
                    serde_json::from_str::<Inputs>(t).is_ok_and(|i| i == inputs)
                };
                let copied = crate::sibling_reuse::mesh(root, &dir, &stem, same_inputs)
                    .map(|(from, _)| (from, None))
                    .or_else(|| {
                        crate::sibling_reuse::mesh(root, &dir, &stem, serves)
                            .map(|(from, e)| (from, Some(e)))
                    });
                if let Some((from, superset)) = copied {
                    if let Some(mut r) = cached_report(&report_path) {
                        let how = match superset {
                            None => "same inputs as",
                            Some(_) => "refined on more teeth than the scene asks for:",
                        };
                        eprintln!(
                            "{stem}: {how} {}, copied",
                            paths::msh(&from, &stem).display()
                        );
                        r.scene = sc.name.clone();
                        write_json(&report_path, &r)?;
                        match superset {
                            None => record(wanted.clone(), &inputs.hash)?,
                            Some(e) => record(e.inputs, &e.inputs_hash)?,
                        }
                        r.reused = true;
                        reports.push(r);
                        continue;
                    }
                }
                let report = mesh_member(&req, &msh).map_err(|e: MeshError| anyhow::anyhow!(e))?;
                convert_to_vtu(&msh, &vtu)?;
                write_json(&report_path, &report)?;
                write_json(&inputs_path, &inputs)?;
                record(wanted.clone(), &inputs.hash)?;
                reports.push(report);
            }
        }
    }
    Ok(reports)
}

/// The mesh report at `path`, if readable.
fn cached_report(path: &Path) -> Option<MeshReport> {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<MeshReport>(&t).ok())
}

/// Writes the manifest entry of the mesh `stem` (its inputs, the hash of
/// its `.msh`, its mass properties integrated over the mesh), unless the
/// manifest already holds one from the same inputs and file.
#[allow(clippy::too_many_arguments)]
fn record_mesh(
    dir: &Path,
    stem: &str,
    member: Member,
    blank: Blank,
    level: MeshLevel,
    inputs: MeshInputs,
    inputs_hash: &str,
    g: &PairGeometry,
) -> anyhow::Result<()> {
    let msh = paths::msh(dir, stem);
    let msh_sha256 = formats::manifest::sha256_file(&msh)
        .map_err(|e| anyhow::anyhow!("reading {}: {e}", msh.display()))?;
    let current = Manifest::read(dir)
        .ok()
        .and_then(|m| m.meshes.get(stem).cloned());
    let same = current.as_ref().is_some_and(|e| {
        e.inputs_hash == inputs_hash && e.msh_sha256 == msh_sha256 && e.inputs == inputs
    });
    if same && current.as_ref().is_some_and(|e| e.body.nodes > 0) {
        return Ok(());
    }
    let body = crate::body_mesh::read(&msh)
        .map_err(|e| anyhow::anyhow!("reading {}: {e}", msh.display()))?;
    if same {
        // An entry from before node counts were recorded: add the count,
        // keep the stiffness files listed on this very mesh.
        let nodes = body.mesh.nodes.len();
        Manifest::update(dir, |m| {
            if let Some(e) = m.meshes.get_mut(stem) {
                e.body.nodes = nodes;
            }
        })?;
        return Ok(());
    }
    let density = g.data.member(member).density;
    let entry = MeshEntry {
        member,
        blank,
        level,
        inputs,
        inputs_hash: inputs_hash.into(),
        msh_sha256,
        body: BodyProperties {
            volume_m3: body.mesh.volume(),
            density_kg_m3: density,
            polar_moment_kgm2: body.mesh.polar_moment(density),
            nodes: body.mesh.nodes.len(),
        },
        stiffness: Default::default(),
    };
    Manifest::update(dir, |m| {
        m.meshes.insert(stem.into(), entry);
    })?;
    Ok(())
}

/// Whether the `.msh` of `stem` is the file the mesh stage wrote: its
/// SHA-256 equals the manifest's (a truncated or replaced mesh is not
/// reused). A mesh the manifest does not list yet (made before manifests
/// existed) counts as intact and is listed when reused.
pub fn mesh_intact(dir: &Path, stem: &str) -> bool {
    let Some(entry) = Manifest::read(dir)
        .ok()
        .and_then(|m| m.meshes.get(stem).cloned())
    else {
        return true;
    };
    let intact =
        formats::manifest::sha256_file(&paths::msh(dir, stem)).is_ok_and(|h| h == entry.msh_sha256);
    if !intact {
        eprintln!("{stem}: the mesh file is not the one the manifest lists (changed or damaged); meshing again");
    }
    intact
}
