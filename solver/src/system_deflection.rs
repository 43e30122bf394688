//! Quasi-static loaded TCA with compliant bearings at one position: the
//! mesh force moves both members on their bearings ([`crate::bearings`]),
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

use crate::bearings::{Displacement, Support};
use crate::compliance::PairCompliance;
use crate::ltca::{assemble, geometry, solve};
use crate::SolverError;
use geometry::generation::Side;
use geometry::misalignment::{BodyPoses, Pose};
use geometry::pair::PairGeometry;
use geometry::scene::UtcaSettings;
use geometry::utca::roll_surface;
use nalgebra::{Rotation3, Vector3, Vector6};

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
        // Every iteration on the posed contact path (the exact mate), the
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
