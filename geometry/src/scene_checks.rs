//! The checks of a scene file, before any work: every number finite and in
//! range, names that become paths plain, and sizes bounded by what a run
//! can hold (with the estimate in the message). [`Scene::load`] runs them.
//! Each limit is an entry of [`crate::limits`], which the checks test
//! values against and refuse with.

use crate::design::PairData;
use crate::error::InputError;
use crate::gear_body::Blank;
use crate::limits::{multibody as mbl, scene as lim, Limit};
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
/// Most entries of a `[lumped]` list that starts a run per entry (extra
/// torques, roughness grades, order-map speeds, design variants): as many
/// as the scene's torques may be.
pub const MAX_LIST_RUNS: usize = 100;
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
        crate::design_file::check_plain_name(path, lim::NAME.field, &self.name)?;
        if let Some(b) = &self.bearings {
            b.check(path)?;
        }
        if let Some(l) = &self.lumped {
            l.check(path)?;
        }
        self.check_rotation_and_utca(path)?;
        self.check_mesh_levels(path)?;
        self.check_marking_and_torques(path)?;
        self.check_stiffness(path)?;
        self.check_ltca(path)?;
        self.check_multibody_runs(path)?;
        self.check_multibody_rattle_and_laws(path)?;
        self.check_blanks(path)
    }

    /// `[rotation]` and `[utca]`: mesh cycles, steps and sample counts.
    fn check_rotation_and_utca(&self, path: &Path) -> Result<(), InputError> {
        let (r, u) = (&self.rotation, &self.utca);
        for (l, v) in [
            (&lim::MESH_CYCLES_STANDARD, r.mesh_cycles_standard),
            (&lim::MESH_CYCLES_LIGHTWEIGHT, r.mesh_cycles_lightweight),
            (&lim::UTCA_MESH_CYCLES, u.mesh_cycles),
            (&lim::ROTATION_STEP, r.step_deg),
            (&lim::UTCA_STEP, u.step_deg),
        ] {
            l.check(path, v)?;
        }
        for (l, v) in [
            (&lim::FACE_SAMPLES, u.face_samples),
            (&lim::PROFILE_SAMPLES, u.profile_samples),
            (&lim::FLANK_GRID_PROFILE, u.flank_grid_profile),
            (&lim::FLANK_GRID_FACE, u.flank_grid_face),
        ] {
            l.check_integer(path, l.field, v)?;
        }
        Ok(())
    }

    /// `[mesh]`: the elements per loaded flank of every level.
    fn check_mesh_levels(&self, path: &Path) -> Result<(), InputError> {
        for (f, e) in [
            ("mesh.reduced_order", self.mesh.reduced_order),
            ("mesh.reference", self.mesh.reference),
            ("mesh.medium", self.mesh.medium()),
        ] {
            for (l, k, v, hi) in [
                (
                    &lim::MESH_PROFILE,
                    "profile",
                    e.profile,
                    MAX_FLANK_ELEMENTS.profile,
                ),
                (&lim::MESH_FACE, "face", e.face, MAX_FLANK_ELEMENTS.face),
            ] {
                l.check_with(path, &format!("{f}.{k}"), v as f64, &[], || {
                    format!(
                        "must lie in [1, {hi}] (elements per loaded flank at most {} × {}; the reference level of the white paper is 35 × 75)",
                        MAX_FLANK_ELEMENTS.profile, MAX_FLANK_ELEMENTS.face
                    )
                })?;
            }
        }
        Ok(())
    }

    /// The marking compound's thickness and the pinion torques.
    fn check_marking_and_torques(&self, path: &Path) -> Result<(), InputError> {
        lim::MARKING_COMPOUND.check(path, self.utca.marking_compound_um)?;
        let torques = &self.pinion_torque_nm;
        let l = &lim::TORQUE_COUNT;
        if !l.admits(torques.len() as f64, &[]) {
            return Err(l.refuse(
                path,
                l.field,
                format!("{} values", torques.len()),
                l.text_of_refusal(),
            ));
        }
        for (i, t) in torques.iter().enumerate() {
            lim::TORQUE.check_at(path, &format!("pinion_torque_nm[{i}]"), *t)?;
        }
        // Each torque names a column of the TE tables and a result file
        // (`pattern_<T>nm`), and the reference FE and the LTCA warm-start
        // each load from the one before: the list is a strictly increasing
        // set of loads.
        if let Some(i) = (1..torques.len()).find(|&i| torques[i] <= torques[i - 1]) {
            let (a, b) = (torques[i - 1], torques[i]);
            return Err(lim::TORQUE_ORDER.refuse(
                path,
                &format!("pinion_torque_nm[{i}]"),
                b.to_string(),
                if a == b {
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
    fn check_stiffness(&self, path: &Path) -> Result<(), InputError> {
        let st = &self.stiffness;
        for (l, v) in [
            (&lim::GRID_PROFILE, st.grid_profile),
            (&lim::GRID_FACE, st.grid_face),
        ] {
            l.check_integer(path, l.field, v)?;
        }
        // 0 takes the reduced-order mesh level's elements (as the
        // stiffness plan does).
        let own = |v: usize, mesh: u32| if v == 0 { mesh as usize } else { v };
        let (gp, gf) = (
            own(st.grid_profile, self.mesh.reduced_order.profile),
            own(st.grid_face, self.mesh.reduced_order.face),
        );
        let grid_points = gp * gf;
        let l = &lim::GRID_POINTS;
        if !l.admits(grid_points as f64, &[]) {
            return Err(l.refuse(
                path,
                l.field,
                format!("{gp} × {gf} = {grid_points}"),
                format!(
                    "must be <= {MAX_GRID_POINTS} points (each compliance block holds points² values: {:.0} MB here)",
                    (grid_points * grid_points * 8) as f64 / 1e6
                ),
            ));
        }
        lim::LOAD_RADIUS.check(path, st.load_radius_factor)?;
        lim::RESPONSE_TEETH.check_integer(path, lim::RESPONSE_TEETH.field, st.response_teeth)?;
        lim::SOLVE_BLOCK.check_integer(path, lim::SOLVE_BLOCK.field, st.solve_block)
    }

    /// `[ltca]`: friction coefficient and slices.
    fn check_ltca(&self, path: &Path) -> Result<(), InputError> {
        lim::FRICTION.check(path, self.ltca.friction_coefficient)?;
        lim::SLICES.check_integer(path, lim::SLICES.field, self.ltca.slices)
    }

    /// `[multibody]`: the quasi-static and run-up runs, the table and the
    /// inertias.
    fn check_multibody_runs(&self, path: &Path) -> Result<(), InputError> {
        let mb = &self.multibody;
        for (l, v) in [
            (&mbl::QUASI_STATIC_WHEEL_RPM, mb.quasi_static_wheel_rpm),
            (&mbl::QUASI_STATIC_MAX_STEP, mb.quasi_static_max_step_s),
            (&mbl::RUNUP_TIME, mb.runup_time_s),
            (&mbl::RUNUP_PINION_TORQUE, mb.runup_pinion_torque_nm),
            (&mbl::RUNUP_MAX_STEP, mb.runup_max_step_s),
            (&mbl::DAMPING_RATIO, mb.damping_ratio),
            (&mbl::RHO_INF, mb.rho_inf),
            (&mbl::TE_TOLERANCE, mb.te_tolerance_urad),
            (&mbl::TABLE_STEP, mb.table_step_deg),
            (&mbl::TABLE_TORQUE_FACTOR, mb.table_torque_factor),
            (&mbl::RUNUP_RPM_START, mb.runup_rpm[0]),
            (&mbl::RUNUP_RPM_END, mb.runup_rpm[1]),
        ] {
            l.check(path, v)?;
        }
        let l = &mbl::TABLE_LAG_NODES;
        if !l.admits(mb.table_lag_nodes as f64, &[]) {
            return Err(l.refuse(
                path,
                l.field,
                mb.table_lag_nodes.to_string(),
                format!(
                    "must lie in [{MIN_TABLE_LAG_NODES}, 2000] (a third of the nodes resolve the band of unloaded TEs; fewer than {MIN_TABLE_LAG_NODES} put the loaded balance beyond the table)"
                ),
            ));
        }
        for (l, v) in [
            (&mbl::PINION_INERTIA, mb.pinion_inertia_kgm2),
            (&mbl::WHEEL_INERTIA, mb.wheel_inertia_kgm2),
        ] {
            if let Some(j) = v {
                l.check(path, j)?;
            }
        }
        Ok(())
    }

    /// `[multibody]`: the rattle run, the impact law, the load run, and
    /// rattle only with coast contact.
    fn check_multibody_rattle_and_laws(&self, path: &Path) -> Result<(), InputError> {
        let mb = &self.multibody;
        for (l, v) in [
            (&mbl::RATTLE_PINION_RPM, mb.rattle_pinion_rpm),
            (&mbl::RATTLE_SPEED_FLUCTUATION, mb.rattle_speed_fluctuation),
            (&mbl::RATTLE_FREQUENCY, mb.rattle_frequency_hz),
            (&mbl::RATTLE_WHEEL_DRAG, mb.rattle_wheel_drag_nm),
            (&mbl::RATTLE_TIME, mb.rattle_time_s),
            (&mbl::RATTLE_MAX_STEP, mb.rattle_max_step_s),
        ] {
            l.check(path, v)?;
        }
        if mb.force_law == crate::scene::ForceLaw::Impact {
            mb.impact.check(path, mb.coast_contact)?;
        }
        if let Some(run) = &mb.load_run {
            run.check(path)?;
        }
        if let Some(sd) = &mb.ste_dte {
            sd.check(path)?;
            self.analysed_wheel_blanks(
                path,
                &mbl::STE_DTE_BLANK_IN_SCENE,
                "multibody.ste_dte.wheel_blanks",
                &sd.wheel_blanks,
            )?;
        }
        if mb.root_stress
            && (mb.force_law != crate::scene::ForceLaw::Element || !self.stiffness.root_stress)
        {
            let l = &mbl::ROOT_STRESS_NEEDS_COEFFICIENTS;
            return Err(l.refuse(
                path,
                l.field,
                "true".into(),
                "must be false unless multibody.force_law = \"element\" and stiffness.root_stress = true".into(),
            ));
        }
        if mb.rattle_time_s > 0.0 && !mb.coast_contact {
            let l = &mbl::RATTLE_NEEDS_COAST;
            return Err(l.refuse(
                path,
                l.field,
                mb.rattle_time_s.to_string(),
                "must be 0 unless multibody.coast_contact = true (rattle needs both flanks)".into(),
            ));
        }
        Ok(())
    }

    /// Every blank of the scene, its dimensions resolved against the design,
    /// is a body: the half-section does not cross itself (a bore or hub
    /// wider than the rim allows). Checked here, before any meshing (the
    /// mesh stage checks it again on the shape it meshes).
    fn check_blank_sections(&self, path: &Path, pair: &PairData) -> Result<(), InputError> {
        use crate::design::Member;
        use crate::gear_body::{blank_shape, BlankDimensions};
        let dims = BlankDimensions::resolve(&self.blank_dimensions, pair);
        for (member, blanks) in [
            (Member::Pinion, &self.blanks.pinion),
            (Member::Wheel, &self.blanks.wheel),
        ] {
            for &blank in blanks {
                let shape = blank_shape(pair, member, blank, &dims);
                if let Some(h) = &shape.holes {
                    // The holes sit halfway between hub and web top: each
                    // must stay off both, and off its neighbours.
                    let height = 2.0 * (h.circle_radius - dims.wheel_hub_radius);
                    let chord =
                        2.0 * h.circle_radius * (std::f64::consts::PI / h.count as f64).sin();
                    let room = height.min(chord);
                    if h.diameter >= room {
                        let l = &lim::WHEEL_HOLES_IN_WEB;
                        return Err(l.refuse(
                            path,
                            l.field,
                            format!("{}", h.diameter * 1e3),
                            format!(
                                "must be < {:.3} mm: the web's radial height from the hub to the rim bottom is {:.3} mm and the holes' centres lie {:.3} mm apart",
                                room * 1e3,
                                height * 1e3,
                                chord * 1e3
                            ),
                        ));
                    }
                }
                if shape.is_body() {
                    continue;
                }
                let (l, value) = match member {
                    Member::Pinion => (&lim::PINION_BLANK_SECTION, dims.pinion_bore_radius),
                    Member::Wheel => (&lim::WHEEL_BLANK_SECTION, dims.wheel_hub_radius),
                };
                return Err(l.refuse(
                    path,
                    l.field,
                    format!("{}", value * 1e3),
                    format!(
                        "the {} blank's half-section crosses itself; the bore and hub must stay inside the body (rim bottom radius at the toe {:.1} mm)",
                        blank.name(),
                        shape.polygon[0][1] * 1e3
                    ),
                ));
            }
        }
        Ok(())
    }

    /// A `multibody.runup_wheel_blanks` the scene file gives (`text`) names
    /// only blanks of `blanks.wheel`. The default list (the standard
    /// wheel) is not checked: a scene of the lightweight wheel alone then
    /// runs no run-up, as before.
    pub fn check_given_run_up_blanks(&self, path: &Path, text: &str) -> Result<(), InputError> {
        let given = toml::from_str::<toml::Value>(text).ok().is_some_and(|v| {
            v.get("multibody")
                .and_then(|m| m.get("runup_wheel_blanks"))
                .is_some()
        });
        if !given {
            return Ok(());
        }
        self.analysed_wheel_blanks(
            path,
            &mbl::RUNUP_BLANK_IN_SCENE,
            "multibody.runup_wheel_blanks",
            &self.multibody.runup_wheel_blanks,
        )
    }

    /// Every blank of `list` (the field `field`) one of `blanks.wheel`,
    /// else refused with `l` naming the first other one.
    fn analysed_wheel_blanks(
        &self,
        path: &Path,
        l: &Limit,
        field: &str,
        list: &[Blank],
    ) -> Result<(), InputError> {
        match list
            .iter()
            .enumerate()
            .find(|(_, wb)| !self.blanks.wheel.contains(wb))
        {
            Some((i, wb)) => Err(l.refuse(
                path,
                &format!("{field}[{i}]"),
                format!("\"{}\"", wb.name()),
                "must be one of blanks.wheel (a blank the scene does not analyse has no stiffness files)".into(),
            )),
            None => Ok(()),
        }
    }

    /// `[blank_dimensions]` and `[blanks]`.
    fn check_blanks(&self, path: &Path) -> Result<(), InputError> {
        let bd = &self.blank_dimensions;
        for (l, v) in [
            (&lim::PINION_BORE_RADIUS, bd.pinion_bore_radius_mm),
            (&lim::PINION_RIM_DEPTH, bd.pinion_rim_depth_mm),
            (&lim::PINION_SHAFT_LENGTH, bd.pinion_shaft_length_mm),
            (&lim::WHEEL_BORE_RADIUS, bd.wheel_bore_radius_mm),
            (&lim::WHEEL_HUB_RADIUS, bd.wheel_hub_radius_mm),
            (&lim::WHEEL_RIM_DEPTH, bd.wheel_rim_depth_mm),
            (&lim::WHEEL_WEB_THICKNESS, bd.wheel_web_thickness_mm),
            (
                &lim::WHEEL_LIGHTWEIGHT_WEB_THICKNESS,
                bd.wheel_lightweight_web_thickness_mm,
            ),
            (&lim::WHEEL_HOLE_DIAMETER, bd.wheel_hole_diameter_mm),
        ] {
            if let Some(v) = v {
                l.check(path, v)?;
            }
        }
        if self.blanks.pinion.is_empty() || self.blanks.wheel.is_empty() {
            let l = &lim::BLANKS;
            return Err(l.refuse(
                path,
                l.field,
                "[]".into(),
                "each member needs at least one blank".into(),
            ));
        }
        for (l, field, list) in [
            (&lim::BLANK_ONCE, "blanks.pinion", &self.blanks.pinion),
            (&lim::BLANK_ONCE, "blanks.wheel", &self.blanks.wheel),
            (
                &mbl::RUNUP_BLANK_ONCE,
                "multibody.runup_wheel_blanks",
                &self.multibody.runup_wheel_blanks,
            ),
        ] {
            if let Some(i) = (1..list.len()).find(|&i| list[..i].contains(&list[i])) {
                return Err(l.refuse(
                    path,
                    &format!("{field}[{i}]"),
                    format!("\"{}\"", list[i].name()),
                    "names a blank listed before it: each blank once (its runs and files are named after it)".into(),
                ));
            }
        }
        Ok(())
    }

    /// The checks that need the design: the number of positions the sweeps
    /// and the multibody runs allocate, estimated from the mesh cycle.
    pub fn check_sizes(&self, path: &Path, pair: &PairData) -> Result<(), InputError> {
        self.misalignment.check(path, "misalignment", pair)?;
        self.check_blank_sections(path, pair)?;
        // A written [sensitivity] table is checked here; the defaults only
        // when the study runs (`solver sensitivity`).
        if let Some(s) = &self.sensitivity {
            s.check(path, &self.misalignment, pair)?;
        }
        let cycle_deg = pair.mesh_cycle().to_degrees();
        let positions = |cycles: f64, step_deg: f64| cycles * cycle_deg / step_deg + 1.0;
        let r = &self.rotation;
        let mut sweeps: Vec<(&Limit, f64, &str, f64)> = self
            .blanks
            .wheel
            .iter()
            .map(|&wb| {
                let cycles = match wb {
                    Blank::Standard => "rotation.mesh_cycles_standard",
                    Blank::Lightweight => "rotation.mesh_cycles_lightweight",
                };
                (
                    &lim::ROTATION_POSITIONS,
                    r.step_deg,
                    cycles,
                    r.mesh_cycles(wb),
                )
            })
            .collect();
        sweeps.push((
            &lim::UTCA_POSITIONS,
            self.utca.step_deg,
            "utca.mesh_cycles",
            self.utca.mesh_cycles,
        ));
        for (l, step, cycles_field, cycles) in sweeps {
            let n = positions(cycles, step);
            if !l.admits(n, &[]) {
                return Err(l.refuse(
                    path,
                    l.field,
                    step.to_string(),
                    format!(
                        "too small: {cycles_field} = {cycles} mesh cycles of {cycle_deg:.4}° in steps of {step}° make {n:.3e} positions per blank, at most {MAX_POSITIONS:.0e} are allowed (step >= {:.3e}°)",
                        cycles * cycle_deg / (MAX_POSITIONS - 1.0)
                    ),
                ));
            }
        }
        if self.analyses.multibody {
            self.check_multibody_sizes(path, pair)?;
        }
        Ok(())
    }

    /// The positions of the multibody contact table and the time steps of
    /// the multibody runs.
    fn check_multibody_sizes(&self, path: &Path, pair: &PairData) -> Result<(), InputError> {
        let r = &self.rotation;
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
        if let Some(sd) = self.blanks.wheel.iter().find_map(|&wb| mb.ste_dte_of(wb)) {
            rotation = rotation.max(sd.rotation());
        }
        let n = rotation / mb.table_step_deg.to_radians() + 1.0;
        let l = &mbl::TABLE_POSITIONS;
        if !l.admits(n, &[]) {
            return Err(l.refuse(
                path,
                l.field,
                mb.table_step_deg.to_string(),
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
                &mbl::QUASI_STATIC_TIME_STEPS,
                mb.quasi_static_max_step_s,
                qs_cycles * tau / pinion_speed,
            ),
            (
                &mbl::RUNUP_TIME_STEPS,
                mb.runup_max_step_s,
                if runs_up { mb.runup_time_s } else { 0.0 },
            ),
        ];
        if mb.coast_contact && mb.rattle_time_s > 0.0 {
            runs.push((
                &mbl::RATTLE_TIME_STEPS,
                mb.rattle_max_step_s,
                mb.rattle_time_s,
            ));
        }
        for (l, step, time) in runs {
            let n = time / step;
            if !l.admits(n, &[]) {
                return Err(l.refuse(
                    path,
                    l.field,
                    step.to_string(),
                    format!(
                        "too small for a run of {time:.4} s: at least {n:.3e} time steps, at most {MAX_TIME_STEPS:.0e} are allowed"
                    ),
                ));
            }
        }
        Ok(())
    }
}
