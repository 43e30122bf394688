//! `preprocess` command line: flank generation and UTCA (more stages follow).

use anyhow::Context;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "preprocess",
    version,
    about = "Spiral bevel gear preprocessing: flanks and unloaded tooth contact"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Generate both members' flanks and run the unloaded tooth contact analysis.
    Flanks {
        /// Design file or scene file (TOML).
        input: PathBuf,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
    },
    /// Mesh every member x blank of a scene (tet10) into <out>/<scene>/: .msh 4.1, .vtu, report.
    Mesh {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Mesh level(s).
        #[arg(long, value_enum, default_value = "reduced")]
        level: preprocess::mesh_stage::Level,
        /// Root directory of the meshes.
        #[arg(long, default_value = "meshes")]
        out: PathBuf,
    },
    /// FE influence fields (stiffness files) from the reduced-order meshes (or another level's).
    Stiffness {
        scene: PathBuf,
        /// Directory holding `<scene>/` meshes; stiffness files go next to them.
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
        /// Mesh level whose meshes are used (the contact grid is the scene's
        /// either way); medium and reference serve mesh-convergence studies.
        #[arg(long, value_enum, default_value = "reduced")]
        level: preprocess::mesh_stage::Level,
    },
    /// The gearbox housing of `[bearings.gearbox.housing]`: laid out around the gears, meshed (tet10), reduced by Craig–Bampton onto its bearing seats -> <meshes>/<scene>/housing.h5.
    Housing {
        scene: PathBuf,
        /// Root directory of the meshes (the file goes to <meshes>/<scene>/).
        #[arg(long, default_value = "meshes")]
        meshes: PathBuf,
    },
}

fn main() -> anyhow::Result<()> {
    // Ctrl-C / SIGTERM: remove this run's unfinished output, then exit 130.
    formats::interrupt::install();
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Flanks { input, out } => {
            let inp = preprocess::flank_stage::load_input(&input)?;
            let Some(s) = preprocess::flank_stage::run(&inp, &out)
                .with_context(|| format!("preprocess flanks {}", input.display()))?
            else {
                return Ok(());
            };
            println!(
                "{}: {} flank, mesh cycle {:.3} deg, contact ratio {:.3}, unloaded TE {:.2} urad peak-to-peak (mean {:.2}), {} positions at {:.3} ms each",
                s.name,
                s.loaded_flank,
                s.mesh_cycle_deg,
                s.utca.contact_ratio,
                s.utca.te_ptp_urad,
                s.utca.te_mean_urad,
                s.utca.positions,
                s.utca.ms_per_position
            );
            for (member, flanks) in &s.mean_point {
                for (flank, m) in flanks {
                    println!(
                        "  {member} {flank:7} ({}) mean point: spiral angle {:.4} deg, normal pressure angle {:.4} deg",
                        m.side, m.spiral_angle_deg, m.normal_pressure_angle_deg
                    );
                }
            }
            println!("  written to {}", out.display());
        }
        Cmd::Mesh { scene, level, out } => {
            let s = geometry::scene::Scene::load(&scene)?;
            let reports = preprocess::mesh_stage::run(&s, &out, level)?;
            for r in &reports {
                let flank = r
                    .refined_flanks
                    .first()
                    .map(|f| format!("{} x {}", f.elements_profile, f.elements_face))
                    .unwrap_or_else(|| "-".into());
                let made = if r.reused {
                    "reused; made earlier in"
                } else {
                    "made in"
                };
                println!(
                    "{} {:?} {}: {} nodes, {} tet10, min SICN {:.3}, refined flanks {} ({} of them: {flank} requested {} x {}), volume mesh/CAD - 1 = {:.2e}, {made} geometry {:.1} s + mesh {:.1} s",
                    r.member,
                    r.blank,
                    r.level,
                    r.nodes,
                    r.tet10_elements,
                    r.quality_min_sicn,
                    r.refined_flanks.len(),
                    r.refined_flanks.len(),
                    r.requested.profile,
                    r.requested.face,
                    r.mesh_volume_m3 / r.occ_volume_m3 - 1.0,
                    r.time_geometry_s,
                    r.time_mesh_s
                );
            }
        }
        Cmd::Stiffness {
            scene,
            meshes,
            level,
        } => {
            let s = geometry::scene::Scene::load(&scene)?;
            for r in preprocess::stiffness_stage::run_level(&s, &meshes, level)? {
                match (&r.stats, r.reused) {
                    (_, true) => println!("{} {} {}: reused {}", r.member, r.blank, r.level, r.path.display()),
                    (Some(st), false) => println!(
                        "{} {} {}: {} dofs, assemble {:.1} s, factor {:.1} s (L {:.0} M values), {} unit loads {:.1} ms each, Gram products {:.1} s, local fields {:.1} s, backward check {:.1e}, total {:.1} s -> {}",
                        r.member,
                        r.blank,
                        r.level,
                        st.dofs,
                        st.assemble_s,
                        st.factor_s,
                        st.factor_nnz as f64 / 1e6,
                        st.right_hand_sides,
                        1e3 * st.solve_s / st.right_hand_sides.max(1) as f64,
                        st.gram_s,
                        st.local_s,
                        st.backward_check.unwrap_or(f64::NAN),
                        r.total_s,
                        r.path.display()
                    ),
                    _ => {}
                }
            }
        }
        Cmd::Housing { scene, meshes } => {
            let s = geometry::scene::Scene::load(&scene)?;
            match preprocess::housing_stage::run(&s, &meshes)
                .with_context(|| format!("preprocess housing {}", scene.display()))?
            {
                None => println!(
                    "scene {}: no [bearings.gearbox.housing]; nothing to do",
                    s.scene.name
                ),
                Some(r) => {
                    let d = &r.data;
                    println!(
                        "housing of {}: {} nodes, {} tet10, {:.1} kg, least gap to the gears and shafts {:.1} mm, seats of {:?} nodes, {} fixed-interface modes up to {:.0} Hz, {} coordinates; modes {:?} Hz, largest difference from the whole housing's {:.2e}{}; {} {:.1} s -> {}",
                        s.scene.name,
                        d.nodes,
                        d.elements,
                        d.mass_kg,
                        1e3 * d.least_gap_m,
                        d.seat_nodes,
                        d.fixed_interface_hz.len(),
                        d.fixed_interface_hz.last().copied().unwrap_or(0.0),
                        d.coordinates(),
                        d.reduced_hz.iter().map(|f| f.round()).collect::<Vec<_>>(),
                        r.truncation_error,
                        r.volume_error.map_or(String::new(), |v| format!(", mesh volume / CAD - 1 = {v:.1e}")),
                        if r.reused { "reused" } else { "made in" },
                        r.seconds,
                        r.path.display()
                    );
                }
            }
        }
    }
    Ok(())
}
