//! `study run-job`: runs one planned job in this process's place (on this
//! machine for the local executor, on a compute node for Slurm: one code
//! path). It records `running.json`, runs the program with its output
//! appended to `log.txt`, and records `done.json` or `failed.json`; a job
//! already done is not run again. Its exit status is the program's.

use crate::state::{self, Ending, Running};
use std::io::Write;
use std::path::Path;
use std::time::{Instant, SystemTime};

/// CPU seconds (user + system) of the finished children of this process.
pub fn children_cpu_s() -> f64 {
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: a valid out-pointer; RUSAGE_CHILDREN exists on Linux.
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut ru) };
    if rc != 0 {
        return f64::NAN;
    }
    let tv = |t: libc::timeval| t.tv_sec as f64 + 1e-6 * t.tv_usec as f64;
    tv(ru.ru_utime) + tv(ru.ru_stime)
}

/// Runs the job `key` of `work`; returns the program's exit code (0 when
/// the job was done already).
pub fn run(work: &Path, key: &str) -> anyhow::Result<i32> {
    if state::done(work, key).is_some() {
        return Ok(0);
    }
    let job = state::read_job(work, key)?;
    let dir = state::dir(work, key);
    let now = || formats::result_set::utc(SystemTime::now());
    let _ = std::fs::remove_file(dir.join("failed.json"));
    // Run outside Slurm now (the local executor, or by hand): an earlier
    // submission's id no longer speaks for the job.
    if std::env::var_os("SLURM_JOB_ID").is_none() {
        let _ = std::fs::remove_file(dir.join("slurm.json"));
    }
    formats::output::write_json(
        &dir.join("running.json"),
        &Running {
            pid: std::process::id(),
            host: formats::result_set::host(),
            started_utc: now(),
        },
    )?;
    let mut log = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(state::log_path(work, key))?;
    writeln!(
        log,
        "== {} on {}: {} {}",
        now(),
        formats::result_set::host(),
        job.program.display(),
        job.args.join(" ")
    )?;
    let (t0, cpu0) = (Instant::now(), children_cpu_s());
    let status = std::process::Command::new(&job.program)
        .args(&job.args)
        .current_dir(&job.cwd)
        .stdin(std::process::Stdio::null())
        .stdout(log.try_clone()?)
        .stderr(log.try_clone()?)
        .status();
    let status = match status {
        Ok(s) => s,
        Err(e) => {
            writeln!(log, "== cannot start {}: {e}", job.program.display())?;
            let ending = Ending {
                host: formats::result_set::host(),
                finished_utc: now(),
                wall_s: 0.0,
                cpu_s: 0.0,
                exit_code: Some(127),
                signal: None,
            };
            formats::output::write_json(&dir.join("failed.json"), &ending)?;
            let _ = std::fs::remove_file(dir.join("running.json"));
            return Ok(127);
        }
    };
    use std::os::unix::process::ExitStatusExt;
    let ending = Ending {
        host: formats::result_set::host(),
        finished_utc: now(),
        wall_s: t0.elapsed().as_secs_f64(),
        cpu_s: children_cpu_s() - cpu0,
        exit_code: status.code(),
        signal: status.signal(),
    };
    writeln!(
        log,
        "== {}: {} after {:.1} s wall, {:.1} s CPU",
        ending.finished_utc,
        match (ending.exit_code, ending.signal) {
            (Some(0), _) => "done".to_string(),
            (Some(c), _) => format!("failed with exit code {c}"),
            (None, Some(s)) => format!("killed by signal {s}"),
            (None, None) => "ended".to_string(),
        },
        ending.wall_s,
        ending.cpu_s
    )?;
    let name = if status.success() {
        "done.json"
    } else {
        "failed.json"
    };
    formats::output::write_json(&dir.join(name), &ending)?;
    let _ = std::fs::remove_file(dir.join("running.json"));
    Ok(status.code().unwrap_or(128 + status.signal().unwrap_or(0)))
}
