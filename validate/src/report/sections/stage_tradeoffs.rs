//! The report's "Run time against error" section, formatted from
//! `<out>/<scene>/tradeoff/summary.json` ([`TradeoffSummary`]): per stage,
//! what cost and error measure, the Pareto chart with the default ringed,
//! a table of the points, the cheapest setting within the target and
//! whether the default is it; the stages that could not run, with why.

use crate::report::figures::{copied, Figure};
use crate::studies::stage_tradeoffs::TradeoffSummary;
use crate::studies::tradeoff_stage::{sig, StageTradeoff};
use std::fmt::Write as _;
use std::path::Path;

/// The section's markdown (None: no summary) and its figures.
#[derive(Debug, Clone, Default)]
pub struct TradeoffSection {
    pub markdown: Option<String>,
    pub figures: Vec<Figure>,
}

/// Reads the summary under `out` and copies its charts into `reports`
/// (as `tradeoff_<stage>.svg`).
pub fn section(out: &Path, scene: &str, reports: &Path) -> TradeoffSection {
    let s = match TradeoffSummary::read(out, scene) {
        Ok(Some(s)) => s,
        Ok(None) => return TradeoffSection::default(),
        Err(e) => {
            return TradeoffSection {
                markdown: Some(format!(
                    "## Run time against error\n\nThe trade-off summary could not be read ({e:#}); run `make stress` again.\n\n"
                )),
                figures: Vec::new(),
            }
        }
    };
    let dir = out.join(scene).join("tradeoff");
    let mut figures = Vec::new();
    let mut m = String::new();
    let _ = writeln!(m, "## Run time against error\n");
    let _ = writeln!(
        m,
        "Every stage of `{}` at other discretization settings, each against a converged value (`validate stage-tradeoffs`, {:.0} s). A point's cost is thread CPU unless its stage says otherwise; the default setting is ringed, the dashed line is the {} % target.\n",
        s.scene,
        s.wall_s,
        s.stages.first().map_or(1.0, |st| st.target_pct)
    );
    for st in &s.stages {
        let fig = st.chart.as_ref().and_then(|c| {
            copied(
                &st.title,
                &dir.join(c),
                Path::new(reports),
                &format!("tradeoff_{c}"),
            )
        });
        stage(&mut m, st, fig.as_ref());
        figures.extend(fig);
    }
    for (stage, why) in &s.missing {
        let _ = writeln!(m, "- **{stage}**: not run: {why}");
    }
    m.push('\n');
    TradeoffSection {
        markdown: Some(m),
        figures,
    }
}

fn stage(m: &mut String, st: &StageTradeoff, fig: Option<&Figure>) {
    let _ = writeln!(m, "### {}\n", st.title);
    let _ = writeln!(m, "Cost: {}. Error: {}.\n", st.cost, st.error);
    let _ = writeln!(m, "**{}.**\n", capitalised(&st.verdict()));
    if let Some(f) = fig {
        let _ = writeln!(m, "![{}]({})\n", f.title, f.file);
    }
    let _ = writeln!(
        m,
        "| parameter | setting | cost (s) | error (%) | secondary (%) | default |"
    );
    let _ = writeln!(m, "|---|---|---|---|---|---|");
    for p in &st.points {
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {} | {} |",
            p.parameter,
            p.setting,
            sig(p.cpu_s),
            sig(p.error_pct.abs()),
            p.secondary_error_pct.map_or("–".into(), |e| sig(e.abs())),
            if p.is_default { "yes" } else { "" }
        );
    }
    m.push('\n');
    for n in &st.not_run {
        let _ = writeln!(
            m,
            "- {} = {}: not run: {}",
            n.parameter, n.setting, n.reason
        );
    }
    if !st.not_run.is_empty() {
        m.push('\n');
    }
}

fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map_or_else(String::new, |f| f.to_uppercase().chain(c).collect())
}

/// The section's text, or one line saying that there is none.
pub fn text(s: &TradeoffSection) -> String {
    match &s.markdown {
        Some(m) => m.clone(),
        None => "## Run time against error\n\nNo trade-off study: `out/<scene>/tradeoff/summary.json` is absent (`make stress` writes it).\n\n".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::studies::tradeoff_stage::TradeoffPoint;

    fn summary() -> TradeoffSummary {
        let mut st = StageTradeoff::new("ltca", "LTCA title", "CPU (s)", "mean TE error");
        for (n, cpu, err) in [(5, 0.02, 4.0), (10, 0.03, 0.86), (30, 0.08, 0.93)] {
            st.push(TradeoffPoint {
                parameter: "slices".into(),
                setting: format!("{n}"),
                value: n as f64,
                cpu_s: cpu,
                error_pct: err,
                secondary_error_pct: Some(2.0 * err),
                is_default: n == 30,
            });
        }
        st.skip("grid", "24 × 40", "stiffness files missing".into());
        st.finish();
        TradeoffSummary {
            scene: "s".into(),
            stages: vec![st],
            missing: vec![("reference".into(), "no convergence study".into())],
            wall_s: 1.0,
        }
    }

    #[test]
    fn section_names_the_cheapest_setting_the_default_and_what_did_not_run() {
        let out = tempfile::tempdir().unwrap();
        let reports = tempfile::tempdir().unwrap();
        let dir = out.path().join("s").join("tradeoff");
        std::fs::create_dir_all(&dir).unwrap();
        formats::output::write_json(&dir.join("summary.json"), &summary()).unwrap();
        let sec = section(out.path(), "s", reports.path());
        let m = text(&sec);
        assert!(m.contains("## Run time against error"), "{m}");
        assert!(
            m.contains(
                "Cheapest within 1 %: slices = 10 (0.03000 s, 0.860 %); the default (slices = 30)"
            ),
            "{m}"
        );
        assert!(
            m.contains("| slices | 30 | 0.08000 | 0.9300 | 1.860 | yes |"),
            "{m}"
        );
        assert!(
            m.contains("grid = 24 × 40: not run: stiffness files missing"),
            "{m}"
        );
        assert!(
            m.contains("**reference**: not run: no convergence study"),
            "{m}"
        );
    }

    #[test]
    fn no_summary_gives_the_line_that_says_how_to_make_one() {
        let out = tempfile::tempdir().unwrap();
        let sec = section(out.path(), "s", out.path());
        assert!(text(&sec).contains("`make stress` writes it"));
    }
}
