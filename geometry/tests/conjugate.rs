//! Conjugacy of the complementary generation: with the ease-off off, pinion
//! and wheel flanks touch along whole lines and the transmission error is
//! zero. Checked by the direct geometric contact search (projection onto the
//! wheel flank), which does not use the surface of roll angles.

mod common;

use geometry::direct::{direct_te, gap};
use geometry::generation::Side;
use geometry::pair::pinion_direction;
use geometry::utca::LineSearch;

/// The limit, 0.01 µrad (about 0.9 nm of normal gap at the 87 mm wheel lever).
const TE_TOL_RAD: f64 = 0.01e-6;

#[test]
fn conjugate_flanks_give_zero_transmission_error_over_a_mesh_cycle() {
    let p = common::white_paper_conjugate();
    let g = common::geometry(&p);
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let rs = common::coarse_roll_surface(fp);
        let dir = pinion_direction(&p, side);
        let tau = p.mesh_cycle();
        let mut worst: f64 = 0.0;
        for k in 0..6 {
            let phi = fp.roll_range[0] + dir * tau * k as f64 / 6.0;
            let c = direct_te(fp, &rs, phi, dir).expect("contact found");
            assert!(
                c.te.abs() < TE_TOL_RAD,
                "{side:?} at {:.2} deg: TE = {:.3e} urad",
                phi.to_degrees(),
                c.te * 1e6
            );
            worst = worst.max(c.te.abs());
            // No interference anywhere on the active flanks.
            assert!(
                c.min_node_gap > -1e-9,
                "{side:?}: interference {:.3e} m",
                c.min_node_gap
            );
        }
        println!("{side:?}: max |TE| = {:.2e} urad", worst * 1e6);
    }
}

#[test]
fn separation_is_zero_along_the_conjugate_contact_line() {
    let p = common::white_paper_conjugate();
    let g = common::geometry(&p);
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let rs = common::coarse_roll_surface(fp);
        let ls = LineSearch::new(fp, &rs);
        let dir = pinion_direction(&p, side);
        let phi = 0.5 * (fp.roll_range[0] + fp.roll_range[1]);
        let at = fp.placement(phi, 0.0, dir);
        let mut n = 0;
        let mut worst: f64 = 0.0;
        for i in 0..=40 {
            let Some(uv) = ls.line_point(i as f64 * 0.5, phi) else {
                continue;
            };
            if !fp.is_active(uv[0], uv[1], 0.0) {
                continue;
            }
            let (s, _) = gap(fp, at, 0, uv, uv).unwrap();
            let lever = fp.pinion.eval_uv(uv[0], uv[1]).wheel_lever;
            assert!(
                (s / lever).abs() < TE_TOL_RAD,
                "{side:?}: separation {s:.3e} m on the line"
            );
            worst = worst.max(s.abs());
            n += 1;
        }
        assert!(n > 20, "{side:?}: only {n} line points on the active flank");
        println!("{side:?}: {n} line points, max |separation| = {worst:.2e} m");
    }
}
