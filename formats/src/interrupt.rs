//! What an interrupted run (Ctrl-C, SIGTERM, SIGHUP) leaves behind: nothing
//! unfinished.
//!
//! A stage registers what it has begun and not finished: a result set's
//! staging directory ([`crate::result_set::ResultSet`]), its lock files
//! ([`crate::result_set::RunLock`]), the temporary file of a writer
//! ([`crate::output::write_via`]). Each registration is a [`Pending`]
//! guard that takes itself back when dropped (the work finished or failed
//! normally). [`install`], called once by each binary, sets a handler that
//! on a termination signal removes what is still registered, says so, and
//! exits with 130: the previous results stay in place, the lock is free,
//! and the next run starts with no warnings about a dead run.
//!
//! A result set's commit (renames) holds [`critical`] so that the handler
//! waits until the set is either wholly in place or not at all.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, Once};

/// One thing to undo if the run is stopped.
#[derive(Debug, Clone)]
enum Undo {
    /// A directory to remove whole.
    Dir(PathBuf),
    /// A file to remove.
    File(PathBuf),
    /// A lock file to remove if it still holds `token` (this run's).
    Lock { path: PathBuf, token: String },
}

static PENDING: Mutex<BTreeMap<u64, Undo>> = Mutex::new(BTreeMap::new());
static NEXT: AtomicU64 = AtomicU64::new(0);
static INSTALL: Once = Once::new();

fn pending() -> MutexGuard<'static, BTreeMap<u64, Undo>> {
    // A panic while the map was held leaves it consistent (inserts and
    // removes are single operations).
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// A registration; dropping it takes it back.
#[derive(Debug)]
pub struct Pending(u64);

impl Drop for Pending {
    fn drop(&mut self) {
        pending().remove(&self.0);
    }
}

fn register(u: Undo) -> Pending {
    let id = NEXT.fetch_add(1, Ordering::Relaxed);
    pending().insert(id, u);
    Pending(id)
}

/// Registers a directory to remove if the run is stopped.
pub fn pending_dir(path: &Path) -> Pending {
    register(Undo::Dir(path.to_path_buf()))
}

/// Registers a file to remove if the run is stopped.
pub fn pending_file(path: &Path) -> Pending {
    register(Undo::File(path.to_path_buf()))
}

/// Registers a lock file to release if the run is stopped: removed only
/// while its content still carries `token`.
pub fn pending_lock(path: &Path, token: &str) -> Pending {
    register(Undo::Lock {
        path: path.to_path_buf(),
        token: token.to_string(),
    })
}

/// Holds the handler off while it lives ([`critical`]).
pub struct Critical(#[allow(dead_code)] MutexGuard<'static, BTreeMap<u64, Undo>>);

/// Holds the handler off while the guard lives: for a sequence of renames
/// that must complete or not start. No [`Pending`] may be made or dropped
/// meanwhile (it would wait for the guard).
pub fn critical() -> Critical {
    Critical(pending())
}

/// Undoes everything registered (what the handler does before exiting);
/// returns what it removed. Public so that tests can run it without a
/// signal.
pub fn undo_all() -> Vec<PathBuf> {
    let mut map = pending();
    let mut removed = Vec::new();
    // Newest first: a set's files before its directory, locks last.
    for (_, u) in std::mem::take(&mut *map).into_iter().rev() {
        match u {
            Undo::Dir(p) => {
                if std::fs::remove_dir_all(&p).is_ok() {
                    removed.push(p);
                }
            }
            Undo::File(p) => {
                if std::fs::remove_file(&p).is_ok() {
                    removed.push(p);
                }
            }
            Undo::Lock { path, token } => {
                let ours = std::fs::read_to_string(&path).is_ok_and(|t| t.contains(&token));
                if ours && std::fs::remove_file(&path).is_ok() {
                    removed.push(path);
                }
            }
        }
    }
    removed
}

/// Installs the termination handler (once per process; later calls do
/// nothing). A second signal while cleaning up is ignored.
pub fn install() {
    INSTALL.call_once(|| {
        let r = ctrlc::set_handler(|| {
            let removed = undo_all();
            if removed.is_empty() {
                eprintln!("interrupted");
            } else {
                eprintln!("interrupted: removed the unfinished output of this run:");
                for p in &removed {
                    eprintln!("  {}", p.display());
                }
                eprintln!("the previous results, if any, are as they were");
            }
            std::process::exit(130);
        });
        if let Err(e) = r {
            eprintln!(
                "warning: no cleanup on Ctrl-C ({e}); the next run clears what this one leaves"
            );
        }
    });
}
