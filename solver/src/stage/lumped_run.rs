//! One run of `solver lumped`: the 8-DOF model of a pinion × wheel blank
//! at one torque and flank variant ([`Case`]) built, integrated and
//! written to its folder; shared by the mesh-cycle runs
//! ([`crate::stage::lumped`]) and the whole-revolution order map
//! ([`crate::stage::lumped_order_map`]).

use crate::lumped::excitation::{
    seed004_impact_force, FittedSeries, ImpactPulse, MeshExcitation, StaticError,
};
use crate::lumped::friction::{
    per_unit_force, seed003_coefficient, FrictionExcitation, FrictionGeometry, SliceFriction,
};
use crate::lumped::from_ltca::MeshSamples;
use crate::lumped::integrate::History;
use crate::lumped::model::{direction_cosines, mesh_damping_for_ratio, Member, Model, WheelHand};
use crate::lumped::response::{response, Response};
use crate::lumped::run::simulate;
use formats::lumped_summary::{
    DesignVariantSummary, Directions, ImpactSummary, LumpedSummary, SeriesSummary,
};
use formats::output::write_atomic;
use geometry::design::Hand;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::Blank;
use geometry::scene_lumped::{DirectionSource, ImpactModel, LumpedSettings};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

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
        blanks: [pinion_blank, wheel_blank],
        samples,
        ..
    } = *case;
    let (mut model, mass, inertia) = model_of(case);
    let period = samples.period_s;
    let mesh_hz = 1.0 / period;
    let (engaging, impact) = impact_of(case, &model, inertia);
    let (exc, normal, angle) = excitation(case, &mut model, impact)?;
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
    crate::stage::lumped_plots::write_plots(
        odir,
        &label,
        &h,
        first,
        mesh_hz,
        model.mean_mesh_force(),
        &r,
        case.max_order,
    )?;
    let summary = summary_of(
        case,
        &Outcome {
            model: &model,
            mass,
            inertia,
            mesh_hz,
            engaging,
            impact,
            exc: &exc,
            normal,
            angle,
            h: &h,
            wall,
            r: &r,
        },
    );
    Ok((summary, r.bearing_spectrum))
}

/// The seed-004 impact estimate at the engagement: force (N), velocity
/// (m/s), the entering pair's stiffness (N/m) and the first loaded
/// rotation (rad); zeros without an engagement.
#[derive(Clone, Copy)]
struct Engaging {
    force_n: f64,
    velocity_m_s: f64,
    stiffness_n_per_m: f64,
    rotation: f64,
}

/// What a run gives besides its case, for the summary.
struct Outcome<'a> {
    model: &'a Model,
    mass: [f64; 2],
    inertia: [f64; 2],
    mesh_hz: f64,
    engaging: Engaging,
    impact: Option<ImpactPulse>,
    exc: &'a MeshExcitation,
    /// The LTCA's force-weighted flank normal and its angle to the model's
    /// direction cosines, deg.
    normal: [f64; 3],
    angle: f64,
    h: &'a History,
    /// Integration wall time, s.
    wall: f64,
    r: &'a Response,
}

/// The 8-DOF model of the case (its mesh damping from the ratio), with the
/// masses and polar moments it uses.
fn model_of(case: &Case) -> (Model, [f64; 2], [f64; 2]) {
    let Case {
        ls,
        torque,
        side,
        g,
        bodies,
        samples,
        fits: [kf, ..],
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
    (model, mass, inertia)
}

/// The seed-004 impact estimate at the case's engagement, and the impact
/// pulse the run applies (seed 004's model with a positive force).
fn impact_of(case: &Case, model: &Model, inertia: [f64; 2]) -> (Engaging, Option<ImpactPulse>) {
    let Case {
        ls, samples, eng, ..
    } = *case;
    let period = samples.period_s;
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
    let engaging = Engaging {
        force_n: fs,
        velocity_m_s: v_s,
        stiffness_n_per_m: k_s,
        rotation: rot,
    };
    (engaging, impact)
}

/// The mesh excitation: the fitted stiffness and loaded deflection, the
/// impact pulse and the friction of the slices (the model's direction
/// cosines replaced by the LTCA's normal where the settings ask); with that
/// normal and its angle to the model's direction cosines, deg.
fn excitation(
    case: &Case,
    model: &mut Model,
    impact: Option<ImpactPulse>,
) -> anyhow::Result<(MeshExcitation, [f64; 3], f64)> {
    let Case {
        ls,
        samples,
        fits: [kf, _, df],
        ..
    } = *case;
    let period = samples.period_s;
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
    Ok((exc, normal, angle))
}

/// The run's `summary.json`.
fn summary_of(case: &Case, o: &Outcome) -> LumpedSummary {
    let Case {
        ls,
        torque,
        blanks: [pinion_blank, wheel_blank],
        samples,
        fits: [kf, ef, df],
        ..
    } = *case;
    let (model, mass, inertia, mesh_hz) = (o.model, o.mass, o.inertia, o.mesh_hz);
    let (impact, exc, normal, angle) = (o.impact, o.exc, o.normal, o.angle);
    let (h, wall, r) = (o.h, o.wall, o.r);
    let Engaging {
        force_n: fs,
        velocity_m_s: v_s,
        stiffness_n_per_m: k_s,
        rotation: rot,
    } = o.engaging;
    let share = r
        .rms_acceleration
        .map(|a| 100.0 * a / r.rms_acceleration[6]);
    let f_static = model.mean_mesh_force();
    LumpedSummary {
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
        natural_frequencies_hz: model.natural_frequencies(kf.series.mean),
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
    }
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
