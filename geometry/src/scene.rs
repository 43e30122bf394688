//! Scene files: what one run needs. Every stage reads the same scene.

use crate::design::PairData;
use crate::design_file::load_pair;
use crate::error::InputError;
use crate::generation::Side;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub use crate::gear_body::Blank;
pub use crate::scene_contact_law::{ForceLaw, ImpactSettings, LoadRun, StepShape};

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
    /// Multibody runs (quasi-static and run-up); defaults when absent.
    #[serde(default)]
    pub multibody: MultibodySettings,
    /// 8-DOF lumped dynamic model (`solver lumped`); absent: not run.
    #[serde(default)]
    pub lumped: Option<crate::scene_lumped::LumpedSettings>,
    /// Static misalignments E, P, G, ΔΣ of the pair (the pinion's pose
    /// relative to the wheel in UTCA, LTCA, multibody and reference); all
    /// zero when absent. Meshes and stiffness files do not depend on them.
    #[serde(default)]
    pub misalignment: crate::misalignment::Misalignment,
    /// Ranges of `solver sensitivity` as the scene writes them; absent:
    /// the defaults ([`Scene::sensitivity_settings`]), checked only when
    /// the study runs (a scene at a misalignment limit has no room for
    /// them, and need not run the study).
    #[serde(default)]
    pub sensitivity: Option<crate::scene_sensitivity::SensitivitySettings>,
    /// Each member's shaft on compliant bearings (`[bearings]`): the LTCA
    /// then also solves every position with the bearings' deflection.
    #[serde(default)]
    pub bearings: Option<crate::scene_bearings::BearingSettings>,
}

/// Settings of the multibody runs (`solver dynamic`): rigid pinion and
/// wheel on revolute joints, coupled by the contact element.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct MultibodySettings {
    /// Quasi-static run: imposed wheel speed (rpm) with each scene torque on
    /// the pinion, over the LTCA's rotation range; largest step (s).
    pub quasi_static_wheel_rpm: f64,
    pub quasi_static_max_step_s: f64,
    /// Run-up: pinion speed ramp (rpm) over `runup_time_s` with
    /// `runup_pinion_torque_nm` resisted at the wheel; largest step (s); the
    /// wheel blanks run up (each needs stiffness data of every wheel tooth
    /// the run-up turns through).
    pub runup_rpm: [f64; 2],
    pub runup_time_s: f64,
    pub runup_pinion_torque_nm: f64,
    pub runup_max_step_s: f64,
    pub runup_wheel_blanks: Vec<Blank>,
    /// Damping ratio of the torsional mesh mode (viscous, on the wheel lag).
    pub damping_ratio: f64,
    /// Spectral radius at infinity of the generalized-α scheme, in [0, 1].
    pub rho_inf: f64,
    /// Local error tolerance of the step control on the TE, µrad.
    pub te_tolerance_urad: f64,
    /// Contact-element table: pinion rotation step (deg), lag nodes, and the
    /// largest pinion torque covered as a multiple of the largest scene torque.
    pub table_step_deg: f64,
    pub table_lag_nodes: usize,
    pub table_torque_factor: f64,
    /// Polar moments of inertia, kg·m²; computed from the body meshes when absent.
    pub pinion_inertia_kgm2: Option<f64>,
    pub wheel_inertia_kgm2: Option<f64>,
    /// Coast-flank contact in the multibody element: the coast flanks of the
    /// teeth that can touch are refined in the meshes too and get their own
    /// stiffness files, and the element carries both flank pairs with the
    /// backlash between them (tooth separation, coast-side impacts, rattle);
    /// `solver ltca` also runs the scene's loads on the coast flanks. With a
    /// lightweight wheel, every wheel tooth whose coast flank the runs meet
    /// is solved (the rattle run's rotation included).
    pub coast_contact: bool,
    /// Root stress in the multibody runs: the contact-element table also
    /// holds, at each node, the loaded teeth's largest root tension of both
    /// members (needs root-stress coefficients in the stiffness files,
    /// `[stiffness] root_stress`); the 10 rpm runs and the run-up report it.
    /// Off by default: it lengthens the table build several times.
    pub root_stress: bool,
    /// Rattle run (needs `coast_contact`): the pinion turns at
    /// `rattle_pinion_rpm` with a speed fluctuation of relative amplitude
    /// `rattle_speed_fluctuation` at `rattle_frequency_hz`; the wheel is
    /// free, braked only by `rattle_wheel_drag_nm`; for `rattle_time_s` (0:
    /// no rattle run) with steps up to `rattle_max_step_s`.
    pub rattle_pinion_rpm: f64,
    pub rattle_speed_fluctuation: f64,
    pub rattle_frequency_hz: f64,
    pub rattle_wheel_drag_nm: f64,
    pub rattle_time_s: f64,
    pub rattle_max_step_s: f64,
    /// The contact's force law: "element" (the FE-analytical element) or
    /// "impact" (the impact function of seeds 001/002, `[multibody.impact]`).
    pub force_law: ForceLaw,
    pub impact: ImpactSettings,
    /// Imposed-speed run under a wheel load (`[multibody.load_run]`; none
    /// when absent).
    pub load_run: Option<LoadRun>,
    /// Static against dynamic TE (`[multibody.ste_dte]`, the white paper's
    /// first use case; none when absent).
    pub ste_dte: Option<crate::scene_ste_dte::SteDte>,
}

impl Default for MultibodySettings {
    fn default() -> Self {
        MultibodySettings {
            quasi_static_wheel_rpm: 10.0,
            quasi_static_max_step_s: 1e-3,
            runup_rpm: [0.0, 1000.0],
            runup_time_s: 0.15,
            runup_pinion_torque_nm: 300.0,
            runup_max_step_s: 1e-5,
            runup_wheel_blanks: vec![Blank::Standard],
            damping_ratio: 0.05,
            rho_inf: 0.9,
            te_tolerance_urad: 1e-3,
            table_step_deg: 0.125,
            table_lag_nodes: 96,
            table_torque_factor: 2.0,
            pinion_inertia_kgm2: None,
            wheel_inertia_kgm2: None,
            coast_contact: false,
            root_stress: false,
            rattle_pinion_rpm: 300.0,
            rattle_speed_fluctuation: 0.05,
            rattle_frequency_hz: 40.0,
            rattle_wheel_drag_nm: 0.0,
            rattle_time_s: 0.0,
            rattle_max_step_s: 1e-5,
            force_law: ForceLaw::Element,
            impact: ImpactSettings::default(),
            load_run: None,
            ste_dte: None,
        }
    }
}

impl Scene {
    /// The ranges of `solver sensitivity`: the scene's `[sensitivity]`
    /// table, or the defaults when it has none.
    pub fn sensitivity_settings(&self) -> crate::scene_sensitivity::SensitivitySettings {
        self.sensitivity.unwrap_or_default()
    }

    /// Mesh cycles through which the scene's analyses turn a wheel blank:
    /// the loaded sweep, or for a lightweight blank that runs up, the run-up
    /// where it is longer (1 cycle margin). A standard blank's stiffness
    /// repeats from tooth to tooth, so its run-up reuses the sweep's teeth.
    pub fn contact_mesh_cycles(&self, wheel: Blank, mesh_cycle_rad: f64) -> f64 {
        let sweep = self.rotation.mesh_cycles(wheel);
        if wheel == Blank::Lightweight && self.analyses.multibody {
            let mb = &self.multibody;
            let mut cycles = sweep;
            if mb.runup_wheel_blanks.contains(&wheel) {
                cycles = cycles.max(mb.runup_rotation() / mesh_cycle_rad + 1.0);
            }
            if mb.coast_contact && mb.rattle_time_s > 0.0 {
                cycles = cycles.max(mb.rattle_rotation() / mesh_cycle_rad + 1.0);
            }
            if let Some(run) = &mb.load_run {
                cycles = cycles.max(run.rotation() / mesh_cycle_rad + 1.0);
            }
            if let Some(sd) = mb.ste_dte_of(wheel) {
                cycles = cycles.max(sd.rotation() / mesh_cycle_rad + 1.0);
            }
            cycles
        } else {
            sweep
        }
    }
}

impl MultibodySettings {
    /// The STE/DTE comparison when it runs wheel blank `wheel`.
    pub fn ste_dte_of(&self, wheel: Blank) -> Option<&crate::scene_ste_dte::SteDte> {
        self.ste_dte
            .as_ref()
            .filter(|sd| sd.wheel_blanks.contains(&wheel))
    }

    /// Pinion rotation of the run-up, rad.
    pub fn runup_rotation(&self) -> f64 {
        let w = |rpm: f64| rpm * std::f64::consts::PI / 30.0;
        0.5 * (w(self.runup_rpm[0]) + w(self.runup_rpm[1])) * self.runup_time_s
    }

    /// Largest pinion rotation of the rattle run, rad: the mean speed with
    /// the fluctuation's amplitude added throughout.
    pub fn rattle_rotation(&self) -> f64 {
        self.rattle_pinion_rpm * std::f64::consts::PI / 30.0
            * (1.0 + self.rattle_speed_fluctuation.abs())
            * self.rattle_time_s
    }
}

/// Settings of the loaded TCA (the contact element).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LtcaSettings {
    /// Slices across the face width per tooth pair.
    pub slices: usize,
    /// Coulomb friction coefficient μ between the flanks, in the loaded TCA
    /// and the multibody element (0: frictionless; our default: the white
    /// paper's element has a Coulomb friction force but states no μ for its
    /// validation).
    pub friction_coefficient: f64,
}

impl Default for LtcaSettings {
    fn default() -> Self {
        LtcaSettings {
            slices: 30,
            friction_coefficient: 0.0,
        }
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
    /// Whether the files also hold root-stress influence coefficients (the
    /// fillet stresses under every grid load), from which the LTCA gives
    /// the loaded teeth's root stress.
    pub root_stress: bool,
}

impl Default for StiffnessSettings {
    fn default() -> Self {
        StiffnessSettings {
            grid_profile: 0,
            grid_face: 0,
            load_radius_factor: 0.75,
            response_teeth: 2,
            solve_block: 16,
            root_stress: true,
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

impl Rotation {
    /// Mesh cycles of the loaded sweep for a wheel blank.
    pub fn mesh_cycles(&self, wheel: Blank) -> f64 {
        match wheel {
            Blank::Standard => self.mesh_cycles_standard,
            Blank::Lightweight => self.mesh_cycles_lightweight,
        }
    }
}

/// Elements along the active profile × along the face width of a loaded flank.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
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
    /// The level between them for mesh-convergence studies; default: the
    /// geometric mean of the two, per direction (the same refinement ratio
    /// from reduced to medium as from medium to reference).
    #[serde(default)]
    pub medium: Option<FlankElements>,
}

impl MeshLevels {
    /// Elements per flank at `level`.
    pub fn elements(&self, level: MeshLevel) -> FlankElements {
        match level {
            MeshLevel::Reduced => self.reduced_order,
            MeshLevel::Medium => self.medium(),
            MeshLevel::Reference => self.reference,
        }
    }

    /// The medium level, given or the geometric mean.
    pub fn medium(&self) -> FlankElements {
        self.medium.unwrap_or_else(|| {
            let g = |a: u32, b: u32| ((a as f64 * b as f64).sqrt().round() as u32).max(1);
            FlankElements {
                profile: g(self.reduced_order.profile, self.reference.profile),
                face: g(self.reduced_order.face, self.reference.face),
            }
        })
    }
}

/// A mesh density of the scene (`[mesh]` table).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MeshLevel {
    /// The reduced model's meshes (`[mesh] reduced_order`).
    Reduced,
    /// Between reduced and reference (mesh-convergence studies).
    Medium,
    /// The fine reference (`[mesh] reference`).
    Reference,
}

impl MeshLevel {
    /// Finest first: the order in which the report looks for a reference.
    pub const FINEST_FIRST: [MeshLevel; 3] =
        [MeshLevel::Reference, MeshLevel::Medium, MeshLevel::Reduced];

    /// The level's name in file names and summaries.
    pub fn name(self) -> &'static str {
        match self {
            MeshLevel::Reduced => "reduced",
            MeshLevel::Medium => "medium",
            MeshLevel::Reference => "reference",
        }
    }

    /// The command-line option that selects the level in `preprocess mesh`
    /// and `preprocess stiffness` (` --level <name>`), empty for the
    /// default (reduced) level.
    pub fn option(self) -> String {
        match self {
            MeshLevel::Reduced => String::new(),
            l => format!(" --level {}", l.name()),
        }
    }

    /// The level of a name ([`MeshLevel::name`]); `None` for any other text.
    pub fn from_name(name: &str) -> Option<MeshLevel> {
        Self::FINEST_FIRST.into_iter().find(|l| l.name() == name)
    }
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

/// Which analyses the run performs. Every stage asks these before it
/// computes anything: meshes and stiffness files are made only when an
/// analysis needs them ([`Analyses::needs_mesh`], [`Analyses::needs_stiffness`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Analyses {
    /// Flank grids, unloaded TCA and their plots (`preprocess flanks`).
    pub utca: bool,
    /// Quasi-static loaded TCA of the reduced model (`solver ltca`).
    pub ltca: bool,
    /// Multibody runs: 10 rpm, run-up, rattle (`solver dynamic`).
    pub multibody: bool,
    /// The FE reference in penalty contact and its studies (`validate reference`, `validate tradeoff`).
    pub reference: bool,
}

impl Analyses {
    /// Whether an analysis needs body meshes of `level`: the reduced level
    /// for the reduced model's stiffness files and the reduced-level
    /// reference; finer levels for the reference only.
    pub fn needs_mesh(&self, level: MeshLevel) -> bool {
        match level {
            MeshLevel::Reduced => self.needs_stiffness() || self.reference,
            MeshLevel::Medium | MeshLevel::Reference => self.reference,
        }
    }

    /// Whether an analysis needs the reduced model's stiffness files.
    pub fn needs_stiffness(&self) -> bool {
        self.ltca || self.multibody
    }
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
        let text = InputError::read_text(path)?;
        let scene = Scene::parse(&text, path)?;
        scene.check(path)?;
        scene.check_given_run_up_blanks(path, &text)?;
        let design_path = path.parent().unwrap_or(Path::new(".")).join(&scene.design);
        let pair = load_pair(&design_path)?;
        scene.check_sizes(path, &pair)?;
        Ok(LoadedScene {
            path: path.to_path_buf(),
            scene,
            design_path,
            pair,
        })
    }

    /// Parses scene text; `path` is used in messages (no checks yet).
    pub fn parse(text: &str, path: &Path) -> Result<Scene, InputError> {
        toml::from_str(text).map_err(|e| InputError::parse(path, text, &e))
    }
}

impl Default for UtcaSettings {
    fn default() -> Self {
        UtcaSettings {
            step_deg: 0.1,
            mesh_cycles: 2.0,
            face_samples: 41,
            profile_samples: 41,
            marking_compound_um: 6.3,
            flank_grid_profile: 36,
            flank_grid_face: 76,
        }
    }
}
