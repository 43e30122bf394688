//! The report's section "Static against dynamic TE (use case 1)": the
//! white paper's first use case, `solver dynamic` on
//! `reference/scenes/white_paper_ste_dte.toml` (`[multibody.ste_dte]`).
//!
//! Reads `<out>/white_paper_ste_dte/multibody/summary.json`: per wheel
//! blank the quasi-static TE (STE, the slow run-up) against the dynamic TE
//! (DTE, the fast one) over the compared revolutions, where the DTE
//! departs most after the acceleration, and the cost of the runs beside
//! the white paper's Table 6. The verdict sentences are computed from
//! those numbers ([`ptp_sentence`], [`transient_sentence`]). The chart of
//! each blank (`ste_dte.svg`) is copied into the report directory as
//! `ste_dte_<blanks>.svg`. An absent summary is one line of text.

use crate::report::figures::figure_lines;
use crate::report::sections::multibody_runs::{absent, charts, holds_none, picked, read, Section};
use formats::summaries::SteDteSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose runs the section reports.
pub const STE_DTE_SCENE: &str = "white_paper_ste_dte";

/// A DTE peak-to-peak further than this from the STE's (relative) is
/// called a significant difference: our threshold; the white paper calls
/// its difference "significant" without a number.
pub const SIGNIFICANT_PTP_DIFFERENCE: f64 = 0.10;

/// The white paper's Table 6 (seed 000): the lightweight pair's dynamic
/// run-up, 1 to 1,000 rpm: simulated time (s), time steps, largest step
/// (s), CPU total (s, "~1.5 h") and per step (s, "~0.4 s").
pub const PAPER_TABLE_6: (f64, usize, f64, f64, f64) = (0.15, 15_258, 1e-5, 5400.0, 0.4);

/// The section's markdown and its charts.
pub type SteDteSection = Section;

/// "a significant difference" or "not a significant difference" of
/// `dte` from `ste` (relative, by [`SIGNIFICANT_PTP_DIFFERENCE`]) with the
/// relative difference in %.
fn judged(ste: f64, dte: f64) -> (f64, &'static str) {
    let rel = (dte - ste) / ste;
    (
        100.0 * rel,
        if rel.abs() > SIGNIFICANT_PTP_DIFFERENCE {
            "a significant difference"
        } else {
            "not a significant difference"
        },
    )
}

/// The sentence on the peak-to-peak TEs of one blank pair: over the whole
/// window and after the acceleration (without its inertia offset).
pub fn ptp_sentence(blanks: &str, s: &SteDteSummary) -> String {
    let (rel, verdict) = judged(s.ste_ptp_urad, s.dte_ptp_urad);
    let (rel_after, verdict_after) = judged(
        s.ste_ptp_after_acceleration_urad,
        s.dte_ptp_after_acceleration_urad,
    );
    format!(
        "{blanks}: over the first {} pinion revolution(s) the DTE ({} rpm) has a peak-to-peak of {:.1} µrad against the quasi-STE's ({} rpm) {:.1} µrad, {rel:+.0} %: {verdict}; after the acceleration (beyond {}°) {:.1} against {:.1} µrad, {rel_after:+.0} %: {verdict_after} (our threshold: {:.0} %).",
        s.compared_revolutions,
        s.dynamic.rpm,
        s.dte_ptp_urad,
        s.quasi_static.rpm,
        s.ste_ptp_urad,
        s.acceleration_end_deg,
        s.dte_ptp_after_acceleration_urad,
        s.ste_ptp_after_acceleration_urad,
        100.0 * SIGNIFICANT_PTP_DIFFERENCE
    )
}

/// The slow run is called quasi-static when its TE lies within this
/// share of its own peak-to-peak of the static balance at every compared
/// rotation (our threshold).
pub const QUASI_STATIC_SHARE: f64 = 0.01;

/// The sentence on how quasi-static the slow run of one blank pair is.
pub fn quasi_static_sentence(blanks: &str, s: &SteDteSummary) -> String {
    let share = s.ste_minus_static_max_urad / s.ste_ptp_urad;
    let verdict = if share <= QUASI_STATIC_SHARE {
        "quasi-static"
    } else {
        "not quasi-static"
    };
    format!(
        "{blanks}: the {} rpm run lies within {:.3} µrad of the static balance (the lag that carries the load without inertia) at every compared rotation, {:.2} % of its peak-to-peak: {verdict} by our threshold of {:.0} %.",
        s.quasi_static.rpm,
        s.ste_minus_static_max_urad,
        100.0 * share,
        100.0 * QUASI_STATIC_SHARE
    )
}

/// The sentence locating the transient of one blank pair against the end
/// of the acceleration.
pub fn transient_sentence(blanks: &str, s: &SteDteSummary) -> String {
    let after = s.departure_largest_at_deg - s.acceleration_end_deg;
    let cycles = after / s.mesh_cycle_deg;
    let place = if cycles <= 1.0 {
        format!(
            "{after:.1}° after the acceleration ends at {}°, within its first mesh cycle: the transient sits at the end of the acceleration",
            s.acceleration_end_deg
        )
    } else {
        format!(
            "{after:.1}° ({cycles:.1} mesh cycles) after the acceleration ends at {}°: the largest departure is not the transient of its end",
            s.acceleration_end_deg
        )
    };
    format!(
        "{blanks}: the DTE departs from the quasi-STE by {:+.1} µrad on average while the pinion accelerates (the wheel's inertia torque) and most, {:+.1} µrad, at {:.1}° of pinion rotation, {place}; over the last mesh cycle compared the departure still spans {:.1} µrad.",
        s.departure_during_acceleration_urad,
        s.departure_largest_urad,
        s.departure_largest_at_deg,
        s.departure_last_cycle_ptp_urad
    )
}

/// The section from the stages' output root `out` (None: no root given),
/// its charts copied into `reports`.
pub fn section(out: Option<&Path>, reports: &Path) -> SteDteSection {
    let heading = String::from("## Static against dynamic TE (use case 1)\n\n");
    let (dir, dynamic) = match read(out, STE_DTE_SCENE) {
        Ok(r) => r,
        Err(why) => return absent(heading, &why),
    };
    let runs = picked(&dynamic, |d| d.ste_dte.as_ref());
    if runs.is_empty() {
        return absent(heading, &holds_none(&dir, "STE/DTE comparison"));
    }
    let mut s = heading;
    let first = runs[0].2;
    let _ = writeln!(
        s,
        "The white paper's first use case (its Figure 13 and Table 6) on `reference/scenes/{STE_DTE_SCENE}.toml`: the pinion at {} N·m is run up from rest twice on the same contact-element table, to {} rpm (quasi-static TE, STE) and to {} rpm (dynamic TE, DTE), both at a constant acceleration that ends at {}° of pinion rotation (our ramp shape; the paper: acceleration ending \"around 30 degrees\"), then at constant speed; the slow run is the fast one with time stretched by the speed ratio. Both TEs are compared at the same pinion rotations ({} samples) over the first {} revolution(s).\n",
        first.pinion_torque_nm,
        first.quasi_static.rpm,
        first.dynamic.rpm,
        first.acceleration_end_deg,
        first.samples,
        first.compared_revolutions
    );
    let _ = writeln!(
        s,
        "| pinion / wheel | STE mean, µrad | STE ptp, µrad | DTE mean, µrad | DTE ptp, µrad | STE / DTE ptp after the acceleration, µrad | DTE − STE while accelerating, µrad | largest DTE − STE after it, µrad (at °) | DTE − STE over the last mesh cycle, ptp µrad | STE − static balance, largest µrad |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for (name, _, r) in &runs {
        let _ = writeln!(
            s,
            "| {name} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} / {:.2} | {:+.2} | {:+.2} ({:.1}) | {:.2} | {:.3} |",
            r.ste_mean_urad,
            r.ste_ptp_urad,
            r.dte_mean_urad,
            r.dte_ptp_urad,
            r.ste_ptp_after_acceleration_urad,
            r.dte_ptp_after_acceleration_urad,
            r.departure_during_acceleration_urad,
            r.departure_largest_urad,
            r.departure_largest_at_deg,
            r.departure_last_cycle_ptp_urad,
            r.ste_minus_static_max_urad
        );
    }
    s.push('\n');
    for (name, _, r) in &runs {
        let _ = writeln!(s, "- {}", quasi_static_sentence(name, r));
        let _ = writeln!(s, "- {}", ptp_sentence(name, r));
        let _ = writeln!(s, "- {}", transient_sentence(name, r));
    }
    s.push('\n');
    let (p_time, p_steps, p_step, p_cpu, p_per) = PAPER_TABLE_6;
    let _ = writeln!(
        s,
        "Table 6 our way: the CPU time of each run (its thread) plus that of building the contact-element table the runs of a blank pair share (summed over the threads that built it), on the machine that ran `make validate`; the white paper's row is its own (Simcenter 3D Motion, its machine, 1 to 1,000 rpm).\n"
    );
    let _ = writeln!(
        s,
        "| run | rpm | sim. time, s | time steps | max. step, s | CPU total (table + run), s | CPU per step, µs |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for (name, _, r) in &runs {
        for run in [&r.quasi_static, &r.dynamic] {
            let _ = writeln!(
                s,
                "| {name} | 0 to {} | {:.4} | {} | {:.0e} | {:.1} ({:.1} + {:.2}) | {:.1} |",
                run.rpm,
                run.sim_time_s,
                run.steps,
                run.max_step_s,
                r.table_cpu_s + run.cpu_s,
                r.table_cpu_s,
                run.cpu_s,
                run.cpu_s_per_step * 1e6
            );
        }
    }
    let _ = writeln!(
        s,
        "| white paper, lightweight | 1 to 1,000 | {p_time} | {p_steps} | {p_step:.0e} | ~{p_cpu:.0} (~1.5 h) | ~{:.0} |\n",
        p_per * 1e6
    );
    let figures = charts(
        &dir,
        runs.iter().map(|r| r.1),
        reports,
        (
            "ste_dte.svg",
            "ste_dte",
            "Quasi-static against dynamic TE in the angle domain",
        ),
    );
    figure_lines(&mut s, &figures, false);
    Section {
        markdown: s,
        figures,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use formats::summaries::SteDteRun;

    fn summary(ste_ptp: f64, dte_ptp: f64, largest_at_deg: f64) -> SteDteSummary {
        summary_after(ste_ptp, dte_ptp, ste_ptp, dte_ptp, largest_at_deg)
    }

    fn summary_after(
        ste_ptp: f64,
        dte_ptp: f64,
        ste_after: f64,
        dte_after: f64,
        largest_at_deg: f64,
    ) -> SteDteSummary {
        let run = |rpm: f64| SteDteRun {
            rpm,
            acceleration_time_s: 0.01,
            sim_time_s: 0.15,
            max_step_s: 1e-5,
            steps: 15000,
            rejected_steps: 0,
            cpu_s: 1.0,
            cpu_s_per_step: 6e-5,
        };
        SteDteSummary {
            pinion_torque_nm: 300.0,
            acceleration_end_deg: 30.0,
            compared_revolutions: 1.0,
            samples: 1281,
            mesh_cycle_deg: 18.0,
            quasi_static: run(10.0),
            dynamic: run(1000.0),
            table_cpu_s: 20.0,
            ste_mean_urad: 1050.0,
            ste_ptp_urad: ste_ptp,
            dte_mean_urad: 1060.0,
            dte_ptp_urad: dte_ptp,
            ste_ptp_after_acceleration_urad: ste_after,
            dte_ptp_after_acceleration_urad: dte_after,
            ste_minus_static_max_urad: 0.01,
            departure_during_acceleration_urad: 300.0,
            departure_largest_urad: 320.0,
            departure_largest_at_deg: largest_at_deg,
            departure_last_cycle_ptp_urad: 40.0,
        }
    }

    #[test]
    fn a_dte_ptp_far_from_the_ste_is_called_significant() {
        let t = ptp_sentence("standard / lightweight", &summary(70.0, 280.0, 31.0));
        assert!(t.contains("+300 %: a significant difference;"), "{t}");
    }

    #[test]
    fn a_difference_made_by_the_acceleration_alone_is_judged_apart_from_the_steady_part() {
        let t = ptp_sentence("x", &summary_after(18.0, 280.0, 18.0, 19.0, 31.0));
        assert!(t.contains("+1456 %: a significant difference;"), "{t}");
        assert!(
            t.contains("19.0 against 18.0 µrad, +6 %: not a significant difference"),
            "{t}"
        );
    }

    #[test]
    fn a_dte_ptp_close_to_the_ste_is_not_called_significant() {
        let t = ptp_sentence("standard / standard", &summary(20.0, 21.0, 31.0));
        assert!(t.contains("+5 %: not a significant difference;"), "{t}");
    }

    #[test]
    fn a_largest_departure_within_a_mesh_cycle_of_the_acceleration_end_is_its_transient() {
        let t = transient_sentence("x", &summary(20.0, 80.0, 35.0));
        assert!(
            t.contains("5.0° after the acceleration ends at 30°, within its first mesh cycle"),
            "{t}"
        );
    }

    #[test]
    fn a_largest_departure_far_after_the_acceleration_end_is_not_called_its_transient() {
        let t = transient_sentence("x", &summary(20.0, 80.0, 120.0));
        assert!(t.contains("90.0° (5.0 mesh cycles) after"), "{t}");
        assert!(t.contains("is not the transient of its end"), "{t}");
    }

    #[test]
    fn a_slow_run_at_the_static_balance_is_called_quasi_static() {
        let t = quasi_static_sentence("x", &summary(20.0, 80.0, 31.0));
        assert!(t.contains("0.010 µrad of the static balance"), "{t}");
        assert!(
            t.contains("0.05 % of its peak-to-peak: quasi-static"),
            "{t}"
        );
    }

    #[test]
    fn a_slow_run_off_the_static_balance_is_not_called_quasi_static() {
        let mut s = summary(20.0, 80.0, 31.0);
        s.ste_minus_static_max_urad = 0.5;
        let t = quasi_static_sentence("x", &s);
        assert!(
            t.contains("2.50 % of its peak-to-peak: not quasi-static"),
            "{t}"
        );
    }

    #[test]
    fn a_missing_summary_is_one_line_naming_the_command() {
        let dir = std::env::temp_dir().join(format!("ste_dte_absent_{}", std::process::id()));
        let sec = section(Some(&dir), &dir);
        assert!(sec.markdown.contains("Not run:"), "{}", sec.markdown);
        assert!(sec
            .markdown
            .contains("solver dynamic reference/scenes/white_paper_ste_dte.toml"));
        assert!(sec.figures.is_empty());
    }
}
