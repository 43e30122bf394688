//! Limits of the design file ([`crate::design_file`], and the tooth checks
//! of [`crate::pair`] when the flanks are built).

use super::*;
use crate::design_file::{
    MAX_CONE_DISTANCE_MM, MAX_CUTTER_RADIUS_CONE_DISTANCES, MAX_DEPTH_MODULES,
    MAX_OFFSET_CONE_DISTANCES, MAX_RADIAL_SETTING_CONE_DISTANCES, MAX_TEETH, MAX_TOPOGRAPHY_NODES,
    MAX_TOPOGRAPHY_UM, MIN_CUTTER_RADIUS_CONE_DISTANCES,
};

/// A number in [lo, hi], refused as "must lie in [lo, hi]".
const fn within(field: &'static str, unit: &'static str, lo: f64, hi: f64) -> Limit {
    Limit::design(field, unit, real(closed(lo), closed(hi)).lie_in(""))
}

/// A number > 0.
const fn positive(field: &'static str, unit: &'static str) -> Limit {
    Limit::design(
        field,
        unit,
        real(open(0.0), End::Unbounded).says("must be > 0"),
    )
}

/// A mean addendum or dedendum: at most [`MAX_DEPTH_MODULES`] modules.
const fn depth(field: &'static str) -> Limit {
    Limit::design(
        field,
        "mm",
        real(
            End::Unbounded,
            closed_at(MAX_DEPTH_MODULES, "pair.mean_normal_module_mm", 0.0),
        )
        .computed(),
    )
    .why("usual: about 1 and 1.25 modules; strongly shifted pinions reach 2")
}

/// A length of the machine settings in (0, `scale` mean cone distances].
const fn settings_length(field: &'static str, scale: f64) -> Limit {
    Limit::design(
        field,
        "mm",
        real(
            open(0.0),
            closed_at(scale, "pair.mean_cone_distance_mm", 0.0),
        )
        .computed(),
    )
}

/// A machine offset (sliding base, machine centre to back, blank
/// offset): at most half the mean cone distance either way.
const fn offset(field: &'static str) -> Limit {
    Limit::design(
        field,
        "mm",
        real(
            closed_at(
                -MAX_OFFSET_CONE_DISTANCES,
                "pair.mean_cone_distance_mm",
                0.0,
            ),
            closed_at(MAX_OFFSET_CONE_DISTANCES, "pair.mean_cone_distance_mm", 0.0),
        )
        .computed(),
    )
}

/// The nodes of a topography axis.
const fn topography_nodes(field: &'static str) -> Limit {
    Limit::design(
        field,
        "nodes",
        count(closed(2.0), closed(MAX_TOPOGRAPHY_NODES as f64)).says("needs 2 to 200 nodes"),
    )
}

limits! {
    NAME = Limit::design("name", "", words(PLAIN_NAME)).why(PLAIN_NAME_WHY);
    SHAFT_ANGLE = within("pair.shaft_angle_deg", "deg", 30.0, 150.0);
    SPIRAL_ANGLE = within("pair.mean_spiral_angle_deg", "deg", 0.0, 50.0);
    NORMAL_MODULE = positive("pair.mean_normal_module_mm", "mm");
    NORMAL_MODULE_FROM_CONE = Limit::design(
        "pair.mean_normal_module_mm",
        "mm",
        derived("2 `pair.mean_cone_distance_mm` sin γ₁ cos β / `pinion.teeth` within 0.2 %, γ₁ the pinion's pitch angle from the tooth numbers"),
    );
    CONE_DISTANCE = Limit::design(
        "pair.mean_cone_distance_mm",
        "mm",
        real(open(0.0), closed(MAX_CONE_DISTANCE_MM)).lie_in(""),
    )
    .why("a 10 m pitch diameter");
    FACE_WIDTH = positive("pair.face_width_mm", "mm");
    FACE_WIDTH_OF_CONE = Limit::design(
        "pair.face_width_mm",
        "mm",
        real(End::Unbounded, closed_at(0.4, "pair.mean_cone_distance_mm", 0.0)).computed(),
    )
    .why("usual limit: a third of the outer cone distance");
    DRIVE_PRESSURE_ANGLE = within("pair.drive_pressure_angle_deg", "deg", 10.0, 35.0);
    COAST_PRESSURE_ANGLE = within("pair.coast_pressure_angle_deg", "deg", 10.0, 35.0);
    TEETH = Limit::design(
        "<member>.teeth",
        "teeth",
        integer(closed(5.0), closed(MAX_TEETH as f64)).lie_in(""),
    );
    PINION_TEETH = Limit::design(
        "pinion.teeth",
        "teeth",
        integer(End::Unbounded, closed_at(1.0, "wheel.teeth", 0.0)).computed(),
    );
    HAND = Limit::design("wheel.hand", "", words("the opposite of `pinion.hand`"));
    PITCH_ANGLE = within("<member>.pitch_angle_deg", "deg", 1.0, 89.0);
    PINION_PITCH_ANGLE = Limit::design(
        "pinion.pitch_angle_deg",
        "deg",
        derived("γ₁ = atan(sin Σ / (z₂/z₁ + cos Σ)) from the tooth numbers and `pair.shaft_angle_deg`, within 0.01"),
    )
    .why("the roll ratios must match z₁/z₂ exactly");
    WHEEL_PITCH_ANGLE = Limit::design(
        "wheel.pitch_angle_deg",
        "deg",
        derived("`pair.shaft_angle_deg` − γ₁, within 0.01"),
    )
    .why("the roll ratios must match z₁/z₂ exactly");
    ROOT_ANGLE = Limit::design(
        "<member>.root_angle_deg",
        "deg",
        real(closed(0.5), closed_at(1.0, "<member>.pitch_angle_deg", 0.0)).computed(),
    );
    FACE_ANGLE = Limit::design(
        "<member>.face_angle_deg",
        "deg",
        real(closed_at(1.0, "<member>.pitch_angle_deg", 0.0), closed(89.9)).computed(),
    );
    ADDENDUM = positive("<member>.mean_addendum_mm", "mm");
    ADDENDUM_DEPTH = depth("<member>.mean_addendum_mm");
    DEDENDUM = positive("<member>.mean_dedendum_mm", "mm");
    DEDENDUM_DEPTH = depth("<member>.mean_dedendum_mm");
    ADDENDUM_AT_TOE = Limit::design(
        "<member>.mean_addendum_mm",
        "mm",
        derived("> (`pair.face_width_mm` / 2) tan(`<member>.face_angle_deg` − `<member>.pitch_angle_deg`), the addendum lost toward the toe"),
    )
    .why("else the tip dips below the pitch cone at the toe");
    DEDENDUM_AT_TOE = Limit::design(
        "<member>.mean_dedendum_mm",
        "mm",
        derived("> (`pair.face_width_mm` / 2) tan(`<member>.pitch_angle_deg` − `<member>.root_angle_deg`), the dedendum lost toward the toe"),
    )
    .why("else the root rises above the pitch cone at the toe");
    POINT_WIDTH = positive("<member>.point_width_mm", "mm");
    YOUNGS_MODULUS = within("<member>.material.youngs_modulus_gpa", "GPa", 1.0, 1000.0);
    POISSON_RATIO = within("<member>.material.poisson_ratio", "", 0.0, 0.49);
    DENSITY = within("<member>.material.density_kg_m3", "kg/m³", 100.0, 30000.0);
    CLEARANCE = Limit::design(
        "<member>.mean_addendum_mm",
        "mm",
        real(End::Unbounded, open_at("<mate>.mean_dedendum_mm")).computed(),
    )
    .why("tip clearance");
    CUTTER_RADIUS = Limit::design(
        "cutter.radius_mm",
        "mm",
        real(
            closed_at(MIN_CUTTER_RADIUS_CONE_DISTANCES, "pair.mean_cone_distance_mm", 0.0),
            closed_at(MAX_CUTTER_RADIUS_CONE_DISTANCES, "pair.mean_cone_distance_mm", 0.0),
        )
        .computed(),
    )
    .why("usual face-mill cutters: 0.5 to 1.5 R_m; beyond, the flanks cannot be generated");
    EDGE_RADIUS = Limit::design(
        "cutter.edge_radius_mm",
        "mm",
        real(
            closed(0.0),
            closed_derived("half the smaller of `pinion.point_width_mm` and `wheel.point_width_mm`"),
        )
        .computed(),
    );
    PROFILE_CROWNING = within("ease_off.profile_crowning_um", "µm", 0.0, 500.0);
    LENGTHWISE_CROWNING = within("ease_off.lengthwise_crowning_um", "µm", 0.0, 500.0);
    MOTION_ERROR = within("ease_off.motion_error_urad", "µrad", 0.0, 500.0);
    BIAS = within("ease_off.bias_um", "µm", -500.0, 500.0);
    TOPOGRAPHY_PROFILE_NODES = topography_nodes("ease_off.topography.profile");
    TOPOGRAPHY_FACE_NODES = topography_nodes("ease_off.topography.face");
    TOPOGRAPHY_PROFILE = within("ease_off.topography.profile[i]", "", 0.0, 1.0);
    TOPOGRAPHY_FACE = within("ease_off.topography.face[i]", "", 0.0, 1.0);
    TOPOGRAPHY_PROFILE_ORDER =
        Limit::design("ease_off.topography.profile[i]", "", words("strictly increasing"));
    TOPOGRAPHY_FACE_ORDER =
        Limit::design("ease_off.topography.face[i]", "", words("strictly increasing"));
    TOPOGRAPHY_SHAPE = Limit::design(
        "ease_off.topography.deviation_um",
        "",
        words("a row per `profile` node, each of a value per `face` node"),
    );
    TOPOGRAPHY_DEVIATION = Limit::design(
        "ease_off.topography.deviation_um[i][j]",
        "µm",
        real(closed(-MAX_TOPOGRAPHY_UM), closed(MAX_TOPOGRAPHY_UM))
            .says("must be finite with |value| <= 1000 µm (a normal deviation from the conjugate flank)"),
    );
    TOOTH_LEFT = Limit::design(
        "<member>.point_width_mm",
        "mm",
        derived("point width + dedendum (tan α_d + tan α_c) < π m_n, the mean normal thickness > 0"),
    )
    .why("else no tooth is left");
    BACKLASH = Limit::design(
        "wheel.point_width_mm",
        "mm",
        derived("normal backlash π m_n − s_n1 − s_n2 ≥ 0"),
    )
    .why("else the teeth interfere");
    CUTTER_CURVATURE = Limit::design(
        "cutter.radius_mm",
        "mm",
        derived("at least the smallest radius whose tooth trace runs from toe to heel with spiral angles in [−85°, 85°] on both sides of the slot"),
    );
    POINTED_TEETH_CUTTER = Limit::design(
        "cutter.radius_mm",
        "mm",
        derived("a top land > 0 at toe, mean and heel of both members, where a larger cutter radius gives one (checked when the flanks are built)"),
    )
    .why("pointed teeth");
    POINTED_TEETH_ADDENDUM = Limit::design(
        "<member>.mean_addendum_mm",
        "mm",
        derived("a top land > 0 at toe, mean and heel, where no cutter radius gives one (checked when the flanks are built)"),
    )
    .why("pointed teeth");
    UNDERCUT = Limit::design(
        "<member>.mean_dedendum_mm",
        "mm",
        derived("both flanks generated regularly down to the fillet limit at toe, mean and heel (checked when the flanks are built)"),
    )
    .why("undercut");
    SETTINGS_BLADE_RADIUS = settings_length(
        "machine_settings.<member>.<flank>.blade_radius_mm",
        MAX_CUTTER_RADIUS_CONE_DISTANCES,
    )
    .why("the largest cutter radius of `cutter.radius_mm`");
    SETTINGS_BLADE_ANGLE = within("machine_settings.<member>.<flank>.blade_angle_deg", "deg", 0.0, 45.0);
    SETTINGS_BLADE_CURVATURE = Limit::design(
        "machine_settings.<member>.<flank>.blade_profile_curvature_per_m",
        "1/m",
        real(closed(-100.0), closed(100.0)).lie_in(""),
    )
    .why("a blade profile radius of at least 10 mm");
    SETTINGS_RADIAL = settings_length(
        "machine_settings.<member>.<flank>.radial_setting_mm",
        MAX_RADIAL_SETTING_CONE_DISTANCES,
    )
    .why("the mean point lies within the cone distance plus the largest cutter radius");
    SETTINGS_CRADLE_ANGLE = within("machine_settings.<member>.<flank>.cradle_angle_deg", "deg", -360.0, 360.0);
    SETTINGS_ROOT_ANGLE = within("machine_settings.<member>.<flank>.machine_root_angle_deg", "deg", 0.0, 90.0);
    SETTINGS_SLIDING_BASE = offset("machine_settings.<member>.<flank>.sliding_base_mm");
    SETTINGS_CENTRE_TO_BACK = offset("machine_settings.<member>.<flank>.machine_center_to_back_mm");
    SETTINGS_BLANK_OFFSET = offset("machine_settings.<member>.<flank>.blank_offset_mm");
    SETTINGS_RATIO_OF_ROLL = Limit::design(
        "machine_settings.<member>.<flank>.ratio_of_roll",
        "",
        real(open(0.0), closed(100.0)).lie_in(""),
    )
    .why("1 / sin γ reaches 57 at a 1° pitch angle");
    SETTINGS_ROLL_2C = within("machine_settings.<member>.<flank>.modified_roll_2c", "1/rad", -10.0, 10.0);
    SETTINGS_ROLL_6D = within("machine_settings.<member>.<flank>.modified_roll_6d", "1/rad²", -100.0, 100.0);
    SETTINGS_TILT = within("machine_settings.<member>.<flank>.cutter_tilt_deg", "deg", 0.0, 45.0);
    SETTINGS_SWIVEL = within("machine_settings.<member>.<flank>.cutter_swivel_deg", "deg", -360.0, 360.0);
    SETTINGS_DEVIATION = Limit::design(
        "machine_settings",
        "µm",
        derived("the flanks the settings cut within 200 µm (relative, pinion and wheel deviation summed at mating points) of the design's conjugate flanks over the pinion's flank, each member's rotation about its axis removed (checked when the flanks are built)"),
    )
    .why("else the settings describe another gear");
}
