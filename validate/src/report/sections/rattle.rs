//! The report's section "Rattle and wedging": `solver dynamic` on
//! `reference/scenes/rattle.toml` (both flank pairs across the backlash,
//! no load, the pinion at a fluctuating speed, the wheel free).
//!
//! Reads `<out>/rattle/multibody/summary.json`: per blank pair the
//! backlash and free play, the impacts on each flank pair with their rate
//! and the largest contact force, the time shares, and whether the pair
//! wedged (both flank pairs in contact at once) — the sentence is computed
//! from those numbers ([`wedging_sentence`]). The wheel-lag chart
//! (`rattle_te.svg`) is copied as `rattle_<blanks>.svg`. An absent summary
//! is one line of text.

use crate::report::figures::figure_lines;
use crate::report::sections::multibody_runs::{absent, charts, holds_none, picked, read, Section};
use formats::summaries::RattleSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose runs the section reports.
pub const RATTLE_SCENE: &str = "rattle";

/// The section's markdown and its charts.
pub type RattleSection = Section;

/// The sentence on wedging of one blank pair.
pub fn wedging_sentence(blanks: &str, r: &RattleSummary) -> String {
    if r.wedging_episodes == 0 {
        format!(
            "{blanks}: no wedging: at no step of the {} s run were both flank pairs in contact at once.",
            r.sim_time_s
        )
    } else {
        format!(
            "{blanks}: **wedged**: both flank pairs were in contact at once in {} episode(s), {:.2} % of the {} s run.",
            r.wedging_episodes,
            100.0 * r.time_share_wedged,
            r.sim_time_s
        )
    }
}

/// The section from the stages' output root `out` (None: no root given),
/// its charts copied into `reports`.
pub fn section(out: Option<&Path>, reports: &Path) -> RattleSection {
    let heading = String::from("## Rattle and wedging (multibody)\n\n");
    let (dir, dynamic) = match read(out, RATTLE_SCENE) {
        Ok(r) => r,
        Err(why) => return absent(heading, &why),
    };
    let runs = picked(&dynamic, |d| d.rattle.as_ref());
    if runs.is_empty() {
        return absent(heading, &holds_none(&dir, "rattle run"));
    }
    let mut s = heading;
    let r0 = runs[0].2;
    let _ = writeln!(
        s,
        "`reference/scenes/{RATTLE_SCENE}.toml`: both flank pairs across the backlash, the pinion at {} rpm with a speed fluctuation of ±{:.1} % at {} Hz, the wheel free under a drag of {} N·m, {} s. An impact is a contact begun on a flank pair; the pair is wedged where both flank pairs are into contact at once.\n",
        r0.pinion_rpm,
        100.0 * r0.speed_fluctuation,
        r0.frequency_hz,
        r0.wheel_drag_nm,
        r0.sim_time_s
    );
    let _ = writeln!(
        s,
        "| pinion / wheel | backlash at the wheel, µrad | free play, µrad | drive impacts (per s) | coast impacts (per s) | largest contact force drive / coast, N | time in drive / coast / free / wedged, % | pinion mesh torque, N·m | steps, CPU per step µs |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
    for (name, d, r) in &runs {
        let t = r.time_share_drive_coast_free;
        let _ = writeln!(
            s,
            "| {name} | {} | {} | {} ({:.0}) | {} ({:.0}) | {:.0} / {:.0} | {:.1} / {:.1} / {:.1} / {:.2} | {:.1} … {:.1} | {}, {:.1} |",
            d.backlash_urad.map_or("–".into(), |b| format!("{b:.1}")),
            d.free_play_urad
                .map_or("–".into(), |f| format!("{:.1} … {:.1}", f[0], f[1])),
            r.drive_impacts,
            r.drive_impacts as f64 / r.sim_time_s,
            r.coast_impacts,
            r.coast_impacts as f64 / r.sim_time_s,
            r.peak_force_drive_coast_n[0],
            r.peak_force_drive_coast_n[1],
            100.0 * t[0],
            100.0 * t[1],
            100.0 * t[2],
            100.0 * r.time_share_wedged,
            r.mesh_torque_min_max_nm[0],
            r.mesh_torque_min_max_nm[1],
            r.steps,
            r.cpu_s_per_step * 1e6
        );
    }
    s.push('\n');
    for (name, _, r) in &runs {
        let _ = writeln!(s, "- {}", wedging_sentence(name, r));
    }
    s.push('\n');
    let figures = charts(
        &dir,
        runs.iter().map(|r| r.1),
        reports,
        (
            "rattle_te.svg",
            "rattle",
            "Rattle: wheel lag between the drive and the coast contact",
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

    fn run(episodes: usize, share: f64) -> RattleSummary {
        RattleSummary {
            pinion_rpm: 300.0,
            speed_fluctuation: 0.05,
            frequency_hz: 25.0,
            wheel_drag_nm: 0.0,
            sim_time_s: 0.2,
            steps: 20000,
            rejected_steps: 0,
            cpu_s: 0.2,
            cpu_s_per_step: 1e-5,
            drive_impacts: 10,
            coast_impacts: 9,
            time_share_drive_coast_free: [0.4, 0.3, 0.3 - share],
            wedging_episodes: episodes,
            time_share_wedged: share,
            peak_force_drive_coast_n: [5000.0, 4000.0],
            mesh_torque_min_max_nm: [-50.0, 60.0],
            te_min_max_urad: [-100.0, 100.0],
            wheel_rpm_min_max: [130.0, 150.0],
        }
    }

    #[test]
    fn a_run_without_double_contact_is_not_called_wedged() {
        let t = wedging_sentence("x", &run(0, 0.0));
        assert!(t.starts_with("x: no wedging"), "{t}");
    }

    #[test]
    fn a_run_with_double_contact_is_called_wedged_with_its_share() {
        let t = wedging_sentence("x", &run(3, 0.0125));
        assert!(t.contains("**wedged**"), "{t}");
        assert!(t.contains("3 episode(s), 1.25 % of the 0.2 s run"), "{t}");
    }

    #[test]
    fn a_missing_summary_is_one_line_naming_the_command() {
        let dir = std::env::temp_dir().join(format!("rattle_absent_{}", std::process::id()));
        let sec = section(Some(&dir), &dir);
        assert!(sec.markdown.contains("Not run:"), "{}", sec.markdown);
        assert!(sec
            .markdown
            .contains("solver dynamic reference/scenes/rattle.toml"));
    }
}
