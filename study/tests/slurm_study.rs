//! A study on a real Slurm: a one-node cluster started on this machine
//! (scripts/slurm_cluster.sh: munged, slurmctld and slurmd as root, no
//! cgroups), the small pair at two offsets E with the LTCA and the
//! reference sweep in two shards, submitted with `--executor slurm`; one
//! shard cancelled with `scancel` while it runs. Checks that `status`
//! says so, that `collect` refuses and writes nothing, that a resubmission
//! submits only the cancelled shard and the job that waited for it, and
//! that the collected result then equals the local executor's bit for bit.
//! Needs root and Debian's slurmctld, slurmd, slurm-client and munge
//! (`make setup` installs them).

mod support;

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use support::{base_scene, build_programs, meshes_root, s, study, study_file, study_ok, workspace};

/// The one-node cluster, stopped when dropped.
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
}

impl Cluster {
    fn start(dir: &Path) -> Cluster {
        let out = Command::new("bash")
            .arg(workspace().join("scripts/slurm_cluster.sh"))
            .arg("start")
            .arg(dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "the one-node Slurm cluster did not start:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        Cluster {
            dir: dir.to_path_buf(),
            conf: dir.join("slurm.conf"),
        }
    }

    fn cmd(&self, program: &str) -> Command {
        let mut c = Command::new(program);
        c.env("SLURM_CONF", &self.conf);
        c
    }
}

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = self.cmd("scancel").args(["--user", "root"]).status();
        let _ = Command::new("bash")
            .arg(workspace().join("scripts/slurm_cluster.sh"))
            .arg("stop")
            .arg(&self.dir)
            .status();
    }
}

/// `study status --json` as (label, state, slurm id).
fn states(args: &[&str]) -> Vec<(String, String, Option<String>)> {
    let mut a = vec!["status"];
    a.extend_from_slice(args);
    a.push("--json");
    let v: Value = serde_json::from_str(&study_ok(&a)).unwrap();
    v.as_array()
        .unwrap()
        .iter()
        .map(|j| {
            let state = match &j["state"] {
                Value::String(s) => s.clone(),
                Value::Object(o) => o.keys().next().unwrap().clone(),
                other => panic!("state {other}"),
            };
            (
                j["label"].as_str().unwrap().to_string(),
                state,
                j["slurm_id"].as_str().map(str::to_string),
            )
        })
        .collect()
}

/// Polls the study's states until `until` holds (panics after `limit`).
fn wait(
    args: &[&str],
    limit: Duration,
    what: &str,
    until: impl Fn(&[(String, String, Option<String>)]) -> bool,
) -> Vec<(String, String, Option<String>)> {
    let t0 = Instant::now();
    loop {
        let st = states(args);
        if until(&st) {
            return st;
        }
        assert!(
            t0.elapsed() < limit,
            "{what}: not reached in {limit:?}: {st:#?}"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
}

fn refs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

#[test]
fn slurm_study_with_a_cancelled_shard_resubmitted_gives_the_local_result_bit_for_bit() {
    let t0 = Instant::now();
    build_programs();
    let tmp = tempfile::tempdir().unwrap();
    let scene = base_scene(tmp.path());
    let file = study_file(
        tmp.path(),
        "slurm_study",
        &scene,
        "[\"ltca\", \"reference\"]",
        "[0.0, 0.05]",
        2,
    );
    let meshes = meshes_root();
    let bin = support::bin_dir();
    let (local, slurm) = (tmp.path().join("local"), tmp.path().join("slurm"));
    let at = |work: &Path| -> Vec<String> {
        ["--work", s(work), "--meshes", s(&meshes), "--bin", s(&bin)]
            .into_iter()
            .map(String::from)
            .collect()
    };
    let with = |cmd: &[&str], work: &Path| -> Vec<String> {
        let mut v: Vec<String> = cmd.iter().map(|c| c.to_string()).collect();
        v.insert(1, s(&file).to_string());
        v.extend(at(work));
        v
    };

    // The local executor's result.
    study_ok(&refs(&with(&["submit"], &local)));
    study_ok(&refs(&with(&["collect"], &local)));
    let t_local = t0.elapsed().as_secs_f64();

    let cluster = Cluster::start(&tmp.path().join("cluster"));
    std::env::set_var("SLURM_CONF", &cluster.conf);
    let out = study_ok(&refs(&with(&["submit", "--executor", "slurm"], &slurm)));
    assert!(
        out.contains("7 jobs submitted, 0 queued or running already, 0 done before"),
        "{out}"
    );
    let status_args = with(&["x"], &slurm)[1..].to_vec();
    let sa = refs(&status_args);

    // Cancel shard 1 while it runs.
    let st = wait(&sa, Duration::from_secs(300), "shard 1 running", |st| {
        st.iter()
            .any(|(l, s, _)| l.contains("reference shard 1/2") && s == "running")
    });
    let id = st
        .iter()
        .find(|(l, _, _)| l.contains("reference shard 1/2"))
        .and_then(|(_, _, id)| id.clone())
        .expect("the shard has a Slurm id");
    assert!(cluster.cmd("scancel").arg(&id).status().unwrap().success());
    let st = wait(&sa, Duration::from_secs(120), "the queue drained", |st| {
        st.iter().all(|(_, s, _)| s != "running" && s != "pending")
    });
    let state_of = |st: &[(String, String, Option<String>)], what: &str| {
        st.iter()
            .find(|(l, _, _)| l.contains(what))
            .map(|(_, s, _)| s.clone())
            .unwrap()
    };
    assert_eq!(state_of(&st, "reference shard 1/2"), "cancelled", "{st:#?}");
    assert_eq!(
        state_of(&st, "reference collection"),
        "cancelled",
        "{st:#?}"
    );
    assert_eq!(
        st.iter().filter(|(_, s, _)| s == "done").count(),
        5,
        "{st:#?}"
    );

    // Collect refuses, naming the cancelled shard, and writes nothing.
    let c = study(&refs(&with(&["collect"], &slurm)));
    let err = String::from_utf8_lossy(&c.stderr);
    assert!(!c.status.success());
    assert!(err.contains("2 of 7 jobs are not done"), "{err}");
    assert!(
        err.contains("reference shard 1/2 (2 cases): cancelled"),
        "{err}"
    );
    assert!(!slurm.join("results").join("slurm_study").exists());

    // A resubmission redoes only the cancelled shard and the collection.
    let out = study_ok(&refs(&with(&["submit", "--executor", "slurm"], &slurm)));
    assert!(
        out.contains("2 jobs submitted, 0 queued or running already, 5 done before"),
        "{out}"
    );
    wait(&sa, Duration::from_secs(300), "every job done", |st| {
        st.iter().all(|(_, s, _)| s == "done")
    });
    study_ok(&refs(&with(&["collect"], &slurm)));

    // The same result as the local executor's, bit for bit (the study's
    // name aside, which is the same here too).
    let read = |work: &Path, f: &str| {
        std::fs::read(work.join("results").join("slurm_study").join(f)).unwrap()
    };
    for f in ["summary.json", "cases.csv", "report.md"] {
        assert!(
            read(&local, f) == read(&slurm, f),
            "{f} differs between the executors"
        );
    }
    eprintln!(
        "slurm study: local executor {t_local:.0} s, whole test {:.0} s",
        t0.elapsed().as_secs_f64()
    );
    drop(cluster);
}
