//! Loaded TE of the reduced model (the multibody 10 rpm run, and the
//! quasi-static LTCA) against the reference FE contact, per blank and load:
//! the white paper's Tables 3–5, our way, from the stages' `summary.json`
//! files, with the published values beside them.

//!
//! In this folder: `published_tables` (the printed Tables 3–5), `rows`
//! (one row per blank and load), `tables` (the markdown tables), `studies`
//! (the text and studies after the tables).

mod published_tables;
mod rows;
mod studies;
mod tables;

pub use rows::interpolate;

use formats::summaries::DynamicSummary;
use geometry::design::PublishedDesign;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub use crate::report::comparison_row::Row;

/// The comparison: rows and the markdown section.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    pub rows: Vec<Row>,
    #[serde(skip)]
    pub markdown: String,
}

/// A stage's output that exists but cannot be read as this build's type:
/// written by another version, or a field renamed. The report fails rather
/// than leaving a table out.
#[derive(Debug, thiserror::Error)]
pub enum ComparisonError {
    #[error("{}: {message}; run the stage that writes it again", .path.display())]
    Unreadable { path: PathBuf, message: String },
    #[error(transparent)]
    Published(#[from] crate::report::published::PublishedError),
    #[error(transparent)]
    Mixed(#[from] formats::result_set::ResultSetError),
}

/// Reads a stage's JSON output: `Ok(None)` when the file is not there (the
/// stage has not run), an error when it is there and does not parse.
pub fn read<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<Option<T>, ComparisonError> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(ComparisonError::Unreadable {
                path: path.to_path_buf(),
                message: e.to_string(),
            })
        }
    };
    serde_json::from_str(&text)
        .map(Some)
        .map_err(|e| ComparisonError::Unreadable {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
}

/// A study kept beside the reference sweep ([`formats::added_files`]).
#[derive(Debug)]
pub enum Study<T> {
    /// Not computed.
    Missing,
    /// Listed with its checksum, unchanged, of the sweep there now (where
    /// it depends on it), and readable as this build's type.
    Current(T),
    /// There, but not to be shown: why.
    NotShown(String),
}

/// Reads the study `<dir>/<rel>` through its registry entry.
pub fn read_study<T: for<'de> Deserialize<'de>>(
    dir: &Path,
    rel: &str,
) -> Result<Study<T>, ComparisonError> {
    use formats::added_files::{read_added, AddedState};
    Ok(match read_added(dir, rel)? {
        AddedState::Missing => Study::Missing,
        AddedState::Current(bytes) => match serde_json::from_slice(&bytes) {
            Ok(v) => Study::Current(v),
            Err(e) => Study::NotShown(format!("written by an older version ({e})")),
        },
        other => Study::NotShown(other.why_not().unwrap_or_default()),
    })
}

/// Builds the comparison from `<out>/<scene>/{multibody,reference}/summary.json`;
/// `published` names the design's published tables; `meshes` is the mesh
/// root, to tell whether the convergence study was computed on today's
/// meshes. `Ok(None)` when either stage has not run.
pub fn compare(
    out: &Path,
    scene: &str,
    published: &PublishedDesign,
    meshes: &Path,
) -> Result<Option<Comparison>, ComparisonError> {
    verify_sets(out, scene)?;
    let Some(mb) = read::<Vec<DynamicSummary>>(&out.join(scene).join("multibody/summary.json"))?
    else {
        return Ok(None);
    };
    let (reduced_level, rf) = rows::reference_summaries(out, scene)?;
    if rf.is_empty() {
        return Ok(None);
    }
    let pub_te: Option<crate::report::published::PublishedTeTables> = published
        .loaded_te
        .as_deref()
        .map(crate::report::published::read_toml)
        .transpose()?;
    let pub_cpu: Option<published_tables::PubCpuTable> = published
        .cpu
        .as_deref()
        .map(crate::report::published::read_toml)
        .transpose()?;
    let rows = rows::build(
        out,
        scene,
        &mb,
        &rf,
        &reduced_level,
        pub_te.as_ref(),
        pub_cpu.as_ref(),
    );
    let markdown = studies::sections(out, scene, meshes, &mb, &rows, &rf)?;
    Ok(Some(Comparison { rows, markdown }))
}

/// Checks that the sets put side by side are unchanged since written and
/// read the same design, meshes and stiffness files wherever they share one.
fn verify_sets(out: &Path, scene: &str) -> Result<(), ComparisonError> {
    // The sets put side by side read the same design, meshes and stiffness
    // files wherever they share one.
    let mut sets = vec![
        out.join(scene).join("ltca"),
        out.join(scene).join("multibody"),
    ];
    sets.extend(
        crate::reference::reference_stage::LEVELS_FINEST_FIRST
            .iter()
            .map(|l| crate::reference::reference_stage::reference_dir(out, scene, l)),
    );
    for d in &sets {
        formats::result_set::verify_files(d)?;
    }
    formats::result_set::check_same_inputs(&sets.iter().map(|p| p.as_path()).collect::<Vec<_>>())?;
    Ok(())
}

#[cfg(test)]
mod read_tests {
    use super::*;

    /// A summary that is there but does not parse as this build's type (a
    /// field renamed by another version) is an error naming the file, not a
    /// missing table.
    #[test]
    fn summary_with_a_renamed_field_is_an_error_not_a_missing_table() {
        let dir = tempfile::tempdir().unwrap();
        let mb = dir.path().join("s/multibody");
        std::fs::create_dir_all(&mb).unwrap();
        assert!(
            compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
                .unwrap()
                .is_none()
        );
        // A committed set (stamped, as the solver writes it) whose summary
        // has a renamed field.
        let set = formats::result_set::ResultSet::begin(&mb, "test run").unwrap();
        std::fs::write(
            set.path().join("summary.json"),
            r#"[{"pinion_blank": "standard", "wheel_blank": "standard", "quasi_static_renamed": []}]"#,
        )
        .unwrap();
        set.commit().unwrap();
        let err = compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
            .unwrap_err()
            .to_string();
        assert!(err.contains("multibody/summary.json"), "{err}");
    }

    /// A multibody set and an LTCA set stamped with different stiffness
    /// files (one rerun after `preprocess stiffness`, the other not) are
    /// refused by the report, naming the file and both runs.
    #[test]
    fn ltca_and_multibody_sets_from_other_stiffness_files_are_refused() {
        use formats::result_set::ResultSet;
        let dir = tempfile::tempdir().unwrap();
        let write = |stage: &str, sha: &str| {
            let mut set = ResultSet::begin(&dir.path().join("s").join(stage), stage).unwrap();
            set.record_input("design", "d0").unwrap();
            set.record_input("stiffness:pinion_standard_reduced", sha)
                .unwrap();
            set.commit().unwrap();
        };
        write("ltca", "aaaaaaaaaaaaaaaa");
        write("multibody", "aaaaaaaaaaaaaaaa");
        assert!(
            compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
                .unwrap()
                .is_none()
        );
        write("multibody", "bbbbbbbbbbbbbbbb");
        let err = compare(dir.path(), "s", &PublishedDesign::default(), dir.path())
            .unwrap_err()
            .to_string();
        for w in [
            "stiffness:pinion_standard_reduced",
            "ltca",
            "multibody",
            "aaaaaaaaaaaa",
            "bbbbbbbbbbbb",
        ] {
            assert!(err.contains(w), "{w} not in: {err}");
        }
    }

    #[test]
    fn study_changed_after_it_was_written_is_not_shown() {
        use super::{read_study, Study};
        use formats::added_files::{add_json, Dependence};
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("reference");
        std::fs::create_dir_all(&dir).unwrap();
        let lock = formats::result_set::RunLock::shared(&dir, "study").unwrap();
        add_json(&lock, "a.json", &vec![1.0, 2.0], Dependence::Beside).unwrap();
        add_json(&lock, "b.json", &"text", Dependence::Beside).unwrap();
        drop(lock);
        assert!(matches!(
            read_study::<Vec<f64>>(&dir, "a.json").unwrap(),
            Study::Current(v) if v == [1.0, 2.0]
        ));
        // Registered but not this build's type.
        match read_study::<Vec<f64>>(&dir, "b.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("older version"), "{why}"),
            other => panic!("{other:?}"),
        }
        // A number edited by hand.
        std::fs::write(dir.join("a.json"), "[1.0, 2.5]").unwrap();
        match read_study::<Vec<f64>>(&dir, "a.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("changed"), "{why}"),
            other => panic!("{other:?}"),
        }
        // Written without a registry entry.
        std::fs::write(dir.join("c.json"), "[3.0]").unwrap();
        match read_study::<Vec<f64>>(&dir, "c.json").unwrap() {
            Study::NotShown(why) => assert!(why.contains("not listed"), "{why}"),
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            read_study::<Vec<f64>>(&dir, "d.json").unwrap(),
            Study::Missing
        ));
    }
}
