//! Limits of the scene's `[multibody]`, `[multibody.impact]`,
//! `[multibody.load_run]` and `[multibody.ste_dte]` tables
//! ([`crate::scene_checks`], [`crate::scene_contact_law`],
//! [`crate::scene_ste_dte`]).

use super::*;
use crate::scene_checks::{
    MAX_POSITIONS, MAX_TIME_STEPS, MIN_TABLE_LAG_NODES, MIN_TE_TOLERANCE_URAD,
};

/// A number in [lo, hi], refused as "must lie in [lo, hi]".
const fn within(field: &'static str, unit: &'static str, lo: f64, hi: f64) -> Limit {
    Limit::scene(field, unit, real(closed(lo), closed(hi)).lie_in(""))
}

/// The time steps of a run: at most [`MAX_TIME_STEPS`].
const fn time_steps(field: &'static str, quantity: &'static str) -> Limit {
    Limit::scene(
        field,
        "time steps",
        real(End::Unbounded, closed_e(MAX_TIME_STEPS))
            .of(quantity)
            .computed(),
    )
}

limits! {
    QUASI_STATIC_WHEEL_RPM = within("multibody.quasi_static_wheel_rpm", "rpm", 1e-3, 1e4);
    QUASI_STATIC_MAX_STEP = within("multibody.quasi_static_max_step_s", "s", 1e-8, 1.0);
    QUASI_STATIC_TIME_STEPS = time_steps(
        "multibody.quasi_static_max_step_s",
        "time steps of the quasi-static run, its time (the sweep's mesh cycles at `multibody.quasi_static_wheel_rpm`) / step",
    );
    RUNUP_RPM_START = within("multibody.runup_rpm[0]", "rpm", 0.0, 1e5);
    RUNUP_RPM_END = within("multibody.runup_rpm[1]", "rpm", 0.0, 1e5);
    RUNUP_TIME = within("multibody.runup_time_s", "s", 1e-4, 100.0);
    RUNUP_PINION_TORQUE = within("multibody.runup_pinion_torque_nm", "N·m", 0.0, 1e6);
    RUNUP_MAX_STEP = within("multibody.runup_max_step_s", "s", 1e-8, 1.0);
    RUNUP_TIME_STEPS = time_steps(
        "multibody.runup_max_step_s",
        "time steps of the run-up, `multibody.runup_time_s` / step",
    );
    RUNUP_BLANK_ONCE = Limit::scene(
        "multibody.runup_wheel_blanks[i]",
        "",
        words("each blank once"),
    )
    .why("its runs and files are named after it");
    RUNUP_BLANK_IN_SCENE = Limit::scene(
        "multibody.runup_wheel_blanks[i]",
        "",
        words("one of `blanks.wheel`, where the scene gives the list"),
    )
    .why("a blank the scene does not analyse has no stiffness files to run on");
    DAMPING_RATIO = within("multibody.damping_ratio", "", 0.0, 10.0);
    RHO_INF = within("multibody.rho_inf", "", 0.0, 1.0);
    TE_TOLERANCE = within("multibody.te_tolerance_urad", "µrad", MIN_TE_TOLERANCE_URAD, 100.0)
        .why("the lag is resolved to about 1e-15 (1 + |q|) rad; tighter tolerances only reject steps down to the smallest step");
    TABLE_STEP = within("multibody.table_step_deg", "deg", 1e-3, 2.0);
    TABLE_POSITIONS = Limit::scene(
        "multibody.table_step_deg",
        "positions",
        real(End::Unbounded, closed_e(MAX_POSITIONS))
            .of("table positions, the pinion rotation the runs cover / step + 1")
            .computed(),
    )
    .why("each position holds the contact of every tooth pair");
    TABLE_LAG_NODES = Limit::scene(
        "multibody.table_lag_nodes",
        "nodes",
        integer(closed(MIN_TABLE_LAG_NODES as f64), closed(2000.0)).computed(),
    )
    .why("a third of the nodes resolve the band of unloaded TEs; fewer put the loaded balance beyond the table");
    TABLE_TORQUE_FACTOR = within("multibody.table_torque_factor", "", 1.0, 100.0);
    PINION_INERTIA = Limit::scene(
        "multibody.pinion_inertia_kgm2",
        "kg·m²",
        real(open(0.0), End::Unbounded).says("must be finite and > 0"),
    );
    WHEEL_INERTIA = Limit::scene(
        "multibody.wheel_inertia_kgm2",
        "kg·m²",
        real(open(0.0), End::Unbounded).says("must be finite and > 0"),
    );
    RATTLE_PINION_RPM = within("multibody.rattle_pinion_rpm", "rpm", 0.0, 1e5);
    RATTLE_SPEED_FLUCTUATION = within("multibody.rattle_speed_fluctuation", "", 0.0, 1.0);
    RATTLE_FREQUENCY = within("multibody.rattle_frequency_hz", "Hz", 0.0, 1e5);
    RATTLE_WHEEL_DRAG = within("multibody.rattle_wheel_drag_nm", "N·m", 0.0, 1e4);
    RATTLE_TIME = within("multibody.rattle_time_s", "s", 0.0, 100.0);
    RATTLE_NEEDS_COAST = Limit::scene(
        "multibody.rattle_time_s",
        "s",
        words("0 unless `multibody.coast_contact` = true"),
    )
    .why("rattle needs both flanks");
    ROOT_STRESS_NEEDS_COEFFICIENTS = Limit::scene(
        "multibody.root_stress",
        "",
        words("false unless `multibody.force_law` = \"element\" and `stiffness.root_stress` = true"),
    )
    .why("the root stress comes from the contact element and the stiffness files' root-stress coefficients");
    RATTLE_MAX_STEP = within("multibody.rattle_max_step_s", "s", 1e-8, 1.0);
    RATTLE_TIME_STEPS = time_steps(
        "multibody.rattle_max_step_s",
        "time steps of the rattle run, `multibody.rattle_time_s` / step",
    );
    IMPACT_LAW = Limit::scene(
        "multibody.force_law",
        "",
        words("`impact` needs `multibody.coast_contact` = false"),
    )
    .why("the impact law's table carries the drive flanks only");
    IMPACT_STIFFNESS = Limit::scene(
        "multibody.impact.stiffness_n_per_mm_e",
        "N/mm^e",
        real(open(0.0), closed_e(1e15)).lie_in(" N/mm^e"),
    );
    IMPACT_EXPONENT = within("multibody.impact.exponent", "", 1.0, 3.0);
    IMPACT_DAMPING = within("multibody.impact.damping_n_s_per_mm", "N·s/mm", 0.0, 1e9);
    IMPACT_STATIC_FRICTION = within("multibody.impact.static_friction", "", 0.0, 2.0);
    IMPACT_DYNAMIC_FRICTION = within("multibody.impact.dynamic_friction", "", 0.0, 2.0);
    IMPACT_PENETRATION_DEPTH = Limit::scene(
        "multibody.impact.penetration_depth_mm",
        "mm",
        real(open(0.0), closed_e(1e6)).lie_in(""),
    );
    IMPACT_STICTION_SPEED = Limit::scene(
        "multibody.impact.stiction_speed_mm_s",
        "mm/s",
        real(open(0.0), closed_e(1e6)).lie_in(""),
    );
    IMPACT_TRANSITION_SPEED = Limit::scene(
        "multibody.impact.friction_transition_speed_mm_s",
        "mm/s",
        real(open_at("multibody.impact.stiction_speed_mm_s"), closed_e(1e6)).computed(),
    );
    STE_DTE_TORQUE = within("multibody.ste_dte.pinion_torque_nm", "N·m", 0.0, 1e6);
    STE_DTE_RPM_QUASI_STATIC = Limit::scene(
        "multibody.ste_dte.rpm[0]",
        "rpm",
        real(open(0.0), closed_e(1e5)).lie_in(""),
    );
    STE_DTE_RPM_DYNAMIC = Limit::scene(
        "multibody.ste_dte.rpm[1]",
        "rpm",
        real(open(0.0), closed_e(1e5)).lie_in(""),
    );
    STE_DTE_SPEEDS = Limit::scene(
        "multibody.ste_dte.rpm[1]",
        "rpm",
        real(open_at("multibody.ste_dte.rpm[0]"), End::Unbounded).computed(),
    )
    .why("the quasi-static run is the slower");
    STE_DTE_ACCELERATION_END = Limit::scene(
        "multibody.ste_dte.acceleration_end_deg",
        "deg",
        real(open(0.0), closed(3600.0)).lie_in(""),
    );
    STE_DTE_TIME = within("multibody.ste_dte.time_s", "s", 1e-4, 100.0);
    STE_DTE_ACCELERATION_WITHIN = Limit::scene(
        "multibody.ste_dte.time_s",
        "s",
        real(
            open_derived("the acceleration's time, 2 `multibody.ste_dte.acceleration_end_deg` / ω of `multibody.ste_dte.rpm[1]`"),
            End::Unbounded,
        )
        .computed(),
    )
    .why("the acceleration ends within the run");
    STE_DTE_MAX_STEP = within("multibody.ste_dte.max_step_s", "s", 1e-8, 1.0);
    STE_DTE_TIME_STEPS = time_steps(
        "multibody.ste_dte.max_step_s",
        "time steps of each run, `multibody.ste_dte.time_s` / step",
    );
    STE_DTE_REVOLUTIONS = Limit::scene(
        "multibody.ste_dte.compared_revolutions",
        "revolutions",
        real(open(0.0), closed(100.0)).lie_in(""),
    );
    STE_DTE_COMPARED_WITHIN = Limit::scene(
        "multibody.ste_dte.compared_revolutions",
        "revolutions",
        real(
            End::Unbounded,
            closed_derived("the pinion revolutions the runs cover, (ω `multibody.ste_dte.time_s` − φₐ) / 2π"),
        )
        .computed(),
    )
    .why("only what was run is compared");
    STE_DTE_BLANK_ONCE = Limit::scene(
        "multibody.ste_dte.wheel_blanks[i]",
        "",
        words("each blank once"),
    )
    .why("its runs and files are named after it");
    STE_DTE_BLANK_IN_SCENE = Limit::scene(
        "multibody.ste_dte.wheel_blanks[i]",
        "",
        words("one of `blanks.wheel`"),
    )
    .why("a blank the scene does not analyse has no stiffness files to run on");
    LOAD_RUN_PINION_RPM = within("multibody.load_run.pinion_rpm", "rpm", 1e-3, 1e5);
    LOAD_RUN_PINION_RAMP = within("multibody.load_run.pinion_ramp_s", "s", 0.0, 100.0);
    LOAD_RUN_WHEEL_TORQUE = within("multibody.load_run.wheel_torque_nm", "N·m", 0.0, 1e7);
    LOAD_RUN_WHEEL_TORQUE_RISE =
        within("multibody.load_run.wheel_torque_rise_s", "s", 0.0, 100.0);
    LOAD_RUN_TIME = within("multibody.load_run.time_s", "s", 1e-4, 100.0);
    LOAD_RUN_MAX_STEP = within("multibody.load_run.max_step_s", "s", 1e-8, 1.0);
    LOAD_RUN_TIME_STEPS = time_steps(
        "multibody.load_run.max_step_s",
        "time steps, `multibody.load_run.time_s` / step",
    );
    LOAD_RUN_STEADY_FROM = within("multibody.load_run.steady_from_s", "s", 0.0, 100.0);
    LOAD_RUN_STEADY_WINDOW = Limit::scene(
        "multibody.load_run.steady_from_s",
        "s",
        real(End::Unbounded, open_at("multibody.load_run.time_s")).computed(),
    )
    .why("the steady window");
    LOAD_RUN_OUTPUT_INTERVAL = Limit::scene(
        "multibody.load_run.output_interval_s",
        "s",
        real(
            closed_at(1.0, "multibody.load_run.max_step_s", 0.0),
            closed_derived("half the steady window, (`multibody.load_run.time_s` − `multibody.load_run.steady_from_s`) / 2"),
        )
        .computed(),
    );
}
