//! The signal tests' parent side, shared by the test binaries that stop a
//! real child process: a previous committed result set in a temporary
//! folder, the child started on that folder, signalled once it has written
//! `<dir>/ready` (and `settle` later), then checked: exit 130, nothing of
//! the child's run left beside the previous set and the marker, the
//! previous set as it was.

use formats::result_set::{lock_path, ResultSet, RUN_FILE};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Runs `child(dir)` against a previous set in `dir/out`, sends `signal`
/// (`kill`'s option, e.g. "-TERM") once it is ready, and checks the result.
pub fn stop_child_and_check(
    child: impl Fn(&Path) -> Command,
    signal: &str,
    ready_within: Duration,
    settle: Duration,
) {
    stop_child_and_check_with(child, signal, ready_within, settle, |_| {});
}

/// [`stop_child_and_check`], with `before_signal(dir)` run once the child
/// is ready (to read what it wrote into its readiness marker).
pub fn stop_child_and_check_with(
    child: impl Fn(&Path) -> Command,
    signal: &str,
    ready_within: Duration,
    settle: Duration,
    before_signal: impl Fn(&Path),
) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // A previous committed set with its own results.
    let previous = ResultSet::begin(&dir.join("out"), "previous run").unwrap();
    std::fs::write(previous.path().join("te.csv"), "previous").unwrap();
    previous.commit().unwrap();
    let mut child = child(dir).spawn().unwrap();
    let t0 = Instant::now();
    while !dir.join("ready").exists() {
        assert!(t0.elapsed() < ready_within, "child never got ready");
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(settle);
    before_signal(dir);
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
