//! A stiffness or reference run stopped by SIGTERM or Ctrl-C while METIS
//! orders a body: METIS (GKlib) sets its own SIGTERM handler around every
//! ordering and long-jumps out of it when the signal comes, which used to
//! end such a run with a false "ordering failed" error or exit 143 with the
//! lock and staging folder left behind. The signal must end it like any
//! other: exit 130, nothing of the run left, the previous results intact.
//! A real child process (this binary in its child mode) orders a block's
//! node graph over and over, so the signal lands inside `METIS_NodeND`.
//! The binary has its own `main` (no test harness) so that, as in the
//! project's binaries, `formats::interrupt::install` runs before any other
//! thread exists: a harness's threads run with the signals unblocked, and
//! one taken there during an ordering goes to METIS's handler.

use fem::structured::mapped_block;
use fem::{assemble, Dofs, Material};
use formats::result_set::{lock_path, ResultSet, RUN_FILE};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Child mode (`ORDERING_CHILD=<dir>`): begins a result set in
/// `<dir>/out`, then orders a 12 × 12 × 12 block's stiffness by METIS in a
/// loop, writing `<dir>/ready` after the first ordering.
fn child_orders_until_stopped(dir: PathBuf) {
    let set = ResultSet::begin(&dir.join("out"), "ordering run").unwrap();
    std::fs::write(set.path().join("te.csv"), "half written").unwrap();
    let b = mapped_block([12, 12, 12], |p| p);
    let fixed: Vec<(usize, f64)> = (0..3).map(|c| (c, 0.0)).collect();
    let dofs = Dofs::new(&b.mesh, &fixed).unwrap();
    let mat = Material {
        youngs_modulus_pa: 2.1e11,
        poisson_ratio: 0.3,
    };
    let sys = assemble(&b.mesh, &mat, &dofs).unwrap();
    let node_of = dofs.node_of_free();
    let t0 = Instant::now();
    while t0.elapsed() < Duration::from_secs(60) {
        fem::ordering::nested_dissection(&sys.matrix, &node_of).expect("METIS ordering");
        if !dir.join("ready").exists() {
            std::fs::write(dir.join("ready"), "").unwrap();
        }
    }
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

fn stopped_while_ordering(signal: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let previous = ResultSet::begin(&dir.join("out"), "previous run").unwrap();
    std::fs::write(previous.path().join("te.csv"), "previous").unwrap();
    previous.commit().unwrap();
    let mut child = Command::new(std::env::current_exe().unwrap())
        .env("ORDERING_CHILD", dir)
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !dir.join("ready").exists() {
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "child never got ready"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    // Into the next orderings.
    std::thread::sleep(Duration::from_millis(150));
    assert!(lock_path(&dir.join("out")).exists());
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(
        code,
        Some(130),
        "exit status after {signal} during the ordering"
    );
    assert_eq!(entries(dir), ["out", "ready"]);
    assert_eq!(
        std::fs::read_to_string(dir.join("out/te.csv")).unwrap(),
        "previous"
    );
    assert!(dir.join("out").join(RUN_FILE).exists());
}

fn main() {
    formats::interrupt::install();
    if let Ok(dir) = std::env::var("ORDERING_CHILD") {
        child_orders_until_stopped(PathBuf::from(dir));
        return;
    }
    for (name, signal) in [
        (
            "sigterm_during_metis_ordering_exits_130_and_leaves_nothing",
            "-TERM",
        ),
        (
            "ctrl_c_during_metis_ordering_exits_130_and_leaves_nothing",
            "-INT",
        ),
    ] {
        stopped_while_ordering(signal);
        println!("test {name} ... ok");
    }
}
