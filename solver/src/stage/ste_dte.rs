//! The white paper's first use case, static against dynamic transmission
//! error (`[multibody.ste_dte]`): the pinion is run up twice on the same
//! contact-element table, slowly (the quasi-static TE, STE) and fast (the
//! dynamic TE, DTE), each from rest at a constant acceleration that ends
//! at the same pinion rotation φₐ and then at constant speed, the wheel
//! resisting the load. The slow run is the fast one with time stretched
//! by the speed ratio (its largest step too), so both take the same steps
//! in the angle domain. Both TEs are sampled at the same pinion rotations
//! ([`crate::signal::angle_domain`], 64 per mesh cycle) over the compared
//! revolutions; the STE is also checked against the static balance (the
//! lag that carries the load without inertia). Writes `ste_dte.csv` (the
//! synchronized signals), `ste_dte_<rpm>rpm.csv` (each run's steps) and
//! `ste_dte.svg` (the white paper's Figure 13, our way).

use crate::ltca::mean_ptp;
use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::MeshTable;
use crate::multibody::model::{Drive, Model, Ramp};
use crate::multibody::time_step::{Integrator, Scheme, StepControl};
use crate::signal::angle_domain::{departure, grid, sample};
use crate::stage::runup::hold_on_drive_flanks;
use crate::stage::trace::{record, trace_csv, Trace};
use anyhow::Context;
use charts::{te_curve, Series};
use formats::output::write_atomic;
use formats::summaries::{SteDteRun, SteDteSummary};
use geometry::scene::Blank;
use geometry::scene_ste_dte::{rad_per_s, SteDte};
use std::fmt::Write as _;
use std::path::Path;

/// Samples per mesh cycle of the angle-domain comparison.
pub const SAMPLES_PER_MESH_CYCLE: usize = 64;

/// What the comparison runs on.
pub struct Setup<'a> {
    pub table: &'a MeshTable,
    pub coast: Option<&'a Coast>,
    pub inertia: [f64; 2],
    pub friction: f64,
    /// The impact law brings its own damping.
    pub impact: bool,
    pub damping_ratio: f64,
    pub scheme: Scheme,
    pub control: &'a dyn Fn(f64) -> StepControl,
    pub mesh_cycle: f64,
    pub blanks: [Blank; 2],
}

/// One run-up from rest to `rpm`, the acceleration ending at the
/// settings' rotation, over the dynamic run's time stretched by
/// `stretch`: its trace, its summary and its model (for the static
/// balance).
fn run<'a>(
    s: &Setup<'a>,
    sd: &SteDte,
    rpm: f64,
    stretch: f64,
) -> anyhow::Result<(Trace, SteDteRun, Model<'a>)> {
    let ratio = s.table.ratio;
    let t_a = sd.acceleration_time_s(rpm);
    let mut m = Model {
        table: s.table,
        coast: s.coast,
        inertia: s.inertia,
        damping: 0.0,
        friction: s.friction,
        drive: Drive::PinionSpeed {
            speed: Ramp {
                from: 0.0,
                to: rad_per_s(rpm),
                duration: t_a,
            },
            wheel_torque: sd.pinion_torque_nm / ratio,
        },
    };
    hold_on_drive_flanks(
        &m,
        ("multibody.ste_dte.pinion_torque_nm", sd.pinion_torque_nm),
        "multibody.ste_dte.rpm",
        s.coast.is_some(),
        s.inertia[1],
        rpm,
    )?;
    let s0 = m.static_state(0.0)?;
    if !s.impact {
        m.damping = m.damping_for_ratio(s.damping_ratio, &s0)?;
    }
    let max_step = sd.max_step_s * stretch;
    let t_end = sd.time_s * stretch;
    let mut integ = Integrator::new(s.scheme, (s.control)(max_step));
    let clock = crate::cpu_clock::thread_cpu_s();
    let (tr, steps) = record(&m, s0, &mut integ, t_end)
        .with_context(|| format!("STE/DTE run-up to {rpm} rpm"))?;
    let cpu = crate::cpu_clock::thread_cpu_s() - clock;
    eprintln!(
        "  STE/DTE: 0 -> {rpm} rpm within {}°, {t_end:.4} s: {steps} steps ({} rejected), {:.1} µs/step",
        sd.acceleration_end_deg,
        integ.rejected,
        cpu / steps.max(1) as f64 * 1e6
    );
    let summary = SteDteRun {
        rpm,
        acceleration_time_s: t_a,
        sim_time_s: t_end,
        max_step_s: max_step,
        steps,
        rejected_steps: integ.rejected,
        cpu_s: cpu,
        cpu_s_per_step: cpu / steps.max(1) as f64,
    };
    Ok((tr, summary, m))
}

/// Runs both run-ups of `sd` and compares them; files into `odir`.
pub fn ste_dte(s: &Setup, sd: &SteDte, odir: &Path) -> anyhow::Result<SteDteSummary> {
    let [pb, wb] = s.blanks;
    let stretch = sd.time_scale();
    let (slow, qs, model) = run(s, sd, sd.rpm[0], stretch)?;
    let (fast, dy, _) = run(s, sd, sd.rpm[1], 1.0)?;
    let end = sd.compared_revolutions * 2.0 * std::f64::consts::PI;
    let n = ((end / s.mesh_cycle) * SAMPLES_PER_MESH_CYCLE as f64).round() as usize;
    let at = grid(end, n.max(2));
    let ste = sample(&slow.q1, &slow.te, &at);
    let dte = sample(&fast.q1, &fast.te, &at);
    let balance: Vec<f64> = at
        .iter()
        .map(|&q| model.static_lag(q))
        .collect::<Result<_, _>>()?;
    let ste_minus_static = ste
        .iter()
        .zip(&balance)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let phi_a = sd.acceleration_end_deg.to_radians();
    let d = departure(&at, &ste, &dte, phi_a, s.mesh_cycle).with_context(|| {
        format!(
            "multibody.ste_dte: the compared {} revolutions end within a mesh cycle of the acceleration's end at {}°",
            sd.compared_revolutions, sd.acceleration_end_deg
        )
    })?;
    let (ste_mean, ste_ptp) = mean_ptp(&ste);
    let (dte_mean, dte_ptp) = mean_ptp(&dte);
    let after = |y: &[f64]| -> f64 {
        let v: Vec<f64> = at
            .iter()
            .zip(y)
            .filter(|(p, _)| **p > phi_a)
            .map(|(_, v)| *v)
            .collect();
        mean_ptp(&v).1
    };
    let mut csv = String::from(
        "pinion_rotation_deg,te_quasi_static_urad,te_dynamic_urad,te_static_balance_urad\n",
    );
    for k in 0..at.len() {
        let _ = writeln!(
            csv,
            "{:.5},{:.5},{:.5},{:.5}",
            at[k].to_degrees(),
            ste[k] * 1e6,
            dte[k] * 1e6,
            balance[k] * 1e6
        );
    }
    write_atomic(&odir.join("ste_dte.csv"), csv.as_bytes())?;
    for (tr, rpm) in [(&slow, sd.rpm[0]), (&fast, sd.rpm[1])] {
        write_atomic(
            &odir.join(format!("ste_dte_{rpm}rpm.csv")),
            trace_csv(tr, None).as_bytes(),
        )?;
    }
    let deg: Vec<f64> = at.iter().map(|v| v.to_degrees()).collect();
    te_curve(
        &odir.join("ste_dte.svg"),
        &format!(
            "Quasi-static ({} rpm) and dynamic ({} rpm) TE at {} N·m, {pb:?} pinion / {wb:?} wheel; acceleration ends at {}°",
            sd.rpm[0], sd.rpm[1], sd.pinion_torque_nm, sd.acceleration_end_deg
        ),
        "pinion rotation (deg)",
        "transmission error (µrad)",
        &[
            Series {
                name: format!("DTE, {} rpm", sd.rpm[1]),
                x: deg.clone(),
                y: dte.iter().map(|v| v * 1e6).collect(),
                dashed: false,
            },
            Series {
                name: format!("quasi-STE, {} rpm", sd.rpm[0]),
                x: deg,
                y: ste.iter().map(|v| v * 1e6).collect(),
                dashed: true,
            },
        ],
    )?;
    eprintln!(
        "  STE/DTE over {} revolution(s): STE ptp {:.2} µrad, DTE ptp {:.2} µrad; largest departure {:.2} µrad at {:.1}°",
        sd.compared_revolutions,
        ste_ptp * 1e6,
        dte_ptp * 1e6,
        d.largest_after_acceleration * 1e6,
        d.largest_after_acceleration_at.to_degrees()
    );
    Ok(SteDteSummary {
        pinion_torque_nm: sd.pinion_torque_nm,
        acceleration_end_deg: sd.acceleration_end_deg,
        compared_revolutions: sd.compared_revolutions,
        samples: at.len(),
        mesh_cycle_deg: s.mesh_cycle.to_degrees(),
        quasi_static: qs,
        dynamic: dy,
        table_cpu_s: s.table.cpu_s_per_position * s.table.spec.positions as f64,
        ste_mean_urad: ste_mean * 1e6,
        ste_ptp_urad: ste_ptp * 1e6,
        dte_mean_urad: dte_mean * 1e6,
        dte_ptp_urad: dte_ptp * 1e6,
        ste_ptp_after_acceleration_urad: after(&ste) * 1e6,
        dte_ptp_after_acceleration_urad: after(&dte) * 1e6,
        ste_minus_static_max_urad: ste_minus_static * 1e6,
        departure_during_acceleration_urad: d.mean_during_acceleration * 1e6,
        departure_largest_urad: d.largest_after_acceleration * 1e6,
        departure_largest_at_deg: d.largest_after_acceleration_at.to_degrees(),
        departure_last_cycle_ptp_urad: d.last_cycle_ptp * 1e6,
    })
}
