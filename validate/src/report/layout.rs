//! The loaded comparison's markdown ([`crate::report::comparison::Comparison`]),
//! sorted by what each part is about, so that the report can open with the
//! loaded TE and put the details after the unloaded TCA.
//!
//! The markdown is split into blocks (a heading, a table, a paragraph or a
//! list; a table ends where a line without `|` starts, blank line or not)
//! and sections (at `## ` and `### ` headings). Sections are placed by their
//! heading; one that is not known here goes to the details, so nothing is
//! lost when the comparison gains a section.

/// One block of lines.
type Block = Vec<String>;

fn is_table(line: &str) -> bool {
    line.trim_start().starts_with('|')
}

fn is_item(line: &str) -> bool {
    line.starts_with("- ") || line.starts_with("* ")
}

fn heading_level(line: &str) -> Option<usize> {
    let t = line.trim_start();
    let n = t.bytes().take_while(|&b| b == b'#').count();
    ((1..=4).contains(&n) && t[n..].starts_with(' ')).then_some(n)
}

/// Blocks of `md`: headings on their own; a table, a list or a paragraph
/// ends at a blank line, a heading, or where the kind of line changes
/// (a list goes on with indented lines), as in [`super::html`].
pub fn blocks(md: &str) -> Vec<Block> {
    let mut out: Vec<Block> = Vec::new();
    let mut cur: Block = Vec::new();
    for line in md.lines() {
        if line.trim().is_empty() {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
            continue;
        }
        if heading_level(line).is_some() {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
            out.push(vec![line.to_string()]);
            continue;
        }
        if let Some(first) = cur.first() {
            // A list goes on with items and indented lines; a table with
            // table lines; a paragraph with text lines.
            let goes_on = if is_table(first) {
                is_table(line)
            } else if is_item(first) {
                is_item(line) || (line.starts_with(' ') && !is_table(line))
            } else {
                !is_table(line) && !is_item(line)
            };
            if !goes_on {
                out.push(std::mem::take(&mut cur));
            }
        }
        cur.push(line.to_string());
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// Blocks back to markdown: one blank line between blocks.
pub fn join(blocks: &[Block]) -> String {
    let mut s = String::new();
    for b in blocks {
        for l in b {
            s.push_str(l);
            s.push('\n');
        }
        s.push('\n');
    }
    s
}

/// Where a section of the comparison goes in the report.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Slot {
    /// The loaded TE tables (Tables 3 and 4).
    Te,
    /// Where the differences come from.
    Discussion,
    /// The contact-pattern paragraphs.
    Patterns,
    /// Run time (Table 5).
    RunTime,
    /// Run time against error over the slices per tooth pair.
    Tradeoff,
    /// Method notes: mesh convergence, line load, anything not known here.
    Details,
}

fn slot(heading: &str, level: usize, parent: Slot) -> Slot {
    let h = heading.trim_start_matches('#').trim().to_lowercase();
    if level >= 3 {
        return if h.starts_with("where the differences come from") {
            Slot::Discussion
        } else {
            parent
        };
    }
    if h.starts_with("loaded te") {
        Slot::Te
    } else if h.contains("run time against error") {
        Slot::Tradeoff
    } else if h.starts_with("run time") {
        Slot::RunTime
    } else {
        Slot::Details
    }
}

/// The comparison's markdown by topic, each part markdown text (empty when
/// the comparison has none of it).
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Loaded {
    /// The loaded TE section: how both methods ran, the reference runs, the
    /// table of Tables 3 and 4.
    pub te: String,
    /// Where the differences come from, and the notes that follow the
    /// tables (friction).
    pub discussion: String,
    /// The contact-pattern paragraphs (peak pressure, edge contact).
    pub patterns: String,
    /// Run time (Table 5).
    pub run_time: String,
    /// Run time against error over the slices per tooth pair.
    pub tradeoff: String,
    /// Mesh convergence, line load and any other section.
    pub details: String,
}

/// Sorts the comparison's markdown `md` by topic.
pub fn split(md: &str) -> Loaded {
    let mut parts: Vec<(Slot, Block)> = Vec::new();
    let mut current = Slot::Te;
    let mut parent = Slot::Te;
    // Blocks of the run-time section after its table: notes that belong to
    // the loaded TE discussion.
    let mut tables_in_section = 0;
    for b in blocks(md) {
        if let Some(level) = heading_level(&b[0]) {
            current = slot(&b[0], level, parent);
            if level <= 2 {
                parent = current;
            }
            tables_in_section = 0;
            parts.push((current, b));
            continue;
        }
        if b[0].starts_with("Contact pattern ") {
            parts.push((Slot::Patterns, b));
            continue;
        }
        let mut to = current;
        if current == Slot::RunTime && tables_in_section > 0 {
            to = Slot::Discussion;
        }
        if is_table(&b[0]) {
            tables_in_section += 1;
        }
        parts.push((to, b));
    }
    let text = |s: Slot| -> String {
        let v: Vec<Block> = parts
            .iter()
            .filter(|(k, _)| *k == s)
            .map(|(_, b)| b.clone())
            .collect();
        join(&v)
    };
    Loaded {
        te: text(Slot::Te),
        discussion: text(Slot::Discussion),
        patterns: text(Slot::Patterns),
        run_time: text(Slot::RunTime),
        tradeoff: text(Slot::Tradeoff),
        details: text(Slot::Details),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MD: &str = "## Loaded TE: reduced model against the reference FE contact (Tables 3 and 4)\n\nIntro.\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n## Run time (Table 5)\n\nMeasured here.\n\n| c |\n|---|\n| 3 |\nContact pattern standard / standard (pattern_700nm): edge contact.\n\nNote: the reduced model ran with Coulomb friction μ = 0.05.\n\n\n## Mesh convergence of the reference\n\nLevels.\n\n| d |\n|---|\n| 4 |\n\n## Line load: global FE + Weber–Banaschek against fine-mesh FE\n\nLine.\n\n## Reduced model: run time against error (slices per tooth pair)\n\nSlices.\n\n## Something new\n\nNew.\n";

    #[test]
    fn a_table_ends_where_a_text_line_starts_without_a_blank_line() {
        let b = blocks("| a |\n|---|\n| 1 |\nText.\n");
        assert_eq!(b.len(), 2);
        assert_eq!(b[1], vec!["Text."]);
    }

    #[test]
    fn a_list_ends_where_an_unindented_text_line_starts() {
        let b = blocks("Intro:\n- one\n  more\n- two\nText.\n");
        assert_eq!(
            b,
            vec![
                vec!["Intro:"],
                vec!["- one", "  more", "- two"],
                vec!["Text."]
            ]
        );
    }

    #[test]
    fn sections_go_to_their_topic() {
        let l = split(MD);
        assert!(l.te.starts_with("## Loaded TE") && l.te.contains("| 1 | 2 |"));
        assert!(l.run_time.starts_with("## Run time (Table 5)") && l.run_time.contains("| 3 |"));
        assert!(l
            .tradeoff
            .starts_with("## Reduced model: run time against error"));
        assert!(l.details.starts_with("## Mesh convergence"));
        assert!(l.details.contains("## Line load") && l.details.contains("## Something new"));
    }

    #[test]
    fn notes_after_the_run_time_table_move_to_the_discussion() {
        let l = split(MD);
        assert!(!l.run_time.contains("Coulomb"));
        assert!(l
            .discussion
            .contains("Note: the reduced model ran with Coulomb friction"));
    }

    #[test]
    fn contact_pattern_paragraphs_are_collected_on_their_own() {
        let l = split(MD);
        assert_eq!(
            l.patterns,
            "Contact pattern standard / standard (pattern_700nm): edge contact.\n\n"
        );
        for part in [&l.te, &l.discussion, &l.run_time, &l.details] {
            assert!(!part.contains("Contact pattern"));
        }
    }

    #[test]
    fn where_the_differences_come_from_is_discussion() {
        let md = "## Run time (Table 5)\n\n| c |\n|---|\n| 3 |\n### Where the differences come from\n\nEach part:\n\n- one\n- two\n\nContact pattern x.\n";
        let l = split(md);
        assert!(l
            .discussion
            .starts_with("### Where the differences come from\n\nEach part:\n\n- one\n- two\n"));
        assert_eq!(l.patterns, "Contact pattern x.\n\n");
        assert_eq!(
            l.run_time,
            "## Run time (Table 5)\n\n| c |\n|---|\n| 3 |\n\n"
        );
    }

    #[test]
    fn no_line_is_lost() {
        let l = split(MD);
        let all = [
            &l.te,
            &l.discussion,
            &l.patterns,
            &l.run_time,
            &l.tradeoff,
            &l.details,
        ]
        .iter()
        .map(|s| s.as_str())
        .collect::<String>();
        for line in MD.lines().filter(|l| !l.trim().is_empty()) {
            assert!(all.contains(line), "{line}");
        }
    }
}
