//! The imposed-speed load run of seeds 001 and 002: the pinion at an
//! imposed (ramped) speed, the wheel free under a resisting torque that
//! rises by the cubic STEP; writes `load_run.csv`, `load_run_speed.svg`,
//! `load_run_torque.svg` and `load_run_force.svg` (the seeds' figures of
//! speeds, wheel torque and meshing force), and summarises the steady window over whole
//! mesh cycles: mean wheel speed against the kinematic ratio, mean wheel
//! mesh torque against the load (torque balance), the tangential
//! component of the contact forces at their contact points against 2T/d
//! at the outer pitch circle, meshing force, fluctuation amplitudes (from
//! every step and, where the scene sets an output interval, from samples
//! at it), TE, and the cost per step.

use crate::ltca::mean_ptp;
use crate::multibody::model::{Drive, Model, Ramp, State};
use crate::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use anyhow::Context;
use charts::{te_curve, Series};
use formats::output::write_atomic;
use formats::summaries::{LoadRunSummary, SampledLoadRun};
use geometry::design::PairData;
use geometry::scene::LoadRun;
use std::fmt::Write as _;
use std::path::Path;

/// Samples of a run: time, pinion and wheel speed (rad/s), TE (rad),
/// wheel mesh torque (N·m, all contact forces), mesh force magnitude (N),
/// tangential component of the contact forces on the wheel (N).
#[derive(Debug, Default, Clone)]
pub struct LoadTrace {
    pub t: Vec<f64>,
    pub q1: Vec<f64>,
    pub w1: Vec<f64>,
    pub w2: Vec<f64>,
    pub te: Vec<f64>,
    pub wheel_torque: Vec<f64>,
    pub pinion_torque: Vec<f64>,
    pub force: Vec<f64>,
    pub tangential: Vec<f64>,
}

/// The drive of a load run.
pub fn drive(run: &LoadRun) -> Drive {
    let w = run.pinion_rpm * std::f64::consts::PI / 30.0;
    Drive::PinionSpeedLoadStep {
        speed: Ramp {
            from: if run.pinion_ramp_s > 0.0 { 0.0 } else { w },
            to: w,
            duration: run.pinion_ramp_s,
        },
        wheel_torque: run.wheel_torque_nm,
        rise_s: run.wheel_torque_rise_s,
    }
}

/// Integrates the model `m` (its drive a load run's) from `s0` to `t_end`,
/// recording every step.
pub fn simulate(
    m: &Model,
    s0: State,
    integ: &mut Integrator,
    t_end: f64,
) -> Result<(LoadTrace, usize), crate::SolverError> {
    let r = m.table.ratio;
    let mut tr = LoadTrace::default();
    let (_, steps) = integrate(m, s0, integ, t_end, |s| {
        let c = m.contact(s.q, s.v)?;
        let f = c.mesh.force;
        tr.t.push(s.t);
        tr.q1.push(s.q[0]);
        tr.w1.push(s.v[0]);
        tr.w2.push(s.v[1]);
        tr.te.push(r * s.q[0] - s.q[1]);
        tr.wheel_torque.push(c.force[1]);
        tr.pinion_torque.push(-c.force[0]);
        tr.force
            .push((f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt());
        tr.tangential.push(m.wheel_tangential_force(s.q)?);
        Ok(())
    })?;
    Ok((tr, steps))
}

/// Means over a window of whole mesh cycles.
#[derive(Debug, Clone, Copy)]
pub struct Window {
    pub from: f64,
    pub to: f64,
    pub cycles: usize,
}

/// The window from `from` (s) to the trace's end, trimmed to whole mesh
/// cycles τ of pinion rotation (its ends interpolated in time from the
/// pinion rotation).
pub fn whole_cycles(tr: &LoadTrace, from: f64, tau: f64) -> Option<Window> {
    let q_at = |t: f64| crate::multibody::model::interpolate(&tr.t, &tr.q1, t);
    let q0 = q_at(from);
    let q_end = *tr.q1.last()?;
    let cycles = ((q_end - q0) / tau).floor();
    if cycles < 1.0 {
        return None;
    }
    let to = crate::multibody::model::interpolate(&tr.q1, &tr.t, q0 + cycles * tau);
    Some(Window {
        from,
        to,
        cycles: cycles as usize,
    })
}

/// Time mean of y over [a, b] (trapezoids on the samples, the ends
/// interpolated).
pub fn time_mean(t: &[f64], y: &[f64], a: f64, b: f64) -> f64 {
    let at = |x: f64| crate::multibody::model::interpolate(t, y, x);
    let mut pts: Vec<(f64, f64)> = vec![(a, at(a))];
    pts.extend(
        t.iter()
            .zip(y)
            .filter(|(x, _)| **x > a && **x < b)
            .map(|(x, v)| (*x, *v)),
    );
    pts.push((b, at(b)));
    let area: f64 = pts
        .windows(2)
        .map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0))
        .sum();
    area / (b - a)
}

/// Buckets of a chart's time axis: each keeps its samples' minimum and
/// maximum (in time order), so the peaks survive.
const CHART_BUCKETS: usize = 4000;

/// The min/max envelope of y(t) over `buckets` equal time buckets (the
/// samples themselves when there are fewer than two per bucket).
pub fn envelope(t: &[f64], y: &[f64], buckets: usize) -> (Vec<f64>, Vec<f64>) {
    if t.len() <= 2 * buckets || t.len() < 2 {
        return (t.to_vec(), y.to_vec());
    }
    let (t0, t1) = (t[0], t[t.len() - 1]);
    let width = (t1 - t0) / buckets as f64;
    let (mut x_out, mut y_out) = (Vec::new(), Vec::new());
    let mut k = 0;
    while k < t.len() {
        let b = (((t[k] - t0) / width) as usize).min(buckets - 1);
        let mut end = k;
        while end < t.len() && (((t[end] - t0) / width) as usize).min(buckets - 1) == b {
            end += 1;
        }
        let (mut lo, mut hi) = (k, k);
        for i in k..end {
            if y[i] < y[lo] {
                lo = i;
            }
            if y[i] > y[hi] {
                hi = i;
            }
        }
        for i in if lo <= hi { [lo, hi] } else { [hi, lo] } {
            x_out.push(t[i]);
            y_out.push(y[i]);
        }
        k = end;
    }
    (x_out, y_out)
}

/// Mean and largest |y − reference| over the samples in [a, b].
fn fluctuation(t: &[f64], y: &[f64], reference: f64, a: f64, b: f64) -> (f64, f64) {
    let d: Vec<f64> = t
        .iter()
        .zip(y)
        .filter(|(x, _)| **x >= a && **x <= b)
        .map(|(_, v)| (v - reference).abs())
        .collect();
    let n = d.len().max(1) as f64;
    (
        d.iter().sum::<f64>() / n,
        d.iter().copied().fold(0.0, f64::max),
    )
}

/// The steady window's statistics from samples every `dt` seconds (at
/// t = k dt inside the window, each linearly interpolated between the
/// integrator's steps): wheel speed against `kinematic` (rad/s), and the
/// tangential force against its sampled mean.
pub fn sampled(tr: &LoadTrace, dt: f64, kinematic: f64, w: Window) -> SampledLoadRun {
    let first = (w.from / dt).ceil() as usize;
    let times: Vec<f64> = (first..)
        .map(|k| k as f64 * dt)
        .take_while(|&t| t <= w.to)
        .collect();
    let at = |y: &[f64]| -> Vec<f64> {
        times
            .iter()
            .map(|&t| crate::multibody::model::interpolate(&tr.t, y, t))
            .collect()
    };
    let (w2, ft) = (at(&tr.w2), at(&tr.tangential));
    let n = times.len().max(1) as f64;
    let mean = |v: &[f64]| v.iter().sum::<f64>() / n;
    let spread = |v: &[f64], c: f64| {
        let d: Vec<f64> = v.iter().map(|x| (x - c).abs()).collect();
        (mean(&d), d.iter().copied().fold(0.0, f64::max))
    };
    let ft_mean = mean(&ft);
    let (w_fl, w_max) = spread(&w2, kinematic);
    let (f_fl, f_max) = spread(&ft, ft_mean);
    SampledLoadRun {
        interval_s: dt,
        samples: times.len(),
        wheel_speed_mean_deg_s: mean(&w2).to_degrees(),
        wheel_speed_fluctuation_mean_deg_s: w_fl.to_degrees(),
        wheel_speed_fluctuation_max_deg_s: w_max.to_degrees(),
        tangential_force_mean_n: ft_mean,
        tangential_force_max_n: ft.iter().copied().fold(0.0, f64::max),
        tangential_force_fluctuation_mean_n: f_fl,
        tangential_force_fluctuation_max_n: f_max,
    }
}

/// Runs the load run with model `m` (drive from [`drive`]) and writes its
/// files into `odir`.
#[allow(clippy::too_many_arguments)]
pub fn run(
    m: &Model,
    s0: State,
    run: &LoadRun,
    pair: &PairData,
    scheme: Scheme,
    control: StepControl,
    odir: &Path,
    label: &str,
) -> anyhow::Result<LoadRunSummary> {
    let mut integ = Integrator::new(scheme, control);
    let clock = crate::cpu_clock::thread_cpu_s();
    let (tr, steps) = simulate(m, s0, &mut integ, run.time_s).context("multibody load run")?;
    let cpu = crate::cpu_clock::thread_cpu_s() - clock;
    let r = m.table.ratio;
    let tau = pair.mesh_cycle();
    let w = Window::checked(whole_cycles(&tr, run.steady_from_s, tau), run)?;
    let deg = |x: f64| x.to_degrees();
    let kinematic = r * run.pinion_rpm * std::f64::consts::PI / 30.0;
    let w2_mean = time_mean(&tr.t, &tr.w2, w.from, w.to);
    let (w2_fl_mean, w2_fl_max) = fluctuation(&tr.t, &tr.w2, kinematic, w.from, w.to);
    let torque_mean = time_mean(&tr.t, &tr.wheel_torque, w.from, w.to);
    let pinion_mean = time_mean(&tr.t, &tr.pinion_torque, w.from, w.to);
    let power = |tq: &[f64], sp: &[f64]| -> f64 {
        let p: Vec<f64> = tq.iter().zip(sp).map(|(a, b)| a * b).collect();
        time_mean(&tr.t, &p, w.from, w.to)
    };
    let efficiency = power(&tr.wheel_torque, &tr.w2) / power(&tr.pinion_torque, &tr.w1);
    let load = run.wheel_torque_nm;
    // Outer pitch radius of the wheel (the seeds' d/2), and the mean point's.
    let whl = &pair.members[1];
    let r_outer = pair.outer_cone_distance() * whl.pitch_angle.sin();
    let r_mean = pair.mean_cone_distance * whl.pitch_angle.sin();
    let ft = &tr.tangential;
    let ft_mean = time_mean(&tr.t, ft, w.from, w.to);
    let (ft_fl_mean, ft_fl_max) = fluctuation(&tr.t, ft, ft_mean, w.from, w.to);
    let theory = load / r_outer;
    let in_window = |v: &[f64]| -> Vec<f64> {
        tr.t.iter()
            .zip(v)
            .filter(|(x, _)| **x >= w.from && **x <= w.to)
            .map(|(_, y)| *y)
            .collect()
    };
    let force_mean = time_mean(&tr.t, &tr.force, w.from, w.to);
    let force_max = in_window(&tr.force).into_iter().fold(0.0, f64::max);
    let (te_mean, te_ptp) = mean_ptp(&in_window(&tr.te));
    let normal_theory = load / (r_mean * pair.pressure_angle[0].cos() * pair.spiral_angle.cos());
    write_csv(&tr, run, r, odir)?;
    write_charts(m, &tr, label, r, r_outer, odir)?;
    eprintln!(
        "  load run ({label}): {steps} steps ({} rejected), {:.1} µs/step; wheel {:.3} deg/s vs {:.3} kinematic, torque {:.3} vs {load} N·m, efficiency {efficiency:.5}, |F| mean {:.0} N max {:.0} N",
        integ.rejected,
        cpu / steps.max(1) as f64 * 1e6,
        deg(w2_mean),
        deg(kinematic),
        torque_mean,
        force_mean,
        force_max
    );
    Ok(LoadRunSummary {
        pinion_rpm: run.pinion_rpm,
        pinion_ramp_s: run.pinion_ramp_s,
        wheel_torque_nm: load,
        wheel_torque_rise_s: run.wheel_torque_rise_s,
        sim_time_s: run.time_s,
        steps,
        rejected_steps: integ.rejected,
        cpu_s: cpu,
        cpu_s_per_step: cpu / steps.max(1) as f64,
        window_s: [w.from, w.to],
        window_mesh_cycles: w.cycles,
        wheel_speed_mean_deg_s: deg(w2_mean),
        wheel_speed_kinematic_deg_s: deg(kinematic),
        wheel_speed_error: w2_mean / kinematic - 1.0,
        wheel_speed_fluctuation_mean_deg_s: deg(w2_fl_mean),
        wheel_speed_fluctuation_max_deg_s: deg(w2_fl_max),
        wheel_mesh_torque_mean_nm: torque_mean,
        torque_balance_error: if load > 0.0 {
            torque_mean / load - 1.0
        } else {
            torque_mean
        },
        pinion_mesh_torque_mean_nm: pinion_mean,
        mesh_efficiency: efficiency,
        tangential_force_mean_n: ft_mean,
        tangential_force_max_n: in_window(ft).into_iter().fold(0.0, f64::max),
        tangential_force_theory_n: theory,
        tangential_force_error: if load > 0.0 {
            ft_mean / theory - 1.0
        } else {
            ft_mean
        },
        tangential_force_error_of_mean: if ft_mean > 0.0 {
            (ft_mean - theory) / ft_mean
        } else {
            0.0
        },
        tangential_force_fluctuation_mean_n: ft_fl_mean,
        tangential_force_fluctuation_max_n: ft_fl_max,
        contact_radius_mm: if ft_mean > 0.0 {
            torque_mean / ft_mean * 1e3
        } else {
            0.0
        },
        outer_pitch_radius_mm: r_outer * 1e3,
        sampled: run
            .output_interval_s
            .map(|dt| sampled(&tr, dt, kinematic, w)),
        mesh_force_mean_n: force_mean,
        mesh_force_max_n: force_max,
        mesh_force_theory_n: normal_theory,
        te_mean_urad: te_mean * 1e6,
        te_ptp_urad: te_ptp * 1e6,
    })
}

/// `load_run.csv`: speeds, TE, wheel mesh torque and forces of the run `tr`
/// (`r` the ratio), rows at most every `max_step_s` of `run`.
fn write_csv(tr: &LoadTrace, run: &LoadRun, r: f64, odir: &Path) -> anyhow::Result<()> {
    let deg = |x: f64| x.to_degrees();
    let ft = &tr.tangential;
    let mut csv = String::from(
        "time_s,pinion_speed_deg_s,wheel_speed_deg_s,wheel_speed_kinematic_deg_s,te_urad,wheel_mesh_torque_nm,tangential_force_n,mesh_force_n\n",
    );
    // Rows at most every max_step_s (the step control halves steps where
    // the contact changes; the summary uses every step).
    let mut next = f64::NEG_INFINITY;
    for (k, ftk) in ft.iter().enumerate() {
        if tr.t[k] < next && k + 1 < ft.len() {
            continue;
        }
        next = tr.t[k] + run.max_step_s * (1.0 - 1e-9);
        let _ = writeln!(
            csv,
            "{:.7},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4}",
            tr.t[k],
            deg(tr.w1[k]),
            deg(tr.w2[k]),
            deg(r * tr.w1[k]),
            tr.te[k] * 1e6,
            tr.wheel_torque[k],
            ftk,
            tr.force[k]
        );
    }
    write_atomic(&odir.join("load_run.csv"), csv.as_bytes())?;
    Ok(())
}

/// The run's charts: pinion and wheel speed, wheel mesh torque against the
/// applied load, meshing and tangential force (`r_outer` the wheel's outer
/// pitch radius, m).
fn write_charts(
    m: &Model,
    tr: &LoadTrace,
    label: &str,
    r: f64,
    r_outer: f64,
    odir: &Path,
) -> anyhow::Result<()> {
    let deg = |x: f64| x.to_degrees();
    let ft = &tr.tangential;
    let series = |name: &str, y: Vec<f64>, dashed: bool| {
        let (x, y) = envelope(&tr.t, &y, CHART_BUCKETS);
        Series {
            name: name.into(),
            x,
            y,
            dashed,
        }
    };
    te_curve(
        &odir.join("load_run_speed.svg"),
        &format!("{label}: pinion and wheel speed"),
        "time (s)",
        "speed (deg/s)",
        &[
            series("pinion", tr.w1.iter().map(|x| deg(*x)).collect(), false),
            series("wheel", tr.w2.iter().map(|x| deg(*x)).collect(), false),
            series(
                "wheel, kinematic",
                tr.w1.iter().map(|x| deg(r * x)).collect(),
                true,
            ),
        ],
    )?;
    let applied: Vec<f64> = tr.t.iter().map(|&t| -m.drive.torques(t)[1]).collect();
    te_curve(
        &odir.join("load_run_torque.svg"),
        &format!("{label}: wheel mesh torque and applied load"),
        "time (s)",
        "torque (N·m)",
        &[
            series("wheel mesh torque", tr.wheel_torque.clone(), false),
            series("applied load", applied.clone(), true),
        ],
    )?;
    te_curve(
        &odir.join("load_run_force.svg"),
        &format!("{label}: meshing force and its tangential component on the wheel"),
        "time (s)",
        "force (N)",
        &[
            series("meshing force", tr.force.clone(), false),
            series("tangential force", ft.clone(), false),
            series(
                "2T/d (applied load over the outer pitch radius)",
                applied.iter().map(|x| x / r_outer).collect(),
                true,
            ),
        ],
    )?;
    Ok(())
}

impl Window {
    fn checked(w: Option<Window>, run: &LoadRun) -> anyhow::Result<Window> {
        w.with_context(|| {
            format!(
                "multibody.load_run: less than one mesh cycle between steady_from_s = {} s and time_s = {} s",
                run.steady_from_s, run.time_s
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn envelope_keeps_each_buckets_extremes_in_time_order() {
        let t: Vec<f64> = (0..10_000).map(|k| k as f64 * 1e-4).collect();
        let mut y: Vec<f64> = t.iter().map(|x| (50.0 * x).sin()).collect();
        y[4321] = 7.0;
        y[8765] = -9.0;
        let (x, v) = envelope(&t, &y, 100);
        assert!(x.len() <= 200 && x.windows(2).all(|w| w[1] > w[0]));
        assert!(v.contains(&7.0) && v.contains(&-9.0));
        // Few samples: unchanged.
        assert_eq!(envelope(&t[..150], &y[..150], 100).0, t[..150].to_vec());
    }

    #[test]
    fn time_mean_of_a_line_is_its_midpoint_value() {
        let t = [0.0, 0.1, 0.35, 0.4, 1.0];
        let y: Vec<f64> = t.iter().map(|x| 2.0 + 3.0 * x).collect();
        assert!((time_mean(&t, &y, 0.05, 0.9) - (2.0 + 3.0 * 0.475)).abs() < 1e-12);
    }

    /// A sine of amplitude A about the kinematic speed: sampled densely the
    /// mean |deviation| is 2A/π and the largest A; sampled once per period
    /// (here in phase with its zero) it shows no fluctuation at all, as a
    /// simulation that writes results only that often would.
    #[test]
    fn sampling_a_sine_densely_gives_its_mean_deviation_and_once_per_period_hides_it() {
        let (kin, amp, period) = (10.0, 0.5, 0.005);
        let t: Vec<f64> = (0..=100_000).map(|k| k as f64 * 1e-5).collect();
        let w2: Vec<f64> = t
            .iter()
            .map(|x| kin + amp * (2.0 * std::f64::consts::PI * x / period).sin())
            .collect();
        let tr = LoadTrace {
            tangential: w2.iter().map(|x| 1000.0 * x).collect(),
            w2,
            t,
            ..LoadTrace::default()
        };
        let w = Window {
            from: 0.2,
            to: 1.0,
            cycles: 160,
        };
        let dense = sampled(&tr, 1.25e-4, kin, w);
        assert_eq!(dense.samples, 6401);
        let mean_dev = dense.wheel_speed_fluctuation_mean_deg_s.to_radians();
        // 40 samples a period: (1/20) cot(π/40) A = 0.6353 A against 2A/π.
        assert!((mean_dev - 2.0 * amp / std::f64::consts::PI).abs() < 3e-3 * amp);
        assert!((dense.wheel_speed_fluctuation_max_deg_s.to_radians() - amp).abs() < 1e-3 * amp);
        assert!((dense.tangential_force_mean_n - 1000.0 * kin).abs() < 1e-6 * kin * 1000.0);
        let aliased = sampled(&tr, period, kin, w);
        assert_eq!(aliased.samples, 161);
        assert!(aliased.wheel_speed_fluctuation_max_deg_s.to_radians() < 1e-9);
        assert!(aliased.tangential_force_fluctuation_max_n < 1e-6);
    }
}
