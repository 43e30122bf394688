//! Scene settings of the multibody's force law (`[multibody] force_law`,
//! `[multibody.impact]`) and of the imposed-speed load run
//! (`[multibody.load_run]`, the drives of seeds 001 and 002), with their
//! checks.

use crate::error::InputError;
use crate::limits::multibody as mbl;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The multibody's contact force law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum ForceLaw {
    /// The FE-analytical contact element (stiffness files + Weber–Banaschek).
    #[default]
    Element,
    /// The impact function F = max(0, K δ^e + C δ̇ STEP(δ, 0, 0, d, 1)) per
    /// tooth pair on the rigid flanks' penetration, with ADAMS-style friction.
    Impact,
}

/// Parameters of the impact law in the seeds' mm-based units.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ImpactSettings {
    /// K, N/mm^e; absent: Hertz point contact 4/3 √R E* (N/mm^1.5) with R
    /// from the outer pitch radii and E* from both members' materials, as
    /// the seeds compute it.
    pub stiffness_n_per_mm_e: Option<f64>,
    /// Force exponent e.
    pub exponent: f64,
    /// C, N·s/mm, reached at the penetration depth d (mm).
    pub damping_n_s_per_mm: f64,
    pub penetration_depth_mm: f64,
    /// Static and dynamic friction coefficients (0: frictionless).
    pub static_friction: f64,
    pub dynamic_friction: f64,
    /// Stiction and friction transition slip speeds, mm/s (ADAMS defaults).
    pub stiction_speed_mm_s: f64,
    pub friction_transition_speed_mm_s: f64,
    /// Shape of the damping's ramp over the penetration depth: ADAMS's
    /// cubic STEP (default) or the haversine step seed 001 names.
    pub damping_step: StepShape,
}

/// Shape of a smooth step from h₀ to h₁ over [x₀, x₁].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StepShape {
    /// ADAMS's STEP: h₀ + (h₁ − h₀) Δ² (3 − 2Δ).
    #[default]
    Cubic,
    /// h₀ + (h₁ − h₀) (1 − cos πΔ)/2.
    Haversine,
}

impl StepShape {
    pub fn name(self) -> &'static str {
        match self {
            StepShape::Cubic => "cubic",
            StepShape::Haversine => "haversine",
        }
    }
}

impl Default for ImpactSettings {
    fn default() -> Self {
        ImpactSettings {
            stiffness_n_per_mm_e: None,
            exponent: 1.5,
            damping_n_s_per_mm: 0.0,
            penetration_depth_mm: 0.1,
            static_friction: 0.0,
            dynamic_friction: 0.0,
            stiction_speed_mm_s: 100.0,
            friction_transition_speed_mm_s: 1000.0,
            damping_step: StepShape::Cubic,
        }
    }
}

/// A run with imposed pinion speed and a resisting wheel torque, as seeds
/// 001 and 002 drive their pairs: the pinion's speed ramps linearly from 0
/// to `pinion_rpm` over `pinion_ramp_s` (0: at speed from the start), the
/// wheel torque rises from 0 to `wheel_torque_nm` over
/// `wheel_torque_rise_s` by the cubic STEP (0: at full torque from the
/// start); `time_s` simulated with steps up to `max_step_s`; the means and
/// fluctuations are taken from `steady_from_s` on. With
/// `output_interval_s` the statistics are also given from samples at that
/// interval (a simulation that writes its results only so often sees
/// those), beside the ones from every step.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LoadRun {
    pub pinion_rpm: f64,
    pub pinion_ramp_s: f64,
    pub wheel_torque_nm: f64,
    pub wheel_torque_rise_s: f64,
    pub time_s: f64,
    pub max_step_s: f64,
    pub steady_from_s: f64,
    #[serde(default)]
    pub output_interval_s: Option<f64>,
}

impl LoadRun {
    /// Pinion rotation of the run, rad.
    pub fn rotation(&self) -> f64 {
        let w = self.pinion_rpm * std::f64::consts::PI / 30.0;
        w * (self.time_s - 0.5 * self.pinion_ramp_s.min(self.time_s))
    }

    /// Range checks naming field, value and limit.
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        for (l, v) in [
            (&mbl::LOAD_RUN_PINION_RPM, self.pinion_rpm),
            (&mbl::LOAD_RUN_PINION_RAMP, self.pinion_ramp_s),
            (&mbl::LOAD_RUN_WHEEL_TORQUE, self.wheel_torque_nm),
            (&mbl::LOAD_RUN_WHEEL_TORQUE_RISE, self.wheel_torque_rise_s),
            (&mbl::LOAD_RUN_TIME, self.time_s),
            (&mbl::LOAD_RUN_MAX_STEP, self.max_step_s),
            (&mbl::LOAD_RUN_STEADY_FROM, self.steady_from_s),
        ] {
            l.check(path, v)?;
        }
        let l = &mbl::LOAD_RUN_STEADY_WINDOW;
        l.check_with(path, l.field, self.steady_from_s, &[self.time_s], || {
            format!(
                "must be below multibody.load_run.time_s = {} (the steady window)",
                self.time_s
            )
        })?;
        if let Some(dt) = self.output_interval_s {
            let hi = 0.5 * (self.time_s - self.steady_from_s);
            let l = &mbl::LOAD_RUN_OUTPUT_INTERVAL;
            l.check_with(path, l.field, dt, &[self.max_step_s, hi], || {
                format!(
                    "must lie in [max_step_s = {}, half the steady window = {hi}] s",
                    self.max_step_s
                )
            })?;
        }
        mbl::LOAD_RUN_TIME_STEPS.check_time_steps(path, self.time_s, self.max_step_s)?;
        Ok(())
    }
}

impl ImpactSettings {
    /// Range checks naming field, value and limit; `coast_contact` must be
    /// off with this law (it carries the drive flanks only).
    pub fn check(&self, path: &Path, coast_contact: bool) -> Result<(), InputError> {
        if let Some(k) = self.stiffness_n_per_mm_e {
            mbl::IMPACT_STIFFNESS.check(path, k)?;
        }
        for (l, v) in [
            (&mbl::IMPACT_EXPONENT, self.exponent),
            (&mbl::IMPACT_DAMPING, self.damping_n_s_per_mm),
            (&mbl::IMPACT_STATIC_FRICTION, self.static_friction),
            (&mbl::IMPACT_DYNAMIC_FRICTION, self.dynamic_friction),
            (&mbl::IMPACT_PENETRATION_DEPTH, self.penetration_depth_mm),
            (&mbl::IMPACT_STICTION_SPEED, self.stiction_speed_mm_s),
        ] {
            l.check(path, v)?;
        }
        let l = &mbl::IMPACT_TRANSITION_SPEED;
        l.check_with(
            path,
            l.field,
            self.friction_transition_speed_mm_s,
            &[self.stiction_speed_mm_s],
            || {
                format!(
                    "must lie in (multibody.impact.stiction_speed_mm_s = {}, 1e6]",
                    self.stiction_speed_mm_s
                )
            },
        )?;
        if coast_contact {
            let l = &mbl::IMPACT_LAW;
            return Err(l.refuse(
                path,
                l.field,
                "impact".into(),
                "needs multibody.coast_contact = false (the impact law's table carries the drive flanks only)".into(),
            ));
        }
        Ok(())
    }
}
