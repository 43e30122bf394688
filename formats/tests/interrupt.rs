//! `formats::interrupt`: a run stopped by Ctrl-C or SIGTERM leaves no
//! staging directory, lock or temporary file, and the previous results as
//! they were. The signal cases run a real child process (this test binary
//! again, in its child mode) and signal it.

use formats::result_set::{lock_path, ResultSet, RUN_FILE};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

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

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn stopped_by(signal: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // A previous committed set with its own results.
    let previous = ResultSet::begin(&dir.join("out"), "previous run").unwrap();
    std::fs::write(previous.path().join("te.csv"), "previous").unwrap();
    previous.commit().unwrap();

    let mut child = Command::new(std::env::current_exe().unwrap())
        .args(["--exact", "child_begins_a_set_and_waits", "--nocapture"])
        .env("INTERRUPT_CHILD", dir)
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !dir.join("ready").exists() {
        assert!(
            t0.elapsed() < Duration::from_secs(30),
            "child never got ready"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(lock_path(&dir.join("out")).exists());
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130), "exit status after {signal}");
    // Only the previous set and the readiness marker are left.
    assert_eq!(entries(dir), ["out", "ready"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("out/te.csv")).unwrap(),
        "previous"
    );
    assert!(dir.join("out").join(RUN_FILE).exists());
}

#[test]
fn ctrl_c_removes_the_staging_directory_lock_and_temporary_file() {
    stopped_by("-INT");
}

#[test]
fn sigterm_removes_the_staging_directory_lock_and_temporary_file() {
    stopped_by("-TERM");
}
