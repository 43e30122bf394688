//! The lock of an output directory: who holds it, whether that process
//! still runs, and taking it (exclusive or shared) or a stale one over.

use super::{host, lock_path, utc};
use super::{next, parent_of, sibling, unwritable, Holder, ResultSetError};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// Start time of process `pid` in clock ticks since boot, from
/// `/proc/<pid>/stat` (field 22); None where it cannot be read.
pub(super) fn process_start(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces.
    let rest = &stat[stat.rfind(')')? + 1..];
    rest.split_whitespace().nth(19)?.parse().ok()
}

/// Whether the holder's process still runs: on this host, `/proc/<pid>`
/// exists and (when recorded) started when the holder's did. Another
/// host's holder, or a system without `/proc`, counts as running.
pub fn holder_alive(h: &Holder) -> bool {
    if h.host != host() || !Path::new("/proc/self").exists() {
        return true;
    }
    if !Path::new(&format!("/proc/{}", h.pid)).exists() {
        return false;
    }
    match (h.process_start, process_start(h.pid)) {
        (Some(a), Some(b)) => a == b,
        _ => true,
    }
}

fn new_holder(what: &str, started: SystemTime) -> Holder {
    let pid = std::process::id();
    Holder {
        pid,
        host: host(),
        started_utc: utc(started),
        command: std::env::args().collect::<Vec<_>>().join(" "),
        what: what.to_string(),
        process_start: process_start(pid),
        token: format!(
            "{pid}-{}-{}",
            next(),
            started
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos())
        ),
    }
}

/// Creates `path` holding `h`, complete or not at all: written to a unique
/// temporary file, then hard-linked to `path` (which fails if `path`
/// exists, as `create_new` does). Ok(false): `path` exists.
fn create_lock_file(path: &Path, h: &Holder) -> Result<bool, ResultSetError> {
    let tmp = sibling(path, &format!(".{}.{}.tmp", std::process::id(), next()));
    let text = serde_json::to_string_pretty(h).map_err(|e| unwritable(path, e))?;
    let write = || -> std::io::Result<()> {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        f.write_all(text.as_bytes())?;
        f.sync_all()
    };
    if let Err(e) = write() {
        let _ = std::fs::remove_file(&tmp);
        return Err(unwritable(parent_of(path), e));
    }
    let linked = std::fs::hard_link(&tmp, path);
    let _ = std::fs::remove_file(&tmp);
    match linked {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
        // A file system without hard links: create_new, then write.
        Err(_) => {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(path)
            {
                Ok(mut f) => {
                    f.write_all(text.as_bytes())
                        .and_then(|()| f.sync_all())
                        .map_err(|e| unwritable(path, e))?;
                    Ok(true)
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(false),
                Err(e) => Err(unwritable(parent_of(path), e)),
            }
        }
    }
}

fn read_holder(path: &Path) -> std::io::Result<Result<Holder, String>> {
    let text = std::fs::read_to_string(path)?;
    Ok(serde_json::from_str(&text).map_err(|e| e.to_string()))
}

/// Removes `path` if it still holds `token`.
fn release_file(path: &Path, token: &str) {
    if let Ok(Ok(h)) = read_holder(path) {
        if h.token == token {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Shared markers of `dir`: `<dir>.shared.<pid>.<n>.lock`.
fn shared_markers(dir: &Path) -> Vec<PathBuf> {
    let name = dir.file_name().unwrap_or_default().to_string_lossy();
    let prefix = format!("{name}.shared.");
    std::fs::read_dir(parent_of(dir))
        .map(|rd| {
            rd.filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| {
                    p.file_name().is_some_and(|n| {
                        let n = n.to_string_lossy();
                        n.starts_with(&prefix) && n.ends_with(".lock")
                    })
                })
                .collect()
        })
        .unwrap_or_default()
}

/// A lock on an output directory, released when dropped.
#[derive(Debug)]
pub struct RunLock {
    dir: PathBuf,
    path: PathBuf,
    pub(super) holder: Holder,
    /// Released by the termination handler if the run is stopped.
    _on_interrupt: crate::interrupt::Pending,
}

impl RunLock {
    /// The one writer of `dir`: refused while another live run holds
    /// `<dir>.lock` or a shared marker of `dir`; a stale lock or marker
    /// (its process is gone) is taken over with a warning. The parent of
    /// `dir` is created; an unwritable one is refused here, naming it.
    pub fn exclusive(dir: &Path, what: &str) -> Result<RunLock, ResultSetError> {
        let lock = Self::acquire(dir, what, lock_path(dir))?;
        for m in shared_markers(dir) {
            match read_holder(&m) {
                Ok(Ok(h)) if holder_alive(&h) => {
                    return Err(ResultSetError::Busy {
                        dir: dir.to_path_buf(),
                        lock: m,
                        holder: Box::new(h),
                    })
                }
                Ok(Ok(h)) => {
                    eprintln!(
                        "warning: removing stale lock {} of a run that no longer runs ({h})",
                        m.display()
                    );
                    let _ = std::fs::remove_file(&m);
                }
                // Being written (a shared holder writes its marker whole
                // through a link, so this is rare) or gone: no holder.
                _ => {}
            }
        }
        Ok(lock)
    }

    /// One of several runs that may write side by side (each into files
    /// of its own): refused while a live run holds the exclusive lock of
    /// `dir`; a stale exclusive lock is left to the next exclusive run.
    pub fn shared(dir: &Path, what: &str) -> Result<RunLock, ResultSetError> {
        let marker = sibling(
            dir,
            &format!(".shared.{}.{}.lock", std::process::id(), next()),
        );
        let lock = Self::acquire(dir, what, marker)?;
        let main = lock_path(dir);
        match read_holder(&main) {
            Ok(Ok(h)) if holder_alive(&h) => Err(ResultSetError::Busy {
                dir: dir.to_path_buf(),
                lock: main,
                holder: Box::new(h),
            }),
            Ok(Err(message)) => Err(ResultSetError::UnreadableLock {
                dir: dir.to_path_buf(),
                lock: main,
                message,
            }),
            _ => Ok(lock),
        }
    }

    fn acquire(dir: &Path, what: &str, path: PathBuf) -> Result<RunLock, ResultSetError> {
        if dir.file_name().is_none() {
            return Err(unwritable(dir, "not a directory name"));
        }
        let parent = parent_of(dir);
        std::fs::create_dir_all(parent).map_err(|e| unwritable(parent, e))?;
        let holder = new_holder(what, SystemTime::now());
        // Twice at most: once more after taking a stale lock over.
        for _ in 0..2 {
            if create_lock_file(&path, &holder)? {
                return Ok(RunLock {
                    dir: dir.to_path_buf(),
                    _on_interrupt: crate::interrupt::pending_lock(&path, &holder.token),
                    path,
                    holder,
                });
            }
            let old = match read_holder(&path) {
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => continue,
                Err(e) => return Err(unwritable(&path, e)),
                Ok(Err(message)) => {
                    return Err(ResultSetError::UnreadableLock {
                        dir: dir.to_path_buf(),
                        lock: path,
                        message,
                    })
                }
                Ok(Ok(h)) => h,
            };
            if holder_alive(&old) {
                return Err(ResultSetError::Busy {
                    dir: dir.to_path_buf(),
                    lock: path,
                    holder: Box::new(old),
                });
            }
            // Stale: move it aside (one taker wins the rename), check that
            // it is the lock judged stale, then take the path.
            let aside = sibling(&path, &format!(".stale.{}.{}", std::process::id(), next()));
            if std::fs::rename(&path, &aside).is_err() {
                continue;
            }
            match read_holder(&aside) {
                Ok(Ok(h)) if h == old => {
                    eprintln!(
                        "warning: taking over the stale lock {} of a run that no longer runs ({old}); its results were not committed",
                        path.display()
                    );
                    let _ = std::fs::remove_file(&aside);
                }
                _ => {
                    // Another run took it over meanwhile: put its lock back.
                    let _ = std::fs::hard_link(&aside, &path);
                    let _ = std::fs::remove_file(&aside);
                }
            }
        }
        match read_holder(&path) {
            Ok(Ok(h)) => Err(ResultSetError::Busy {
                dir: dir.to_path_buf(),
                lock: path,
                holder: Box::new(h),
            }),
            _ => Err(unwritable(&path, "the lock changed hands while taking it")),
        }
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The locked output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// This run as written into the lock.
    pub fn holder(&self) -> &Holder {
        &self.holder
    }
}

impl Drop for RunLock {
    fn drop(&mut self) {
        release_file(&self.path, &self.holder.token);
    }
}
