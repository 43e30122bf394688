//! `reports/report.md`, a self-contained `reports/report.html` and
//! `reports/summary.json`, written atomically.

use crate::utca_check::UtcaCheck;
use formats::output::{write_atomic, write_json, WriteError};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// A published value to compare with, and where it comes from.
#[derive(Debug, Clone, Serialize)]
pub struct Published {
    pub value: f64,
    pub source: String,
}

#[derive(Debug, Clone, Serialize)]
pub struct Summary<'a> {
    pub utca: &'a UtcaCheck,
    /// Per blank and load: TE of the reduced model and the reference, their
    /// differences and run times.
    pub loaded_te: Option<&'a [crate::comparison::Row]>,
    pub published_te_ptp_1nm_urad: Option<&'a Published>,
    pub te_ptp_difference_percent: Option<f64>,
}

fn markdown(
    c: &UtcaCheck,
    published: Option<&Published>,
    loaded: Option<&crate::comparison::Comparison>,
) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Validation report: scene `{}`\n", c.name);
    let _ = writeln!(s, "## Unloaded tooth contact ({} flank)\n", c.side);
    let _ = writeln!(s, "| quantity | this toolkit | published |");
    let _ = writeln!(s, "|---|---|---|");
    match published {
        Some(p) => {
            let d = (c.fast_te_ptp_urad - p.value) / p.value * 100.0;
            let _ = writeln!(
                s,
                "| TE peak-to-peak, µrad | {:.2} (unloaded) | {:.1} at 1 N·m ({}); difference {:+.1}% |",
                c.fast_te_ptp_urad, p.value, p.source, d
            );
        }
        None => {
            let _ = writeln!(
                s,
                "| TE peak-to-peak, µrad | {:.2} (unloaded) | not available |",
                c.fast_te_ptp_urad
            );
        }
    }
    let _ = writeln!(s, "| TE mean, µrad | {:.2} | |", c.fast_te_mean_urad);
    let _ = writeln!(s, "| conjugate contact ratio | {:.3} | |", c.contact_ratio);
    let _ = writeln!(
        s,
        "| run time per position | {:.3} ms (surface of roll angles) | direct search {:.1} ms |\n",
        c.fast_ms_per_position, c.direct_ms_per_position
    );
    let _ = writeln!(
        s,
        "## Surface of roll angles against the direct contact search\n\nThe fast UTCA finds contact through the tabulated surface of roll angles; the reference places both flanks, projects every pinion point onto the wheel flank and minimises the gap. Largest difference: **{:.4} µrad**; smallest gap on the active flanks at the reference TE: {:.2e} µm (no penetration).\n",
        c.max_abs_difference_urad, c.min_gap_um
    );
    let _ = writeln!(
        s,
        "| pinion rotation, deg | fast TE, µrad | direct TE, µrad | difference, µrad |"
    );
    let _ = writeln!(s, "|---|---|---|---|");
    for r in &c.rows {
        let _ = writeln!(
            s,
            "| {:.2} | {:.4} | {:.4} | {:+.4} |",
            r.pinion_rotation_deg, r.fast_te_urad, r.direct_te_urad, r.difference_urad
        );
    }
    match loaded {
        Some(cmp) => {
            s.push('\n');
            s.push_str(&cmp.markdown);
        }
        None => {
            let _ = writeln!(
                s,
                "\n## Loaded TCA\n\nNo comparison: run `solver dynamic` and `validate reference` first (`make validate REFERENCE=1` does)."
            );
        }
    }
    s
}

fn html(md: &str, svgs: &[(String, String)]) -> String {
    let mut body = String::new();
    for line in md.lines() {
        let esc = line
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;");
        if let Some(h) = esc.strip_prefix("## ") {
            let _ = writeln!(body, "<h2>{h}</h2>");
        } else if let Some(h) = esc.strip_prefix("# ") {
            let _ = writeln!(body, "<h1>{h}</h1>");
        } else if esc.starts_with('|') {
            if esc.starts_with("|---") {
                continue;
            }
            let cells: Vec<&str> = esc.trim_matches('|').split('|').map(str::trim).collect();
            let _ = writeln!(
                body,
                "<tr>{}</tr>",
                cells
                    .iter()
                    .map(|c| format!("<td>{c}</td>"))
                    .collect::<String>()
            );
        } else if !esc.is_empty() {
            let _ = writeln!(body, "<p>{}</p>", esc.replace("**", ""));
        }
    }
    let body = body
        .replace("</p>\n<tr>", "</p>\n<table><tr>")
        .replace("</tr>\n<h", "</tr></table>\n<h")
        .replace("</tr>\n<p", "</tr></table>\n<p");
    let mut out = String::from("<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Validation report</title><style>body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse}td{border:1px solid #ccc;padding:2px 8px}</style></head><body>\n");
    out.push_str(&body);
    for (title, svg) in svgs {
        let _ = writeln!(out, "<h2>{title}</h2>\n{svg}");
    }
    out.push_str("</body></html>\n");
    out
}

/// Writes the three report files into `dir`; `plots_dir` holds the SVG plots of the flank stage.
pub fn write(
    dir: &Path,
    c: &UtcaCheck,
    published: Option<&Published>,
    plots_dir: &Path,
    loaded: Option<&crate::comparison::Comparison>,
    figures: &[crate::figures::Figure],
) -> Result<(), WriteError> {
    let mut md = markdown(c, published, loaded);
    if !figures.is_empty() {
        md.push_str("\n## Loaded TE and contact pattern figures\n\n");
        for (t, _) in figures {
            let _ = writeln!(md, "- {t} (SVG in report.html)");
        }
    }
    write_atomic(&dir.join("report.md"), md.as_bytes())?;
    let mut svgs: Vec<(String, String)> = [
        ("Unloaded transmission error", "te.svg"),
        ("Path of contact", "contact_path.svg"),
        ("Ease-off", "ease_off.svg"),
    ]
    .iter()
    .filter_map(|(t, f)| {
        std::fs::read_to_string(plots_dir.join(f))
            .ok()
            .map(|s| (t.to_string(), s))
    })
    .collect();
    svgs.extend(figures.iter().cloned());
    write_atomic(&dir.join("report.html"), html(&md, &svgs).as_bytes())?;
    let summary = Summary {
        utca: c,
        loaded_te: loaded.map(|l| l.rows.as_slice()),
        published_te_ptp_1nm_urad: published,
        te_ptp_difference_percent: published
            .map(|p| (c.fast_te_ptp_urad - p.value) / p.value * 100.0),
    };
    write_json(&dir.join("summary.json"), &summary)
}
