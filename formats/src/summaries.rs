//! The solver's stage summaries (`out/<scene>/{ltca,multibody}/summary.json`
//! and each blank pair's own `summary.json`): one type per file, written by
//! the solver and read by the report with the same definition, so a renamed
//! field fails to compile or fails to read, never drops a table silently.

use geometry::gear_body::Blank;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

// Loaded TCA (`solver ltca`).

/// Per-torque summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadSummary {
    pub torque_nm: f64,
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    /// Geometry + compliance + contact solve of one position at this torque, s.
    pub cpu_s_per_position: f64,
    /// Contact solve alone, s per position.
    pub solve_s_per_position: f64,
    /// Root stress alone (part of `cpu_s_per_position`), s per position.
    #[serde(default)]
    pub root_stress_s_per_position: f64,
    pub max_pressure_mpa: f64,
    pub mesh_stiffness_mean_nm_per_rad: f64,
    /// Largest torque share of one tooth pair over the sweep.
    pub max_pair_share: f64,
    /// Mean torque driving the wheel, N·m; the mesh efficiency is this ·
    /// z₁/z₂ / torque (one without friction, to the ease-off's departure
    /// from conjugate levers).
    pub wheel_torque_mean_nm: f64,
    /// The first position of the sweep (in its order) where a loaded
    /// slice's contact reaches an edge of the active flank; None where the
    /// contact stays inside at every position (or in files written before
    /// the check existed).
    #[serde(default)]
    pub edge_contact: Option<EdgeContact>,
    /// Each member's largest root (fillet) tension and compression over
    /// the sweep, with where they sit; None when the stiffness files hold
    /// no root-stress coefficients (or in files written before them).
    #[serde(default)]
    pub root_stress: Option<crate::root_stress::RootStressSummary>,
}

/// An edge of the active flank that the contact can reach.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Edge {
    /// Inner end of the face width (small cone distance).
    Toe,
    /// Outer end of the face width.
    Heel,
    PinionTip,
    /// The pinion flank's lower limit, where the root fillet meets it.
    PinionRootFillet,
    WheelTip,
    WheelRootFillet,
}

impl Edge {
    pub fn name(self) -> &'static str {
        match self {
            Edge::Toe => "toe",
            Edge::Heel => "heel",
            Edge::PinionTip => "pinion tip",
            Edge::PinionRootFillet => "pinion root-fillet limit",
            Edge::WheelTip => "wheel tip",
            Edge::WheelRootFillet => "wheel root-fillet limit",
        }
    }
}

/// Contact reaching an edge of the active flank at one position.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct EdgeContact {
    pub edge: Edge,
    /// Pinion rotation from the sweep start, deg.
    pub pinion_rotation_deg: f64,
    /// Tooth pair whose slice reaches the edge.
    pub pair: i32,
    /// How far the contact reaches past the edge, mm (≥ 0). Along the
    /// profile: the Hertz half-width beyond the tip or the root-fillet
    /// limit. At the toe and heel the slice's band is cut at the face's
    /// end, so a loaded end band reaches it with overshoot 0.
    pub overshoot_mm: f64,
}

/// Summary of one pinion × wheel blank combination.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BlankSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub positions: usize,
    pub step_deg: f64,
    pub mesh_cycles: f64,
    pub slices_per_pair: usize,
    /// Coulomb friction coefficient of the flanks.
    pub friction_coefficient: f64,
    pub utca_te_mean_urad: f64,
    pub utca_te_ptp_urad: f64,
    pub stiffness_files: Vec<PathBuf>,
    pub wall_s: f64,
    pub loads: Vec<LoadSummary>,
    pub dir: PathBuf,
    /// With coast-side contact (`multibody.coast_contact`): the same loads
    /// on the coast flanks.
    pub coast: Option<CoastSummary>,
    /// With the scene's `[bearings]`: the loads solved with the members on
    /// their compliant bearings (`bearings.csv` per position).
    #[serde(default)]
    pub bearings: Option<Vec<BearingLoadSummary>>,
    /// The ablation study: the same sweep with one of the element's
    /// modelling changes switched off per entry (empty in files written
    /// before the study existed).
    #[serde(default)]
    pub ablation: Vec<AblationVariant>,
    /// The loaded-pair rule over the sweep (None in files written before it).
    #[serde(default)]
    pub loaded_pair_rule: Option<LoadedPairRule>,
}

/// The loaded-pair rule over a sweep: tooth pairs beyond the active roll
/// range whose unloaded closest point lies below a position's largest
/// loaded TE (rigidly they would penetrate), and whether they close under
/// the bodies' coupled deflection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadedPairRule {
    pub positions: usize,
    /// Positions with such a pair.
    pub with_candidates: usize,
    /// Positions where one closes (it is then part of the contact problem).
    pub closing: usize,
    /// Positions with a candidate whose teeth the stiffness files do not
    /// hold (not checked), and those pairs.
    pub unchecked: usize,
    pub unchecked_pairs: Vec<i32>,
}

/// One variant of the ablation study: the element with one modelling
/// change switched off, over the same sweep and loads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AblationVariant {
    /// Short name of the variant.
    pub variant: String,
    /// The modelling change switched off, in words.
    pub change_off: String,
    pub loads: Vec<LoadSummary>,
}

/// One torque of the LTCA with bearing deflection, over the sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BearingLoadSummary {
    pub torque_nm: f64,
    /// Loaded TE with the bearings' deflection, µrad.
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    /// The same positions with rigid bearings (same contact search), µrad.
    pub rigid_te_mean_urad: f64,
    pub rigid_te_ptp_urad: f64,
    /// Largest displacement of each member's pitch apex on its bearings, µm.
    pub pinion_apex_displacement_um: f64,
    pub wheel_apex_displacement_um: f64,
    /// Largest force of each bearing (in the scene's order), N.
    pub pinion_bearing_force_n: Vec<f64>,
    pub wheel_bearing_force_n: Vec<f64>,
    /// Most iterations a position needed.
    pub max_iterations: usize,
    /// Largest last change of a member's displacement between iterations
    /// over the positions, nm (at most the tolerance, or ten times it where
    /// the iteration settled at the contact search's noise).
    #[serde(default)]
    pub max_change_nm: f64,
}

/// The coast flanks under the scene's loads: the pinion driving the other
/// way over the same pinion angles (the sweep run backwards), each coast
/// flank with its own body tooth's compliance. TEs are the coast side's
/// lags (positive, as on the drive side); the drive side's lag at coast
/// contact is −backlash − TE.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CoastSummary {
    /// Angular backlash B of the conjugate flanks at the wheel, µrad.
    pub backlash_urad: f64,
    /// Body wheel tooth of the coast model's tooth k: k + this.
    pub wheel_tooth_shift: i64,
    pub utca_te_mean_urad: f64,
    pub utca_te_ptp_urad: f64,
    pub stiffness_files: Vec<PathBuf>,
    pub loads: Vec<LoadSummary>,
    pub dir: PathBuf,
}

// Multibody runs (`solver dynamic`).

/// One quasi-static run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuasiStaticSummary {
    pub torque_nm: f64,
    /// TE sampled at the LTCA's positions.
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// The loaded teeth's largest root tension over the sweep, [pinion,
    /// wheel], MPa; None when the stiffness files hold no root-stress
    /// coefficients.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_tension_mpa: Option<[f64; 2]>,
}

/// The run-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunupSummary {
    pub pinion_torque_nm: f64,
    pub rpm: [f64; 2],
    pub sim_time_s: f64,
    pub max_step_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Dynamic minus quasi-static TE: extremes over the run, µrad.
    pub te_dynamic_minus_static_urad: [f64; 2],
    /// The loaded teeth's largest root tension over the run, [pinion,
    /// wheel], MPa, dynamic and quasi-static (at the same pinion rotations,
    /// the static lag); None without root-stress coefficients.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_tension_mpa: Option<RunupRootTension>,
}

/// The run-up's largest root tensions, MPa.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunupRootTension {
    pub dynamic: [f64; 2],
    pub quasi_static: [f64; 2],
}

/// One run-up of the STE/DTE comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SteDteRun {
    pub rpm: f64,
    /// Time of the acceleration from rest, and the whole run, s.
    pub acceleration_time_s: f64,
    pub sim_time_s: f64,
    pub max_step_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    /// CPU time of the run (this thread), s, and per step.
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
}

/// The white paper's first use case: the quasi-static TE (STE, slow
/// run-up) against the dynamic TE (DTE, fast run-up) of one pinion × wheel
/// blank, both accelerating from rest to their speed within the same
/// pinion rotation, compared at the same pinion rotations
/// (`ste_dte.csv`, `ste_dte.svg`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SteDteSummary {
    pub pinion_torque_nm: f64,
    pub acceleration_end_deg: f64,
    /// The comparison's window, pinion revolutions from rest, and its
    /// samples (evenly spaced in rotation).
    pub compared_revolutions: f64,
    pub samples: usize,
    /// The pair's mesh cycle (360° / z₁), deg.
    pub mesh_cycle_deg: f64,
    pub quasi_static: SteDteRun,
    pub dynamic: SteDteRun,
    /// CPU time of the contact-element table both runs share, s.
    pub table_cpu_s: f64,
    /// Over the window: mean and peak-to-peak of STE and DTE, µrad.
    pub ste_mean_urad: f64,
    pub ste_ptp_urad: f64,
    pub dte_mean_urad: f64,
    pub dte_ptp_urad: f64,
    /// Peak-to-peak of STE and DTE after the acceleration (the window's
    /// rotations beyond it), µrad: the DTE's without the inertia offset
    /// of the acceleration.
    pub ste_ptp_after_acceleration_urad: f64,
    pub dte_ptp_after_acceleration_urad: f64,
    /// Largest |STE − static balance| over the window, µrad: how
    /// quasi-static the slow run is (the static balance is the lag that
    /// carries the load with no inertia).
    pub ste_minus_static_max_urad: f64,
    /// DTE − STE: its mean during the acceleration, its largest value
    /// after it (signed) and where (pinion rotation, deg), and its
    /// peak-to-peak over the window's last mesh cycle, µrad.
    pub departure_during_acceleration_urad: f64,
    pub departure_largest_urad: f64,
    pub departure_largest_at_deg: f64,
    pub departure_last_cycle_ptp_urad: f64,
}

/// `runup_orders.json` of a run-up: the wheel bearing force's order
/// spectrum over windows of one wheel revolution of pinion angle
/// (`solver::signal::runup_orders`), every half revolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunupOrders {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub pinion_teeth: usize,
    pub wheel_teeth: usize,
    /// Samples per window (one wheel revolution) and the line spacing,
    /// pinion orders (z₁/z₂).
    pub samples_per_window: usize,
    pub order_resolution: f64,
    pub windows: Vec<RunupOrderWindow>,
}

/// One window of [`RunupOrders`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunupOrderWindow {
    /// Pinion revolutions from the run-up's start and time (s) at the
    /// window's ends.
    pub pinion_rev: [f64; 2],
    pub time_s: [f64; 2],
    /// Mean pinion speed over the window (its rotation over its duration)
    /// and the speeds at its ends, rpm.
    pub mean_pinion_rpm: f64,
    pub pinion_rpm: [f64; 2],
    /// Resultant wheel bearing-force amplitude (N) at the marked orders.
    pub marked: Vec<crate::lumped_summary::MarkedOrder>,
}

/// Summary of one pinion × wheel blank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DynamicSummary {
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    pub inertia_kgm2: [f64; 2],
    /// "scene" or "mesh" (∫ρr² dV over the body mesh).
    pub inertia_source: String,
    pub damping_nm_s_per_rad: f64,
    /// Coulomb friction coefficient of the flanks.
    pub friction_coefficient: f64,
    pub table_positions: usize,
    pub table_lag_nodes: usize,
    pub table_build_s: f64,
    pub table_cpu_s_per_position: f64,
    pub quasi_static: Vec<QuasiStaticSummary>,
    pub runup: Option<RunupSummary>,
    /// With coast-side contact: the conjugate flanks' angular backlash at
    /// the wheel and the free play between drive and coast contact over a
    /// mesh cycle (min, max), µrad, and the rattle run.
    pub backlash_urad: Option<f64>,
    pub free_play_urad: Option<[f64; 2]>,
    pub rattle: Option<RattleSummary>,
    /// The contact's force law, "element" or "impact", and the impact
    /// law's parameters when it is used.
    #[serde(default = "element_law")]
    pub force_law: String,
    #[serde(default)]
    pub impact_law: Option<ImpactLawSummary>,
    /// The imposed-speed load run (seeds 001/002), when the scene has one.
    #[serde(default)]
    pub load_run: Option<LoadRunSummary>,
    /// The runs with compliant bearings, when the scene has `[bearings]`.
    #[serde(default)]
    pub compliant: Option<CompliantSummary>,
    /// Static against dynamic TE, when the scene's `[multibody.ste_dte]`
    /// compares this wheel blank.
    #[serde(default)]
    pub ste_dte: Option<SteDteSummary>,
    pub dir: PathBuf,
}

/// The multibody with compliant bearings of one pinion × wheel blank.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompliantSummary {
    /// Wall time of the unloaded TE's shift per misalignment (8 misaligned
    /// contact searches over the table's positions), s.
    pub lag_shift_s: f64,
    pub masses_kg: [f64; 2],
    /// Where the masses, centres and transverse moments come from.
    pub mass_source: String,
    /// What the compliant runs leave out that the rigid runs have.
    pub notes: Vec<String>,
    pub runs: Vec<CompliantRunSummary>,
    /// The bearings and the members' mass properties as the runs used them
    /// (None in files written before it was recorded).
    #[serde(default)]
    pub used: Option<CompliantBodiesUsed>,
    /// The flexible gearbox (`[bearings.gearbox]`; None without it and in
    /// files written before it existed).
    #[serde(default)]
    pub gearbox: Option<GearboxSummary>,
}

/// The flexible gearbox: the shafts with their mass as Timoshenko beam
/// elements on the bearings, its loaded modes, where the orders meet them,
/// and its run-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearboxSummary {
    /// Coordinates of the structure (turns, gear bodies, shaft nodes).
    pub coordinates: usize,
    /// Each shaft's mass, kg (0: a rigid shaft, the bearings on the gear).
    pub shaft_mass_kg: [f64; 2],
    /// Longest shaft element, mm.
    pub shaft_element_mm: f64,
    /// Pinion torque of the quasi-static state the contact element is
    /// linearized at for the modes, N·m (the run-up's).
    pub modes_torque_nm: f64,
    /// Names of each mode's energy shares.
    pub energy_parts: Vec<String>,
    /// The modes up to the scene's `modes_up_to_hz`, ascending.
    pub modes: Vec<GearboxMode>,
    /// Where the order lines meet them within the run-up's speeds.
    pub crossings: Vec<GearboxCrossing>,
    /// The run-up on the gearbox (None where the scene runs none).
    pub run: Option<CompliantRunSummary>,
    /// The housing reduced by Craig–Bampton (None: rigid).
    #[serde(default)]
    pub housing: Option<HousingSummary>,
    /// What the gearbox leaves out.
    pub notes: Vec<String>,
}

/// The gearbox's FE housing (`preprocess housing`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HousingSummary {
    pub mass_kg: f64,
    pub nodes: usize,
    pub elements: usize,
    /// Least gap to the gears' blanks and shafts at the sampled points, mm.
    pub least_gap_mm: f64,
    /// Nodes on each seat's bore, seat order.
    pub seat_nodes: Vec<usize>,
    /// The bearing of each seat: (member, index).
    pub seats: Vec<(usize, usize)>,
    /// Fixed-interface modes kept, and the highest of them, Hz.
    pub fixed_interface_modes: usize,
    pub highest_fixed_interface_hz: f64,
    /// The cut-off they were kept up to, Hz.
    pub modes_up_to_hz: f64,
    /// The housing alone (feet clamped, seats rigid and free) up to the
    /// gearbox's `modes_up_to_hz`: the reduced model's frequencies and the
    /// whole FE model's (no truncation), Hz.
    pub reduced_hz: Vec<f64>,
    pub reference_hz: Vec<f64>,
    /// Largest |reduced/whole − 1| of them.
    pub truncation_error: f64,
    /// The run-up's largest acceleration of each seat's reference point,
    /// m/s², seat order (empty without a run-up).
    #[serde(default)]
    pub seat_acceleration_m_s2: Vec<f64>,
}

/// One mode of the loaded gearbox.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearboxMode {
    pub frequency_hz: f64,
    /// Share of the kinetic energy per [`GearboxSummary::energy_parts`].
    pub energy_share: Vec<f64>,
}

/// An order line meeting a mode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearboxCrossing {
    /// Index into [`GearboxSummary::modes`].
    pub mode: usize,
    pub frequency_hz: f64,
    /// Pinion order (multiples of the pinion's speed).
    pub order: f64,
    pub pinion_rpm: f64,
}

/// The bearings of both shafts (the scene's) and the members' mass
/// properties the runs used (the scene's `*_body` or the approximation
/// named in [`CompliantSummary::mass_source`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompliantBodiesUsed {
    pub pinion_bearings: Vec<geometry::scene_bearings::BearingMm>,
    pub wheel_bearings: Vec<geometry::scene_bearings::BearingMm>,
    /// Pinion, wheel: mass, centre of mass from the pitch apex (mm) and
    /// transverse moment about it.
    pub bodies: [geometry::scene_bearings::BodyMass; 2],
}

/// One run with compliant bearings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CompliantRunSummary {
    /// "10 rpm" or "run-up".
    pub case: String,
    pub torque_nm: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Shaft TE r q₁ − q₂, µrad: the 10 rpm runs at the table's positions
    /// they pass, the run-up over its steps.
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
    /// Largest |E|, |P|, |G| (µm) and |ΔΣ| (µrad) the bearings give.
    pub largest_misalignment: [f64; 4],
    /// Largest estimate of the TE the linear shift of the unloaded TE
    /// leaves out, ½ Σ |∂²θ₀/∂mᵢ²| mᵢ², µrad.
    pub largest_linearization_urad: f64,
    /// Its mean over the run's steps, µrad (the largest comes from the
    /// tooth changes, where θ₀(m) has a kink: the next pair's first contact
    /// moves with m).
    #[serde(default)]
    pub mean_linearization_urad: f64,
    /// Largest force magnitude per bearing, N.
    pub pinion_bearing_force_n: Vec<f64>,
    pub wheel_bearing_force_n: Vec<f64>,
    /// The run's CSV, in the blank pair's folder.
    pub csv: String,
}

fn element_law() -> String {
    "element".into()
}

/// The impact law's parameters as used (seeds' mm-based units), and the
/// Hertz stiffness of the pair for comparison.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImpactLawSummary {
    /// K (N/mm^e), and where it comes from ("scene" or "hertz").
    pub stiffness_n_per_mm_e: f64,
    pub stiffness_source: String,
    /// 4/3 √R E* (N/mm^1.5) with R from the outer pitch radii (mm).
    pub hertz_stiffness_n_per_mm_1_5: f64,
    pub hertz_radii_mm: [f64; 2],
    pub exponent: f64,
    pub damping_n_s_per_mm: f64,
    pub penetration_depth_mm: f64,
    pub static_friction: f64,
    pub dynamic_friction: f64,
    pub stiction_speed_mm_s: f64,
    pub friction_transition_speed_mm_s: f64,
    /// The damping ramp's shape: "cubic" (ADAMS's STEP) or "haversine"
    /// (absent in summaries written before it was recorded: cubic).
    #[serde(default = "cubic")]
    pub damping_step: String,
}

fn cubic() -> String {
    "cubic".into()
}

/// The imposed-speed load run: drive, cost, and the means and
/// fluctuations over whole mesh cycles of its steady window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadRunSummary {
    pub pinion_rpm: f64,
    pub pinion_ramp_s: f64,
    pub wheel_torque_nm: f64,
    pub wheel_torque_rise_s: f64,
    pub sim_time_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Steady window [from, to] (s), trimmed to whole mesh cycles, and
    /// the mesh cycles it holds.
    pub window_s: [f64; 2],
    pub window_mesh_cycles: usize,
    /// Wheel speed: time mean, kinematic value (pinion speed × z₁/z₂), the
    /// relative difference, and the mean and largest |ω₂ − kinematic|, °/s.
    pub wheel_speed_mean_deg_s: f64,
    pub wheel_speed_kinematic_deg_s: f64,
    pub wheel_speed_error: f64,
    pub wheel_speed_fluctuation_mean_deg_s: f64,
    pub wheel_speed_fluctuation_max_deg_s: f64,
    /// Wheel mesh torque: time mean against the load (relative difference).
    pub wheel_mesh_torque_mean_nm: f64,
    pub torque_balance_error: f64,
    /// Pinion mesh torque (time mean, N·m) and the mesh efficiency
    /// mean(T₂ ω₂) / mean(T₁ ω₁) over the window (1 without friction and
    /// damping losses).
    pub pinion_mesh_torque_mean_nm: f64,
    pub mesh_efficiency: f64,
    /// Tangential (circumferential) component of the contact forces on the
    /// wheel, Σ F λ₂ / ρ₂ at the contact points (N): mean and largest over
    /// the window, 2T/d with d the outer pitch diameter, the relative
    /// difference on the base of 2T/d (mean / (2T/d) − 1) and on the base
    /// of the mean ((mean − 2T/d) / mean, as seed 002's Table 2 states
    /// it), and the mean and largest |F_t − mean|, N.
    pub tangential_force_mean_n: f64,
    pub tangential_force_max_n: f64,
    pub tangential_force_theory_n: f64,
    pub tangential_force_error: f64,
    pub tangential_force_error_of_mean: f64,
    pub tangential_force_fluctuation_mean_n: f64,
    pub tangential_force_fluctuation_max_n: f64,
    /// Where the contact acts on average: mean wheel mesh torque over the
    /// mean tangential force, against the outer pitch radius d/2, mm.
    pub contact_radius_mm: f64,
    pub outer_pitch_radius_mm: f64,
    /// The same statistics from the run sampled at the scene's output
    /// interval (as a simulation that writes only every so many
    /// milliseconds sees it); None without an output interval.
    pub sampled: Option<SampledLoadRun>,
    /// Meshing (contact) force magnitude: mean, peak, and the normal force
    /// at the mean point T / (r_m cos α_n cos β_m), N.
    pub mesh_force_mean_n: f64,
    pub mesh_force_max_n: f64,
    pub mesh_force_theory_n: f64,
    /// TE mean and peak-to-peak over the window, µrad.
    pub te_mean_urad: f64,
    pub te_ptp_urad: f64,
}

/// A load run's steady-window statistics from samples at a fixed output
/// interval (linear interpolation between the integrator's steps).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SampledLoadRun {
    pub interval_s: f64,
    pub samples: usize,
    pub wheel_speed_mean_deg_s: f64,
    pub wheel_speed_fluctuation_mean_deg_s: f64,
    pub wheel_speed_fluctuation_max_deg_s: f64,
    pub tangential_force_mean_n: f64,
    pub tangential_force_max_n: f64,
    pub tangential_force_fluctuation_mean_n: f64,
    pub tangential_force_fluctuation_max_n: f64,
}

/// The rattle run: fluctuating pinion speed, free wheel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RattleSummary {
    pub pinion_rpm: f64,
    pub speed_fluctuation: f64,
    pub frequency_hz: f64,
    pub wheel_drag_nm: f64,
    pub sim_time_s: f64,
    pub steps: usize,
    pub rejected_steps: usize,
    pub cpu_s: f64,
    pub cpu_s_per_step: f64,
    /// Contacts begun on the drive and on the coast flanks.
    pub drive_impacts: usize,
    pub coast_impacts: usize,
    /// Share of the time in drive contact, coast contact and free flight.
    pub time_share_drive_coast_free: [f64; 3],
    /// Episodes with both flank pairs in contact at once (wedging) and
    /// their share of the time.
    #[serde(default)]
    pub wedging_episodes: usize,
    #[serde(default)]
    pub time_share_wedged: f64,
    /// Largest contact force on the wheel of the drive and of the coast
    /// flanks over the run, N.
    #[serde(default)]
    pub peak_force_drive_coast_n: [f64; 2],
    /// Extremes of the pinion mesh torque, N·m (negative: coast side).
    pub mesh_torque_min_max_nm: [f64; 2],
    /// Extremes of the wheel lag, µrad, and of the wheel speed, rpm.
    pub te_min_max_urad: [f64; 2],
    pub wheel_rpm_min_max: [f64; 2],
}
