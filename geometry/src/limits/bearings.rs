//! Limits of the scene's `[bearings]` table ([`crate::scene_bearings`]).

use super::*;
use crate::scene_bearings::{
    MAX_BEARING_DAMPING_N_S_PER_M, MAX_BEARING_POSITION_MM, MAX_BEARING_STIFFNESS_N_PER_M,
    MAX_SHAFT_DIAMETER_MM, MAX_SHAFT_SEGMENTS,
};

/// A position along the member's axis from its pitch apex.
const fn position(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "mm",
        real(
            closed(-MAX_BEARING_POSITION_MM),
            closed(MAX_BEARING_POSITION_MM),
        )
        .says("must be finite, within ±10,000 mm of the pitch apex"),
    )
}

/// A bearing stiffness.
const fn stiffness(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "N/m",
        real(closed(0.0), closed_e(MAX_BEARING_STIFFNESS_N_PER_M)).lie_in(" N/m"),
    )
    .why("stiffer than this is rigid for any gear mesh")
}

/// A bearing damping.
const fn damping(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "N·s/m",
        real(closed(0.0), closed_e(MAX_BEARING_DAMPING_N_S_PER_M)).lie_in(" N·s/m"),
    )
}

limits! {
    AXIAL_POSITION = position("bearings.<member>[i].axial_position_mm");
    RADIAL_STIFFNESS = stiffness("bearings.<member>[i].radial_stiffness_n_per_m");
    AXIAL_STIFFNESS = stiffness("bearings.<member>[i].axial_stiffness_n_per_m");
    RADIAL_DAMPING = damping("bearings.<member>[i].radial_damping_n_s_per_m");
    AXIAL_DAMPING = damping("bearings.<member>[i].axial_damping_n_s_per_m");
    HELD_AGAINST_TILT = Limit::scene(
        "bearings.<member>",
        "",
        words("two bearings with radial stiffness at different axial positions"),
    )
    .why("to hold tilt");
    HELD_ALONG_AXIS = Limit::scene(
        "bearings.<member>",
        "",
        words("one bearing with `axial_stiffness_n_per_m` > 0"),
    )
    .why("else the shaft slides along its axis");
    BODY_MASS = Limit::scene(
        "bearings.<member>_body.mass_kg",
        "kg",
        real(open(0.0), closed_e(1e5)).lie_in(" kg"),
    );
    BODY_CENTROID = position("bearings.<member>_body.centroid_mm");
    BODY_TRANSVERSE_INERTIA = Limit::scene(
        "bearings.<member>_body.transverse_inertia_kgm2",
        "kg·m²",
        real(open(0.0), closed_e(1e4)).lie_in(" kg·m²"),
    );
    SHAFT_SEAT = position("bearings.<member>_shaft.seat_mm");
    SHAFT_FROM = position("bearings.<member>_shaft.segments[i].from_mm");
    SHAFT_TO = position("bearings.<member>_shaft.segments[i].to_mm");
    SHAFT_SEGMENTS = Limit::scene(
        "bearings.<member>_shaft.segments",
        "",
        count(closed(1.0), closed(MAX_SHAFT_SEGMENTS as f64)).says("needs 1 to 50 segments"),
    );
    SHAFT_DIAMETER = Limit::scene(
        "bearings.<member>_shaft.segments[i].outer_diameter_mm",
        "mm",
        real(open(0.0), closed(MAX_SHAFT_DIAMETER_MM)).lie_in(" mm"),
    );
    SHAFT_BORE = Limit::scene(
        "bearings.<member>_shaft.segments[i].inner_diameter_mm",
        "mm",
        real(closed(0.0), closed(MAX_SHAFT_DIAMETER_MM)).lie_in(" mm"),
    );
    SHAFT_ORDER = Limit::scene(
        "bearings.<member>_shaft",
        "",
        words("segments contiguous in axial order, inner below outer diameter, the seat and every bearing on the shaft"),
    );
    GEARBOX_SHAFT_ELEMENT = Limit::scene(
        "bearings.gearbox.shaft_element_mm",
        "mm",
        real(closed(0.5), closed(1_000.0)).lie_in(" mm"),
    )
    .why("finer than 0.5 mm adds coordinates, not accuracy, to a shaft model");
    GEARBOX_MODES_UP_TO = Limit::scene(
        "bearings.gearbox.modes_up_to_hz",
        "Hz",
        real(closed(1.0), closed(1e6)).lie_in(" Hz"),
    );
    HOUSING_PINION_BORE = Limit::scene(
        "bearings.gearbox.housing.pinion_bore_diameter_mm",
        "mm",
        real(open(0.0), closed(MAX_SHAFT_DIAMETER_MM)).lie_in(" mm"),
    );
    HOUSING_WHEEL_BORE = Limit::scene(
        "bearings.gearbox.housing.wheel_bore_diameter_mm",
        "mm",
        real(open(0.0), closed(MAX_SHAFT_DIAMETER_MM)).lie_in(" mm"),
    );
    HOUSING_WALL = Limit::scene(
        "bearings.gearbox.housing.wall_mm",
        "mm",
        real(closed(1.0), closed(500.0)).lie_in(" mm"),
    );
    HOUSING_FLOOR = Limit::scene(
        "bearings.gearbox.housing.floor_mm",
        "mm",
        real(closed(1.0), closed(500.0)).lie_in(" mm"),
    );
    HOUSING_RIM = Limit::scene(
        "bearings.gearbox.housing.rim_mm",
        "mm",
        real(closed(1.0), closed(500.0)).lie_in(" mm"),
    );
    HOUSING_CLEARANCE = Limit::scene(
        "bearings.gearbox.housing.clearance_mm",
        "mm",
        real(closed(0.5), closed(500.0)).lie_in(" mm"),
    );
    HOUSING_FOOT = Limit::scene(
        "bearings.gearbox.housing.foot_mm",
        "mm",
        real(closed(1.0), closed(1_000.0)).lie_in(" mm"),
    );
    HOUSING_ELEMENT = Limit::scene(
        "bearings.gearbox.housing.element_mm",
        "mm",
        real(closed(1.0), closed(200.0)).lie_in(" mm"),
    )
    .why("finer than 1 mm makes a housing mesh of millions of nodes");
    HOUSING_MODES_UP_TO = Limit::scene(
        "bearings.gearbox.housing.modes_up_to_hz",
        "Hz",
        real(closed(0.0), closed(1e6)).lie_in(" Hz"),
    );
    HOUSING_DAMPING = Limit::scene(
        "bearings.gearbox.housing.damping_ratio",
        "",
        real(closed(0.0), closed(0.5)).lie_in(""),
    );
    HOUSING_MODES_COVER = Limit::scene(
        "bearings.gearbox.housing.modes_up_to_hz",
        "Hz",
        words("at least `bearings.gearbox.modes_up_to_hz`"),
    )
    .why("the housing's modes are checked against the whole FE housing's up to the gearbox's range");
    HOUSING_YOUNGS_MODULUS = Limit::scene(
        "bearings.gearbox.housing.youngs_modulus_gpa",
        "GPa",
        real(closed(1.0), closed(1_000.0)).lie_in(" GPa"),
    );
    HOUSING_POISSON_RATIO = Limit::scene(
        "bearings.gearbox.housing.poisson_ratio",
        "",
        real(closed(0.0), open(0.5)).lie_in(""),
    );
    HOUSING_DENSITY = Limit::scene(
        "bearings.gearbox.housing.density_kg_m3",
        "kg/m³",
        real(closed(100.0), closed(30_000.0)).lie_in(" kg/m³"),
    );
    HOUSING_FITS = Limit::scene(
        "bearings.gearbox.housing",
        "",
        words("bores wider than their shafts, `clearance_mm` kept from every gear blank and shaft, the feet on the floor"),
    )
    .why("the housing must hold the bearings without touching what turns");
    TOLERANCE = Limit::scene(
        "bearings.tolerance_nm",
        "nm",
        real(closed(1e-3), closed(1e3)).lie_in(" nm"),
    );
    MAX_ITERATIONS = Limit::scene(
        "bearings.max_iterations",
        "iterations",
        integer(closed(2.0), closed(500.0)).lie_in(""),
    );
}
