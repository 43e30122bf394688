//! `study collect`: the results of every case merged into one result set
//! `<work>/results/<study>/` (`summary.json`, `cases.csv`, `report.md`,
//! a chart per misalignment axis that varies), written only when every job
//! of the study is done; otherwise nothing is written and the error names
//! each job that is missing, with its state and log.

use crate::cases::{Case, Expanded};
use crate::jobs::Job;
use crate::status::{JobState, JobStatus};
use crate::study_file::{Analysis, StudyFile};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The numbers of one analysis at one torque.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Numbers {
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    pub max_pressure_mpa: Option<f64>,
    pub pinion_root_tension_mpa: Option<f64>,
    pub wheel_root_tension_mpa: Option<f64>,
}

/// One case, blank pair and torque.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    pub case: String,
    pub offset_mm: f64,
    pub pinion_axial_mm: f64,
    pub wheel_axial_mm: f64,
    pub shaft_angle_deg: f64,
    /// `<pinion blank>_<wheel blank>`.
    pub blanks: String,
    pub torque_nm: f64,
    /// The UTCA's mean TE at the reference's positions (its unloaded
    /// check), else at the LTCA's, µrad: the geometric part of the mean,
    /// which a misalignment shifts (it may pass through zero).
    pub utca_te_mean_urad: Option<f64>,
    /// The UTCA's peak-to-peak TE of `preprocess flanks` (the `utca`
    /// analysis), µrad.
    pub utca_te_ptp_urad: Option<f64>,
    pub ltca: Option<Numbers>,
    pub multibody: Option<Numbers>,
    pub reference: Option<Numbers>,
}

impl Row {
    /// The reduced model's numbers: the multibody 10 rpm run where the
    /// study ran it (what the project's main table compares), else the
    /// LTCA.
    pub fn reduced(&self) -> Option<(&'static str, &Numbers)> {
        self.multibody
            .as_ref()
            .map(|n| ("multibody", n))
            .or(self.ltca.as_ref().map(|n| ("ltca", n)))
    }
}

/// The collected study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Collected {
    pub study: String,
    pub analyses: Vec<Analysis>,
    pub reference_level: String,
    pub cases: usize,
    pub rows: Vec<Row>,
}

/// The study is not finished.
#[derive(Debug, thiserror::Error)]
#[error("study {study}: {} of {total} jobs are not done, nothing collected:\n{}", .missing.len(), .missing.join("\n"))]
pub struct Incomplete {
    pub study: String,
    pub total: usize,
    pub missing: Vec<String>,
}

/// Refuses a study with jobs not done, naming each.
pub fn check_complete(study: &str, status: &[JobStatus]) -> Result<(), Incomplete> {
    let missing: Vec<String> = status
        .iter()
        .filter(|s| s.state != JobState::Done)
        .map(|s| {
            format!(
                "  {}: {} (log {})",
                s.label,
                s.state.name(),
                s.log.display()
            )
        })
        .collect();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(Incomplete {
            study: study.into(),
            total: status.len(),
            missing,
        })
    }
}

fn read_json(path: &Path) -> anyhow::Result<Value> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        anyhow::anyhow!(
            "{}: cannot read ({e}); the job that writes it is done, so the case folder was changed",
            path.display()
        )
    })?;
    Ok(serde_json::from_str(&text)?)
}

fn f(v: &Value, k: &str) -> Option<f64> {
    v.get(k).and_then(Value::as_f64)
}

/// The numbers of a load entry of an LTCA or reference summary.
fn numbers(load: &Value) -> Option<Numbers> {
    let root = |m: &str| {
        load.get("root_stress")
            .and_then(|r| r.get(m))
            .and_then(|r| f(r, "tension_mpa"))
    };
    Some(Numbers {
        te_mean_urad: f(load, "te_mean_urad")?,
        te_ptp_urad: f(load, "te_ptp_urad")?,
        max_pressure_mpa: f(load, "max_pressure_mpa"),
        pinion_root_tension_mpa: root("pinion"),
        wheel_root_tension_mpa: root("wheel"),
    })
}

/// The entry of blank pair `[p, w]` in a summary list (`ltca`,
/// `reference`, `multibody`), if the analysis ran.
fn blank_entry<'a>(summary: &'a Option<Value>, p: &str, w: &str) -> Option<&'a Value> {
    summary.as_ref()?.as_array()?.iter().find(|b| {
        b.get("pinion_blank").and_then(Value::as_str) == Some(p)
            && b.get("wheel_blank").and_then(Value::as_str) == Some(w)
    })
}

/// The list `field` of a blank pair's entry (its loads), empty without one.
fn entry_list<'a>(entry: Option<&'a Value>, field: &str) -> Vec<&'a Value> {
    entry
        .and_then(|b| b.get(field))
        .and_then(Value::as_array)
        .map(|a| a.iter().collect())
        .unwrap_or_default()
}

fn at_torque(loads: &[&Value], t: f64) -> Option<Numbers> {
    loads
        .iter()
        .find(|l| f(l, "torque_nm") == Some(t))
        .and_then(|l| numbers(l))
}

/// Reads the case's results.
fn case_rows(study: &StudyFile, ex: &Expanded, c: &Case) -> anyhow::Result<Vec<Row>> {
    let scene = geometry::scene::Scene::load(&c.scene_path)?;
    let name = &ex.designs[c.design].name;
    let base = c.out.join(name);
    let ltca = study
        .runs(Analysis::Ltca)
        .then(|| read_json(&base.join("ltca").join("summary.json")))
        .transpose()?;
    let multibody = study
        .runs(Analysis::Multibody)
        .then(|| read_json(&base.join("multibody").join("summary.json")))
        .transpose()?;
    let reference = study
        .runs(Analysis::Reference)
        .then(|| {
            read_json(
                &formats::paths::reference_dir(&c.out, name, &study.reference.level)
                    .join("summary.json"),
            )
        })
        .transpose()?;
    let utca = study
        .runs(Analysis::Utca)
        .then(|| read_json(&base.join("flanks").join("summary.json")))
        .transpose()?;
    let utca_ptp = utca
        .as_ref()
        .and_then(|u| u.get("utca"))
        .and_then(|u| f(u, "te_ptp_urad"));
    let mut rows = Vec::new();
    for p in &scene.scene.blanks.pinion {
        for w in &scene.scene.blanks.wheel {
            let blanks = format!("{}_{}", p.name(), w.name());
            let (le, me, re) = (
                blank_entry(&ltca, p.name(), w.name()),
                blank_entry(&multibody, p.name(), w.name()),
                blank_entry(&reference, p.name(), w.name()),
            );
            let (l, m, r) = (
                entry_list(le, "loads"),
                entry_list(me, "quasi_static"),
                entry_list(re, "loads"),
            );
            let utca_mean = re
                .and_then(|b| b.get("unloaded"))
                .and_then(|u| f(u, "utca_te_mean_urad"))
                .or_else(|| le.and_then(|b| f(b, "utca_te_mean_urad")));
            for &t in &c.pinion_torque_nm {
                rows.push(Row {
                    case: c.id.clone(),
                    offset_mm: c.misalignment.offset_mm,
                    pinion_axial_mm: c.misalignment.pinion_axial_mm,
                    wheel_axial_mm: c.misalignment.wheel_axial_mm,
                    shaft_angle_deg: c.misalignment.shaft_angle_deg,
                    blanks: blanks.clone(),
                    torque_nm: t,
                    utca_te_mean_urad: utca_mean,
                    utca_te_ptp_urad: utca_ptp,
                    ltca: at_torque(&l, t),
                    multibody: at_torque(&m, t),
                    reference: at_torque(&r, t),
                });
            }
        }
    }
    Ok(rows)
}

/// Collects the study into its result set; refuses (writing nothing) when
/// a job is not done.
pub fn collect(
    study: &StudyFile,
    ex: &Expanded,
    jobs: &[Job],
    status: &[JobStatus],
    work: &Path,
) -> anyhow::Result<(PathBuf, Collected)> {
    debug_assert_eq!(jobs.len(), status.len());
    check_complete(&study.name, status)?;
    let mut rows = Vec::new();
    for c in &ex.cases {
        rows.extend(case_rows(study, ex, c)?);
    }
    let collected = Collected {
        study: study.name.clone(),
        analyses: study.analyses.clone(),
        reference_level: study.reference.level.clone(),
        cases: ex.cases.len(),
        rows,
    };
    let dir = work.join("results").join(&study.name);
    let mut set =
        formats::result_set::ResultSet::begin(&dir, &format!("study collect {}", study.name))?;
    for c in &ex.cases {
        set.record_input(&format!("case:{}", c.id), &c.key)?;
    }
    formats::output::write_json(&set.path().join("summary.json"), &collected)?;
    formats::output::write_atomic(
        &set.path().join("cases.csv"),
        crate::report::csv(&collected).as_bytes(),
    )?;
    let charts = crate::report::charts(&collected, set.path())?;
    formats::output::write_atomic(
        &set.path().join("report.md"),
        crate::report::markdown(&collected, &charts).as_bytes(),
    )?;
    set.commit()?;
    Ok((dir, collected))
}
