//! `formats::interrupt`: a run stopped by Ctrl-C or SIGTERM leaves no
//! staging directory, lock or temporary file, and the previous results as
//! they were. The signal cases run a real child process (this test binary
//! again, in its child mode) and signal it.

#[path = "support/signalled_child.rs"]
mod signalled_child;

use formats::result_set::ResultSet;
use signalled_child::{stop_child_and_check, stop_child_and_check_with};
use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

/// Child mode: with `INTERRUPT_CHILD=<dir>`, begins a set in `<dir>/out`,
/// writes into it, starts a `write_via` into `<dir>/big.h5` and signals
/// readiness with `<dir>/ready`, then waits to be stopped.
#[test]
fn child_begins_a_set_and_waits() {
    let Ok(dir) = std::env::var("INTERRUPT_CHILD") else {
        return;
    };
    let dir = PathBuf::from(dir);
    formats::interrupt::install();
    let set = ResultSet::begin(&dir.join("out"), "interrupted run").unwrap();
    std::fs::write(set.path().join("te.csv"), "half written").unwrap();
    let _ = formats::output::write_via(
        &dir.join("big.h5"),
        |tmp| -> Result<(), formats::output::WriteError> {
            std::fs::write(tmp, "partial").unwrap();
            std::fs::write(dir.join("ready"), "").unwrap();
            std::thread::sleep(Duration::from_secs(60));
            Ok(())
        },
    );
    drop(set);
    panic!("not stopped within 60 s");
}

fn stopped_by(signal: &str) {
    let child = |dir: &std::path::Path| {
        let mut c = Command::new(std::env::current_exe().unwrap());
        c.args(["--exact", "child_begins_a_set_and_waits", "--nocapture"])
            .env("INTERRUPT_CHILD", dir);
        c
    };
    stop_child_and_check(child, signal, Duration::from_secs(30), Duration::ZERO);
}

#[test]
fn ctrl_c_removes_the_staging_directory_lock_and_temporary_file() {
    stopped_by("-INT");
}

#[test]
fn sigterm_removes_the_staging_directory_lock_and_temporary_file() {
    stopped_by("-TERM");
}

/// Child mode: with `INTERRUPT_GRANDCHILD=<dir>`, begins a set in
/// `<dir>/out` and runs a shell as a child of its own
/// ([`formats::interrupt::output`]) that writes its pid into `<dir>/ready`
/// and then sleeps, as a converter writing this run's output would work.
#[test]
fn child_runs_a_grandchild_and_waits() {
    let Ok(dir) = std::env::var("INTERRUPT_GRANDCHILD") else {
        return;
    };
    let dir = PathBuf::from(dir);
    formats::interrupt::install();
    let set = ResultSet::begin(&dir.join("out"), "interrupted run").unwrap();
    let script = format!("echo $$ > {}/ready; sleep 60", dir.display());
    let _ = formats::interrupt::output(Command::new("sh").args(["-c", &script]));
    drop(set);
    panic!("not stopped within 60 s");
}

#[test]
fn sigterm_kills_a_child_process_that_writes_the_run_s_output() {
    let child = |dir: &std::path::Path| {
        let mut c = Command::new(std::env::current_exe().unwrap());
        c.args([
            "--exact",
            "child_runs_a_grandchild_and_waits",
            "--nocapture",
        ])
        .env("INTERRUPT_GRANDCHILD", dir);
        c
    };
    let pid = std::sync::Mutex::new(String::new());
    let check = |dir: &std::path::Path| {
        *pid.lock().unwrap() = std::fs::read_to_string(dir.join("ready")).unwrap();
    };
    stop_child_and_check_with(
        child,
        "-TERM",
        Duration::from_secs(30),
        Duration::from_millis(200),
        check,
    );
    let pid = pid.lock().unwrap().trim().to_string();
    assert!(!pid.is_empty());
    // Killed and reaped by the handler: no process of that id is left.
    assert!(
        !std::path::Path::new(&format!("/proc/{pid}")).exists(),
        "the child process {pid} outlived the stopped run"
    );
}
