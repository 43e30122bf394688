//! `solver dynamic <scene>`: the multibody runs of every pinion × wheel blank
//! of a scene, to `<out>/<scene>/multibody/<pinion>_<wheel>/`:
//! - `quasi_static_<T>nm.csv` per scene torque: the white paper's 10 rpm run
//!   (imposed wheel speed, torque on the pinion) over the LTCA's rotation
//!   range: time, pinion rotation, TE, mesh torques, bearing forces;
//! - `runup.csv`, `runup_te.svg` (dynamic against quasi-static TE over the
//!   pinion speed, the white paper's Figure 13) and `runup_spectrogram.svg`
//!   (the wheel bearing force with the mesh orders) for the blanks that run up;
//! - `summary.json`: per torque TE mean and peak-to-peak, steps and CPU time.
//!
//! `<out>/<scene>/multibody/` is written as one set
//! ([`formats::result_set`]): into a staging sibling, put in place whole
//! with its `run.json` once every blank has run; a run that fails leaves
//! the previous set as it was.
//!
//! Bearings are rigid: the bearing force of each member is the reaction to
//! the contact force (the wheel's is reported; the pinion's is its negative).
use crate::multibody::impact_law::{Friction, ImpactLaw};
use crate::stage::context::{analysis_enabled, LoadedPair, StageContext};
use crate::stage::runup::runup_drive;
use crate::stage::runup::runup_spectrogram;
use crate::stage::runup::write_runup_orders;
use formats::summaries::ImpactLawSummary;
use geometry::utca::RollSurface;

use crate::ltca::mean_ptp;
use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::{MeshTable, TableSpec};
use crate::multibody::model::{
    interpolate, wheel_driven, Drive, Fluctuation, Impacts, Model, Ramp, State,
};
use crate::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use crate::stage::context::coast_compliance;
use anyhow::Context;
use charts::{te_curve, Series};
use formats::columns::{PINION_ROTATION_DEG, PINION_RPM, TE_URAD, TIME_S};
use formats::manifest::Manifest;
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use geometry::pair::pinion_direction;
use geometry::scene::{Blank, ForceLaw, LoadedScene};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

pub use formats::summaries::{DynamicSummary, QuasiStaticSummary, RattleSummary, RunupSummary};

struct Trace {
    t: Vec<f64>,
    q1: Vec<f64>,
    speed: Vec<f64>,
    te: Vec<f64>,
    torque: Vec<[f64; 2]>,
    force: Vec<[f64; 3]>,
}

/// Integrates to `t_end`, recording every step.
fn record(
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
    };
    let (_, steps) = integrate(m, s0, integ, t_end, |s| {
        let (ms, _) = m.mesh(s.q)?;
        tr.t.push(s.t);
        tr.q1.push(s.q[0]);
        tr.speed.push(s.v[0]);
        tr.te.push(r * s.q[0] - s.q[1]);
        tr.torque.push([ms.grad[0], -ms.grad[1]]);
        tr.force.push(ms.force);
        Ok(())
    })?;
    Ok((tr, steps))
}

fn trace_csv(tr: &Trace, statics: Option<&[f64]>) -> String {
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
        out.push('\n');
    }
    out
}

/// Runs the multibody analyses of the scene.
pub fn run(scene: &LoadedScene, meshes: &Path, out: &Path) -> anyhow::Result<Vec<DynamicSummary>> {
    if !analysis_enabled(
        scene,
        scene.scene.analyses.multibody,
        "multibody",
        "no multibody runs",
    ) {
        return Ok(Vec::new());
    }
    let sc = &scene.scene;
    let mb = &sc.multibody;
    // Taken before any work: refuses an output that another run is writing
    // or that cannot be written.
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("multibody"),
        &format!("solver dynamic {}", scene.path.display()),
    )?;
    let ctx = StageContext::new(scene, meshes)?;
    let side = ctx.side();
    let rs = ctx.roll_surface(side)?;
    let coast_rs = if mb.coast_contact {
        Some(ctx.roll_surface(side.other())?)
    } else {
        None
    };
    let impact = match mb.force_law {
        ForceLaw::Element => None,
        ForceLaw::Impact => Some(crate::multibody::impact_law::from_settings(
            &ctx.g.data,
            &mb.impact,
        )),
    };
    let mut all = Vec::new();
    ctx.for_each_pair(|pair| {
        ctx.record_inputs(&mut set, pair.blanks, coast_rs.is_some())?;
        let summary = blank_pair(&ctx, &pair, &rs, coast_rs.as_ref(), impact.as_ref(), &set)?;
        all.push(summary);
        Ok(())
    })?;
    write_json(&set.path().join("summary.json"), &all)?;
    set.commit()?;
    Ok(all)
}

/// The impact law, its friction and its summary
/// ([`crate::multibody::impact_law::from_settings`]).
type Impact = (ImpactLaw, Option<Friction>, ImpactLawSummary);

/// The force elements of one pinion × wheel blank: the loaded flanks'
/// table (the contact element's, or the impact law's) and, with coast
/// contact, the coast flanks' placed across the backlash.
struct Tables {
    table: MeshTable,
    coast: Option<Coast>,
    /// Whether the scene runs up this wheel blank.
    runs_up: bool,
    /// Wall time of building both tables, s.
    build_s: f64,
}

/// Builds the tables of `pair` over the rotation its runs need, up to the
/// largest torque they apply.
fn tables(
    ctx: &StageContext,
    pair: &LoadedPair,
    rs: &RollSurface,
    coast_rs: Option<&RollSurface>,
    impact: Option<&Impact>,
) -> anyhow::Result<Tables> {
    let (scene, g) = (ctx.scene, &ctx.g);
    let (sc, mb) = (&scene.scene, &scene.scene.multibody);
    let ([pb, wb], pc, sweep) = (pair.blanks, &pair.pc, &pair.sweep);
    let (fp, coast_side) = (ctx.fp(), ctx.side().other());
    let tau = g.data.mesh_cycle();
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    let runs_up = mb.runup_wheel_blanks.contains(&wb);
    // Standard blanks repeat every mesh cycle; with a lightweight
    // member the table spans the whole rotation the runs need.
    let periodic = wb == Blank::Standard && pb == Blank::Standard;
    let per_cycle = (tau / mb.table_step_deg.to_radians()).round().max(8.0) as usize;
    // The 10 rpm runs go one sweep step past the sweep's end.
    let mut cycles = sc.rotation.mesh_cycles(wb);
    if runs_up {
        cycles = cycles.max(mb.runup_rotation() / tau);
    }
    if coast_rs.is_some() && mb.rattle_time_s > 0.0 {
        cycles = cycles.max(mb.rattle_rotation() / tau);
    }
    let range = cycles * tau + 3.0 * sweep.step;
    let step = tau / per_cycle as f64;
    let positions = if periodic {
        per_cycle
    } else {
        (range / step).ceil() as usize + 3
    };
    let torque_max = sc
        .pinion_torque_nm
        .iter()
        .copied()
        .chain(runs_up.then_some(mb.runup_pinion_torque_nm))
        .chain(mb.load_run.as_ref().map(|r| r.wheel_torque_nm * ratio))
        .fold(0.0, f64::max)
        * mb.table_torque_factor;
    let t0 = Instant::now();
    eprintln!(
        "multibody {pb:?}/{wb:?}: contact-element table {positions} positions x {} lags",
        mb.table_lag_nodes
    );
    let spec = TableSpec {
        start: sweep.start,
        direction: sweep.direction,
        step,
        positions,
        periodic,
        slices: sc.ltca.slices,
        lag_nodes: mb.table_lag_nodes,
        torque_max_nm: torque_max.max(1.0),
    };
    let table = match impact {
        None => MeshTable::build(fp, rs, pc, &g.frames[0], ratio, spec),
        Some((law, friction, _)) => crate::multibody::impact_table::build(
            fp,
            rs,
            &g.frames[0],
            ratio,
            spec,
            *law,
            *friction,
        ),
    }
    .with_context(|| format!("scene {}: contact-element table, {wb:?} wheel", sc.name))?;
    let coast = match coast_rs {
        Some(crs) => {
            let cfp = g.side(coast_side);
            let cpc = coast_compliance(scene, g, &ctx.dir, pb, wb)?.0;
            eprintln!("multibody {pb:?}/{wb:?}: coast-flank table");
            let ctable = MeshTable::build(
                cfp,
                crs,
                &cpc,
                &g.frames[0],
                ratio,
                TableSpec {
                    start: if periodic {
                        cfp.roll_range[0]
                    } else {
                        Coast::mirrored_start(&table)
                    },
                    direction: pinion_direction(&g.data, coast_side),
                    ..table.spec
                },
            )
            .with_context(|| format!("scene {}: coast-flank table, {wb:?} wheel", sc.name))?;
            Some(Coast::place(fp, &table, cfp, ctable)?)
        }
        None => None,
    };
    Ok(Tables {
        table,
        coast,
        runs_up,
        build_s: t0.elapsed().as_secs_f64(),
    })
}

/// The 10 rpm (quasi-static) runs of `pair` at the scene's torques: their
/// summaries, files and chart in `odir`, and the mesh damping they ran
/// with.
#[allow(clippy::too_many_arguments)]
fn quasi_static(
    sc: &geometry::scene::Scene,
    pair: &LoadedPair,
    t: &Tables,
    inertia: [f64; 2],
    impact: bool,
    scheme: Scheme,
    control: &dyn Fn(f64) -> StepControl,
    odir: &Path,
) -> anyhow::Result<(Vec<QuasiStaticSummary>, f64)> {
    let mb = &sc.multibody;
    let ([pb, wb], sweep) = (pair.blanks, &pair.sweep);
    let (table, coast) = (&t.table, &t.coast);
    let ratio = table.ratio;
    // Quasi-static runs.
    let wheel_speed = mb.quasi_static_wheel_rpm * std::f64::consts::PI / 30.0;
    let sweep_range = sweep.step * (sweep.positions - 1) as f64;
    let mut qs = Vec::new();
    let mut damping = 0.0;
    let mut qs_series = Vec::new();
    for &torque in &sc.pinion_torque_nm {
        let (m, s0) = wheel_driven(
            table,
            inertia,
            wheel_speed,
            torque,
            mb.damping_ratio,
            sc.ltca.friction_coefficient,
        )?;
        let m = Model {
            coast: coast.as_ref(),
            // The impact law brings its own damping and friction.
            damping: if impact { 0.0 } else { m.damping },
            friction: if impact { 0.0 } else { m.friction },
            ..m
        };
        damping = m.damping;
        let mut integ = Integrator::new(scheme, control(mb.quasi_static_max_step_s));
        let t = Instant::now();
        // Slightly beyond the sweep so that its last position is inside.
        let t_end = (sweep_range + 2.0 * sweep.step) / (wheel_speed / ratio);
        let (tr, steps) = record(&m, s0, &mut integ, t_end)
            .with_context(|| format!("scene {}: 10 rpm run at {torque} N·m", sc.name))?;
        let cpu = t.elapsed().as_secs_f64();
        let sampled: Vec<f64> = (0..sweep.positions)
            .map(|k| interpolate(&tr.q1, &tr.te, sweep.step * k as f64))
            .collect();
        let (mean, ptp) = mean_ptp(&sampled);
        write_atomic(
            &odir.join(format!("quasi_static_{torque}nm.csv")),
            trace_csv(&tr, None).as_bytes(),
        )?;
        qs_series.push(Series {
            name: format!("{torque} N·m"),
            x: (0..sweep.positions)
                .map(|k| (sweep.step * k as f64).to_degrees())
                .collect(),
            y: sampled.iter().map(|v| v * 1e6).collect(),
            dashed: false,
        });
        eprintln!(
            "  10 rpm {torque:6.1} N·m: TE mean {:8.2} µrad, ptp {:7.2} µrad, {steps} steps, {:.1} µs/step",
            mean * 1e6,
            ptp * 1e6,
            cpu / steps.max(1) as f64 * 1e6
        );
        qs.push(QuasiStaticSummary {
            torque_nm: torque,
            te_mean_urad: mean * 1e6,
            te_ptp_urad: ptp * 1e6,
            steps,
            rejected_steps: integ.rejected,
            cpu_s: cpu,
            cpu_s_per_step: cpu / steps.max(1) as f64,
        });
    }
    te_curve(
        &odir.join("quasi_static_te.svg"),
        &format!(
            "Multibody {} rpm wheel, {pb:?} pinion / {wb:?} wheel",
            mb.quasi_static_wheel_rpm
        ),
        "pinion rotation (deg)",
        "transmission error (µrad)",
        &qs_series,
    )?;
    Ok((qs, damping))
}

/// Everything `solver dynamic` runs on one pinion × wheel blank, its files
/// written into `set`'s staging folder.
fn blank_pair(
    ctx: &StageContext,
    pair: &LoadedPair,
    rs: &RollSurface,
    coast_rs: Option<&RollSurface>,
    impact: Option<&Impact>,
    set: &ResultSet,
) -> anyhow::Result<DynamicSummary> {
    let (scene, g, dir) = (ctx.scene, &ctx.g, ctx.dir.as_path());
    let (sc, mb) = (&scene.scene, &scene.scene.multibody);
    let [pb, wb] = pair.blanks;
    let [(j1, src1), (j2, src2)] = ctx.inertia(pair)?;
    let inertia = [j1, j2];
    let tables = tables(ctx, pair, rs, coast_rs, impact)?;
    let (table, coast, runs_up) = (&tables.table, &tables.coast, tables.runs_up);
    let positions = table.spec.positions;
    let name = pair.name();
    // Written into the staging directory; the summary names the
    // final path.
    let odir = set.path().join(&name);
    std::fs::create_dir_all(&odir)?;
    let control = |max_step: f64| StepControl {
        max_step,
        min_step: max_step * 1e-6,
        tolerance: mb.te_tolerance_urad * 1e-6,
    };
    let scheme = Scheme::GeneralizedAlpha {
        rho_inf: mb.rho_inf,
    };
    let (qs, damping) = quasi_static(
        sc,
        pair,
        &tables,
        inertia,
        impact.is_some(),
        scheme,
        &control,
        &odir,
    )?;
    let element_friction = if impact.is_some() {
        0.0
    } else {
        sc.ltca.friction_coefficient
    };
    let load_run = match &mb.load_run {
        Some(run) => {
            let drive = crate::multibody::load_run::drive(run);
            let mut m = Model {
                table,
                coast: coast.as_ref(),
                inertia,
                damping: 0.0,
                friction: element_friction,
                drive,
            };
            let s0 = m.static_state(0.0)?;
            if impact.is_none() {
                // The element's mesh damping at the full load's balance.
                let loaded = Model {
                    drive: Drive::PinionSpeed {
                        speed: Ramp {
                            from: 0.0,
                            to: 0.0,
                            duration: 0.0,
                        },
                        wheel_torque: run.wheel_torque_nm,
                    },
                    ..m
                };
                let s = loaded.static_state(0.0)?;
                m.damping = loaded.damping_for_ratio(mb.damping_ratio, &s)?;
            }
            eprintln!(
                "  load run: pinion {} rpm (ramp {} s), wheel {} N·m (rise {} s), {} s",
                run.pinion_rpm,
                run.pinion_ramp_s,
                run.wheel_torque_nm,
                run.wheel_torque_rise_s,
                run.time_s
            );
            Some(crate::multibody::load_run::run(
                &m,
                s0,
                run,
                &g.data,
                scheme,
                control(run.max_step_s),
                &odir,
                &format!("{} ({:?} law)", sc.name, mb.force_law).to_lowercase(),
            )?)
        }
        None => None,
    };
    let runup = if runs_up {
        Some(run_up(
            table,
            inertia,
            mb,
            &odir,
            scheme,
            &control,
            pb,
            wb,
            g.data.members[0].teeth as f64,
            element_friction,
            impact.is_some(),
            coast.as_ref(),
        )?)
    } else {
        None
    };
    let free_play = match &coast {
        Some(c) => {
            let fp: Vec<f64> = (0..table.spec.positions)
                .map(|k| c.free_play(table, table.spec.step * k as f64))
                .collect::<Result<_, _>>()?;
            let lo = fp.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = fp.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            eprintln!(
                "  backlash {:.2} µrad at the wheel, free play {:.2}..{:.2} µrad",
                c.backlash * 1e6,
                lo * 1e6,
                hi * 1e6
            );
            Some([lo * 1e6, hi * 1e6])
        }
        None => None,
    };
    let rattle = match &coast {
        Some(c) if mb.rattle_time_s > 0.0 => Some(rattle(
            table,
            c,
            inertia,
            damping,
            mb,
            &odir,
            scheme,
            &control,
            sc.ltca.friction_coefficient,
        )?),
        _ => None,
    };
    let compliant = match (&sc.bearings, impact) {
        (Some(_), None) => {
            let manifest = Manifest::read(dir)?;
            let mass = |stem: &str| -> anyhow::Result<f64> {
                let b = manifest.mesh(dir, stem)?.body;
                Ok(b.volume_m3 * b.density_kg_m3)
            };
            Some(crate::stage::compliant::run(
                &crate::stage::compliant::Setup {
                    scene,
                    g,
                    table,
                    inertia,
                    mesh_mass_kg: [
                        mass(&pair.plans[0].mesh_stem)?,
                        mass(&pair.plans[1].mesh_stem)?,
                    ],
                    blanks: [pb, wb],
                    odir: &odir,
                    control: &control,
                    runs_up,
                },
            )?)
        }
        (Some(_), Some(_)) => {
            eprintln!(
                "  [bearings] with the impact law: no compliant-bearing runs (they take the element's table)"
            );
            None
        }
        _ => None,
    };
    let summary = DynamicSummary {
        compliant,
        backlash_urad: coast.as_ref().map(|c| c.backlash * 1e6),
        free_play_urad: free_play,
        rattle,
        friction_coefficient: sc.ltca.friction_coefficient,
        pinion_blank: pb,
        wheel_blank: wb,
        inertia_kgm2: inertia,
        inertia_source: if src1 == src2 {
            src1.into()
        } else {
            format!("pinion {src1}, wheel {src2}")
        },
        damping_nm_s_per_rad: damping,
        table_positions: positions,
        table_lag_nodes: mb.table_lag_nodes,
        table_build_s: tables.build_s,
        table_cpu_s_per_position: table.cpu_s_per_position,
        quasi_static: qs,
        runup,
        force_law: format!("{:?}", mb.force_law).to_lowercase(),
        impact_law: impact.as_ref().map(|i| i.2.clone()),
        load_run,
        dir: set.dir().join(&name),
    };
    write_json(&odir.join("summary.json"), &summary)?;
    write_json(&odir.join("summary.json"), &summary)?;
    Ok(summary)
}

#[allow(clippy::too_many_arguments)]
fn run_up(
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
    // Without coast flanks the wheel must stay on the drive flanks up to
    // the top speed: below the holding torque it runs ahead at the tooth
    // changes and leaves the mesh, and the run-up's TE means nothing.
    let holding = m.holding_torque()?;
    if torque < holding {
        if coast.is_none() {
            anyhow::bail!(
                "multibody.runup_pinion_torque_nm = {torque} N·m is below {holding:.3e} N·m, the torque that holds the wheel (inertia {:.4e} kg·m²) on the drive flanks up to the run-up's {} rpm (the flanks can only push it forward: below this it runs ahead at the tooth changes and, without coast flanks, leaves the mesh); raise the torque, lower multibody.runup_rpm, or set multibody.coast_contact = true to follow the impacts across the backlash",
                inertia[1],
                mb.runup_rpm[0].abs().max(mb.runup_rpm[1].abs())
            );
        }
        eprintln!(
            "  run-up: {torque} N·m is below the holding torque {holding:.3e} N·m at the top speed: the wheel will leave the drive flanks at the tooth changes (coast contact is on: impacts across the backlash)"
        );
    }
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
    })
}

/// The rattle run: the pinion at a fluctuating speed, the wheel free under
/// its drag torque, both flank pairs across the backlash; writes
/// `rattle.csv` and `rattle_te.svg` (the lag between the two contact limits).
#[allow(clippy::too_many_arguments)]
fn rattle(
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
    let mut share = [0.0; 3];
    let mut torque = [f64::INFINITY, f64::NEG_INFINITY];
    let mut wheel = [f64::INFINITY, f64::NEG_INFINITY];
    let mut last_t = 0.0;
    let rpm = |x: f64| x * 30.0 / std::f64::consts::PI;
    let clock = crate::cpu_clock::thread_cpu_s();
    let (_, steps) = integrate(&m, s0, &mut integ, mb.rattle_time_s, |s| {
        let c = m.contact(s.q, s.v)?;
        let now = c.touching();
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
        "  rattle: {steps} steps ({} rejected), {} drive and {} coast impacts, mesh torque {:.1}..{:.1} N·m, {:.1} µs/step",
        integ.rejected,
        impacts.drive,
        impacts.coast,
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
        time_share_drive_coast_free: share.map(|x| x / total),
        mesh_torque_min_max_nm: torque,
        te_min_max_urad: [te_lo, te_hi],
        wheel_rpm_min_max: wheel,
    })
}
