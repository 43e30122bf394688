//! A multibody run recorded at every step (time, pinion rotation and
//! speed, TE, mesh torques, wheel bearing force and, where the table has
//! it, the loaded teeth's largest root tension) and its CSV: the 10 rpm
//! runs of [`crate::stage::dynamic`] and the run-up of
//! [`crate::stage::runup`].

use crate::multibody::model::{Model, State};
use crate::multibody::time_step::{integrate, Integrator};
use formats::columns::{PINION_ROTATION_DEG, PINION_RPM, TE_URAD, TIME_S};
use std::fmt::Write as _;

/// Every step of a run.
pub(crate) struct Trace {
    pub(crate) t: Vec<f64>,
    pub(crate) q1: Vec<f64>,
    pub(crate) speed: Vec<f64>,
    pub(crate) te: Vec<f64>,
    pub(crate) torque: Vec<[f64; 2]>,
    pub(crate) force: Vec<[f64; 3]>,
    /// The loaded teeth's largest root tension [pinion, wheel], Pa, from
    /// the table ([`crate::multibody::mesh_table::MeshTable::root_tension_at`]);
    /// empty when the table has none.
    pub(crate) root: Vec<[f64; 2]>,
}

impl Trace {
    /// The largest root tension [pinion, wheel] over the steps whose pinion
    /// rotation lies in `q1_range`, Pa; None without root tension.
    pub(crate) fn largest_root_tension(&self, q1_range: [f64; 2]) -> Option<[f64; 2]> {
        if self.root.is_empty() {
            return None;
        }
        Some(
            self.q1
                .iter()
                .zip(&self.root)
                .filter(|(q, _)| **q >= q1_range[0] && **q <= q1_range[1])
                .fold([0.0f64; 2], |m, (_, r)| [m[0].max(r[0]), m[1].max(r[1])]),
        )
    }
}

/// Integrates to `t_end`, recording every step.
pub(crate) fn record(
    m: &Model,
    s0: State,
    integ: &mut Integrator,
    t_end: f64,
) -> Result<(Trace, usize), crate::SolverError> {
    let r = m.table.ratio;
    let mut tr = Trace {
        t: vec![],
        q1: vec![],
        speed: vec![],
        te: vec![],
        torque: vec![],
        force: vec![],
        root: vec![],
    };
    let (_, steps) = integrate(m, s0, integ, t_end, |s| {
        let (ms, _) = m.mesh(s.q)?;
        tr.t.push(s.t);
        tr.q1.push(s.q[0]);
        tr.speed.push(s.v[0]);
        tr.te.push(r * s.q[0] - s.q[1]);
        tr.torque.push([ms.grad[0], -ms.grad[1]]);
        tr.force.push(ms.force);
        if let Some(r) = m.table.root_tension_at(s.q[0], r * s.q[0] - s.q[1])? {
            tr.root.push(r);
        }
        Ok(())
    })?;
    Ok((tr, steps))
}

pub(crate) fn trace_csv(tr: &Trace, statics: Option<&[f64]>) -> String {
    let mut out = [
        TIME_S,
        PINION_ROTATION_DEG,
        PINION_RPM,
        TE_URAD,
        "pinion_mesh_torque_nm,wheel_mesh_torque_nm,wheel_bearing_fx_n,wheel_bearing_fy_n,wheel_bearing_fz_n",
    ]
    .join(",");
    if statics.is_some() {
        out.push_str(",te_quasi_static_urad");
    }
    if !tr.root.is_empty() {
        out.push_str(",pinion_root_tension_mpa,wheel_root_tension_mpa");
    }
    out.push('\n');
    for k in 0..tr.t.len() {
        // Rigid bearings: the wheel's bearing carries the contact force.
        let f = tr.force[k].map(|c| -c);
        let _ = write!(
            out,
            "{:.7},{:.5},{:.4},{:.5},{:.5},{:.5},{:.4},{:.4},{:.4}",
            tr.t[k],
            tr.q1[k].to_degrees(),
            tr.speed[k] * 30.0 / std::f64::consts::PI,
            tr.te[k] * 1e6,
            tr.torque[k][0],
            tr.torque[k][1],
            f[0],
            f[1],
            f[2]
        );
        if let Some(st) = statics {
            let _ = write!(out, ",{:.5}", st[k] * 1e6);
        }
        if let Some(r) = tr.root.get(k) {
            let _ = write!(out, ",{:.3},{:.3}", r[0] * 1e-6, r[1] * 1e-6);
        }
        out.push('\n');
    }
    out
}
