//! The study file (TOML): base scenes (one per design variant), the cases
//! over them (a grid of misalignments, or a list), the analyses to run,
//! the reference sweep's level and shards, and the Slurm resources. It is
//! checked before any work, like a scene: every error names the file, the
//! field, the value and the limit ([`InputError::Invalid`]).

use geometry::error::InputError;
use geometry::misalignment::Misalignment;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Top level of a study file.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    /// Name of the study: its results go to `<work>/results/<name>/`.
    pub name: String,
    /// Base scenes, relative to the study file: each is one design variant
    /// (its design, ease-off, blanks and mesh levels); every case runs on
    /// every base scene. Their names must differ (meshes are kept per
    /// scene name).
    pub scenes: Vec<PathBuf>,
    /// Analyses of every case: `utca` (`preprocess flanks`), `ltca`
    /// (`solver ltca`), `multibody` (`solver dynamic`), `reference`
    /// (`validate reference`, in shards).
    pub analyses: Vec<Analysis>,
    /// Pinion torques of every case, N·m (default: each scene's own).
    #[serde(default)]
    pub pinion_torque_nm: Option<Vec<f64>>,
    /// A full-factorial grid of the misalignments; an axis left out keeps
    /// the scene's own value.
    #[serde(default)]
    pub grid: Option<Grid>,
    /// Cases listed one by one (beside or instead of the grid).
    #[serde(default)]
    pub cases: Vec<ListedCase>,
    /// The reference sweep of every case.
    #[serde(default)]
    pub reference: ReferenceSettings,
    /// Resources and placement of the Slurm jobs.
    #[serde(default)]
    pub slurm: SlurmSettings,
}

/// One analysis of a case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Analysis {
    Utca,
    Ltca,
    Multibody,
    Reference,
}

impl Analysis {
    pub fn name(self) -> &'static str {
        match self {
            Analysis::Utca => "utca",
            Analysis::Ltca => "ltca",
            Analysis::Multibody => "multibody",
            Analysis::Reference => "reference",
        }
    }
}

/// The misalignment grid: values of each of E, P, G, ΔΣ (absolute, in the
/// scene's `[misalignment]` units), every combination a case.
#[derive(Debug, Clone, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Grid {
    pub offset_mm: Option<Vec<f64>>,
    pub pinion_axial_mm: Option<Vec<f64>>,
    pub wheel_axial_mm: Option<Vec<f64>>,
    pub shaft_angle_deg: Option<Vec<f64>>,
}

/// A case given by name and its misalignments (absent ones zero).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ListedCase {
    pub name: String,
    #[serde(flatten)]
    pub misalignment: Misalignment,
}

/// `[reference]`: the level of both bodies' meshes, the sweep's stride
/// and the number of shards each case's sweep is split into.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ReferenceSettings {
    /// `reduced`, `medium` or `reference`.
    pub level: String,
    /// Every stride-th position of the scene's sweep.
    pub stride: usize,
    /// Shards per sweep (positions i with i mod shards = shard).
    pub shards: usize,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        ReferenceSettings {
            level: "reference".into(),
            stride: 1,
            shards: 4,
        }
    }
}

/// `[slurm]`: where and with what the jobs run on a cluster.
#[derive(Debug, Clone, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SlurmSettings {
    pub partition: Option<String>,
    pub account: Option<String>,
    /// Time limit of every job, Slurm's format (`MM`, `HH:MM:SS`, `D-HH`,
    /// `D-HH:MM:SS`).
    pub time: Option<String>,
    /// Cores per job (default 2).
    pub cpus_per_task: Option<usize>,
    /// Memory of every reference job, GB (default: the factor estimate
    /// from the meshes; see [`crate::resources`]).
    pub reference_mem_gb: Option<f64>,
}

/// Limits of the study file.
pub const MAX_SCENES: usize = 20;
pub const MAX_AXIS_VALUES: usize = 11;
pub const MAX_CASES: usize = 2000;
pub const MAX_SHARDS: usize = 1000;
pub const MAX_CPUS: usize = 1024;
pub const LEVELS: [&str; 3] = ["reduced", "medium", "reference"];

fn invalid(path: &Path, field: &str, value: impl ToString, limit: impl ToString) -> InputError {
    InputError::Invalid {
        path: path.to_path_buf(),
        field: field.into(),
        value: value.to_string(),
        limit: limit.to_string(),
    }
}

impl StudyFile {
    /// Reads and checks a study file.
    pub fn load(path: &Path) -> Result<StudyFile, InputError> {
        let text = InputError::read_text(path)?;
        let s: StudyFile = toml::from_str(&text).map_err(|e| InputError::parse(path, &text, &e))?;
        s.check(path)?;
        Ok(s)
    }

    /// The checks that need no scene (the cases are checked as scenes when
    /// they are expanded).
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        geometry::design_file::check_plain_name(path, "name", &self.name)?;
        if self.scenes.is_empty() || self.scenes.len() > MAX_SCENES {
            return Err(invalid(
                path,
                "scenes",
                format!("{} scenes", self.scenes.len()),
                format!("must list 1 to {MAX_SCENES} base scenes"),
            ));
        }
        if self.analyses.is_empty() {
            return Err(invalid(
                path,
                "analyses",
                "[]",
                "must list at least one of utca, ltca, multibody, reference",
            ));
        }
        let mut a = self.analyses.clone();
        a.sort();
        if let Some(w) = a.windows(2).find(|w| w[0] == w[1]) {
            return Err(invalid(path, "analyses", w[0].name(), "listed twice"));
        }
        if let Some(t) = &self.pinion_torque_nm {
            if t.is_empty() {
                return Err(invalid(
                    path,
                    "pinion_torque_nm",
                    "[]",
                    "must list at least one torque",
                ));
            }
        }
        if let Some(g) = &self.grid {
            for (field, v) in g.axes() {
                if let Some(v) = v {
                    if v.is_empty() || v.len() > MAX_AXIS_VALUES {
                        return Err(invalid(
                            path,
                            &format!("grid.{field}"),
                            format!("{} values", v.len()),
                            format!("must list 1 to {MAX_AXIS_VALUES} values"),
                        ));
                    }
                    if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                        return Err(invalid(path, &format!("grid.{field}"), x, "must be finite"));
                    }
                }
            }
        }
        if self.grid.is_none() && self.cases.is_empty() {
            return Err(invalid(
                path,
                "grid",
                "absent",
                "a study needs a [grid] or at least one [[cases]]",
            ));
        }
        let mut names = std::collections::BTreeSet::new();
        for (i, c) in self.cases.iter().enumerate() {
            geometry::design_file::check_plain_name(path, &format!("cases[{i}].name"), &c.name)?;
            if !names.insert(c.name.as_str()) {
                return Err(invalid(
                    path,
                    &format!("cases[{i}].name"),
                    &c.name,
                    "listed twice",
                ));
            }
        }
        let grid_cases: usize = self.grid.as_ref().map_or(0, |g| {
            g.axes()
                .iter()
                .map(|(_, v)| v.map_or(1, |v| v.len()))
                .product()
        });
        let total = self.scenes.len() * (grid_cases + self.cases.len());
        if total > MAX_CASES {
            return Err(invalid(
                path,
                "grid",
                format!("{total} cases over {} scenes", self.scenes.len()),
                format!("at most {MAX_CASES} cases per study"),
            ));
        }
        let r = &self.reference;
        if !LEVELS.contains(&r.level.as_str()) {
            return Err(invalid(
                path,
                "reference.level",
                &r.level,
                "must be reduced, medium or reference",
            ));
        }
        if r.stride == 0 {
            return Err(invalid(path, "reference.stride", 0, "must be at least 1"));
        }
        if r.shards == 0 || r.shards > MAX_SHARDS {
            return Err(invalid(
                path,
                "reference.shards",
                r.shards,
                format!("must lie in 1..={MAX_SHARDS}"),
            ));
        }
        let sl = &self.slurm;
        if let Some(c) = sl.cpus_per_task {
            if c == 0 || c > MAX_CPUS {
                return Err(invalid(
                    path,
                    "slurm.cpus_per_task",
                    c,
                    format!("must lie in 1..={MAX_CPUS}"),
                ));
            }
        }
        if let Some(m) = sl.reference_mem_gb {
            if !(m.is_finite() && m > 0.0) {
                return Err(invalid(
                    path,
                    "slurm.reference_mem_gb",
                    m,
                    "must be a positive number of GB",
                ));
            }
        }
        if let Some(t) = &sl.time {
            if !slurm_time_ok(t) {
                return Err(invalid(
                    path,
                    "slurm.time",
                    t,
                    "must be Slurm's MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS",
                ));
            }
        }
        for (field, v) in [
            ("slurm.partition", &sl.partition),
            ("slurm.account", &sl.account),
        ] {
            if let Some(v) = v {
                if v.is_empty()
                    || !v
                        .chars()
                        .all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))
                {
                    return Err(invalid(
                        path,
                        field,
                        v,
                        "letters, digits, '-', '_' and '.' only",
                    ));
                }
            }
        }
        Ok(())
    }

    /// Base scene paths resolved against the study file's folder.
    pub fn scene_paths(&self, study_path: &Path) -> Vec<PathBuf> {
        let dir = study_path.parent().unwrap_or(Path::new("."));
        self.scenes.iter().map(|s| dir.join(s)).collect()
    }

    pub fn runs(&self, a: Analysis) -> bool {
        self.analyses.contains(&a)
    }
}

impl Grid {
    /// The four axes by scene field name.
    pub fn axes(&self) -> [(&'static str, Option<&Vec<f64>>); 4] {
        [
            ("offset_mm", self.offset_mm.as_ref()),
            ("pinion_axial_mm", self.pinion_axial_mm.as_ref()),
            ("wheel_axial_mm", self.wheel_axial_mm.as_ref()),
            ("shaft_angle_deg", self.shaft_angle_deg.as_ref()),
        ]
    }
}

/// Slurm's time formats: `MM`, `MM:SS`, `HH:MM:SS`, `D-HH`, `D-HH:MM`,
/// `D-HH:MM:SS`, all numbers.
fn slurm_time_ok(t: &str) -> bool {
    let num = |s: &str| !s.is_empty() && s.len() <= 4 && s.chars().all(|c| c.is_ascii_digit());
    let (days, rest) = match t.split_once('-') {
        Some((d, r)) => (Some(d), r),
        None => (None, t),
    };
    if days.is_some_and(|d| !num(d)) {
        return false;
    }
    let parts: Vec<&str> = rest.split(':').collect();
    let n = parts.len();
    parts.iter().all(|p| num(p)) && (1..=3).contains(&n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<StudyFile, InputError> {
        let p = Path::new("study.toml");
        let s: StudyFile = toml::from_str(text).map_err(|e| InputError::parse(p, text, &e))?;
        s.check(p)?;
        Ok(s)
    }

    const MINIMAL: &str = r#"
name = "s"
scenes = ["a.toml"]
analyses = ["ltca", "reference"]
[grid]
offset_mm = [0.0, 0.05]
"#;

    #[test]
    fn minimal_study_file_is_read_with_the_defaults() {
        let s = parse(MINIMAL).unwrap();
        assert_eq!(s.reference, ReferenceSettings::default());
        assert_eq!(s.grid.unwrap().offset_mm, Some(vec![0.0, 0.05]));
        assert!(s.cases.is_empty());
    }

    /// Every refusal names the field, the value and the limit.
    #[test]
    fn bad_fields_are_refused_with_field_value_and_limit() {
        let cases = [
            (
                MINIMAL.replace("[\"ltca\", \"reference\"]", "[]"),
                "analyses",
            ),
            (
                MINIMAL.replace("[\"ltca\", \"reference\"]", "[\"ltca\", \"ltca\"]"),
                "analyses",
            ),
            (MINIMAL.replace("[0.0, 0.05]", "[]"), "grid.offset_mm"),
            (
                format!("{MINIMAL}[reference]\nshards = 0\n"),
                "reference.shards",
            ),
            (
                format!("{MINIMAL}[reference]\nlevel = \"fine\"\n"),
                "reference.level",
            ),
            (format!("{MINIMAL}[slurm]\ntime = \"1:x\"\n"), "slurm.time"),
            (
                format!("{MINIMAL}[slurm]\npartition = \"a b\"\n"),
                "slurm.partition",
            ),
            (
                format!("{MINIMAL}[slurm]\ncpus_per_task = 0\n"),
                "slurm.cpus_per_task",
            ),
            (
                MINIMAL.replace("scenes = [\"a.toml\"]", "scenes = []"),
                "scenes",
            ),
        ];
        for (text, field) in cases {
            match parse(&text) {
                Err(InputError::Invalid {
                    field: f,
                    value,
                    limit,
                    ..
                }) => {
                    assert_eq!(f, field, "{text}");
                    assert!(!value.is_empty() && !limit.is_empty());
                }
                other => panic!("{field}: expected a refusal, got {other:?}"),
            }
        }
    }

    #[test]
    fn unknown_fields_and_a_study_without_cases_are_refused() {
        assert!(matches!(
            parse(&format!("{MINIMAL}colour = 1\n")),
            Err(InputError::Parse { .. })
        ));
        let no_cases = "name = \"s\"\nscenes = [\"a.toml\"]\nanalyses = [\"ltca\"]\n";
        assert!(
            matches!(parse(no_cases), Err(InputError::Invalid { field, .. }) if field == "grid")
        );
        let twice = format!(
            "{}[[cases]]\nname = \"x\"\n[[cases]]\nname = \"x\"\noffset_mm = 0.1\n",
            no_cases
        );
        assert!(
            matches!(parse(&twice), Err(InputError::Invalid { field, .. }) if field == "cases[1].name")
        );
    }

    #[test]
    fn slurm_time_formats_are_those_of_sbatch() {
        for t in ["30", "30:00", "02:00:00", "1-00", "1-02:00", "1-02:00:00"] {
            assert!(slurm_time_ok(t), "{t}");
        }
        for t in ["", "1:2:3:4", "a", "1-", "-1", "1h"] {
            assert!(!slurm_time_ok(t), "{t}");
        }
    }
}
