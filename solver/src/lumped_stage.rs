//! `solver lumped <scene>`: the 8-DOF lumped model of every pinion × wheel
//! blank of a scene with a `[lumped]` section, driven by our LTCA at the
//! operating torque, to `<out>/<scene>/lumped/<pinion>_<wheel>/`:
//! `time_history.csv`, `mesh_excitation.csv`, `bearing_spectrum.csv` and
//! `summary.json` ([`formats::lumped_summary::LumpedSummary`]) and the charts
//! of [`crate::lumped_plots`], written as one result set.

use crate::compliance::PairCompliance;
use crate::ltca::{geometry, run as run_sweep};
use crate::ltca_stage::{member_compliance, record_stiffness_inputs, scene_sweep};
use crate::lumped::excitation::{
    seed004_impact_force, FittedSeries, ImpactPulse, MeshExcitation, StaticError,
};
use crate::lumped::friction::{
    per_unit_force, seed003_coefficient, FrictionExcitation, FrictionGeometry, SliceFriction,
};
use crate::lumped::from_ltca::{fit_series, mesh_samples, tangent_torques, MeshSamples};
use crate::lumped::impact::engagement;
use crate::lumped::model::{direction_cosines, mesh_damping_for_ratio, Member, Model, WheelHand};
use crate::lumped::response::{response, Response};
use crate::lumped::run::simulate;
use crate::lumped_roughness::roughened;
use crate::slices::friction_direction;
use anyhow::Context;
use formats::lumped_summary::{
    DesignVariantSummary, Directions, ImpactSummary, LumpedSummary, SeriesSummary,
};
use formats::manifest::Manifest;
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use geometry::design::PairData;
use geometry::design::{Hand, Member as Which};
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::scene_lumped::{DesignVariant, DirectionSource, ImpactModel, LumpedSettings};
use geometry::utca::roll_surface;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Spectrum range, mesh orders.
const MAX_ORDER: f64 = 5.0;

fn series_summary(f: &FittedSeries) -> SeriesSummary {
    SeriesSummary {
        mean: f.series.mean,
        harmonics: f.series.amplitudes(),
        max_residual_of_ptp: f.max_residual_of_ptp,
        tolerance_of_ptp: f.tolerance_of_ptp,
        met: f.met,
    }
}

fn directions(v: [f64; 7]) -> Directions {
    Directions {
        pinion_x: v[0],
        pinion_y: v[1],
        pinion_z: v[2],
        wheel_x: v[3],
        wheel_y: v[4],
        wheel_z: v[5],
        mesh_normal: v[6],
    }
}

/// Natural frequencies (Hz) of the linear model at stiffness `k`, the rigid
/// rotation left out.
pub fn natural_frequencies(model: &Model, k: f64) -> Vec<f64> {
    let kmat = model.stiffness(k);
    let m = model.mass_diagonal();
    let s: Vec<f64> = m.iter().map(|x| 1.0 / x.sqrt()).collect();
    let a = nalgebra::DMatrix::from_fn(8, 8, |i, j| s[i] * kmat[(i, j)] * s[j]);
    let mut w: Vec<f64> = nalgebra::SymmetricEigen::new(a)
        .eigenvalues
        .iter()
        .map(|l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    w.sort_by(f64::total_cmp);
    w.into_iter().skip(1).collect()
}

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
            "scene {}: no [lumped] section; add one (see geometry/src/scene_lumped.rs) to run the lumped model",
            sc.name
        );
    };
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("lumped"),
        &format!("solver lumped {}", scene.path.display()),
    )?;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = sc.loaded_flank;
    let dir = meshes.join(&sc.name);
    let manifest = Manifest::read(&dir)?;
    let torques = torques(ls);
    let variants = flank_variants(ls);
    if let Some(om) = &ls.order_map {
        let all = crate::lumped_order_map::run(scene, ls, om, &g, &dir, &manifest, &mut set)?;
        write_json(&set.path().join("summary.json"), &all)?;
        set.commit()?;
        return Ok(all);
    }
    let omega = ls.pinion_speed_rpm * std::f64::consts::PI / 30.0;
    let mut all = Vec::new();
    for &pb in &sc.blanks.pinion {
        let (pin, pin_plan) = member_compliance(scene, &g, &dir, Which::Pinion, pb)?;
        for &wb in &sc.blanks.wheel {
            let (whl, whl_plan) = member_compliance(scene, &g, &dir, Which::Wheel, wb)?;
            record_stiffness_inputs(&mut set, scene, &g, &dir, [pb, wb], false)?;
            let body = |stem: &str| -> anyhow::Result<_> { Ok(manifest.mesh(&dir, stem)?.body) };
            let bodies = [body(&pin_plan.mesh_stem)?, body(&whl_plan.mesh_stem)?];
            let pc = PairCompliance {
                pinion: pin.clone(),
                wheel: whl,
            };
            for flanks in &variants {
                let other_pair;
                let (gr, mut rough, design) = match flanks {
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
                            *ra,
                            r.seed,
                            [r.profile_nodes, r.face_nodes],
                            sc.mesh.reduced_order.profile as usize,
                        )?;
                        other_pair = PairGeometry::build(&p, Some(&scene.design_path))
                            .with_context(|| {
                                format!("scene {}: the pair with Ra {ra} µm", sc.name)
                            })?;
                        (&other_pair, Some(summary), None)
                    }
                    Flanks::Variant(v) => {
                        let (p, summary) = varied(&scene.pair, v);
                        other_pair = PairGeometry::build(&p, Some(&scene.design_path))
                            .with_context(|| {
                                format!("scene {}: design variant {}", sc.name, v.name)
                            })?;
                        (&other_pair, None, Some(summary))
                    }
                    Flanks::Design => (&g, None, None),
                };
                let fp = gr.side(side);
                let rs = roll_surface(fp, &sc.utca)?;
                let sweep = scene_sweep(scene, gr, wb);
                for &torque in &torques {
                    let res = run_sweep(fp, &rs, &pc, &sweep, &tangent_torques(torque))
                        .with_context(|| format!("scene {}: LTCA for the lumped model", sc.name))?;
                    let samples = mesh_samples(&res, torque, omega, gr.data.mesh_cycle())?;
                    let [kf, ef, df] = fit_series(&samples, ls.fourier_tolerance_of_ptp)?;
                    let tau = fp.pinion.gen.frame.pitch();
                    let geo = |k: usize| {
                        let phi = sweep.start + sweep.direction * res[k].rotation;
                        (phi, geometry(fp, &rs, phi, tau, sweep.slices))
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
                    let odir = set.path().join(&name);
                    std::fs::create_dir_all(&odir)?;
                    let case = Case {
                        ls,
                        torque,
                        blanks: [pb, wb],
                        side,
                        g: gr,
                        bodies,
                        samples: &samples,
                        fits: [&kf, &ef, &df],
                        eng,
                        slice_friction,
                        roughness: rough.clone(),
                        design: design.clone(),
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
                    all.push(summary);
                }
            }
        }
    }
    write_json(&set.path().join("summary.json"), &all)?;
    set.commit()?;
    Ok(all)
}

/// The friction data of one position: each loaded slice's force, sliding
/// direction and normal on the pinion axis, the wheel axis and their cross
/// product, and its friction levers (the loaded slice matched to the
/// geometry's by tooth pair and (ξ, η), which the LTCA copies from it).
/// Slices carry tooth 0's point and normal: pair j's are seen at pinion
/// angle φ + jτ, as the slicing does.
pub fn slice_friction(
    fp: &geometry::pair::FlankPair,
    phi: f64,
    tau: f64,
    geo: &[crate::slices::Slice],
    loaded: &[crate::ltca::SliceLoad],
) -> Vec<SliceFriction> {
    let (pf, wf) = (&fp.pinion.gen.frame, &fp.wheel.gen.frame);
    loaded
        .iter()
        .filter_map(|l| {
            let s = geo
                .iter()
                .find(|s| s.pair == l.pair && s.xi == l.xi && s.eta == l.eta)?;
            let target = phi + s.pair as f64 * tau;
            let a2 = pf.to_member(&wf.axis(), target);
            let ey = [a2[0], a2[1], a2[2]].map(|c| c / a2.norm());
            let ex = [0.0, 0.0, 1.0];
            let ez = [-ey[1], ey[0], 0.0];
            let zn = ez[0].hypot(ez[1]);
            let ez = ez.map(|c| c / zn);
            let on = |v: [f64; 3]| [ex, ey, ez].map(|e| e.iter().zip(v).map(|(a, b)| a * b).sum());
            let u = friction_direction(fp, s.pos, s.normal, target).unwrap_or([0.0; 3]);
            Some(SliceFriction {
                force_n: l.force_n,
                direction: on(u),
                normal: on(s.normal),
                levers_m: s.friction_lever,
            })
        })
        .collect()
}

/// One run: the settings, the operating torque, the LTCA's excitation and
/// what else the run takes.
pub(crate) struct Case<'a> {
    pub(crate) ls: &'a LumpedSettings,
    pub(crate) torque: f64,
    pub(crate) blanks: [Blank; 2],
    pub(crate) side: Side,
    pub(crate) g: &'a PairGeometry,
    pub(crate) bodies: [formats::manifest::BodyProperties; 2],
    pub(crate) samples: &'a MeshSamples,
    pub(crate) fits: [&'a FittedSeries; 3],
    pub(crate) eng: Option<crate::lumped::impact::Engagement>,
    pub(crate) slice_friction: Vec<Vec<SliceFriction>>,
    pub(crate) roughness: Option<formats::lumped_summary::RoughnessSummary>,
    pub(crate) design: Option<DesignVariantSummary>,
    pub(crate) contact_ratio: f64,
    pub(crate) variant: String,
    /// Spectrum range, mesh orders.
    pub(crate) max_order: f64,
}

/// One run: model, excitation, integration, files; the summary and the
/// bearing-force spectrum (mesh order, pinion N, wheel N).
pub(crate) fn run_blank(
    case: &Case,
    odir: &Path,
) -> anyhow::Result<(LumpedSummary, Vec<[f64; 3]>)> {
    let Case {
        ls,
        torque,
        blanks: [pinion_blank, wheel_blank],
        side,
        g,
        bodies,
        samples,
        fits: [kf, ef, df],
        eng,
        ..
    } = *case;
    let d = &g.data;
    let mass = [
        ls.pinion_mass_kg
            .unwrap_or(bodies[0].volume_m3 * bodies[0].density_kg_m3),
        ls.wheel_mass_kg
            .unwrap_or(bodies[1].volume_m3 * bodies[1].density_kg_m3),
    ];
    let inertia = [
        ls.pinion_inertia_kgm2
            .unwrap_or(bodies[0].polar_moment_kgm2),
        ls.wheel_inertia_kgm2.unwrap_or(bodies[1].polar_moment_kgm2),
    ];
    let hand = match d.members[1].hand {
        Hand::Left => WheelHand::Left,
        Hand::Right => WheelHand::Right,
    };
    let flank = d.pressure_angle[side.index()];
    let member = |i: usize, k: [f64; 3]| Member {
        mass_kg: mass[i],
        inertia_kgm2: inertia[i],
        bearing_stiffness_n_per_m: k,
        bearing_damping_ns_per_m: k
            .map(|kk| 2.0 * ls.bearing_damping_ratio * (kk * mass[i]).sqrt()),
    };
    let mut model = Model {
        members: [
            member(0, ls.pinion_bearing_stiffness_n_per_m),
            member(1, ls.wheel_bearing_stiffness_n_per_m),
        ],
        direction: direction_cosines(flank, d.spiral_angle, d.members[1].pitch_angle, hand, side),
        levers_m: samples.levers_m,
        mesh_damping_ns_per_m: 0.0,
        pinion_torque_nm: torque,
    };
    model.mesh_damping_ns_per_m = mesh_damping_for_ratio(
        ls.mesh_damping_ratio,
        kf.series.mean,
        model.equivalent_mass(),
    );
    let period = samples.period_s;
    let mesh_hz = 1.0 / period;
    let (fs, v_s, k_s, rot) = match eng {
        Some(e) => (
            seed004_impact_force(
                e.velocity_m_s,
                e.pair_stiffness_n_per_m,
                inertia,
                model.levers_m,
            ),
            e.velocity_m_s,
            e.pair_stiffness_n_per_m,
            e.rotation,
        ),
        None => (0.0, 0.0, 0.0, 0.0),
    };
    let pulse = ls.impact_pulse_of_mesh_period * period;
    let omega = ls.pinion_speed_rpm * std::f64::consts::PI / 30.0;
    let impact = match ls.impact {
        ImpactModel::Seed004 if fs > 0.0 => Some(ImpactPulse {
            peak_n: fs,
            duration_s: pulse,
            start_s: (rot / omega).rem_euclid(period),
            period_s: period,
        }),
        _ => None,
    };
    let FrictionGeometry {
        per_unit_force: g,
        normal,
        angle_deg: angle,
    } = per_unit_force(&case.slice_friction, model.direction)?;
    if ls.direction_cosines == DirectionSource::Ltca {
        model.direction = normal;
    }
    let friction = match &ls.friction {
        Some(f) => {
            let r = case.roughness.as_ref().map_or(0.0, |r| r.ra_um);
            // Both flanks of roughness Ra: R = √(Ra² + Ra²).
            let mu =
                seed003_coefficient(f.base_coefficient, f.roughness_coefficient_per_um, [r, r]);
            Some(FrictionExcitation::new(
                mu,
                samples.time_s.clone(),
                g,
                period,
            )?)
        }
        None => None,
    };
    let exc = MeshExcitation {
        stiffness: kf.series.clone(),
        transmission_error: StaticError::LoadedDeflection {
            deflection: df.series.clone(),
            force_n: model.mean_mesh_force(),
        },
        impact,
        friction,
    };
    let t0 = Instant::now();
    let h = simulate(
        &model,
        &exc,
        mesh_hz,
        ls.mesh_cycles,
        ls.samples_per_mesh_cycle,
        ls.relative_tolerance,
    )?;
    let wall = t0.elapsed().as_secs_f64();
    let first =
        h.t.iter()
            .position(|t| *t >= ls.dropped_mesh_cycles * period * (1.0 - 1e-12))
            .unwrap_or(0);
    let r = response(&model, &exc, &h, first, mesh_hz, case.max_order);
    write_files(odir, &model, &exc, &h, samples, &r)?;
    let label = format!(
        "{pinion_blank:?} pinion / {wheel_blank:?} wheel, {} rpm",
        ls.pinion_speed_rpm
    );
    crate::lumped_plots::write_plots(
        odir,
        &label,
        &h,
        first,
        mesh_hz,
        model.mean_mesh_force(),
        &r,
        case.max_order,
    )?;
    let share = r
        .rms_acceleration
        .map(|a| 100.0 * a / r.rms_acceleration[6]);
    let f_static = model.mean_mesh_force();
    let summary = LumpedSummary {
        pinion_blank,
        wheel_blank,
        pinion_speed_rpm: ls.pinion_speed_rpm,
        mesh_frequency_hz: mesh_hz,
        pinion_torque_nm: torque,
        mesh_cycles: ls.mesh_cycles,
        dropped_mesh_cycles: ls.dropped_mesh_cycles,
        direction_cosines: model.direction,
        levers_m: model.levers_m,
        masses_kg: mass,
        inertias_kgm2: inertia,
        mesh_damping_ns_per_m: model.mesh_damping_ns_per_m,
        bearing_stiffness_n_per_m: [
            ls.pinion_bearing_stiffness_n_per_m,
            ls.wheel_bearing_stiffness_n_per_m,
        ],
        bearing_damping_ratio: ls.bearing_damping_ratio,
        mesh_stiffness_n_per_m: series_summary(kf),
        secant_mesh_stiffness_mean_n_per_m: samples.secant_n_per_m.iter().sum::<f64>()
            / samples.secant_n_per_m.len() as f64,
        transmission_error_m: series_summary(ef),
        loaded_deflection_m: series_summary(df),
        natural_frequencies_hz: natural_frequencies(&model, kf.series.mean),
        impact: ImpactSummary {
            model: match ls.impact {
                ImpactModel::Engagement => "engagement".into(),
                ImpactModel::Seed004 => "seed004".into(),
            },
            seed004_force_n: fs,
            velocity_m_s: v_s,
            entering_pair_stiffness_n_per_m: k_s,
            first_loaded_rotation_deg: rot.to_degrees(),
            applied_peak_n: impact.map_or(0.0, |p| p.peak_n),
            pulse_s: impact.map_or(0.0, |p| p.duration_s),
        },
        impact_force_n: impact.map_or(0.0, |p| p.peak_n),
        rms_acceleration_m_s2: directions(r.rms_acceleration),
        relative_normal_acceleration_rms_m_s2: r.relative_normal_rms,
        rms_acceleration_share_percent: directions(share),
        peak_to_peak_displacement_m: directions(r.peak_to_peak),
        mesh_force_mean_n: r.mesh_force[0],
        mesh_force_min_n: r.mesh_force[1],
        mesh_force_max_n: r.mesh_force[2],
        dynamic_factor: r.mesh_force[2] / f_static,
        pinion_bearing_force_rms_n: [r.bearing_rms[0], r.bearing_rms[1], r.bearing_rms[2]],
        wheel_bearing_force_rms_n: [r.bearing_rms[3], r.bearing_rms[4], r.bearing_rms[5]],
        bearing_force_peaks: r.bearing_peaks.clone(),
        steps: h.steps,
        evaluations: h.evaluations,
        integration_wall_s: wall,
        variant: case.variant.clone(),
        roughness: case.roughness.clone(),
        design_variant: case.design.clone(),
        loaded_contact_ratio: case.contact_ratio,
        friction_coefficient: exc.friction.as_ref().map_or(0.0, |f| f.coefficient),
        friction_normal_angle_deg: angle,
        ltca_normal_model_axes: normal,
        rms_velocity_m_s: directions(r.rms_velocity),
        member_velocity_rms_m_s: r.member_velocity_rms,
    };
    Ok((summary, r.bearing_spectrum))
}

fn write_files(
    odir: &Path,
    model: &Model,
    exc: &MeshExcitation,
    h: &crate::lumped::integrate::History,
    samples: &MeshSamples,
    r: &Response,
) -> anyhow::Result<()> {
    let mut s = String::from("time_s,x1_m,y1_m,z1_m,theta1_rad,x2_m,y2_m,z2_m,theta2_rad,ax1_m_s2,ay1_m_s2,az1_m_s2,ax2_m_s2,ay2_m_s2,az2_m_s2,lambda_m,mesh_stiffness_n_per_m,mesh_force_n,impact_n,bearing1_x_n,bearing1_y_n,bearing1_z_n,bearing2_x_n,bearing2_y_n,bearing2_z_n\n");
    for i in 0..h.t.len() {
        let (q, a, m) = (&h.q[i], &h.qdd[i], &h.mesh[i]);
        let b1 = model.bearing_force(0, q, &h.qd[i]);
        let b2 = model.bearing_force(1, q, &h.qd[i]);
        let _ = write!(s, "{:.9e}", h.t[i]);
        for v in q.iter().chain([a[0], a[1], a[2], a[4], a[5], a[6]].iter()) {
            let _ = write!(s, ",{v:.6e}");
        }
        for v in [m.lambda_m, m.stiffness_n_per_m, m.force_n, m.impact_n]
            .iter()
            .chain(b1.iter())
            .chain(b2.iter())
        {
            let _ = write!(s, ",{v:.6e}");
        }
        s.push('\n');
    }
    write_atomic(&odir.join("time_history.csv"), s.as_bytes())?;
    let mut e = String::from("time_s,tangent_stiffness_n_per_m,secant_stiffness_n_per_m,stiffness_series_n_per_m,te_m,te_series_m,loaded_te_rad,unloaded_te_rad\n");
    for i in 0..samples.time_s.len() {
        let t = samples.time_s[i];
        let _ = writeln!(
            e,
            "{t:.9e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
            samples.tangent_n_per_m[i],
            samples.secant_n_per_m[i],
            exc.stiffness.value(t),
            samples.te_m[i],
            exc.te(t)[0],
            samples.loaded_te_rad[i],
            samples.unloaded_te_rad[i]
        );
    }
    write_atomic(&odir.join("mesh_excitation.csv"), e.as_bytes())?;
    let mut b = String::from("mesh_order,pinion_bearing_force_n,wheel_bearing_force_n\n");
    for l in &r.bearing_spectrum {
        let _ = writeln!(b, "{:.5},{:.6e},{:.6e}", l[0], l[1], l[2]);
    }
    write_atomic(&odir.join("bearing_spectrum.csv"), b.as_bytes())?;
    Ok(())
}
