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

mod lock;
mod staging;
mod stamp;
#[cfg(test)]
mod tests;

pub use lock::{holder_alive, RunLock};
pub use staging::ResultSet;
pub use stamp::{check_same_inputs, read_run_info, verify_file, verify_files, AddedStamp};

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::fmt;
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
    #[error("cannot put the results of this run in place at {}: {message} (they are left in {}, which the next run on that folder removes; the previous results are untouched)", .dir.display(), .staging.display())]
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
    #[error("{} holds results without their stamp run.json: which run wrote them, and whether a file was replaced since, cannot be checked; run the stage that writes {} again (or remove the folder)", .dir.display(), .dir.display())]
    Unstamped { dir: PathBuf },
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
