//! The study's jobs and their dependencies. Per design: its meshes at
//! each level the analyses need, then its stiffness files; per case: the
//! reduced-model runs and the reference sweep in shards, then the sweep's
//! collection (a `validate reference` run without `--shard`, which finds
//! every position in the cache). A job's key is the hash of what it runs
//! and reads: the program's SHA-256, its arguments (absolute paths) and the
//! keys of the designs or cases whose files it reads; a job with the same
//! key in the same work folder is the same job, so it runs once however
//! many cases and studies need it.

use crate::cases::{absolute, key_of, Expanded};
use crate::study_file::{Analysis, StudyFile};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What a job does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JobKind {
    Mesh,
    Stiffness,
    Utca,
    Ltca,
    Multibody,
    ReferenceShard,
    ReferenceCollect,
}

/// One job: a command of one of the project's programs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Job {
    pub key: String,
    /// Design or case and what the job does, for people.
    pub label: String,
    pub kind: JobKind,
    /// The program (absolute path) and its arguments.
    pub program: PathBuf,
    pub args: Vec<String>,
    /// Folder the program runs in.
    pub cwd: PathBuf,
    /// Keys of the jobs that must have finished first.
    pub deps: Vec<String>,
    /// Memory and cores it asks for.
    pub mem_mb: u64,
    pub cpus: usize,
    /// The jobs of one array (the shards of one case's reference sweep)
    /// share this name; Slurm submits them as one job array.
    pub array: Option<String>,
    /// The case it belongs to (none for a design's preprocessing).
    pub case: Option<String>,
}

/// The project's programs: where they are, and their SHA-256 (part of
/// every job's key, so that a rebuilt program makes new jobs).
#[derive(Debug, Clone)]
pub struct Tools {
    pub bin: PathBuf,
    pub sha256: BTreeMap<String, String>,
}

pub const PROGRAMS: [&str; 4] = ["preprocess", "solver", "validate", "study"];

impl Tools {
    /// The programs in `bin`, hashed (a program missing there is an error
    /// naming the folder: `make build` makes them).
    pub fn find(bin: &Path) -> anyhow::Result<Tools> {
        let bin = absolute(bin);
        let mut sha256 = BTreeMap::new();
        for p in PROGRAMS {
            let path = bin.join(p);
            let sha = formats::manifest::sha256_file(&path).map_err(|e| {
                anyhow::anyhow!(
                    "--bin {}: cannot read the program {p} ({e}); `make build` builds the project's programs",
                    bin.display()
                )
            })?;
            sha256.insert(p.to_string(), sha);
        }
        Ok(Tools { bin, sha256 })
    }

    pub fn program(&self, name: &str) -> PathBuf {
        self.bin.join(name)
    }
}

/// Memory (MB) and cores of each kind of job.
#[derive(Debug, Clone)]
pub struct Resources {
    pub cpus: usize,
    /// Reference jobs: per design, estimated from its meshes (or the
    /// study's `[slurm] reference_mem_gb`).
    pub reference_mem_mb: BTreeMap<String, u64>,
}

/// Memory of the jobs that do not factor FE bodies, MB: measured peaks of
/// the default scene's stages on the 2-core machine, rounded up (see
/// docs/studies.md).
pub fn mem_mb(kind: JobKind, level: &str) -> u64 {
    match kind {
        JobKind::Mesh => match level {
            "reduced" => 3000,
            "medium" => 6000,
            _ => 12000,
        },
        JobKind::Stiffness => 6000,
        JobKind::Utca => 1000,
        JobKind::Ltca | JobKind::Multibody => 3000,
        JobKind::ReferenceShard | JobKind::ReferenceCollect => 4000,
    }
}

/// Builds the jobs of an expanded study.
pub fn plan(
    study: &StudyFile,
    ex: &Expanded,
    tools: &Tools,
    meshes: &Path,
    res: &Resources,
) -> Vec<Job> {
    let meshes = absolute(meshes);
    let cwd = absolute(Path::new("."));
    let mut jobs: Vec<Job> = Vec::new();
    let s = |p: &Path| p.display().to_string();
    let make = |label: String,
                kind: JobKind,
                program: &str,
                args: Vec<String>,
                deps: Vec<String>,
                inputs: &str,
                mem_mb: u64,
                array: Option<String>,
                case: Option<String>| {
        let key = key_of(&serde_json::json!({
            "program": tools.sha256[program], "args": args, "cwd": cwd,
            "inputs": inputs, "deps": deps,
        }));
        Job {
            key,
            label,
            kind,
            program: tools.program(program),
            args,
            cwd: cwd.clone(),
            deps,
            mem_mb,
            cpus: res.cpus,
            array,
            case,
        }
    };
    let reduced_model = study.runs(Analysis::Ltca) || study.runs(Analysis::Multibody);
    let reference = study.runs(Analysis::Reference);
    let level = study.reference.level.as_str();
    let mut design_jobs = Vec::new();
    for d in &ex.designs {
        let scene = s(&d.scene_path);
        let mut mesh_jobs: BTreeMap<&str, String> = BTreeMap::new();
        let mut levels = Vec::new();
        if reduced_model || (reference && level == "reduced") {
            levels.push("reduced");
        }
        if reference && level != "reduced" {
            levels.push(level);
        }
        for lv in levels {
            let j = make(
                format!("{}: mesh {lv}", d.name),
                JobKind::Mesh,
                "preprocess",
                vec![
                    "mesh".into(),
                    scene.clone(),
                    "--level".into(),
                    lv.into(),
                    "--out".into(),
                    s(&meshes),
                ],
                vec![],
                &d.key,
                mem_mb(JobKind::Mesh, lv),
                None,
                None,
            );
            mesh_jobs.insert(lv, j.key.clone());
            jobs.push(j);
        }
        let stiffness = reduced_model.then(|| {
            let j = make(
                format!("{}: stiffness files", d.name),
                JobKind::Stiffness,
                "preprocess",
                vec![
                    "stiffness".into(),
                    scene.clone(),
                    "--meshes".into(),
                    s(&meshes),
                ],
                vec![mesh_jobs["reduced"].clone()],
                &d.key,
                mem_mb(JobKind::Stiffness, "reduced"),
                None,
                None,
            );
            let k = j.key.clone();
            jobs.push(j);
            k
        });
        design_jobs.push((stiffness, mesh_jobs.get(level).cloned()));
    }
    // The case jobs, kind by kind and design by design, so that the cases
    // of one kind and design follow each other: Slurm submits them as one
    // job array (a failed case is submitted again alone, by its index).
    let kinds = [
        (Analysis::Utca, JobKind::Utca, "unloaded TCA"),
        (Analysis::Ltca, JobKind::Ltca, "loaded TCA"),
        (Analysis::Multibody, JobKind::Multibody, "multibody"),
    ];
    for (a, kind, what) in kinds {
        if !study.runs(a) {
            continue;
        }
        for (d, design) in ex.designs.iter().enumerate() {
            let stiffness = &design_jobs[d].0;
            for c in ex.cases.iter().filter(|c| c.design == d) {
                let scene = s(&c.scene_path);
                let out = s(&absolute(&c.out));
                let (program, args, deps) = match kind {
                    JobKind::Utca => (
                        "preprocess",
                        vec![
                            "flanks".into(),
                            scene,
                            "--out".into(),
                            s(&absolute(&c.out).join(&design.name).join("flanks")),
                        ],
                        vec![],
                    ),
                    _ => (
                        "solver",
                        vec![
                            if kind == JobKind::Ltca {
                                "ltca"
                            } else {
                                "dynamic"
                            }
                            .into(),
                            scene,
                            "--meshes".into(),
                            s(&meshes),
                            "--out".into(),
                            out,
                        ],
                        stiffness.iter().cloned().collect(),
                    ),
                };
                jobs.push(make(
                    format!("{}: {what}", c.id),
                    kind,
                    program,
                    args,
                    deps,
                    &c.key,
                    mem_mb(kind, "reduced"),
                    Some(format!("{}-{}", crate::cases::short(&design.key), a.name())),
                    Some(c.id.clone()),
                ));
            }
        }
    }
    // The reference sweeps: per design, all its cases in one run of
    // `validate reference` (each body factored once for every case: the
    // misalignment changes only the placement), in shards, then one run
    // without --shard that finds every position cached and writes each
    // case's results.
    if reference {
        let n = study.reference.shards;
        for (d, design) in ex.designs.iter().enumerate() {
            let cases: Vec<&crate::cases::Case> =
                ex.cases.iter().filter(|c| c.design == d).collect();
            if cases.is_empty() {
                continue;
            }
            let ref_mesh = &design_jobs[d].1;
            let mut base: Vec<String> = vec!["reference".into()];
            base.extend(cases.iter().map(|c| s(&c.scene_path)));
            base.extend(["--meshes".into(), s(&meshes)]);
            for c in &cases {
                base.extend(["--out".into(), s(&absolute(&c.out))]);
            }
            base.extend([
                "--level".into(),
                level.into(),
                "--stride".into(),
                study.reference.stride.to_string(),
            ]);
            let inputs: String = cases
                .iter()
                .map(|c| c.key.as_str())
                .collect::<Vec<_>>()
                .join(",");
            let mem = res
                .reference_mem_mb
                .get(&design.name)
                .copied()
                .unwrap_or_else(|| mem_mb(JobKind::ReferenceShard, level));
            let what = format!("{} cases", cases.len());
            let mut shard_keys = Vec::new();
            if n > 1 {
                for k in 0..n {
                    let mut args = base.clone();
                    args.extend(["--shard".into(), format!("{k}/{n}")]);
                    let j = make(
                        format!("{}: reference shard {k}/{n} ({what})", design.name),
                        JobKind::ReferenceShard,
                        "validate",
                        args,
                        ref_mesh.iter().cloned().collect(),
                        &inputs,
                        mem,
                        Some(format!("{}-reference", crate::cases::short(&design.key))),
                        None,
                    );
                    shard_keys.push(j.key.clone());
                    jobs.push(j);
                }
            }
            let deps = if n > 1 {
                shard_keys
            } else {
                ref_mesh.iter().cloned().collect()
            };
            let collect_mem = if n > 1 {
                mem_mb(JobKind::ReferenceCollect, level)
            } else {
                mem
            };
            jobs.push(make(
                format!(
                    "{}: reference {} ({what})",
                    design.name,
                    if n > 1 { "collection" } else { "sweep" }
                ),
                JobKind::ReferenceCollect,
                "validate",
                base,
                deps,
                &inputs,
                collect_mem,
                None,
                None,
            ));
        }
    }
    // The same job needed twice (two cases with the same inputs) is one.
    let mut seen = std::collections::BTreeSet::new();
    jobs.retain(|j| seen.insert(j.key.clone()));
    jobs
}

/// The jobs in an order where every job follows its dependencies (the
/// plan's order already is; this checks it).
pub fn check_order(jobs: &[Job]) -> Result<(), String> {
    let mut done = std::collections::BTreeSet::new();
    for j in jobs {
        if let Some(d) = j.deps.iter().find(|d| !done.contains(d.as_str())) {
            return Err(format!(
                "{} depends on {d}, which does not come before it",
                j.label
            ));
        }
        done.insert(j.key.as_str());
    }
    Ok(())
}

/// The reference jobs' memory from a design's meshes of `level` (the two
/// largest bodies' factors at the estimate's upper band plus 2 GB for the
/// rest of the process), when the meshes and their manifest exist.
pub fn reference_mem_from_meshes(meshes: &Path, design: &str, level: &str) -> Option<u64> {
    let dir = meshes.join(design);
    let manifest = formats::manifest::Manifest::read(&dir).ok()?;
    let mut dofs: Vec<usize> = manifest
        .meshes
        .iter()
        .filter(|(stem, _)| stem.ends_with(&format!("_{level}")))
        .map(|(_, e)| 3 * e.body.nodes)
        .collect();
    if dofs.is_empty() {
        return None;
    }
    dofs.sort_unstable_by(|a, b| b.cmp(a));
    let bytes: f64 = dofs
        .iter()
        .take(2)
        .map(|&n| formats::memory_estimate::factor(n).high_bytes)
        .sum();
    Some(((bytes + 2e9) / 1e6).ceil() as u64)
}
