//! Machine settings of a face-milled flank: the design file's form (mm,
//! degrees, in the field names) and the checked form in SI.

use crate::design::{Member, PairData};
use crate::generation::{Generator, Side};
use serde::{Deserialize, Serialize};

/// The settings of one flank as a design file gives them
/// (`[machine_settings.<member>.<flank>]`, `<flank>` = `concave` or
/// `convex`). Signs and frames are the toolkit's ([`crate::machine`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlankSettingsDesign {
    /// Radius of the blade cone in the cradle plane (the cutter's reference
    /// plane), mm: the cutter's mean radius ± half the point width.
    pub blade_radius_mm: f64,
    /// Blade angle against the cutter axis, deg.
    pub blade_angle_deg: f64,
    /// Profile curvature of a curved blade, 1/m (0: straight; positive:
    /// its ends cut deeper, crowning the work's profile).
    #[serde(default)]
    pub blade_profile_curvature_per_m: f64,
    /// Distance of the cutter centre from the cradle axis, mm.
    pub radial_setting_mm: f64,
    /// Angle of the cutter centre about the cradle axis from the machine
    /// frame's x axis, deg.
    pub cradle_angle_deg: f64,
    /// Angle of the work axis against the cradle plane, deg.
    pub machine_root_angle_deg: f64,
    /// The work's apex moved along the cradle axis (+z, from the pinion's
    /// side of the cradle plane to the wheel's), mm.
    #[serde(default)]
    pub sliding_base_mm: f64,
    /// The work's apex moved along the work axis, toward the member's back, mm.
    #[serde(default)]
    pub machine_center_to_back_mm: f64,
    /// The work's apex moved along the machine frame's y axis, mm.
    #[serde(default)]
    pub blank_offset_mm: f64,
    /// Ratio of roll, work rotation per cradle rotation (magnitude).
    pub ratio_of_roll: f64,
    /// Modified roll, second order: the work turns
    /// R_a (φ_c − C φ_c² − D φ_c³) for the cradle's φ_c, with 2C this value, 1/rad.
    #[serde(default)]
    pub modified_roll_2c: f64,
    /// Modified roll, third order: 6D, 1/rad².
    #[serde(default)]
    pub modified_roll_6d: f64,
    /// Tilt of the cutter axis against the cradle axis, deg.
    #[serde(default)]
    pub cutter_tilt_deg: f64,
    /// Direction the cutter axis tilts toward, in the cradle plane, from the
    /// cutter centre's radial direction, deg.
    #[serde(default)]
    pub cutter_swivel_deg: f64,
    /// Generated (rolled) flank; false: Formate, the cutter's imprint with
    /// cradle and work at rest.
    #[serde(default = "yes")]
    pub generated: bool,
}

fn yes() -> bool {
    true
}

/// Both flanks of one member.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberSettingsDesign {
    pub concave: FlankSettingsDesign,
    pub convex: FlankSettingsDesign,
}

/// `[machine_settings]` of a design file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineSettingsDesign {
    pub pinion: MemberSettingsDesign,
    pub wheel: MemberSettingsDesign,
}

/// Checked settings of one flank, SI (m, rad).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FlankSettings {
    pub blade_radius: f64,
    pub blade_angle: f64,
    /// 1/m.
    pub blade_profile_curvature: f64,
    pub radial_setting: f64,
    pub cradle_angle: f64,
    pub machine_root_angle: f64,
    pub sliding_base: f64,
    pub machine_center_to_back: f64,
    pub blank_offset: f64,
    pub ratio_of_roll: f64,
    pub modified_roll_2c: f64,
    pub modified_roll_6d: f64,
    pub cutter_tilt: f64,
    pub cutter_swivel: f64,
    pub generated: bool,
}

impl FlankSettings {
    /// SI form of a design file's entry.
    pub fn from_design(d: &FlankSettingsDesign) -> Self {
        let deg = f64::to_radians;
        let mm = |x: f64| x * 1e-3;
        FlankSettings {
            blade_radius: mm(d.blade_radius_mm),
            blade_angle: deg(d.blade_angle_deg),
            blade_profile_curvature: d.blade_profile_curvature_per_m,
            radial_setting: mm(d.radial_setting_mm),
            cradle_angle: deg(d.cradle_angle_deg),
            machine_root_angle: deg(d.machine_root_angle_deg),
            sliding_base: mm(d.sliding_base_mm),
            machine_center_to_back: mm(d.machine_center_to_back_mm),
            blank_offset: mm(d.blank_offset_mm),
            ratio_of_roll: d.ratio_of_roll,
            modified_roll_2c: d.modified_roll_2c,
            modified_roll_6d: d.modified_roll_6d,
            cutter_tilt: deg(d.cutter_tilt_deg),
            cutter_swivel: deg(d.cutter_swivel_deg),
            generated: d.generated,
        }
    }

    /// The design file's form (mm, degrees).
    pub fn to_design(&self) -> FlankSettingsDesign {
        let deg = f64::to_degrees;
        let mm = |x: f64| x * 1e3;
        FlankSettingsDesign {
            blade_radius_mm: mm(self.blade_radius),
            blade_angle_deg: deg(self.blade_angle),
            blade_profile_curvature_per_m: self.blade_profile_curvature,
            radial_setting_mm: mm(self.radial_setting),
            cradle_angle_deg: deg(self.cradle_angle),
            machine_root_angle_deg: deg(self.machine_root_angle),
            sliding_base_mm: mm(self.sliding_base),
            machine_center_to_back_mm: mm(self.machine_center_to_back),
            blank_offset_mm: mm(self.blank_offset),
            ratio_of_roll: self.ratio_of_roll,
            modified_roll_2c: self.modified_roll_2c,
            modified_roll_6d: self.modified_roll_6d,
            cutter_tilt_deg: deg(self.cutter_tilt),
            cutter_swivel_deg: deg(self.cutter_swivel),
            generated: self.generated,
        }
    }
}

/// The settings of a pair's four flanks, indexed `[member][side]` (side:
/// drive = pinion concave / wheel convex, as [`Side`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MachineSettings {
    pub flanks: [[FlankSettings; 2]; 2],
}

/// The side a member's concave or convex flank is on.
pub fn side_of(m: Member, concave: bool) -> Side {
    match (m, concave) {
        (Member::Pinion, true) | (Member::Wheel, false) => Side::Drive,
        _ => Side::Coast,
    }
}

impl MachineSettings {
    /// SI form of a design file's `[machine_settings]`.
    pub fn from_design(d: &MachineSettingsDesign) -> Self {
        let mut flanks = [[FlankSettings::from_design(&d.pinion.concave); 2]; 2];
        for (i, (m, md)) in [(Member::Pinion, &d.pinion), (Member::Wheel, &d.wheel)]
            .into_iter()
            .enumerate()
        {
            flanks[i][side_of(m, true).index()] = FlankSettings::from_design(&md.concave);
            flanks[i][side_of(m, false).index()] = FlankSettings::from_design(&md.convex);
        }
        MachineSettings { flanks }
    }

    /// The design file's form.
    pub fn to_design(&self) -> MachineSettingsDesign {
        let member = |m: Member| MemberSettingsDesign {
            concave: self.flank(m, side_of(m, true)).to_design(),
            convex: self.flank(m, side_of(m, false)).to_design(),
        };
        MachineSettingsDesign {
            pinion: member(Member::Pinion),
            wheel: member(Member::Wheel),
        }
    }

    /// One flank's settings.
    pub fn flank(&self, m: Member, side: Side) -> &FlankSettings {
        &self.flanks[m as usize][side.index()]
    }

    /// The settings that cut the design's own flanks: the complementary
    /// crown gear of [`crate::generation`] as a cradle (machine root angle
    /// = pitch angle, ratio of roll 1 / sin γ, no offsets, no modified
    /// roll, no tilt), each flank's blade cone placed where the generating
    /// cone is, turned by its tooth-thickness phase.
    pub fn of_crown_generation(pair: &PairData) -> Self {
        let g = Generator::new(pair);
        let flank = |m: Member, side: Side| {
            let f = g.flank(m, side);
            let c = &f.cone;
            let gamma = pair.member(m).pitch_angle;
            FlankSettings {
                blade_radius: c.radius,
                blade_angle: c.tan_alpha.atan(),
                blade_profile_curvature: 0.0,
                radial_setting: c.center[0].hypot(c.center[1]),
                cradle_angle: c.center[1].atan2(c.center[0]) + f.phase,
                machine_root_angle: gamma,
                sliding_base: 0.0,
                machine_center_to_back: 0.0,
                blank_offset: 0.0,
                ratio_of_roll: 1.0 / gamma.sin(),
                modified_roll_2c: 0.0,
                modified_roll_6d: 0.0,
                cutter_tilt: 0.0,
                cutter_swivel: 0.0,
                generated: true,
            }
        };
        let member = |m: Member| [flank(m, Side::Drive), flank(m, Side::Coast)];
        MachineSettings {
            flanks: [member(Member::Pinion), member(Member::Wheel)],
        }
    }
}
