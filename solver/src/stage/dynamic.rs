//! `solver dynamic <scene>`: the multibody runs of every pinion × wheel blank
//! of a scene, to `<out>/<scene>/multibody/<pinion>_<wheel>/`:
//! - `quasi_static_<T>nm.csv` per scene torque: the white paper's 10 rpm run
//!   (imposed wheel speed, torque on the pinion) over the LTCA's rotation
//!   range: time, pinion rotation, TE, mesh torques, bearing forces;
//! - `runup.csv`, `runup_te.svg` (dynamic against quasi-static TE over the
//!   pinion speed; the white paper's Figure 13 compares the two in the
//!   angle domain, lightweight pair, first pinion revolution, which this
//!   chart is not) and `runup_spectrogram.svg`
//!   (the wheel bearing force with the mesh orders) for the blanks that run up;
//! - `ste_dte.csv`, `ste_dte.svg` for the wheel blanks `[multibody.ste_dte]`
//!   compares: the white paper's first use case, quasi-static against
//!   dynamic TE in the angle domain ([`crate::stage::ste_dte`]);
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
use crate::stage::rattle::rattle;
use crate::stage::runup::run_up;
use crate::stage::trace::record;
use crate::stage::trace::trace_csv;
use formats::summaries::ImpactLawSummary;
use geometry::utca::RollSurface;

use crate::ltca::mean_ptp;
use crate::multibody::backlash::Coast;
use crate::multibody::mesh_table::{MeshTable, TableSpec};
use crate::multibody::model::{interpolate, wheel_driven, Drive, Model, Ramp};
use crate::multibody::time_step::{Integrator, Scheme, StepControl};
use crate::stage::context::coast_compliance;
use anyhow::Context;
use charts::{te_curve, Series};
use formats::manifest::Manifest;
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use geometry::pair::pinion_direction;
use geometry::scene::{Blank, ForceLaw, LoadedScene};
use std::path::Path;
use std::time::Instant;

pub use formats::summaries::{DynamicSummary, QuasiStaticSummary, RattleSummary, RunupSummary};

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
    let housing = crate::stage::gearbox::load_housing(scene, &ctx.dir)?;
    formats::stop_point::at("reading");
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
        let summary = blank_pair(
            &ctx,
            &pair,
            &rs,
            coast_rs.as_ref(),
            impact.as_ref(),
            housing.as_ref(),
            &set,
        )?;
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
    let per_cycle = geometry::teeth::table_positions_per_cycle(sc, tau);
    // The 10 rpm runs go one sweep step past the sweep's end.
    let cycles = geometry::teeth::table_mesh_cycles(sc, wb, tau);
    let range = cycles * tau + 3.0 * sweep.step;
    let step = tau / per_cycle as f64;
    let positions = if periodic {
        per_cycle
    } else {
        (range / step).ceil() as usize + 3
    };
    let torque_max = geometry::teeth::table_torque_nm(sc, wb, ratio);
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
        None if mb.root_stress => {
            anyhow::ensure!(
                pc.pinion.root_points().is_some() && pc.wheel.root_points().is_some(),
                "scene {}: multibody.root_stress = true needs root-stress coefficients in the stiffness files ([stiffness] root_stress = true, then `preprocess stiffness`)",
                sc.name
            );
            MeshTable::build_with_root_stress(fp, rs, pc, &g.frames[0], ratio, spec)
        }
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
    // The stiffness plan solved the teeth of the lead-in it bounds.
    let lead = table.lead as f64 * table.spec.step;
    let bound = geometry::teeth::table_span(g, sc, wb, sweep.step)[0];
    anyhow::ensure!(
        periodic || lead <= bound,
        "scene {}: the contact-element table's lead-in before the sweep, {:.3} deg at {torque_max} N m, exceeds the {:.3} deg the stiffness plan covers (the loaded lag is that of a mesh stiffness below {} N/(mm um)); lower multibody.table_torque_factor or the largest torque",
        sc.name,
        lead.to_degrees(),
        bound.to_degrees(),
        geometry::teeth::MIN_MESH_STIFFNESS_STEEL * 1e-9
    );
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
            root_tension_mpa: tr
                .largest_root_tension([0.0, sweep_range])
                .map(|r| r.map(|v| v * 1e-6)),
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
    housing: Option<&crate::stage::gearbox::LoadedHousing>,
    set: &ResultSet,
) -> anyhow::Result<DynamicSummary> {
    let (scene, g) = (ctx.scene, &ctx.g);
    let (sc, mb) = (&scene.scene, &scene.scene.multibody);
    let [pb, wb] = pair.blanks;
    let [(j1, src1), (j2, src2)] = ctx.inertia(pair)?;
    let inertia = [j1, j2];
    let tables = tables(ctx, pair, rs, coast_rs, impact)?;
    formats::stop_point::at("solving");
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
        Some(run) => Some(seed_load_run(
            ctx,
            run,
            table,
            coast.as_ref(),
            inertia,
            element_friction,
            impact.is_some(),
            scheme,
            control(run.max_step_s),
            &odir,
        )?),
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
    let ste_dte = match mb.ste_dte_of(wb) {
        Some(sd) => Some(crate::stage::ste_dte::ste_dte(
            &crate::stage::ste_dte::Setup {
                table,
                coast: coast.as_ref(),
                inertia,
                friction: element_friction,
                impact: impact.is_some(),
                damping_ratio: mb.damping_ratio,
                scheme,
                control: &control,
                mesh_cycle: g.data.mesh_cycle(),
                blanks: [pb, wb],
            },
            sd,
            &odir,
        )?),
        None => None,
    };
    let free_play = coast.as_ref().map(|c| free_play(c, table)).transpose()?;
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
    let compliant = compliant_runs(
        ctx,
        pair,
        table,
        inertia,
        impact.is_some(),
        &odir,
        &control,
        runs_up,
        housing,
    )?;
    let summary = DynamicSummary {
        compliant,
        ste_dte,
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
    Ok(summary)
}

/// Seeds 001 and 002's imposed-speed load run ([`crate::multibody::load_run`])
/// on the table, with the element's mesh damping at the full load's
/// balance (the impact law brings its own).
#[allow(clippy::too_many_arguments)]
fn seed_load_run(
    ctx: &StageContext,
    run: &geometry::scene_contact_law::LoadRun,
    table: &MeshTable,
    coast: Option<&Coast>,
    inertia: [f64; 2],
    element_friction: f64,
    impact: bool,
    scheme: Scheme,
    control: StepControl,
    odir: &Path,
) -> anyhow::Result<formats::summaries::LoadRunSummary> {
    let (g, sc) = (&ctx.g, &ctx.scene.scene);
    let mb = &sc.multibody;
    let drive = crate::multibody::load_run::drive(run);
    let mut m = Model {
        table,
        coast,
        inertia,
        damping: 0.0,
        friction: element_friction,
        drive,
    };
    let s0 = m.static_state(0.0)?;
    if !impact {
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
        run.pinion_rpm, run.pinion_ramp_s, run.wheel_torque_nm, run.wheel_torque_rise_s, run.time_s
    );
    crate::multibody::load_run::run(
        &m,
        s0,
        run,
        &g.data,
        scheme,
        control,
        odir,
        &format!("{} ({:?} law)", sc.name, mb.force_law).to_lowercase(),
    )
}

/// The free play across the backlash over the table's positions (least,
/// largest), µrad at the wheel.
fn free_play(c: &Coast, table: &MeshTable) -> anyhow::Result<[f64; 2]> {
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
    Ok([lo * 1e6, hi * 1e6])
}

/// With the scene's `[bearings]`, the runs again on compliant bearings
/// ([`crate::stage::compliant`]); the impact law has no compliant runs.
#[allow(clippy::too_many_arguments)]
fn compliant_runs(
    ctx: &StageContext,
    pair: &LoadedPair,
    table: &MeshTable,
    inertia: [f64; 2],
    impact: bool,
    odir: &Path,
    control: &dyn Fn(f64) -> StepControl,
    runs_up: bool,
    housing: Option<&crate::stage::gearbox::LoadedHousing>,
) -> anyhow::Result<Option<formats::summaries::CompliantSummary>> {
    let (scene, g, dir) = (ctx.scene, &ctx.g, ctx.dir.as_path());
    let sc = &scene.scene;
    let [pb, wb] = pair.blanks;
    Ok(match (&sc.bearings, impact) {
        (Some(_), false) => {
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
                    odir,
                    control,
                    runs_up,
                    housing,
                },
            )?)
        }
        (Some(_), true) => {
            eprintln!(
                "  [bearings] with the impact law: no compliant-bearing runs (they take the element's table)"
            );
            None
        }
        _ => None,
    })
}
