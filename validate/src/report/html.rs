//! The small markdown subset the report is written in, as HTML: headings
//! (`#` to `####`), paragraphs, pipe tables (header row, `|---|` delimiter,
//! `\|` for a literal bar), `- ` lists, `**bold**`, `` `code` `` and figure
//! lines `![caption](file.svg)`.
//!
//! Blocks are told apart line by line, so a table needs no blank line before
//! or after it: a table right under a paragraph line or a heading, or a
//! paragraph right under a table, still renders as a table. Figure lines are
//! replaced by the SVG text that `figure` returns for the file (inline, so
//! that the page is self-contained); consecutive figure lines share a
//! two-column grid.

use std::fmt::Write as _;

/// What a line starts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Blank,
    Heading,
    Table,
    Item,
    Figure,
    Text,
}

fn kind(line: &str) -> Kind {
    let t = line.trim_start();
    if t.is_empty() {
        Kind::Blank
    } else if heading(t).is_some() {
        Kind::Heading
    } else if t.starts_with('|') {
        Kind::Table
    } else if t.starts_with("- ") || t.starts_with("* ") {
        Kind::Item
    } else if figure_line(t).is_some() {
        Kind::Figure
    } else {
        Kind::Text
    }
}

/// `(level, text)` of an ATX heading `# ` … `#### `.
fn heading(t: &str) -> Option<(usize, &str)> {
    let level = t.bytes().take_while(|&b| b == b'#').count();
    if !(1..=4).contains(&level) {
        return None;
    }
    t[level..].strip_prefix(' ').map(|h| (level, h.trim()))
}

/// `(caption, file)` of a line that is one image `![caption](file)`.
pub fn figure_line(t: &str) -> Option<(&str, &str)> {
    let rest = t.trim().strip_prefix("![")?;
    let (caption, rest) = rest.split_once("](")?;
    let file = rest.strip_suffix(')')?;
    (!file.is_empty() && !file.contains(' ')).then_some((caption, file))
}

/// HTML-escapes `&`, `<`, `>` and `"`.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Inline markup of escaped text: `**bold**` and `` `code` ``. An unpaired
/// marker stays as it is.
pub fn inline(text: &str) -> String {
    let s = escape(text);
    let s = pairs(&s, "`", "<code>", "</code>");
    pairs(&s, "**", "<strong>", "</strong>")
}

/// Replaces paired `marker`s by `open` … `close`.
fn pairs(s: &str, marker: &str, open: &str, close: &str) -> String {
    let parts: Vec<&str> = s.split(marker).collect();
    let mut out = String::new();
    let paired = parts.len() - (parts.len() + 1) % 2; // an odd count pairs up
    for (i, p) in parts.iter().enumerate() {
        if i > 0 {
            if i < paired {
                out.push_str(if i % 2 == 1 { open } else { close });
            } else {
                out.push_str(marker);
            }
        }
        out.push_str(p);
    }
    out
}

/// Cells of a table row: split at `|` that are not escaped as `\|`, the
/// leading and trailing bar dropped.
fn cells(line: &str) -> Vec<String> {
    let t = line.trim();
    let t = t.strip_prefix('|').unwrap_or(t);
    let t = t
        .strip_suffix('|')
        .filter(|r| !r.ends_with('\\'))
        .unwrap_or(t);
    let mut out = vec![String::new()];
    let mut chars = t.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\\' if chars.peek() == Some(&'|') => {
                out.last_mut().unwrap().push('|');
                chars.next();
            }
            '|' => out.push(String::new()),
            _ => out.last_mut().unwrap().push(c),
        }
    }
    out.iter().map(|c| c.trim().to_string()).collect()
}

/// A delimiter row `|---|:--:|`.
fn is_delimiter(line: &str) -> bool {
    let c = cells(line);
    !c.is_empty()
        && c.iter().all(|c| {
            let c = c.trim_matches(':');
            c.len() >= 3 && c.bytes().all(|b| b == b'-')
        })
}

/// A number-like cell: digits, sign, decimal point and the separators of
/// the report's compound cells (`17.81 (17.81)`, `16.38 / 36.65`).
fn numeric(cell: &str) -> bool {
    let mut has_digit = false;
    for c in cell.chars() {
        match c {
            '0'..='9' => has_digit = true,
            '+' | '-' | '.' | 'e' | ' ' | '/' | '(' | ')' | '–' | '×' => {}
            _ => return false,
        }
    }
    has_digit
}

/// A cell without a value: empty or a dash.
fn no_value(cell: &str) -> bool {
    matches!(cell, "" | "–" | "-")
}

fn table(out: &mut String, lines: &[&str]) {
    let header = lines.len() >= 2 && is_delimiter(lines[1]);
    let body: Vec<Vec<String>> = lines[if header { 2 } else { 0 }..]
        .iter()
        .filter(|l| !is_delimiter(l))
        .map(|l| cells(l))
        .collect();
    // A column is right-aligned when every cell with a value is a number.
    let width = body.iter().map(Vec::len).max().unwrap_or(0);
    let right: Vec<bool> = (0..width)
        .map(|j| {
            let vals: Vec<&str> = body
                .iter()
                .filter_map(|r| r.get(j).map(String::as_str))
                .filter(|c| !no_value(c))
                .collect();
            !vals.is_empty() && vals.iter().all(|c| numeric(c))
        })
        .collect();
    out.push_str("<div class=\"table\"><table>\n");
    if header {
        let _ = writeln!(
            out,
            "<thead><tr>{}</tr></thead>",
            cells(lines[0])
                .iter()
                .map(|c| format!("<th>{}</th>", inline(c)))
                .collect::<String>()
        );
    }
    out.push_str("<tbody>\n");
    for r in &body {
        let row: String = r
            .iter()
            .enumerate()
            .map(|(j, c)| {
                if right[j] {
                    format!("<td class=\"num\">{}</td>", inline(c))
                } else {
                    format!("<td>{}</td>", inline(c))
                }
            })
            .collect();
        let _ = writeln!(out, "<tr>{row}</tr>");
    }
    out.push_str("</tbody></table></div>\n");
}

fn figures(out: &mut String, lines: &[&str], figure: &dyn Fn(&str) -> Option<String>) {
    let grid = lines.len() > 1;
    if grid {
        out.push_str("<div class=\"figures\">\n");
    }
    for l in lines {
        let Some((caption, file)) = figure_line(l) else {
            continue;
        };
        let body = figure(file).unwrap_or_else(|| {
            format!("<img src=\"{}\" alt=\"{}\">", escape(file), escape(caption))
        });
        let _ = writeln!(
            out,
            "<figure title=\"{}\">\n{}\n</figure>",
            escape(caption),
            body.trim()
        );
    }
    if grid {
        out.push_str("</div>\n");
    }
}

/// `id` of a heading: lower-case letters and digits, `-` between words.
pub fn slug(text: &str) -> String {
    let mut s = String::new();
    for c in text.chars() {
        if c.is_alphanumeric() {
            s.extend(c.to_lowercase());
        } else if !s.is_empty() && !s.ends_with('-') {
            s.push('-');
        }
    }
    s.trim_end_matches('-').to_string()
}

/// The HTML body of `md`; `figure` gives the inline markup (SVG) of a
/// figure file, None for an `<img>` link instead.
pub fn body(md: &str, figure: &dyn Fn(&str) -> Option<String>) -> String {
    let lines: Vec<&str> = md.lines().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < lines.len() {
        let k = kind(lines[i]);
        // The run of lines of this block.
        let mut j = i + 1;
        match k {
            Kind::Blank | Kind::Heading => {}
            // A list item continues on indented text lines.
            Kind::Item => {
                while j < lines.len()
                    && (kind(lines[j]) == Kind::Item
                        || (kind(lines[j]) == Kind::Text && lines[j].starts_with(' ')))
                {
                    j += 1;
                }
            }
            _ => {
                while j < lines.len() && kind(lines[j]) == k {
                    j += 1;
                }
            }
        }
        let block = &lines[i..j];
        match k {
            Kind::Blank => {}
            Kind::Heading => {
                let (level, h) = heading(block[0].trim_start()).unwrap_or((2, ""));
                let _ = writeln!(out, "<h{level} id=\"{}\">{}</h{level}>", slug(h), inline(h));
            }
            Kind::Table => table(&mut out, block),
            Kind::Figure => figures(&mut out, block, figure),
            Kind::Item => {
                out.push_str("<ul>\n");
                let mut items: Vec<String> = Vec::new();
                for l in block {
                    let t = l.trim();
                    match t.strip_prefix("- ").or_else(|| t.strip_prefix("* ")) {
                        Some(item) if kind(l) == Kind::Item => items.push(item.to_string()),
                        _ => {
                            if let Some(last) = items.last_mut() {
                                last.push(' ');
                                last.push_str(t);
                            }
                        }
                    }
                }
                for it in items {
                    let _ = writeln!(out, "<li>{}</li>", inline(&it));
                }
                out.push_str("</ul>\n");
            }
            Kind::Text => {
                let text: Vec<&str> = block.iter().map(|l| l.trim()).collect();
                let _ = writeln!(out, "<p>{}</p>", inline(&text.join(" ")));
            }
        }
        i = j;
    }
    out
}

/// Style of the report page: tables with borders and right-aligned numbers,
/// wide tables scroll sideways, SVG figures scale to the column (two per
/// row in a figure grid).
pub const STYLE: &str = "body{font-family:sans-serif;max-width:1200px;margin:auto;padding:0 16px;line-height:1.4;color:#222}\
h1{font-size:1.6em}h2{font-size:1.3em;border-bottom:1px solid #ccc;padding-bottom:2px;margin-top:1.8em}h3{font-size:1.1em;margin-top:1.4em}\
div.table{overflow-x:auto;margin:0.6em 0}table{border-collapse:collapse;font-size:0.85em}\
th,td{border:1px solid #ccc;padding:2px 6px;vertical-align:top}th{background:#f2f2f2;text-align:left}td.num{text-align:right}\
code{background:#f4f4f4;padding:0 2px}\
figure{margin:0.6em 0;max-width:1000px}figure svg,figure img{width:100%;height:auto;display:block}\
div.figures{display:grid;grid-template-columns:1fr 1fr;gap:8px}div.figures figure{margin:0;max-width:none}";

/// A whole HTML page of `md` with `title`.
pub fn page(title: &str, md: &str, figure: &dyn Fn(&str) -> Option<String>) -> String {
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}</style></head><body>\n{}</body></html>\n",
        escape(title),
        body(md, figure)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn html(md: &str) -> String {
        body(md, &|_| None)
    }

    #[test]
    fn table_right_after_a_heading_renders_as_a_table() {
        let h = html("## Unloaded\n| a | b |\n|---|---|\n| 1 | 2 |\n");
        assert!(h.starts_with("<h2 id=\"unloaded\">Unloaded</h2>\n<div class=\"table\"><table>"));
        assert!(h.contains("<thead><tr><th>a</th><th>b</th></tr></thead>"));
        assert!(h.contains("<tr><td class=\"num\">1</td><td class=\"num\">2</td></tr>"));
        assert!(h.contains("</tbody></table></div>"));
    }

    #[test]
    fn table_after_a_blank_line_under_a_heading_renders_as_a_table() {
        let h =
            html("# Report\n\n## Unloaded\n\n| quantity | value |\n|---|---|\n| TE | 37.77 |\n");
        assert_eq!(h.matches("<table>").count(), 1);
        assert!(!h.contains("<p>|"), "no table row as a paragraph: {h}");
    }

    #[test]
    fn paragraph_line_right_after_a_table_closes_the_table() {
        let h = html("| a |\n|---|\n| 1 |\nContact pattern: edge contact.\n");
        let close = h.find("</table>").expect("table closed");
        let p = h
            .find("<p>Contact pattern: edge contact.</p>")
            .expect("paragraph");
        assert!(close < p);
    }

    #[test]
    fn table_right_after_a_paragraph_line_renders_as_a_table() {
        let h = html("Some text\n| a |\n|---|\n| 1 |\n");
        assert!(h.starts_with("<p>Some text</p>\n<div class=\"table\"><table>"));
    }

    #[test]
    fn two_tables_with_text_between_are_two_tables() {
        let h = html("| a |\n|---|\n| 1 |\n\ntext\n\n| b |\n|---|\n| 2 |\n");
        assert_eq!(h.matches("<table>").count(), 2);
        assert_eq!(h.matches("</table>").count(), 2);
    }

    #[test]
    fn escaped_bar_stays_inside_its_cell() {
        let h = html("| mean \\|diff\\| % | b |\n|---|---|\n| 1 | 2 |\n");
        assert!(h.contains("<th>mean |diff| %</th><th>b</th>"), "{h}");
    }

    #[test]
    fn table_without_delimiter_row_has_no_header() {
        let h = html("| a | b |\n| c | d |\n");
        assert!(!h.contains("<th>"));
        assert_eq!(h.matches("<tr>").count(), 2);
    }

    #[test]
    fn empty_cells_are_kept() {
        let h = html("| a | b | c |\n|---|---|---|\n| TE mean | 13.44 | |\n");
        assert!(h.contains("<tr><td>TE mean</td><td class=\"num\">13.44</td><td></td></tr>"));
    }

    #[test]
    fn a_column_is_right_aligned_only_when_all_its_values_are_numbers() {
        let h =
            html("| q | v | w |\n|---|---|---|\n| a | 37.77 (unloaded) | 1 |\n| b | 13.44 | – |\n");
        assert!(
            h.contains("<tr><td>b</td><td>13.44</td><td class=\"num\">–</td></tr>"),
            "{h}"
        );
    }

    #[test]
    fn paragraph_lines_join_into_one_paragraph() {
        assert_eq!(
            html("one\ntwo\n\nthree\n"),
            "<p>one two</p>\n<p>three</p>\n"
        );
    }

    #[test]
    fn bold_and_code_become_strong_and_code() {
        assert_eq!(
            inline("largest **0.0016 µrad** in `validate reference`"),
            "largest <strong>0.0016 µrad</strong> in <code>validate reference</code>"
        );
        assert_eq!(inline("a ** b"), "a ** b", "an unpaired marker stays");
    }

    #[test]
    fn html_special_characters_are_escaped() {
        assert_eq!(html("a < b & c > d\n"), "<p>a &lt; b &amp; c &gt; d</p>\n");
        assert!(html("| x<y |\n").contains("<td>x&lt;y</td>"));
    }

    #[test]
    fn list_items_become_one_list() {
        let h = html("Intro:\n\n- first\n- second with **bold**\n  continued\n\nafter\n");
        assert!(h.contains(
            "<ul>\n<li>first</li>\n<li>second with <strong>bold</strong> continued</li>\n</ul>"
        ));
        assert!(h.ends_with("<p>after</p>\n"));
    }

    #[test]
    fn heading_levels_one_to_four() {
        let h = html("# A\n## B\n### C\n#### D\n##### E\n");
        for t in [
            "<h1 id=\"a\">A</h1>",
            "<h2 id=\"b\">B</h2>",
            "<h3 id=\"c\">C</h3>",
            "<h4 id=\"d\">D</h4>",
        ] {
            assert!(h.contains(t), "{t} in {h}");
        }
        assert!(h.contains("<p>##### E</p>"));
    }

    #[test]
    fn figure_line_inlines_the_svg() {
        let h = body("![Loaded TE](te.svg)\n", &|f| {
            (f == "te.svg").then(|| "<svg viewBox=\"0 0 1 1\"></svg>".to_string())
        });
        assert_eq!(
            h,
            "<figure title=\"Loaded TE\">\n<svg viewBox=\"0 0 1 1\"></svg>\n</figure>\n"
        );
    }

    #[test]
    fn consecutive_figures_share_a_grid_and_a_missing_one_is_linked() {
        let h = body("![a](a.svg)\n![b](b.svg)\n", &|f| {
            (f == "a.svg").then(|| "<svg></svg>".to_string())
        });
        assert!(h.starts_with("<div class=\"figures\">"));
        assert!(h.contains("<img src=\"b.svg\" alt=\"b\">"));
        assert_eq!(h.matches("<figure").count(), 2);
    }

    #[test]
    fn numbers_are_right_aligned_and_words_are_not() {
        assert!(numeric("+3.74"));
        assert!(numeric("17.81 (17.81)"));
        assert!(numeric("1.38e-5"));
        assert!(numeric("16.38 / 36.65 (+8.72 / +0.0)"));
        assert!(!numeric("standard"));
        assert!(!numeric(""));
    }

    #[test]
    fn slug_of_a_heading() {
        assert_eq!(slug("Run time (Table 5)"), "run-time-table-5");
    }
}
