//! The local executor: the study's jobs on this machine, each through
//! `study run-job` (the same wrapper a Slurm job runs), in dependency
//! order, up to `parallel` at once and only as many as the memory they
//! ask for allows (the machine's available memory, read before each
//! start). Every stage already uses all cores (rayon), so one job at a
//! time is the default. A failed job stops its dependents, not the
//! others.

use crate::jobs::Job;
use crate::state;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// What the run did.
#[derive(Debug, Default)]
pub struct LocalOutcome {
    /// Jobs done before the run (their `done.json` found).
    pub already_done: usize,
    /// Jobs run now and done.
    pub ran: Vec<String>,
    /// Jobs run now that failed: label and log.
    pub failed: Vec<(String, PathBuf)>,
    /// Jobs not run because a dependency failed: label.
    pub blocked: Vec<String>,
}

impl LocalOutcome {
    pub fn ok(&self) -> bool {
        self.failed.is_empty() && self.blocked.is_empty()
    }
}

#[derive(Clone, Copy, PartialEq)]
enum St {
    Waiting,
    Running,
    Done,
    Failed,
    Blocked,
}

/// Runs the jobs not yet done; `study` is the program that runs a job
/// (`study run-job`).
pub fn run(
    work: &Path,
    jobs: &[Job],
    study: &Path,
    parallel: usize,
) -> anyhow::Result<LocalOutcome> {
    let parallel = parallel.max(1);
    let mut out = LocalOutcome::default();
    let mut st: BTreeMap<&str, St> = BTreeMap::new();
    for j in jobs {
        let done = state::done(work, &j.key).is_some();
        out.already_done += usize::from(done);
        st.insert(&j.key, if done { St::Done } else { St::Waiting });
    }
    let total = jobs.len();
    let mut running: Vec<(usize, std::process::Child)> = Vec::new();
    loop {
        // Jobs whose dependency failed cannot run.
        let mut changed = true;
        while changed {
            changed = false;
            for j in jobs {
                if st[j.key.as_str()] == St::Waiting
                    && j.deps
                        .iter()
                        .any(|d| matches!(st.get(d.as_str()), Some(St::Failed | St::Blocked)))
                {
                    st.insert(&j.key, St::Blocked);
                    out.blocked.push(j.label.clone());
                    changed = true;
                }
            }
        }
        // Start what is ready, within the job and memory bounds.
        let mut used_mb: u64 = running.iter().map(|(i, _)| jobs[*i].mem_mb).sum();
        let available_mb = crate::resources::available_mb();
        for (i, j) in jobs.iter().enumerate() {
            if running.len() >= parallel {
                break;
            }
            let ready = st[j.key.as_str()] == St::Waiting
                && j.deps.iter().all(|d| st.get(d.as_str()) == Some(&St::Done));
            if !ready {
                continue;
            }
            let fits = available_mb.is_none_or(|a| used_mb + j.mem_mb <= a);
            if !running.is_empty() && !fits {
                continue;
            }
            let done_count = st.values().filter(|s| **s == St::Done).count();
            eprintln!("study: [{}/{total}] {}", done_count + 1, j.label);
            let child = std::process::Command::new(study)
                .args(["run-job", "--work"])
                .arg(work)
                .arg(&j.key)
                .stdin(std::process::Stdio::null())
                .spawn()?;
            used_mb += j.mem_mb;
            st.insert(&j.key, St::Running);
            running.push((i, child));
        }
        if running.is_empty() {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
        let mut still = Vec::new();
        for (i, mut c) in running {
            match c.try_wait()? {
                None => still.push((i, c)),
                Some(_) => {
                    let j = &jobs[i];
                    if let Some(e) = state::done(work, &j.key) {
                        eprintln!("study: done {} ({:.1} s)", j.label, e.wall_s);
                        st.insert(&j.key, St::Done);
                        out.ran.push(j.label.clone());
                    } else {
                        let log = state::log_path(work, &j.key);
                        eprintln!("study: FAILED {} (log {})", j.label, log.display());
                        st.insert(&j.key, St::Failed);
                        out.failed.push((j.label.clone(), log));
                    }
                }
            }
        }
        running = still;
    }
    let left: BTreeSet<&str> = st
        .iter()
        .filter(|(_, s)| **s == St::Waiting)
        .map(|(k, _)| *k)
        .collect();
    if !left.is_empty() {
        anyhow::bail!(
            "{} jobs could not be ordered (a dependency missing from the plan)",
            left.len()
        );
    }
    Ok(out)
}
