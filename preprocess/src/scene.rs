//! Scene files: what one run needs. Every stage reads the same scene.

use crate::design::{load_pair, PairData};
use crate::error::InputError;
use crate::generation::Side;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Gear blank variant of a member.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Blank {
    /// Solid web.
    Standard,
    /// Thin web with three equally spaced holes.
    Lightweight,
}

/// Top level of a scene file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Name used in output paths.
    pub name: String,
    /// Design file, relative to the scene file.
    pub design: PathBuf,
    /// Loaded flank side: "drive" (pinion concave) or "coast".
    pub loaded_flank: Side,
    /// Blank variants per member; every listed combination is analysed.
    pub blanks: Blanks,
    /// Pinion torques, N·m.
    pub pinion_torque_nm: Vec<f64>,
    pub rotation: Rotation,
    pub mesh: MeshLevels,
    pub utca: UtcaSettings,
    pub analyses: Analyses,
    /// Blank dimensions; missing values get defaults from the design.
    #[serde(default)]
    pub blank_dimensions: crate::gear_body::BlankDimensionsMm,
    /// FE influence fields (stiffness files); defaults when absent.
    #[serde(default)]
    pub stiffness: StiffnessSettings,
    /// Loaded TCA with the reduced model; defaults when absent.
    #[serde(default)]
    pub ltca: LtcaSettings,
}

/// Settings of the loaded TCA (the contact element).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LtcaSettings {
    /// Slices across the face width per tooth pair.
    pub slices: usize,
}

impl Default for LtcaSettings {
    fn default() -> Self {
        LtcaSettings { slices: 30 }
    }
}

/// Settings of the FE influence fields written to the stiffness files.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct StiffnessSettings {
    /// Contact grid points along the profile × face width of each loaded
    /// flank; 0 means "the reduced-order mesh level".
    pub grid_profile: usize,
    pub grid_face: usize,
    /// Radius of the distributed unit load, as a fraction of the largest grid spacing.
    pub load_radius_factor: f64,
    /// Responding teeth on each side of the loaded one.
    pub response_teeth: usize,
    /// Right-hand sides per sequential solve block (two blocks run in parallel).
    pub solve_block: usize,
}

impl Default for StiffnessSettings {
    fn default() -> Self {
        StiffnessSettings {
            grid_profile: 0,
            grid_face: 0,
            load_radius_factor: 0.75,
            response_teeth: 2,
            solve_block: 16,
        }
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Blanks {
    pub pinion: Vec<Blank>,
    pub wheel: Vec<Blank>,
}

/// Rotation range of the loaded analyses.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rotation {
    /// Mesh cycles for a standard wheel blank.
    pub mesh_cycles_standard: f64,
    /// Mesh cycles for a lightweight wheel blank.
    pub mesh_cycles_lightweight: f64,
    /// Pinion rotation step, degrees.
    pub step_deg: f64,
}

/// Elements along the active profile × along the face width of a loaded flank.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlankElements {
    pub profile: u32,
    pub face: u32,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshLevels {
    pub reduced_order: FlankElements,
    pub reference: FlankElements,
}

/// Unloaded TCA settings.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UtcaSettings {
    /// Pinion rotation step, degrees.
    pub step_deg: f64,
    /// Mesh cycles swept.
    pub mesh_cycles: f64,
    /// Samples across the face width along each contact line.
    pub face_samples: usize,
    /// Profile nodes of the tabulated surface of roll angles.
    pub profile_samples: usize,
    /// Separation that marks the contact pattern (marking compound), µm.
    pub marking_compound_um: f64,
    /// Flank grid written for meshing: points along profile × face.
    pub flank_grid_profile: usize,
    pub flank_grid_face: usize,
}

/// Which analyses the run performs.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Analyses {
    pub utca: bool,
    pub mesh: bool,
    pub stiffness: bool,
    pub ltca: bool,
    pub multibody: bool,
    pub reference: bool,
}

/// A scene with its design loaded and checked.
#[derive(Debug, Clone)]
pub struct LoadedScene {
    pub path: PathBuf,
    pub scene: Scene,
    pub design_path: PathBuf,
    pub pair: PairData,
}

impl Scene {
    pub fn load(path: &Path) -> Result<LoadedScene, InputError> {
        let text = std::fs::read_to_string(path).map_err(|e| InputError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        let scene: Scene = toml::from_str(&text).map_err(|e| InputError::parse(path, &text, &e))?;
        scene.check(path)?;
        let design_path = path.parent().unwrap_or(Path::new(".")).join(&scene.design);
        let pair = load_pair(&design_path)?;
        Ok(LoadedScene {
            path: path.to_path_buf(),
            scene,
            design_path,
            pair,
        })
    }

    fn check(&self, path: &Path) -> Result<(), InputError> {
        let fail = |field: &str, value: String, limit: &str| InputError::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            value,
            limit: limit.into(),
        };
        let r = &self.rotation;
        for (f, v) in [
            ("rotation.mesh_cycles_standard", r.mesh_cycles_standard),
            (
                "rotation.mesh_cycles_lightweight",
                r.mesh_cycles_lightweight,
            ),
            ("utca.mesh_cycles", self.utca.mesh_cycles),
        ] {
            if !(v > 0.0 && v <= 100.0) {
                return Err(fail(f, v.to_string(), "must lie in (0, 100]"));
            }
        }
        for (f, v) in [
            ("rotation.step_deg", r.step_deg),
            ("utca.step_deg", self.utca.step_deg),
        ] {
            if !(v > 0.0 && v <= 5.0) {
                return Err(fail(f, v.to_string(), "must lie in (0, 5]"));
            }
        }
        for (f, v) in [
            ("utca.face_samples", self.utca.face_samples),
            ("utca.profile_samples", self.utca.profile_samples),
            ("utca.flank_grid_profile", self.utca.flank_grid_profile),
            ("utca.flank_grid_face", self.utca.flank_grid_face),
        ] {
            if !(5..=1000).contains(&v) {
                return Err(fail(f, v.to_string(), "must lie in [5, 1000]"));
            }
        }
        for (f, e) in [
            ("mesh.reduced_order", self.mesh.reduced_order),
            ("mesh.reference", self.mesh.reference),
        ] {
            for (k, v) in [("profile", e.profile), ("face", e.face)] {
                if !(1..=500).contains(&v) {
                    return Err(fail(
                        &format!("{f}.{k}"),
                        v.to_string(),
                        "must lie in [1, 500]",
                    ));
                }
            }
        }
        if !(self.utca.marking_compound_um > 0.0 && self.utca.marking_compound_um < 100.0) {
            return Err(fail(
                "utca.marking_compound_um",
                self.utca.marking_compound_um.to_string(),
                "must lie in (0, 100)",
            ));
        }
        for (i, t) in self.pinion_torque_nm.iter().enumerate() {
            if !(t.is_finite() && *t >= 0.0) {
                return Err(fail(
                    &format!("pinion_torque_nm[{i}]"),
                    t.to_string(),
                    "must be >= 0",
                ));
            }
        }
        let st = &self.stiffness;
        for (f, v) in [
            ("stiffness.grid_profile", st.grid_profile),
            ("stiffness.grid_face", st.grid_face),
        ] {
            if v != 0 && !(2..=200).contains(&v) {
                return Err(fail(
                    f,
                    v.to_string(),
                    "must be 0 (mesh level) or lie in [2, 200]",
                ));
            }
        }
        if !(st.load_radius_factor >= 0.25 && st.load_radius_factor <= 3.0) {
            return Err(fail(
                "stiffness.load_radius_factor",
                st.load_radius_factor.to_string(),
                "must lie in [0.25, 3]",
            ));
        }
        if st.response_teeth > 5 {
            return Err(fail(
                "stiffness.response_teeth",
                st.response_teeth.to_string(),
                "must be <= 5",
            ));
        }
        if !(1..=256).contains(&st.solve_block) {
            return Err(fail(
                "stiffness.solve_block",
                st.solve_block.to_string(),
                "must lie in [1, 256]",
            ));
        }
        if !(4..=400).contains(&self.ltca.slices) {
            return Err(fail(
                "ltca.slices",
                self.ltca.slices.to_string(),
                "must lie in [4, 400]",
            ));
        }
        if self.blanks.pinion.is_empty() || self.blanks.wheel.is_empty() {
            return Err(fail(
                "blanks",
                "[]".into(),
                "each member needs at least one blank",
            ));
        }
        Ok(())
    }
}
