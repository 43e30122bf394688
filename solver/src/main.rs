//! `solver` command line.

use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "solver",
    version,
    about = "Gear contact element, loaded TCA and multibody runs"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Contact-detection plan: tooth pairs that can touch at each position, and the teeth that need stiffness data.
    Plan {
        scene: PathBuf,
        /// Write the full plan into this directory as one result set
        /// (`plan.json`, and `run.json` with the checksums of the plan, the
        /// scene and the design).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Quasi-static loaded TCA of every blank combination and torque of the scene, from its stiffness files.
    Ltca {
        scene: PathBuf,
        /// Root of the meshes and stiffness files (`<meshes>/<scene>/`).
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
        /// Results go to `<out>/<scene>/ltca/`.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Multibody runs (10 rpm quasi-static per torque, run-up) of every blank combination, from the stiffness files.
    Dynamic {
        scene: PathBuf,
        /// Root of the meshes and stiffness files (`<meshes>/<scene>/`).
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
        /// Results go to `<out>/<scene>/multibody/`.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Misalignment sensitivity: E, P, G, ΔΣ each swept over the scene's `[sensitivity]` range, LTCA at the scene's loads.
    Sensitivity {
        scene: PathBuf,
        /// Root of the meshes and stiffness files (`<meshes>/<scene>/`).
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
        /// Results go to `<out>/<scene>/sensitivity/`.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// 8-DOF lumped dynamic model (scene's `[lumped]`), driven by the LTCA's k(t) and e(t).
    Lumped {
        scene: PathBuf,
        /// Root of the meshes and stiffness files (`<meshes>/<scene>/`).
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
        /// Results go to `<out>/<scene>/lumped/`.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
}

fn main() -> anyhow::Result<()> {
    // Ctrl-C / SIGTERM: remove this run's unfinished output, then exit 130.
    formats::interrupt::install();
    match Cli::parse().cmd {
        Cmd::Plan { scene, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            let plans = match &out {
                Some(o) => solver::stage::plan::write_plan_set(&s, o)?,
                None => solver::stage::plan::plan(&s)?,
            };
            for p in &plans {
                let (lo, hi) = p.positions.iter().fold((usize::MAX, 0), |(a, b), q| {
                    (a.min(q.tooth_pairs.len()), b.max(q.tooth_pairs.len()))
                });
                println!(
                    "{:?} wheel blank, {} flank: {} positions over {} mesh cycles, {}..{} tooth pairs per position; pinion teeth {:?}, wheel teeth {:?}",
                    p.blank, p.loaded_flank.name(), p.positions.len(), p.mesh_cycles, lo, hi, p.pinion_teeth, p.wheel_teeth
                );
            }
            if let Some(o) = out {
                println!("written {}", o.join("plan.json").display());
            }
        }
        Cmd::Dynamic { scene, meshes, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            let res = solver::stage::dynamic::run(&s, &meshes, &out)?;
            for b in &res {
                for q in &b.quasi_static {
                    println!(
                        "{:?}/{:?} {:6.1} N·m: multibody TE mean {:8.2} µrad, ptp {:7.2} µrad ({} steps)",
                        b.pinion_blank, b.wheel_blank, q.torque_nm, q.te_mean_urad, q.te_ptp_urad, q.steps
                    );
                }
            }
        }
        Cmd::Lumped { scene, meshes, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            for b in solver::stage::lumped::run(&s, &meshes, &out)? {
                let a = &b.rms_acceleration_m_s2;
                println!(
                    "{:?}/{:?}: RMS acceleration m/s² pinion X {:.2} Y {:.2} Z {:.2}, wheel X {:.2} Y {:.2} Z {:.2}, mesh normal {:.2}; impact {:.0} N",
                    b.pinion_blank, b.wheel_blank, a.pinion_x, a.pinion_y, a.pinion_z, a.wheel_x, a.wheel_y, a.wheel_z, a.mesh_normal, b.impact_force_n
                );
            }
        }
        Cmd::Sensitivity { scene, meshes, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            let r = solver::stage::sensitivity::run(&s, &meshes, &out)?;
            for c in &r.curves {
                for p in &c.points {
                    let l = &p.loads[p.loads.len() - 1];
                    println!(
                        "{} {:+.4} {}: {} N·m TE ptp {:7.2} µrad, mean {:8.2} µrad, pattern centre L {:.2} mm d {:.2} mm, length {:.2} mm, p_max {:.0} MPa",
                        c.symbol, p.value, c.unit, l.torque_nm, l.te_ptp_urad, l.te_mean_urad, l.pattern_centre_l_mm, l.pattern_centre_d_mm, l.pattern_length_mm, l.max_pressure_mpa
                    );
                }
            }
            println!("{:.1} s", r.wall_s);
        }
        Cmd::Ltca { scene, meshes, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            let res = solver::stage::ltca::run(&s, &meshes, &out)?;
            for b in &res {
                println!(
                    "{:?} pinion / {:?} wheel: {} positions -> {}",
                    b.pinion_blank,
                    b.wheel_blank,
                    b.positions,
                    b.dir.display()
                );
            }
        }
    }
    Ok(())
}
