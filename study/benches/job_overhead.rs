//! `make bench` (study): what the study machinery adds per job on top of
//! the stage's own time, with the local executor: a study of the small
//! scene at 8 offsets E × 2 axial P (16 cases, LTCA only: 18 jobs) whose programs are stand-ins
//! that exit at once, so that the whole wall time is the executor's
//! (planning, hashing the programs, `study run-job`, job files, polling).
//! Target: under 1 s per job. Results in `bench/study.json`.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use study::run_job::children_cpu_s;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let study_exe = root.join("target/release/study");
    assert!(
        study_exe.exists(),
        "build the programs first (`make build`)"
    );
    let tmp = tempfile::tempdir().unwrap();
    let bin = tmp.path().join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    std::os::unix::fs::symlink(&study_exe, bin.join("study")).unwrap();
    for p in ["preprocess", "solver", "validate"] {
        let f = bin.join(p);
        std::fs::write(&f, "#!/bin/sh\nexit 0\n").unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o755)).unwrap();
    }
    let offsets: Vec<String> = (0..8)
        .map(|i| format!("{:.3}", -0.04 + 0.01 * i as f64))
        .collect();
    let file = tmp.path().join("overhead.toml");
    std::fs::write(
        &file,
        format!(
            "name = \"overhead\"\nscenes = [\"{}\"]\nanalyses = [\"ltca\"]\n[grid]\noffset_mm = [{}]\npinion_axial_mm = [0.0, 0.02]\n",
            root.join("reference/scenes/small.toml").display(),
            offsets.join(", ")
        ),
    )
    .unwrap();
    let work = tmp.path().join("work");
    let run = |cmd: &str| {
        let (t0, c0) = (Instant::now(), children_cpu_s());
        let out = Command::new(&study_exe)
            .args([
                cmd,
                file.to_str().unwrap(),
                "--work",
                work.to_str().unwrap(),
            ])
            .args(["--meshes", tmp.path().join("meshes").to_str().unwrap()])
            .args(["--bin", bin.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (t0.elapsed().as_secs_f64(), children_cpu_s() - c0)
    };
    let (plan_wall, plan_cpu) = run("plan");
    let (wall, cpu) = run("submit");
    let jobs: Vec<serde_json::Value> = std::fs::read_dir(work.join("jobs"))
        .unwrap()
        .flatten()
        .map(|d| {
            serde_json::from_str(&std::fs::read_to_string(d.path().join("done.json")).unwrap())
                .unwrap()
        })
        .collect();
    let n = jobs.len();
    let programs: f64 = jobs.iter().map(|j| j["wall_s"].as_f64().unwrap()).sum();
    let per_job = (wall - programs) / n as f64;
    // The real programs' hashes (part of every job key), once per `study`
    // command: the stand-ins above hash in no time.
    let t_hash = Instant::now();
    study::jobs::Tools::find(&root.join("target/release")).expect("the project's programs");
    let hash_s = t_hash.elapsed().as_secs_f64();
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    println!(
        "\nstudy benchmark ({cores} cores): plan {plan_wall:.2} s wall ({plan_cpu:.2} s CPU); {n} jobs run locally in {wall:.2} s wall ({cpu:.2} s CPU, the stand-in programs {programs:.2} s): {per_job:.3} s per job; target < 1 s per job; hashing the real programs {hash_s:.2} s per `study` command"
    );
    formats::output::write_json(
        &root.join("bench/study.json"),
        &serde_json::json!({
            "cores": cores,
            "jobs": n,
            "plan_wall_s": plan_wall,
            "plan_cpu_s": plan_cpu,
            "submit_wall_s": wall,
            "submit_cpu_s": cpu,
            "programs_wall_s": programs,
            "overhead_s_per_job": per_job,
            "hash_programs_s": hash_s,
            "target_s_per_job": 1.0,
        }),
    )
    .unwrap();
    println!("written to bench/study.json");
}
