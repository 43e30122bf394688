//! `[multibody.ste_dte]`: the white paper's first use case, the static
//! against the dynamic transmission error. The pinion is run up twice on
//! the same model, once slowly (quasi-static TE, STE) and once fast
//! (dynamic TE, DTE), each accelerating from rest to its speed within the
//! same pinion rotation and holding it; both are compared in the pinion's
//! angle domain.

use crate::error::InputError;
use crate::limits::multibody as mbl;
use crate::scene::Blank;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use std::path::Path;

/// The two run-ups of the STE/DTE comparison.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SteDte {
    /// Wheel blanks compared (each with the scene's pinion blanks).
    pub wheel_blanks: Vec<Blank>,
    /// Pinion torque, resisted at the wheel through the ratio, N·m.
    pub pinion_torque_nm: f64,
    /// Pinion speeds of the quasi-static and of the dynamic run, rpm.
    pub rpm: [f64; 2],
    /// Pinion rotation at which both runs end their (constant)
    /// acceleration from rest, deg.
    pub acceleration_end_deg: f64,
    /// Simulated time of the dynamic run, s; the quasi-static run covers
    /// the same pinion rotation (its time scaled by the speed ratio).
    pub time_s: f64,
    /// Largest time step of the dynamic run, s; the quasi-static run's is
    /// scaled by the speed ratio (the same steps in the angle domain).
    pub max_step_s: f64,
    /// Pinion revolutions from rest over which STE and DTE are compared.
    pub compared_revolutions: f64,
}

/// rpm → rad/s.
pub fn rad_per_s(rpm: f64) -> f64 {
    rpm * PI / 30.0
}

impl SteDte {
    /// Time to reach `rpm` from rest with the acceleration ending at
    /// `acceleration_end_deg`: φ_a = ω t_a / 2, so t_a = 2 φ_a / ω, s.
    pub fn acceleration_time_s(&self, rpm: f64) -> f64 {
        2.0 * self.acceleration_end_deg.to_radians() / rad_per_s(rpm)
    }

    /// Time scale of the quasi-static run against the dynamic one,
    /// ω_dynamic / ω_quasi-static.
    pub fn time_scale(&self) -> f64 {
        self.rpm[1] / self.rpm[0]
    }

    /// Pinion rotation of either run, rad: ω (t − t_a) + φ_a with
    /// t_a = 2 φ_a / ω, that is ω t − φ_a (t ≥ t_a).
    pub fn rotation(&self) -> f64 {
        rad_per_s(self.rpm[1]) * self.time_s - self.acceleration_end_deg.to_radians()
    }

    /// Range checks naming field, value and limit.
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        for (l, v) in [
            (&mbl::STE_DTE_TORQUE, self.pinion_torque_nm),
            (&mbl::STE_DTE_RPM_QUASI_STATIC, self.rpm[0]),
            (&mbl::STE_DTE_RPM_DYNAMIC, self.rpm[1]),
            (&mbl::STE_DTE_ACCELERATION_END, self.acceleration_end_deg),
            (&mbl::STE_DTE_TIME, self.time_s),
            (&mbl::STE_DTE_MAX_STEP, self.max_step_s),
            (&mbl::STE_DTE_REVOLUTIONS, self.compared_revolutions),
        ] {
            l.check(path, v)?;
        }
        let l = &mbl::STE_DTE_SPEEDS;
        l.check_with(path, l.field, self.rpm[1], &[self.rpm[0]], || {
            format!(
                "must be above multibody.ste_dte.rpm[0] = {} (the quasi-static run is the slower)",
                self.rpm[0]
            )
        })?;
        let t_a = self.acceleration_time_s(self.rpm[1]);
        let l = &mbl::STE_DTE_ACCELERATION_WITHIN;
        l.check_with(path, l.field, self.time_s, &[t_a], || {
            format!(
                "must exceed the {t_a:.4e} s the dynamic run takes to reach {} rpm at {}° (the acceleration ends within the run)",
                self.rpm[1], self.acceleration_end_deg
            )
        })?;
        let turns = self.rotation() / (2.0 * PI);
        let l = &mbl::STE_DTE_COMPARED_WITHIN;
        l.check_with(path, l.field, self.compared_revolutions, &[turns], || {
            format!(
                "must be at most the {turns:.4} pinion revolutions the runs cover (multibody.ste_dte.time_s at multibody.ste_dte.rpm[1])"
            )
        })?;
        mbl::STE_DTE_TIME_STEPS.check_time_steps(path, self.time_s, self.max_step_s)?;
        if let Some(i) = (1..self.wheel_blanks.len())
            .find(|&i| self.wheel_blanks[..i].contains(&self.wheel_blanks[i]))
        {
            let l = &mbl::STE_DTE_BLANK_ONCE;
            return Err(l.refuse(
                path,
                &format!("multibody.ste_dte.wheel_blanks[{i}]"),
                format!("\"{}\"", self.wheel_blanks[i].name()),
                "names a blank listed before it: each blank once (its runs and files are named after it)".into(),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper() -> SteDte {
        SteDte {
            wheel_blanks: vec![Blank::Lightweight],
            pinion_torque_nm: 300.0,
            rpm: [10.0, 1000.0],
            acceleration_end_deg: 30.0,
            time_s: 0.15,
            max_step_s: 1e-5,
            compared_revolutions: 1.0,
        }
    }

    #[test]
    fn constant_acceleration_to_1000_rpm_within_30_degrees_takes_10_ms() {
        // φ = ω t / 2 at the end of a constant acceleration from rest.
        let s = paper();
        let t_a = s.acceleration_time_s(1000.0);
        assert!((t_a - 0.01).abs() < 1e-15, "{t_a}");
        assert!((0.5 * rad_per_s(1000.0) * t_a - 30f64.to_radians()).abs() < 1e-15);
        // The quasi-static run's takes the speed ratio longer.
        assert!((s.acceleration_time_s(10.0) / t_a - s.time_scale()).abs() < 1e-12);
    }

    #[test]
    fn the_paper_run_turns_the_pinion_2_42_revolutions() {
        // 30° + (0.15 − 0.01) s × 1000 rpm = 30° + 840°.
        let turns = paper().rotation().to_degrees() / 360.0;
        assert!((turns - 870.0 / 360.0).abs() < 1e-12, "{turns}");
    }

    #[test]
    fn out_of_range_entries_are_refused_naming_the_field() {
        let p = Path::new("scene.toml");
        assert!(paper().check(p).is_ok());
        let refused = |s: SteDte, field: &str| {
            let e = s.check(p).expect_err(field).to_string();
            assert!(e.contains(field), "{e}");
        };
        refused(
            SteDte {
                rpm: [10.0, 5.0],
                ..paper()
            },
            "multibody.ste_dte.rpm[1]",
        );
        refused(
            SteDte {
                time_s: 0.005,
                ..paper()
            },
            "multibody.ste_dte.time_s",
        );
        refused(
            SteDte {
                compared_revolutions: 3.0,
                ..paper()
            },
            "multibody.ste_dte.compared_revolutions",
        );
        refused(
            SteDte {
                max_step_s: 1e-12,
                ..paper()
            },
            "multibody.ste_dte.max_step_s",
        );
        refused(
            SteDte {
                wheel_blanks: vec![Blank::Standard, Blank::Standard],
                ..paper()
            },
            "multibody.ste_dte.wheel_blanks[1]",
        );
        refused(
            SteDte {
                acceleration_end_deg: 0.0,
                ..paper()
            },
            "multibody.ste_dte.acceleration_end_deg",
        );
    }
}
