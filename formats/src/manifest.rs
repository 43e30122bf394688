//! The manifest of a mesh folder (`meshes/<scene>/manifest.json`): for every
//! body mesh, the inputs it was made from, the hash of its `.msh`, the body's
//! mass properties, and the stiffness files computed on it. The mesh stage
//! writes a body's entry, the stiffness stage adds its files; the solver
//! reads nothing else besides the stiffness files themselves.
//!
//! Updates are read-modify-write with an atomic replace
//! ([`crate::output::write_atomic`]); the stages of one scene run one after
//! the other.

use crate::output::{write_json, WriteError};
use crate::paths::{self, MeshLevel};
use geometry::design::Member;
use geometry::gear_body::{Blank, BlankDimensions};
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{FlankElements, LoadedScene};
use geometry::teeth::{opposite_refined_teeth, periodic_teeth, refined_teeth};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Bumped whenever the manifest's layout or meaning changes.
pub const MANIFEST_SCHEMA: u32 = 1;

/// Errors reading a manifest or finding what it should hold.
#[derive(Debug, thiserror::Error)]
pub enum ManifestError {
    #[error("{}: no manifest; run `preprocess mesh` on the scene first", .path.display())]
    Missing { path: PathBuf },
    #[error("{}: {message}", .path.display())]
    Unreadable { path: PathBuf, message: String },
    #[error("{}: schema {found}, this build reads {MANIFEST_SCHEMA}; run `preprocess mesh` again", .path.display())]
    Schema { path: PathBuf, found: u32 },
    #[error("{}: no entry `{stem}`; run `preprocess {stage}` on the scene", .path.display())]
    NoEntry {
        path: PathBuf,
        stem: String,
        stage: &'static str,
    },
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// The manifest of one mesh folder.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub schema: u32,
    /// Body meshes by stem ([`paths::mesh_stem`]).
    pub meshes: BTreeMap<String, MeshEntry>,
}

impl Default for Manifest {
    fn default() -> Self {
        Manifest {
            schema: MANIFEST_SCHEMA,
            meshes: BTreeMap::new(),
        }
    }
}

/// One body mesh and what was computed on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshEntry {
    pub member: Member,
    pub blank: Blank,
    pub level: MeshLevel,
    pub inputs: MeshInputs,
    /// The mesh stage's hash of its inputs (it includes its own schema).
    pub inputs_hash: String,
    /// SHA-256 of the `.msh` file.
    pub msh_sha256: String,
    pub body: BodyProperties,
    /// Stiffness files on this mesh, by stem ([`paths::stiffness_stem`]).
    #[serde(default)]
    pub stiffness: BTreeMap<String, StiffnessEntry>,
}

/// The scene's fields a body mesh depends on, in plain values, so a reader
/// can say which one changed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshInputs {
    /// SHA-256 of the design file's geometry text ([`geometry::design::geometry_text`]).
    pub design_sha256: String,
    /// The resolved blank dimensions (SI), as the mesh stage hashes them.
    pub blank_dimensions: serde_json::Value,
    pub flank_elements: FlankElements,
    pub loaded_flank: Side,
    pub refined_teeth: Vec<usize>,
    pub opposite_refined_teeth: Vec<usize>,
    pub periodic_teeth: Vec<usize>,
}

/// Mass properties of a body, integrated over its mesh by the mesh stage.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyProperties {
    pub volume_m3: f64,
    pub density_kg_m3: f64,
    /// ∫ ρ (x² + y²) dV about the member axis, kg·m².
    pub polar_moment_kgm2: f64,
    /// Nodes of the tet10 mesh (0 in manifests written before it was
    /// recorded): 3 degrees of freedom each, for the memory estimate of
    /// its factor ([`crate::memory_estimate`]).
    #[serde(default)]
    pub nodes: usize,
}

/// One stiffness file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StiffnessEntry {
    /// File name in the folder.
    pub file: String,
    /// The file's `input_hash` attribute.
    pub input_hash: String,
    /// SHA-256 of the file's bytes.
    pub sha256: String,
    pub solved_teeth: Vec<usize>,
}

/// SHA-256 of a file's bytes, hex.
pub fn sha256_file(path: &Path) -> std::io::Result<String> {
    Ok(sha256_bytes(&std::fs::read(path)?))
}

/// SHA-256 of bytes, hex.
pub fn sha256_bytes(bytes: &[u8]) -> String {
    format!("{:x}", Sha256::digest(bytes))
}

/// Why an existing HDF5 file may not be opened: HDF5 opens only files a
/// manifest lists with their present bytes, because a damaged file can
/// crash the HDF5 C library itself (not an error, a segmentation fault).
/// `listed` is the manifest's SHA-256 of `path`, if it lists the file.
/// `None`: the file may be opened.
pub fn not_openable(path: &Path, listed: Option<&str>) -> Option<String> {
    match (listed, sha256_file(path)) {
        (None, _) => Some(
            "no manifest lists it, so its bytes cannot be checked before HDF5 opens them".into(),
        ),
        (Some(_), Err(e)) => Some(format!("unreadable: {e}")),
        (Some(sha), Ok(now)) if now != sha => {
            Some("its bytes differ from the manifest's SHA-256 (changed or damaged)".into())
        }
        _ => None,
    }
}

/// SHA-256 of a text, hex.
pub fn sha256_text(text: &str) -> String {
    sha256_bytes(text.as_bytes())
}

impl MeshInputs {
    /// What a body mesh of `member` × `blank` at `elements` per flank needs
    /// from `scene` (`design_text`: the design file's geometry text).
    pub fn of_scene(
        scene: &LoadedScene,
        g: &PairGeometry,
        design_text: &str,
        member: Member,
        blank: Blank,
        elements: FlankElements,
    ) -> MeshInputs {
        let sc = &scene.scene;
        let dims = BlankDimensions::resolve(&sc.blank_dimensions, &g.data);
        let refined = refined_teeth(g, sc, member, blank);
        let opposite = opposite_refined_teeth(g, sc, member, blank);
        let periodic = periodic_teeth(blank, &refined, &opposite);
        MeshInputs {
            design_sha256: sha256_text(design_text),
            blank_dimensions: serde_json::to_value(&dims).unwrap_or_default(),
            flank_elements: elements,
            loaded_flank: sc.loaded_flank,
            refined_teeth: refined,
            opposite_refined_teeth: opposite,
            periodic_teeth: periodic,
        }
    }

    /// The fields that differ from the scene's, each as `field: manifest vs scene`.
    pub fn differences(&self, scene: &MeshInputs) -> Vec<String> {
        field_differences(self, scene, "in the manifest", "for the scene")
    }

    /// What keeps a mesh made from these inputs from serving a scene that
    /// asks for `scene` (empty: it serves), each as `field: manifest vs
    /// scene`: every field equal, except that a mesh refined on more teeth
    /// (loaded or opposite flanks) serves a scene that asks for fewer; its
    /// periodic sectors follow from its own refined teeth, and the
    /// stiffness plan takes its teeth from the mesh
    /// ([`crate::stiffness_plan::plan`]).
    pub fn serves(&self, scene: &MeshInputs) -> Vec<String> {
        let covers = |have: &[usize], want: &[usize]| want.iter().all(|t| have.contains(t));
        let teeth = MeshInputs {
            refined_teeth: self.refined_teeth.clone(),
            opposite_refined_teeth: self.opposite_refined_teeth.clone(),
            periodic_teeth: self.periodic_teeth.clone(),
            ..scene.clone()
        };
        let mut d = field_differences(self, &teeth, "in the manifest", "for the scene");
        for (field, have, want) in [
            ("refined_teeth", &self.refined_teeth, &scene.refined_teeth),
            (
                "opposite_refined_teeth",
                &self.opposite_refined_teeth,
                &scene.opposite_refined_teeth,
            ),
        ] {
            if !covers(have, want) {
                d.push(format!(
                    "{field}: {have:?} in the manifest, {want:?} for the scene (not all of them)"
                ));
            }
        }
        d
    }
}

impl Manifest {
    /// Reads `<dir>/manifest.json`.
    pub fn read(dir: &Path) -> Result<Manifest, ManifestError> {
        let path = paths::manifest(dir);
        let text = std::fs::read_to_string(&path).map_err(|e| match e.kind() {
            std::io::ErrorKind::NotFound => ManifestError::Missing { path: path.clone() },
            _ => ManifestError::Unreadable {
                path: path.clone(),
                message: e.to_string(),
            },
        })?;
        let schema = serde_json::from_str::<serde_json::Value>(&text)
            .ok()
            .and_then(|v| v.get("schema").and_then(|s| s.as_u64()));
        if let Some(found) = schema.filter(|&s| s != MANIFEST_SCHEMA as u64) {
            return Err(ManifestError::Schema {
                path,
                found: found as u32,
            });
        }
        serde_json::from_str(&text).map_err(|e| ManifestError::Unreadable {
            path,
            message: e.to_string(),
        })
    }

    /// Reads the manifest (an empty one if there is none or it is of
    /// another schema), applies `change` and writes it back atomically.
    pub fn update(dir: &Path, change: impl FnOnce(&mut Manifest)) -> Result<(), ManifestError> {
        let mut m = match Manifest::read(dir) {
            Ok(m) => m,
            Err(ManifestError::Missing { .. } | ManifestError::Schema { .. }) => {
                Manifest::default()
            }
            Err(e) => return Err(e),
        };
        change(&mut m);
        Ok(write_json(&paths::manifest(dir), &m)?)
    }

    /// The entry of the mesh `stem`.
    pub fn mesh(&self, dir: &Path, stem: &str) -> Result<&MeshEntry, ManifestError> {
        self.meshes.get(stem).ok_or_else(|| ManifestError::NoEntry {
            path: paths::manifest(dir),
            stem: stem.into(),
            stage: "mesh",
        })
    }
}

/// The top-level fields in which two values' JSON forms differ, each as
/// `field: <a> <a_is> , <b> <b_is>`.
pub fn field_differences<T: Serialize>(a: &T, b: &T, a_is: &str, b_is: &str) -> Vec<String> {
    let (a, b) = (
        serde_json::to_value(a).unwrap_or_default(),
        serde_json::to_value(b).unwrap_or_default(),
    );
    let (Some(a), Some(b)) = (a.as_object(), b.as_object()) else {
        return vec!["(not comparable)".into()];
    };
    let null = serde_json::Value::Null;
    a.iter()
        .filter(|(k, v)| b.get(*k) != Some(*v))
        .map(|(k, v)| format!("{k}: {v} {a_is}, {} {b_is}", b.get(k).unwrap_or(&null)))
        .collect()
}

/// SHA-256 of a misalignment as its JSON text, the key a result set records
/// it under (`misalignment`): `None` for the aligned pair, which records
/// nothing (so sets from before misalignments existed still compare).
pub fn misalignment_sha256(m: &geometry::misalignment::Misalignment) -> Option<String> {
    (!m.is_zero()).then(|| sha256_text(&serde_json::to_string(m).unwrap_or_default()))
}

#[cfg(test)]
mod tests {
    use super::not_openable;

    #[test]
    fn only_a_listed_unchanged_file_may_be_opened_by_hdf5() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("x.h5");
        std::fs::write(&f, b"bytes").unwrap();
        let sha = super::sha256_file(&f).unwrap();
        assert_eq!(not_openable(&f, Some(&sha)), None);
        assert!(not_openable(&f, None)
            .unwrap()
            .contains("no manifest lists it"));
        std::fs::write(&f, b"bytez").unwrap();
        assert!(not_openable(&f, Some(&sha)).unwrap().contains("differ"));
        std::fs::remove_file(&f).unwrap();
        assert!(not_openable(&f, Some(&sha)).unwrap().contains("unreadable"));
    }
    use super::*;

    fn inputs() -> MeshInputs {
        MeshInputs {
            design_sha256: "d".into(),
            blank_dimensions: serde_json::json!({"pinion_bore_radius": 0.0127}),
            flank_elements: FlankElements {
                profile: 6,
                face: 10,
            },
            loaded_flank: Side::Drive,
            refined_teeth: vec![0, 1, 19],
            opposite_refined_teeth: vec![],
            periodic_teeth: vec![0, 1, 19],
        }
    }

    #[test]
    fn manifest_reads_back_what_update_wrote() {
        let dir = tempfile::tempdir().unwrap();
        assert!(matches!(
            Manifest::read(dir.path()),
            Err(ManifestError::Missing { .. })
        ));
        let entry = MeshEntry {
            member: Member::Pinion,
            blank: Blank::Standard,
            level: MeshLevel::Reduced,
            inputs: inputs(),
            inputs_hash: "h".into(),
            msh_sha256: "m".into(),
            body: BodyProperties {
                nodes: 1000,
                volume_m3: 1.5e-4,
                density_kg_m3: 7850.0,
                polar_moment_kgm2: 1.0 / 3.0 * 1e-3,
            },
            stiffness: BTreeMap::new(),
        };
        Manifest::update(dir.path(), |m| {
            m.meshes
                .insert("pinion_standard_reduced".into(), entry.clone());
        })
        .unwrap();
        let m = Manifest::read(dir.path()).unwrap();
        assert_eq!(
            m.mesh(dir.path(), "pinion_standard_reduced").unwrap(),
            &entry
        );
        assert!(matches!(
            m.mesh(dir.path(), "wheel_standard_reduced"),
            Err(ManifestError::NoEntry { .. })
        ));
    }

    #[test]
    fn changed_mesh_inputs_are_named_by_field() {
        let mut scene = inputs();
        scene.refined_teeth.push(2);
        scene.flank_elements.face = 20;
        let d = inputs().differences(&scene);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(
            d[0].starts_with("flank_elements") && d[1].starts_with("refined_teeth"),
            "{d:?}"
        );
        assert!(inputs().differences(&inputs()).is_empty());
    }

    #[test]
    fn a_mesh_refined_on_more_teeth_serves_a_scene_that_asks_for_fewer() {
        let mut fewer = inputs();
        fewer.refined_teeth.pop();
        fewer.periodic_teeth = vec![];
        assert!(
            inputs().serves(&fewer).is_empty(),
            "{:?}",
            inputs().serves(&fewer)
        );
        assert!(inputs().serves(&inputs()).is_empty());
        // Not the other way round, and not with any other field changed.
        let d = fewer.serves(&inputs());
        assert!(d.len() == 1 && d[0].starts_with("refined_teeth"), "{d:?}");
        let mut more_opposite = inputs();
        more_opposite.opposite_refined_teeth.push(7);
        let d = inputs().serves(&more_opposite);
        assert!(
            d.len() == 1 && d[0].starts_with("opposite_refined_teeth"),
            "{d:?}"
        );
        fewer.flank_elements.face = 99;
        let d = inputs().serves(&fewer);
        assert!(d.len() == 1 && d[0].starts_with("flank_elements"), "{d:?}");
    }

    #[test]
    fn manifest_of_another_schema_is_refused_by_number() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            paths::manifest(dir.path()),
            r#"{"schema": 999, "meshes": {}}"#,
        )
        .unwrap();
        let e = Manifest::read(dir.path()).unwrap_err();
        assert!(matches!(e, ManifestError::Schema { found: 999, .. }), "{e}");
    }
}
