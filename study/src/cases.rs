//! A study's cases: every base scene (design variant) × every grid point
//! and listed case, each written as a scene file of its own and keyed by
//! the hash of what its runs read.
//!
//! A case scene is its base scene with the case's misalignment, the
//! study's torques (when given), the study's analyses switched on, and its
//! design path made absolute; it keeps the base scene's name, so that all
//! cases of one design share its meshes and stiffness files
//! (`<meshes>/<scene name>/`: they do not depend on the misalignment), and
//! writes its results under `<work>/cases/<key>/`, a folder named after its
//! own key: two cases, or two studies, with the same inputs share one.

use crate::study_file::{Analysis, StudyFile};
use geometry::error::InputError;
use geometry::misalignment::Misalignment;
use geometry::scene::Scene;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// One design variant of the study: a base scene with the misalignment
/// zero, what its meshes and stiffness files are made from.
#[derive(Debug, Clone)]
pub struct Design {
    /// The base scene's name (its meshes' folder).
    pub name: String,
    pub base: PathBuf,
    /// The scene file written for the preprocessing jobs.
    pub scene_path: PathBuf,
    /// Hash of the design scene's text, its design file and the mesh root.
    pub key: String,
}

/// One case: a design variant at one misalignment.
#[derive(Debug, Clone, Serialize)]
pub struct Case {
    /// `<scene name>/<case name>`.
    pub id: String,
    /// Index of its design in [`Expanded::designs`].
    #[serde(skip)]
    pub design: usize,
    pub misalignment: Misalignment,
    pub pinion_torque_nm: Vec<f64>,
    /// Its scene file and its output root.
    #[serde(skip)]
    pub scene_path: PathBuf,
    #[serde(skip)]
    pub out: PathBuf,
    pub key: String,
}

/// The study expanded.
#[derive(Debug, Clone)]
pub struct Expanded {
    pub designs: Vec<Design>,
    pub cases: Vec<Case>,
}

/// SHA-256 of a JSON value's text, hex.
pub fn key_of(v: &serde_json::Value) -> String {
    formats::manifest::sha256_text(&v.to_string())
}

/// The first 16 hex digits of a key: folder names.
pub fn short(key: &str) -> &str {
    &key[..16.min(key.len())]
}

/// Errors of the expansion.
#[derive(Debug, thiserror::Error)]
pub enum ExpandError {
    #[error(transparent)]
    Input(#[from] Box<InputError>),
    #[error("{study}: case {case}: {source}")]
    Case {
        study: PathBuf,
        case: String,
        source: Box<InputError>,
    },
    #[error("{study}: scenes {a} and {b} are both named {name}: their meshes would share a folder; give them different names")]
    SameName {
        study: PathBuf,
        a: PathBuf,
        b: PathBuf,
        name: String,
    },
    #[error("cannot write {path}: {source}")]
    Write {
        path: PathBuf,
        source: formats::output::WriteError,
    },
}

/// The misalignments of the study's grid and listed cases, named.
pub fn misalignments(study: &StudyFile, own: Misalignment) -> Vec<(String, Misalignment)> {
    let mut out = Vec::new();
    if let Some(g) = &study.grid {
        let axis = |v: Option<&Vec<f64>>, own: f64| v.cloned().unwrap_or_else(|| vec![own]);
        for &e in &axis(g.offset_mm.as_ref(), own.offset_mm) {
            for &p in &axis(g.pinion_axial_mm.as_ref(), own.pinion_axial_mm) {
                for &gg in &axis(g.wheel_axial_mm.as_ref(), own.wheel_axial_mm) {
                    for &s in &axis(g.shaft_angle_deg.as_ref(), own.shaft_angle_deg) {
                        out.push((
                            format!("E{e:+.4}_P{p:+.4}_G{gg:+.4}_S{s:+.4}"),
                            Misalignment {
                                offset_mm: e,
                                pinion_axial_mm: p,
                                wheel_axial_mm: gg,
                                shaft_angle_deg: s,
                            },
                        ));
                    }
                }
            }
        }
    }
    out.extend(study.cases.iter().map(|c| (c.name.clone(), c.misalignment)));
    out
}

/// Writes `text` to `path` unless it holds it already (content-addressed
/// files: the same name, the same text).
fn write_once(path: &Path, text: &str) -> Result<(), ExpandError> {
    if std::fs::read_to_string(path).is_ok_and(|t| t == text) {
        return Ok(());
    }
    formats::output::write_atomic(path, text.as_bytes()).map_err(|source| ExpandError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// A scene as written for a job: its text and key (with the design file's
/// hash and the mesh root, which its runs read too).
fn scene_text(scene: &Scene) -> String {
    toml::to_string(scene).expect("a scene serializes to TOML")
}

/// Expands the study: checks every case as a scene (misalignment limits
/// included) before writing anything, then writes the design and case
/// scenes into `<work>/scenes/` (named by key; written once).
pub fn expand(
    study: &StudyFile,
    study_path: &Path,
    work: &Path,
    meshes: &Path,
) -> Result<Expanded, ExpandError> {
    let meshes_abs = absolute(meshes);
    let mut designs = Vec::new();
    let mut cases = Vec::new();
    let mut writes = Vec::new();
    let scenes_dir = work.join("scenes");
    for base in study.scene_paths(study_path) {
        let loaded = Scene::load(&base).map_err(Box::new)?;
        if let Some(d) = designs
            .iter()
            .find(|d: &&Design| d.name == loaded.scene.name)
        {
            return Err(ExpandError::SameName {
                study: study_path.to_path_buf(),
                a: d.base.clone(),
                b: base.clone(),
                name: loaded.scene.name.clone(),
            });
        }
        let design_sha256 = formats::manifest::sha256_file(&loaded.design_path).map_err(|e| {
            Box::new(InputError::Io {
                path: loaded.design_path.clone(),
                message: e.to_string(),
            })
        })?;
        let mut scene = loaded.scene.clone();
        scene.design = absolute(&loaded.design_path);
        if let Some(t) = &study.pinion_torque_nm {
            scene.pinion_torque_nm = t.clone();
        }
        scene.analyses.utca |= study.runs(Analysis::Utca);
        scene.analyses.ltca |= study.runs(Analysis::Ltca);
        scene.analyses.multibody |= study.runs(Analysis::Multibody);
        scene.analyses.reference |= study.runs(Analysis::Reference);
        let own = scene.misalignment;
        let mut design_scene = scene.clone();
        design_scene.misalignment = Misalignment::default();
        let text = scene_text(&design_scene);
        let key = key_of(&serde_json::json!({
            "scene": text, "design_sha256": design_sha256, "meshes": meshes_abs,
        }));
        let scene_path = scenes_dir.join(format!("design_{}.toml", short(&key)));
        writes.push((scene_path.clone(), text));
        let d = designs.len();
        designs.push(Design {
            name: scene.name.clone(),
            base: base.clone(),
            scene_path,
            key,
        });
        for (name, m) in misalignments(study, own) {
            let id = format!("{}/{name}", scene.name);
            let mut cs = scene.clone();
            cs.misalignment = m;
            cs.check(study_path)
                .and_then(|_| cs.check_sizes(study_path, &loaded.pair))
                .map_err(|source| ExpandError::Case {
                    study: study_path.to_path_buf(),
                    case: id.clone(),
                    source: Box::new(source),
                })?;
            let text = scene_text(&cs);
            let key = key_of(&serde_json::json!({
                "scene": text, "design_sha256": design_sha256, "meshes": meshes_abs,
            }));
            let scene_path = scenes_dir.join(format!("case_{}.toml", short(&key)));
            writes.push((scene_path.clone(), text));
            cases.push(Case {
                id,
                design: d,
                misalignment: m,
                pinion_torque_nm: cs.pinion_torque_nm.clone(),
                scene_path,
                out: work.join("cases").join(short(&key)),
                key,
            });
        }
    }
    for (path, text) in writes {
        write_once(&path, &text)?;
    }
    Ok(Expanded { designs, cases })
}

/// `p` made absolute against the current directory (not resolved;
/// [`std::path::absolute`], `p` itself where that fails).
pub fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study_file::Grid;

    fn study(grid: Grid) -> StudyFile {
        StudyFile {
            name: "s".into(),
            scenes: vec!["a.toml".into()],
            analyses: vec![Analysis::Ltca],
            pinion_torque_nm: None,
            grid: Some(grid),
            cases: vec![],
            reference: Default::default(),
            slurm: Default::default(),
        }
    }

    /// The grid is the full factorial; an axis left out keeps the scene's
    /// own value.
    #[test]
    fn grid_is_the_full_factorial_with_the_scenes_own_values_elsewhere() {
        let s = study(Grid {
            offset_mm: Some(vec![-0.05, 0.0, 0.05]),
            shaft_angle_deg: Some(vec![0.0, 0.01]),
            ..Default::default()
        });
        let own = Misalignment {
            pinion_axial_mm: 0.02,
            ..Default::default()
        };
        let m = misalignments(&s, own);
        assert_eq!(m.len(), 6);
        assert!(m
            .iter()
            .all(|(_, m)| m.pinion_axial_mm == 0.02 && m.wheel_axial_mm == 0.0));
        let names: std::collections::BTreeSet<_> = m.iter().map(|(n, _)| n.clone()).collect();
        assert_eq!(names.len(), 6, "names are distinct: {names:?}");
        assert_eq!(m[5].0, "E+0.0500_P+0.0200_G+0.0000_S+0.0100");
    }
}
