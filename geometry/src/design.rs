//! Gear pair design files (TOML, units in the field names) and the checked
//! pair data in SI units they turn into.
//!
//! A design file holds what a bevel gear designer has on the dimension sheet.
//! [`crate::design_file`] reads and checks it: `DesignFile::load` parses it
//! (unknown fields and malformed TOML are errors with line and column) and
//! `DesignFile::to_pair` checks it and converts it to [`PairData`]. Every
//! rejection names the file, the field, the value and the limit.

use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// Hand of spiral, seen from the face of the gear (from the cone apex side):
/// right hand when the outer half of the tooth turns clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Hand {
    Right,
    Left,
}

/// Top level of a design file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// Short name used in output paths.
    pub name: String,
    /// Where the data come from (paper, table).
    pub source: String,
    /// What was not published and was chosen, and why.
    #[serde(default)]
    pub notes: Vec<String>,
    pub pair: PairDesign,
    pub pinion: MemberDesign,
    pub wheel: MemberDesign,
    pub cutter: CutterDesign,
    #[serde(default)]
    pub ease_off: EaseOffDesign,
    /// Machine settings of the four flanks; the flanks they cut enter as
    /// a topography of the pinion's ease-off ([`crate::machine`]).
    #[serde(default)]
    pub machine_settings: Option<crate::machine::settings::MachineSettingsDesign>,
    /// Published results this pair is compared with. Not part of the
    /// geometry: [`geometry_text`] leaves this table out of what the meshes
    /// and stiffness files are hashed from.
    #[serde(default)]
    pub published: PublishedDesign,
}

/// Files of published results for this pair (TOML, paths relative to the
/// design file), for the report's comparison.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PublishedDesign {
    /// Loaded TE per blank and load (mean and peak-to-peak, multibody and
    /// NLFEA), e.g. the white paper's Tables 3–4.
    #[serde(default)]
    pub loaded_te: Option<PathBuf>,
    /// Run time per step or position, e.g. the white paper's Table 5.
    #[serde(default)]
    pub cpu: Option<PathBuf>,
}

/// The design file's text without its `[published]` table: what the pair's
/// geometry and material are read from (the hash of the meshes' inputs).
/// The table and the blank lines before it are cut up to the next table
/// header or the end, so adding it leaves the hash of a file unchanged.
pub fn geometry_text(text: &str) -> String {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let Some(start) = lines.iter().position(|l| l.trim() == "[published]") else {
        return text.to_string();
    };
    let end = (start + 1..lines.len())
        .find(|&i| lines[i].trim_start().starts_with('['))
        .unwrap_or(lines.len());
    let mut keep = start;
    while keep > 0 && lines[keep - 1].trim().is_empty() {
        keep -= 1;
    }
    let mut out: String = lines[..keep].concat();
    if end < lines.len() {
        out.push('\n');
        out.push_str(&lines[end..].concat());
    }
    out
}

/// Data common to both members.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairDesign {
    pub shaft_angle_deg: f64,
    pub mean_spiral_angle_deg: f64,
    pub mean_normal_module_mm: f64,
    pub mean_cone_distance_mm: f64,
    pub face_width_mm: f64,
    /// Normal pressure angle of the drive side (pinion concave, wheel convex).
    pub drive_pressure_angle_deg: f64,
    /// Normal pressure angle of the coast side (pinion convex, wheel concave).
    pub coast_pressure_angle_deg: f64,
}

/// Data of one member.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberDesign {
    pub teeth: u32,
    pub hand: Hand,
    pub pitch_angle_deg: f64,
    pub root_angle_deg: f64,
    pub face_angle_deg: f64,
    /// Addendum at the mean cone distance, measured normal to the pitch cone.
    pub mean_addendum_mm: f64,
    /// Dedendum at the mean cone distance, measured normal to the pitch cone.
    pub mean_dedendum_mm: f64,
    /// Point width of the blades that cut this member's slots (normal section, blade tips).
    pub point_width_mm: f64,
    pub material: MaterialDesign,
}

/// Linear elastic material, as the design file gives it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialDesign {
    pub youngs_modulus_gpa: f64,
    pub poisson_ratio: f64,
    pub density_kg_m3: f64,
}

/// The face-mill cutter of the generating crown gear.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutterDesign {
    /// Mean (nominal) cutter radius: centre of the pinion slot at the pitch plane.
    pub radius_mm: f64,
    /// Blade edge radius that cuts the root fillet.
    pub edge_radius_mm: f64,
}

/// Flank modification (ease-off) designed on the pinion, as normal deviations
/// from the conjugate flank (positive = material removed).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EaseOffDesign {
    /// Deviation at the tip and root limits of the active profile, relative to its middle.
    #[serde(default)]
    pub profile_crowning_um: f64,
    /// Deviation at toe and heel, relative to the mean point.
    #[serde(default)]
    pub lengthwise_crowning_um: f64,
    /// Flank twist: deviation at heel-tip (positive) and toe-tip (negative) corners.
    #[serde(default)]
    pub bias_um: f64,
    /// Parabolic motion error: wheel-side transmission error reached half a
    /// mesh cycle away from the parabola's vertex.
    #[serde(default)]
    pub motion_error_urad: f64,
    /// Measured or imported topography added on top (normal deviations on a grid).
    #[serde(default)]
    pub topography: Option<TopographyDesign>,
}

/// Normal deviations on a grid in normalised flank coordinates (profile 0 = root
/// limit of the flank, 1 = tip; face 0 = toe, 1 = heel), bicubic between nodes.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TopographyDesign {
    /// Strictly increasing profile coordinates in [0, 1].
    pub profile: Vec<f64>,
    /// Strictly increasing face coordinates in [0, 1].
    pub face: Vec<f64>,
    /// `deviation_um[i][j]` at (`profile[i]`, `face[j]`).
    pub deviation_um: Vec<Vec<f64>>,
}

/// Which member.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Member {
    Pinion,
    Wheel,
}

impl Member {
    pub fn name(self) -> &'static str {
        match self {
            Member::Pinion => "pinion",
            Member::Wheel => "wheel",
        }
    }
}

/// Checked design data in SI units (m, rad, Pa).
#[derive(Debug, Clone, Serialize)]
pub struct PairData {
    pub name: String,
    pub shaft_angle: f64,
    pub spiral_angle: f64,
    pub normal_module: f64,
    pub mean_cone_distance: f64,
    pub face_width: f64,
    /// Normal pressure angle, index 0 = drive side, 1 = coast side.
    pub pressure_angle: [f64; 2],
    pub members: [MemberData; 2],
    pub cutter_radius: f64,
    pub edge_radius: f64,
    pub ease_off: EaseOffDesign,
    /// Machine settings of the four flanks, if the design file gives them.
    pub machine_settings: Option<crate::machine::settings::MachineSettings>,
    /// Published results, paths resolved against the design file's folder.
    pub published: PublishedDesign,
}

/// One member, SI.
#[derive(Debug, Clone, Serialize)]
pub struct MemberData {
    pub teeth: u32,
    pub hand: Hand,
    pub pitch_angle: f64,
    pub root_angle: f64,
    pub face_angle: f64,
    pub mean_addendum: f64,
    pub mean_dedendum: f64,
    pub point_width: f64,
    pub youngs_modulus: f64,
    pub poisson_ratio: f64,
    pub density: f64,
}

impl MemberData {
    /// The member's elastic constants.
    pub fn material(&self) -> crate::Material {
        crate::Material {
            youngs_modulus_pa: self.youngs_modulus,
            poisson_ratio: self.poisson_ratio,
        }
    }
}

impl PairData {
    pub fn member(&self, m: Member) -> &MemberData {
        match m {
            Member::Pinion => &self.members[0],
            Member::Wheel => &self.members[1],
        }
    }
    /// Outer (heel) and inner (toe) cone distances.
    pub fn outer_cone_distance(&self) -> f64 {
        self.mean_cone_distance + 0.5 * self.face_width
    }
    pub fn inner_cone_distance(&self) -> f64 {
        self.mean_cone_distance - 0.5 * self.face_width
    }
    /// Mean normal circular tooth thickness at the pitch cone, from the point
    /// width: slot = W + h_f (tan α_d + tan α_c), thickness = π m_n − slot.
    pub fn normal_thickness(&self, m: Member) -> f64 {
        let d = self.member(m);
        let slot = d.point_width
            + d.mean_dedendum * (self.pressure_angle[0].tan() + self.pressure_angle[1].tan());
        std::f64::consts::PI * self.normal_module - slot
    }
    /// Normal backlash at the mean point: π m_n − s_n1 − s_n2.
    pub fn normal_backlash(&self) -> f64 {
        std::f64::consts::PI * self.normal_module
            - self.normal_thickness(Member::Pinion)
            - self.normal_thickness(Member::Wheel)
    }
    /// Number of teeth of the virtual generating crown gear, z / sin γ.
    pub fn crown_teeth(&self) -> f64 {
        self.members[0].teeth as f64 / self.members[0].pitch_angle.sin()
    }
    /// Pinion rotation of one mesh cycle, 2π / z₁.
    pub fn mesh_cycle(&self) -> f64 {
        2.0 * std::f64::consts::PI / self.members[0].teeth as f64
    }
}

/// Pitch cone angle of the pinion from the tooth numbers and shaft angle:
/// tan γ₁ = sin Σ / (z₂/z₁ + cos Σ).
pub fn pinion_pitch_angle(z1: f64, z2: f64, shaft_angle: f64) -> f64 {
    (shaft_angle.sin() / (z2 / z1 + shaft_angle.cos())).atan()
}
