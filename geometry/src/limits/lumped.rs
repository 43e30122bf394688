//! Limits of the scene's `[lumped]` table and its sub-tables
//! ([`crate::scene_lumped`]).

use super::*;
use crate::design_file::MAX_TOPOGRAPHY_NODES;
use crate::scene_checks::MAX_LIST_RUNS;

/// A positive number up to `hi`, refused as "must lie in (0, hi]".
const fn up_to(field: &'static str, unit: &'static str, hi: End) -> Limit {
    Limit::scene(field, unit, real(open(0.0), hi).lie_in(""))
}

/// A number in [lo, hi], refused as "must lie in [lo, hi]`suffix`".
const fn within(
    field: &'static str,
    unit: &'static str,
    lo: f64,
    hi: f64,
    suffix: &'static str,
) -> Limit {
    Limit::scene(field, unit, real(closed(lo), closed(hi)).lie_in(suffix))
}

/// An optional mass or inertia (absent: from the mesh).
const fn positive(field: &'static str, unit: &'static str) -> Limit {
    Limit::scene(
        field,
        unit,
        real(open(0.0), End::Unbounded).says("must be finite and > 0"),
    )
}

/// The three bearing stiffnesses (X, Y, Z) of a member.
const fn bearing_stiffness(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "N/m",
        real(open(0.0), closed_e(1e13)).each().each_lie_in(""),
    )
}

/// Topography nodes of the roughness.
const fn nodes(field: &'static str) -> Limit {
    Limit::scene(
        field,
        "nodes",
        integer(closed(2.0), closed(MAX_TOPOGRAPHY_NODES as f64)).lie_in(""),
    )
}

limits! {
    PINION_SPEED = up_to("lumped.pinion_speed_rpm", "rpm", closed(1e5));
    PINION_TORQUE = up_to("lumped.pinion_torque_nm", "N·m", closed_e(1e6));
    MESH_CYCLES = up_to("lumped.mesh_cycles", "mesh cycles", closed(1e4));
    DROPPED_MESH_CYCLES = Limit::scene(
        "lumped.dropped_mesh_cycles",
        "mesh cycles",
        real(closed(0.0), open_at("lumped.mesh_cycles")).says("must lie in [0, mesh_cycles)"),
    );
    SAMPLES = Limit::scene(
        "lumped.samples_per_mesh_cycle",
        "samples",
        integer(closed(16.0), closed(4096.0)).lie_in(""),
    );
    RELATIVE_TOLERANCE = Limit::scene(
        "lumped.relative_tolerance",
        "",
        real(open_e(1e-13), closed_e(1e-2)).lie_in(""),
    );
    FOURIER_TOLERANCE = up_to("lumped.fourier_tolerance_of_ptp", "", closed(1.0));
    MESH_DAMPING = within("lumped.mesh_damping_ratio", "", 0.0, 1.0, "");
    BEARING_DAMPING = within("lumped.bearing_damping_ratio", "", 0.0, 1.0, "");
    PINION_BEARING_STIFFNESS = bearing_stiffness("lumped.pinion_bearing_stiffness_n_per_m");
    WHEEL_BEARING_STIFFNESS = bearing_stiffness("lumped.wheel_bearing_stiffness_n_per_m");
    PINION_MASS = positive("lumped.pinion_mass_kg", "kg");
    WHEEL_MASS = positive("lumped.wheel_mass_kg", "kg");
    PINION_INERTIA = positive("lumped.pinion_inertia_kgm2", "kg·m²");
    WHEEL_INERTIA = positive("lumped.wheel_inertia_kgm2", "kg·m²");
    IMPACT_PULSE = up_to("lumped.impact_pulse_of_mesh_period", "mesh periods", closed(0.5));
    MORE_PINION_TORQUES = Limit::scene(
        "lumped.more_pinion_torques_nm",
        "N·m",
        real(open(0.0), closed_e(1e6)).each().each_lie_in(""),
    );
    FRICTION_BASE = within("lumped.friction.base_coefficient", "", 0.0, 2.0, "");
    FRICTION_ROUGHNESS =
        within("lumped.friction.roughness_coefficient_per_um", "1/µm", 0.0, 2.0, "");
    ROUGHNESS_GRADES = Limit::scene(
        "lumped.roughness.ra_um",
        "",
        count(closed(1.0), closed(MAX_LIST_RUNS as f64)).says("needs 1 to 100 grades"),
    )
    .why("one run per grade");
    ROUGHNESS_RA = Limit::scene(
        "lumped.roughness.ra_um",
        "µm",
        real(open(0.0), closed(10.0)).each().each_lie_in(" µm"),
    );
    ROUGHNESS_PROFILE_NODES = nodes("lumped.roughness.profile_nodes");
    ROUGHNESS_FACE_NODES = nodes("lumped.roughness.face_nodes");
    MORE_PINION_TORQUE_COUNT = Limit::scene(
        "lumped.more_pinion_torques_nm",
        "",
        count(End::Unbounded, closed(MAX_LIST_RUNS as f64)).says("holds at most 100 torques"),
    )
    .why("one run per torque");
    VARIANT_COUNT = Limit::scene(
        "lumped.design_variants",
        "",
        count(End::Unbounded, closed(MAX_LIST_RUNS as f64)).says("holds at most 100 variants"),
    )
    .why("one run per variant");
    VARIANT_NAMES_UNIQUE = Limit::scene(
        "lumped.design_variants.name",
        "",
        words("each name once"),
    )
    .why("the name in the output");
    VARIANT_NAME = Limit::scene(
        "lumped.design_variants.name",
        "",
        words("1 to 100 characters: letters, digits, `_`, `.`, `-`"),
    )
    .why("the name in the output");
    VARIANT_TE_SLOPE =
        within("lumped.design_variants.te_slope_m21", "1/rad", -0.1, 0.0, " per rad");
    VARIANT_PROFILE_CROWNING =
        within("lumped.design_variants.profile_crowning_um", "µm", 0.0, 500.0, " µm");
    VARIANT_LENGTHWISE_CROWNING =
        within("lumped.design_variants.lengthwise_crowning_um", "µm", 0.0, 500.0, " µm");
    ORDER_MAP_SPEED_COUNT = Limit::scene(
        "lumped.order_map.pinion_speeds_rpm",
        "",
        count(closed(1.0), closed(MAX_LIST_RUNS as f64)).says("must hold 1 to 100 speeds"),
    )
    .why("one run per speed");
    ORDER_MAP_SPEEDS = Limit::scene(
        "lumped.order_map.pinion_speeds_rpm",
        "rpm",
        real(open(0.0), closed(1e5)).each().lie_in(" rpm"),
    );
    ORDER_MAP_REVOLUTIONS = within(
        "lumped.order_map.wheel_revolutions",
        "wheel revolutions",
        1.0,
        20.0,
        "",
    );
    ORDER_MAP_DROPPED = Limit::scene(
        "lumped.order_map.dropped_wheel_revolutions",
        "wheel revolutions",
        real(
            closed(0.0),
            closed_at(1.0, "lumped.order_map.wheel_revolutions", -1.0),
        )
        .says("must be >= 0 and leave at least one wheel revolution"),
    );
    ORDER_MAP_MAX_ORDER = positive("lumped.order_map.max_pinion_order", "pinion orders");
}
