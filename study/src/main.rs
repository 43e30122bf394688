//! `study`: plan, submit, follow and collect a study (see docs/studies.md).

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "study",
    about = "Studies over many cases, run locally or on Slurm"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(clap::Args, Clone)]
struct Where {
    /// Study file (TOML).
    study: PathBuf,
    /// Work folder: case scenes, job folders, case results, collected
    /// results (shared by studies that should share jobs).
    #[arg(long, default_value = "out/studies")]
    work: PathBuf,
    /// Mesh root of the designs' meshes and stiffness files.
    #[arg(long, default_value = "meshes")]
    meshes: PathBuf,
    /// Folder of the project's programs (default: this program's folder).
    #[arg(long)]
    bin: Option<PathBuf>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Expands the study and prints its cases and jobs (nothing runs).
    Plan {
        #[command(flatten)]
        at: Where,
        /// Also size the reference sweeps on paper from the base scenes'
        /// measured sweeps under this output root (`validate reference`
        /// of each base scene at the study's level).
        #[arg(long)]
        estimate_from: Option<PathBuf>,
        /// Shard counts (one node each) of the estimate.
        #[arg(long, value_delimiter = ',', default_value = "1,4,16,64")]
        nodes: Vec<usize>,
    },
    /// Runs (local) or submits (slurm) every job not done yet.
    Submit {
        #[command(flatten)]
        at: Where,
        /// local: this machine; slurm: sbatch.
        #[arg(long, default_value = "local", value_parser = ["local", "slurm"])]
        executor: String,
        /// Local executor: jobs at once (each stage uses every core).
        #[arg(long, default_value_t = 1)]
        parallel: usize,
        /// Slurm partition, account and time limit (default: the study
        /// file's `[slurm]`).
        #[arg(long)]
        partition: Option<String>,
        #[arg(long)]
        account: Option<String>,
        #[arg(long)]
        time: Option<String>,
    },
    /// Every job's state: done, running, pending, failed (with its log),
    /// cancelled, lost or not run.
    Status {
        #[command(flatten)]
        at: Where,
        /// Print the states as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Merges every case into one result set; refuses while a job is not done.
    Collect(Where),
    /// Runs one planned job (what the executors call).
    RunJob {
        #[arg(long)]
        work: PathBuf,
        key: String,
    },
}

fn planned(w: &Where) -> anyhow::Result<study::Planned> {
    let bin = match &w.bin {
        Some(b) => b.clone(),
        None => std::env::current_exe()?
            .parent()
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(".")),
    };
    study::plan(&w.study, &w.work, &w.meshes, &bin)
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Plan {
            at,
            estimate_from,
            nodes,
        } => {
            let p = planned(&at)?;
            println!(
                "study {}: {} cases, {} jobs",
                p.study.name,
                p.expanded.cases.len(),
                p.jobs.len()
            );
            for j in &p.jobs {
                println!(
                    "  {} {:>6} MB  {}",
                    study::cases::short(&j.key),
                    j.mem_mb,
                    j.label
                );
            }
            if let Some(out) = estimate_from {
                if nodes.contains(&0) {
                    anyhow::bail!("--nodes: 0 in {nodes:?}; shard counts are at least 1");
                }
                let (level, stride) = (&p.study.reference.level, p.study.reference.stride);
                for (k, d) in p.expanded.designs.iter().enumerate() {
                    let m = study::estimate::measured(&out, &d.name, level)?;
                    let cases = p.expanded.cases.iter().filter(|c| c.design == k).count();
                    println!(
                        "\nreference sweeps of {} ({cases} cases, level {level}, stride {stride}), from the measured sweep under {}:",
                        d.name,
                        out.display()
                    );
                    for b in &m {
                        println!(
                            "  {}: {} positions at {:.1} s wall each, bodies factored in {:.0} s",
                            b.blanks, b.positions, b.wall_s_per_position, b.factor_s
                        );
                    }
                    println!(
                        "  {:>6}  {:>12}  {:>12}",
                        "nodes", "study wall h", "node-hours"
                    );
                    for s in study::estimate::sizing(&m, cases, stride, &nodes) {
                        println!(
                            "  {:>6}  {:>12.1}  {:>12.1}",
                            s.shards, s.study_wall_h, s.node_hours
                        );
                    }
                }
            }
        }
        Cmd::Submit {
            at,
            executor,
            parallel,
            partition,
            account,
            time,
        } => {
            let p = planned(&at)?;
            let me = p.tools.program("study");
            if executor == "local" {
                let o = study::local::run(&p.work, &p.jobs, &me, parallel)?;
                println!(
                    "study {}: {} jobs done before, {} run now, {} failed, {} not run (a dependency failed)",
                    p.study.name,
                    o.already_done,
                    o.ran.len(),
                    o.failed.len(),
                    o.blocked.len()
                );
                for (label, log) in &o.failed {
                    println!("  failed: {label} (log {})", log.display());
                }
                if !o.ok() {
                    std::process::exit(1);
                }
            } else {
                let sl = &p.study.slurm;
                let opt = study::slurm::SlurmOptions {
                    partition: partition.or(sl.partition.clone()),
                    account: account.or(sl.account.clone()),
                    time: time.or(sl.time.clone()),
                };
                let s = study::slurm::submit(&p.work, &p.jobs, &me, &opt)?;
                println!(
                    "study {}: {} jobs submitted, {} queued or running already, {} done before",
                    p.study.name,
                    s.submitted.len(),
                    s.active,
                    s.already_done
                );
                for (label, id) in &s.submitted {
                    println!("  {id:>10}  {label}");
                }
            }
        }
        Cmd::Status { at, json } => {
            let p = planned(&at)?;
            let st = study::status::status(&p.work, &p.jobs)?;
            if json {
                println!("{}", serde_json::to_string_pretty(&st)?);
            } else {
                for s in &st {
                    println!(
                        "{:<22} {:>10}  {}  (log {})",
                        s.state.name(),
                        s.slurm_id.as_deref().unwrap_or("-"),
                        s.label,
                        s.log.display()
                    );
                }
                let done = st
                    .iter()
                    .filter(|s| s.state == study::status::JobState::Done)
                    .count();
                println!("study {}: {done} of {} jobs done", p.study.name, st.len());
            }
        }
        Cmd::Collect(w) => {
            let p = planned(&w)?;
            let st = study::status::status(&p.work, &p.jobs)?;
            let (dir, c) = study::collect::collect(&p.study, &p.expanded, &p.jobs, &st, &p.work)?;
            println!("{}", study::report::verdict(&c));
            println!("written {}", dir.display());
        }
        Cmd::RunJob { work, key } => {
            let code = study::run_job::run(&work, &key)?;
            std::process::exit(code);
        }
    }
    Ok(())
}
