//! The rattle run of `solver dynamic`: both flank pairs across the
//! backlash, the pinion at a fluctuating speed and the wheel free under its
//! drag torque.
use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::MeshTable;
use crate::multibody::model::Drive;
use crate::multibody::model::Fluctuation;
use crate::multibody::model::Impacts;
use crate::multibody::model::Model;
use crate::multibody::model::State;
use crate::multibody::time_step::integrate;
use crate::multibody::time_step::Integrator;
use crate::multibody::time_step::Scheme;
use crate::multibody::time_step::StepControl;
use anyhow::Context;
use charts::te_curve;
use charts::Series;
use formats::output::write_atomic;
use formats::summaries::RattleSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The rattle run: the pinion at a fluctuating speed, the wheel free under
/// its drag torque, both flank pairs across the backlash; writes
/// `rattle.csv` and `rattle_te.svg` (the lag between the two contact limits).
#[allow(clippy::too_many_arguments)]
pub(crate) fn rattle(
    table: &MeshTable,
    coast: &Coast,
    inertia: [f64; 2],
    damping: f64,
    mb: &geometry::scene::MultibodySettings,
    odir: &Path,
    scheme: Scheme,
    control: &dyn Fn(f64) -> StepControl,
    friction: f64,
) -> anyhow::Result<RattleSummary> {
    let r = table.ratio;
    let w = mb.rattle_pinion_rpm * std::f64::consts::PI / 30.0;
    let m = Model {
        table,
        coast: Some(coast),
        inertia,
        damping,
        friction,
        drive: Drive::PinionFluctuating {
            speed: Fluctuation {
                mean: w,
                amplitude: mb.rattle_speed_fluctuation,
                omega: 2.0 * std::f64::consts::PI * mb.rattle_frequency_hz,
            },
            wheel_torque: mb.rattle_wheel_drag_nm,
        },
    };
    // Start in the middle of the free play, both members at the mean speed.
    let [hi, lo] = coast.contact_lags(table, 0.0)?;
    let theta0 = 0.5 * (hi + lo);
    let s0 = State {
        t: 0.0,
        q: [0.0, -theta0],
        v: [w, r * w],
        a: [0.0; 2],
    };
    let mut integ = Integrator::new(scheme, control(mb.rattle_max_step_s));
    eprintln!(
        "  rattle: pinion {} rpm ± {:.1} % at {} Hz, wheel drag {} N·m, {} s",
        mb.rattle_pinion_rpm,
        100.0 * mb.rattle_speed_fluctuation,
        mb.rattle_frequency_hz,
        mb.rattle_wheel_drag_nm,
        mb.rattle_time_s
    );
    let mut rows = String::from(
        "time_s,pinion_rotation_deg,pinion_rpm,wheel_rpm,te_urad,drive_contact_lag_urad,coast_contact_lag_urad,pinion_mesh_torque_nm,contact\n",
    );
    let (mut t, mut te, mut lim_hi, mut lim_lo) = (vec![], vec![], vec![], vec![]);
    let mut impacts = Impacts::default();
    let mut share = [0.0; 4];
    // Largest contact force on the wheel of the drive and of the coast
    // flanks, N.
    let mut peak = [0.0f64; 2];
    let mut torque = [f64::INFINITY, f64::NEG_INFINITY];
    let mut wheel = [f64::INFINITY, f64::NEG_INFINITY];
    let mut last_t = 0.0;
    let rpm = |x: f64| x * 30.0 / std::f64::consts::PI;
    let clock = crate::cpu_clock::thread_cpu_s();
    let (_, steps) = integrate(&m, s0, &mut integ, mb.rattle_time_s, |s| {
        let c = m.contact(s.q, s.v)?;
        let now = c.touching();
        let norm = |f: [f64; 3]| (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let coast_force = c.coast.map_or([0.0; 3], |cs| cs.force);
        let drive_force: [f64; 3] = std::array::from_fn(|i| c.mesh.force[i] - coast_force[i]);
        peak = [
            peak[0].max(norm(drive_force)),
            peak[1].max(norm(coast_force)),
        ];
        let before = impacts.record(now);
        share[before.slot()] += s.t - last_t;
        last_t = s.t;
        let [dl, cl] = coast.contact_lags(table, s.q[0])?;
        let theta = r * s.q[0] - s.q[1];
        torque = [torque[0].min(c.mesh.grad[0]), torque[1].max(c.mesh.grad[0])];
        wheel = [wheel[0].min(rpm(s.v[1])), wheel[1].max(rpm(s.v[1]))];
        let _ = writeln!(
            rows,
            "{:.8},{:.5},{:.4},{:.4},{:.4},{:.4},{:.4},{:.5},{}",
            s.t,
            s.q[0].to_degrees(),
            rpm(s.v[0]),
            rpm(s.v[1]),
            theta * 1e6,
            dl * 1e6,
            cl * 1e6,
            c.mesh.grad[0],
            now.name()
        );
        t.push(s.t * 1e3);
        te.push(theta * 1e6);
        lim_hi.push(dl * 1e6);
        lim_lo.push(cl * 1e6);
        Ok(())
    })
    .context("multibody rattle run")?;
    let cpu = crate::cpu_clock::thread_cpu_s() - clock;
    write_atomic(&odir.join("rattle.csv"), rows.as_bytes())?;
    te_curve(
        &odir.join("rattle_te.svg"),
        &format!(
            "Rattle: pinion {} rpm ± {:.1} % at {} Hz, free wheel",
            mb.rattle_pinion_rpm,
            100.0 * mb.rattle_speed_fluctuation,
            mb.rattle_frequency_hz
        ),
        "time (ms)",
        "wheel lag (µrad)",
        &[
            Series {
                name: "wheel lag".into(),
                x: t.clone(),
                y: te.clone(),
                dashed: false,
            },
            Series {
                name: "drive contact".into(),
                x: t.clone(),
                y: lim_hi,
                dashed: true,
            },
            Series {
                name: "coast contact".into(),
                x: t,
                y: lim_lo,
                dashed: true,
            },
        ],
    )?;
    let total = share.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    let te_lo = te.iter().copied().fold(f64::INFINITY, f64::min);
    let te_hi = te.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    eprintln!(
        "  rattle: {steps} steps ({} rejected), {} drive and {} coast impacts, {} wedging episodes, mesh torque {:.1}..{:.1} N·m, {:.1} µs/step",
        integ.rejected,
        impacts.drive,
        impacts.coast,
        impacts.wedged,
        torque[0],
        torque[1],
        cpu / steps.max(1) as f64 * 1e6
    );
    Ok(RattleSummary {
        pinion_rpm: mb.rattle_pinion_rpm,
        speed_fluctuation: mb.rattle_speed_fluctuation,
        frequency_hz: mb.rattle_frequency_hz,
        wheel_drag_nm: mb.rattle_wheel_drag_nm,
        sim_time_s: mb.rattle_time_s,
        steps,
        rejected_steps: integ.rejected,
        cpu_s: cpu,
        cpu_s_per_step: cpu / steps.max(1) as f64,
        drive_impacts: impacts.drive,
        coast_impacts: impacts.coast,
        time_share_drive_coast_free: [share[0] / total, share[1] / total, share[2] / total],
        wedging_episodes: impacts.wedged,
        time_share_wedged: share[3] / total,
        peak_force_drive_coast_n: peak,
        mesh_torque_min_max_nm: torque,
        te_min_max_urad: [te_lo, te_hi],
        wheel_rpm_min_max: wheel,
    })
}
