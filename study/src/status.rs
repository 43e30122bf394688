//! `study status`: every job's state from its folder and, for submitted
//! jobs, from Slurm: done, running, pending, failed (with its log),
//! cancelled, lost, or not run.

use crate::jobs::Job;
use crate::slurm::SlurmState;
use crate::state::{self, FileState};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// A job's state.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum JobState {
    Done,
    Running,
    /// Queued in Slurm (its state there).
    Pending(String),
    /// Ended without success: exit code or signal, or Slurm's state.
    Failed(String),
    /// Cancelled in Slurm before it ended.
    Cancelled,
    /// Started, but gone without an ending, and not known to Slurm as
    /// cancelled.
    Lost,
    NotRun,
}

impl JobState {
    pub fn name(&self) -> String {
        match self {
            JobState::Done => "done".into(),
            JobState::Running => "running".into(),
            JobState::Pending(s) if s == "PENDING" => "pending".into(),
            JobState::Pending(s) => format!("pending ({})", s.to_lowercase()),
            JobState::Failed(why) => format!("failed ({why})"),
            JobState::Cancelled => "cancelled".into(),
            JobState::Lost => "lost".into(),
            JobState::NotRun => "not run".into(),
        }
    }
}

/// One row of the status.
#[derive(Debug, Clone, Serialize)]
pub struct JobStatus {
    pub label: String,
    pub key: String,
    pub state: JobState,
    pub slurm_id: Option<String>,
    pub log: PathBuf,
}

/// The state from the job's files and Slurm's state of its id.
pub fn combine(files: FileState, slurm: Option<&SlurmState>) -> JobState {
    let ended = |e: &state::Ending| match (e.exit_code, e.signal) {
        (Some(c), _) => format!("exit code {c}"),
        (None, Some(s)) => format!("signal {s}"),
        _ => "no exit status".into(),
    };
    // Slurm's word on a job that ended decides over a `running.json`
    // left by a run on another node (its process cannot be checked from
    // here); a job without a Slurm id is judged by its files alone.
    match (files, slurm) {
        (FileState::Done(_), _) => JobState::Done,
        (_, Some(SlurmState::Active(s)))
            if s == "RUNNING" || s == "COMPLETING" || s == "CONFIGURING" =>
        {
            JobState::Running
        }
        (_, Some(SlurmState::Active(s))) => JobState::Pending(s.clone()),
        (FileState::Failed(e), _) => JobState::Failed(ended(&e)),
        (_, Some(SlurmState::Ended(s))) if s == "CANCELLED" => JobState::Cancelled,
        (_, Some(SlurmState::Ended(s))) if s != "COMPLETED" => {
            JobState::Failed(format!("Slurm {s}"))
        }
        (FileState::Running(_), _) => JobState::Running,
        (FileState::Lost(_), _) => JobState::Lost,
        (FileState::NotRun, _) => JobState::NotRun,
    }
}

/// Every job's status; Slurm is asked only when some job was submitted.
pub fn status(work: &Path, jobs: &[Job]) -> anyhow::Result<Vec<JobStatus>> {
    let ids = crate::slurm::ids(work, jobs);
    let known = if ids.is_empty() {
        Default::default()
    } else {
        crate::slurm::states(&ids.values().cloned().collect::<Vec<_>>())?
    };
    Ok(jobs
        .iter()
        .map(|j| {
            let sid = ids.get(&j.key).cloned();
            let st = sid.as_ref().and_then(|s| known.get(s));
            JobStatus {
                label: j.label.clone(),
                key: j.key.clone(),
                state: combine(state::file_state(work, &j.key), st),
                slurm_id: sid,
                log: state::log_path(work, &j.key),
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ending(code: Option<i32>, signal: Option<i32>) -> state::Ending {
        state::Ending {
            host: "h".into(),
            finished_utc: "t".into(),
            wall_s: 1.0,
            cpu_s: 1.0,
            exit_code: code,
            signal,
        }
    }

    fn run2() -> state::Running {
        state::Running {
            pid: 2,
            host: "node7".into(),
            started_utc: "t".into(),
        }
    }

    #[test]
    fn states_combine_the_job_files_with_slurms_view() {
        let run = state::Running {
            pid: 1,
            host: "h".into(),
            started_utc: "t".into(),
        };
        let ended = |s: &str| SlurmState::Ended(s.into());
        let active = |s: &str| SlurmState::Active(s.into());
        assert_eq!(
            combine(
                FileState::Done(ending(Some(0), None)),
                Some(&ended("CANCELLED"))
            ),
            JobState::Done
        );
        assert_eq!(
            combine(FileState::NotRun, Some(&active("PENDING"))),
            JobState::Pending("PENDING".into())
        );
        assert_eq!(
            combine(FileState::NotRun, Some(&active("RUNNING"))),
            JobState::Running
        );
        assert_eq!(
            combine(FileState::Lost(run.clone()), Some(&ended("CANCELLED"))),
            JobState::Cancelled
        );
        assert_eq!(combine(FileState::Lost(run), None), JobState::Lost);
        assert_eq!(
            combine(
                FileState::Failed(ending(Some(2), None)),
                Some(&ended("FAILED"))
            ),
            JobState::Failed("exit code 2".into())
        );
        assert_eq!(
            combine(FileState::NotRun, Some(&ended("TIMEOUT"))),
            JobState::Failed("Slurm TIMEOUT".into())
        );
        assert_eq!(combine(FileState::NotRun, None), JobState::NotRun);
        // A run on another node whose `running.json` outlived it.
        assert_eq!(
            combine(FileState::Running(run2()), Some(&ended("NODE_FAIL"))),
            JobState::Failed("Slurm NODE_FAIL".into())
        );
        assert_eq!(
            combine(FileState::Running(run2()), Some(&ended("CANCELLED"))),
            JobState::Cancelled
        );
        assert_eq!(combine(FileState::Running(run2()), None), JobState::Running);
    }
}
