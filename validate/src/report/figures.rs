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

/// A figure from an SVG file `from`, copied to `reports/<file>`; None when
/// `from` cannot be read or the copy cannot be written.
pub fn copied(title: &str, from: &Path, reports: &Path, file: &str) -> Option<Figure> {
    let svg = std::fs::read_to_string(from).ok()?;
    formats::output::write_atomic(&reports.join(file), svg.as_bytes()).ok()?;
    Some(Figure {
        title: title.into(),
        file: file.into(),
        svg,
    })
}
