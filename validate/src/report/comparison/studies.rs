//! The comparison's text after the loaded-TE table: the breakdown of the
//! differences, the contact-pattern peaks, a friction note, and the studies
//! kept beside the reference sweep (mesh convergence, line load, the
//! slice-count trade-off), each shown only when current.

use super::tables::{convergence_markdown, markdown, tradeoff_markdown};
use super::{read_study, ComparisonError, Row, Study};
use crate::reference::reference_stage::BlankSummary;
use formats::summaries::DynamicSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The markdown of the comparison: the tables of `rows`, then every
/// section that follows them.
pub(super) fn sections(
    out: &Path,
    scene: &str,
    meshes: &Path,
    mb: &[DynamicSummary],
    rows: &[Row],
    rf: &[BlankSummary],
) -> Result<String, ComparisonError> {
    let ref_dir = out.join(scene).join("reference");
    let shown = |rel: &str, why: &str, cmd: &str| {
        format!(
            "Not shown: {} is {why}; `{cmd}` recomputes it.",
            ref_dir.join(rel).display()
        )
    };
    let conv =
        read_study::<crate::studies::convergence::Convergence>(&ref_dir, "convergence.json")?;
    let conv_current = match &conv {
        Study::Current(c) if c.stale_levels(&meshes.join(scene)).is_empty() => Some(c),
        _ => None,
    };
    let line_load = other_note(read_study::<crate::studies::line_load::LineLoad>(
        &ref_dir,
        "line_load.json",
    )?);
    let line_load_current = line_load
        .as_ref()
        .and_then(|l| l.as_ref().ok())
        .filter(|l| l.current(&meshes.join(scene)));
    let mut markdown = markdown(rows, rf, conv_current);
    crate::report::differences::breakdown(&mut markdown, rows, rf, conv_current, line_load_current);
    for r in rf {
        let blank = format!("{}_{}", r.pinion_blank, r.wheel_blank);
        if let Some(line) = crate::report::differences::pattern_peak(out, scene, &blank) {
            let _ = writeln!(markdown, "{line}\n");
        }
    }
    if let Some(mu) = mb
        .iter()
        .map(|b| b.friction_coefficient)
        .find(|&mu| mu > 0.0)
    {
        let _ = writeln!(
            markdown,
            "Note: the reduced model ran with Coulomb friction μ = {mu}; the reference contact is frictionless, so part of the difference is friction.\n"
        );
    }
    const CONV: &str = "\n## Mesh convergence of the reference\n";
    match conv {
        Study::Missing => {}
        Study::NotShown(why) => {
            let _ = writeln!(
                markdown,
                "{CONV}\n{}",
                shown("convergence.json", &why, "make convergence")
            );
        }
        Study::Current(c) => {
            let stale = c.stale_levels(&meshes.join(scene));
            if stale.is_empty() {
                convergence_markdown(&mut markdown, &c);
            } else {
                let _ = writeln!(
                    markdown,
                    "{CONV}\nNot shown: the meshes of level(s) {} changed since the study ran; `make convergence` recomputes it.",
                    stale.join(", ")
                );
            }
        }
    }
    const LINE: &str = "\n## Line load: global FE + Weber–Banaschek against fine-mesh FE\n";
    match line_load {
        None => {}
        Some(Err(why)) => {
            let _ = writeln!(
                markdown,
                "{LINE}\n{}",
                shown("line_load.json", &why, "make convergence")
            );
        }
        Some(Ok(l)) if l.current(&meshes.join(scene)) => l.markdown(&mut markdown),
        Some(Ok(_)) => {
            let _ = writeln!(
                markdown,
                "{LINE}\nNot shown: the meshes changed since {} was computed; `make convergence` recomputes it.",
                ref_dir.join("line_load.json").display()
            );
        }
    }
    match read_study::<Vec<crate::studies::tradeoff::Point>>(&ref_dir, "tradeoff.json")? {
        Study::Missing => {}
        Study::Current(t) => tradeoff_markdown(&mut markdown, &t),
        Study::NotShown(why) => {
            let _ = writeln!(
                markdown,
                "\n## Reduced model: run time against error (slices per tooth pair)\n\n{}",
                shown("tradeoff.json", &why, "validate tradeoff")
            );
        }
    }
    Ok(markdown)
}

/// A study as an option: missing `None`, current `Some(Ok)`, there but
/// not to be shown `Some(Err(why))`.
fn other_note<T>(s: Study<T>) -> Option<Result<T, String>> {
    match s {
        Study::Missing => None,
        Study::Current(v) => Some(Ok(v)),
        Study::NotShown(why) => Some(Err(why)),
    }
}
