//! Limits of the scene file's top level, `[blanks]`, `[rotation]`, `[utca]`,
//! `[mesh]`, `[stiffness]`, `[ltca]`, `[blank_dimensions]`,
//! `[misalignment]` and `[sensitivity]` ([`crate::scene_checks`],
//! [`crate::misalignment`], [`crate::scene_sensitivity`]).

use super::*;
use crate::design_file::MAX_CONE_DISTANCE_MM;
use crate::misalignment::{MAX_SHAFT_ANGLE_DEG, MAX_SHIFT_PER_MODULE};
use crate::scene_checks::{
    MAX_FLANK_ELEMENTS, MAX_GRID_POINTS, MAX_POSITIONS, MAX_TORQUES, MAX_TORQUE_NM,
};

const MESH_CYCLES: Rule = real(open(0.0), closed(100.0)).lie_in("");
const STEP_DEG: Rule = real(open(0.0), closed(5.0)).lie_in("");
const UTCA_SAMPLES: Rule = integer(closed(5.0), closed(1000.0)).lie_in("");
const POSITIONS_WHY: &str = "each position holds the contact of every tooth pair";

/// A dimension of `[blank_dimensions]` (each optional).
const fn blank_dimension(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "mm",
        real(open(0.0), closed(MAX_CONE_DISTANCE_MM)).lie_in(" mm"),
    )
    .why("at most the largest mean cone distance of a design")
}

/// A shift of `[misalignment]`: at most a fifth of the mean normal module.
const fn shift(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "mm",
        real(
            closed_at(-MAX_SHIFT_PER_MODULE, "pair.mean_normal_module_mm", 0.0),
            closed_at(MAX_SHIFT_PER_MODULE, "pair.mean_normal_module_mm", 0.0),
        )
        .computed(),
    )
    .why("beyond a fifth of a module the contact leaves the flanks of a localized bearing")
}

/// A half range of `[sensitivity]`: positive, within what the scene's own
/// misalignment leaves of its limit.
const fn half_range(field: &'static str, unit: &'static str, room: &'static str) -> Limit {
    Limit::scene(
        field,
        unit,
        real(open(0.0), closed_derived(room)).computed(),
    )
    .why("the swept misalignment stays within its limit")
}

limits! {
    NAME = Limit::scene("name", "", words(PLAIN_NAME)).why(PLAIN_NAME_WHY);
    TORQUE_COUNT = Limit::scene(
        "pinion_torque_nm",
        "",
        count(closed(1.0), closed(MAX_TORQUES as f64))
            .says("needs 1 to 100 torques (the loads analysed)"),
    )
    .why("the loads analysed");
    TORQUE = Limit::scene(
        "pinion_torque_nm[i]",
        "N·m",
        real(open(0.0), closed(MAX_TORQUE_NM)).lie_in(" N·m"),
    );
    TORQUE_ORDER = Limit::scene(
        "pinion_torque_nm[i]",
        "N·m",
        words("greater than the torque before it (strictly increasing)"),
    )
    .why("each torque names a column of the TE tables and a result file, and the reference FE and the LTCA warm start each load from the one before");
    BLANKS = Limit::scene(
        "blanks",
        "",
        words("`blanks.pinion` and `blanks.wheel` name at least one blank each"),
    );
    BLANK_ONCE = Limit::scene("blanks.<member>[i]", "", words("each blank once"))
        .why("its runs and files are named after it");
    MESH_CYCLES_STANDARD =
        Limit::scene("rotation.mesh_cycles_standard", "mesh cycles", MESH_CYCLES);
    MESH_CYCLES_LIGHTWEIGHT =
        Limit::scene("rotation.mesh_cycles_lightweight", "mesh cycles", MESH_CYCLES);
    ROTATION_STEP = Limit::scene("rotation.step_deg", "deg", STEP_DEG);
    ROTATION_POSITIONS = Limit::scene(
        "rotation.step_deg",
        "positions",
        real(End::Unbounded, closed_e(MAX_POSITIONS))
            .of("positions per wheel blank, mesh cycles × mesh cycle / step + 1")
            .computed(),
    )
    .why(POSITIONS_WHY);
    UTCA_MESH_CYCLES = Limit::scene("utca.mesh_cycles", "mesh cycles", MESH_CYCLES);
    UTCA_STEP = Limit::scene("utca.step_deg", "deg", STEP_DEG);
    UTCA_POSITIONS = Limit::scene(
        "utca.step_deg",
        "positions",
        real(End::Unbounded, closed_e(MAX_POSITIONS))
            .of("positions, `utca.mesh_cycles` × mesh cycle / step + 1")
            .computed(),
    )
    .why(POSITIONS_WHY);
    FACE_SAMPLES = Limit::scene("utca.face_samples", "samples", UTCA_SAMPLES);
    PROFILE_SAMPLES = Limit::scene("utca.profile_samples", "samples", UTCA_SAMPLES);
    FLANK_GRID_PROFILE = Limit::scene("utca.flank_grid_profile", "points", UTCA_SAMPLES);
    FLANK_GRID_FACE = Limit::scene("utca.flank_grid_face", "points", UTCA_SAMPLES);
    MARKING_COMPOUND = Limit::scene(
        "utca.marking_compound_um",
        "µm",
        real(open(0.0), open(100.0)).lie_in(""),
    );
    MESH_PROFILE = Limit::scene(
        "mesh.<level>.profile",
        "elements",
        integer(closed(1.0), closed(MAX_FLANK_ELEMENTS.profile as f64)).computed(),
    )
    .why("elements along the active profile of a loaded flank; the white paper's reference level is 35 × 75");
    MESH_FACE = Limit::scene(
        "mesh.<level>.face",
        "elements",
        integer(closed(1.0), closed(MAX_FLANK_ELEMENTS.face as f64)).computed(),
    )
    .why("elements along the face width of a loaded flank; the white paper's reference level is 35 × 75");
    GRID_PROFILE = Limit::scene(
        "stiffness.grid_profile",
        "points",
        integer(closed(2.0), closed(200.0))
            .or_zero()
            .says("must be 0 (mesh level) or lie in [2, 200]"),
    )
    .why("0: the reduced-order mesh level's");
    GRID_FACE = Limit::scene(
        "stiffness.grid_face",
        "points",
        integer(closed(2.0), closed(200.0))
            .or_zero()
            .says("must be 0 (mesh level) or lie in [2, 200]"),
    )
    .why("0: the reduced-order mesh level's");
    GRID_POINTS = Limit::scene(
        "stiffness.grid_profile × stiffness.grid_face",
        "points",
        integer(End::Unbounded, closed(MAX_GRID_POINTS as f64)).computed(),
    )
    .why("each compliance block holds points² values");
    LOAD_RADIUS = Limit::scene(
        "stiffness.load_radius_factor",
        "grid spacings",
        real(closed(0.25), closed(3.0)).lie_in(""),
    );
    RESPONSE_TEETH = Limit::scene(
        "stiffness.response_teeth",
        "teeth",
        integer(End::Unbounded, closed(5.0)).says("must be <= 5"),
    );
    SOLVE_BLOCK = Limit::scene(
        "stiffness.solve_block",
        "right-hand sides",
        integer(closed(1.0), closed(256.0)).lie_in(""),
    );
    FRICTION = Limit::scene(
        "ltca.friction_coefficient",
        "",
        real(closed(0.0), closed(0.5)).lie_in(""),
    );
    SLICES = Limit::scene(
        "ltca.slices",
        "slices",
        integer(closed(4.0), closed(400.0)).lie_in(""),
    );
    PINION_BORE_RADIUS = blank_dimension("blank_dimensions.pinion_bore_radius_mm");
    PINION_RIM_DEPTH = blank_dimension("blank_dimensions.pinion_rim_depth_mm");
    PINION_SHAFT_LENGTH = blank_dimension("blank_dimensions.pinion_shaft_length_mm");
    WHEEL_BORE_RADIUS = blank_dimension("blank_dimensions.wheel_bore_radius_mm");
    WHEEL_HUB_RADIUS = blank_dimension("blank_dimensions.wheel_hub_radius_mm");
    WHEEL_RIM_DEPTH = blank_dimension("blank_dimensions.wheel_rim_depth_mm");
    WHEEL_WEB_THICKNESS = blank_dimension("blank_dimensions.wheel_web_thickness_mm");
    WHEEL_LIGHTWEIGHT_WEB_THICKNESS =
        blank_dimension("blank_dimensions.wheel_lightweight_web_thickness_mm");
    WHEEL_HOLE_DIAMETER = blank_dimension("blank_dimensions.wheel_hole_diameter_mm");
    PINION_BLANK_SECTION = Limit::scene(
        "blank_dimensions.pinion_bore_radius_mm",
        "mm",
        derived("the pinion blank's half-section a simple polygon off the axis: the bore inside the body (below the rim bottom at the toe)"),
    )
    .why("the body to mesh");
    WHEEL_HOLES_IN_WEB = Limit::scene(
        "blank_dimensions.wheel_hole_diameter_mm",
        "mm",
        derived("below the lightweight web's radial height (hub to rim bottom) and the distance between the three holes' centres"),
    )
    .why("the holes stay inside the web and apart");
    WHEEL_BLANK_SECTION = Limit::scene(
        "blank_dimensions.wheel_hub_radius_mm",
        "mm",
        derived("each wheel blank's half-section a simple polygon off the axis: the hub around the bore and below the rim bottom at the toe"),
    )
    .why("the body to mesh");
    OFFSET = shift("misalignment.offset_mm");
    PINION_AXIAL = shift("misalignment.pinion_axial_mm");
    WHEEL_AXIAL = shift("misalignment.wheel_axial_mm");
    SHAFT_ANGLE = Limit::scene(
        "misalignment.shaft_angle_deg",
        "deg",
        real(closed(-MAX_SHAFT_ANGLE_DEG), closed(MAX_SHAFT_ANGLE_DEG))
            .says("|ΔΣ| must be at most 0.5 deg"),
    );
    SENSITIVITY_VALUES = Limit::scene(
        "sensitivity.values",
        "values",
        odd(closed(3.0), closed(41.0)).says("must be odd and lie in [3, 41]"),
    )
    .why("odd, so that the middle value is the scene's own");
    SENSITIVITY_OFFSET = half_range(
        "sensitivity.offset_mm",
        "mm",
        "the limit of `misalignment.offset_mm` − |`misalignment.offset_mm`|",
    );
    SENSITIVITY_PINION_AXIAL = half_range(
        "sensitivity.pinion_axial_mm",
        "mm",
        "the limit of `misalignment.pinion_axial_mm` − |`misalignment.pinion_axial_mm`|",
    );
    SENSITIVITY_WHEEL_AXIAL = half_range(
        "sensitivity.wheel_axial_mm",
        "mm",
        "the limit of `misalignment.wheel_axial_mm` − |`misalignment.wheel_axial_mm`|",
    );
    SENSITIVITY_SHAFT_ANGLE = half_range(
        "sensitivity.shaft_angle_deg",
        "deg",
        "the limit of `misalignment.shaft_angle_deg` − |`misalignment.shaft_angle_deg`|",
    );
}
