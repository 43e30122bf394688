//! The local executor on the small pair (6 × 10 reduced meshes): the
//! study gives what its stages give when run by hand; a job that fails
//! stops its dependents, and `collect` names it and writes nothing; two
//! studies sharing a design run the design's jobs once. Long tier
//! (`make test-long`): about 2 min with the meshes made.

mod support;

use std::path::Path;
use std::process::Command;
use std::sync::Mutex;
use support::{base_scene, build_programs, meshes_root, s, study, study_file, study_ok};

/// The tests share the mesh root: one at a time.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn args<'a>(
    cmd: &'a str,
    file: &'a Path,
    work: &'a Path,
    meshes: &'a Path,
    bin: &'a Path,
) -> Vec<&'a str> {
    vec![
        cmd,
        s(file),
        "--work",
        s(work),
        "--meshes",
        s(meshes),
        "--bin",
        s(bin),
    ]
}

#[test]
fn local_study_gives_what_its_stages_give_by_hand() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    build_programs();
    let tmp = tempfile::tempdir().unwrap();
    let scene = base_scene(tmp.path());
    let file = study_file(
        tmp.path(),
        "by_hand",
        &scene,
        "[\"ltca\", \"reference\"]",
        "[0.0, 0.05]",
        2,
    );
    let (meshes, bin, work) = (meshes_root(), support::bin_dir(), tmp.path().join("work"));
    study_ok(&args("submit", &file, &work, &meshes, &bin));
    study_ok(&args("collect", &file, &work, &meshes, &bin));
    // Each case by hand: its scene (as the study wrote it) through
    // `solver ltca` and a `validate reference` without shards.
    let cases: Vec<_> = std::fs::read_dir(work.join("scenes"))
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("case_")
        })
        .collect();
    assert_eq!(cases.len(), 2);
    for case in cases {
        let key = case
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .trim_start_matches("case_")
            .to_string();
        let hand = tmp.path().join("hand").join(&key);
        for (program, a) in [
            (
                "solver",
                vec!["ltca", s(&case), "--meshes", s(&meshes), "--out", s(&hand)],
            ),
            (
                "validate",
                vec![
                    "reference",
                    s(&case),
                    "--meshes",
                    s(&meshes),
                    "--out",
                    s(&hand),
                    "--level",
                    "reduced",
                ],
            ),
        ] {
            let out = Command::new(bin.join(program)).args(&a).output().unwrap();
            assert!(
                out.status.success(),
                "{program} {a:?}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        let from_study = work.join("cases").join(&key).join("study_small");
        for f in [
            "ltca/standard_standard/te.csv",
            "reference/standard_standard/te.csv",
        ] {
            let (a, b) = (
                std::fs::read(from_study.join(f)).unwrap(),
                std::fs::read(hand.join("study_small").join(f)).unwrap(),
            );
            assert!(
                a == b,
                "case {key}: {f} of the study differs from the stage run by hand"
            );
        }
    }
}

#[test]
fn failed_job_stops_its_dependents_and_collect_names_it_and_writes_nothing() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    build_programs();
    let tmp = tempfile::tempdir().unwrap();
    // The project's programs, but a solver that fails.
    let bin = tmp.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    for p in ["preprocess", "validate", "study"] {
        std::os::unix::fs::symlink(support::bin_dir().join(p), bin.join(p)).unwrap();
    }
    let solver = bin.join("solver");
    std::fs::write(
        &solver,
        "#!/bin/sh\necho 'solver: made to fail by the test' >&2\nexit 3\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&solver, std::fs::Permissions::from_mode(0o755)).unwrap();
    let scene = base_scene(tmp.path());
    let file = study_file(tmp.path(), "fails", &scene, "[\"ltca\"]", "[0.0, 0.05]", 1);
    let (meshes, work) = (meshes_root(), tmp.path().join("work"));
    let out = study(&args("submit", &file, &work, &meshes, &bin));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!out.status.success());
    assert!(text.contains("2 failed"), "{text}");
    let c = study(&args("collect", &file, &work, &meshes, &bin));
    let err = String::from_utf8_lossy(&c.stderr);
    assert!(!c.status.success());
    assert!(err.contains("2 of 4 jobs are not done"), "{err}");
    assert!(err.contains("loaded TCA: failed (exit code 3)"), "{err}");
    let log = err
        .lines()
        .find(|l| l.contains("failed (exit code 3)"))
        .and_then(|l| l.split("(log ").nth(1))
        .map(|l| l.trim_end_matches(')').to_string())
        .unwrap();
    assert!(std::fs::read_to_string(log)
        .unwrap()
        .contains("made to fail by the test"));
    assert!(!work.join("results").join("fails").exists());
}

#[test]
fn two_studies_sharing_a_design_run_its_jobs_once() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    build_programs();
    let tmp = tempfile::tempdir().unwrap();
    let scene = base_scene(tmp.path());
    let a = study_file(tmp.path(), "first", &scene, "[\"ltca\"]", "[0.0]", 1);
    let b = study_file(tmp.path(), "second", &scene, "[\"ltca\"]", "[0.0, 0.05]", 1);
    let (meshes, bin, work) = (meshes_root(), support::bin_dir(), tmp.path().join("work"));
    let first = study_ok(&args("submit", &a, &work, &meshes, &bin));
    assert!(first.contains("0 jobs done before, 3 run now"), "{first}");
    let second = study_ok(&args("submit", &b, &work, &meshes, &bin));
    // The mesh, the stiffness files and the aligned case's LTCA are the
    // first study's: only the new case runs.
    assert!(second.contains("3 jobs done before, 1 run now"), "{second}");
    let runs_in = |label: &str| {
        let plan = study_ok(&args("plan", &b, &work, &meshes, &bin));
        let key = plan
            .lines()
            .find(|l| l.ends_with(label))
            .and_then(|l| l.split_whitespace().next())
            .unwrap()
            .to_string();
        let log = std::fs::read_to_string(work.join("jobs").join(key).join("log.txt")).unwrap();
        log.lines()
            .filter(|l| l.starts_with("== ") && l.contains(" on "))
            .count()
    };
    assert_eq!(runs_in("study_small: mesh reduced"), 1);
    assert_eq!(runs_in("study_small: stiffness files"), 1);
}
