//! What a job folder `<work>/jobs/<key>/` says about its job:
//! `job.json` (the job as planned), `running.json` (pid, host, start),
//! `done.json` or `failed.json` (how it ended), `log.txt` (everything the
//! program printed, runs appended), `slurm.json` (the Slurm job id it was
//! submitted as). Every file is written atomically; a job counts as done
//! only by its `done.json`.

use crate::jobs::Job;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// How a run ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ending {
    pub host: String,
    pub finished_utc: String,
    pub wall_s: f64,
    /// CPU time of the program (user + system, its children included).
    pub cpu_s: f64,
    /// Exit code (None: killed by a signal).
    pub exit_code: Option<i32>,
    pub signal: Option<i32>,
}

/// A live run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Running {
    pub pid: u32,
    pub host: String,
    pub started_utc: String,
}

/// How a job was submitted to Slurm: `<job id>` or `<array id>_<task>`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Submitted {
    pub slurm_id: String,
    pub submitted_utc: String,
}

pub fn dir(work: &Path, key: &str) -> PathBuf {
    work.join("jobs").join(crate::cases::short(key))
}
pub fn log_path(work: &Path, key: &str) -> PathBuf {
    dir(work, key).join("log.txt")
}

fn read<T: for<'de> Deserialize<'de>>(path: &Path) -> Option<T> {
    serde_json::from_str(&std::fs::read_to_string(path).ok()?).ok()
}

/// Writes the job's `job.json` (its plan; rewritten when it differs).
pub fn write_job(work: &Path, job: &Job) -> anyhow::Result<()> {
    let path = dir(work, &job.key).join("job.json");
    if read::<Job>(&path).as_ref() != Some(job) {
        formats::output::write_json(&path, job)?;
    }
    Ok(())
}

pub fn read_job(work: &Path, key: &str) -> anyhow::Result<Job> {
    let path = dir(work, key).join("job.json");
    read(&path).ok_or_else(|| {
        anyhow::anyhow!(
            "{}: no job planned under this key (run `study submit` first)",
            path.display()
        )
    })
}

pub fn done(work: &Path, key: &str) -> Option<Ending> {
    read(&dir(work, key).join("done.json"))
}
pub fn failed(work: &Path, key: &str) -> Option<Ending> {
    read(&dir(work, key).join("failed.json"))
}
pub fn running(work: &Path, key: &str) -> Option<Running> {
    read(&dir(work, key).join("running.json"))
}
pub fn submitted(work: &Path, key: &str) -> Option<Submitted> {
    read(&dir(work, key).join("slurm.json"))
}

pub fn write_submitted(work: &Path, key: &str, slurm_id: &str) -> anyhow::Result<()> {
    formats::output::write_json(
        &dir(work, key).join("slurm.json"),
        &Submitted {
            slurm_id: slurm_id.into(),
            submitted_utc: formats::result_set::utc(std::time::SystemTime::now()),
        },
    )?;
    Ok(())
}

/// Whether a run recorded in `running.json` is still alive: on this host
/// by `/proc/<pid>`; a run on another host is taken as alive (Slurm's
/// state decides there).
pub fn alive(r: &Running) -> bool {
    if r.host != formats::result_set::host() {
        return true;
    }
    Path::new(&format!("/proc/{}", r.pid)).exists()
}

/// A job's state as the files tell it (Slurm's view is added by
/// [`crate::slurm`]).
#[derive(Debug, Clone, PartialEq)]
pub enum FileState {
    Done(Ending),
    Failed(Ending),
    Running(Running),
    /// Started, but its process is gone without an ending (killed hard).
    Lost(Running),
    NotRun,
}

pub fn file_state(work: &Path, key: &str) -> FileState {
    if let Some(e) = done(work, key) {
        return FileState::Done(e);
    }
    match (running(work, key), failed(work, key)) {
        (Some(r), _) if alive(&r) => FileState::Running(r),
        (_, Some(e)) => FileState::Failed(e),
        (Some(r), None) => FileState::Lost(r),
        (None, None) => FileState::NotRun,
    }
}
