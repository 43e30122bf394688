//! A stage's output directory written as one set.
//!
//! Each file is written atomically ([`crate::output`]), but a run writes
//! many files; a killed run, a run that fails half-way or two runs into one
//! output would otherwise leave a directory that mixes two runs' results.
//! [`ResultSet::begin`] takes a lock beside the directory (`<dir>.lock`:
//! pid, host, start time, command), refuses while a live run holds it and
//! takes over a stale one (its process is gone) with a warning; the run
//! writes into a staging sibling `<dir>.staging.<pid>.<n>`, and
//! [`ResultSet::commit`] stamps it with `run.json` and swaps it into place
//! (the old directory renamed aside, the staging directory renamed onto
//! `<dir>`, the old one removed). Dropped without a commit, the set removes
//! its staging directory and its lock: the previous results are left as
//! they were.
//!
//! [`RunLock`] is the lock alone: [`RunLock::exclusive`] (what
//! [`ResultSet::begin`] takes) and [`RunLock::shared`] for runs that may
//! work side by side but not beside an exclusive run (the shards of the
//! reference sweep, which write only into its shared position cache);
//! shared holders leave markers `<dir>.shared.<pid>.<n>.lock`.
//!
//! Liveness is judged on this host from `/proc/<pid>` (and the process's
//! start time there, so that a reused pid is not taken for the holder); a
//! lock written on another host, or where `/proc` is missing, is taken as
//! live.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{SystemTime, UNIX_EPOCH};

/// The file stamped into every committed set.
pub const RUN_FILE: &str = "run.json";

/// Who holds (or held) a lock: written into the lock file as JSON.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Holder {
    pub pid: u32,
    pub host: String,
    /// Start of the run, UTC (`YYYY-MM-DDTHH:MM:SSZ`).
    pub started_utc: String,
    /// The process's command line.
    pub command: String,
    /// What the run writes (the stage and its input).
    pub what: String,
    /// Start time of the process in clock ticks since boot
    /// (`/proc/<pid>/stat`), to tell a reused pid from the holder.
    pub process_start: Option<u64>,
    /// Unique per lock taken: a holder releases only its own lock.
    pub token: String,
}

impl fmt::Display for Holder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "pid {} on {}, started {} ({}; command `{}`)",
            self.pid, self.host, self.started_utc, self.what, self.command
        )
    }
}

/// The stamp of a committed set (`run.json`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct RunInfo {
    /// `<start time>-<host>-<pid>-<n>`, unique per run.
    pub run_id: String,
    /// Start of the run, UTC.
    pub started_utc: String,
    /// Commit of the set, UTC.
    pub committed_utc: String,
    pub what: String,
    pub command: String,
    pub pid: u32,
    pub host: String,
    /// The input files the run read, by role (`design`, `mesh:<stem>`,
    /// `stiffness:<stem>`), with their SHA-256: what [`check_same_inputs`]
    /// compares between sets that a report puts side by side.
    #[serde(default)]
    pub inputs: BTreeMap<String, String>,
    /// SHA-256 of every file the run wrote into the set (paths relative to
    /// the set, `/`-separated; `run.json` and carried-over entries not
    /// included): what [`verify_files`] checks before a reader uses them.
    #[serde(default)]
    pub files: BTreeMap<String, String>,
}

/// Why a set (or a lock) could not be taken or committed; every variant
/// names the paths involved.
#[derive(Debug, thiserror::Error)]
pub enum ResultSetError {
    #[error("{} is being written by another run: {holder}; lock {}. Wait for that run to finish{}", .dir.display(), .lock.display(), hint(.holder))]
    Busy {
        dir: PathBuf,
        lock: PathBuf,
        holder: Box<Holder>,
    },
    #[error("{} is locked by {} (unreadable: {message}); remove it if no run is writing {}", .lock.display(), .lock.display(), .dir.display())]
    UnreadableLock {
        dir: PathBuf,
        lock: PathBuf,
        message: String,
    },
    #[error("cannot write results to {}: {message}", .path.display())]
    Unwritable { path: PathBuf, message: String },
    #[error("cannot read the run stamp {}: {message}", .path.display())]
    UnreadableStamp { path: PathBuf, message: String },
    #[error("cannot put the results of this run in place at {}: {message} (they are left in {})", .dir.display(), .staging.display())]
    Commit {
        dir: PathBuf,
        staging: PathBuf,
        message: String,
    },
    #[error("run {run} recorded two inputs as `{key}`: {first} and {second}")]
    TwoInputs {
        run: String,
        key: String,
        first: String,
        second: String,
    },
    #[error(transparent)]
    MixedInputs(Box<MixedInputs>),
    #[error("{}: {why} since run {run} wrote it; run the stage that writes {} again", .file.display(), .dir.display())]
    Tampered {
        dir: PathBuf,
        file: PathBuf,
        run: String,
        why: String,
    },
    #[error(transparent)]
    Write(#[from] crate::output::WriteError),
}

/// Two committed sets that name one input with different files.
#[derive(Debug, thiserror::Error)]
#[error("{} and {} come from different inputs: `{key}` was {} in run {} ({}) and {} in run {} ({}); rerun the older one so both see the same files", .a.display(), .b.display(), short(.a_sha), .a_run, .a_what, short(.b_sha), .b_run, .b_what)]
pub struct MixedInputs {
    pub key: String,
    pub a: PathBuf,
    pub a_run: String,
    pub a_what: String,
    pub a_sha: String,
    pub b: PathBuf,
    pub b_run: String,
    pub b_what: String,
    pub b_sha: String,
}

fn short(sha: &str) -> String {
    format!("sha256 {}…", sha.chars().take(12).collect::<String>())
}

fn hint(h: &Holder) -> String {
    if h.host == host() {
        String::new()
    } else {
        format!(
            " (the lock is from host {}, where this run cannot check whether pid {} still runs; remove the lock if it does not)",
            h.host, h.pid
        )
    }
}

/// A per-process counter for unique sibling names.
static COUNTER: AtomicU64 = AtomicU64::new(0);

fn next() -> u64 {
    COUNTER.fetch_add(1, Ordering::Relaxed)
}

/// `<dir><suffix>` beside `dir`.
fn sibling(dir: &Path, suffix: &str) -> PathBuf {
    let name = dir.file_name().unwrap_or_default().to_string_lossy();
    dir.with_file_name(format!("{name}{suffix}"))
}

/// The lock file of output directory `dir`: `<dir>.lock`.
pub fn lock_path(dir: &Path) -> PathBuf {
    sibling(dir, ".lock")
}

/// The directory holding `dir` (`.` for a bare name).
fn parent_of(dir: &Path) -> &Path {
    dir.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

fn unwritable(path: &Path, e: impl fmt::Display) -> ResultSetError {
    ResultSetError::Unwritable {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// This host's name.
pub fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .unwrap_or_else(|| "unknown-host".into())
}

/// `t` as `YYYY-MM-DDTHH:MM:SSZ`.
pub fn utc(t: SystemTime) -> String {
    let s = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs());
    let (days, rem) = ((s / 86_400) as i64, s % 86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// Start time of process `pid` in clock ticks since boot, from
/// `/proc/<pid>/stat` (field 22); None where it cannot be read.
fn process_start(pid: u32) -> Option<u64> {
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
    holder: Holder,
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
fn file_hashes(root: &Path) -> std::io::Result<BTreeMap<String, String>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d)? {
            let p = e?.path();
            if p.is_dir() {
                stack.push(p);
            } else if p != root.join(RUN_FILE) {
                let rel = p.strip_prefix(root).unwrap_or(&p);
                let key = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy())
                    .collect::<Vec<_>>()
                    .join("/");
                out.insert(key, crate::manifest::sha256_file(&p)?);
            }
        }
    }
    Ok(out)
}

/// Checks that every file the committed set in `dir` lists is there with
/// the bytes its run wrote; returns the set's stamp (`None` when `dir`
/// holds no committed set).
pub fn verify_files(dir: &Path) -> Result<Option<RunInfo>, ResultSetError> {
    let Some(info) = read_run_info(dir)? else {
        return Ok(None);
    };
    for (rel, sha) in &info.files {
        let file = dir.join(rel);
        let why = match crate::manifest::sha256_file(&file) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Some("removed".to_string()),
            Err(e) => Some(format!("unreadable ({e})")),
            Ok(now) if &now != sha => Some("changed".to_string()),
            Ok(_) => None,
        };
        if let Some(why) = why {
            return Err(ResultSetError::Tampered {
                dir: dir.to_path_buf(),
                file,
                run: info.run_id.clone(),
                why,
            });
        }
    }
    Ok(Some(info))
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

/// A stage's output directory written as one set: see the module
/// documentation.
#[derive(Debug)]
pub struct ResultSet {
    lock: RunLock,
    staging: PathBuf,
    started: SystemTime,
    carried: Vec<PathBuf>,
    inputs: BTreeMap<String, String>,
    done: bool,
    /// Removed by the termination handler if the run is stopped.
    _on_interrupt: crate::interrupt::Pending,
}

impl ResultSet {
    /// Takes the lock of `dir` ([`RunLock::exclusive`]), clears what killed
    /// runs left beside it, and creates the staging directory. `what` names
    /// the run in the lock and in `run.json` (the stage and its input).
    /// Everything that can refuse the output (a live run holding it, an
    /// unwritable parent, `dir` not a directory) refuses here, before any
    /// work.
    pub fn begin(dir: &Path, what: &str) -> Result<ResultSet, ResultSetError> {
        let started = SystemTime::now();
        let lock = RunLock::exclusive(dir, what)?;
        if dir.exists() && !dir.is_dir() {
            return Err(unwritable(dir, "exists and is not a directory"));
        }
        clear_leftovers(dir);
        let staging = sibling(dir, &format!(".staging.{}.{}", std::process::id(), next()));
        std::fs::create_dir(&staging).map_err(|e| unwritable(&staging, e))?;
        Ok(ResultSet {
            _on_interrupt: crate::interrupt::pending_dir(&staging),
            lock,
            staging,
            started,
            carried: Vec::new(),
            inputs: BTreeMap::new(),
            done: false,
        })
    }

    /// Records an input file the run reads (`key` its role, e.g.
    /// `stiffness:<stem>`), written into `run.json` at commit. The same
    /// key with another SHA-256 within one run is refused.
    pub fn record_input(&mut self, key: &str, sha256: &str) -> Result<(), ResultSetError> {
        match self.inputs.get(key) {
            Some(first) if first != sha256 => Err(ResultSetError::TwoInputs {
                run: self.lock.holder.what.clone(),
                key: key.to_string(),
                first: first.clone(),
                second: sha256.to_string(),
            }),
            _ => {
                self.inputs.insert(key.to_string(), sha256.to_string());
                Ok(())
            }
        }
    }

    /// Where this run writes: the staging directory.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The final output directory.
    pub fn dir(&self) -> &Path {
        self.lock.dir()
    }

    /// Where `staged`, a path under [`Self::path`], will be once committed
    /// (for paths recorded inside the results).
    pub fn final_path(&self, staged: &Path) -> PathBuf {
        match staged.strip_prefix(&self.staging) {
            Ok(rel) => self.dir().join(rel),
            Err(_) => staged.to_path_buf(),
        }
    }

    /// Carries `rel` (a file or directory under the current `<dir>`, if
    /// there) over into the new set at commit, where this run did not write
    /// it: for what outlives a run, such as a cache that other runs share.
    pub fn carry_over(&mut self, rel: &Path) {
        self.carried.push(rel.to_path_buf());
    }

    /// Stamps the set with `run.json` and puts it in place of `<dir>`:
    /// the old directory is renamed aside, the staging directory renamed
    /// onto `<dir>`, the old one removed; then the lock is released.
    pub fn commit(mut self) -> Result<RunInfo, ResultSetError> {
        let dir = self.dir().to_path_buf();
        let host = self.lock.holder.host.clone();
        let info = RunInfo {
            run_id: format!(
                "{}-{host}-{}-{}",
                utc(self.started).replace([':', '-'], ""),
                std::process::id(),
                next()
            ),
            started_utc: utc(self.started),
            committed_utc: utc(SystemTime::now()),
            what: self.lock.holder.what.clone(),
            command: self.lock.holder.command.clone(),
            pid: std::process::id(),
            host,
            inputs: std::mem::take(&mut self.inputs),
            files: file_hashes(&self.staging).map_err(|e| unwritable(&self.staging, e))?,
        };
        crate::output::write_json(&self.staging.join(RUN_FILE), &info)?;
        let err = |staging: &Path, m: String| ResultSetError::Commit {
            dir: dir.clone(),
            staging: staging.to_path_buf(),
            message: m,
        };
        // From here until the set is in place (or back as it was), a
        // termination signal waits: carried-over entries (shared caches)
        // are inside the staging directory meanwhile.
        let critical = crate::interrupt::critical();
        // Carried-over entries move into the staging directory.
        // A failure part way moves back what was moved, so that dropping
        // the staging directory cannot take a shared cache with it.
        let mut moved: Vec<(PathBuf, PathBuf)> = Vec::new();
        let move_back = |moved: &[(PathBuf, PathBuf)]| {
            for (from, to) in moved.iter().rev() {
                let _ = std::fs::rename(to, from);
            }
        };
        for rel in &self.carried {
            let (from, to) = (dir.join(rel), self.staging.join(rel));
            if from.exists() && !to.exists() {
                let r = to
                    .parent()
                    .map_or(Ok(()), std::fs::create_dir_all)
                    .and_then(|()| std::fs::rename(&from, &to));
                if let Err(e) = r {
                    move_back(&moved);
                    return Err(err(
                        &self.staging,
                        format!("cannot move {} into the set: {e}", from.display()),
                    ));
                }
                moved.push((from, to));
            }
        }
        let old = sibling(&dir, &format!(".old.{}.{}", std::process::id(), next()));
        let had_old = dir.exists();
        let swap = (|| -> std::io::Result<()> {
            if had_old {
                std::fs::rename(&dir, &old)?;
            }
            if let Err(e) = std::fs::rename(&self.staging, &dir) {
                if had_old {
                    let _ = std::fs::rename(&old, &dir);
                }
                return Err(e);
            }
            Ok(())
        })();
        if let Err(e) = swap {
            move_back(&moved);
            return Err(err(&self.staging, e.to_string()));
        }
        self.done = true;
        drop(critical);
        if had_old {
            if let Err(e) = std::fs::remove_dir_all(&old) {
                eprintln!(
                    "warning: the previous results of {} are in place but their old copy {} could not be removed: {e}",
                    dir.display(),
                    old.display()
                );
            }
        }
        Ok(info)
    }
}

impl Drop for ResultSet {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        // The lock goes with `self.lock`.
    }
}

/// The pid in a sibling name `<dir><kind><pid>.<n>`.
fn sibling_pid(name: &str, prefix: &str) -> Option<u32> {
    name.strip_prefix(prefix)?.split('.').next()?.parse().ok()
}

/// With the lock held: removes the staging directories that runs of dead
/// processes left beside `dir`, and puts back a previous set that a commit
/// killed between its two renames had moved aside.
fn clear_leftovers(dir: &Path) {
    let name = dir.file_name().unwrap_or_default().to_string_lossy();
    let (staging, old) = (format!("{name}.staging."), format!("{name}.old."));
    let Ok(rd) = std::fs::read_dir(parent_of(dir)) else {
        return;
    };
    let dead = |pid: u32| pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists();
    let on_proc = Path::new("/proc/self").exists();
    for e in rd.filter_map(Result::ok) {
        let n = e.file_name().to_string_lossy().into_owned();
        let p = e.path();
        if let Some(pid) = sibling_pid(&n, &staging).filter(|&pid| on_proc && dead(pid)) {
            eprintln!(
                "warning: removing {}, the unfinished results of a run (pid {pid}) that no longer runs",
                p.display()
            );
            let _ = std::fs::remove_dir_all(&p);
        } else if let Some(pid) = sibling_pid(&n, &old).filter(|&pid| on_proc && dead(pid)) {
            if dir.exists() {
                let _ = std::fs::remove_dir_all(&p);
            } else if std::fs::rename(&p, dir).is_ok() {
                eprintln!(
                    "warning: a run (pid {pid}) was stopped while putting its results in place; the previous results are back in {}",
                    dir.display()
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_formats_known_dates() {
        let at = |s: u64| utc(UNIX_EPOCH + std::time::Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01T00:00:00Z");
        assert_eq!(at(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(at(1_709_210_096), "2024-02-29T12:34:56Z");
    }

    #[test]
    fn process_start_of_this_process_is_read() {
        if Path::new("/proc/self/stat").exists() {
            assert!(process_start(std::process::id()).is_some());
        }
    }
}
