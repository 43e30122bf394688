//! The reference sweep's position cache: one JSON file per solved position,
//! shared by shards and later runs (a stopped sweep resumes from it). The
//! cache outlives the result sets, so their `run.json` checksums do not
//! cover it: each file carries the SHA-256 of its own result
//! (`content_sha256`, of the result's JSON without that field), and a file
//! whose result does not match it (edited, or damaged yet still JSON) is
//! not used: the position is solved again and the file replaced. Files
//! written before the checksum existed are used as they are.

use crate::reference::reference_ltca::PositionResult;
use formats::manifest::sha256_text;
use std::path::Path;

/// The field holding the checksum.
const FIELD: &str = "content_sha256";

/// A cached position as read.
#[derive(Debug)]
pub enum Cached {
    /// Its checksum matches (or it has none: written before checksums).
    Valid(Box<PositionResult>),
    /// Readable, but its result is not the one its checksum was made of.
    Changed { found: String, listed: String },
    /// Missing, unreadable or not a position result.
    Absent,
}

/// Reads the cached position at `path`.
pub fn read(path: &Path) -> Cached {
    let Some(mut v) = std::fs::read_to_string(path)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
    else {
        return Cached::Absent;
    };
    let listed = v
        .as_object_mut()
        .and_then(|o| o.remove(FIELD))
        .and_then(|h| h.as_str().map(str::to_string));
    let Ok(r) = serde_json::from_value::<PositionResult>(v) else {
        return Cached::Absent;
    };
    match listed {
        Some(listed) => {
            let found = checksum(&r);
            if found == listed {
                Cached::Valid(Box::new(r))
            } else {
                Cached::Changed { found, listed }
            }
        }
        None => Cached::Valid(Box::new(r)),
    }
}

/// SHA-256 of a result's JSON text.
fn checksum(r: &PositionResult) -> String {
    sha256_text(&serde_json::to_string(r).unwrap_or_default())
}

/// Writes `r` to `path` atomically, with its checksum.
pub fn write(path: &Path, r: &PositionResult) -> Result<(), formats::output::WriteError> {
    let mut v = serde_json::to_value(r).unwrap_or_default();
    if let Some(o) = v.as_object_mut() {
        o.insert(FIELD.into(), checksum(r).into());
    }
    formats::output::write_json(path, &v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small position result (the shape the sweep writes).
    fn result() -> PositionResult {
        serde_json::from_str(
            r#"{"phi": -0.1748, "searched": 835, "constraints": 173,
                "unloaded_te": 9.9485e-06, "unloaded_point": [0.0506, 0.0141, 0.1072],
                "loads": [{"torque_nm": 1.0, "te": 1.2728535201493911e-05,
                           "te_check": 1.27e-05, "active": 5, "max_pressure_pa": 7.6e6,
                           "torque_balance": 0.0, "band_margin_m": 2.9e-05,
                           "search_margin_m": 5.8e-05}],
                "pattern": [[[0.0498, 0.0120, 0.1045], 1.48e8]],
                "new_columns": 38, "cpu_s": 2.77}"#,
        )
        .unwrap()
    }

    #[test]
    fn a_written_position_reads_back_as_it_was() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("phi_1udeg.json");
        write(&p, &result()).unwrap();
        let Cached::Valid(r) = read(&p) else {
            panic!("not valid")
        };
        assert_eq!(r.loads[0].te, result().loads[0].te);
    }

    #[test]
    fn an_edited_position_is_not_used() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("phi_1udeg.json");
        write(&p, &result()).unwrap();
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
        v["loads"][0]["te"] = 1.3e-5.into();
        std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
        assert!(matches!(read(&p), Cached::Changed { .. }));
    }

    #[test]
    fn a_position_from_before_checksums_is_used_and_a_damaged_one_is_absent() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("phi_1udeg.json");
        std::fs::write(&p, serde_json::to_string(&result()).unwrap()).unwrap();
        assert!(matches!(read(&p), Cached::Valid(_)));
        std::fs::write(&p, "{\"phi\": 1.0").unwrap();
        assert!(matches!(read(&p), Cached::Absent));
        assert!(matches!(
            read(&dir.path().join("none.json")),
            Cached::Absent
        ));
    }
}
