//! The `preprocess mesh` stage: every member × blank × mesh level of a scene
//! into `meshes/<scene>/`: `.msh` (4.1), `.vtu` (meshio) and a report.

use crate::design::Member;
use crate::gear_body::BlankDimensions;
use crate::mesh::{mesh_member, MeshError, MeshReport, MeshRequest};
use crate::output::write_json;
use crate::pair::{opposite_teeth_in_contact, teeth_in_contact, PairGeometry};
use crate::scene::{Blank, FlankElements, LoadedScene};
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
pub fn convert_to_vtu(msh: &Path, vtu: &Path) -> Result<(), String> {
    let tmp = vtu.with_extension("tmp.vtu");
    let (py, script) = meshio_command();
    let out = std::process::Command::new(&py)
        .arg(&script)
        .arg(msh)
        .arg(&tmp)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", py.display()))?;
    if !out.status.success() {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!(
            "meshio conversion of {} failed: {}",
            msh.display(),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    std::fs::rename(&tmp, vtu).map_err(|e| format!("cannot rename {}: {e}", tmp.display()))
}

/// Teeth of `member` whose loaded flank the scene brings into contact: the
/// wheel blank sets the rotation range (the pinion takes the longest of the
/// scene's wheel blanks).
pub fn refined_teeth(
    g: &PairGeometry,
    sc: &crate::scene::Scene,
    member: Member,
    blank: Blank,
) -> Vec<usize> {
    refined_teeth_on(g, sc, member, blank, sc.loaded_flank)
}

/// The tooth whose flank the influence solves of an axisymmetric (standard)
/// blank load: the middle one of the refined teeth.
pub fn solved_tooth(refined: &[usize]) -> Option<usize> {
    refined.get(refined.len() / 2).copied()
}

/// Teeth meshed as periodic sectors (rotated copies of the solved tooth's
/// sector, [`crate::periodic_sectors`]): on a standard blank the solved tooth
/// first, then every other refined tooth whose opposite flank is refined
/// alike; none on a lightweight blank (its holes break the symmetry) or
/// with fewer than two such teeth.
pub fn periodic_teeth(blank: Blank, refined: &[usize], opposite: &[usize]) -> Vec<usize> {
    let Some(master) = solved_tooth(refined) else {
        return Vec::new();
    };
    if blank != Blank::Standard {
        return Vec::new();
    }
    let alike = |t: usize| opposite.contains(&t) == opposite.contains(&master);
    let mut out = vec![master];
    out.extend(refined.iter().copied().filter(|&t| t != master && alike(t)));
    if out.len() < 2 {
        out.clear();
    }
    out
}

/// Teeth whose opposite (coast) flank is refined: those the same rotation
/// brings into contact on that side, when the scene asks for coast-side
/// contact; none otherwise.
pub fn opposite_refined_teeth(
    g: &PairGeometry,
    sc: &crate::scene::Scene,
    member: Member,
    blank: Blank,
) -> Vec<usize> {
    if sc.multibody.coast_contact {
        refined_teeth_on(g, sc, member, blank, sc.loaded_flank.other())
    } else {
        Vec::new()
    }
}

/// Teeth of `member` whose `side` flank the scene's rotation brings into contact.
pub fn refined_teeth_on(
    g: &PairGeometry,
    sc: &crate::scene::Scene,
    member: Member,
    blank: Blank,
    side: crate::generation::Side,
) -> Vec<usize> {
    // A standard pinion's loads repeat from tooth to tooth: its range is the
    // loaded sweep's. A lightweight wheel needs every tooth a run-up meets.
    let cycles_of = |b: Blank| sc.rotation.mesh_cycles(b);
    let cycles = match member {
        Member::Wheel => sc.contact_mesh_cycles(blank, g.data.mesh_cycle()),
        Member::Pinion => sc
            .blanks
            .wheel
            .iter()
            .map(|&b| cycles_of(b))
            .fold(0.0, f64::max),
    };
    let step = sc.rotation.step_deg.to_radians();
    // The opposite flanks are numbered as the body's teeth over the loaded
    // side's sweep (both sides share the pinion angle).
    let (pt, wt) = if side == sc.loaded_flank {
        teeth_in_contact(g, side, cycles, step)
    } else {
        opposite_teeth_in_contact(g, sc.loaded_flank, cycles, step)
    };
    match member {
        Member::Pinion => pt,
        Member::Wheel => wt,
    }
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
    let levels: Vec<(&str, FlankElements)> = match level {
        Level::Reduced => vec![("reduced", sc.mesh.reduced_order)],
        Level::Reference => vec![("reference", sc.mesh.reference)],
        Level::Medium => vec![("medium", sc.mesh.medium())],
        Level::Both => vec![
            ("reduced", sc.mesh.reduced_order),
            ("reference", sc.mesh.reference),
        ],
    };
    let design_text = std::fs::read_to_string(&scene.design_path)?;
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
            for &(name, lv) in &levels {
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
                let stem = format!(
                    "{}_{}_{}",
                    member.name(),
                    format!("{blank:?}").to_lowercase(),
                    name
                );
                let msh = dir.join(format!("{stem}.msh"));
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
                    && vtu.exists();
                let cached = std::fs::read_to_string(&report_path)
                    .ok()
                    .and_then(|t| serde_json::from_str::<MeshReport>(&t).ok());
                if let (true, Some(r)) = (unchanged, cached) {
                    eprintln!("{stem}: inputs unchanged, reusing {}", msh.display());
                    reports.push(r);
                    continue;
                }
                let report = mesh_member(&req, &msh).map_err(|e: MeshError| anyhow::anyhow!(e))?;
                convert_to_vtu(&msh, &vtu).map_err(anyhow::Error::msg)?;
                write_json(&report_path, &report)?;
                write_json(&inputs_path, &inputs)?;
                reports.push(report);
            }
        }
    }
    Ok(reports)
}
