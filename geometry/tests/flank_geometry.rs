//! Flank geometry against the design data and against finite differences.

mod common;

use geometry::design::Member;
use geometry::flank::{curvature_from_derivatives, Flank};
use geometry::generation::Side;
use nalgebra::Vector3;

/// Spiral and pressure angle in degrees.
fn angles_at(f: &Flank, l: f64, d: f64) -> (f64, f64) {
    let (b, a) = f.spiral_and_pressure_angle(l, d).unwrap();
    (b.to_degrees(), a.to_degrees())
}

#[test]
fn spiral_and_pressure_angles_at_the_mean_point_equal_the_design_values() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    for m in [Member::Pinion, Member::Wheel] {
        for side in [Side::Drive, Side::Coast] {
            let (beta, alpha) = angles_at(g.flank(m, side), p.mean_cone_distance, 0.0);
            let name = format!("{} {}", m.name(), side.flank_name(m));
            assert!((beta - 32.0).abs() < 0.01, "{name}: spiral angle {beta}");
            assert!(
                (alpha - 20.0).abs() < 0.01,
                "{name}: pressure angle {alpha}"
            );
        }
    }
}

#[test]
fn spiral_angle_grows_from_toe_to_heel_as_the_cutter_circle_predicts() {
    let p = common::white_paper_conjugate();
    let g = common::geometry(&p);
    let f = g.flank(Member::Pinion, Side::Drive);
    let r = f.gen.cone.radius;
    for l in [p.inner_cone_distance(), p.outer_cone_distance()] {
        let (beta, _) = angles_at(f, l, 0.0);
        let expect =
            geometry::design_file::spiral_angle_at(p.mean_cone_distance, p.spiral_angle, r, l)
                .unwrap()
                .to_degrees();
        assert!(
            (beta - expect).abs() < 1e-6,
            "at L = {l}: {beta} vs circle {expect}"
        );
    }
}

#[test]
fn flank_spans_from_the_root_cone_to_the_face_cone_with_the_design_depth() {
    let p = common::white_paper_conjugate();
    let g = common::geometry(&p);
    for m in [Member::Pinion, Member::Wheel] {
        let md = p.member(m);
        // Height above the pitch cone from a 3-D point: ρ cos γ − z sin γ.
        let (s, c) = md.pitch_angle.sin_cos();
        let h = |q: [f64; 3]| q[0].hypot(q[1]) * c - q[2] * s;
        for side in [Side::Drive, Side::Coast] {
            let f = g.flank(m, side);
            for xi in [0.0, 0.5, 1.0] {
                let l = p.inner_cone_distance() + xi * p.face_width;
                let tip = f.at_unit(xi, 1.0).unwrap();
                let face = md.mean_addendum
                    + (l - p.mean_cone_distance) * (md.face_angle - md.pitch_angle).tan();
                assert!(
                    (h(tip.pos) - face).abs() < 1e-9,
                    "{m:?} {side:?} xi {xi}: tip {} vs face cone {face}",
                    h(tip.pos)
                );
                // The deepest point of the generated fillet section.
                let arc = f.fillet_arc_at(l).unwrap();
                let root = f.gen.eval_fillet(1.0, arc);
                let (lr, _) = f.gen.frame.axial(&root.pos);
                let root_cone = -md.mean_dedendum
                    + (lr - p.mean_cone_distance) * (md.root_angle - md.pitch_angle).tan();
                assert!(
                    (h(root.pos) - root_cone).abs() < 2e-6,
                    "{m:?} {side:?} xi {xi}: root {} vs root cone {root_cone}",
                    h(root.pos)
                );
                if xi == 0.5 {
                    // Root point carried along the root cone to the mean section.
                    let root_at_mean = h(root.pos)
                        + (p.mean_cone_distance - lr) * (md.root_angle - md.pitch_angle).tan();
                    let depth = h(tip.pos) - root_at_mean;
                    let design = md.mean_addendum + md.mean_dedendum;
                    assert!(
                        (depth - design).abs() < 5e-6,
                        "{m:?}: tooth depth {depth} vs design {design}"
                    );
                }
            }
        }
    }
}

#[test]
fn principal_curvatures_match_finite_differences_of_positions() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    for m in [Member::Pinion, Member::Wheel] {
        for side in [Side::Drive, Side::Coast] {
            let f = g.flank(m, side);
            for (xi, eta) in [(0.5, 0.5), (0.1, 0.8), (0.9, 0.2)] {
                let pt = f.at_unit(xi, eta).unwrap();
                let [u, v] = pt.uv;
                let exact = f.curvature_uv(u, v);
                let h = 5e-5;
                let r = |a: f64, b: f64| Vector3::from(f.eval_uv(u + a, v + b).pos);
                let ru = (r(h, 0.0) - r(-h, 0.0)) / (2.0 * h);
                let rv = (r(0.0, h) - r(0.0, -h)) / (2.0 * h);
                let ruu = (r(h, 0.0) - r(0.0, 0.0) * 2.0 + r(-h, 0.0)) / (h * h);
                let rvv = (r(0.0, h) - r(0.0, 0.0) * 2.0 + r(0.0, -h)) / (h * h);
                let ruv = (r(h, h) - r(h, -h) - r(-h, h) + r(-h, -h)) / (4.0 * h * h);
                let fd = curvature_from_derivatives(
                    [ru.into(), rv.into()],
                    [ruu.into(), ruv.into(), rvv.into()],
                    &Vector3::from(pt.normal),
                );
                let scale = exact.k[0].abs().max(exact.k[1].abs());
                for i in 0..2 {
                    let rel = (exact.k[i] - fd.k[i]).abs() / scale;
                    assert!(
                        rel < 1e-4,
                        "{m:?} {side:?} ({xi},{eta}) k{i}: {} vs fd {} (rel {rel:e})",
                        exact.k[i],
                        fd.k[i]
                    );
                    let dot = Vector3::from(exact.dir[i])
                        .dot(&Vector3::from(fd.dir[i]))
                        .abs();
                    assert!(
                        dot > 1.0 - 1e-6,
                        "{m:?} {side:?}: direction {i} off, |cos| = {dot}"
                    );
                }
            }
        }
    }
}

#[test]
fn blade_cone_curvatures_are_zero_and_cos_alpha_over_radius() {
    // The curvature routine on a surface with a closed form: a straight-blade
    // cone has κ = 0 along the blade and κ = cos α / r around the cutter axis.
    let p = common::white_paper();
    let g = common::geometry(&p);
    let cone = g.generator.cones[0];
    let c = |u: f64, v: f64| {
        let (x, _) = cone.point(u, v);
        Vector3::from(x)
    };
    let (u, v, h) = (0.0, 0.0, 1e-4);
    let ru = (c(h, v) - c(-h, v)) / (2.0 * h);
    let rv = (c(u, h) - c(u, -h)) / (2.0 * h);
    let ruu = (c(h, v) - c(u, v) * 2.0 + c(-h, v)) / (h * h);
    let rvv = (c(u, h) - c(u, v) * 2.0 + c(u, -h)) / (h * h);
    let ruv = (c(h, h) - c(h, -h) - c(-h, h) + c(-h, -h)) / (4.0 * h * h);
    let (_, n) = cone.point(u, v);
    let k = curvature_from_derivatives(
        [ru.into(), rv.into()],
        [ruu.into(), ruv.into(), rvv.into()],
        &Vector3::from(n),
    );
    let expect = cone.cos_alpha / cone.radius;
    let kmax = k.k[0].abs().max(k.k[1].abs());
    let kmin = k.k[0].abs().min(k.k[1].abs());
    assert!(
        (kmax - expect).abs() / expect < 1e-6,
        "cone curvature {kmax} vs cos α / r = {expect}"
    );
    assert!(kmin < 1e-9, "straight blade: {kmin}");
}

#[test]
fn radius_from_axial_section_coordinates_is_the_distance_from_the_axis() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    for m in [Member::Pinion, Member::Wheel] {
        let f = g.flank(m, Side::Drive);
        for (xi, eta) in [(0.0, 0.0), (0.5, 0.5), (1.0, 1.0), (0.2, 0.9)] {
            let q = f.at_unit(xi, eta).unwrap();
            let (l, d) = f.gen.frame.axial(&q.pos);
            let rho = q.pos[0].hypot(q.pos[1]);
            let r = f.gen.frame.radius_at(l, d);
            assert!(
                (r - rho).abs() < 1e-12,
                "{} at ({xi}, {eta}): {r} vs {rho}",
                m.name()
            );
        }
    }
}
