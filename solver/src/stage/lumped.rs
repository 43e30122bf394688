//! `solver lumped <scene>`: the 8-DOF lumped model of every pinion × wheel
//! blank of a scene with a `[lumped]` section, driven by our LTCA at the
//! operating torque, to `<out>/<scene>/lumped/<pinion>_<wheel>/`:
//! `time_history.csv`, `mesh_excitation.csv`, `bearing_spectrum.csv` and
//! `summary.json` ([`formats::lumped_summary::LumpedSummary`]) and the charts
//! of [`crate::stage::lumped_plots`], written as one result set.
use crate::lumped::friction::slice_friction;

use crate::element::compliance::PairCompliance;
use crate::ltca::Sweep;
use crate::ltca::{geometry, run as run_sweep};
use crate::lumped::from_ltca::{fit_series, mesh_samples, tangent_torques};
use crate::lumped::impact::engagement;
use crate::lumped::roughness::roughened;
use crate::stage::context::{scene_sweep, StageContext};
use crate::stage::lumped_run::{run_blank, Case};
use anyhow::Context;
use formats::lumped_summary::{DesignVariantSummary, LumpedSummary, RoughnessSummary};
use formats::manifest::{BodyProperties, Manifest};
use formats::output::write_json;
use formats::result_set::ResultSet;
use geometry::design::PairData;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::scene_lumped::{DesignVariant, LumpedSettings};
use geometry::utca::{roll_surface, RollSurface};
use std::path::Path;

/// Spectrum range, mesh orders.
const MAX_ORDER: f64 = 5.0;

/// The operating torques of the scene: `pinion_torque_nm`, then
/// `more_pinion_torques_nm`.
fn torques(ls: &LumpedSettings) -> Vec<f64> {
    std::iter::once(ls.pinion_torque_nm)
        .chain(ls.more_pinion_torques_nm.iter().copied())
        .collect()
}

/// A flank variant of the scene's design.
#[derive(Debug, Clone, Copy)]
enum Flanks<'a> {
    /// The design as it is.
    Design,
    /// A W–M roughness grade, Ra in µm.
    Rough(f64),
    /// An ease-off variant.
    Variant(&'a DesignVariant),
}

impl Flanks<'_> {
    fn label(&self) -> String {
        match self {
            Flanks::Design => "design".into(),
            Flanks::Rough(ra) => format!("ra{ra}"),
            Flanks::Variant(v) => v.name.clone(),
        }
    }
}

/// The flank variants: the design, each roughness grade, each ease-off variant.
fn flank_variants(ls: &LumpedSettings) -> Vec<Flanks<'_>> {
    std::iter::once(Flanks::Design)
        .chain(
            ls.roughness
                .iter()
                .flat_map(|r| r.ra_um.iter().map(|x| Flanks::Rough(*x))),
        )
        .chain(ls.design_variants.iter().map(Flanks::Variant))
        .collect()
}

/// The design with the ease-off of `v`, and what it used.
pub fn varied(pair: &PairData, v: &DesignVariant) -> (PairData, DesignVariantSummary) {
    let mut p = pair.clone();
    let e = &mut p.ease_off;
    if let Some(m) = v.te_slope_m21 {
        let half = 0.5 * pair.mesh_cycle();
        e.motion_error_urad = 0.5 * m.abs() * half * half * 1e6;
    }
    if let Some(c) = v.profile_crowning_um {
        e.profile_crowning_um = c;
    }
    if let Some(c) = v.lengthwise_crowning_um {
        e.lengthwise_crowning_um = c;
    }
    let summary = DesignVariantSummary {
        name: v.name.clone(),
        te_slope_m21: v.te_slope_m21,
        motion_error_urad: e.motion_error_urad,
        profile_crowning_um: e.profile_crowning_um,
        lengthwise_crowning_um: e.lengthwise_crowning_um,
    };
    (p, summary)
}

/// Mean number of tooth pairs carrying load over the positions of one
/// mesh cycle at the operating torque (load index 1 of the tangent torques).
fn loaded_contact_ratio(res: &[crate::ltca::PositionResult], positions: usize) -> f64 {
    res[..positions]
        .iter()
        .map(|p| p.loads[1].pair_force.iter().filter(|f| f.1 > 0.0).count() as f64)
        .sum::<f64>()
        / positions.max(1) as f64
}

/// Runs the lumped model of the scene: per blank pair, roughness grade and
/// operating torque.
pub fn run(scene: &LoadedScene, meshes: &Path, out: &Path) -> anyhow::Result<Vec<LumpedSummary>> {
    let sc = &scene.scene;
    let Some(ls) = &sc.lumped else {
        anyhow::bail!(
            "scene {}: no [lumped] section; add one to run the lumped model (reference/scenes/seed004_lumped.toml is a complete example; its fields and limits: docs/limits.md)",
            sc.name
        );
    };
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("lumped"),
        &format!("solver lumped {}", scene.path.display()),
    )?;
    let ctx = StageContext::aligned(scene, meshes)?;
    let (g, dir) = (&ctx.g, ctx.dir.as_path());
    let side = sc.loaded_flank;
    let manifest = Manifest::read(dir)?;
    let torques = torques(ls);
    let variants = flank_variants(ls);
    if let Some(om) = &ls.order_map {
        let all = crate::stage::lumped_order_map::run(&ctx, ls, om, &manifest, &mut set)?;
        write_json(&set.path().join("summary.json"), &all)?;
        set.commit()?;
        return Ok(all);
    }
    let omega = ls.pinion_speed_rpm * std::f64::consts::PI / 30.0;
    let mut all = Vec::new();
    ctx.for_each_pair(|pair| {
        let [_, wb] = pair.blanks;
        ctx.record_inputs(&mut set, pair.blanks, false)?;
        let body = |stem: &str| -> anyhow::Result<_> { Ok(manifest.mesh(&ctx.dir, stem)?.body) };
        let bodies = [
            body(&pair.plans[0].mesh_stem)?,
            body(&pair.plans[1].mesh_stem)?,
        ];
        let pc = pair.pc;
        for &flanks in &variants {
            let (other_pair, mut rough, design) = flank_geometry(scene, ls, g, flanks)?;
            let gr = other_pair.as_ref().unwrap_or(g);
            let fp = gr.side(side);
            let rs = roll_surface(fp, &sc.utca)?;
            let sweep = scene_sweep(scene, gr, wb);
            let run = FlankRun {
                scene,
                ls,
                blanks: pair.blanks,
                bodies,
                pc: &pc,
                flanks,
                gr,
                rs: &rs,
                sweep: &sweep,
                omega,
                torques: &torques,
                design: &design,
            };
            for &torque in &torques {
                all.push(torque_run(&run, torque, &mut rough, set.path())?);
            }
        }
        Ok(())
    })?;
    write_json(&set.path().join("summary.json"), &all)?;
    set.commit()?;
    Ok(all)
}

/// The pair of flank variant `flanks`: `None` for the design's own (`g`),
/// else the roughened or varied design built; with what it used.
fn flank_geometry(
    scene: &LoadedScene,
    ls: &LumpedSettings,
    g: &PairGeometry,
    flanks: Flanks,
) -> anyhow::Result<(
    Option<PairGeometry>,
    Option<RoughnessSummary>,
    Option<DesignVariantSummary>,
)> {
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    Ok(match flanks {
        Flanks::Rough(ra) => {
            let Some(r) = ls.roughness.as_ref() else {
                anyhow::bail!(
                    "scene {}: a roughness grade without [lumped.roughness]",
                    sc.name
                );
            };
            let (p, summary) = roughened(
                &scene.pair,
                g.side(side),
                ra,
                r.seed,
                [r.profile_nodes, r.face_nodes],
                sc.mesh.reduced_order.profile as usize,
            )?;
            let other_pair = PairGeometry::build(&p, Some(&scene.design_path))
                .with_context(|| format!("scene {}: the pair with Ra {ra} µm", sc.name))?;
            (Some(other_pair), Some(summary), None)
        }
        Flanks::Variant(v) => {
            let (p, summary) = varied(&scene.pair, v);
            let other_pair = PairGeometry::build(&p, Some(&scene.design_path))
                .with_context(|| format!("scene {}: design variant {}", sc.name, v.name))?;
            (Some(other_pair), None, Some(summary))
        }
        Flanks::Design => (None, None, None),
    })
}

/// What every operating torque of one blank pair and flank variant shares.
struct FlankRun<'a> {
    scene: &'a LoadedScene,
    ls: &'a LumpedSettings,
    blanks: [Blank; 2],
    bodies: [BodyProperties; 2],
    pc: &'a PairCompliance,
    flanks: Flanks<'a>,
    /// The variant's pair, its surface of roll angles and sweep.
    gr: &'a PairGeometry,
    rs: &'a RollSurface,
    sweep: &'a Sweep,
    /// Pinion speed, rad/s.
    omega: f64,
    /// Every operating torque (the first on the design's flanks is the
    /// scene's base run).
    torques: &'a [f64],
    design: &'a Option<DesignVariantSummary>,
}

/// One operating torque: the LTCA, its fitted excitation, engagement and
/// slice friction, the lumped run and its files under `staging`; the
/// roughness summary takes the run's Hertz half-width.
fn torque_run(
    r: &FlankRun,
    torque: f64,
    rough: &mut Option<RoughnessSummary>,
    staging: &Path,
) -> anyhow::Result<LumpedSummary> {
    let (scene, ls, gr, flanks, omega) = (r.scene, r.ls, r.gr, r.flanks, r.omega);
    let (rs, sweep, pc, torques) = (r.rs, r.sweep, r.pc, r.torques);
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    let fp = gr.side(side);
    let [pb, wb] = r.blanks;
    let res = run_sweep(fp, rs, pc, sweep, &tangent_torques(torque))
        .with_context(|| format!("scene {}: LTCA for the lumped model", sc.name))?;
    let samples = mesh_samples(&res, torque, omega, gr.data.mesh_cycle())?;
    let [kf, ef, df] = fit_series(&samples, ls.fourier_tolerance_of_ptp)?;
    let tau = fp.pinion.gen.frame.pitch();
    let geo = |k: usize| {
        let phi = sweep.start + sweep.direction * res[k].rotation;
        (phi, geometry(fp, rs, phi, tau, sweep.slices))
    };
    let lag = |k: usize, pair: i32| {
        geo(k)
            .1
            .slices
            .iter()
            .filter(|s| s.pair == pair)
            .map(|s| s.lag)
            .reduce(f64::min)
    };
    let eng = engagement(&res, &samples, omega, lag);
    if let Some(r) = rough.as_mut() {
        let (fb, f) = res
            .iter()
            .flat_map(|p| p.loads[1].slices.iter())
            .fold((0.0, 0.0), |(fb, f), s| {
                (fb + s.force_n * s.half_width_m, f + s.force_n)
            });
        r.hertz_half_width_m = if f > 0.0 { fb / f } else { 0.0 };
    }
    let slice_friction = (0..samples.time_s.len())
        .map(|k| {
            let (phi, gk) = geo(k);
            slice_friction(fp, phi, tau, &gk.slices, &res[k].loads[1].slices)
        })
        .collect::<Vec<_>>();
    // The first torque on the design's own flanks is the
    // scene's base run: no suffix.
    let variant = if torque == torques[0] && matches!(flanks, Flanks::Design) {
        String::new()
    } else {
        format!("t{torque}_{}", flanks.label())
    };
    let mut name = format!("{pb:?}_{wb:?}").to_lowercase();
    if !variant.is_empty() {
        name = format!("{name}_{variant}");
    }
    let odir = staging.join(&name);
    std::fs::create_dir_all(&odir)?;
    let case = Case {
        ls,
        torque,
        blanks: [pb, wb],
        side,
        g: gr,
        bodies: r.bodies,
        samples: &samples,
        fits: [&kf, &ef, &df],
        eng,
        slice_friction,
        roughness: rough.clone(),
        design: r.design.clone(),
        contact_ratio: loaded_contact_ratio(&res, samples.time_s.len()),
        variant,
        max_order: MAX_ORDER,
    };
    let (summary, _) = run_blank(&case, &odir)?;
    eprintln!(
        "lumped {pb:?}/{wb:?} {}: k mean {:.4e} N/m ({} harmonics), μ {:.3}, RMS along the normal {:.2} m/s², pinion velocity RMS {:.3} mm/s, {} steps, {:.2} s",
        summary.variant,
        summary.mesh_stiffness_n_per_m.mean,
        summary.mesh_stiffness_n_per_m.harmonics.len(),
        summary.friction_coefficient,
        summary.rms_acceleration_m_s2.mesh_normal,
        1e3 * summary.member_velocity_rms_m_s[0],
        summary.steps[0],
        summary.integration_wall_s
    );
    write_json(&odir.join("summary.json"), &summary)?;
    Ok(summary)
}
