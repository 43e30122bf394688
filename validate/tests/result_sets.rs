//! `validate reference` writes its results as one set and keeps its
//! position cache shared (see `validate::reference::reference_stage`): the cases that
//! end before any mesh is read, so no meshes are made (milliseconds). The
//! cache across shards, a full run and `--compare-cache` is tried by
//! `reference_sweep.rs`.

use formats::result_set::{lock_path, Holder, ResultSet, RunLock};
use geometry::scene::{LoadedScene, Scene};
use std::path::{Path, PathBuf};
use validate::reference::reference_options::StageOptions;
use validate::reference::reference_stage::{reference_dir, run};
#[path = "support/reference_options.rs"]
mod reference_options;

/// The small scene, reference on, written into `dir`.
fn scene(dir: &Path) -> LoadedScene {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference");
    let text = std::fs::read_to_string(root.join("scenes/small.toml")).unwrap();
    let head = text.split("[analyses]").next().unwrap();
    let design = root.join("white_paper_20x43.toml");
    let head = head.replace(
        "design = \"../white_paper_20x43.toml\"",
        &format!("design = {:?}", design.to_str().unwrap()),
    );
    let path = dir.join("scene.toml");
    std::fs::write(
        &path,
        format!(
            "{head}[analyses]\nutca = false\nltca = false\nmultibody = false\nreference = true\n"
        ),
    )
    .unwrap();
    Scene::load(&path).unwrap()
}

#[path = "../../formats/tests/support/tree.rs"]
mod tree;
use tree::{files, names};

/// A previous complete set in `out`, with a position cache beside its
/// results (as a full run leaves it).
fn previous_set(out: &Path) -> PathBuf {
    let dir = reference_dir(out, "small", "reduced");
    let set = ResultSet::begin(&dir, "validate reference earlier").unwrap();
    let b = set.path().join("standard_standard");
    std::fs::create_dir_all(b.join("positions/0123456789abcdef")).unwrap();
    std::fs::write(b.join("te.csv"), "pinion_rotation_deg\n0\n").unwrap();
    std::fs::write(b.join("summary.json"), "{}").unwrap();
    std::fs::write(b.join("positions/0123456789abcdef/phi_0udeg.json"), "{}").unwrap();
    std::fs::write(set.path().join("summary.json"), "[]").unwrap();
    set.commit().unwrap();
    dir
}

#[test]
fn reference_run_that_fails_midway_leaves_the_previous_results_and_the_position_cache() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let dir = previous_set(&out);
    let before = files(&dir);
    // No meshes: the run takes its set, then fails at the first blank.
    let err = run(
        &scene(tmp.path()),
        &tmp.path().join("meshes"),
        &out,
        &reference_options::options(1, None),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("no mesh"), "{err}");
    assert_eq!(files(&dir), before, "the previous results changed");
    assert_eq!(names(&out.join("small")), ["reference"]);
}

#[test]
fn reference_full_run_into_an_output_another_full_run_holds_is_refused_naming_it() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let dir = reference_dir(&out, "small", "reduced");
    let _other = ResultSet::begin(&dir, "validate reference other.toml").unwrap();
    for opt in [
        reference_options::options(1, None),
        StageOptions {
            compare_cache: true,
            ..reference_options::options(1, None)
        },
        reference_options::options(1, Some((0, 2))),
    ] {
        let err = run(&scene(tmp.path()), &tmp.path().join("meshes"), &out, &opt)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("validate reference other.toml")
                && err.contains(&lock_path(&dir).display().to_string()),
            "{err}"
        );
    }
}

#[test]
fn reference_shards_share_the_output_but_a_full_run_waits_for_them() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let dir = reference_dir(&out, "small", "reduced");
    let _shard = RunLock::shared(&dir, "validate reference small.toml --shard 1/2").unwrap();
    // Another shard passes the lock (and stops at the missing meshes).
    let err = run(
        &scene(tmp.path()),
        &tmp.path().join("meshes"),
        &out,
        &reference_options::options(1, Some((0, 2))),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("no mesh"), "{err}");
    // A full run would move the cache the shard writes into: refused.
    let err = run(
        &scene(tmp.path()),
        &tmp.path().join("meshes"),
        &out,
        &reference_options::options(1, None),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("--shard 1/2"), "{err}");
}

#[test]
fn reference_killed_run_lock_is_taken_over_and_its_staging_dir_removed() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let dir = previous_set(&out);
    let before = files(&dir);
    let mut c = std::process::Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    let killed = Holder {
        pid,
        host: formats::result_set::host(),
        started_utc: "2020-01-01T00:00:00Z".into(),
        command: "validate reference small.toml".into(),
        what: "validate reference small.toml".into(),
        process_start: None,
        token: "killed".into(),
    };
    std::fs::write(lock_path(&dir), serde_json::to_string(&killed).unwrap()).unwrap();
    let staging = out.join(format!("small/reference.staging.{pid}.0"));
    std::fs::create_dir_all(staging.join("standard_standard")).unwrap();
    let err = run(
        &scene(tmp.path()),
        &tmp.path().join("meshes"),
        &out,
        &reference_options::options(1, None),
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("no mesh"), "not past the lock: {err}");
    assert_eq!(files(&dir), before);
    assert_eq!(names(&out.join("small")), ["reference"]);
}
