//! `reports/results.md`: the loaded TE of the reduced model against the fine
//! reference, per wheel blank and load, with the run times, from the same
//! rows as the report; headed with the date (UTC) and the git commit it was
//! computed at. The same text replaces what stands between the markers
//! [`BEGIN`] and [`END`] in the README, when the README has both.

use crate::report::comparison::Row;
use formats::output::{write_atomic, WriteError};
use std::fmt::Write as _;
use std::path::Path;

/// The README's marker before the results.
pub const BEGIN: &str = "<!-- results:begin -->";
/// The README's marker after the results.
pub const END: &str = "<!-- results:end -->";

/// When and from which commit the results were computed.
#[derive(Debug, Clone, PartialEq)]
pub struct Stamp {
    /// `YYYY-MM-DD`, UTC.
    pub date_utc: String,
    /// `git rev-parse --short HEAD`, or "unknown".
    pub commit: String,
}

impl Stamp {
    /// Today (UTC) and the commit of the working directory.
    pub fn now() -> Self {
        let secs = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs());
        Stamp {
            date_utc: utc_date(secs),
            commit: git_commit(),
        }
    }
}

/// `YYYY-MM-DD` of `secs` seconds after 1970-01-01 00:00 UTC (proleptic
/// Gregorian calendar).
pub fn utc_date(secs: u64) -> String {
    // Days to civil date (H. Hinnant's algorithm), eras of 400 years from
    // 0000-03-01.
    let z = (secs / 86_400) as i64 + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}

/// `git rev-parse --short HEAD` in the working directory; "unknown" when
/// git is not there or this is not a repository.
pub fn git_commit() -> String {
    formats::interrupt::child(&mut std::process::Command::new("git"))
        .args(["rev-parse", "--short", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into())
}

/// The results table of `rows` for scene `scene`, headed with `stamp`.
pub fn markdown(scene: &str, rows: &[Row], stamp: &Stamp) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Loaded transmission error (TE), reduced model against the fine reference FE contact, scene `{scene}`: computed on {} (UTC) at commit `{}`.\n",
        stamp.date_utc, stamp.commit
    );
    if rows.is_empty() {
        let _ = writeln!(
            s,
            "No loaded comparison: run `solver dynamic` and `validate reference` first (`make validate REFERENCE=1` does)."
        );
        return s;
    }
    let one_pinion = rows.iter().all(|r| r.pinion_blank == rows[0].pinion_blank);
    let _ = writeln!(
        s,
        "| {} | load, N·m | mean TE reduced, µrad | mean TE reference, µrad | diff % | ptp TE reduced, µrad | ptp TE reference, µrad | diff % | run time reduced (run + table), s | run time reference, s |",
        if one_pinion { "wheel blank" } else { "pinion / wheel blank" }
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let blank = if one_pinion {
            r.wheel_blank.clone()
        } else {
            format!("{} / {}", r.pinion_blank, r.wheel_blank)
        };
        let _ = writeln!(
            s,
            "| {blank} | {} | {:.2} | {:.2} | {:+.2} | {:.2} | {:.2} | {:+.1} | {:.2} | {:.0} |",
            r.torque_nm,
            r.multibody_te_mean_urad,
            r.reference_te_mean_urad,
            r.te_mean_difference_pct,
            r.multibody_te_ptp_urad,
            r.reference_te_ptp_urad,
            r.te_ptp_difference_pct,
            r.multibody_cpu_s + r.multibody_table_cpu_s,
            r.reference_cpu_s,
        );
    }
    let mut levels: Vec<&str> = rows.iter().map(|r| r.reference_level.as_str()).collect();
    levels.dedup();
    let _ = writeln!(
        s,
        "\nReduced model: the multibody run with the wheel at 10 rpm; its run time is that run's CPU per load plus the CPU of the contact-element table it runs on (built once per blank pair, shared by its loads). Reference: both gear bodies as tet10 FE bodies in penalty contact ({} mesh level), solved statically at every position; its run time is the whole sweep of a blank, all loads at once. Differences are (reduced − reference) / reference at the reference's positions. Measured on this machine; the full comparison is in `reports/report.md`.",
        levels.join(", ")
    );
    s
}

/// `readme` with the text between [`BEGIN`] and [`END`] replaced by
/// `block`; None when the markers are not both there, in this order.
pub fn replace_between_markers(readme: &str, block: &str) -> Option<String> {
    let b = readme.find(BEGIN)? + BEGIN.len();
    let e = b + readme[b..].find(END)?;
    Some(format!(
        "{}\n\n{}\n\n{}",
        &readme[..b],
        block.trim_end(),
        &readme[e..]
    ))
}

/// Replaces the results between the markers of the README at `path`,
/// atomically; true when the README has the markers (and now holds
/// `block`). A README without both markers, or no README, is left as it is.
pub fn update_readme(path: &Path, block: &str) -> Result<bool, WriteError> {
    let Ok(text) = std::fs::read_to_string(path) else {
        return Ok(false);
    };
    match replace_between_markers(&text, block) {
        Some(new) if new != text => write_atomic(path, new.as_bytes()).map(|_| true),
        Some(_) => Ok(true),
        None => Ok(false),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_date_of_known_instants() {
        assert_eq!(utc_date(0), "1970-01-01");
        assert_eq!(utc_date(951_782_400), "2000-02-29");
        assert_eq!(utc_date(1_709_251_199), "2024-02-29");
        assert_eq!(utc_date(1_709_251_200), "2024-03-01");
        assert_eq!(utc_date(4_102_444_800), "2100-01-01");
    }

    #[test]
    fn commit_is_a_short_hash_or_unknown() {
        let c = git_commit();
        assert!(
            c == "unknown" || (c.len() >= 4 && c.chars().all(|c| c.is_ascii_hexdigit())),
            "{c}"
        );
    }

    #[test]
    fn text_between_the_markers_is_replaced_and_the_rest_kept() {
        let readme = format!("# Title\n\nBefore.\n\n{BEGIN}\nold table\n{END}\n\nAfter.\n");
        let new = replace_between_markers(&readme, "| new |\n").unwrap();
        assert_eq!(
            new,
            format!("# Title\n\nBefore.\n\n{BEGIN}\n\n| new |\n\n{END}\n\nAfter.\n")
        );
        // Replacing again gives the same text.
        assert_eq!(replace_between_markers(&new, "| new |\n").unwrap(), new);
    }

    #[test]
    fn without_both_markers_in_order_nothing_is_replaced() {
        assert_eq!(replace_between_markers("no markers", "x"), None);
        assert_eq!(replace_between_markers(&format!("{BEGIN} only"), "x"), None);
        assert_eq!(
            replace_between_markers(&format!("{END} then {BEGIN}"), "x"),
            None
        );
    }

    #[test]
    fn no_readme_is_not_an_error() {
        let p = std::env::temp_dir().join(format!("no_readme_{}.md", std::process::id()));
        assert!(!update_readme(&p, "x").unwrap());
        assert!(!p.exists());
    }
}
