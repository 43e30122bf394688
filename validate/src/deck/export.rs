//! `validate export-inp`: the deck of one position written to
//! `<out>/<scene>/calculix/<stem>.inp`, and with `--run` solved by
//! CalculiX: `<stem>.dat` (its printed results) and `<stem>.json` (the
//! loaded TE per torque read from them). CalculiX works in a scratch
//! folder beside them, removed afterwards; each file is put in place whole.

use super::{build, ccx, inp, Deck, DeckContact, DeckOptions};
use formats::output::{write_atomic, write_json};
use geometry::scene::LoadedScene;
use serde::Serialize;
use sha2::Digest;
use std::path::{Path, PathBuf};

/// Layout version of `<stem>.json`.
pub const SOLUTION_SCHEMA: u32 = 1;

/// The loaded TE of one step, read from CalculiX's output.
#[derive(Debug, Clone, Serialize)]
pub struct CcxLoad {
    pub torque_nm: f64,
    /// (z₁/z₂) · d · u_z of the rotation node, µrad.
    pub te_urad: f64,
    /// The rotation node's moment about z (the applied torque, N·m).
    pub moment_nm: f64,
}

/// What a run of the deck gave.
#[derive(Debug, Clone, Serialize)]
pub struct CcxSolution {
    /// Layout version of this file ([`SOLUTION_SCHEMA`]).
    pub schema: u32,
    /// SHA-256 of the deck CalculiX solved (its header carries the mesh
    /// files' hashes).
    pub inp_sha256: String,
    pub scene: String,
    pub position: usize,
    pub pinion_angle_deg: f64,
    pub contact: String,
    pub penalty_slope_pa_per_m: f64,
    /// Step 1: the prescribed rotation (driving sense), µrad of wheel lag,
    /// and the moment it takes, N·m.
    pub start_te_urad: f64,
    pub start_moment_nm: f64,
    pub loads: Vec<CcxLoad>,
    /// CPU time of CalculiX (all its threads), s.
    pub cpu_s: f64,
}

/// The files of an export.
#[derive(Debug, Clone)]
pub struct Exported {
    pub inp: PathBuf,
    pub deck: Deck,
    pub solution: Option<CcxSolution>,
}

/// The file stem of a deck: `<pinion>_<wheel>_<level>_position<K>_<contact>`.
pub fn stem(opt: &DeckOptions) -> String {
    format!(
        "{}_{}_{}_position{}_{}",
        opt.pinion_blank.name(),
        opt.wheel_blank.name(),
        opt.level.name(),
        opt.position,
        opt.contact.name().replace('-', "_")
    )
}

/// Builds and writes the deck; with `run`, solves it with CalculiX
/// (`threads` solver threads) and writes what it gave.
pub fn export(
    scene: &LoadedScene,
    meshes: &Path,
    out: &Path,
    opt: &DeckOptions,
    run: bool,
    threads: usize,
) -> anyhow::Result<Exported> {
    let deck = build(scene, meshes, opt)?;
    let dir = out.join(&scene.scene.name).join("calculix");
    std::fs::create_dir_all(&dir)?;
    let stem = stem(opt);
    let text = inp::write(&deck);
    let inp_path = dir.join(format!("{stem}.inp"));
    write_atomic(&inp_path, text.as_bytes())?;
    let solution = if run {
        let scratch = dir.join(format!(".{stem}.ccx-{}", std::process::id()));
        std::fs::create_dir_all(&scratch)?;
        let _cleanup = Scratch {
            _registered: formats::interrupt::pending_dir(&scratch),
            dir: scratch.clone(),
        };
        std::fs::write(scratch.join("deck.inp"), text.as_bytes())?;
        let r = ccx::run(&scratch, "deck", threads)?;
        let sha = format!("{:x}", sha2::Sha256::digest(text.as_bytes()));
        let s = solution(&deck, &r, sha)?;
        write_atomic(&dir.join(format!("{stem}.dat")), &std::fs::read(&r.dat)?)?;
        write_json(&dir.join(format!("{stem}.json")), &s)?;
        Some(s)
    } else {
        None
    };
    Ok(Exported {
        inp: inp_path,
        deck,
        solution,
    })
}

/// Removes the scratch folder when dropped; a stopped run removes it
/// through its registration (after killing CalculiX).
struct Scratch {
    dir: PathBuf,
    _registered: formats::interrupt::Pending,
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The loaded TE of every step from a run of `deck`, whose text hashes to
/// `inp_sha256`.
pub fn solution(
    deck: &Deck,
    r: &ccx::CcxRun,
    inp_sha256: String,
) -> Result<CcxSolution, ccx::CcxError> {
    let u = |step| r.node_value("displacements", "NROT", step, 3);
    let m = |step| r.node_value("forces", "NROT", step, 3);
    let mut loads = Vec::new();
    if deck.contact != DeckContact::None {
        for (k, &t) in deck.torques_nm.iter().enumerate() {
            loads.push(CcxLoad {
                torque_nm: t,
                te_urad: deck.te_of_rotation(u(k + 2)?) * 1e6,
                moment_nm: m(k + 2)?,
            });
        }
    }
    Ok(CcxSolution {
        schema: SOLUTION_SCHEMA,
        inp_sha256,
        scene: deck.scene.clone(),
        position: deck.position,
        pinion_angle_deg: deck.phi.to_degrees(),
        contact: deck.contact.name().into(),
        penalty_slope_pa_per_m: deck.penalty_slope,
        start_te_urad: deck.te_of_rotation(u(1)?) * 1e6,
        start_moment_nm: m(1)?,
        loads,
        cpu_s: r.cpu_s,
    })
}
