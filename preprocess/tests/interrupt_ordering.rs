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
use formats::result_set::ResultSet;
use signalled_child::stop_child_and_check;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

#[path = "../../formats/tests/support/signalled_child.rs"]
mod signalled_child;

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

fn stopped_while_ordering(signal: &str) {
    let child = |dir: &Path| {
        let mut c = Command::new(std::env::current_exe().unwrap());
        c.env("ORDERING_CHILD", dir);
        c
    };
    // 150 ms into the next orderings.
    stop_child_and_check(
        child,
        signal,
        Duration::from_secs(60),
        Duration::from_millis(150),
    );
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
