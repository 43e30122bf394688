//! `validate` command line.

use anyhow::Context;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "validate",
    version,
    about = "Independent checks and comparison reports"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Unloaded TCA against the direct contact search and the published 1 N·m TE.
    Utca {
        /// Scene or design file.
        scene: PathBuf,
        /// Output directory of `preprocess flanks` (for the plots).
        #[arg(long)]
        flanks: PathBuf,
        /// Report directory.
        #[arg(long, default_value = "reports")]
        reports: PathBuf,
        /// Positions per mesh cycle for the direct search.
        #[arg(long, default_value_t = 12)]
        positions: usize,
    },
}

fn main() -> anyhow::Result<()> {
    match Cli::parse().cmd {
        Cmd::Utca {
            scene,
            flanks,
            reports,
            positions,
        } => {
            let input = preprocess::flank_stage::load_input(&scene)?;
            let c = validate::utca_check::check(&input, positions).context("UTCA cross-check")?;
            let published = validate::published::te_ptp_1nm(&input.design_path);
            validate::report::write(&reports, &c, published.as_ref(), &flanks)?;
            println!(
                "UTCA cross-check: {} positions, max |fast - direct| = {:.4} urad, TE ptp {:.2} urad{}; reports in {}",
                c.rows.len(),
                c.max_abs_difference_urad,
                c.fast_te_ptp_urad,
                published.map(|p| format!(" (published {:.1} at 1 N m)", p.value)).unwrap_or_default(),
                reports.display()
            );
        }
    }
    Ok(())
}
