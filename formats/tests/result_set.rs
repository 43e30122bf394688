//! `formats::result_set`: a stage's output directory written as one set.
//! Each test is named after the case it tries; all run in milliseconds.

use formats::result_set::{
    host, lock_path, utc, Holder, ResultSet, ResultSetError, RunInfo, RunLock, RUN_FILE,
};
use std::path::{Path, PathBuf};

#[path = "support/tree.rs"]
mod tree;
use tree::{files, names};

/// A committed set with `a/one.csv` holding `text`.
fn commit_set(dir: &Path, text: &str) -> RunInfo {
    let set = ResultSet::begin(dir, "test run").unwrap();
    std::fs::create_dir_all(set.path().join("a")).unwrap();
    std::fs::write(set.path().join("a/one.csv"), text).unwrap();
    set.commit().unwrap()
}

/// A pid that no longer runs: a child that has exited and been waited for.
fn dead_pid() -> u32 {
    let mut c = std::process::Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    pid
}

fn holder(pid: u32, process_start: Option<u64>) -> Holder {
    Holder {
        pid,
        host: host(),
        started_utc: "2020-01-01T00:00:00Z".into(),
        command: "solver ltca killed.toml".into(),
        what: "solver ltca killed.toml".into(),
        process_start,
        token: "old".into(),
    }
}

#[test]
fn a_committed_set_replaces_the_previous_one_whole_and_is_stamped_with_run_json() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    commit_set(&dir, "first");
    // The second run writes another file set: nothing of the first stays.
    let set = ResultSet::begin(&dir, "second run").unwrap();
    assert_eq!(set.dir(), dir);
    assert_eq!(
        set.final_path(&set.path().join("b/two.csv")),
        dir.join("b/two.csv")
    );
    std::fs::create_dir_all(set.path().join("b")).unwrap();
    std::fs::write(set.path().join("b/two.csv"), "second").unwrap();
    let info = set.commit().unwrap();
    let got: Vec<PathBuf> = files(&dir).into_iter().map(|(p, _)| p).collect();
    assert_eq!(got, [PathBuf::from("b/two.csv"), PathBuf::from(RUN_FILE)]);
    let stamp: RunInfo =
        serde_json::from_str(&std::fs::read_to_string(dir.join(RUN_FILE)).unwrap()).unwrap();
    assert_eq!(stamp, info);
    assert_eq!(stamp.what, "second run");
    assert_eq!(stamp.pid, std::process::id());
    // Nothing left beside the set: no lock, no staging, no old copy.
    assert_eq!(names(tmp.path()), ["ltca"]);
}

#[test]
fn a_run_that_fails_midway_leaves_the_previous_set_untouched_and_no_staging_dir() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    commit_set(&dir, "complete");
    let before = files(&dir);
    let r: Result<(), String> = (|| {
        let set = ResultSet::begin(&dir, "failing run").map_err(|e| e.to_string())?;
        std::fs::create_dir_all(set.path().join("a")).unwrap();
        std::fs::write(set.path().join("a/one.csv"), "half").unwrap();
        Err("the second blank failed".into())
    })();
    assert!(r.is_err());
    assert_eq!(files(&dir), before, "the previous set changed");
    assert_eq!(names(tmp.path()), ["ltca"]);
}

#[test]
fn a_second_begin_on_one_dir_is_refused_naming_the_first_run_and_the_lock() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("multibody");
    let first = ResultSet::begin(&dir, "solver dynamic first.toml").unwrap();
    let err = ResultSet::begin(&dir, "solver dynamic second.toml").unwrap_err();
    let msg = err.to_string();
    let ResultSetError::Busy { holder, lock, .. } = &err else {
        panic!("{msg}")
    };
    assert_eq!(lock, &lock_path(&dir));
    assert_eq!(holder.pid, std::process::id());
    for part in [
        format!("pid {}", std::process::id()),
        holder.started_utc.clone(),
        "solver dynamic first.toml".to_string(),
        lock_path(&dir).display().to_string(),
        dir.display().to_string(),
    ] {
        assert!(msg.contains(&part), "{part:?} not in: {msg}");
    }
    // The refused run touched nothing of the first's.
    assert!(first.path().is_dir());
    drop(first);
    assert_eq!(names(tmp.path()), Vec::<String>::new());
    // Released: the next run may begin.
    ResultSet::begin(&dir, "third").unwrap();
}

#[test]
fn a_stale_lock_of_a_dead_process_is_taken_over_and_its_staging_dir_removed() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    commit_set(&dir, "complete");
    let before = files(&dir);
    let pid = dead_pid();
    std::fs::write(
        lock_path(&dir),
        serde_json::to_string(&holder(pid, None)).unwrap(),
    )
    .unwrap();
    let leftover = tmp.path().join(format!("ltca.staging.{pid}.0"));
    std::fs::create_dir_all(leftover.join("a")).unwrap();
    std::fs::write(leftover.join("a/one.csv"), "half").unwrap();

    let set = ResultSet::begin(&dir, "next run").unwrap();
    assert!(!leftover.exists(), "the killed run's staging dir is left");
    assert_eq!(files(&dir), before, "the previous set changed");
    let lock: Holder =
        serde_json::from_str(&std::fs::read_to_string(lock_path(&dir)).unwrap()).unwrap();
    assert_eq!(lock.pid, std::process::id());
    drop(set);
    assert_eq!(names(tmp.path()), ["ltca"]);
}

#[test]
fn a_lock_whose_pid_was_reused_by_another_process_is_stale() {
    if !Path::new("/proc/self/stat").exists() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    // This process's pid, but another process start time.
    std::fs::write(
        lock_path(&dir),
        serde_json::to_string(&holder(std::process::id(), Some(1))).unwrap(),
    )
    .unwrap();
    ResultSet::begin(&dir, "next run").unwrap();
}

#[test]
fn a_lock_from_another_host_is_not_taken_over() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    let h = Holder {
        host: format!("{}-elsewhere", host()),
        ..holder(dead_pid(), None)
    };
    std::fs::write(lock_path(&dir), serde_json::to_string(&h).unwrap()).unwrap();
    let msg = ResultSet::begin(&dir, "next run").unwrap_err().to_string();
    assert!(
        msg.contains("elsewhere") && msg.contains("remove the lock"),
        "{msg}"
    );
}

#[test]
fn an_unwritable_output_is_refused_at_begin_naming_the_path() {
    let tmp = tempfile::tempdir().unwrap();
    // A parent that is a file.
    let file = tmp.path().join("out");
    std::fs::write(&file, "").unwrap();
    let dir = file.join("scene/ltca");
    let err = ResultSet::begin(&dir, "run").unwrap_err();
    assert!(matches!(&err, ResultSetError::Unwritable { .. }), "{err:?}");
    assert!(
        err.to_string()
            .contains(&file.join("scene").display().to_string()),
        "{err}"
    );
    // The output itself is a file.
    let err = ResultSet::begin(&file, "run").unwrap_err();
    assert!(
        err.to_string().contains(&file.display().to_string()),
        "{err}"
    );
    assert!(!lock_path(&file).exists());
    // A read-only parent (not for root, who may write anyway).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let ro = tmp.path().join("ro");
        std::fs::create_dir(&ro).unwrap();
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
        if std::fs::write(ro.join("probe"), "").is_err() {
            let err = ResultSet::begin(&ro.join("ltca"), "run").unwrap_err();
            assert!(err.to_string().contains(&ro.display().to_string()), "{err}");
        }
        std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
}

#[test]
fn temporary_names_are_unique_per_process_and_per_set() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    let a = ResultSet::begin(&dir, "a").unwrap();
    let a_path = a.path().to_path_buf();
    drop(a);
    let b = ResultSet::begin(&dir, "b").unwrap();
    let other = ResultSet::begin(&tmp.path().join("multibody"), "c").unwrap();
    let pid = std::process::id();
    for p in [&a_path, b.path(), other.path()] {
        let n = p.file_name().unwrap().to_string_lossy();
        assert!(n.contains(&format!(".staging.{pid}.")), "{n}");
    }
    assert_ne!(a_path, b.path());
    // Each begin's lock is its own: a released set does not release another.
    let la: Holder =
        serde_json::from_str(&std::fs::read_to_string(lock_path(&dir)).unwrap()).unwrap();
    let lb: Holder = serde_json::from_str(
        &std::fs::read_to_string(lock_path(&tmp.path().join("multibody"))).unwrap(),
    )
    .unwrap();
    assert_ne!(la.token, lb.token);
}

#[test]
fn shared_runs_may_work_side_by_side_but_not_beside_an_exclusive_run() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("reference");
    let s1 = RunLock::shared(&dir, "shard 0/2").unwrap();
    let s2 = RunLock::shared(&dir, "shard 1/2").unwrap();
    assert_ne!(s1.path(), s2.path());
    let msg = ResultSet::begin(&dir, "full run").unwrap_err().to_string();
    assert!(msg.contains("shard"), "{msg}");
    // The refused run left no lock of its own behind.
    assert!(!lock_path(&dir).exists());
    drop((s1, s2));
    let full = RunLock::exclusive(&dir, "full run").unwrap();
    let msg = RunLock::shared(&dir, "shard 0/2").unwrap_err().to_string();
    assert!(msg.contains("full run"), "{msg}");
    drop(full);
    // A dead shard's marker does not hold a full run back.
    let marker = tmp
        .path()
        .join(format!("reference.shared.{}.0.lock", dead_pid()));
    std::fs::write(
        &marker,
        serde_json::to_string(&holder(dead_pid(), None)).unwrap(),
    )
    .unwrap();
    RunLock::exclusive(&dir, "full run").unwrap();
    assert!(!marker.exists());
}

#[test]
fn a_commit_killed_between_its_renames_gets_the_previous_set_back() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ltca");
    commit_set(&dir, "complete");
    let before = files(&dir);
    let pid = dead_pid();
    // As a run killed after moving the old set aside.
    std::fs::rename(&dir, tmp.path().join(format!("ltca.old.{pid}.3"))).unwrap();
    std::fs::create_dir(tmp.path().join(format!("ltca.staging.{pid}.2"))).unwrap();
    drop(ResultSet::begin(&dir, "next run").unwrap());
    assert_eq!(files(&dir), before);
    assert_eq!(names(tmp.path()), ["ltca"]);
}

#[test]
fn utc_names_the_date() {
    let t = std::time::UNIX_EPOCH + std::time::Duration::from_secs(1_700_000_000);
    assert_eq!(utc(t), "2023-11-14T22:13:20Z");
}

#[test]
fn a_carried_over_cache_outlives_the_set_it_was_written_beside() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("reference");
    commit_set(&dir, "first");
    // A cache written in place (as shards do), beside the committed set.
    std::fs::create_dir_all(dir.join("a/positions/k")).unwrap();
    std::fs::write(dir.join("a/positions/k/phi_0udeg.json"), "{}").unwrap();
    let mut set = ResultSet::begin(&dir, "second").unwrap();
    std::fs::create_dir_all(set.path().join("a")).unwrap();
    std::fs::write(set.path().join("a/one.csv"), "second").unwrap();
    set.carry_over(Path::new("a/positions"));
    set.carry_over(Path::new("absent/positions"));
    set.commit().unwrap();
    let got: Vec<PathBuf> = files(&dir).into_iter().map(|(p, _)| p).collect();
    assert_eq!(
        got,
        [
            PathBuf::from("a/one.csv"),
            PathBuf::from("a/positions/k/phi_0udeg.json"),
            PathBuf::from(RUN_FILE)
        ]
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("a/one.csv")).unwrap(),
        "second"
    );
}

#[test]
fn one_input_recorded_with_two_hashes_in_one_run_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let mut set = ResultSet::begin(&tmp.path().join("out"), "test run").unwrap();
    set.record_input("design", "aa").unwrap();
    set.record_input("design", "aa").unwrap();
    let err = set.record_input("design", "bb").unwrap_err();
    assert!(matches!(err, ResultSetError::TwoInputs { .. }), "{err}");
    let info = set.commit().unwrap();
    assert_eq!(info.inputs.get("design").map(String::as_str), Some("aa"));
}

#[test]
fn sets_sharing_no_input_or_the_same_hashes_pass_and_a_differing_one_is_named() {
    use formats::result_set::check_same_inputs;
    let tmp = tempfile::tempdir().unwrap();
    let stamp = |name: &str, inputs: &[(&str, &str)]| {
        let dir = tmp.path().join(name);
        let mut set = ResultSet::begin(&dir, name).unwrap();
        for (k, v) in inputs {
            set.record_input(k, v).unwrap();
        }
        set.commit().unwrap();
        dir
    };
    let a = stamp("a", &[("design", "d1"), ("mesh:p", "m1")]);
    let b = stamp("b", &[("design", "d1"), ("stiffness:p", "s1")]);
    let c = stamp("c", &[("other", "x")]);
    let missing = tmp.path().join("never_run");
    check_same_inputs(&[&a, &b, &c, &missing]).unwrap();
    let d = stamp("d", &[("mesh:p", "m2")]);
    let err = check_same_inputs(&[&a, &b, &d]).unwrap_err().to_string();
    assert!(
        err.contains("mesh:p") && err.contains("m1") && err.contains("m2"),
        "{err}"
    );
}

#[test]
fn a_committed_file_changed_or_removed_afterwards_is_named_by_the_reader_check() {
    use formats::result_set::verify_files;
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let info = commit_set(&dir, "te");
    assert_eq!(info.files.keys().collect::<Vec<_>>(), ["a/one.csv"]);
    assert_eq!(verify_files(&dir).unwrap(), Some(info));
    // A file added in place later is not the run's: not checked.
    std::fs::write(dir.join("later.json"), "{}").unwrap();
    assert!(verify_files(&dir).is_ok());
    std::fs::write(dir.join("a/one.csv"), "tf").unwrap();
    let e = verify_files(&dir).unwrap_err().to_string();
    assert!(e.contains("one.csv") && e.contains("changed"), "{e}");
    std::fs::remove_file(dir.join("a/one.csv")).unwrap();
    let e = verify_files(&dir).unwrap_err().to_string();
    assert!(e.contains("removed"), "{e}");
    assert_eq!(verify_files(&tmp.path().join("never")).unwrap(), None);
}

#[test]
fn a_set_whose_stamp_was_deleted_is_refused_by_the_reader_check() {
    use formats::result_set::verify_files;
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    commit_set(&dir, "te");
    // Without its stamp nothing vouches for the files: a replaced one
    // would go through unnoticed, so the set is refused, naming it.
    std::fs::remove_file(dir.join(RUN_FILE)).unwrap();
    std::fs::write(dir.join("a/one.csv"), "replaced").unwrap();
    let e = verify_files(&dir).unwrap_err();
    assert!(matches!(e, ResultSetError::Unstamped { .. }), "{e}");
    let e = e.to_string();
    assert!(e.contains("run.json") && e.contains("out"), "{e}");
    // An empty folder holds no results to vouch for.
    let empty = tmp.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    assert_eq!(verify_files(&empty).unwrap(), None);
}

#[test]
fn one_file_is_checked_against_the_nearest_stamped_folder_above_it() {
    use formats::result_set::verify_file;
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("out");
    let info = commit_set(&dir, "te");
    let file = dir.join("a/one.csv");
    assert_eq!(verify_file(&file).unwrap(), Some(info.clone()));
    // Added in place later: not the run's file, passes with the set's stamp.
    std::fs::write(dir.join("a/later.svg"), "<svg/>").unwrap();
    assert_eq!(verify_file(&dir.join("a/later.svg")).unwrap(), Some(info));
    // Missing: nothing to vouch for.
    assert_eq!(verify_file(&dir.join("a/none.csv")).unwrap(), None);
    std::fs::write(&file, "tf").unwrap();
    let e = verify_file(&file).unwrap_err().to_string();
    assert!(e.contains("one.csv") && e.contains("changed"), "{e}");
    std::fs::remove_file(dir.join(RUN_FILE)).unwrap();
    let e = verify_file(&file).unwrap_err();
    assert!(matches!(e, ResultSetError::Unstamped { .. }), "{e}");
}

#[test]
fn a_commit_that_fails_keeps_the_new_results_where_its_message_says() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("reference");
    commit_set(&dir, "first");
    // A carried-over entry that cannot move into the new set: its parent
    // in the staging directory is a file.
    std::fs::create_dir_all(dir.join("cache")).unwrap();
    std::fs::write(dir.join("cache/x.json"), "{}").unwrap();
    let mut set = ResultSet::begin(&dir, "second").unwrap();
    std::fs::write(set.path().join("cache"), "not a folder").unwrap();
    std::fs::create_dir_all(set.path().join("a")).unwrap();
    std::fs::write(set.path().join("a/one.csv"), "second").unwrap();
    set.carry_over(Path::new("cache/x.json"));
    let e = set.commit().unwrap_err();
    let ResultSetError::Commit { staging, .. } = &e else {
        panic!("expected a commit error, got {e}")
    };
    assert!(
        e.to_string().contains(&staging.display().to_string()),
        "{e}"
    );
    assert_eq!(
        std::fs::read_to_string(staging.join("a/one.csv")).unwrap(),
        "second",
        "the new results are where the message says"
    );
    // The previous set and its cache are untouched.
    assert_eq!(
        std::fs::read_to_string(dir.join("a/one.csv")).unwrap(),
        "first"
    );
    assert!(dir.join("cache/x.json").exists());
    // The next run on the folder clears the leftover staging directory
    // of this (finished) run only once its process is gone; ours is alive,
    // so here it is still there.
    assert!(staging.exists());
}
