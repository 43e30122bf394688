//! Files that a later command adds in place to a committed result set
//! (the studies kept beside the reference sweep: `validate convergence`,
//! `line-load`, `tradeoff`, `reference --compare-cache`), with their
//! checksums in the set's registry `<dir>/added.json`.
//!
//! A committed set lists the files its own run wrote in `run.json`
//! ([`crate::result_set::verify_files`]); a file added afterwards is not
//! among them. [`add_file`] writes it atomically under a lock held on the
//! set's directory (shared or exclusive, so that no run swaps the set out
//! meanwhile) and records its SHA-256 and an [`AddedStamp`] (which set it
//! was added to, by whom) in the registry. [`read_added`] is the readers'
//! check: the file must be listed, unchanged since it was written, and,
//! where it was computed from the set's own results
//! ([`Dependence::OnSet`]), added to the set committed there now.
//!
//! The registry is itself rewritten atomically, under a short lock of its
//! own (`<dir>/added.lock`), since several shared holders may add files
//! side by side. A set committed anew carries the registry over with the
//! added files (the reference sweep carries over whatever it did not
//! write), so a file computed from the old set reads as
//! [`AddedState::OtherSet`].

use crate::result_set::{AddedStamp, ResultSetError, RunLock};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The registry of added files inside a set's directory.
pub const ADDED_FILE: &str = "added.json";

/// How long [`add_file`] waits for another writer of the registry.
const REGISTRY_WAIT: Duration = Duration::from_secs(30);

/// Whether an added file was computed from the set's own results.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Dependence {
    /// Computed from the set's results (e.g. the slice trade-off, which
    /// compares with the sweep's TE): stale once the set is replaced.
    OnSet,
    /// Kept beside the set only (e.g. the mesh convergence study, which
    /// checks its own inputs): valid whatever set is committed there.
    Beside,
}

/// One added file's registry entry.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct AddedRecord {
    pub sha256: String,
    pub dependence: Dependence,
    pub stamp: AddedStamp,
}

/// What [`read_added`] found.
#[derive(Debug, Clone, PartialEq)]
pub enum AddedState {
    /// No such file.
    Missing,
    /// The file exists but the registry does not list it (written by an
    /// older version, or by hand).
    Unlisted,
    /// Its bytes differ from those recorded when it was written.
    Changed,
    /// Computed from a set other than the one committed there now.
    OtherSet {
        of_run_id: Option<String>,
        now_run_id: Option<String>,
    },
    /// Listed, unchanged, and (where it depends on it) of the current set.
    Current(Vec<u8>),
}

impl AddedState {
    /// Why the file cannot be used, for a report line; `None` when current.
    pub fn why_not(&self) -> Option<String> {
        match self {
            AddedState::Current(_) => None,
            AddedState::Missing => Some("missing".into()),
            AddedState::Unlisted => Some(format!(
                "not listed in {ADDED_FILE} (written by an older version or by hand)"
            )),
            AddedState::Changed => Some("changed since it was written (checksum)".into()),
            AddedState::OtherSet {
                of_run_id,
                now_run_id,
            } => Some(format!(
                "computed from run {} of the results beside it, which run {} has replaced",
                of_run_id.as_deref().unwrap_or("(none)"),
                now_run_id.as_deref().unwrap_or("(none)")
            )),
        }
    }
}

fn registry_path(dir: &Path) -> PathBuf {
    dir.join(ADDED_FILE)
}

/// The registry of `dir` (empty when there is none).
pub fn registry(dir: &Path) -> Result<BTreeMap<String, AddedRecord>, ResultSetError> {
    let path = registry_path(dir);
    match std::fs::read_to_string(&path) {
        Ok(text) => serde_json::from_str(&text).map_err(|e| ResultSetError::UnreadableStamp {
            path,
            message: e.to_string(),
        }),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(BTreeMap::new()),
        Err(e) => Err(ResultSetError::UnreadableStamp {
            path,
            message: e.to_string(),
        }),
    }
}

/// The registry's own lock, waited for up to [`REGISTRY_WAIT`].
fn registry_lock(dir: &Path, what: &str) -> Result<RunLock, ResultSetError> {
    let start = Instant::now();
    loop {
        match RunLock::exclusive(&dir.join("added"), what) {
            Err(ResultSetError::Busy { .. }) if start.elapsed() < REGISTRY_WAIT => {
                std::thread::sleep(Duration::from_millis(50))
            }
            other => return other,
        }
    }
}

/// Writes `bytes` to `<dir>/<rel>` (`rel` `/`-separated, inside `dir`)
/// atomically and records it in the registry of `dir`. `lock` must be held
/// on `dir` (shared or exclusive).
pub fn add_file(
    lock: &RunLock,
    rel: &str,
    bytes: &[u8],
    dependence: Dependence,
) -> Result<(), ResultSetError> {
    let dir = lock.dir();
    if rel.is_empty()
        || rel == ADDED_FILE
        || Path::new(rel)
            .components()
            .any(|c| !matches!(c, std::path::Component::Normal(_)))
    {
        return Err(ResultSetError::Unwritable {
            path: dir.join(rel),
            message: format!(
                "an added file must be a relative path inside {} other than {ADDED_FILE}",
                dir.display()
            ),
        });
    }
    let stamp = AddedStamp::new(lock)?;
    let _registry = registry_lock(dir, &lock.holder().what)?;
    crate::output::write_atomic(&dir.join(rel), bytes)?;
    let mut reg = registry(dir)?;
    reg.insert(
        rel.to_string(),
        AddedRecord {
            sha256: crate::manifest::sha256_bytes(bytes),
            dependence,
            stamp,
        },
    );
    crate::output::write_json(&registry_path(dir), &reg)?;
    Ok(())
}

/// [`add_file`] of `value` as pretty JSON.
pub fn add_json<T: Serialize>(
    lock: &RunLock,
    rel: &str,
    value: &T,
    dependence: Dependence,
) -> Result<(), ResultSetError> {
    let text = serde_json::to_string_pretty(value).map_err(|e| ResultSetError::Unwritable {
        path: lock.dir().join(rel),
        message: e.to_string(),
    })?;
    add_file(lock, rel, text.as_bytes(), dependence)
}

/// The readers' check of `<dir>/<rel>`: see [`AddedState`].
pub fn read_added(dir: &Path, rel: &str) -> Result<AddedState, ResultSetError> {
    let path = dir.join(rel);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(AddedState::Missing),
        Err(e) => {
            return Err(ResultSetError::UnreadableStamp {
                path,
                message: e.to_string(),
            })
        }
    };
    let Some(rec) = registry(dir)?.remove(rel) else {
        return Ok(AddedState::Unlisted);
    };
    if crate::manifest::sha256_bytes(&bytes) != rec.sha256 {
        return Ok(AddedState::Changed);
    }
    if rec.dependence == Dependence::OnSet && !rec.stamp.belongs_to(dir)? {
        return Ok(AddedState::OtherSet {
            of_run_id: rec.stamp.of_run_id,
            now_run_id: crate::result_set::read_run_info(dir)?.map(|r| r.run_id),
        });
    }
    Ok(AddedState::Current(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::result_set::ResultSet;

    fn committed_set(root: &Path) -> PathBuf {
        let dir = root.join("reference");
        let set = ResultSet::begin(&dir, "test set").unwrap();
        std::fs::write(set.path().join("summary.json"), "[]").unwrap();
        set.commit().unwrap();
        dir
    }

    #[test]
    fn added_file_reads_current_until_changed() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        let lock = RunLock::shared(&dir, "study").unwrap();
        add_file(&lock, "study.json", b"{\"a\": 1}", Dependence::Beside).unwrap();
        drop(lock);
        assert_eq!(
            read_added(&dir, "study.json").unwrap(),
            AddedState::Current(b"{\"a\": 1}".to_vec())
        );
        std::fs::write(dir.join("study.json"), b"{\"a\": 2}").unwrap();
        assert_eq!(read_added(&dir, "study.json").unwrap(), AddedState::Changed);
        std::fs::remove_file(dir.join("study.json")).unwrap();
        assert_eq!(read_added(&dir, "study.json").unwrap(), AddedState::Missing);
    }

    #[test]
    fn unlisted_file_is_not_trusted() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        std::fs::write(dir.join("old_study.json"), b"{}").unwrap();
        let s = read_added(&dir, "old_study.json").unwrap();
        assert_eq!(s, AddedState::Unlisted);
        assert!(s.why_not().unwrap().contains("not listed"));
    }

    #[test]
    fn file_computed_from_a_replaced_set_reads_other_set() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        let lock = RunLock::shared(&dir, "study").unwrap();
        add_file(&lock, "on_set.json", b"1", Dependence::OnSet).unwrap();
        add_file(&lock, "beside.json", b"2", Dependence::Beside).unwrap();
        drop(lock);
        assert!(matches!(
            read_added(&dir, "on_set.json").unwrap(),
            AddedState::Current(_)
        ));
        // A new run replaces the set and carries the added files over, as
        // the reference sweep does.
        let mut set = ResultSet::begin(&dir, "test set again").unwrap();
        std::fs::write(set.path().join("summary.json"), "[1]").unwrap();
        for n in ["on_set.json", "beside.json", ADDED_FILE] {
            set.carry_over(Path::new(n));
        }
        set.commit().unwrap();
        let s = read_added(&dir, "on_set.json").unwrap();
        assert!(matches!(s, AddedState::OtherSet { .. }), "{s:?}");
        assert!(s.why_not().unwrap().contains("replaced"));
        assert!(matches!(
            read_added(&dir, "beside.json").unwrap(),
            AddedState::Current(_)
        ));
    }

    #[test]
    fn added_file_outside_the_set_is_refused() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        let lock = RunLock::shared(&dir, "study").unwrap();
        for rel in ["../escape.json", "/abs.json", "", ADDED_FILE] {
            let e = add_file(&lock, rel, b"x", Dependence::Beside).unwrap_err();
            assert!(e.to_string().contains("relative path inside"), "{rel}: {e}");
        }
        assert!(!root.path().join("escape.json").exists());
    }

    #[test]
    fn adding_beside_an_exclusive_run_is_refused() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        // A reference sweep holding the set (in this process: a holder that
        // is alive).
        let _sweep = RunLock::exclusive(&dir, "validate reference").unwrap();
        let e = RunLock::shared(&dir, "study").unwrap_err();
        assert!(matches!(e, ResultSetError::Busy { .. }), "{e}");
    }

    #[test]
    fn side_by_side_additions_keep_both_records() {
        let root = tempfile::tempdir().unwrap();
        let dir = committed_set(root.path());
        std::thread::scope(|s| {
            for k in 0..4 {
                let dir = &dir;
                s.spawn(move || {
                    let lock = RunLock::shared(dir, "study").unwrap();
                    for i in 0..5 {
                        let rel = format!("s{k}_{i}.json");
                        add_file(&lock, &rel, rel.as_bytes(), Dependence::Beside).unwrap();
                    }
                });
            }
        });
        let reg = registry(&dir).unwrap();
        assert_eq!(reg.len(), 20);
        for rel in reg.keys() {
            assert!(matches!(
                read_added(&dir, rel).unwrap(),
                AddedState::Current(_)
            ));
        }
    }
}
