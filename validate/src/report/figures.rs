//! The report's shared figure and CSV helpers: a [`Figure`] (title, file,
//! SVG), copying a stage's SVG into the report folder, reading a stage's
//! CSV by column name, and placing figures in the markdown.

use crate::report::layout;
use std::fmt::Write as _;
use std::path::Path;

/// A figure of the report: its title, its file in the report directory
/// (linked from `report.md`) and the SVG text (inline in `report.html`).
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    pub title: String,
    pub file: String,
    pub svg: String,
}

/// A CSV file's header and columns (non-numeric cells become NaN).
pub type Csv = (Vec<String>, Vec<Vec<f64>>);

/// Columns of a CSV file by header name (non-numeric cells become NaN).
pub fn read_csv(path: &Path) -> Option<Csv> {
    let text = std::fs::read_to_string(path).ok()?;
    let mut lines = text.lines();
    let header: Vec<String> = lines.next()?.split(',').map(str::to_string).collect();
    let mut cols = vec![Vec::new(); header.len()];
    for l in lines.filter(|l| !l.trim().is_empty()) {
        for (c, v) in cols.iter_mut().zip(l.split(',')) {
            c.push(v.trim().parse().unwrap_or(f64::NAN));
        }
    }
    Some((header, cols))
}

/// The column named `name`.
pub fn column<'a>(csv: &'a Csv, name: &str) -> Option<&'a [f64]> {
    let i = csv.0.iter().position(|h| h == name)?;
    Some(&csv.1[i])
}

/// Figure lines `![title](file)` of `figs`: one after the other (side by
/// side in the HTML) when `side_by_side`, else each a block of its own
/// (the column's width).
pub fn figure_lines(s: &mut String, figs: &[Figure], side_by_side: bool) {
    for f in figs {
        // `]` would end the caption early.
        let _ = writeln!(s, "![{}]({})", f.title.replace(['[', ']'], ""), f.file);
        if !side_by_side {
            s.push('\n');
        }
    }
    if side_by_side && !figs.is_empty() {
        s.push('\n');
    }
}

/// `md` with `figs` before its first table (after the text that introduces
/// them), or at its end when it has no table.
pub fn figures_before_table(md: &str, figs: &[Figure]) -> String {
    let mut figure_md = String::new();
    figure_lines(&mut figure_md, figs, false);
    let blocks = layout::blocks(md);
    let Some(k) = blocks.iter().position(|b| b[0].starts_with('|')) else {
        return format!("{md}{figure_md}");
    };
    format!(
        "{}{figure_md}{}",
        layout::join(&blocks[..k]),
        layout::join(&blocks[k..])
    )
}

/// Figures left out or shown unvouched while a report was made, by report
/// folder: the figure and why ([`left_out_section`] says so in the report).
static LEFT_OUT: std::sync::Mutex<Vec<(std::path::PathBuf, String)>> =
    std::sync::Mutex::new(Vec::new());

/// The report's closing section on the figures of `reports` that their
/// result set could not vouch for: left out when changed since their run,
/// shown and named when their folder has no stamp (empty when none); drains
/// them.
pub fn left_out_section(reports: &Path) -> String {
    let mut all = LEFT_OUT.lock().unwrap_or_else(|e| e.into_inner());
    let (mine, rest): (Vec<_>, Vec<_>) = all.drain(..).partition(|(d, _)| d == reports);
    *all = rest;
    if mine.is_empty() {
        return String::new();
    }
    let mut s = String::from(
        "\n## Figures their result sets do not vouch for\n\nA figure whose file changed since its run wrote it is left out; one from a folder without a stamp is shown, and named here.\n\n",
    );
    for (_, note) in mine {
        let _ = writeln!(s, "- {note}");
    }
    s
}

/// A figure from an SVG file `from`, copied to `reports/<file>`; None when
/// `from` cannot be read or the copy cannot be written, or when its result
/// set says it changed since its run wrote it. Left out, or copied from a
/// folder without a stamp, it is named with the reason in the report's
/// closing section.
pub fn copied(title: &str, from: &Path, reports: &Path, file: &str) -> Option<Figure> {
    let note = |n: String| {
        LEFT_OUT
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .push((reports.to_path_buf(), n));
    };
    match formats::result_set::verify_file(from) {
        // No stamp above it: shown, and said so.
        Err(formats::result_set::ResultSetError::Unstamped { dir }) => note(format!(
            "{title}: shown, but not vouched for: {} has no run.json, so whether the figure was replaced since its run cannot be checked",
            dir.display()
        )),
        Err(e) => {
            note(format!("{title}: left out: {e}"));
            return None;
        }
        Ok(_) => {}
    }
    let svg = std::fs::read_to_string(from).ok()?;
    formats::output::write_atomic(&reports.join(file), svg.as_bytes()).ok()?;
    Some(Figure {
        title: title.into(),
        file: file.into(),
        svg,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use formats::result_set::{ResultSet, RUN_FILE};

    /// A committed set in `dir` holding `plot.svg`.
    fn set_with_figure(dir: &Path) -> std::path::PathBuf {
        let set = ResultSet::begin(dir, "test run").unwrap();
        std::fs::write(set.path().join("plot.svg"), "<svg>run</svg>").unwrap();
        set.commit().unwrap();
        dir.join("plot.svg")
    }

    #[test]
    fn figure_its_set_vouches_for_is_copied_and_nothing_is_left_out() {
        let tmp = tempfile::tempdir().unwrap();
        let (from, reports) = (
            set_with_figure(&tmp.path().join("out")),
            tmp.path().join("r"),
        );
        std::fs::create_dir_all(&reports).unwrap();
        let f = copied("A plot", &from, &reports, "a.svg").unwrap();
        assert_eq!(f.svg, "<svg>run</svg>");
        assert_eq!(left_out_section(&reports), "");
    }

    #[test]
    fn replaced_figure_is_left_out_and_unstamped_one_shown_both_named_with_the_reason() {
        let tmp = tempfile::tempdir().unwrap();
        let reports = tmp.path().join("r");
        std::fs::create_dir_all(&reports).unwrap();
        // Changed after its run wrote it.
        let changed = set_with_figure(&tmp.path().join("changed"));
        std::fs::write(&changed, "<svg>other</svg>").unwrap();
        assert!(copied("Changed plot", &changed, &reports, "c.svg").is_none());
        // Its set's stamp deleted: nothing can vouch for it; shown, and
        // said so.
        let unstamped = set_with_figure(&tmp.path().join("unstamped"));
        std::fs::remove_file(tmp.path().join("unstamped").join(RUN_FILE)).unwrap();
        assert!(copied("Unstamped plot", &unstamped, &reports, "u.svg").is_some());
        assert!(!reports.join("c.svg").exists() && reports.join("u.svg").exists());
        let s = left_out_section(&reports);
        assert!(
            s.contains("## Figures their result sets do not vouch for"),
            "{s}"
        );
        assert!(
            s.contains("Changed plot: left out") && s.contains("changed since run"),
            "{s}"
        );
        assert!(
            s.contains("Unstamped plot: shown, but not vouched for") && s.contains("run.json"),
            "{s}"
        );
        // Drained: a second report of the same folder starts clean.
        assert_eq!(left_out_section(&reports), "");
    }
}
