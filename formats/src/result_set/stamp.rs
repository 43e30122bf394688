//! A committed set's stamp (`run.json`): reading it, comparing the inputs
//! of sets put side by side, checking the files against their checksums,
//! and the stamp of a file added in place to a committed set.

use super::{utc, MixedInputs, ResultSetError, RunInfo, RunLock, RUN_FILE};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

/// The committed set's stamp in `dir` (`<dir>/run.json`), `None` when
/// `dir` holds no committed set.
pub fn read_run_info(dir: &Path) -> Result<Option<RunInfo>, ResultSetError> {
    let path = dir.join(RUN_FILE);
    match std::fs::read_to_string(&path) {
        Ok(text) => {
            serde_json::from_str(&text)
                .map(Some)
                .map_err(|e| ResultSetError::UnreadableStamp {
                    path: path.clone(),
                    message: e.to_string(),
                })
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(ResultSetError::UnreadableStamp {
            path,
            message: e.to_string(),
        }),
    }
}

/// Checks that the committed sets in `dirs` (those that exist) read the
/// same files wherever they name the same input: a report that puts an
/// LTCA, a multibody run and a reference side by side must not compare
/// runs made from different designs, meshes or stiffness files. Sets
/// without a stamp, or stamped before inputs were recorded, are passed.
pub fn check_same_inputs(dirs: &[&Path]) -> Result<(), ResultSetError> {
    let mut seen: Vec<(PathBuf, RunInfo)> = Vec::new();
    for dir in dirs {
        if let Some(info) = read_run_info(dir)? {
            for (other, o) in &seen {
                for (key, sha) in &info.inputs {
                    if let Some(osha) = o.inputs.get(key) {
                        if osha != sha {
                            return Err(ResultSetError::MixedInputs(Box::new(MixedInputs {
                                key: key.clone(),
                                a: other.clone(),
                                a_run: o.run_id.clone(),
                                a_what: o.what.clone(),
                                a_sha: osha.clone(),
                                b: dir.to_path_buf(),
                                b_run: info.run_id.clone(),
                                b_what: info.what.clone(),
                                b_sha: sha.clone(),
                            })));
                        }
                    }
                }
            }
            seen.push((dir.to_path_buf(), info));
        }
    }
    Ok(())
}

/// SHA-256 of every file under `root`, by path relative to it
/// (`/`-separated), `run.json` left out.
pub(super) fn file_hashes(root: &Path) -> std::io::Result<BTreeMap<String, String>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d)? {
            let p = e?.path();
            if p.is_dir() {
                stack.push(p);
            } else if p != root.join(RUN_FILE) {
                out.insert(set_key(root, &p), crate::manifest::sha256_file(&p)?);
            }
        }
    }
    Ok(out)
}

/// The key of `path` in the `files` of the set at `root`: its path relative
/// to it, `/`-separated.
fn set_key(root: &Path, path: &Path) -> String {
    path.strip_prefix(root)
        .unwrap_or(path)
        .components()
        .map(|c| c.as_os_str().to_string_lossy())
        .collect::<Vec<_>>()
        .join("/")
}

/// `file` of the set in `dir` (stamped `info`) has the bytes `sha` its run
/// wrote, else why not.
fn check_listed(dir: &Path, file: &Path, sha: &str, info: &RunInfo) -> Result<(), ResultSetError> {
    let why = match crate::manifest::sha256_file(file) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "removed".to_string(),
        Err(e) => format!("unreadable ({e})"),
        Ok(now) if now != sha => "changed".to_string(),
        Ok(_) => return Ok(()),
    };
    Err(ResultSetError::Tampered {
        dir: dir.to_path_buf(),
        file: file.to_path_buf(),
        run: info.run_id.clone(),
        why,
    })
}

/// Checks that every file the committed set in `dir` lists is there with
/// the bytes its run wrote; returns the set's stamp (`None` when `dir`
/// does not exist). A folder with files but no stamp is refused
/// ([`ResultSetError::Unstamped`]): every stage commits its set with one,
/// so a missing stamp means the set cannot be vouched for.
pub fn verify_files(dir: &Path) -> Result<Option<RunInfo>, ResultSetError> {
    let Some(info) = read_run_info(dir)? else {
        let holds_files = std::fs::read_dir(dir)
            .map(|mut r| r.next().is_some())
            .unwrap_or(false);
        if holds_files {
            return Err(ResultSetError::Unstamped {
                dir: dir.to_path_buf(),
            });
        }
        return Ok(None);
    };
    for (rel, sha) in &info.files {
        check_listed(dir, &dir.join(rel), sha, &info)?;
    }
    Ok(Some(info))
}

/// Checks one file before a reader uses it alone (a figure copied into a
/// report): the nearest enclosing folder with a stamp is its set; a file
/// that set lists must have the bytes its run wrote. A file the set does
/// not list (added in place later, see [`AddedStamp`]) passes with the
/// set's stamp; a missing file passes with `None` (the reader says what is
/// missing); a file with no stamped folder above it is refused
/// ([`ResultSetError::Unstamped`], naming its folder).
pub fn verify_file(path: &Path) -> Result<Option<RunInfo>, ResultSetError> {
    if !path.is_file() {
        return Ok(None);
    }
    for dir in path.ancestors().skip(1) {
        let Some(info) = read_run_info(dir)? else {
            continue;
        };
        if let Some(sha) = info.files.get(&set_key(dir, path)) {
            check_listed(dir, path, sha, &info)?;
        }
        return Ok(Some(info));
    }
    Err(ResultSetError::Unstamped {
        dir: path.parent().unwrap_or(path).to_path_buf(),
    })
}

/// The stamp of a file that a later run adds in place to a committed set
/// without replacing the set (`validate reference --compare-cache`): the
/// set it was computed from (`of_run_id`, that set's `run.json` id; `None`
/// when the directory held no committed set) and the run that wrote it.
/// A reader checks [`AddedStamp::belongs_to`] before trusting the file
/// beside the set: once a new run replaces the set, the file is stale.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct AddedStamp {
    pub of_run_id: Option<String>,
    pub written_utc: String,
    pub command: String,
    pub pid: u32,
    pub host: String,
}

impl AddedStamp {
    /// Stamps a file added under `lock` (held on the set's directory)
    /// to the set committed there now.
    pub fn new(lock: &RunLock) -> Result<AddedStamp, ResultSetError> {
        Ok(AddedStamp {
            of_run_id: read_run_info(lock.dir())?.map(|r| r.run_id),
            written_utc: utc(SystemTime::now()),
            command: lock.holder.command.clone(),
            pid: std::process::id(),
            host: lock.holder.host.clone(),
        })
    }

    /// Whether the set committed in `dir` now is the one this file was
    /// computed from.
    pub fn belongs_to(&self, dir: &Path) -> Result<bool, ResultSetError> {
        Ok(read_run_info(dir)?.map(|r| r.run_id) == self.of_run_id)
    }
}
