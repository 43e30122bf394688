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
}

fn main() -> anyhow::Result<()> {
    let cli = Cli::parse();
    match cli.cmd {
        Cmd::Flanks { input, out } => {
            let inp = preprocess::flank_stage::load_input(&input)?;
            let s = preprocess::flank_stage::run_stage(&inp, &out)
                .with_context(|| format!("preprocess flanks {}", input.display()))?;
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
    }
    Ok(())
}
