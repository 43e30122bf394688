//! The multibody cells of one design: the undamped free runs of the step,
//! tolerance and speed studies, and the loaded runs with the wheel's
//! impulse balance, on the scene's contact-element table.

use super::cell::{cell, classify, Cell, Study};
use super::{
    log_cell, Design, MAX_RUN_S, MAX_RUN_STEPS, MAX_STEPS_S, MB_LOADS_NM, PROBE_NM, SPEEDS_RPM,
    STEP_STUDY_RPM, STUDY_MAX_STEP_S, STUDY_TOLERANCE_RAD, TOLERANCES_RAD,
};
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::RollSurface;
use indicatif::ProgressBar;
use solver::cpu_clock::{thread_cpu_s, timed};
use solver::element::compliance::PairCompliance;
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{Drive, Model};
use solver::multibody::time_step::{discrete_gradient, integrate, Integrator, Scheme, StepControl};
use solver::stage::context::scene_sweep;
use solver::SolverError;

/// The multibody cells of a design (see the module's notes).
pub(super) fn multibody_cells(
    d: &Design,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    inertia: [f64; 2],
    bar: &ProgressBar,
) -> Vec<Cell> {
    let name = d.name();
    let tau = d.g.data.mesh_cycle();
    let mut specs: Vec<(Study, f64, &str, String, f64, f64, f64)> = Vec::new();
    for h in MAX_STEPS_S {
        specs.push((
            Study::MaxStep,
            h,
            "s",
            format!("{h:e} s"),
            STEP_STUDY_RPM,
            h,
            STUDY_TOLERANCE_RAD,
        ));
    }
    for tol in TOLERANCES_RAD {
        specs.push((
            Study::Tolerance,
            tol * 1e6,
            "µrad",
            format!("{:e} µrad", tol * 1e6),
            STEP_STUDY_RPM,
            STUDY_MAX_STEP_S,
            tol,
        ));
    }
    for rpm in SPEEDS_RPM {
        specs.push((
            Study::Speed,
            rpm,
            "rpm",
            format!("{rpm} rpm"),
            rpm,
            STUDY_MAX_STEP_S,
            STUDY_TOLERANCE_RAD,
        ));
    }
    let (table, build_s) = timed(|| probe_table(&d.scene, &d.g, fp, rs, pc, PROBE_NM));
    let mut cells = Vec::new();
    for (study, value, unit, label, rpm, max_step, tol) in specs {
        let mut c = cell(name, study, value, unit, label);
        match &table {
            Err(e) => c.outcome = classify(e),
            Ok(table) => {
                let cpu0 = thread_cpu_s();
                if let Err(e) = free_run(&mut c, table, inertia, tau, rpm, max_step, tol) {
                    c.outcome = classify(&e);
                }
                c.cpu_s = thread_cpu_s() - cpu0 + build_s / 14.0;
            }
        }
        log_cell(bar, &c);
        cells.push(c);
        bar.inc(1);
    }
    cells
}

/// The scene's contact-element table over one mesh cycle (periodic, the
/// scene's table step, lag nodes and slices), standard blanks, covering
/// `torque_nm` × `multibody.table_torque_factor`.
pub fn probe_table(
    scene: &LoadedScene,
    g: &PairGeometry,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    torque_nm: f64,
) -> Result<MeshTable, SolverError> {
    let sc = &scene.scene;
    let mb = &sc.multibody;
    let tau = g.data.mesh_cycle();
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    let sweep = scene_sweep(scene, g, Blank::Standard);
    let per_cycle = (tau / mb.table_step_deg.to_radians()).round().max(8.0) as usize;
    MeshTable::build(
        fp,
        rs,
        pc,
        &g.frames[0],
        ratio,
        TableSpec {
            start: sweep.start,
            direction: sweep.direction,
            step: tau / per_cycle as f64,
            positions: per_cycle,
            periodic: true,
            slices: sc.ltca.slices,
            lag_nodes: mb.table_lag_nodes,
            torque_max_nm: torque_nm * mb.table_torque_factor,
        },
    )
}

/// One undamped free run over a mesh cycle at `rpm` (see the module).
fn free_run(
    c: &mut Cell,
    table: &MeshTable,
    inertia: [f64; 2],
    tau: f64,
    rpm: f64,
    max_step: f64,
    tolerance: f64,
) -> Result<(), SolverError> {
    let r = table.ratio;
    let m = Model {
        table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::Free {
            pinion_torque: PROBE_NM,
            wheel_torque: PROBE_NM / r,
        },
    };
    let w1 = rpm * std::f64::consts::PI / 30.0;
    let mut s = m.static_state(0.0)?;
    s.v = [w1, r * w1];
    let t_end = (tau / w1).min(MAX_RUN_S);
    let e0 = m.energy(&s)?;
    let scale = 0.5 * (inertia[0] * w1 * w1 + inertia[1] * (r * w1).powi(2)) + PROBE_NM * tau;
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step,
            min_step: max_step * 1e-6,
            tolerance,
        },
    );
    let (mut drift, mut finite, mut te_sum, mut n) = (0.0f64, true, 0.0, 0usize);
    let (_, steps) = integrate(&m, s, &mut integ, t_end, |s| {
        if n > MAX_RUN_STEPS {
            return Err(SolverError::NotConverged {
                what: format!(
                    "the run of {t_end:.3e} s at t = {:.3e} s, more than {MAX_RUN_STEPS} steps",
                    s.t
                ),
                iterations: n,
            });
        }
        let e = m.energy(s)?;
        finite &= e.is_finite() && s.q.iter().chain(&s.v).chain(&s.a).all(|x| x.is_finite());
        drift = drift.max((e - e0).abs());
        te_sum += r * s.q[0] - s.q[1];
        n += 1;
        Ok(())
    })?;
    c.steps = Some(steps);
    c.sim_time_s = Some(t_end);
    c.rejected_steps = Some(integ.rejected);
    c.iterations = Some(integ.newton_iterations);
    c.non_finite = !finite;
    c.energy_drift = Some(drift / scale);
    c.te_mean_urad = Some(te_sum / n.max(1) as f64 * 1e6);
    Ok(())
}

/// The multibody load cells: the pinion at [`STEP_STUDY_RPM`] (imposed),
/// the wheel resisting each torque of [`MB_LOADS_NM`] (as a pinion torque),
/// undamped, frictionless, over one mesh cycle from the static state, on a
/// table covering the largest load. Without coast flanks a torque below the
/// holding torque (the wheel would run ahead at the tooth changes and leave
/// the mesh across the backlash, a rattle the model cannot follow) is
/// refused, naming the limit. Torque balance: the wheel's angular impulse
/// over the run, |Σ h (−ḡ₂) − T₂ t − J₂ Δω₂| / (max(T₂, 1 N·m) t), with
/// ḡ₂ the scheme's discrete gradient of the element's potential in each
/// accepted step ([`discrete_gradient`], the torque the integrator
/// applied; it is the element's pointwise torque −∂V/∂q₂ at the step's
/// midpoint to second order in the step).
pub(super) fn multibody_load_cells(
    d: &Design,
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    inertia: [f64; 2],
    bar: &ProgressBar,
) -> Vec<Cell> {
    let top = MB_LOADS_NM.iter().copied().fold(0.0, f64::max);
    let (table, build_s) = timed(|| probe_table(&d.scene, &d.g, fp, rs, pc, top));
    let mut cells = Vec::new();
    for t in MB_LOADS_NM {
        let mut c = cell(d.name(), Study::MultibodyLoad, t, "N·m", format!("{t} N·m"));
        match &table {
            Err(e) => c.outcome = classify(e),
            Ok(table) => {
                let cpu0 = thread_cpu_s();
                if let Err(e) = loaded_run(&mut c, table, inertia, d.g.data.mesh_cycle(), t) {
                    c.outcome = classify(&e);
                }
                c.cpu_s = thread_cpu_s() - cpu0 + build_s / MB_LOADS_NM.len() as f64;
            }
        }
        log_cell(bar, &c);
        cells.push(c);
        bar.inc(1);
    }
    cells
}

/// One run of [`multibody_load_cells`] into `c` (its torque balance, steps,
/// TE); a refusal or failure as the error.
pub fn loaded_run(
    c: &mut Cell,
    table: &MeshTable,
    inertia: [f64; 2],
    tau: f64,
    torque: f64,
) -> Result<(), SolverError> {
    let r = table.ratio;
    let w1 = STEP_STUDY_RPM * std::f64::consts::PI / 30.0;
    let wheel_torque = torque / r;
    let m = Model {
        table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::PinionSpeed {
            speed: solver::multibody::model::Ramp {
                from: w1,
                to: w1,
                duration: 0.0,
            },
            wheel_torque,
        },
    };
    let holding = m.holding_torque()?;
    if torque < holding {
        return Err(SolverError::Table(format!(
            "pinion torque {torque} N·m is below {holding:.3e} N·m, the torque that holds the wheel (inertia {:.4e} kg·m²) on the drive flanks at {STEP_STUDY_RPM} rpm; without coast flanks it would leave the mesh across the backlash (rattle), which this element cannot follow",
            inertia[1]
        )));
    }
    let s = m.static_state(0.0)?;
    let t_end = (tau / w1).min(MAX_RUN_S);
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step: STUDY_MAX_STEP_S,
            min_step: STUDY_MAX_STEP_S * 1e-6,
            tolerance: STUDY_TOLERANCE_RAD,
        },
    );
    let w2_0 = s.v[1];
    // The scheme's own wheel balance per step: J₂ (v⁺ − v) = −h T₂ − h ḡ₂,
    // ḡ the scheme's discrete gradient of V between the step's ends.
    let (mut impulse, mut last): (f64, Option<(f64, [f64; 2])>) = (0.0, None);
    let (mut finite, mut te_sum, mut n) = (true, 0.0, 0usize);
    let (end, steps) = integrate(&m, s, &mut integ, t_end, |s| {
        if let Some((t0, q0)) = last {
            let mid = [0.5 * (s.q[0] + q0[0]), 0.5 * (s.q[1] + q0[1])];
            let g = discrete_gradient(&m, q0, s.q, m.mesh(mid)?.0.grad)?[1];
            impulse -= g * (s.t - t0);
        }
        last = Some((s.t, s.q));
        finite &= s.q.iter().chain(&s.v).chain(&s.a).all(|x| x.is_finite());
        te_sum += r * s.q[0] - s.q[1];
        n += 1;
        Ok(())
    })?;
    let residual = impulse - wheel_torque * t_end - inertia[1] * (end.v[1] - w2_0);
    c.steps = Some(steps);
    c.sim_time_s = Some(t_end);
    c.rejected_steps = Some(integ.rejected);
    c.iterations = Some(integ.newton_iterations);
    c.non_finite = !finite;
    c.torque_balance = Some(residual.abs() / (wheel_torque.max(1.0) * t_end));
    c.te_mean_urad = Some(te_sum / n.max(1) as f64 * 1e6);
    Ok(())
}
