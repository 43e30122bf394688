//! `solver lumped` with `[lumped.order_map]`: the 8-DOF model of every
//! pinion × wheel blank driven by k(t), δ(t) over one wheel revolution
//! ([`crate::lumped::revolution`]) at each pinion speed of the section,
//! to `<out>/<scene>/lumped/<pinion>_<wheel>_<rpm>rpm/` (the files of
//! one lumped run), `order_map_<pinion>_<wheel>.svg` (the wheel
//! bearing-force spectrum over pinion orders and speed, the mesh orders
//! z₁, 2z₁, the lobe family n·z₁/z₂ and its side bands z₁ ± n·z₁/z₂
//! marked) and `order_map.json` ([`OrderMapSummary`] per blank pair).
//!
//! The lobe count n is the lightweight wheel's web holes
//! ([`geometry::gear_body::WHEEL_WEB_HOLES`]); the standard wheel is
//! axisymmetric (n = 0). The marked orders are the same for both, so the
//! standard wheel's amplitudes at the lobe orders show what it has there.
use crate::signal::runup_orders::amplitude_at;
use crate::signal::runup_orders::marked_orders;

use crate::element::compliance::PairCompliance;
use crate::ltca::{geometry, run as run_sweep, PositionResult, Sweep};
use crate::lumped::friction::slice_friction;
use crate::lumped::from_ltca::{fit_series, mesh_samples, span_samples, tangent_torques};
use crate::lumped::revolution::{lobe_repeat_mismatch, Revolution};
use crate::signal::spectrum::{plot_order_map, OrderLine};
use crate::stage::context::{scene_sweep, LoadedPair, StageContext};
use crate::stage::lumped_run::{run_blank, Case};
use anyhow::Context;
use formats::lumped_summary::{
    LobeFit, LumpedSummary, MarkedOrder, OrderMapSpeed, OrderMapSummary,
};
use formats::manifest::{BodyProperties, Manifest};
use formats::output::write_json;
use formats::result_set::ResultSet;
use geometry::gear_body::{hole_wheel_teeth, WHEEL_WEB_HOLES};
use geometry::scene::Blank;
use geometry::scene_lumped::{ImpactModel, LumpedSettings, OrderMapSettings};
use geometry::utca::{roll_surface, RollSurface};
use std::time::Instant;

/// Force-weighted wheel tooth of the loaded pairs (pinion tooth j meshes
/// wheel tooth −j) at the operating torque.
fn loaded_wheel_tooth(p: &crate::ltca::PositionResult) -> f64 {
    let (fw, f) = p.loads[1]
        .pair_force
        .iter()
        .fold((0.0, 0.0), |(fw, f), (j, x)| (fw - *j as f64 * x, f + x));
    if f > 0.0 {
        fw / f
    } else {
        f64::NAN
    }
}

/// Runs the order map of the scene (see the module's doc).
pub fn run(
    ctx: &StageContext,
    ls: &LumpedSettings,
    om: &OrderMapSettings,
    manifest: &Manifest,
    set: &mut ResultSet,
) -> anyhow::Result<Vec<LumpedSummary>> {
    let (scene, g, _dir) = (ctx.scene, &ctx.g, ctx.dir.as_path());
    let sc = &scene.scene;
    anyhow::ensure!(
        ls.impact == ImpactModel::Engagement && ls.friction.is_none() && ls.roughness.is_none(),
        "scene {}: [lumped.order_map] runs the design's smooth flanks without friction and with impact = \"engagement\"",
        sc.name
    );
    anyhow::ensure!(
        ls.design_variants.is_empty() && ls.more_pinion_torques_nm.is_empty(),
        "scene {}: [lumped.order_map] runs one torque on the design (no design_variants, no more_pinion_torques_nm)",
        sc.name
    );
    let side = sc.loaded_flank;
    let fp = g.side(side);
    let rs = roll_surface(fp, &sc.utca)?;
    let (z1, z2) = (
        g.data.members[0].teeth as usize,
        g.data.members[1].teeth as usize,
    );
    let tau = g.data.mesh_cycle();
    let torque = ls.pinion_torque_nm;
    let marks = marked_orders(z1, z2, WHEEL_WEB_HOLES);
    let setup = MapSetup {
        ctx,
        ls,
        om,
        rs: &rs,
        teeth: [z1, z2],
        tau,
        torque,
        marks: &marks,
    };
    let mut all = Vec::new();
    let mut maps = Vec::new();
    ctx.for_each_pair(|pair| {
        maps.push(blank_pair_map(&setup, pair, manifest, set, &mut all)?);
        Ok(())
    })?;
    write_json(&set.path().join("order_map.json"), &maps)?;
    Ok(all)
}

/// What every blank pair's order map shares.
struct MapSetup<'a> {
    ctx: &'a StageContext<'a>,
    ls: &'a LumpedSettings,
    om: &'a OrderMapSettings,
    /// The loaded flanks' surface of roll angles.
    rs: &'a RollSurface,
    /// Pinion and wheel teeth.
    teeth: [usize; 2],
    /// Mesh cycle, rad, and the operating torque, N·m.
    tau: f64,
    torque: f64,
    /// The marked pinion orders and their labels.
    marks: &'a [(String, f64)],
}

/// One blank pair's LTCA over its sweep and the revolution fitted to it.
struct Revolved {
    sweep: Sweep,
    res: Vec<PositionResult>,
    ltca_wall: f64,
    rev: Revolution,
    /// With every wheel tooth solved: the lobe fitted to the scene's span
    /// alone, and how far the solved revolution repeats with the lobes.
    short_span_lobe: Option<LobeFit>,
    lobe_repeat: Option<[f64; 2]>,
}

/// The runs of one blank pair at every pinion speed: the spectra's pinion
/// orders, one row of wheel bearing-force amplitudes per speed, the speeds'
/// summaries, and the series' harmonics and residuals of the last speed.
struct SpeedRuns {
    orders: Vec<f64>,
    rows: Vec<Vec<f64>>,
    speeds: Vec<OrderMapSpeed>,
    info: Option<(usize, usize, [f64; 2])>,
}

/// One blank pair: its LTCA and revolution, the runs at every speed (each
/// summary pushed to `all`), the order map chart and its summary.
fn blank_pair_map(
    m: &MapSetup,
    pair: LoadedPair,
    manifest: &Manifest,
    set: &mut ResultSet,
    all: &mut Vec<LumpedSummary>,
) -> anyhow::Result<OrderMapSummary> {
    let (ctx, g) = (m.ctx, &m.ctx.g);
    let side = ctx.scene.scene.loaded_flank;
    let [z1, z2] = m.teeth;
    let [pb, wb] = pair.blanks;
    let solved = pair.pc.wheel.solved_teeth().to_vec();
    ctx.record_inputs(set, pair.blanks, false)?;
    let body = |stem: &str| -> anyhow::Result<_> { Ok(manifest.mesh(&ctx.dir, stem)?.body) };
    let bodies = [
        body(&pair.plans[0].mesh_stem)?,
        body(&pair.plans[1].mesh_stem)?,
    ];
    let pc = pair.pc;
    let lobes = if wb == Blank::Lightweight {
        WHEEL_WEB_HOLES
    } else {
        0
    };
    // Every wheel tooth solved: the LTCA sweeps one whole
    // revolution and drives the runs itself.
    let whole = lobes > 0 && solved.len() == z2;
    let r = revolved(m, &pc, wb, lobes, whole)?;
    let hole_teeth = if lobes > 0 {
        hole_wheel_teeth(g, side)?
    } else {
        Vec::new()
    };
    let SpeedRuns {
        orders,
        rows,
        speeds,
        info,
    } = speed_runs(m, &r, [pb, wb], bodies, set, all)?;
    let (mesh_harmonics, revolution_harmonics, residual) = info.context("order map: no speeds")?;
    plot_map(m, [pb, wb], &orders, rows, set)?;
    let Revolved {
        rev,
        ltca_wall,
        short_span_lobe,
        lobe_repeat,
        ..
    } = r;
    Ok(OrderMapSummary {
        pinion_blank: pb,
        wheel_blank: wb,
        pinion_teeth: z1,
        wheel_teeth: z2,
        lobes,
        wheel_solved_teeth: solved,
        ltca_span_mesh_cycles: rev.span_cycles,
        cycle_mean_stiffness_n_per_m: rev.cycle_mean_stiffness_n_per_m.clone(),
        cycle_wheel_tooth: rev.cycle_wheel_tooth.clone(),
        stiffness_lobe: rev.stiffness_lobe,
        deflection_lobe_m: rev.deflection_lobe_m,
        stiffness_lobe_ptp_relative: rev.stiffness_lobe_ptp(),
        stiffness_lobe_minimum_wheel_tooth: rev.stiffness_lobe_minimum_wheel_tooth(),
        span_fit_residual_of_ptp: rev.max_residual_of_ptp,
        mesh_harmonics,
        revolution_harmonics,
        revolution_series_residual_of_ptp: residual,
        ltca_wall_s: ltca_wall,
        speeds,
        excitation: if rev.solved.is_some() {
            "solved revolution"
        } else if lobes == 0 {
            "mesh cycle repeated (axisymmetric wheel)"
        } else {
            "lobe fitted to the span"
        }
        .into(),
        short_span_lobe,
        lobe_repeat_mismatch_of_mean: lobe_repeat,
        hole_wheel_teeth: hole_teeth,
    })
}

/// The LTCA over the `wb` wheel's sweep (one whole revolution when every
/// wheel tooth is solved) and the revolution of k and δ fitted to it.
fn revolved(
    m: &MapSetup,
    pc: &PairCompliance,
    wb: Blank,
    lobes: usize,
    whole: bool,
) -> anyhow::Result<Revolved> {
    let (scene, g, om, rs) = (m.ctx.scene, &m.ctx.g, m.om, m.rs);
    let sc = &scene.scene;
    let fp = g.side(sc.loaded_flank);
    let [_, z2] = m.teeth;
    let (tau, torque) = (m.tau, m.torque);
    let mut sweep = scene_sweep(scene, g, wb);
    if whole {
        sweep.positions = sweep
            .positions
            .max((z2 as f64 * tau / sweep.step).round() as usize + 1);
    }
    let t0 = Instant::now();
    let res = run_sweep(fp, rs, pc, &sweep, &tangent_torques(torque))
        .with_context(|| format!("scene {}: LTCA for the order map", sc.name))?;
    let ltca_wall = t0.elapsed().as_secs_f64();
    let cycles = sc.rotation.mesh_cycles(wb);
    // The revolution depends on positions in mesh cycles only: any
    // speed serves; the first one's.
    let omega0 = om.pinion_speeds_rpm[0] * std::f64::consts::PI / 30.0;
    let fit = |cycles: f64| -> anyhow::Result<Revolution> {
        let span = span_samples(&res, torque, omega0, tau, cycles)?;
        let teeth: Vec<f64> = res[..span.time_s.len()]
            .iter()
            .map(loaded_wheel_tooth)
            .collect();
        let r = if cycles >= z2 as f64 {
            Revolution::from_revolution(&span, &teeth, tau, sweep.step, z2, lobes)
        } else {
            Revolution::from_span(&span, &teeth, tau, sweep.step, z2, lobes)
        };
        r.with_context(|| format!("scene {}: {wb:?} wheel's revolution", sc.name))
    };
    let rev = fit(if whole { z2 as f64 } else { cycles })?;
    let short_span_lobe = if whole {
        let r = fit(cycles)?;
        Some(LobeFit {
            span_mesh_cycles: r.span_cycles,
            stiffness_lobe: r.stiffness_lobe,
            stiffness_lobe_ptp_relative: r.stiffness_lobe_ptp(),
            stiffness_lobe_minimum_wheel_tooth: r.stiffness_lobe_minimum_wheel_tooth(),
        })
    } else {
        None
    };
    let lobe_repeat = if whole {
        Some(lobe_repeat_mismatch(
            &rev.cycle_mean_stiffness_n_per_m,
            lobes,
        )?)
    } else {
        None
    };
    Ok(Revolved {
        sweep,
        res,
        ltca_wall,
        rev,
        short_span_lobe,
        lobe_repeat,
    })
}

/// The lumped runs over the wheel revolutions at every pinion speed of the
/// section, each to `<pinion>_<wheel>_<rpm>rpm/` in the set, its summary
/// pushed to `all`.
fn speed_runs(
    m: &MapSetup,
    r: &Revolved,
    [pb, wb]: [Blank; 2],
    bodies: [BodyProperties; 2],
    set: &ResultSet,
    all: &mut Vec<LumpedSummary>,
) -> anyhow::Result<SpeedRuns> {
    let (g, ls, om, rs, marks) = (&m.ctx.g, m.ls, m.om, m.rs, m.marks);
    let side = m.ctx.scene.scene.loaded_flank;
    let fp = g.side(side);
    let [z1, z2] = m.teeth;
    let (tau, torque) = (m.tau, m.torque);
    let (sweep, res, rev) = (&r.sweep, &r.res, &r.rev);
    let tau_p = fp.pinion.gen.frame.pitch();
    let mut rows = Vec::new();
    let mut speeds = Vec::new();
    let mut orders = Vec::new();
    let mut info = None;
    for &rpm in &om.pinion_speeds_rpm {
        let tr = Instant::now();
        let omega = rpm * std::f64::consts::PI / 30.0;
        let samples = mesh_samples(res, torque, omega, tau)?;
        let [kf, ef, df] = fit_series(&samples, ls.fourier_tolerance_of_ptp)?;
        let mesh_harmonics = kf.series.harmonics().max(df.series.harmonics());
        let [kr, dr] = rev.series(
            samples.period_s,
            mesh_harmonics,
            ls.fourier_tolerance_of_ptp,
        )?;
        let slice_friction = (0..samples.time_s.len())
            .map(|k| {
                let phi = sweep.start + sweep.direction * res[k].rotation;
                let gk = geometry(fp, rs, phi, tau_p, sweep.slices);
                slice_friction(fp, phi, tau_p, &gk.slices, &res[k].loads[1].slices)
            })
            .collect::<Vec<_>>();
        let run_ls = LumpedSettings {
            pinion_speed_rpm: rpm,
            mesh_cycles: om.wheel_revolutions * z2 as f64,
            dropped_mesh_cycles: om.dropped_wheel_revolutions * z2 as f64,
            ..ls.clone()
        };
        let variant = format!("{rpm}rpm");
        let name = format!("{pb:?}_{wb:?}_{variant}").to_lowercase();
        let odir = set.path().join(&name);
        std::fs::create_dir_all(&odir)?;
        let case = Case {
            ls: &run_ls,
            torque,
            blanks: [pb, wb],
            side,
            g,
            bodies,
            samples: &samples,
            fits: [&kr, &ef, &dr],
            eng: None,
            slice_friction,
            roughness: None,
            design: None,
            contact_ratio: 0.0,
            variant,
            max_order: om.max_pinion_order / z1 as f64,
        };
        let (summary, spectrum) = run_blank(&case, &odir)?;
        let run_wall = tr.elapsed().as_secs_f64();
        write_json(&odir.join("summary.json"), &summary)?;
        let wheel: Vec<(f64, f64)> = spectrum.iter().map(|l| (l[0] * z1 as f64, l[2])).collect();
        if orders.is_empty() {
            orders = wheel.iter().map(|l| l.0).collect();
        }
        anyhow::ensure!(
            wheel.len() == orders.len(),
            "order map: the runs' spectra differ in length"
        );
        rows.push(wheel.iter().map(|l| l.1).collect::<Vec<_>>());
        eprintln!(
            "order map {pb:?}/{wb:?} {rpm} rpm: k series {} harmonics, {} steps, integration {:.2} s, run {:.2} s",
            kr.series.harmonics(),
            summary.steps[0],
            summary.integration_wall_s,
            run_wall
        );
        speeds.push(OrderMapSpeed {
            pinion_speed_rpm: rpm,
            mesh_frequency_hz: summary.mesh_frequency_hz,
            integration_wall_s: summary.integration_wall_s,
            run_wall_s: run_wall,
            order_resolution: if orders.len() > 1 {
                orders[1] - orders[0]
            } else {
                0.0
            },
            marked: marks
                .iter()
                .map(|(label, o)| MarkedOrder {
                    label: label.clone(),
                    pinion_order: *o,
                    wheel_bearing_force_n: amplitude_at(&wheel, *o),
                })
                .collect(),
        });
        info = Some((
            mesh_harmonics,
            kr.series.harmonics(),
            [kr.max_residual_of_ptp, dr.max_residual_of_ptp],
        ));
        all.push(summary);
    }
    Ok(SpeedRuns {
        orders,
        rows,
        speeds,
        info,
    })
}

/// `order_map_<pinion>_<wheel>.svg`: the wheel bearing-force amplitudes
/// `rows` (one per speed, in the section's order) over the pinion `orders`,
/// rows sorted by speed, the marked orders drawn.
fn plot_map(
    m: &MapSetup,
    [pb, wb]: [Blank; 2],
    orders: &[f64],
    rows: Vec<Vec<f64>>,
    set: &ResultSet,
) -> anyhow::Result<()> {
    let (om, torque, marks) = (m.om, m.torque, m.marks);
    let mut order_rows: Vec<(f64, Vec<f64>)> =
        om.pinion_speeds_rpm.iter().copied().zip(rows).collect();
    order_rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (sp, am): (Vec<f64>, Vec<Vec<f64>>) = order_rows.into_iter().unzip();
    plot_order_map(
        &set.path()
            .join(format!("order_map_{pb:?}_{wb:?}.svg").to_lowercase()),
        &format!("Wheel bearing force, 8-DOF model, {torque} N·m ({pb:?} pinion / {wb:?} wheel)"),
        orders,
        &sp,
        &am,
        &marks
            .iter()
            .map(|(label, o)| OrderLine {
                order: *o,
                label: label.clone(),
            })
            .collect::<Vec<_>>(),
    )?;
    Ok(())
}
