//! The checks of a scene file, before any work: every number finite and in
//! range, names that become paths plain, and sizes bounded by what a run
//! can hold (with the estimate in the message). [`Scene::load`] runs them.

use crate::design::PairData;
use crate::error::InputError;
use crate::gear_body::Blank;
use crate::scene::{FlankElements, Scene};
use std::path::Path;

/// Largest number of positions of one sweep (per wheel blank) or of the
/// multibody contact table: each position holds the contact of every tooth
/// pair, so far more would not fit in memory.
pub const MAX_POSITIONS: f64 = 1e6;
/// Largest number of time steps of one multibody run (run time / largest step).
pub const MAX_TIME_STEPS: f64 = 1e7;
/// Most elements along the active profile × face width of a loaded flank at
/// any mesh level (the white paper's reference level: 35 × 75).
pub const MAX_FLANK_ELEMENTS: FlankElements = FlankElements {
    profile: 100,
    face: 200,
};
/// Most contact grid points of a stiffness file (grid_profile × grid_face).
pub const MAX_GRID_POINTS: usize = 2500;
/// Most pinion torques of one scene.
pub const MAX_TORQUES: usize = 100;
/// Largest pinion torque, N·m.
pub const MAX_TORQUE_NM: f64 = 1e6;
/// Fewest lag nodes of the multibody contact table: a third of them cover
/// the band of unloaded TEs, and with fewer than 16 (5 in the band, about
/// one node per half the unloaded TE's range) the interpolated pinion
/// torque there is so far off that the balance at the scene's torque lies
/// beyond the table's largest lag (8 nodes left no band spacing at all).
pub const MIN_TABLE_LAG_NODES: usize = 16;
/// Smallest local error tolerance of the multibody step control on the TE,
/// µrad: the lag is the difference r q₁ − q₂ of rotations of several rad,
/// resolved to about 1e-15 (1 + |q|) rad by Newton and rounding; tighter
/// tolerances only reject steps down to the smallest step.
pub const MIN_TE_TOLERANCE_URAD: f64 = 1e-6;

impl Scene {
    /// The checks that need no design: every number finite and in range,
    /// names that become paths plain, sizes bounded.
    pub fn check(&self, path: &Path) -> Result<(), InputError> {
        let ck = SceneCheck { path };
        crate::design_file::check_plain_name(path, "name", &self.name)?;
        if let Some(b) = &self.bearings {
            b.check(path)?;
        }
        if let Some(l) = &self.lumped {
            l.check(path)?;
        }
        self.check_rotation_and_utca(&ck)?;
        self.check_mesh_levels(&ck)?;
        self.check_marking_and_torques(&ck)?;
        self.check_stiffness(&ck)?;
        self.check_ltca(&ck)?;
        self.check_multibody_runs(&ck)?;
        self.check_multibody_rattle_and_laws(&ck)?;
        self.check_blanks(&ck)
    }

    /// `[rotation]` and `[utca]`: mesh cycles, steps and sample counts.
    fn check_rotation_and_utca(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let r = &self.rotation;
        for (f, v) in [
            ("rotation.mesh_cycles_standard", r.mesh_cycles_standard),
            (
                "rotation.mesh_cycles_lightweight",
                r.mesh_cycles_lightweight,
            ),
            ("utca.mesh_cycles", self.utca.mesh_cycles),
        ] {
            if !(v > 0.0 && v <= 100.0) {
                return Err(ck.fail(f, v.to_string(), "must lie in (0, 100]"));
            }
        }
        for (f, v) in [
            ("rotation.step_deg", r.step_deg),
            ("utca.step_deg", self.utca.step_deg),
        ] {
            if !(v > 0.0 && v <= 5.0) {
                return Err(ck.fail(f, v.to_string(), "must lie in (0, 5]"));
            }
        }
        for (f, v) in [
            ("utca.face_samples", self.utca.face_samples),
            ("utca.profile_samples", self.utca.profile_samples),
            ("utca.flank_grid_profile", self.utca.flank_grid_profile),
            ("utca.flank_grid_face", self.utca.flank_grid_face),
        ] {
            if !(5..=1000).contains(&v) {
                return Err(ck.fail(f, v.to_string(), "must lie in [5, 1000]"));
            }
        }
        Ok(())
    }

    /// `[mesh]`: the elements per loaded flank of every level.
    fn check_mesh_levels(&self, ck: &SceneCheck) -> Result<(), InputError> {
        for (f, e) in [
            ("mesh.reduced_order", self.mesh.reduced_order),
            ("mesh.reference", self.mesh.reference),
            ("mesh.medium", self.mesh.medium()),
        ] {
            for (k, v, hi) in [
                ("profile", e.profile, MAX_FLANK_ELEMENTS.profile),
                ("face", e.face, MAX_FLANK_ELEMENTS.face),
            ] {
                if !(1..=hi).contains(&v) {
                    return Err(ck.fail(
                        &format!("{f}.{k}"),
                        v.to_string(),
                        &format!(
                            "must lie in [1, {hi}] (elements per loaded flank at most {} × {}; the reference level of the white paper is 35 × 75)",
                            MAX_FLANK_ELEMENTS.profile, MAX_FLANK_ELEMENTS.face
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The marking compound's thickness and the pinion torques.
    fn check_marking_and_torques(&self, ck: &SceneCheck) -> Result<(), InputError> {
        if !(self.utca.marking_compound_um > 0.0 && self.utca.marking_compound_um < 100.0) {
            return Err(ck.fail(
                "utca.marking_compound_um",
                self.utca.marking_compound_um.to_string(),
                "must lie in (0, 100)",
            ));
        }
        if self.pinion_torque_nm.is_empty() || self.pinion_torque_nm.len() > MAX_TORQUES {
            return Err(ck.fail(
                "pinion_torque_nm",
                format!("{} values", self.pinion_torque_nm.len()),
                &format!("needs 1 to {MAX_TORQUES} torques (the loads analysed)"),
            ));
        }
        for (i, t) in self.pinion_torque_nm.iter().enumerate() {
            if !(t.is_finite() && *t > 0.0 && *t <= MAX_TORQUE_NM) {
                return Err(ck.fail(
                    &format!("pinion_torque_nm[{i}]"),
                    t.to_string(),
                    &format!("must lie in (0, {MAX_TORQUE_NM}] N·m"),
                ));
            }
        }
        // Each torque names a column of the TE tables and a result file
        // (`pattern_<T>nm`), and the reference FE and the LTCA warm-start
        // each load from the one before: the list is a strictly increasing
        // set of loads.
        if let Some(i) = (1..self.pinion_torque_nm.len())
            .find(|&i| self.pinion_torque_nm[i] <= self.pinion_torque_nm[i - 1])
        {
            let (a, b) = (self.pinion_torque_nm[i - 1], self.pinion_torque_nm[i]);
            return Err(ck.fail(
                &format!("pinion_torque_nm[{i}]"),
                b.to_string(),
                &if a == b {
                    format!("repeats pinion_torque_nm[{}] = {a}: each load once", i - 1)
                } else {
                    format!(
                        "must exceed pinion_torque_nm[{}] = {a}: list the loads in increasing order",
                        i - 1
                    )
                },
            ));
        }
        Ok(())
    }

    /// `[stiffness]`: grid, load radius, response teeth, solve block.
    fn check_stiffness(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let st = &self.stiffness;
        for (f, v) in [
            ("stiffness.grid_profile", st.grid_profile),
            ("stiffness.grid_face", st.grid_face),
        ] {
            if v != 0 && !(2..=200).contains(&v) {
                return Err(ck.fail(
                    f,
                    v.to_string(),
                    "must be 0 (mesh level) or lie in [2, 200]",
                ));
            }
        }
        let grid_points = st.grid_profile * st.grid_face;
        if grid_points > MAX_GRID_POINTS {
            return Err(ck.fail(
                "stiffness.grid_profile × stiffness.grid_face",
                format!("{} × {} = {grid_points}", st.grid_profile, st.grid_face),
                &format!(
                    "must be <= {MAX_GRID_POINTS} points (each compliance block holds points² values: {:.0} MB here)",
                    (grid_points * grid_points * 8) as f64 / 1e6
                ),
            ));
        }
        if !(st.load_radius_factor >= 0.25 && st.load_radius_factor <= 3.0) {
            return Err(ck.fail(
                "stiffness.load_radius_factor",
                st.load_radius_factor.to_string(),
                "must lie in [0.25, 3]",
            ));
        }
        if st.response_teeth > 5 {
            return Err(ck.fail(
                "stiffness.response_teeth",
                st.response_teeth.to_string(),
                "must be <= 5",
            ));
        }
        if !(1..=256).contains(&st.solve_block) {
            return Err(ck.fail(
                "stiffness.solve_block",
                st.solve_block.to_string(),
                "must lie in [1, 256]",
            ));
        }
        Ok(())
    }

    /// `[ltca]`: friction coefficient and slices.
    fn check_ltca(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let mu = self.ltca.friction_coefficient;
        if !(0.0..=0.5).contains(&mu) {
            return Err(ck.fail(
                "ltca.friction_coefficient",
                mu.to_string(),
                "must lie in [0, 0.5]",
            ));
        }
        if !(4..=400).contains(&self.ltca.slices) {
            return Err(ck.fail(
                "ltca.slices",
                self.ltca.slices.to_string(),
                "must lie in [4, 400]",
            ));
        }
        Ok(())
    }

    /// `[multibody]`: the quasi-static and run-up runs, the table and the
    /// inertias.
    fn check_multibody_runs(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let mb = &self.multibody;
        for (f, v, lo, hi) in [
            (
                "multibody.quasi_static_wheel_rpm",
                mb.quasi_static_wheel_rpm,
                1e-3,
                1e4,
            ),
            (
                "multibody.quasi_static_max_step_s",
                mb.quasi_static_max_step_s,
                1e-8,
                1.0,
            ),
            ("multibody.runup_time_s", mb.runup_time_s, 1e-4, 100.0),
            (
                "multibody.runup_pinion_torque_nm",
                mb.runup_pinion_torque_nm,
                0.0,
                1e6,
            ),
            ("multibody.runup_max_step_s", mb.runup_max_step_s, 1e-8, 1.0),
            ("multibody.damping_ratio", mb.damping_ratio, 0.0, 10.0),
            ("multibody.rho_inf", mb.rho_inf, 0.0, 1.0),
            (
                "multibody.te_tolerance_urad",
                mb.te_tolerance_urad,
                MIN_TE_TOLERANCE_URAD,
                100.0,
            ),
            ("multibody.table_step_deg", mb.table_step_deg, 1e-3, 2.0),
            (
                "multibody.table_torque_factor",
                mb.table_torque_factor,
                1.0,
                100.0,
            ),
        ] {
            if !(v >= lo && v <= hi) {
                return Err(ck.fail(f, v.to_string(), &format!("must lie in [{lo}, {hi}]")));
            }
        }
        for (f, v) in [
            ("multibody.runup_rpm[0]", mb.runup_rpm[0]),
            ("multibody.runup_rpm[1]", mb.runup_rpm[1]),
        ] {
            if !(0.0..=1e5).contains(&v) {
                return Err(ck.fail(f, v.to_string(), "must lie in [0, 100000]"));
            }
        }
        if !(MIN_TABLE_LAG_NODES..=2000).contains(&mb.table_lag_nodes) {
            return Err(ck.fail(
                "multibody.table_lag_nodes",
                mb.table_lag_nodes.to_string(),
                &format!(
                    "must lie in [{MIN_TABLE_LAG_NODES}, 2000] (a third of the nodes resolve the band of unloaded TEs; fewer than {MIN_TABLE_LAG_NODES} put the loaded balance beyond the table)"
                ),
            ));
        }
        for (f, v) in [
            ("multibody.pinion_inertia_kgm2", mb.pinion_inertia_kgm2),
            ("multibody.wheel_inertia_kgm2", mb.wheel_inertia_kgm2),
        ] {
            if let Some(j) = v {
                if !(j > 0.0 && j.is_finite()) {
                    return Err(ck.fail(f, j.to_string(), "must be finite and > 0"));
                }
            }
        }
        Ok(())
    }

    /// `[multibody]`: the rattle run, the impact law, the load run, and
    /// rattle only with coast contact.
    fn check_multibody_rattle_and_laws(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let mb = &self.multibody;
        for (f, v, lo, hi) in [
            (
                "multibody.rattle_pinion_rpm",
                mb.rattle_pinion_rpm,
                0.0,
                1e5,
            ),
            (
                "multibody.rattle_speed_fluctuation",
                mb.rattle_speed_fluctuation,
                0.0,
                1.0,
            ),
            (
                "multibody.rattle_frequency_hz",
                mb.rattle_frequency_hz,
                0.0,
                1e5,
            ),
            (
                "multibody.rattle_wheel_drag_nm",
                mb.rattle_wheel_drag_nm,
                0.0,
                1e4,
            ),
            ("multibody.rattle_time_s", mb.rattle_time_s, 0.0, 100.0),
            (
                "multibody.rattle_max_step_s",
                mb.rattle_max_step_s,
                1e-8,
                1.0,
            ),
        ] {
            if !(v >= lo && v <= hi) {
                return Err(ck.fail(f, v.to_string(), &format!("must lie in [{lo}, {hi}]")));
            }
        }
        if mb.force_law == crate::scene::ForceLaw::Impact {
            mb.impact.check(ck.path, mb.coast_contact)?;
        }
        if let Some(run) = &mb.load_run {
            run.check(ck.path)?;
        }
        if mb.rattle_time_s > 0.0 && !mb.coast_contact {
            return Err(ck.fail(
                "multibody.rattle_time_s",
                mb.rattle_time_s.to_string(),
                "must be 0 unless multibody.coast_contact = true (rattle needs both flanks)",
            ));
        }
        Ok(())
    }

    /// `[blank_dimensions]` and `[blanks]`.
    fn check_blanks(&self, ck: &SceneCheck) -> Result<(), InputError> {
        let bd = &self.blank_dimensions;
        for (f, v) in [
            ("pinion_bore_radius_mm", bd.pinion_bore_radius_mm),
            ("pinion_rim_depth_mm", bd.pinion_rim_depth_mm),
            ("pinion_shaft_length_mm", bd.pinion_shaft_length_mm),
            ("wheel_bore_radius_mm", bd.wheel_bore_radius_mm),
            ("wheel_hub_radius_mm", bd.wheel_hub_radius_mm),
            ("wheel_rim_depth_mm", bd.wheel_rim_depth_mm),
            ("wheel_web_thickness_mm", bd.wheel_web_thickness_mm),
            (
                "wheel_lightweight_web_thickness_mm",
                bd.wheel_lightweight_web_thickness_mm,
            ),
            ("wheel_hole_diameter_mm", bd.wheel_hole_diameter_mm),
        ] {
            if let Some(v) = v {
                let hi = crate::design_file::MAX_CONE_DISTANCE_MM;
                if !(v.is_finite() && v > 0.0 && v <= hi) {
                    return Err(ck.fail(
                        &format!("blank_dimensions.{f}"),
                        v.to_string(),
                        &format!("must lie in (0, {hi}] mm"),
                    ));
                }
            }
        }
        if self.blanks.pinion.is_empty() || self.blanks.wheel.is_empty() {
            return Err(ck.fail(
                "blanks",
                "[]".into(),
                "each member needs at least one blank",
            ));
        }
        for (field, list) in [
            ("blanks.pinion", &self.blanks.pinion),
            ("blanks.wheel", &self.blanks.wheel),
            (
                "multibody.runup_wheel_blanks",
                &self.multibody.runup_wheel_blanks,
            ),
        ] {
            if let Some(i) = (1..list.len()).find(|&i| list[..i].contains(&list[i])) {
                return Err(ck.fail(
                    &format!("{field}[{i}]"),
                    format!("\"{}\"", list[i].name()),
                    "names a blank listed before it: each blank once (its runs and files are named after it)",
                ));
            }
        }
        Ok(())
    }

    /// The checks that need the design: the number of positions the sweeps
    /// and the multibody runs allocate, estimated from the mesh cycle.
    pub fn check_sizes(&self, path: &Path, pair: &PairData) -> Result<(), InputError> {
        let fail = |field: &str, value: f64, limit: String| InputError::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            value: value.to_string(),
            limit,
        };
        self.misalignment.check(path, "misalignment", pair)?;
        // A written [sensitivity] table is checked here; the defaults only
        // when the study runs (`solver sensitivity`).
        if let Some(s) = &self.sensitivity {
            s.check(path, &self.misalignment, pair)?;
        }
        let cycle_deg = pair.mesh_cycle().to_degrees();
        let positions = |cycles: f64, step_deg: f64| cycles * cycle_deg / step_deg + 1.0;
        let r = &self.rotation;
        let mut sweeps: Vec<(&str, f64, &str, f64)> = self
            .blanks
            .wheel
            .iter()
            .map(|&wb| {
                let cycles = match wb {
                    Blank::Standard => "rotation.mesh_cycles_standard",
                    Blank::Lightweight => "rotation.mesh_cycles_lightweight",
                };
                ("rotation.step_deg", r.step_deg, cycles, r.mesh_cycles(wb))
            })
            .collect();
        sweeps.push((
            "utca.step_deg",
            self.utca.step_deg,
            "utca.mesh_cycles",
            self.utca.mesh_cycles,
        ));
        for (f, step, cycles_field, cycles) in sweeps {
            let n = positions(cycles, step);
            if n > MAX_POSITIONS {
                return Err(fail(
                    f,
                    step,
                    format!(
                        "too small: {cycles_field} = {cycles} mesh cycles of {cycle_deg:.4}° in steps of {step}° make {n:.3e} positions per blank, at most {MAX_POSITIONS:.0e} are allowed (step >= {:.3e}°)",
                        cycles * cycle_deg / (MAX_POSITIONS - 1.0)
                    ),
                ));
            }
        }
        if self.analyses.multibody {
            let mb = &self.multibody;
            let tau = pair.mesh_cycle();
            let mut rotation: f64 = self
                .blanks
                .wheel
                .iter()
                .map(|&wb| r.mesh_cycles(wb) * tau)
                .fold(0.0, f64::max);
            let runs_up = self
                .blanks
                .wheel
                .iter()
                .any(|wb| mb.runup_wheel_blanks.contains(wb));
            if runs_up {
                rotation = rotation.max(mb.runup_rotation());
            }
            if mb.coast_contact && mb.rattle_time_s > 0.0 {
                rotation = rotation.max(mb.rattle_rotation());
            }
            if let Some(run) = &mb.load_run {
                rotation = rotation.max(run.rotation());
            }
            let n = rotation / mb.table_step_deg.to_radians() + 1.0;
            if n > MAX_POSITIONS {
                return Err(fail(
                    "multibody.table_step_deg",
                    mb.table_step_deg,
                    format!(
                        "too small for the {:.1}° of pinion rotation the runs cover: {n:.3e} table positions, at most {MAX_POSITIONS:.0e} are allowed",
                        rotation.to_degrees()
                    ),
                ));
            }
            let wheel_speed = mb.quasi_static_wheel_rpm * std::f64::consts::PI / 30.0;
            let pinion_speed =
                wheel_speed * pair.members[1].teeth as f64 / pair.members[0].teeth as f64;
            let qs_cycles = self
                .blanks
                .wheel
                .iter()
                .map(|&wb| r.mesh_cycles(wb))
                .fold(0.0, f64::max);
            let mut runs = vec![
                (
                    "multibody.quasi_static_max_step_s",
                    mb.quasi_static_max_step_s,
                    qs_cycles * tau / pinion_speed,
                ),
                (
                    "multibody.runup_max_step_s",
                    mb.runup_max_step_s,
                    if runs_up { mb.runup_time_s } else { 0.0 },
                ),
            ];
            if mb.coast_contact && mb.rattle_time_s > 0.0 {
                runs.push((
                    "multibody.rattle_max_step_s",
                    mb.rattle_max_step_s,
                    mb.rattle_time_s,
                ));
            }
            for (f, step, time) in runs {
                let n = time / step;
                if n > MAX_TIME_STEPS {
                    return Err(fail(
                        f,
                        step,
                        format!(
                            "too small for a run of {time:.4} s: at least {n:.3e} time steps, at most {MAX_TIME_STEPS:.0e} are allowed"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The checks' error for a field of the scene at `path`.
struct SceneCheck<'a> {
    path: &'a Path,
}

impl SceneCheck<'_> {
    /// `field` = `value` outside `limit`.
    fn fail(&self, field: &str, value: String, limit: &str) -> InputError {
        InputError::Invalid {
            path: self.path.to_path_buf(),
            field: field.into(),
            value,
            limit: limit.into(),
        }
    }
}
