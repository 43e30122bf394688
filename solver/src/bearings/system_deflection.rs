//! Quasi-static loaded TCA with compliant bearings at one position: the
//! mesh force moves both members on their bearings ([`crate::bearings::support`]),
//! the moved members change the pair's relative pose (a load-dependent
//! misalignment, [`geometry::misalignment`]), and the contact is solved
//! again on that pose until the members' displacements settle.
//!
//! Iteration k: the LTCA on the poses Pₖ gives the slice forces Fᵢ ≥ 0 at
//! the pinion contact points xᵢ with the pinion's outward normals nᵢ
//! (fixed frame, the poses applied). The contact's wrench on the pinion
//! about the common apex is g₁ = Σ [−Fᵢ nᵢ; xᵢ × (−Fᵢ nᵢ)], on the wheel
//! g₂ = −g₁. Each member's bearings carry its wrench but the moment about
//! its own axis (the shaft torque): displacement dₘ = Sₘ⁻¹ gₘ. The next
//! poses are Pₖ₊₁ = D(dₘ) ∘ P_static (D: the small rigid displacement as a
//! pose, rotation about the apex then translation), the step halved from
//! the third iteration on (slices entering and leaving contact make the
//! plain iteration alternate). Converged when a member's displacement
//! changes by no more than `tolerance_m` (rotations times 0.1 m); the
//! exact contact search's own noise is about 1e-11 m.
//!
//! The normal forces alone load the bearings; the LTCA here runs
//! frictionless (friction forces would add μ of the normal load to the
//! wrench, and are left to the caller's friction-free check).

use crate::bearings::support::{Bearing, BearingError, Displacement, Support};
use crate::element::compliance::PairCompliance;
use crate::ltca::{assemble, geometry, mean_ptp, solve, Sweep};
use crate::SolverError;
use formats::summaries::BearingLoadSummary;
use geometry::generation::Side;
use geometry::misalignment::{BodyPoses, Pose};
use geometry::pair::PairGeometry;
use geometry::scene::UtcaSettings;
use geometry::scene_bearings::BearingSettings;
use geometry::utca::roll_surface;
use nalgebra::{Rotation3, Vector3, Vector6};
use rayon::prelude::*;

/// Both members' supports, fixed frame (apices at the origin).
#[derive(Debug, Clone)]
pub struct Supports {
    pub pinion: Support,
    pub wheel: Support,
}

/// Settings of the iteration.
#[derive(Debug, Clone, Copy)]
pub struct DeflectionSettings {
    /// Slices per tooth pair.
    pub slices: usize,
    /// Largest change of a member displacement (translation, and rotation
    /// times 0.1 m) between iterations at convergence, m.
    pub tolerance_m: f64,
    pub max_iterations: usize,
}

/// One position's converged state.
#[derive(Debug, Clone)]
pub struct DeflectedPosition {
    /// Loaded TE on the deflected poses, rad.
    pub te: f64,
    /// Loaded TE with rigid bearings (the first iteration), rad.
    pub te_rigid_bearings: f64,
    /// Members' displacements on their bearings.
    pub pinion: Displacement,
    pub wheel: Displacement,
    /// Each bearing's force on its member, N (in the order given).
    pub pinion_reactions: Vec<Vector3<f64>>,
    pub wheel_reactions: Vec<Vector3<f64>>,
    /// The contact's wrench on the pinion about the apex, [N; N·m].
    pub pinion_wrench: Vector6<f64>,
    /// The torque about the pinion's (moved) axis that the contact forces
    /// exert, N·m: the applied torque to rounding.
    pub pinion_contact_torque_nm: f64,
    /// The poses the contact was solved on last.
    pub poses: BodyPoses,
    pub iterations: usize,
}

/// A small rigid displacement as a pose: rotation θ about the apex, then
/// translation u.
pub fn displacement_pose(d: &Displacement) -> Pose {
    Pose {
        rotation: *Rotation3::new(d.rotation).matrix(),
        translation: d.translation,
    }
}

/// Weight of the new displacement after the second iteration.
const RELAXATION: f64 = 0.5;

/// (1 − w) a + w b.
fn blend(a: &Displacement, b: &Displacement, w: f64) -> Displacement {
    Displacement {
        translation: a.translation * (1.0 - w) + b.translation * w,
        rotation: a.rotation * (1.0 - w) + b.rotation * w,
    }
}

/// Largest change between two displacements, rotations weighted by 0.1 m.
fn change(a: &Displacement, b: &Displacement) -> f64 {
    (a.translation - b.translation)
        .amax()
        .max(0.1 * (a.rotation - b.rotation).amax())
}

/// Solves the position at pinion angle `phi` and pinion torque `torque`
/// (N·m) with the members on `supports`; `static_poses` are the scene's
/// misalignments (None: aligned). `g` is placed on the converged poses on
/// return.
#[allow(clippy::too_many_arguments)]
pub fn deflected_position(
    g: &mut PairGeometry,
    side: Side,
    utca: &UtcaSettings,
    pc: &PairCompliance,
    supports: &Supports,
    static_poses: Option<BodyPoses>,
    phi: f64,
    torque: f64,
    settings: DeflectionSettings,
) -> Result<DeflectedPosition, SolverError> {
    let base = static_poses.unwrap_or(BodyPoses {
        pinion: Pose::identity(),
        wheel: Pose::identity(),
    });
    let zero = Displacement {
        translation: Vector3::zeros(),
        rotation: Vector3::zeros(),
    };
    let (mut d1, mut d2) = (zero, zero);
    let mut te_rigid = f64::NAN;
    for it in 0..settings.max_iterations {
        // Every iteration on the posed contact path (the aligned model plus
        // the pose's exact change, geometry::mate::pose_correction), the
        // first with the members where the scene puts them (rigid
        // bearings), so that both TEs come from one contact search.
        let poses = BodyPoses {
            pinion: displacement_pose(&d1).after(&base.pinion),
            wheel: displacement_pose(&d2).after(&base.wheel),
        };
        g.set_poses(Some(poses));
        let fp = g.side(side);
        let rs = roll_surface(fp, utca)
            .map_err(|e| SolverError::Table(format!("roll surface on the deflected pose: {e}")))?;
        let tau = fp.pinion.gen.frame.pitch();
        let geo = geometry(fp, &rs, phi, tau, settings.slices);
        if geo.slices.is_empty() {
            return Err(SolverError::NoContact);
        }
        let a = assemble(&geo, pc, 0.0)?;
        let s = solve(&a, torque, None)?;
        if it == 0 {
            te_rigid = s.theta;
        }
        // The wrench on the pinion, fixed frame.
        let frame = &fp.pinion.gen.frame;
        let mut w = Vector6::zeros();
        for (sl, &f) in geo.slices.iter().zip(&s.force) {
            if f <= 0.0 {
                continue;
            }
            let turn = phi + sl.pair as f64 * tau;
            let x = poses
                .pinion
                .apply(&frame.to_fixed(&Vector3::from(sl.pos), turn));
            let n = poses.pinion.rotation * frame.to_fixed(&Vector3::from(sl.normal), turn);
            let force = -f * n;
            let m = x.cross(&force);
            w += Vector6::new(force.x, force.y, force.z, m.x, m.y, m.z);
        }
        let n1 = supports.pinion.displacement(&w);
        let n2 = supports.wheel.displacement(&(-w));
        let moved = change(&n1, &d1).max(change(&n2, &d2));
        if it > 0 && moved <= settings.tolerance_m {
            // The contact torque about the moved pinion axis through its
            // moved apex.
            let axis = poses.pinion.rotation * frame.axis();
            let apex = poses.pinion.translation;
            let force = Vector3::new(w[0], w[1], w[2]);
            let m_apex = Vector3::new(w[3], w[4], w[5]) - apex.cross(&force);
            return Ok(DeflectedPosition {
                te: s.theta,
                te_rigid_bearings: te_rigid,
                pinion_reactions: supports.pinion.reactions(&n1),
                wheel_reactions: supports.wheel.reactions(&n2),
                pinion: n1,
                wheel: n2,
                pinion_wrench: w,
                pinion_contact_torque_nm: m_apex.dot(&axis),
                poses,
                iterations: it + 1,
            });
        }
        // The first step in full; then half steps, which damp the
        // alternation that slices entering and leaving contact cause.
        let w_new = if it <= 1 { 1.0 } else { RELAXATION };
        d1 = blend(&d1, &n1, w_new);
        d2 = blend(&d2, &n2, w_new);
    }
    Err(SolverError::NotConverged {
        what: "bearing deflection".into(),
        iterations: settings.max_iterations,
    })
}

/// The scene's bearings as supports of `g`'s members (fixed frame, apices
/// at the origin).
pub fn supports_of(settings: &BearingSettings, g: &PairGeometry) -> Result<Supports, BearingError> {
    let one = |m: usize, name: &str, list: &[geometry::scene_bearings::BearingMm]| {
        let bearings: Vec<Bearing> = list
            .iter()
            .map(|b| Bearing {
                axial_position_m: b.axial_position_mm * 1e-3,
                radial_stiffness_n_per_m: b.radial_stiffness_n_per_m,
                axial_stiffness_n_per_m: b.axial_stiffness_n_per_m,
            })
            .collect();
        Support::new(name, g.frames[m].axis(), Vector3::zeros(), &bearings)
    };
    Ok(Supports {
        pinion: one(0, "bearings.pinion", &settings.pinion)?,
        wheel: one(1, "bearings.wheel", &settings.wheel)?,
    })
}

/// One position × torque of [`bearing_sweep`].
#[derive(Debug, Clone)]
pub struct BearingRow {
    /// Pinion rotation from the sweep start, rad.
    pub rotation: f64,
    pub torque_nm: f64,
    pub state: DeflectedPosition,
}

/// Every position of `sweep` at every torque with the members on
/// `supports` (positions in parallel, frictionless); rows by position,
/// then torque.
#[allow(clippy::too_many_arguments)]
pub fn bearing_sweep(
    g: &PairGeometry,
    side: Side,
    utca: &UtcaSettings,
    pc: &PairCompliance,
    supports: &Supports,
    static_poses: Option<BodyPoses>,
    sweep: &Sweep,
    torques: &[f64],
    settings: DeflectionSettings,
) -> Result<Vec<BearingRow>, SolverError> {
    let rows: Vec<Vec<BearingRow>> = (0..sweep.positions)
        .into_par_iter()
        .map(|k| {
            let rotation = sweep.step * k as f64;
            let phi = sweep.start + sweep.direction * rotation;
            let mut g = g.clone();
            torques
                .iter()
                .map(|&torque_nm| {
                    deflected_position(
                        &mut g,
                        side,
                        utca,
                        pc,
                        supports,
                        static_poses,
                        phi,
                        torque_nm,
                        settings,
                    )
                    .map(|state| BearingRow {
                        rotation,
                        torque_nm,
                        state,
                    })
                })
                .collect()
        })
        .collect::<Result<_, _>>()?;
    Ok(rows.into_iter().flatten().collect())
}

/// Per-torque statistics of [`bearing_sweep`]'s rows.
pub fn bearing_summaries(rows: &[BearingRow], torques: &[f64]) -> Vec<BearingLoadSummary> {
    torques
        .iter()
        .map(|&t| {
            let sel: Vec<&DeflectedPosition> = rows
                .iter()
                .filter(|r| r.torque_nm == t)
                .map(|r| &r.state)
                .collect();
            let te: Vec<f64> = sel.iter().map(|s| s.te).collect();
            let rigid: Vec<f64> = sel.iter().map(|s| s.te_rigid_bearings).collect();
            let (m, p) = mean_ptp(&te);
            let (rm, rp) = mean_ptp(&rigid);
            let most = |f: &dyn Fn(&DeflectedPosition) -> f64| {
                sel.iter().map(|s| f(s)).fold(0.0, f64::max)
            };
            let forces = |f: &dyn Fn(&DeflectedPosition) -> &Vec<Vector3<f64>>| {
                let n = sel.first().map_or(0, |s| f(s).len());
                (0..n)
                    .map(|i| sel.iter().map(|s| f(s)[i].norm()).fold(0.0, f64::max))
                    .collect()
            };
            BearingLoadSummary {
                torque_nm: t,
                te_mean_urad: m * 1e6,
                te_ptp_urad: p * 1e6,
                rigid_te_mean_urad: rm * 1e6,
                rigid_te_ptp_urad: rp * 1e6,
                pinion_apex_displacement_um: most(&|s| s.pinion.translation.norm()) * 1e6,
                wheel_apex_displacement_um: most(&|s| s.wheel.translation.norm()) * 1e6,
                pinion_bearing_force_n: forces(&|s| &s.pinion_reactions),
                wheel_bearing_force_n: forces(&|s| &s.wheel_reactions),
                max_iterations: sel.iter().map(|s| s.iterations).max().unwrap_or(0),
            }
        })
        .collect()
}

/// `bearings.csv`: one row per position and torque.
pub fn bearing_csv(rows: &[BearingRow]) -> String {
    use std::fmt::Write;
    let nb = |f: &dyn Fn(&DeflectedPosition) -> usize| rows.first().map_or(0, |r| f(&r.state));
    let (np, nw) = (
        nb(&|s| s.pinion_reactions.len()),
        nb(&|s| s.wheel_reactions.len()),
    );
    let mut out = String::from(
        "pinion_rotation_deg,torque_nm,te_urad,te_rigid_bearings_urad,iterations,pinion_ux_um,pinion_uy_um,pinion_uz_um,pinion_rx_urad,pinion_ry_urad,pinion_rz_urad,wheel_ux_um,wheel_uy_um,wheel_uz_um,wheel_rx_urad,wheel_ry_urad,wheel_rz_urad",
    );
    for (member, n) in [("pinion", np), ("wheel", nw)] {
        for i in 0..n {
            let _ = write!(
                out,
                ",{member}_bearing{i}_fx_n,{member}_bearing{i}_fy_n,{member}_bearing{i}_fz_n"
            );
        }
    }
    out.push('\n');
    for r in rows {
        let s = &r.state;
        let _ = write!(
            out,
            "{:.5},{},{:.5},{:.5},{}",
            r.rotation.to_degrees(),
            r.torque_nm,
            s.te * 1e6,
            s.te_rigid_bearings * 1e6,
            s.iterations
        );
        for d in [&s.pinion, &s.wheel] {
            for v in d.translation.iter() {
                let _ = write!(out, ",{:.5}", v * 1e6);
            }
            for v in d.rotation.iter() {
                let _ = write!(out, ",{:.5}", v * 1e6);
            }
        }
        for f in s.pinion_reactions.iter().chain(&s.wheel_reactions) {
            let _ = write!(out, ",{:.4},{:.4},{:.4}", f.x, f.y, f.z);
        }
        out.push('\n');
    }
    out
}
