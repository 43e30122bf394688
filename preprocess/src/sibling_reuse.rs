//! Reuse of another scene's files in the same mesh root: meshes and
//! stiffness files are keyed by scene name (`meshes/<scene>/`), but their
//! inputs hashes do not contain it (a scene that meshes the same design,
//! blank, level and refined teeth as another gets a byte-identical `.msh`,
//! and the same stiffness file from it). When a stage would compute a file
//! that a sibling folder already holds from the same inputs, it copies the
//! sibling's instead (each file atomically), after the same checks it
//! would make on its own: the inputs hash, and the sibling manifest's
//! SHA-256 of the file.

use formats::manifest::{sha256_file, Manifest, MeshEntry};
use std::path::{Path, PathBuf};

/// Other scene folders of `root` than `own`, sorted (deterministic choice).
fn siblings(root: &Path, own: &Path) -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map(|r| {
            r.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.is_dir() && p != own)
                .collect()
        })
        .unwrap_or_default();
    dirs.sort();
    dirs
}

/// Copies `names` from `from` into `to`, each atomically, the last one
/// last (the file whose presence says the set is complete).
fn copy_all(from: &Path, to: &Path, names: &[String]) -> anyhow::Result<()> {
    std::fs::create_dir_all(to)?;
    for n in names {
        let bytes = std::fs::read(from.join(n))?;
        formats::output::write_atomic(&to.join(n), &bytes)?;
    }
    Ok(())
}

/// A sibling folder whose mesh `stem` serves (`accept` on the text of its
/// `<stem>.inputs.json` and its manifest entry: the same inputs, or a mesh
/// refined on more teeth) and whose `.msh` is the one its manifest lists:
/// its `.msh`, `.vtu`, `.report.json` and `.inputs.json` are copied into
/// `dir`. Returns the folder copied from and its manifest entry.
pub fn mesh(
    root: &Path,
    dir: &Path,
    stem: &str,
    accept: impl Fn(&str, &MeshEntry) -> bool,
) -> Option<(PathBuf, MeshEntry)> {
    for other in siblings(root, dir) {
        let Some(entry) = Manifest::read(&other)
            .ok()
            .and_then(|m| m.meshes.get(stem).cloned())
        else {
            continue;
        };
        let accepted = std::fs::read_to_string(other.join(format!("{stem}.inputs.json")))
            .is_ok_and(|t| accept(&t, &entry));
        if !accepted {
            continue;
        }
        let msh = formats::paths::msh(&other, stem);
        let intact = sha256_file(&msh).is_ok_and(|x| x == entry.msh_sha256);
        let names: Vec<String> = ["msh", "vtu", "report.json", "inputs.json"]
            .iter()
            .map(|e| format!("{stem}.{e}"))
            .collect();
        if !intact || !names.iter().all(|n| other.join(n).is_file()) {
            continue;
        }
        if copy_all(&other, dir, &names).is_ok() {
            return Some((other, entry));
        }
    }
    None
}

/// A sibling folder whose stiffness file `stem` (mesh `mesh_stem`) its
/// manifest lists with inputs hash `hash` and whose bytes match the listed
/// SHA-256: the `.stiffness.h5` and `.stiffness.json` are copied into
/// `dir`. Returns the folder copied from.
pub fn stiffness(
    root: &Path,
    dir: &Path,
    mesh_stem: &str,
    stem: &str,
    hash: &str,
) -> Option<PathBuf> {
    for other in siblings(root, dir) {
        let Some(entry) = Manifest::read(&other).ok().and_then(|m| {
            m.meshes
                .get(mesh_stem)
                .and_then(|e| e.stiffness.get(stem).cloned())
        }) else {
            continue;
        };
        let h5 = formats::paths::stiffness_h5(&other, stem);
        if entry.input_hash != hash || !sha256_file(&h5).is_ok_and(|x| x == entry.sha256) {
            continue;
        }
        let names = vec![
            format!("{stem}.stiffness.json"),
            format!("{stem}.stiffness.h5"),
        ];
        if !names.iter().all(|n| other.join(n).is_file()) {
            continue;
        }
        if copy_all(&other, dir, &names).is_ok() {
            return Some(other);
        }
    }
    None
}
