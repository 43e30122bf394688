//! The run-up's drive and its outputs, shared by the rigid-bearing
//! ([`crate::stage::dynamic`]) and compliant-bearing
//! ([`crate::stage::compliant`]) multibody stages: the pinion's speed ramp,
//! the spectrogram of a bearing force over the pinion speed, and the order
//! analysis in the pinion's angle domain (`runup_orders.json`).
use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::MeshTable;
use crate::multibody::model::Model;
use crate::multibody::time_step::Integrator;
use crate::multibody::time_step::Scheme;
use crate::multibody::time_step::StepControl;
use crate::stage::trace::record;
use crate::stage::trace::trace_csv;
use anyhow::Context;
use charts::te_curve;
use charts::Series;
use formats::output::write_atomic;
use formats::summaries::{RunupRootTension, RunupSummary};
use std::time::Instant;

use crate::multibody::model::{Drive, Ramp};
use crate::signal::spectrum::{plot_with_modes, resample, stft, OrderLine};
use formats::output::write_json;
use formats::summaries::RunupOrders;
use geometry::gear_body::WHEEL_WEB_HOLES;
use geometry::scene::Blank;
use std::path::Path;

/// `runup_orders.json`-style order analysis of a run-up's wheel bearing
/// force ([`crate::signal::runup_orders::windows`]) in the pinion's angle domain,
/// one wheel revolution per window (32 samples per mesh cycle), at the
/// marked orders of the pair (z₁ = `z1`, ratio z₁/z₂ = `ratio`): `trace`
/// is (time s, pinion rotation rad, wheel bearing force N, fixed frame).
pub(crate) fn write_runup_orders(
    path: &Path,
    blanks: [Blank; 2],
    z1: f64,
    ratio: f64,
    trace: (&[f64], &[f64], &[[f64; 3]]),
) -> anyhow::Result<()> {
    let teeth = [z1.round() as usize, (z1 / ratio).round() as usize];
    let per_window = 32 * teeth[1];
    let marks = crate::signal::runup_orders::marked_orders(teeth[0], teeth[1], WHEEL_WEB_HOLES);
    write_json(
        path,
        &RunupOrders {
            pinion_blank: blanks[0],
            wheel_blank: blanks[1],
            pinion_teeth: teeth[0],
            wheel_teeth: teeth[1],
            samples_per_window: per_window,
            order_resolution: ratio,
            windows: crate::signal::runup_orders::windows(
                trace.0, trace.1, trace.2, teeth, per_window, &marks,
            ),
        },
    )?;
    Ok(())
}

/// The run-up's pinion speed ramp, rad/s.
pub(crate) fn runup_ramp(mb: &geometry::scene::MultibodySettings) -> Ramp {
    let w = |rpm: f64| rpm * std::f64::consts::PI / 30.0;
    Ramp {
        from: w(mb.runup_rpm[0]),
        to: w(mb.runup_rpm[1]),
        duration: mb.runup_time_s,
    }
}

/// The run-up's drive: the pinion on [`runup_ramp`], the wheel resisting
/// the run-up torque (at the pinion) through the ratio `ratio`.
pub(crate) fn runup_drive(mb: &geometry::scene::MultibodySettings, ratio: f64) -> Drive {
    Drive::PinionSpeed {
        speed: runup_ramp(mb),
        wheel_torque: mb.runup_pinion_torque_nm / ratio,
    }
}

/// The run-up's spectrogram of a force magnitude `series` (times, |F|)
/// over the pinion speed, with the tooth orders (and, with the lightweight
/// wheel, its 3-hole side bands) marked.
#[allow(clippy::too_many_arguments)]
pub(crate) fn runup_spectrogram(
    path: &Path,
    title: &str,
    series: (&[f64], &[f64]),
    mb: &geometry::scene::MultibodySettings,
    z1: f64,
    ratio: f64,
    wb: Blank,
    modes_hz: &[f64],
) -> anyhow::Result<()> {
    let ramp = runup_ramp(mb);
    let dt = mb.runup_max_step_s.max(mb.runup_time_s / 2e5);
    let y = resample(series.0, series.1, dt);
    let window = ((mb.runup_time_s / 8.0) / dt).round().max(16.0) as usize;
    let fmax = 3.2 * z1 * ramp.to / (2.0 * std::f64::consts::PI);
    let freq: Vec<f64> = (0..200).map(|k| fmax * k as f64 / 199.0).collect();
    let spec = stft(&y, dt, window.min(y.len()), (window / 8).max(1), &freq);
    let hz = |t: f64| ramp.at(t)[1] / (2.0 * std::f64::consts::PI);
    let mut orders: Vec<OrderLine> = (1..=3)
        .map(|k| OrderLine {
            order: z1 * k as f64,
            label: format!("{}", z1 * k as f64),
        })
        .collect();
    if wb == Blank::Lightweight {
        let o = 3.0 * ratio;
        orders.push(OrderLine {
            order: z1 + o,
            label: format!("{z1}+{o:.2}"),
        });
        orders.push(OrderLine {
            order: z1 - o,
            label: format!("{z1}-{o:.2}"),
        });
    }
    plot_with_modes(path, title, &spec, &hz, &orders, modes_hz)?;
    Ok(())
}

/// Without coast flanks the wheel must stay on the drive flanks up to the
/// run-up's top speed `top_rpm`: below the holding torque
/// ([`Model::holding_torque`]) it runs ahead at the tooth changes and
/// leaves the mesh, and the run's TE means nothing; refused then. With
/// coast flanks the impacts across the backlash are followed (a note).
pub(crate) fn hold_on_drive_flanks(
    m: &Model,
    (field, torque): (&str, f64),
    speed_field: &str,
    coast: bool,
    wheel_inertia: f64,
    top_rpm: f64,
) -> anyhow::Result<()> {
    let holding = m.holding_torque()?;
    if torque < holding {
        if !coast {
            anyhow::bail!(
                "{field} = {torque} N·m is below {holding:.3e} N·m, the torque that holds the wheel (inertia {wheel_inertia:.4e} kg·m²) on the drive flanks up to the run-up's {top_rpm} rpm (the flanks can only push it forward: below this it runs ahead at the tooth changes and, without coast flanks, leaves the mesh); raise the torque, lower {speed_field}, or set multibody.coast_contact = true to follow the impacts across the backlash"
            );
        }
        eprintln!(
            "  run-up: {torque} N·m is below the holding torque {holding:.3e} N·m at the top speed: the wheel will leave the drive flanks at the tooth changes (coast contact is on: impacts across the backlash)"
        );
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn run_up(
    table: &MeshTable,
    inertia: [f64; 2],
    mb: &geometry::scene::MultibodySettings,
    odir: &Path,
    scheme: Scheme,
    control: &dyn Fn(f64) -> StepControl,
    pb: Blank,
    wb: Blank,
    z1: f64,
    friction: f64,
    impact_law: bool,
    coast: Option<&Coast>,
) -> anyhow::Result<RunupSummary> {
    let torque = mb.runup_pinion_torque_nm;
    let mut m = Model {
        table,
        coast,
        inertia,
        damping: 0.0,
        friction,
        drive: runup_drive(mb, table.ratio),
    };
    hold_on_drive_flanks(
        &m,
        ("multibody.runup_pinion_torque_nm", torque),
        "multibody.runup_rpm",
        coast.is_some(),
        inertia[1],
        mb.runup_rpm[0].abs().max(mb.runup_rpm[1].abs()),
    )?;
    let s0 = m.static_state(0.0)?;
    if !impact_law {
        m.damping = m.damping_for_ratio(mb.damping_ratio, &s0)?;
    }
    let mut integ = Integrator::new(scheme, control(mb.runup_max_step_s));
    let t = Instant::now();
    eprintln!(
        "  run-up {}..{} rpm in {} s at {torque} N·m",
        mb.runup_rpm[0], mb.runup_rpm[1], mb.runup_time_s
    );
    let (tr, steps) = record(&m, s0, &mut integ, mb.runup_time_s).context("multibody run-up")?;
    let cpu = t.elapsed().as_secs_f64();
    // Quasi-static TE at the same pinion rotations: the static lag that
    // balances the wheel's load (with friction, the pinion torque that
    // needs includes the mesh losses).
    let statics: Vec<f64> = tr
        .q1
        .iter()
        .map(|&q| m.static_lag(q))
        .collect::<Result<_, _>>()?;
    write_atomic(
        &odir.join("runup.csv"),
        trace_csv(&tr, Some(&statics)).as_bytes(),
    )?;
    // The root tension at the quasi-static lags of the same rotations.
    let root_tension_mpa = match tr.largest_root_tension([f64::NEG_INFINITY, f64::INFINITY]) {
        Some(dynamic) => {
            let mut quasi_static = [0.0f64; 2];
            for (&q, &lag) in tr.q1.iter().zip(&statics) {
                if let Some(r) = table.root_tension_at(q, lag)? {
                    quasi_static = [quasi_static[0].max(r[0]), quasi_static[1].max(r[1])];
                }
            }
            Some(RunupRootTension {
                dynamic: dynamic.map(|v| v * 1e-6),
                quasi_static: quasi_static.map(|v| v * 1e-6),
            })
        }
        None => None,
    };
    let diff: Vec<f64> = tr.te.iter().zip(&statics).map(|(a, b)| a - b).collect();
    let lo = diff.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = diff.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let rpm: Vec<f64> = tr
        .speed
        .iter()
        .map(|v| v * 30.0 / std::f64::consts::PI)
        .collect();
    te_curve(
        &odir.join("runup_te.svg"),
        &format!(
            "Run-up at {torque} N·m, {pb:?} pinion / {wb:?} wheel: dynamic and quasi-static TE"
        ),
        "pinion speed (rpm)",
        "transmission error (µrad)",
        &[
            Series {
                name: "dynamic".into(),
                x: rpm.clone(),
                y: tr.te.iter().map(|v| v * 1e6).collect(),
                dashed: false,
            },
            Series {
                name: "quasi-static".into(),
                x: rpm,
                y: statics.iter().map(|v| v * 1e6).collect(),
                dashed: true,
            },
        ],
    )?;
    // Spectrogram of the wheel bearing force magnitude.
    let mag: Vec<f64> = tr
        .force
        .iter()
        .map(|f| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt())
        .collect();
    runup_spectrogram(
        &odir.join("runup_spectrogram.svg"),
        &format!("Wheel bearing force |F|, run-up at {torque} N·m ({pb:?}/{wb:?})"),
        (&tr.t, &mag),
        mb,
        z1,
        table.ratio,
        wb,
        &[],
    )?;
    let bearing: Vec<[f64; 3]> = tr.force.iter().map(|f| f.map(|c| -c)).collect();
    write_runup_orders(
        &odir.join("runup_orders.json"),
        [pb, wb],
        z1,
        table.ratio,
        (&tr.t, &tr.q1, &bearing),
    )?;
    eprintln!(
        "  run-up: {steps} steps ({} rejected), {:.1} µs/step, dynamic - static TE in [{:.2}, {:.2}] µrad",
        integ.rejected,
        cpu / steps.max(1) as f64 * 1e6,
        lo * 1e6,
        hi * 1e6
    );
    Ok(RunupSummary {
        pinion_torque_nm: torque,
        rpm: mb.runup_rpm,
        sim_time_s: mb.runup_time_s,
        max_step_s: mb.runup_max_step_s,
        steps,
        rejected_steps: integ.rejected,
        cpu_s: cpu,
        cpu_s_per_step: cpu / steps.max(1) as f64,
        te_dynamic_minus_static_urad: [lo * 1e6, hi * 1e6],
        root_tension_mpa,
    })
}
