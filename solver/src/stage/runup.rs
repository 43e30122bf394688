//! The run-up's drive and its outputs, shared by the rigid-bearing
//! ([`crate::stage::dynamic`]) and compliant-bearing
//! ([`crate::stage::compliant`]) multibody stages: the pinion's speed ramp,
//! the spectrogram of a bearing force over the pinion speed, and the order
//! analysis in the pinion's angle domain (`runup_orders.json`).

use crate::multibody::model::{Drive, Ramp};
use crate::signal::spectrum::{plot, resample, stft, OrderLine};
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
pub(crate) fn runup_spectrogram(
    path: &Path,
    title: &str,
    series: (&[f64], &[f64]),
    mb: &geometry::scene::MultibodySettings,
    z1: f64,
    ratio: f64,
    wb: Blank,
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
    plot(path, title, &spec, &hz, &orders)?;
    Ok(())
}
