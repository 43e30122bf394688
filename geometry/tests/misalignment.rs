//! Misalignments E, P, G, ΔΣ in the unloaded TCA: the misaligned UTCA
//! against the direct contact search, frame invariance, the aligned path
//! left as it was, and the direction the contact pattern moves with P.

mod common;

use geometry::direct::direct_te;
use geometry::generation::Side;
use geometry::misalignment::{rot_y, Component, Misalignment, Pose};
use geometry::pair::{pinion_direction, PairGeometry};
use geometry::utca::{run, LineGrid, RollSurface, Utca};
use nalgebra::{Matrix3, Vector3};

/// UTCA of the drive side over one mesh cycle in `n` positions.
fn utca(g: &PairGeometry, n: usize) -> Utca {
    let fp = g.side(Side::Drive);
    let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
    let dir = pinion_direction(&g.data, Side::Drive);
    run(
        fp,
        &rs,
        fp.roll_range[0],
        g.data.mesh_cycle() / n as f64,
        n,
        dir,
    )
}

fn misaligned(m: Misalignment) -> PairGeometry {
    let mut g = common::geometry(&common::white_paper());
    g.misalign(&m);
    g
}

#[test]
fn misaligned_utca_agrees_with_the_direct_contact_search() {
    let cases = [
        Misalignment::default().with(Component::Offset, 0.08),
        Misalignment::default().with(Component::PinionAxial, -0.08),
        Misalignment::default().with(Component::WheelAxial, 0.08),
        Misalignment::default().with(Component::ShaftAngle, 0.03),
        Misalignment {
            offset_mm: -0.05,
            pinion_axial_mm: 0.05,
            wheel_axial_mm: -0.05,
            shaft_angle_deg: -0.02,
        },
    ];
    let aligned = utca(&misaligned(Misalignment::default()), 5);
    for m in cases {
        let g = misaligned(m);
        let fp = g.side(Side::Drive);
        let dir = pinion_direction(&g.data, Side::Drive);
        let coarse = common::coarse_roll_surface(fp);
        let u = utca(&g, 5);
        let mut moved: f64 = 0.0;
        for k in 0..5 {
            let d = direct_te(fp, &coarse, u.pinion_angle[k], dir).unwrap();
            let diff = (d.te - u.te[k]).abs() * 1e6;
            println!(
                "{m:?} step {k}: UTCA {:.5} direct {:.5} urad (aligned {:.5})",
                u.te[k] * 1e6,
                d.te * 1e6,
                aligned.te[k] * 1e6
            );
            assert!(
                diff < 0.01,
                "{m:?} step {k}: UTCA {:.5} vs direct {:.5} urad",
                u.te[k] * 1e6,
                d.te * 1e6
            );
            assert!(
                d.min_node_gap > -1e-9,
                "{m:?}: penetration {:.2e} m at the direct TE",
                d.min_node_gap
            );
            moved = moved.max((u.te[k] - aligned.te[k]).abs());
        }
        // The misalignment does something: the TE moves by far more than the tolerance.
        assert!(
            moved * 1e6 > 0.5,
            "{m:?}: TE moved by {:.3} urad only",
            moved * 1e6
        );
    }
}

#[test]
fn common_rigid_motion_of_both_bodies_changes_nothing() {
    let m = Misalignment {
        offset_mm: 0.06,
        pinion_axial_mm: -0.04,
        wheel_axial_mm: 0.05,
        shaft_angle_deg: 0.02,
    };
    let mut g = common::geometry(&common::white_paper());
    let poses = m.poses(&g.data);
    g.set_poses(Some(poses));
    let base = utca(&g, 6);
    // A translation of 3 cm and a turn of 40° about a skew axis, applied to both.
    let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
    let turn = nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(axis), 0.7);
    let common = Pose {
        rotation: *turn.matrix() * rot_y(0.1),
        translation: Vector3::new(0.03, -0.02, 0.01),
    };
    g.set_poses(Some(poses.moved(&common)));
    let moved = utca(&g, 6);
    for k in 0..6 {
        let d = (moved.te[k] - base.te[k]).abs() * 1e6;
        assert!(
            d < 1e-6,
            "step {k}: {:.8} vs {:.8} urad",
            moved.te[k] * 1e6,
            base.te[k] * 1e6
        );
    }
    // Moving the pinion alone by the same motion is not the same pair.
    let mut alone = poses;
    alone.pinion = common.after(&poses.pinion);
    g.set_poses(Some(alone));
    assert!(alone.relative() != poses.relative());
    assert_ne!(alone.relative().rotation, Matrix3::identity());
}

#[test]
fn zero_misalignment_leaves_the_pair_aligned() {
    let g0 = common::geometry(&common::white_paper());
    let g = misaligned(Misalignment::default());
    assert!(g.sides.iter().all(|fp| fp.pose.is_none()));
    let (a, b) = (utca(&g0, 7), utca(&g, 7));
    assert_eq!(a.te, b.te);
    // A misalignment of 1e-9 mm takes the misaligned path (the aligned
    // model plus the pose's exact change) and moves the TE by about
    // 1e-5 µrad (P shifts it by ~7 µrad per µm, first order).
    let tiny = misaligned(Misalignment::default().with(Component::PinionAxial, 1e-9));
    assert!(tiny.side(Side::Drive).pose.is_some());
    let c = utca(&tiny, 7);
    for k in 0..7 {
        assert!(
            (c.te[k] - a.te[k]).abs() * 1e6 < 1e-4,
            "step {k}: {} vs {} urad",
            c.te[k] * 1e6,
            a.te[k] * 1e6
        );
    }
}

/// The misaligned path with the identity pose: the pose's correction is
/// exactly zero, so the UTCA (surface of roll angles, node activity, the
/// contact search) is the aligned one, bit for bit.
#[test]
fn identity_pose_gives_the_aligned_utca() {
    let g0 = common::geometry(&common::white_paper());
    let mut g = g0.clone();
    for fp in g.sides.iter_mut() {
        fp.pose = Some(Pose::identity());
    }
    let (a, b) = (utca(&g0, 7), utca(&g, 7));
    assert_eq!(a.te, b.te);
    for (x, y) in a.teeth.iter().zip(&b.teeth) {
        let uv = |t: &[geometry::utca::ToothContact]| {
            t.iter().map(|c| (c.tooth, c.uv)).collect::<Vec<_>>()
        };
        assert_eq!(uv(x), uv(y));
    }
}

/// Mean height d (m) of the UTCA contact points over one mesh cycle of `side`.
fn mean_contact_height(g: &PairGeometry, side: Side) -> f64 {
    let fp = g.side(side);
    let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
    let dir = pinion_direction(&g.data, side);
    let n = 10;
    let u = run(
        fp,
        &rs,
        fp.roll_range[0],
        g.data.mesh_cycle() / n as f64,
        n,
        dir,
    );
    (0..n).map(|k| u.teeth[k][u.contact[k]].d).sum::<f64>() / n as f64
}

/// The shop rule for the pinion's mounting distance (e.g. Nissan's final
/// drive service manual, "Tooth Contact": contact near the face (top) or
/// heel of the ring gear is corrected by moving the drive pinion closer to
/// the ring gear, contact near the flank or toe by moving it farther away):
/// withdrawing the pinion (P > 0) moves the pattern toward the wheel's face,
/// i.e. down the pinion's flank toward its root, on both sides; P < 0 the
/// other way. (Lengthwise the white-paper pair's pattern moves by less than
/// a millimetre with P; E moves it along the face, opposite on the two
/// sides, which is why the V/H check pairs them.)
#[test]
fn pinion_withdrawn_moves_the_pattern_toward_the_wheel_face() {
    for side in [Side::Drive, Side::Coast] {
        let d0 = mean_contact_height(&misaligned(Misalignment::default()), side);
        let p = |v: f64| {
            mean_contact_height(
                &misaligned(Misalignment::default().with(Component::PinionAxial, v)),
                side,
            )
        };
        let (out, inn) = (p(0.02), p(-0.02));
        println!(
            "{side:?}: mean pinion contact height {:.3} mm aligned, {:.3} mm with P = +0.02 mm, {:.3} mm with P = -0.02 mm",
            d0 * 1e3,
            out * 1e3,
            inn * 1e3
        );
        // 0.05 mm at least each way (the flank is about 9 mm high).
        assert!(
            out < d0 - 0.05e-3,
            "{side:?}: P > 0 did not move the pattern down the pinion"
        );
        assert!(
            inn > d0 + 0.05e-3,
            "{side:?}: P < 0 did not move the pattern up the pinion"
        );
    }
}
