//! Unloaded tooth contact analysis: ease-off topography, transmission error,
//! checked against the direct geometric contact search.

mod common;

use geometry::direct::{contact_ellipse, direct_te, gap};
use geometry::generation::Side;
use geometry::pair::pinion_direction;
use geometry::utca::{run, LineGrid, RollSurface};

#[test]
fn separation_map_equals_the_designed_ease_off() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let dir = pinion_direction(&p, side);
        let rs = RollSurface::new(
            fp,
            LineGrid {
                n_face: 11,
                n_profile: 11,
            },
        )
        .unwrap();
        let mut checked = 0;
        let mut worst: f64 = 0.0;
        for &uv in &rs.uv {
            if !fp.is_active(uv[0], uv[1], 0.0) {
                continue;
            }
            let pt = fp.pinion.eval_uv(uv[0], uv[1]);
            // Rotate the pair to the conjugate position where this point is on the contact line.
            let at = fp.placement(pt.pinion_roll, 0.0, dir);
            let (s, _) = gap(fp, at, 0, uv, uv).unwrap();
            worst = worst.max((s - pt.ease_off).abs());
            assert!(
                (s - pt.ease_off).abs() < 0.05e-6,
                "{side:?}: separation {:.4} um vs ease-off {:.4} um",
                s * 1e6,
                pt.ease_off * 1e6
            );
            checked += 1;
        }
        assert!(checked > 50, "{side:?}: only {checked} active nodes");
        println!(
            "{side:?}: {checked} nodes, worst |separation - ease-off| = {:.2e} um",
            worst * 1e6
        );
    }
}

#[test]
fn white_paper_pair_mesh_cycle_is_18_degrees_and_unloaded_te_is_37_urad_peak_to_peak() {
    let p = common::white_paper();
    assert!((p.mesh_cycle().to_degrees() - 18.0).abs() < 1e-12);
    let g = common::geometry(&p);
    let fp = g.side(Side::Drive);
    let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
    let dir = pinion_direction(&p, Side::Drive);
    let u = run(fp, &rs, fp.roll_range[0], 0.1f64.to_radians(), 361, dir);
    let ptp = u.te_ptp() * 1e6;
    println!(
        "unloaded TE peak-to-peak {ptp:.2} urad, contact ratio {:.3}",
        u.contact_ratio
    );
    assert!((ptp - 37.0).abs() < 3.7, "TE ptp {ptp} urad");
    // Periodic with the mesh cycle: 180 steps of 0.1°.
    for k in 0..181 {
        assert!(
            (u.te[k] - u.te[k + 180]).abs() < 1e-9,
            "not periodic at step {k}"
        );
    }
    assert!(u.te.iter().all(|&t| t >= 0.0), "TE must be a lag (>= 0)");
}

#[test]
fn fast_utca_agrees_with_the_direct_contact_search() {
    let p = common::white_paper();
    let g = common::geometry(&p);
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let dir = pinion_direction(&p, side);
        let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
        let coarse = common::coarse_roll_surface(fp);
        let step = p.mesh_cycle() / 5.0;
        let u = run(fp, &rs, fp.roll_range[0], step, 5, dir);
        for k in 0..5 {
            let d = direct_te(fp, &coarse, u.pinion_angle[k], dir).unwrap();
            let diff = (d.te - u.te[k]).abs() * 1e6;
            assert!(
                diff < 0.02,
                "{side:?} step {k}: fast {:.4} vs direct {:.4} urad",
                u.te[k] * 1e6,
                d.te * 1e6
            );
            assert!(
                d.min_node_gap > -1e-9,
                "{side:?}: penetration {:.2e} m at the direct TE",
                d.min_node_gap
            );
        }
    }
}

#[test]
fn contact_ellipse_semi_axes_follow_the_separation_they_mark() {
    // Quadratic separation: the semi-axes grow with √δ.
    let p = common::white_paper();
    let g = common::geometry(&p);
    let fp = g.side(Side::Drive);
    let dir = pinion_direction(&p, Side::Drive);
    let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
    let phi = 0.5 * (fp.roll_range[0] + fp.roll_range[1]);
    let u = run(fp, &rs, phi, 0.0, 1, dir);
    let c = u.teeth[0][u.contact[0]];
    let at = fp.placement(phi, u.te[0], dir);
    let e1 = contact_ellipse(fp, at, c.tooth, c.uv, 6.3e-6).unwrap();
    let e4 = contact_ellipse(fp, at, c.tooth, c.uv, 4.0 * 6.3e-6).unwrap();
    for i in 0..2 {
        assert!((e4.semi_axes[i] / e1.semi_axes[i] - 2.0).abs() < 1e-9);
    }
    assert!(e1.semi_axes[0] > e1.semi_axes[1]);
    // A localized bearing: the major axis is a few mm, the minor axis below a mm.
    assert!(
        e1.semi_axes[0] > 2e-3 && e1.semi_axes[0] < 30e-3,
        "major {}",
        e1.semi_axes[0]
    );
    assert!(e1.semi_axes[1] < 1e-3, "minor {}", e1.semi_axes[1]);
    // The contact point at the UTCA lag has (almost) zero gap.
    let (s, _) = gap(fp, at, c.tooth, c.uv, c.uv).unwrap();
    assert!(s.abs() < 1e-9, "gap at the contact point {s}");
}

#[test]
fn imported_topography_is_added_on_top_and_a_linear_field_is_reproduced_exactly() {
    use geometry::design::{Member, TopographyDesign};
    let mut p = common::white_paper_conjugate();
    let profile = vec![0.0, 0.3, 0.55, 1.0];
    let face = vec![0.0, 0.2, 0.7, 0.85, 1.0];
    let field = |eta: f64, xi: f64| 2.0 + 3.0 * eta - xi;
    p.ease_off.topography = Some(TopographyDesign {
        deviation_um: profile
            .iter()
            .map(|&e| face.iter().map(|&x| field(e, x)).collect())
            .collect(),
        profile,
        face,
    });
    let g = common::geometry(&p);
    let fp = g.side(Side::Drive);
    let f = g.flank(Member::Pinion, Side::Drive);
    for (xi, eta) in [(0.1, 0.1), (0.45, 0.62), (0.93, 0.4), (0.5, 0.5)] {
        let pt = f.at_unit(xi, eta).unwrap();
        assert!(
            (pt.ease_off - field(eta, xi) * 1e-6).abs() < 1e-13,
            "({xi},{eta}): {}",
            pt.ease_off
        );
        if fp.is_active(pt.uv[0], pt.uv[1], 0.0) {
            let at = fp.placement(pt.pinion_roll, 0.0, pinion_direction(&p, Side::Drive));
            let (s, _) = gap(fp, at, 0, pt.uv, pt.uv).unwrap();
            assert!(
                (s - pt.ease_off).abs() < 0.05e-6,
                "separation {s} vs {}",
                pt.ease_off
            );
        }
    }
}

/// The toe and heel rows of the flank grid lie exactly on the face-width
/// bounds, where Newton's 1e-13 m round-off used to decide whether a row
/// counted as active (and so where first contact began: 0.57° apart between
/// two equally exact solvers). Each edge node must be active exactly when the
/// point 1e-9 of the face width inside it is.
#[test]
fn toe_and_heel_rows_are_active_like_the_points_just_inside_them() {
    let g = common::geometry(&common::white_paper());
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let grid = LineGrid {
            n_face: 41,
            n_profile: 41,
        };
        let rs = RollSurface::new(fp, grid).unwrap();
        let np = grid.n_profile;
        let mut edge_active = 0;
        for (row, xi) in [(0, 1e-9), (grid.n_face - 1, 1.0 - 1e-9)] {
            for k in 1..np - 1 {
                let eta = k as f64 / (np - 1) as f64;
                let p = fp.pinion.at_unit(xi, eta).unwrap();
                let inside = fp.is_active(p.uv[0], p.uv[1], 0.0);
                assert_eq!(
                    rs.active[row * np + k],
                    inside,
                    "{side:?} row {row}, eta {eta}"
                );
                edge_active += usize::from(inside);
            }
        }
        // The check means something: part of each edge row is active.
        assert!(
            edge_active > 10,
            "{side:?}: {edge_active} active edge nodes"
        );
    }
}
