//! Example 01 (`examples/01_flanks/`): the flank stage on the small scene's
//! settings (white-paper pair, drive flanks, one mesh cycle at 0.5°), its
//! key numbers against `examples/01_flanks/golden.json`. `BLESS=1` rewrites
//! the golden file.
//!
//! Tolerance: relative 1e-9 on every value, plus an absolute floor for
//! values that can be near zero (1e-12 m on positions, 1e-9 µm / µrad / deg
//! on ease-off, TE and angles). The stage is deterministic: two runs on the
//! same machine agree bit for bit; the tolerance leaves room for other
//! compilers and CPUs only.

#[path = "../../examples/golden.rs"]
mod golden;

#[path = "support/flank_example.rs"]
mod flank_example;

use flank_example::{flank_quantities, num, read, summary_quantities, utca_quantities};
use preprocess::flank_stage::{load_input, run_stage};

#[test]
fn example_01_flanks_matches_its_golden_output() {
    let dir = golden::example_dir(env!("CARGO_MANIFEST_DIR"), "01_flanks");
    let input = load_input(&dir.join("scene.toml")).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("flanks");
    let summary = run_stage(&input, &out).unwrap();

    let mut q = Vec::new();
    // summary.json (also the returned FlankSummary).
    let s = read(&out.join("summary.json"));
    assert_eq!(
        num(&s["utca"]["te_ptp_urad"], "te_ptp"),
        summary.utca.te_ptp_urad
    );
    summary_quantities(&mut q, &s, &summary);

    // utca.json: the roll range, the TE at five positions, the contact path
    // at the middle of the sweep.
    let u = read(&out.join("utca.json"));
    utca_quantities(&mut q, &u);

    // flanks.json: three grid points of the loaded pinion flank (toe-root,
    // middle, heel-tip corner) and the middle of the wheel's loaded flank.
    let grids = read(&out.join("flanks.json"));
    flank_quantities(&mut q, &grids);

    golden::check(
        &dir.join("golden.json"),
        "examples/01_flanks: preprocess::flank_stage::run_stage on examples/01_flanks/scene.toml (test preprocess/tests/example_01_flanks.rs)",
        &q,
    );
}
