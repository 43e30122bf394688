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
//!
//! The signals are taken by a thread of their own (`sigwait`), not by an
//! asynchronous handler: [`install`] blocks SIGINT, SIGTERM and SIGHUP in
//! the calling thread, so every thread started after it (rayon's, faer's)
//! inherits the block, and the signal waits, pending, until the signal
//! thread takes it. A library that sets its own handler meanwhile cannot
//! intercept it: METIS (GKlib) installs one for SIGTERM around every
//! ordering and long-jumps out of the ordering when it fires, which made a
//! SIGTERM during `METIS_NodeND` a false "ordering failed" error (or an
//! exit 143 with the lock and staging folder left behind). Threads that
//! already ran before [`install`] (a test harness's) keep the signals
//! unblocked; for them a handler forwards the signal to the signal thread.
//! gmsh starts such a thread from its library constructor, before `main`,
//! and its initialization replaces the forwarding handlers (leaving SIGTERM
//! and SIGHUP at their defaults, which killed the process outright): the
//! `gmsh` crate's session puts every disposition back. Child processes get
//! the signals unblocked again ([`child`]).
//!
//! The signal tests stop real binaries at named phases
//! ([`crate::stop_point`]).

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
    /// A child process to kill (and reap) before the files are removed,
    /// so that it cannot write them again.
    Process(u32),
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

/// Registers a child process to kill if the run is stopped (before the
/// files registered earlier are removed: a child writing one of them
/// cannot write it again afterwards).
pub fn pending_process(pid: u32) -> Pending {
    register(Undo::Process(pid))
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
pub struct Critical(MutexGuard<'static, BTreeMap<u64, Undo>>);

impl Critical {
    /// Registers a directory to remove if the run is stopped once the guard
    /// is gone: for what a critical section leaves to be removed after it
    /// (a replaced set's old copy), so that a signal arriving right after
    /// the section cannot leave it behind.
    pub fn pending_dir(&mut self, path: &Path) -> Pending {
        let id = NEXT.fetch_add(1, Ordering::Relaxed);
        self.0.insert(id, Undo::Dir(path.to_path_buf()));
        Pending(id)
    }
}

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
            Undo::Process(pid) => {
                // SAFETY: kill and waitpid on a child of this process; a
                // child already reaped gives ESRCH / ECHILD, harmlessly.
                unsafe {
                    libc::kill(pid as libc::pid_t, libc::SIGKILL);
                    libc::waitpid(pid as libc::pid_t, std::ptr::null_mut(), 0);
                }
            }
        }
    }
    removed
}

/// SIGINT, SIGTERM and SIGHUP.
fn termination_set() -> libc::sigset_t {
    // SAFETY: sigemptyset and sigaddset initialise and fill a local set.
    unsafe {
        let mut set: libc::sigset_t = std::mem::zeroed();
        libc::sigemptyset(&mut set);
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            libc::sigaddset(&mut set, sig);
        }
        set
    }
}

/// The signal thread (0: none yet).
static SIGNAL_THREAD: AtomicU64 = AtomicU64::new(0);

/// Handler of threads that run with the signals unblocked: hands the
/// signal to the signal thread, which has it blocked and waits for it.
extern "C" fn forward(sig: libc::c_int) {
    let t = SIGNAL_THREAD.load(Ordering::SeqCst);
    if t != 0 {
        // SAFETY: pthread_kill is async-signal-safe; `t` is a live thread
        // (the signal thread never returns).
        unsafe {
            libc::pthread_kill(t as libc::pthread_t, sig);
        }
    }
}

/// Removes what is registered, says so, exits 130.
fn stop() -> ! {
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
}

/// Installs the termination handling (once per process; later calls do
/// nothing): call it first in `main`, before any thread is started, so
/// that every thread inherits the blocked signals (see the module doc). A
/// second signal while cleaning up is ignored.
pub fn install() {
    INSTALL.call_once(|| {
        let set = termination_set();
        // SAFETY: changes this thread's signal mask only.
        let rc = unsafe { libc::pthread_sigmask(libc::SIG_BLOCK, &set, std::ptr::null_mut()) };
        if rc != 0 {
            eprintln!(
                "warning: no cleanup on Ctrl-C (signal mask: error {rc}); the next run clears what this one leaves"
            );
            return;
        }
        let (tx, rx) = std::sync::mpsc::channel();
        let spawned = std::thread::Builder::new()
            .name("signals".into())
            .spawn(move || {
                // SAFETY: pthread_self has no preconditions.
                let _ = tx.send(unsafe { libc::pthread_self() } as u64);
                loop {
                    let mut sig: libc::c_int = 0;
                    // SAFETY: `set` is blocked in this thread (inherited).
                    if unsafe { libc::sigwait(&set, &mut sig) } == 0 {
                        stop();
                    }
                }
            });
        let Ok(t) = spawned.map_err(|e| e.to_string()).and_then(|_| rx.recv().map_err(|e| e.to_string())) else {
            eprintln!("warning: no cleanup on Ctrl-C (no signal thread); the next run clears what this one leaves");
            return;
        };
        SIGNAL_THREAD.store(t, Ordering::SeqCst);
        for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
            // SAFETY: installs `forward`, which only calls pthread_kill.
            unsafe {
                let mut act: libc::sigaction = std::mem::zeroed();
                act.sa_sigaction = forward as *const () as usize;
                act.sa_flags = libc::SA_RESTART;
                libc::sigemptyset(&mut act.sa_mask);
                libc::sigaction(sig, &act, std::ptr::null_mut());
            }
        }
    });
}

/// Runs `cmd` to completion as [`std::process::Command::output`] does, as
/// a child that receives the termination signals ([`child`]) and that a
/// stopped run kills ([`pending_process`]): for a child that writes this
/// run's output (a converter writing a temporary file).
pub fn output(cmd: &mut std::process::Command) -> std::io::Result<std::process::Output> {
    let spawned = child(cmd)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()?;
    let _on_interrupt = pending_process(spawned.id());
    spawned.wait_with_output()
}

/// Lets a child process receive SIGINT, SIGTERM and SIGHUP again (a
/// child inherits the blocked mask of the thread that starts it).
pub fn child(cmd: &mut std::process::Command) -> &mut std::process::Command {
    use std::os::unix::process::CommandExt;
    // SAFETY: between fork and exec only pthread_sigmask (async-signal-safe)
    // runs, on a set built before the fork.
    let set = termination_set();
    unsafe {
        cmd.pre_exec(move || {
            libc::pthread_sigmask(libc::SIG_UNBLOCK, &set, std::ptr::null_mut());
            Ok(())
        })
    }
}
