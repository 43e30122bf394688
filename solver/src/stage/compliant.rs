//! `solver dynamic` with the scene's `[bearings]`: the multibody runs again
//! with the members on compliant bearings ([`crate::multibody::compliant`]):
//! the 10 rpm run at every scene torque and, where the rigid run-up runs,
//! the run-up with the spectrogram of the wheel's bearing force. Files, in
//! the blank pair's folder beside the rigid runs':
//!
//! - `bearings_quasi_static_<T>nm.csv`, `bearings_runup.csv`: per step the
//!   time, pinion rotation and speed, shaft TE, the relative pose (E, P, G,
//!   ΔΣ), both members' displacements [u; θ] about their apices (fixed
//!   frame), every bearing's force (x, y, z) and the estimate of the TE the
//!   linear shift leaves out;
//! - `bearings_runup_spectrogram.svg`: the wheel bearings' total force |F|.

use crate::bearings::support::Support;
use crate::bearings::system_deflection::supports_of;
use crate::ltca::mean_ptp;
use crate::multibody::compliant::{
    integrate, CState, CompliantIntegrator, CompliantModel, MemberBody,
};
use crate::multibody::lag_shift::LagShift;
use crate::multibody::mesh_table::MeshTable;
use crate::multibody::model::{interpolate, wheel_driven, Model};
use crate::multibody::time_step::StepControl;
use anyhow::Context;
use formats::summaries::{CompliantBodiesUsed, CompliantRunSummary, CompliantSummary};
use geometry::generation::trace_sign;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::scene_bearings::{BearingMm, BodyMass};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// What the compliant runs need of the rigid runs' set-up.
pub struct Setup<'a> {
    pub scene: &'a LoadedScene,
    /// The pair, placed by the scene's misalignment.
    pub g: &'a PairGeometry,
    pub table: &'a MeshTable,
    pub inertia: [f64; 2],
    /// Mass (volume × density) of each member's mesh, kg.
    pub mesh_mass_kg: [f64; 2],
    pub blanks: [Blank; 2],
    pub odir: &'a Path,
    pub control: &'a dyn Fn(f64) -> StepControl,
    pub runs_up: bool,
    /// The gearbox's FE housing (`[bearings.gearbox.housing]`).
    pub housing: Option<&'a crate::stage::gearbox::LoadedHousing>,
}

/// The members as bodies on the scene's bearings.
fn bodies(
    g: &PairGeometry,
    bearings: &geometry::scene_bearings::BearingSettings,
    inertia: [f64; 2],
    mesh_mass: [f64; 2],
) -> anyhow::Result<([MemberBody; 2], String)> {
    let supports = supports_of(bearings, g)?;
    let mut source = Vec::new();
    let one = |m: usize, support: Support, list: &[BearingMm], given: Option<BodyMass>| {
        let mean = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        let (mass, centroid, jt) = match given {
            Some(b) => (b.mass_kg, b.centroid_mm * 1e-3, b.transverse_inertia_kgm2),
            None => (mesh_mass[m], mean, 0.5 * inertia[m]),
        };
        MemberBody {
            support,
            damping: list
                .iter()
                .map(|b| (b.radial_damping_n_s_per_m, b.axial_damping_n_s_per_m))
                .collect(),
            mass_kg: mass,
            centroid_m: centroid,
            transverse_inertia_kgm2: jt,
        }
    };
    for (name, given) in [
        ("pinion", bearings.pinion_body),
        ("wheel", bearings.wheel_body),
    ] {
        source.push(match given {
            Some(_) => format!("{name}: scene [bearings.{name}_body]"),
            None => format!(
                "{name}: mass from the mesh, centre of mass at the mean point, transverse moment half the polar moment (thin disc)"
            ),
        });
    }
    Ok((
        [
            one(0, supports.pinion, &bearings.pinion, bearings.pinion_body),
            one(1, supports.wheel, &bearings.wheel, bearings.wheel_body),
        ],
        source.join("; "),
    ))
}

/// One run's per-step record.
#[derive(Default)]
struct Trace {
    t: Vec<f64>,
    q1: Vec<f64>,
    te: Vec<f64>,
    rows: String,
    /// Both wheel bearings' forces together (fixed frame), N.
    wheel_force: Vec<[f64; 3]>,
    most_m: [f64; 4],
    most_linear: f64,
    sum_linear: f64,
    most_force: [Vec<f64>; 2],
}

fn header(cm: &CompliantModel) -> String {
    let mut h = String::from(
        "time_s,pinion_rotation_deg,pinion_rpm,te_urad,e_um,p_um,g_um,shaft_angle_urad",
    );
    for m in ["pinion", "wheel"] {
        for c in ["ux_um", "uy_um", "uz_um", "rx_urad", "ry_urad", "rz_urad"] {
            let _ = write!(h, ",{m}_{c}");
        }
    }
    for (k, m) in ["pinion", "wheel"].iter().enumerate() {
        for i in 0..cm.members[k].support.bearings().len() {
            let _ = write!(
                h,
                ",{m}_bearing{i}_fx_n,{m}_bearing{i}_fy_n,{m}_bearing{i}_fz_n"
            );
        }
    }
    h.push_str(",linearization_urad\n");
    h
}

/// Runs `cm` from `s0` to `t_end`, recording every step.
fn record(
    cm: &CompliantModel,
    s0: CState,
    integ: &mut CompliantIntegrator,
    t_end: f64,
) -> Result<(Trace, usize), crate::SolverError> {
    let r = cm.rigid.table.ratio;
    let mut tr = Trace {
        rows: header(cm),
        most_force: [
            vec![0.0; cm.members[0].support.bearings().len()],
            vec![0.0; cm.members[1].support.bearings().len()],
        ],
        ..Default::default()
    };
    let (_, steps) = integrate(cm, s0, integ, t_end, |s, _| {
        let c = cm.contact_map() * s.x;
        let m = [c[2], c[3], c[4], c[5]];
        let te = r * s.x[0] - s.x[1];
        let linear = cm.shift.nonlinearity(cm.rigid.table, c[0], &m);
        tr.t.push(s.t);
        tr.q1.push(s.x[0]);
        tr.te.push(te);
        let _ = write!(
            tr.rows,
            "{:.9},{:.6},{:.4},{:.5},{:.5},{:.5},{:.5},{:.5}",
            s.t,
            s.x[0].to_degrees(),
            s.v[0] * 30.0 / std::f64::consts::PI,
            te * 1e6,
            m[0] * 1e6,
            m[1] * 1e6,
            m[2] * 1e6,
            m[3] * 1e6
        );
        for k in 0..2 {
            for v in cm.displacement(&s.x, k).iter() {
                let _ = write!(tr.rows, ",{:.5}", v * 1e6);
            }
        }
        let mut wheel = nalgebra::Vector3::zeros();
        for k in 0..2 {
            for (i, f) in cm.bearing_forces(&s.x, &s.v, k).iter().enumerate() {
                let _ = write!(tr.rows, ",{:.4},{:.4},{:.4}", f.x, f.y, f.z);
                tr.most_force[k][i] = tr.most_force[k][i].max(f.norm());
                if k == 1 {
                    wheel += f;
                }
            }
        }
        let _ = writeln!(tr.rows, ",{:.5}", linear * 1e6);
        tr.wheel_force.push([wheel.x, wheel.y, wheel.z]);
        for (most, v) in tr.most_m.iter_mut().zip(m) {
            *most = most.max(v.abs());
        }
        tr.most_linear = tr.most_linear.max(linear);
        tr.sum_linear += linear;
        Ok(())
    })?;
    Ok((tr, steps))
}

/// The run's summary; its TE mean and peak-to-peak over the steps, or with
/// `q1_step` (rad) at the pinion rotations k·q1_step the run passes (as the
/// rigid 10 rpm runs sample theirs).
#[allow(clippy::too_many_arguments)]
fn summary(
    case: &str,
    torque: f64,
    tr: &Trace,
    steps: usize,
    integ: &CompliantIntegrator,
    cpu: f64,
    csv: &str,
    q1_step: Option<f64>,
) -> CompliantRunSummary {
    let sampled: Vec<f64> = match q1_step {
        Some(h) => {
            let (lo, hi) = (tr.q1[0], tr.q1[tr.q1.len() - 1]);
            let first = (lo / h).ceil() as i64;
            let last = (hi / h).floor() as i64;
            (first..=last)
                .map(|k| interpolate(&tr.q1, &tr.te, k as f64 * h))
                .collect()
        }
        None => tr.te.clone(),
    };
    let (mean, ptp) = mean_ptp(&sampled);
    CompliantRunSummary {
        case: case.into(),
        torque_nm: torque,
        steps,
        rejected_steps: integ.rejected,
        cpu_s: cpu,
        cpu_s_per_step: cpu / steps.max(1) as f64,
        te_mean_urad: mean * 1e6,
        te_ptp_urad: ptp * 1e6,
        largest_misalignment: tr.most_m.map(|v| v * 1e6),
        largest_linearization_urad: tr.most_linear * 1e6,
        mean_linearization_urad: tr.sum_linear / tr.te.len().max(1) as f64 * 1e6,
        pinion_bearing_force_n: tr.most_force[0].clone(),
        wheel_bearing_force_n: tr.most_force[1].clone(),
        csv: csv.into(),
    }
}

/// The compliant-bearing runs of one blank pair.
pub fn run(s: &Setup) -> anyhow::Result<CompliantSummary> {
    let sc = &s.scene.scene;
    let mb = &sc.multibody;
    let bearings = sc
        .bearings
        .as_ref()
        .context("compliant-bearing runs without [bearings]")?;
    let mut notes = Vec::new();
    if sc.ltca.friction_coefficient > 0.0 {
        notes.push(format!(
            "frictionless (the scene's μ = {} acts in the rigid runs only)",
            sc.ltca.friction_coefficient
        ));
    }
    if mb.coast_contact {
        notes.push("drive flanks only (no coast contact, no rattle)".into());
    }
    let t0 = Instant::now();
    let shift = LagShift::build(s.g, sc.loaded_flank, &sc.utca, s.table, &sc.misalignment)
        .context("shift of the unloaded TE per misalignment")?;
    let lag_shift_s = t0.elapsed().as_secs_f64();
    eprintln!(
        "  compliant bearings: unloaded TE's shift per misalignment at {} of the table's {} positions in {lag_shift_s:.1} s",
        shift.solved_nodes,
        s.table.nodes()
    );
    let (members, mass_source) = bodies(s.g, bearings, s.inertia, s.mesh_mass_kg)?;
    let masses = [members[0].mass_kg, members[1].mass_kg];
    let hand = trace_sign(s.g.data.members[0].hand);
    let mut runs = Vec::new();
    let wheel_speed = mb.quasi_static_wheel_rpm * std::f64::consts::PI / 30.0;
    let ratio = s.table.ratio;
    let sweep_span = s.table.span();
    for &torque in &sc.pinion_torque_nm {
        let (m, _) = wheel_driven(
            s.table,
            s.inertia,
            wheel_speed,
            torque,
            mb.damping_ratio,
            0.0,
        )?;
        let cm = CompliantModel::new(m, &shift, members.clone(), hand)?;
        let s0 = cm.static_state(0.0)?;
        let mut integ =
            CompliantIntegrator::new(mb.rho_inf, (s.control)(mb.quasi_static_max_step_s));
        let t_end = sweep_span.min(sc.rotation.mesh_cycles(s.blanks[1]) * s.g.data.mesh_cycle())
            / (wheel_speed / ratio);
        let t = Instant::now();
        let (tr, steps) = record(&cm, s0, &mut integ, t_end)
            .with_context(|| format!("compliant bearings, 10 rpm at {torque} N·m"))?;
        let cpu = t.elapsed().as_secs_f64();
        let csv = format!("bearings_quasi_static_{torque}nm.csv");
        formats::output::write_atomic(&s.odir.join(&csv), tr.rows.as_bytes())?;
        let sum = summary(
            "10 rpm",
            torque,
            &tr,
            steps,
            &integ,
            cpu,
            &csv,
            Some(s.table.spec.step),
        );
        eprintln!(
            "  compliant 10 rpm {torque:6.1} N·m: TE mean {:8.2} µrad, ptp {:7.2} µrad, linearization estimate mean {:.2} µrad (largest {:.2}), |E|,|P|,|G| up to {:.2}, {:.2}, {:.2} µm, |ΔΣ| {:.2} µrad, {steps} steps, {:.1} µs/step",
            sum.te_mean_urad,
            sum.te_ptp_urad,
            sum.mean_linearization_urad,
            sum.largest_linearization_urad,
            sum.largest_misalignment[0],
            sum.largest_misalignment[1],
            sum.largest_misalignment[2],
            sum.largest_misalignment[3],
            sum.cpu_s_per_step * 1e6
        );
        runs.push(sum);
    }
    if s.runs_up {
        runs.push(run_up(s, &shift, &members, hand)?);
    }
    let gearbox = match &bearings.gearbox {
        Some(gb) => Some(crate::stage::gearbox::run(
            s, gb, &shift, &members, hand, s.housing,
        )?),
        None => None,
    };
    let used = |b: &MemberBody| BodyMass {
        mass_kg: b.mass_kg,
        centroid_mm: b.centroid_m * 1e3,
        transverse_inertia_kgm2: b.transverse_inertia_kgm2,
    };
    Ok(CompliantSummary {
        lag_shift_s,
        masses_kg: masses,
        mass_source,
        notes,
        runs,
        used: Some(CompliantBodiesUsed {
            pinion_bearings: bearings.pinion.clone(),
            wheel_bearings: bearings.wheel.clone(),
            bodies: [used(&members[0]), used(&members[1])],
        }),
        gearbox,
    })
}

/// The rigid model of the scene's run-up drive on `s`'s table, its mesh
/// damping set to the scene's ratio at the quasi-static start.
pub(crate) fn runup_model<'a>(s: &Setup<'a>) -> anyhow::Result<Model<'a>> {
    let mb = &s.scene.scene.multibody;
    let mut m = Model {
        table: s.table,
        coast: None,
        inertia: s.inertia,
        damping: 0.0,
        friction: 0.0,
        drive: crate::stage::runup::runup_drive(mb, s.table.ratio),
    };
    let rs0 = m.static_state(0.0)?;
    m.damping = m.damping_for_ratio(mb.damping_ratio, &rs0)?;
    Ok(m)
}

/// The run-up on compliant bearings and the wheel bearings' spectrogram.
fn run_up(
    s: &Setup,
    shift: &LagShift,
    members: &[MemberBody; 2],
    hand: f64,
) -> anyhow::Result<CompliantRunSummary> {
    let mb = &s.scene.scene.multibody;
    let torque = mb.runup_pinion_torque_nm;
    let cm = CompliantModel::new(runup_model(s)?, shift, members.clone(), hand)?;
    let s0 = cm.static_state(0.0)?;
    let mut integ = CompliantIntegrator::new(mb.rho_inf, (s.control)(mb.runup_max_step_s));
    let t = Instant::now();
    let (tr, steps) =
        record(&cm, s0, &mut integ, mb.runup_time_s).context("compliant bearings, run-up")?;
    let cpu = t.elapsed().as_secs_f64();
    let csv = "bearings_runup.csv";
    formats::output::write_atomic(&s.odir.join(csv), tr.rows.as_bytes())?;
    let magnitude: Vec<f64> = tr
        .wheel_force
        .iter()
        .map(|f| f.iter().map(|c| c * c).sum::<f64>().sqrt())
        .collect();
    crate::stage::runup::runup_spectrogram(
        &s.odir.join("bearings_runup_spectrogram.svg"),
        &format!(
            "Wheel bearings' force |F|, compliant bearings, run-up at {torque} N·m ({:?}/{:?})",
            s.blanks[0], s.blanks[1]
        ),
        (&tr.t, &magnitude),
        mb,
        s.g.data.members[0].teeth as f64,
        s.table.ratio,
        s.blanks[1],
        &[],
    )?;
    // The same order analysis as the rigid run-up's `runup_orders.json`, of
    // both wheel bearings' force together.
    crate::stage::runup::write_runup_orders(
        &s.odir.join("bearings_runup_orders.json"),
        s.blanks,
        s.g.data.members[0].teeth as f64,
        s.table.ratio,
        (&tr.t, &tr.q1, &tr.wheel_force),
    )?;
    let sum = summary("run-up", torque, &tr, steps, &integ, cpu, csv, None);
    eprintln!(
        "  compliant run-up: {steps} steps ({} rejected), {:.1} µs/step, |E|,|P|,|G| up to {:.2}, {:.2}, {:.2} µm, |ΔΣ| {:.2} µrad",
        integ.rejected,
        sum.cpu_s_per_step * 1e6,
        sum.largest_misalignment[0],
        sum.largest_misalignment[1],
        sum.largest_misalignment[2],
        sum.largest_misalignment[3]
    );
    Ok(sum)
}
