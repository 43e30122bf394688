//! The signal matrix's parent side, shared by the binaries' signal tests
//! (`preprocess stiffness`, `solver dynamic`, `validate reference`): a real
//! binary is started with its stop point at one phase
//! ([`formats::stop_point`]), sent SIGINT or SIGTERM once there, and must
//! exit with 130; the caller then compares what the watched folder holds
//! with what it held before ([`tree`]).

#![allow(dead_code)]

use formats::stop_point::{STOP_AT, STOP_READY};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

/// Everything under `dir`: relative path → file bytes (`None` for a
/// directory, so that an empty folder left behind shows too).
pub fn tree(dir: &Path) -> BTreeMap<PathBuf, Option<Vec<u8>>> {
    fn walk(root: &Path, d: &Path, t: &mut BTreeMap<PathBuf, Option<Vec<u8>>>) {
        for e in std::fs::read_dir(d).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(root).unwrap().to_path_buf();
            if p.is_dir() {
                t.insert(rel, None);
                walk(root, &p, t);
            } else {
                t.insert(rel, Some(std::fs::read(&p).unwrap()));
            }
        }
    }
    let mut t = BTreeMap::new();
    if dir.exists() {
        walk(dir, dir, &mut t);
    }
    t
}

/// The paths of `after` not in `before` or with other bytes, and those of
/// `before` gone: what a run changed.
pub fn changed(
    before: &BTreeMap<PathBuf, Option<Vec<u8>>>,
    after: &BTreeMap<PathBuf, Option<Vec<u8>>>,
) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = after
        .iter()
        .filter(|(p, b)| before.get(*p) != Some(*b))
        .map(|(p, _)| p.clone())
        .collect();
    v.extend(before.keys().filter(|p| !after.contains_key(*p)).cloned());
    v.sort();
    v
}

/// Names of what a run must never leave behind: staging folders, old
/// copies, locks, temporary files.
pub fn leftovers(t: &BTreeMap<PathBuf, Option<Vec<u8>>>) -> Vec<PathBuf> {
    t.keys()
        .filter(|p| {
            let n = p.file_name().unwrap().to_string_lossy();
            n.contains(".staging.")
                || n.contains(".old.")
                || n.ends_with(".lock")
                || n.starts_with(".tmp")
        })
        .cloned()
        .collect()
}

/// Runs `cmd` with its stop point at `phase`, sends `signal` (`kill`'s
/// option, e.g. "-TERM") once the run is there, and checks the exit code
/// 130. The readiness marker and the run's stderr go into `scratch`, which
/// must lie outside the folders the caller compares.
pub fn stop_at(mut cmd: Command, phase: &str, signal: &str, scratch: &Path) {
    let ready = scratch.join(format!("ready_{phase}{signal}"));
    let log = scratch.join(format!("stderr_{phase}{signal}"));
    let _ = std::fs::remove_file(&ready);
    cmd.env(STOP_AT, phase)
        .env(STOP_READY, &ready)
        .stdout(std::process::Stdio::null())
        .stderr(std::fs::File::create(&log).unwrap());
    let mut child = cmd.spawn().unwrap();
    let t0 = Instant::now();
    let stderr = || std::fs::read_to_string(&log).unwrap_or_default();
    while !ready.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            panic!(
                "the run ended ({status}) before reaching phase {phase}; its stderr:\n{}",
                stderr()
            );
        }
        assert!(
            t0.elapsed() < Duration::from_secs(600),
            "phase {phase} not reached within 600 s; stderr:\n{}",
            stderr()
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(
        code,
        Some(130),
        "exit status after {signal} at {phase}; stderr:\n{}",
        stderr()
    );
}

/// What a run stopped at `phase` must leave in `root` (snapshots `before`
/// and `after`): before the commit, `root` exactly as it was; once
/// committed, only `set` (relative to `root`) changed, holding a set whose
/// files verify, and nothing left behind.
pub fn check_left(
    root: &Path,
    set: &Path,
    phase: &str,
    before: &BTreeMap<PathBuf, Option<Vec<u8>>>,
    after: &BTreeMap<PathBuf, Option<Vec<u8>>>,
) {
    assert_eq!(
        leftovers(after),
        Vec::<PathBuf>::new(),
        "left behind at {phase}"
    );
    let changed = changed(before, after);
    if phase != "committed" {
        assert_eq!(
            changed,
            Vec::<PathBuf>::new(),
            "changed by a run stopped at {phase}"
        );
        return;
    }
    let outside: Vec<&PathBuf> = changed.iter().filter(|p| !p.starts_with(set)).collect();
    assert!(
        outside.is_empty(),
        "changed outside the set at {phase}: {outside:?}"
    );
    assert!(!changed.is_empty(), "the committed set is the previous one");
    formats::result_set::verify_files(&root.join(set))
        .expect("the committed set verifies")
        .expect("the committed set has run.json");
}
