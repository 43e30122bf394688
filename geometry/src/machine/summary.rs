//! Settings out: a pair's machine settings with what a shop or another
//! tool reads beside them, per member.
//!
//! The settings are the design file's where it gives them, else the local
//! synthesis of the pinion from the design's ease-off with the wheel cut
//! by the crown generation's settings ([`crate::machine::synthesis`]).
//! Each member's summary holds, per flank: the settings in the design
//! file's form, the flank's spiral and normal pressure angles at the mean
//! point, and the deviation the settings cut relative to the conjugate
//! flank on a 5 × 9 grid of its own normalised flank coordinates (profile
//! 0 = root limit, 1 = tip; face 0 = toe, 1 = heel), each member's
//! rotation about its axis removed at the mean point.

use crate::design::Member;
use crate::error::GeometryError;
use crate::generation::Side;
use crate::machine::deviation::{member_grid, unit_nodes};
use crate::machine::settings::{side_of, FlankSettingsDesign, MachineSettings};
use crate::machine::synthesis::{synthesize, SideSynthesis};
use crate::pair::PairGeometry;
use serde::Serialize;

/// Profile nodes of a summary's deviation grid.
pub const SUMMARY_PROFILE: usize = 5;
/// Face nodes of a summary's deviation grid.
pub const SUMMARY_FACE: usize = 9;

/// Where a pair's settings come from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SettingsSource {
    DesignFile,
    LocalSynthesis,
}

/// One flank's settings and what they cut.
#[derive(Debug, Clone, Serialize)]
pub struct FlankSettingsSummary {
    pub spiral_angle_deg: f64,
    pub normal_pressure_angle_deg: f64,
    /// The rotation about the member's axis removed from the deviation, µrad.
    pub removed_rotation_urad: f64,
    pub settings: FlankSettingsDesign,
    pub deviation: DeviationGrid,
}

/// A deviation grid in the design file's topography form.
#[derive(Debug, Clone, Serialize)]
pub struct DeviationGrid {
    pub profile: Vec<f64>,
    pub face: Vec<f64>,
    /// `deviation_um[i][j]` at (`profile[i]`, `face[j]`), material removed
    /// positive, µm.
    pub deviation_um: Vec<Vec<f64>>,
}

/// One member's summary file.
#[derive(Debug, Clone, Serialize)]
pub struct MemberSettingsSummary {
    pub member: &'static str,
    pub pair: String,
    pub source: SettingsSource,
    /// Where the frames and signs of the settings are defined.
    pub conventions: &'static str,
    pub teeth: u32,
    pub mean_normal_thickness_mm: f64,
    pub blade_edge_radius_mm: f64,
    pub concave: FlankSettingsSummary,
    pub convex: FlankSettingsSummary,
}

/// A pair's settings, their source, the synthesis (where made) and both
/// members' summaries.
#[derive(Debug, Clone, Serialize)]
pub struct SettingsOut {
    pub settings: MachineSettings,
    pub source: SettingsSource,
    pub synthesis: Vec<SideSynthesis>,
    pub members: [MemberSettingsSummary; 2],
}

/// The settings of `g` and their summaries (`g` aligned, as designed).
pub fn settings_out(g: &PairGeometry) -> Result<SettingsOut, GeometryError> {
    let (settings, source, synthesis) = match &g.data.machine_settings {
        Some(s) => (*s, SettingsSource::DesignFile, Vec::new()),
        None => {
            let s = synthesize(g)?;
            (s.settings, SettingsSource::LocalSynthesis, s.sides)
        }
    };
    let (profile, face) = (unit_nodes(SUMMARY_PROFILE), unit_nodes(SUMMARY_FACE));
    let data = &g.data;
    let flank = |m: Member, concave: bool| -> Result<FlankSettingsSummary, GeometryError> {
        let side: Side = side_of(m, concave);
        let f = g.flank(m, side);
        let s = settings.flank(m, side);
        let (spiral, pressure) = f.spiral_and_pressure_angle(data.mean_cone_distance, 0.0)?;
        let dev = member_grid(f, s, &profile, &face)?;
        Ok(FlankSettingsSummary {
            spiral_angle_deg: spiral.to_degrees(),
            normal_pressure_angle_deg: pressure.to_degrees(),
            removed_rotation_urad: dev.removed_rotation_urad,
            settings: s.to_design(),
            deviation: DeviationGrid {
                profile: profile.clone(),
                face: face.clone(),
                deviation_um: dev.deviation_um,
            },
        })
    };
    let member = |m: Member| -> Result<MemberSettingsSummary, GeometryError> {
        Ok(MemberSettingsSummary {
            member: m.name(),
            pair: data.name.clone(),
            source,
            conventions: "docs/machine_settings.md",
            teeth: data.member(m).teeth,
            mean_normal_thickness_mm: data.normal_thickness(m) * 1e3,
            blade_edge_radius_mm: data.edge_radius * 1e3,
            concave: flank(m, true)?,
            convex: flank(m, false)?,
        })
    };
    Ok(SettingsOut {
        settings,
        source,
        synthesis,
        members: [member(Member::Pinion)?, member(Member::Wheel)?],
    })
}
