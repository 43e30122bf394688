//! Named points of a run where the signal tests stop it: the phases of a
//! stage (reading its inputs and factoring, solving, writing a file,
//! committing a result set, the moment after the commit) are marked with
//! [`at`], so that a test can send SIGINT or SIGTERM to a real binary at a
//! known phase instead of after a guessed delay, and check that the run
//! leaves nothing behind there.
//!
//! Inert unless the environment variable [`STOP_AT`] names the phase: then
//! the first time the run reaches it, it writes the file named by
//! [`STOP_READY`] and waits up to [`WAIT_S`] seconds to be stopped (and
//! goes on with a warning if it is not). One environment lookup per process.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// The environment variable naming the phase to wait at.
pub const STOP_AT: &str = "GEARS_STOP_AT";
/// The environment variable naming the file written on arrival.
pub const STOP_READY: &str = "GEARS_STOP_READY";
/// How long a run waits at its stop point, s.
pub const WAIT_S: u64 = 120;

/// The phases the stages mark.
pub const PHASES: [&str; 5] = ["reading", "solving", "writing", "committing", "committed"];

static WANTED: OnceLock<Option<(String, PathBuf)>> = OnceLock::new();
static REACHED: AtomicBool = AtomicBool::new(false);

/// Marks `phase` (one of [`PHASES`]); waits there if [`STOP_AT`] asks.
pub fn at(phase: &str) {
    debug_assert!(PHASES.contains(&phase), "unknown phase {phase}");
    let wanted = WANTED.get_or_init(|| {
        let p = std::env::var(STOP_AT).ok()?;
        let ready = std::env::var(STOP_READY).ok()?;
        Some((p, PathBuf::from(ready)))
    });
    let Some((p, ready)) = wanted else {
        return;
    };
    if p != phase || REACHED.swap(true, Ordering::SeqCst) {
        return;
    }
    if let Err(e) = std::fs::write(ready, phase) {
        eprintln!(
            "warning: stop point {phase}: cannot write {}: {e}",
            ready.display()
        );
    }
    std::thread::sleep(std::time::Duration::from_secs(WAIT_S));
    eprintln!("warning: stop point {phase}: not stopped within {WAIT_S} s, going on");
}
