//! Run time against error of the multibody integration: the
//! maximum step and the TE tolerance of the step control, the others at the
//! scene's values, generalized-α with the scene's ρ∞ and mesh damping
//! ratio, frictionless, standard blanks, the contact-element table of one
//! mesh cycle at [`PROBE_NM`]:
//!
//! - quasi-static: the wheel at `multibody.quasi_static_wheel_rpm`, the
//!   pinion loaded with [`PROBE_NM`], over one mesh cycle, against the
//!   loaded TCA at the same positions (the scene's rotation step):
//!   |mean TE − LTCA| / LTCA (secondary: peak-to-peak), %;
//! - run-up: the pinion ramped from 90 % to 100 % of the top run-up speed
//!   in [`RUNUP_WINDOW_S`] against [`PROBE_NM`] at the wheel, from the
//!   static state, against one run with a 10× smaller step than the
//!   smallest studied and the tightest studied tolerance:
//!   max |TE(t) − TE_ref(t)| / mean TE_ref, %.
//!
//! Cost: thread CPU of the integration (the table, shared, not counted).

use crate::studies::stress::{probe_table, PROBE_NM};
use crate::studies::tradeoff_stage::{rel_pct, StageTradeoff, TradeoffPoint};
use geometry::pair::{FlankPair, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::RollSurface;
use solver::cpu_clock::timed;
use solver::element::compliance::PairCompliance;
use solver::ltca::{mean_ptp, run as run_sweep, Sweep};
use solver::multibody::mesh_table::MeshTable;
use solver::multibody::model::{interpolate, wheel_driven, Drive, Model, Ramp, State};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use solver::stage::context::scene_sweep;
use solver::SolverError;

/// Quasi-static maximum steps, s.
pub const QS_STEPS_S: [f64; 4] = [1e-2, 1e-3, 1e-4, 1e-5];
/// Run-up maximum steps, s.
pub const RUNUP_STEPS_S: [f64; 4] = [1e-3, 1e-4, 3e-5, 1e-5];
/// TE tolerances, µrad.
pub const TOLERANCES_URAD: [f64; 4] = [1.0, 1e-1, 1e-2, 1e-3];
/// Simulated time of the run-up window, s.
pub const RUNUP_WINDOW_S: f64 = 0.01;

const QS_STEP: &str = "10 rpm: max step (s)";
const QS_TOL: &str = "10 rpm: TE tolerance (µrad)";
const RU_STEP: &str = "run-up: max step (s)";
const RU_TOL: &str = "run-up: TE tolerance (µrad)";

/// (times, pinion rotations, TEs) of a run.
type Trace = (Vec<f64>, Vec<f64>, Vec<f64>);

fn trace(
    m: &Model,
    s0: State,
    scheme: Scheme,
    max_step: f64,
    tol_urad: f64,
    t_end: f64,
) -> Result<(Trace, f64), SolverError> {
    let r = m.table.ratio;
    let mut integ = Integrator::new(
        scheme,
        StepControl {
            max_step,
            min_step: max_step * 1e-6,
            tolerance: tol_urad * 1e-6,
        },
    );
    let mut tr: Trace = (Vec::new(), Vec::new(), Vec::new());
    let (res, cpu) = timed(|| {
        integrate(m, s0, &mut integ, t_end, |s| {
            tr.0.push(s.t);
            tr.1.push(s.q[0]);
            tr.2.push(r * s.q[0] - s.q[1]);
            Ok(())
        })
    });
    res?;
    Ok((tr, cpu))
}

struct Setup<'a> {
    scene: &'a LoadedScene,
    table: MeshTable,
    inertia: [f64; 2],
    scheme: Scheme,
}

impl Setup<'_> {
    fn quasi_static(
        &self,
        max_step: f64,
        tol: f64,
        ltca: &[f64],
        step: f64,
    ) -> anyhow::Result<(f64, f64, f64)> {
        let mb = &self.scene.scene.multibody;
        let w2 = mb.quasi_static_wheel_rpm * std::f64::consts::PI / 30.0;
        let (m, s0) = wheel_driven(
            &self.table,
            self.inertia,
            w2,
            PROBE_NM,
            mb.damping_ratio,
            0.0,
        )?;
        let range = step * (ltca.len() - 1) as f64;
        let t_end = (range + 2.0 * step) / (w2 / self.table.ratio);
        let ((_, q1, te), cpu) = trace(&m, s0, self.scheme, max_step, tol, t_end)?;
        let sampled: Vec<f64> = (0..ltca.len())
            .map(|k| interpolate(&q1, &te, step * k as f64))
            .collect();
        let (m1, p1) = mean_ptp(&sampled);
        let (m0, p0) = mean_ptp(ltca);
        Ok((cpu, rel_pct(m1, m0).abs(), rel_pct(p1, p0).abs()))
    }

    fn runup_model(&self) -> Result<(Model<'_>, State), SolverError> {
        let mb = &self.scene.scene.multibody;
        let top = mb.runup_rpm[0].abs().max(mb.runup_rpm[1].abs()) * std::f64::consts::PI / 30.0;
        let mut m = Model {
            table: &self.table,
            coast: None,
            inertia: self.inertia,
            damping: 0.0,
            friction: 0.0,
            drive: Drive::PinionSpeed {
                speed: Ramp {
                    from: 0.9 * top,
                    to: top,
                    duration: RUNUP_WINDOW_S,
                },
                wheel_torque: PROBE_NM / self.table.ratio,
            },
        };
        let s0 = m.static_state(0.0)?;
        m.damping = m.damping_for_ratio(mb.damping_ratio, &s0)?;
        Ok((m, s0))
    }

    fn runup(&self, max_step: f64, tol: f64, reference: &Trace) -> anyhow::Result<(f64, f64)> {
        let (m, s0) = self.runup_model()?;
        let ((t, _, te), cpu) = trace(&m, s0, self.scheme, max_step, tol, RUNUP_WINDOW_S)?;
        let mean = reference.2.iter().map(|x| x.abs()).sum::<f64>() / reference.2.len() as f64;
        let worst = reference
            .0
            .iter()
            .zip(&reference.2)
            .map(|(&ti, &r)| (interpolate(&t, &te, ti) - r).abs())
            .fold(0.0f64, f64::max);
        Ok((cpu, worst / mean * 100.0))
    }
}

pub fn run(
    scene: &LoadedScene,
    g: &PairGeometry,
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    inertia: [f64; 2],
) -> anyhow::Result<[StageTradeoff; 2]> {
    let sc = &scene.scene;
    let mb = &sc.multibody;
    let top = mb.runup_rpm[0].abs().max(mb.runup_rpm[1].abs());
    let mut qs = StageTradeoff::new(
        "multibody_quasi_static",
        &format!("Multibody, {} rpm: thread CPU against the error to the LTCA ({PROBE_NM} N·m)", mb.quasi_static_wheel_rpm),
        "thread CPU of the integration (s)",
        &format!("|mean TE − LTCA| / LTCA over one mesh cycle at the scene's rotation step (secondary: peak-to-peak), wheel at {} rpm", mb.quasi_static_wheel_rpm),
    );
    let mut ru = StageTradeoff::new(
        "multibody_runup",
        &format!("Multibody run-up: thread CPU against the error to a 10× smaller step ({PROBE_NM} N·m)"),
        "thread CPU of the integration (s)",
        &format!("max |TE(t) − TE_ref(t)| / mean TE_ref over the pinion's ramp from 90 to 100 % of {top} rpm in {RUNUP_WINDOW_S} s; the reference with a 10× smaller step than the smallest studied and the tightest studied tolerance"),
    );
    let table = probe_table(scene, g, fp, rs, pc, PROBE_NM)?;
    let setup = Setup {
        scene,
        table,
        inertia,
        scheme: Scheme::GeneralizedAlpha {
            rho_inf: mb.rho_inf,
        },
    };
    // The LTCA at the scene's rotation step over one mesh cycle.
    let base = scene_sweep(scene, g, Blank::Standard);
    let positions = (g.data.mesh_cycle() / base.step).round() as usize + 1;
    let sweep = Sweep {
        positions,
        friction: 0.0,
        ..base
    };
    let res = run_sweep(fp, rs, pc, &sweep, &[PROBE_NM])?;
    let ltca: Vec<f64> = res.iter().map(|p| p.loads[0].te).collect();
    let with = |v: &[f64], d: f64| {
        let mut v = v.to_vec();
        if !v.contains(&d) {
            v.push(d);
            v.sort_by(|a, b| b.total_cmp(a));
        }
        v
    };
    let tol0 = mb.te_tolerance_urad;
    let add = |st: &mut StageTradeoff,
               par: &str,
               v: f64,
               d: bool,
               r: anyhow::Result<(f64, f64, Option<f64>)>| {
        let label = format!("{v:e}");
        match r {
            Ok((cpu, e, e2)) => st.push(TradeoffPoint {
                parameter: par.into(),
                setting: label,
                value: v,
                cpu_s: cpu,
                error_pct: e,
                secondary_error_pct: e2,
                is_default: d,
            }),
            Err(e) => st.skip(par, &label, format!("{e:#}")),
        }
    };
    let h0 = mb.quasi_static_max_step_s;
    for h in with(&QS_STEPS_S, h0) {
        let r = setup
            .quasi_static(h, tol0, &ltca, sweep.step)
            .map(|(c, e, p)| (c, e, Some(p)));
        add(&mut qs, QS_STEP, h, h == h0, r);
    }
    for tol in with(&TOLERANCES_URAD, tol0) {
        let r = setup
            .quasi_static(h0, tol, &ltca, sweep.step)
            .map(|(c, e, p)| (c, e, Some(p)));
        add(&mut qs, QS_TOL, tol, tol == tol0, r);
    }
    // Run-up, against one reference run.
    let h0 = mb.runup_max_step_s;
    let steps = with(&RUNUP_STEPS_S, h0);
    let tols = with(&TOLERANCES_URAD, tol0);
    let h_ref = steps.iter().copied().fold(f64::INFINITY, f64::min) / 10.0;
    let tol_ref = tols.iter().copied().fold(f64::INFINITY, f64::min);
    let reference = setup
        .runup_model()
        .map_err(anyhow::Error::from)
        .and_then(|(m, s0)| Ok(trace(&m, s0, setup.scheme, h_ref, tol_ref, RUNUP_WINDOW_S)?.0));
    match reference {
        Err(e) => ru.skip(
            RU_STEP,
            "all",
            format!("reference run-up ({h_ref:e} s): {e:#}"),
        ),
        Ok(reference) => {
            for h in steps {
                let r = setup.runup(h, tol0, &reference).map(|(c, e)| (c, e, None));
                add(&mut ru, RU_STEP, h, h == h0, r);
            }
            for tol in tols {
                let r = setup.runup(h0, tol, &reference).map(|(c, e)| (c, e, None));
                add(&mut ru, RU_TOL, tol, tol == tol0, r);
            }
        }
    }
    qs.finish();
    ru.finish();
    Ok([qs, ru])
}
