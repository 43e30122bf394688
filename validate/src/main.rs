//! `validate` command line.

use clap::{Parser, Subcommand};
use cli::args::{
    CalibrateArgs, ConvergenceArgs, ExportInpArgs, GridConvergenceArgs, LineLoadArgs,
    MeshStiffnessArgs, ReferenceArgs, ReportArgs, StageTradeoffsArgs, StressArgs, TradeoffArgs,
    UtcaArgs,
};
use cli::commands;

mod cli;

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
    /// The whole validation report: loaded TE against the reference and the
    /// published tables, run times, unloaded TCA, the UTCA cross-check and
    /// the method notes (report.md, report.html, summary.json, results.md
    /// and the SVG figures), and the results table in the README.
    Report(ReportArgs),
    /// UTCA cross-check: the surface of roll angles against the direct
    /// contact search over one mesh cycle.
    Utca(UtcaArgs),
    /// Reference loaded TCA: fine FE bodies in penalty contact.
    Reference(ReferenceArgs),
    /// The reduced model's run time against its error to the reference, over
    /// the slices per tooth pair (needs `validate reference` results).
    Tradeoff(TradeoffArgs),
    /// The stress matrix (loads up to edge contact, slices, stiffness
    /// grids, flanks, multibody step, tolerance and speed) for the scene's
    /// design and the seed pairs beside it, on cached meshes and stiffness
    /// files: `<out>/<scene>/stress/summary.json` and `outcomes.svg`.
    Stress(StressArgs),
    /// Run time against error for every stage of the scene's design (UTCA,
    /// stiffness fields, LTCA, multibody, reference), as Pareto charts:
    /// `<out>/<scene>/tradeoff/` (summary.json, <stage>.json, <stage>.svg).
    StageTradeoffs(StageTradeoffsArgs),
    /// The reduced model against its own discretization limit: the LTCA on
    /// the scene's stiffness files and those of finer contact grids
    /// (`--grid-scene`), extrapolated per load;
    /// `<out>/<scene>/grid_convergence/summary.json`.
    GridConvergence(GridConvergenceArgs),
    /// Mesh convergence of the reference LTCA: TE at one position and torque
    /// on three mesh levels (standard blanks), observed order, extrapolation.
    Convergence(ConvergenceArgs),
    /// Mesh stiffness at one position: the FE reference (smooth flanks) on
    /// the scene's mesh levels against our LTCA at the same position and
    /// torques, k = dF/dδ and F/δ; `<out>/<scene>/mesh_stiffness/summary.json`.
    MeshStiffness(MeshStiffnessArgs),
    /// The line-load check: a Hertzian line load on one pinion tooth,
    /// fine-mesh FE against the reduced model's global FE + Weber–Banaschek.
    LineLoad(LineLoadArgs),
    /// A calibrated variant of the white-paper design: the unpublished
    /// pinion ease-off and lightweight web fitted to the published NLFEA
    /// rows at 1 and 100 N·m; writes the calibrated design, its scene and
    /// the fit's record (reference/white_paper_20x43_calibrat*).
    Calibrate(CalibrateArgs),
    /// One position of the reference as a CalculiX / Abaqus input deck
    /// (both bodies as C3D10, the clamped and the driven bore, the flank
    /// surfaces in penalty contact, a rotation step and one torque step
    /// per load): `<out>/<scene>/calculix/<stem>.inp`; with `--run`,
    /// solved by CalculiX, its loaded TE in `<stem>.json`.
    ExportInp(ExportInpArgs),
}

fn main() -> anyhow::Result<()> {
    // Ctrl-C / SIGTERM: remove this run's unfinished output, then exit 130.
    formats::interrupt::install();
    match Cli::parse().cmd {
        Cmd::Report(a) => commands::report(a)?,
        Cmd::Utca(a) => commands::utca(a)?,
        Cmd::Reference(a) => commands::reference(a)?,
        Cmd::ExportInp(a) => commands::export_inp(a)?,
        Cmd::Stress(a) => commands::stress(a)?,
        Cmd::StageTradeoffs(a) => commands::stage_tradeoffs(a)?,
        Cmd::GridConvergence(a) => commands::grid_convergence(a)?,
        Cmd::Tradeoff(a) => commands::tradeoff(a)?,
        Cmd::Convergence(a) => commands::convergence(a)?,
        Cmd::MeshStiffness(a) => commands::mesh_stiffness(a)?,
        Cmd::LineLoad(a) => commands::line_load(a)?,
        Cmd::Calibrate(a) => commands::calibrate(a)?,
    }
    Ok(())
}

#[cfg(test)]
mod command_line_ranges {
    //! Counts on the command line: within their documented range they
    //! parse, outside it clap refuses them before any work, naming the
    //! option.

    use super::Cli;
    use clap::Parser;
    use proptest::prelude::*;

    fn parse(args: &[&str]) -> Result<(), String> {
        Cli::try_parse_from(args)
            .map(|_| ())
            .map_err(|e| e.to_string())
    }

    #[test]
    fn reference_stride_zero_is_refused_naming_the_option() {
        let e = parse(&["validate", "reference", "s.toml", "--stride", "0"]).unwrap_err();
        assert!(
            e.contains("--stride") && e.contains("'0'") && e.contains(">= 1"),
            "{e}"
        );
        let e = parse(&[
            "validate",
            "reference",
            "s.toml",
            "--stride-lightweight",
            "0",
        ])
        .unwrap_err();
        assert!(e.contains("--stride-lightweight"), "{e}");
    }

    #[test]
    fn reference_contact_takes_its_two_passes_and_refuses_others() {
        for c in ["two-pass", "pinion-slave"] {
            assert!(parse(&["validate", "reference", "s.toml", "--contact", c]).is_ok());
        }
        let e = parse(&[
            "validate",
            "reference",
            "s.toml",
            "--contact",
            "wheel-slave",
        ])
        .unwrap_err();
        assert!(
            e.contains("--contact") && e.contains("wheel-slave") && e.contains("pinion-slave"),
            "{e}"
        );
    }

    #[test]
    fn utca_positions_zero_is_refused_naming_the_option() {
        let e = parse(&["validate", "utca", "s.toml", "--positions", "0"]).unwrap_err();
        assert!(e.contains("--positions") && e.contains("[1, 3600]"), "{e}");
    }

    #[test]
    fn line_load_column_ranges_parse_as_a_dash_b_in_order() {
        let ok = |extra: &[&str]| {
            let mut args = vec!["validate", "line-load", "s.toml"];
            args.extend_from_slice(extra);
            parse(&args)
        };
        assert!(ok(&["--columns", "34-39"]).is_ok());
        assert!(ok(&[
            "--columns",
            "7-7",
            "--member",
            "wheel",
            "--blank",
            "lightweight"
        ])
        .is_ok());
        assert!(ok(&["--response-tooth", "-1"]).is_ok());
        for bad in ["39", "a-3", "9-3", "-"] {
            let e = ok(&["--columns", bad]).unwrap_err();
            assert!(e.contains("--columns"), "{bad}: {e}");
        }
        let e = ok(&["--member", "gear"]).unwrap_err();
        assert!(e.contains("--member") && e.contains("wheel"), "{e}");
    }

    proptest! {
        #[test]
        fn stride_parses_exactly_when_at_least_one(n in 0u64..1_000_000) {
            let r = parse(&["validate", "reference", "s.toml", "--stride", &n.to_string()]);
            prop_assert_eq!(r.is_ok(), n >= 1, "{:?}", r);
        }

        #[test]
        fn positions_parse_exactly_within_their_range(n in 0u64..10_000) {
            for cmd in ["utca", "report"] {
                let mut args = vec!["validate", cmd, "s.toml", "--positions"];
                let v = n.to_string();
                args.push(&v);
                if cmd == "report" {
                    args.extend(["--flanks", "f"]);
                }
                let r = parse(&args);
                prop_assert_eq!(r.is_ok(), (1..=3600).contains(&n), "{} {:?}", cmd, r);
                if let Err(e) = r {
                    prop_assert!(e.contains("--positions"), "{}", e);
                }
            }
        }
    }
}
