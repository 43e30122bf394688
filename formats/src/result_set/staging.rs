//! The set itself: the staging sibling a run writes into, the commit that
//! stamps it and swaps it into place, and the clean-up of what killed runs
//! left beside the directory.

use super::stamp::file_hashes;
use super::{
    next, parent_of, sibling, unwritable, utc, ResultSetError, RunInfo, RunLock, RUN_FILE,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

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
        crate::stop_point::at("committing");
        let err = |staging: &Path, m: String| ResultSetError::Commit {
            dir: dir.clone(),
            staging: staging.to_path_buf(),
            message: m,
        };
        // From here until the set is in place (or back as it was), a
        // termination signal waits: carried-over entries (shared caches)
        // are inside the staging directory meanwhile.
        let mut critical = crate::interrupt::critical();
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
                    // The run's results stay in the staging directory (the
                    // message names it); the next run on `dir` clears it.
                    self.done = true;
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
            self.done = true;
            return Err(err(&self.staging, e.to_string()));
        }
        self.done = true;
        // The old copy is this run's to remove: a signal from here on
        // removes it too (the new set is in place).
        let old_pending = had_old.then(|| critical.pending_dir(&old));
        drop(critical);
        crate::stop_point::at("committed");
        if had_old {
            if let Err(e) = std::fs::remove_dir_all(&old) {
                eprintln!(
                    "warning: the previous results of {} are in place but their old copy {} could not be removed: {e}",
                    dir.display(),
                    old.display()
                );
            }
        }
        drop(old_pending);
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
