//! What the report's sections on other scenes' multibody runs share: the
//! runs read from `<out>/<scene>/multibody/summary.json`, a section that
//! says in one line why it has nothing, and each blank pair's chart copied
//! into the report directory.

use crate::report::figures::{copied, Figure};
use formats::summaries::DynamicSummary;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A section's markdown and the figures it shows (already written into
/// the report directory).
#[derive(Debug, Clone, Default)]
pub struct Section {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

/// The section `heading` with one line saying why it has nothing.
pub fn absent(heading: String, why: &str) -> Section {
    let mut s = heading;
    let _ = writeln!(s, "Not run: {why}.\n");
    Section {
        markdown: s,
        figures: vec![],
    }
}

/// The multibody folder of `scene` under `out` and its runs; Err with the
/// reason (naming the command that writes them) when they cannot be read.
pub fn read(out: Option<&Path>, scene: &str) -> Result<(PathBuf, Vec<DynamicSummary>), String> {
    let out = out.ok_or("the report was built without an output root")?;
    let dir = out.join(scene).join("multibody");
    let path = dir.join("summary.json");
    let runs = std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
        .map_err(|e| {
            format!(
                "`{}` cannot be read ({e}); `solver dynamic reference/scenes/{scene}.toml` writes it",
                path.display()
            )
        })?;
    Ok((dir, runs))
}

/// A run's blank pair as the report names it ("standard / lightweight")
/// and as its folder does ("standard_lightweight").
pub fn blank_names(d: &DynamicSummary) -> (String, String) {
    let name = format!("{:?} / {:?}", d.pinion_blank, d.wheel_blank).to_lowercase();
    let folder = format!("{:?}_{:?}", d.pinion_blank, d.wheel_blank).to_lowercase();
    (name, folder)
}

/// Each run's chart `file` (in its blank pair's folder under `dir`)
/// copied into `reports` as `<prefix>_<blanks>.svg`, titled `title` and
/// the blank pair.
pub fn charts<'a>(
    dir: &Path,
    runs: impl Iterator<Item = &'a DynamicSummary>,
    reports: &Path,
    (file, prefix, title): (&str, &str, &str),
) -> Vec<Figure> {
    runs.filter_map(|d| {
        let (name, folder) = blank_names(d);
        copied(
            &format!("{title}, {name}"),
            &dir.join(&folder).join(file),
            reports,
            &format!("{prefix}_{folder}.svg"),
        )
    })
    .collect()
}

/// The runs that hold what `pick` takes from them, each with its blank
/// pair's name.
pub fn picked<'a, T>(
    runs: &'a [DynamicSummary],
    pick: impl Fn(&'a DynamicSummary) -> Option<&'a T>,
) -> Vec<(String, &'a DynamicSummary, &'a T)> {
    runs.iter()
        .filter_map(|d| pick(d).map(|x| (blank_names(d).0, d, x)))
        .collect()
}

/// The line of a section whose summary at `dir` holds no `what`.
pub fn holds_none(dir: &Path, what: &str) -> String {
    format!("`{}` holds no {what}", dir.join("summary.json").display())
}
