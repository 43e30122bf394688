//! Studies that outgrow one run: a study file expands into cases (design
//! variants × misalignments), the cases into jobs keyed by their inputs
//! (meshes, stiffness files, reduced-model runs, reference shards), run on
//! this machine or submitted to Slurm through one wrapper
//! (`study run-job`), then collected into one result set with a report.
//! See docs/studies.md.

pub mod cases;
pub mod collect;
pub mod estimate;
pub mod jobs;
pub mod local;
pub mod report;
pub mod resources;
pub mod run_job;
pub mod slurm;
pub mod state;
pub mod status;
pub mod study_file;

use std::path::{Path, PathBuf};

/// A study read, expanded and planned, its jobs written into the work
/// folder.
pub struct Planned {
    pub path: PathBuf,
    pub study: study_file::StudyFile,
    pub expanded: cases::Expanded,
    pub jobs: Vec<jobs::Job>,
    pub work: PathBuf,
    pub tools: jobs::Tools,
}

/// Reads the study file, expands and checks its cases, plans the jobs and
/// writes each job's `job.json` (before any job runs).
pub fn plan(study_path: &Path, work: &Path, meshes: &Path, bin: &Path) -> anyhow::Result<Planned> {
    let study = study_file::StudyFile::load(study_path)?;
    let tools = jobs::Tools::find(bin)?;
    let work = cases::absolute(work);
    let expanded = cases::expand(&study, study_path, &work, meshes)?;
    let mut reference_mem_mb = std::collections::BTreeMap::new();
    for d in &expanded.designs {
        let mb = match study.slurm.reference_mem_gb {
            Some(gb) => Some((gb * 1000.0).ceil() as u64),
            None => jobs::reference_mem_from_meshes(meshes, &d.name, &study.reference.level),
        };
        if let Some(mb) = mb {
            reference_mem_mb.insert(d.name.clone(), mb);
        }
    }
    let res = jobs::Resources {
        cpus: study.slurm.cpus_per_task.unwrap_or(2),
        reference_mem_mb,
    };
    let jobs = jobs::plan(&study, &expanded, &tools, meshes, &res);
    jobs::check_order(&jobs).map_err(|e| anyhow::anyhow!(e))?;
    for j in &jobs {
        state::write_job(&work, j)?;
    }
    Ok(Planned {
        path: study_path.to_path_buf(),
        study,
        expanded,
        jobs,
        work,
        tools,
    })
}
