//! The Slurm executor: each job not done is submitted with `sbatch`
//! (the shards of one case's reference sweep as one job array), with
//! `--dependency=afterok` on the jobs it needs that are still queued or
//! running, its `--mem` and `--cpus-per-task` from the plan, and the
//! study's partition, account and time limit. The batch script runs
//! `study run-job`, the local executor's wrapper. A job that is queued or
//! running is not submitted twice; a job that failed, was cancelled or
//! was lost is submitted again, alone (an array with only its index).

use crate::jobs::Job;
use crate::state;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Where and how the jobs run on the cluster.
#[derive(Debug, Clone, Default)]
pub struct SlurmOptions {
    pub partition: Option<String>,
    pub account: Option<String>,
    pub time: Option<String>,
}

/// Slurm's view of one job.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SlurmState {
    /// Queued or running (PENDING, RUNNING, CONFIGURING, COMPLETING,
    /// SUSPENDED, REQUEUED ...).
    Active(String),
    /// Ended (COMPLETED, FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY ...).
    Ended(String),
    /// Slurm no longer knows the id.
    Unknown,
}

fn run_cmd(cmd: &mut Command) -> anyhow::Result<String> {
    let out = cmd.output().map_err(|e| {
        anyhow::anyhow!(
            "cannot run {:?}: {e} (is Slurm's client installed?)",
            cmd.get_program()
        )
    })?;
    if !out.status.success() {
        anyhow::bail!(
            "{:?} {:?} failed: {}",
            cmd.get_program(),
            cmd.get_args().collect::<Vec<_>>(),
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

const ACTIVE: [&str; 9] = [
    "PENDING",
    "RUNNING",
    "CONFIGURING",
    "COMPLETING",
    "SUSPENDED",
    "REQUEUED",
    "REQUEUE_HOLD",
    "RESIZING",
    "STAGE_OUT",
];

/// Slurm's states of the ids asked for: one `squeue` for the queued and
/// running ones, `scontrol show job` for the others (Slurm keeps ended
/// jobs for `MinJobAge`).
pub fn states(ids: &[String]) -> anyhow::Result<BTreeMap<String, SlurmState>> {
    let mut out = BTreeMap::new();
    if ids.is_empty() {
        return Ok(out);
    }
    let queue = run_cmd(Command::new("squeue").args(["-h", "-r", "-o", "%i %T"]))?;
    let queued: BTreeMap<&str, &str> = queue.lines().filter_map(|l| l.split_once(' ')).collect();
    for id in ids {
        if let Some(s) = queued.get(id.as_str()) {
            let s = s.trim().to_string();
            let st = if ACTIVE.contains(&s.as_str()) {
                SlurmState::Active(s)
            } else {
                SlurmState::Ended(s)
            };
            out.insert(id.clone(), st);
            continue;
        }
        let shown = Command::new("scontrol")
            .args(["show", "job", "-o", id])
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).into_owned());
        let st = shown
            .as_deref()
            .and_then(|t| job_state_of(t, id))
            .map(|s| {
                if ACTIVE.contains(&s.as_str()) {
                    SlurmState::Active(s)
                } else {
                    SlurmState::Ended(s)
                }
            })
            .unwrap_or(SlurmState::Unknown);
        out.insert(id.clone(), st);
    }
    Ok(out)
}

/// The `JobState` of job `id` (`<job>` or `<array>_<task>`) in the output
/// of `scontrol show job -o`, one line per job (an array shows a line per
/// task, with `ArrayJobId` and `ArrayTaskId`).
pub fn job_state_of(text: &str, id: &str) -> Option<String> {
    let (array, task) = match id.split_once('_') {
        Some((a, t)) => (a, Some(t)),
        None => (id, None),
    };
    for line in text.lines() {
        let f: BTreeMap<&str, &str> = line
            .split_whitespace()
            .filter_map(|w| w.split_once('='))
            .collect();
        let matches = match task {
            Some(t) => f.get("ArrayJobId") == Some(&array) && f.get("ArrayTaskId") == Some(&t),
            None => f.get("JobId") == Some(&array),
        };
        if matches {
            return f.get("JobState").map(|s| s.to_string());
        }
    }
    None
}

/// What a submission did.
#[derive(Debug, Default)]
pub struct Submitted {
    /// Jobs submitted now (label, Slurm id).
    pub submitted: Vec<(String, String)>,
    /// Jobs found queued or running, not submitted again.
    pub active: usize,
    pub already_done: usize,
}

/// Submits every job of `jobs` that is not done and not queued or running.
pub fn submit(
    work: &Path,
    jobs: &[Job],
    study: &Path,
    opt: &SlurmOptions,
) -> anyhow::Result<Submitted> {
    let ids: Vec<String> = jobs
        .iter()
        .filter_map(|j| state::submitted(work, &j.key).map(|s| s.slurm_id))
        .collect();
    let known = states(&ids)?;
    let mut handle: BTreeMap<&str, Option<String>> = BTreeMap::new();
    let mut res = Submitted::default();
    let slurm_dir = work.join("slurm");
    std::fs::create_dir_all(&slurm_dir)?;
    let mut i = 0;
    while i < jobs.len() {
        // One job, or the whole array group it starts.
        let group: Vec<&Job> = match &jobs[i].array {
            Some(a) => jobs[i..]
                .iter()
                .take_while(|j| j.array.as_ref() == Some(a))
                .collect(),
            None => vec![&jobs[i]],
        };
        i += group.len();
        let mut todo = Vec::new();
        for (k, j) in group.iter().enumerate() {
            if state::done(work, &j.key).is_some() {
                res.already_done += 1;
                handle.insert(&j.key, None);
                continue;
            }
            let active =
                state::submitted(work, &j.key).and_then(|s| match known.get(&s.slurm_id) {
                    Some(SlurmState::Active(_)) => Some(s.slurm_id),
                    _ => None,
                });
            match active {
                Some(id) => {
                    res.active += 1;
                    handle.insert(&j.key, Some(id));
                }
                None => todo.push(k),
            }
        }
        if todo.is_empty() {
            continue;
        }
        let first = group[todo[0]];
        let mut deps: Vec<String> = Vec::new();
        for &k in &todo {
            for d in &group[k].deps {
                match handle.get(d.as_str()) {
                    Some(Some(id)) if !deps.contains(id) => deps.push(id.clone()),
                    Some(_) => {}
                    None => anyhow::bail!(
                        "{}: its dependency {d} is not planned before it",
                        group[k].label
                    ),
                }
            }
        }
        let keys: Vec<&str> = group.iter().map(|j| j.key.as_str()).collect();
        let script = batch_script(study, work, &keys, first.array.is_some());
        let name = match &first.array {
            Some(a) => format!("array_{a}.sh"),
            None => format!("job_{}.sh", crate::cases::short(&first.key)),
        };
        let script_path = slurm_dir.join(name);
        formats::output::write_atomic(&script_path, script.as_bytes())?;
        let mut cmd = Command::new("sbatch");
        cmd.args(["--parsable", "--kill-on-invalid-dep=yes"])
            .arg(format!("--job-name=study-{:?}", first.kind).to_lowercase())
            .arg(format!("--mem={}M", first.mem_mb))
            .arg(format!("--cpus-per-task={}", first.cpus))
            .arg(format!("--chdir={}", first.cwd.display()))
            .arg(format!(
                "--output={}",
                slurm_dir.join("%A_%a.out").display()
            ));
        if first.array.is_some() {
            let idx: Vec<String> = todo.iter().map(|k| k.to_string()).collect();
            cmd.arg(format!("--array={}", idx.join(",")));
        }
        if !deps.is_empty() {
            cmd.arg(format!("--dependency=afterok:{}", deps.join(":")));
        }
        for (flag, v) in [
            ("--partition", &opt.partition),
            ("--account", &opt.account),
            ("--time", &opt.time),
        ] {
            if let Some(v) = v {
                cmd.arg(format!("{flag}={v}"));
            }
        }
        cmd.arg(&script_path);
        let out = run_cmd(&mut cmd)?;
        let id = out.trim().split(';').next().unwrap_or("").to_string();
        if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
            anyhow::bail!("sbatch gave no job id (printed {out:?})");
        }
        for &k in &todo {
            let j = group[k];
            let sid = if first.array.is_some() {
                format!("{id}_{k}")
            } else {
                id.clone()
            };
            // A fresh submission: the last run's ending is history (its
            // log keeps it).
            let _ = std::fs::remove_file(state::dir(work, &j.key).join("failed.json"));
            let _ = std::fs::remove_file(state::dir(work, &j.key).join("running.json"));
            state::write_submitted(work, &j.key, &sid)?;
            // Dependents wait for the whole job (an array as a whole).
            handle.insert(&j.key, Some(id.clone()));
            res.submitted.push((j.label.clone(), sid));
        }
    }
    Ok(res)
}

/// The batch script: `study run-job` for the job's key, or for the array
/// task's key.
fn batch_script(study: &Path, work: &Path, keys: &[&str], array: bool) -> String {
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let mut s = String::from("#!/bin/bash\n# Written by `study submit`: one job of a study (see docs/studies.md).\nset -eu\n");
    if array {
        s.push_str(&format!("keys=({})\n", keys.join(" ")));
        s.push_str(&format!(
            "exec {} run-job --work {} \"${{keys[$SLURM_ARRAY_TASK_ID]}}\"\n",
            q(study),
            q(work)
        ));
    } else {
        s.push_str(&format!(
            "exec {} run-job --work {} {}\n",
            q(study),
            q(work),
            keys[0]
        ));
    }
    s
}

fn shell_quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', "'\\''"))
}

/// The Slurm ids of the jobs that have them.
pub fn ids(work: &Path, jobs: &[Job]) -> BTreeMap<String, String> {
    jobs.iter()
        .filter_map(|j| state::submitted(work, &j.key).map(|s| (j.key.clone(), s.slurm_id)))
        .collect()
}

/// Where Slurm writes the batch script's own output of an id.
pub fn output_path(work: &Path, slurm_id: &str) -> PathBuf {
    let (a, t) = slurm_id.split_once('_').unwrap_or((slurm_id, "4294967294"));
    work.join("slurm").join(format!("{a}_{t}.out"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn job_state_is_read_from_scontrol_lines_of_jobs_and_array_tasks() {
        let text = "JobId=7 JobName=a JobState=COMPLETED Reason=None\n\
                    JobId=9 ArrayJobId=8 ArrayTaskId=1 JobState=CANCELLED Reason=None\n\
                    JobId=8 ArrayJobId=8 ArrayTaskId=0 JobState=COMPLETED Reason=None\n";
        assert_eq!(job_state_of(text, "7").as_deref(), Some("COMPLETED"));
        assert_eq!(job_state_of(text, "8_1").as_deref(), Some("CANCELLED"));
        assert_eq!(job_state_of(text, "8_0").as_deref(), Some("COMPLETED"));
        assert_eq!(job_state_of(text, "8_2"), None);
    }

    #[test]
    fn array_script_picks_the_task_key_and_quotes_paths() {
        let s = batch_script(
            Path::new("/b/study"),
            Path::new("/w o"),
            &["k0", "k1"],
            true,
        );
        assert!(s.contains("keys=(k0 k1)"));
        assert!(
            s.contains("exec '/b/study' run-job --work '/w o' \"${keys[$SLURM_ARRAY_TASK_ID]}\"")
        );
    }
}
