//! The scene's optional `[bearings]` table: each member's shaft on
//! compliant bearings, for the LTCA with bearing deflection
//! (`solver::bearings::system_deflection`). Positions are along the member's axis from
//! its pitch apex, positive toward (and beyond) the teeth.
//!
//! ```toml
//! [bearings]
//! pinion = [
//!   { axial_position_mm = 110.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 5e8 },
//!   { axial_position_mm = 170.0, radial_stiffness_n_per_m = 5e8, axial_stiffness_n_per_m = 0.0 },
//! ]
//! wheel = [ ... ]
//! ```

use crate::error::InputError;
use crate::limits::bearings as lim;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// One bearing of a shaft.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingMm {
    /// Along the member's axis from its pitch apex, mm.
    pub axial_position_mm: f64,
    /// Radial stiffness, N/m (the same in every radial direction).
    pub radial_stiffness_n_per_m: f64,
    /// Axial stiffness, N/m (0: floating).
    pub axial_stiffness_n_per_m: f64,
    /// Viscous damping, radial and axial, N·s/m (multibody with compliant
    /// bearings only; the quasi-static LTCA has no speeds). Default 0.
    #[serde(default)]
    pub radial_damping_n_s_per_m: f64,
    #[serde(default)]
    pub axial_damping_n_s_per_m: f64,
}

/// A member's mass properties for the multibody with compliant bearings
/// (the translations and tilts on its bearings). Without it: the mass from
/// the mesh (volume × density, the folder's manifest), the centre of mass
/// at the mean point of the pitch cone's axis, and the transverse moment
/// half the polar moment (a thin disc's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyMass {
    pub mass_kg: f64,
    /// Centre of mass along the member's axis from its pitch apex, mm.
    pub centroid_mm: f64,
    /// Moment of inertia about an axis ⊥ the shaft through the centre of
    /// mass, kg·m².
    pub transverse_inertia_kgm2: f64,
}

/// Both members' bearings and the iteration's settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSettings {
    pub pinion: Vec<BearingMm>,
    pub wheel: Vec<BearingMm>,
    /// Convergence of the members' displacements, nm.
    #[serde(default = "default_tolerance_nm")]
    pub tolerance_nm: f64,
    /// Most iterations of contact and bearing deflection per position.
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    /// Mass properties of the members (multibody; see [`BodyMass`]).
    #[serde(default)]
    pub pinion_body: Option<BodyMass>,
    #[serde(default)]
    pub wheel_body: Option<BodyMass>,
    /// Flexible shafts (`[bearings.pinion_shaft]`, `[bearings.wheel_shaft]`):
    /// Timoshenko beam elements of the member's shaft on its bearings,
    /// condensed onto the gear's seat (`solver::bearings::flexible_shaft`);
    /// absent: a rigid shaft.
    #[serde(default)]
    pub pinion_shaft: Option<ShaftMm>,
    #[serde(default)]
    pub wheel_shaft: Option<ShaftMm>,
    /// The flexible gearbox (`[bearings.gearbox]`): the shafts with their
    /// mass as Timoshenko beam elements in the multibody, its loaded modes,
    /// and a run-up on it beside the compliant-bearing one
    /// (`solver::gearbox`); absent: none.
    #[serde(default)]
    pub gearbox: Option<GearboxMm>,
}

/// Settings of the flexible gearbox.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearboxMm {
    /// Longest shaft element, mm (the shafts' named positions are cut
    /// into elements no longer than this).
    #[serde(default = "default_shaft_element_mm")]
    pub shaft_element_mm: f64,
    /// Modes listed, drawn over the spectrogram and met by the order lines
    /// up to this frequency, Hz.
    #[serde(default = "default_modes_up_to_hz")]
    pub modes_up_to_hz: f64,
    /// The housing as a reduced FE body (`[bearings.gearbox.housing]`,
    /// meshed and reduced by `preprocess stiffness`); absent: rigid.
    #[serde(default)]
    pub housing: Option<HousingMm>,
}

/// A parametric housing: a floor plate under both shafts, clamped at four
/// square feet at its corners, and one wall per bearing, normal to the
/// bearing's shaft, standing on the floor and holding the bearing's outer
/// ring in a bore. Each bore's surface moves rigidly with its seat (the
/// bearing's centre). The walls and floor keep `clearance_mm` from the
/// gears' blanks (as bodies of revolution) and the shafts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HousingMm {
    /// Bore (bearing outer ring) diameter at the pinion's bearings, mm.
    pub pinion_bore_diameter_mm: f64,
    /// Bore diameter at the wheel's bearings, mm.
    pub wheel_bore_diameter_mm: f64,
    /// Wall thickness along its shaft, mm.
    #[serde(default = "default_housing_wall_mm")]
    pub wall_mm: f64,
    /// Floor thickness, mm.
    #[serde(default = "default_housing_floor_mm")]
    pub floor_mm: f64,
    /// Material around a bore: a wall is the bore diameter + 2 rim wide
    /// and reaches one rim above the bore, mm.
    #[serde(default = "default_housing_rim_mm")]
    pub rim_mm: f64,
    /// Least gap between the housing and the gears' and shafts' envelopes;
    /// the floor's top lies this far below the lowest envelope, mm.
    #[serde(default = "default_housing_clearance_mm")]
    pub clearance_mm: f64,
    /// Side of the square feet at the floor's corners (clamped), mm.
    #[serde(default = "default_housing_foot_mm")]
    pub foot_mm: f64,
    /// Target size of the tet10 elements, mm.
    #[serde(default = "default_housing_element_mm")]
    pub element_mm: f64,
    /// Fixed-interface (Craig–Bampton) modes kept up to, Hz.
    #[serde(default = "default_housing_modes_up_to_hz")]
    pub modes_up_to_hz: f64,
    /// Young's modulus, GPa.
    #[serde(default = "default_housing_youngs_modulus_gpa")]
    pub youngs_modulus_gpa: f64,
    #[serde(default = "default_housing_poisson_ratio")]
    pub poisson_ratio: f64,
    /// kg/m³.
    #[serde(default = "default_housing_density_kg_m3")]
    pub density_kg_m3: f64,
    /// Modal damping ratio of the kept fixed-interface modes (the seats'
    /// coordinates are damped through the bearings).
    #[serde(default = "default_housing_damping_ratio")]
    pub damping_ratio: f64,
}

/// Chosen: a few per cent is usual for a cast housing.
fn default_housing_damping_ratio() -> f64 {
    0.02
}

fn default_housing_wall_mm() -> f64 {
    15.0
}
fn default_housing_floor_mm() -> f64 {
    20.0
}
fn default_housing_rim_mm() -> f64 {
    20.0
}
fn default_housing_clearance_mm() -> f64 {
    10.0
}
fn default_housing_foot_mm() -> f64 {
    50.0
}
fn default_housing_element_mm() -> f64 {
    10.0
}
fn default_housing_modes_up_to_hz() -> f64 {
    10_000.0
}
/// Grey cast iron (EN-GJL-250), chosen.
fn default_housing_youngs_modulus_gpa() -> f64 {
    110.0
}
fn default_housing_poisson_ratio() -> f64 {
    0.26
}
fn default_housing_density_kg_m3() -> f64 {
    7_200.0
}

impl HousingMm {
    /// Every number in range (the fit around the gears is checked where
    /// the housing is built, `preprocess::housing`).
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        for (l, v) in [
            (&lim::HOUSING_PINION_BORE, self.pinion_bore_diameter_mm),
            (&lim::HOUSING_WHEEL_BORE, self.wheel_bore_diameter_mm),
            (&lim::HOUSING_WALL, self.wall_mm),
            (&lim::HOUSING_FLOOR, self.floor_mm),
            (&lim::HOUSING_RIM, self.rim_mm),
            (&lim::HOUSING_CLEARANCE, self.clearance_mm),
            (&lim::HOUSING_FOOT, self.foot_mm),
            (&lim::HOUSING_ELEMENT, self.element_mm),
            (&lim::HOUSING_MODES_UP_TO, self.modes_up_to_hz),
            (&lim::HOUSING_YOUNGS_MODULUS, self.youngs_modulus_gpa),
            (&lim::HOUSING_POISSON_RATIO, self.poisson_ratio),
            (&lim::HOUSING_DENSITY, self.density_kg_m3),
            (&lim::HOUSING_DAMPING, self.damping_ratio),
        ] {
            l.check(path, v)?;
        }
        Ok(())
    }
}

fn default_shaft_element_mm() -> f64 {
    10.0
}

fn default_modes_up_to_hz() -> f64 {
    5_000.0
}

/// A member's shaft: round segments along its axis and the gear's seat.
/// The material is the design's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShaftMm {
    /// Where the gear body sits on the shaft, mm from the pitch apex along
    /// the member's axis (the node the rigid gear hangs on).
    pub seat_mm: f64,
    /// Contiguous segments in axial order; every bearing and the seat on
    /// them.
    pub segments: Vec<ShaftSegmentMm>,
}

/// A length of shaft of one round section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShaftSegmentMm {
    pub from_mm: f64,
    pub to_mm: f64,
    pub outer_diameter_mm: f64,
    /// 0 for a solid shaft.
    #[serde(default)]
    pub inner_diameter_mm: f64,
}

/// Most segments of one shaft.
pub const MAX_SHAFT_SEGMENTS: usize = 50;
/// Largest shaft diameter, mm.
pub const MAX_SHAFT_DIAMETER_MM: f64 = 2_000.0;

fn default_tolerance_nm() -> f64 {
    1.0
}

fn default_max_iterations() -> usize {
    60
}

/// Stiffer than this is rigid for any gear mesh, N/m.
pub const MAX_BEARING_STIFFNESS_N_PER_M: f64 = 1e14;
/// Largest bearing damping, N·s/m.
pub const MAX_BEARING_DAMPING_N_S_PER_M: f64 = 1e9;
/// Farthest bearing from the apex, mm.
pub const MAX_BEARING_POSITION_MM: f64 = 10_000.0;

impl BearingSettings {
    /// Every number finite and in range; each shaft held against tilt (two
    /// radial bearings at different positions) and along its axis (one
    /// axial bearing).
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        for (member, list) in [("pinion", &self.pinion), ("wheel", &self.wheel)] {
            for (i, b) in list.iter().enumerate() {
                let f = |name: &str| format!("bearings.{member}[{i}].{name}");
                for (l, name, v) in [
                    (
                        &lim::AXIAL_POSITION,
                        "axial_position_mm",
                        b.axial_position_mm,
                    ),
                    (
                        &lim::RADIAL_STIFFNESS,
                        "radial_stiffness_n_per_m",
                        b.radial_stiffness_n_per_m,
                    ),
                    (
                        &lim::AXIAL_STIFFNESS,
                        "axial_stiffness_n_per_m",
                        b.axial_stiffness_n_per_m,
                    ),
                    (
                        &lim::RADIAL_DAMPING,
                        "radial_damping_n_s_per_m",
                        b.radial_damping_n_s_per_m,
                    ),
                    (
                        &lim::AXIAL_DAMPING,
                        "axial_damping_n_s_per_m",
                        b.axial_damping_n_s_per_m,
                    ),
                ] {
                    l.check_at(path, &f(name), v)?;
                }
            }
            let radial: Vec<f64> = list
                .iter()
                .filter(|b| b.radial_stiffness_n_per_m > 0.0)
                .map(|b| b.axial_position_mm)
                .collect();
            let distinct = radial.iter().any(|&a| radial.iter().any(|&b| a != b));
            if !distinct {
                return Err(lim::HELD_AGAINST_TILT.refuse(
                    path,
                    &format!("bearings.{member}"),
                    format!("{} bearings with radial stiffness", radial.len()),
                    "needs two bearings with radial stiffness at different axial positions (to hold tilt)".into(),
                ));
            }
            if list.iter().all(|b| b.axial_stiffness_n_per_m <= 0.0) {
                return Err(lim::HELD_ALONG_AXIS.refuse(
                    path,
                    &format!("bearings.{member}"),
                    "no axial stiffness".into(),
                    "needs one bearing with axial_stiffness_n_per_m > 0 (else the shaft slides along its axis)".into(),
                ));
            }
        }
        for (member, body) in [
            ("pinion_body", &self.pinion_body),
            ("wheel_body", &self.wheel_body),
        ] {
            let Some(b) = body else { continue };
            for (l, name, v) in [
                (&lim::BODY_MASS, "mass_kg", b.mass_kg),
                (&lim::BODY_CENTROID, "centroid_mm", b.centroid_mm),
                (
                    &lim::BODY_TRANSVERSE_INERTIA,
                    "transverse_inertia_kgm2",
                    b.transverse_inertia_kgm2,
                ),
            ] {
                l.check_at(path, &format!("bearings.{member}.{name}"), v)?;
            }
        }
        for (member, shaft, list) in [
            ("pinion_shaft", &self.pinion_shaft, &self.pinion),
            ("wheel_shaft", &self.wheel_shaft, &self.wheel),
        ] {
            if let Some(sh) = shaft {
                sh.check(path, member, list)?;
            }
        }
        if let Some(g) = &self.gearbox {
            lim::GEARBOX_SHAFT_ELEMENT.check(path, g.shaft_element_mm)?;
            lim::GEARBOX_MODES_UP_TO.check(path, g.modes_up_to_hz)?;
            if let Some(h) = &g.housing {
                h.check(path)?;
                if h.modes_up_to_hz < g.modes_up_to_hz {
                    return Err(lim::HOUSING_MODES_COVER.refuse(
                        path,
                        lim::HOUSING_MODES_COVER.field,
                        format!("{} Hz", h.modes_up_to_hz),
                        format!(
                            "must be at least bearings.gearbox.modes_up_to_hz = {} Hz",
                            g.modes_up_to_hz
                        ),
                    ));
                }
            }
        }
        lim::TOLERANCE.check(path, self.tolerance_nm)?;
        lim::MAX_ITERATIONS.check_integer(path, lim::MAX_ITERATIONS.field, self.max_iterations)
    }
}

impl ShaftMm {
    /// Every number in range; segments contiguous in axial order with
    /// 0 ≤ inner < outer diameter; the seat and every bearing of `bearings`
    /// on the shaft.
    pub fn check(
        &self,
        path: &Path,
        member: &str,
        bearings: &[BearingMm],
    ) -> Result<(), InputError> {
        let f = |name: &str| format!("bearings.{member}.{name}");
        lim::SHAFT_SEAT.check_at(path, &f("seat_mm"), self.seat_mm)?;
        let (l, n) = (&lim::SHAFT_SEGMENTS, self.segments.len());
        if !l.admits(n as f64, &[]) {
            return Err(l.refuse(
                path,
                &f("segments"),
                format!("{n} entries"),
                l.text_of_refusal(),
            ));
        }
        for (i, sg) in self.segments.iter().enumerate() {
            let g = |name: &str| f(&format!("segments[{i}].{name}"));
            lim::SHAFT_FROM.check_at(path, &g("from_mm"), sg.from_mm)?;
            lim::SHAFT_TO.check_at(path, &g("to_mm"), sg.to_mm)?;
            lim::SHAFT_DIAMETER.check_at(path, &g("outer_diameter_mm"), sg.outer_diameter_mm)?;
            lim::SHAFT_BORE.check_at(path, &g("inner_diameter_mm"), sg.inner_diameter_mm)?;
            if sg.to_mm <= sg.from_mm {
                return Err(lim::SHAFT_ORDER.refuse(
                    path,
                    &g("to_mm"),
                    format!("{}", sg.to_mm),
                    format!("must exceed from_mm = {}", sg.from_mm),
                ));
            }
            if sg.inner_diameter_mm >= sg.outer_diameter_mm {
                return Err(lim::SHAFT_ORDER.refuse(
                    path,
                    &g("inner_diameter_mm"),
                    format!("{}", sg.inner_diameter_mm),
                    format!("must be below outer_diameter_mm = {}", sg.outer_diameter_mm),
                ));
            }
            if i > 0 && (sg.from_mm - self.segments[i - 1].to_mm).abs() > 1e-6 {
                return Err(lim::SHAFT_ORDER.refuse(
                    path,
                    &g("from_mm"),
                    format!("{}", sg.from_mm),
                    format!(
                        "must equal the previous segment's to_mm = {} (segments contiguous, in axial order)",
                        self.segments[i - 1].to_mm
                    ),
                ));
            }
        }
        let lo = self.segments[0].from_mm;
        let hi = self.segments[self.segments.len() - 1].to_mm;
        let on = |x: f64| (lo - 1e-9..=hi + 1e-9).contains(&x);
        if !on(self.seat_mm) {
            return Err(lim::SHAFT_ORDER.refuse(
                path,
                &f("seat_mm"),
                format!("{}", self.seat_mm),
                format!("must lie on the shaft, [{lo}, {hi}] mm"),
            ));
        }
        for (i, b) in bearings.iter().enumerate() {
            if !on(b.axial_position_mm) {
                return Err(lim::SHAFT_ORDER.refuse(
                    path,
                    &format!(
                        "bearings.{}[{i}].axial_position_mm",
                        member.trim_end_matches("_shaft")
                    ),
                    format!("{}", b.axial_position_mm),
                    format!("must lie on the {member}, [{lo}, {hi}] mm"),
                ));
            }
        }
        Ok(())
    }
}
