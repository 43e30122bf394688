//! The opposite (coast) flank pair placed against the loaded (drive) one:
//! the backlash between them and which body tooth each coast contact falls
//! on, checked with the direct geometric contact search.

mod common;

use geometry::direct::direct_te;
use geometry::generation::Side;
use geometry::pair::{opposite_teeth_in_contact, pinion_direction};
use nalgebra::Vector3;

/// The wheel body stands where the drive model puts it at drive lag
/// θ = −B − θᶜ, θᶜ being the coast contact's lag that the direct search
/// finds in the coast model at the same pinion angle. Then:
/// - the coast contact point lies on the coast flank of body tooth
///   −j + shift (j the coast model's tooth pair) and on no other tooth's;
/// - the drive flanks are open there, by the free play B + θ + θᶜ, which
///   is a small fraction of a wheel pitch (the coast flank across the same
///   tooth space, not one a pitch away);
/// - `opposite_teeth_in_contact` lists that body tooth.
#[test]
fn coast_contact_falls_on_the_body_tooth_that_the_shift_names() {
    let g = common::geometry(&common::white_paper());
    let (dfp, cfp) = (g.side(Side::Drive), g.side(Side::Coast));
    let dd = pinion_direction(&g.data, Side::Drive);
    let op = g.opposite_placement(Side::Drive);
    let drs = common::coarse_roll_surface(dfp);
    let crs = common::coarse_roll_surface(cfp);
    let (f1, f2) = (&cfp.pinion.gen.frame, &cfp.wheel.gen.frame);
    let z2 = g.data.members[1].teeth as i64;
    let tau = g.data.mesh_cycle();
    let cycles = 3.0;
    let (_, listed) = opposite_teeth_in_contact(&g, Side::Drive, cycles, 0.5f64.to_radians());
    eprintln!(
        "backlash {:.2} µrad, wheel tooth shift {}, coast teeth {listed:?}",
        op.backlash * 1e6,
        op.wheel_tooth_shift
    );
    let mut named = std::collections::BTreeSet::new();
    for k in 0..9 {
        let phi = dfp.roll_range[0] + dd * tau * cycles * (k as f64 + 0.4) / 9.0;
        let c = direct_te(cfp, &crs, phi, -dd).expect("coast contact");
        let p = Vector3::from(cfp.pinion.eval_uv(c.uv[0], c.uv[1]).pos);
        let x = f1.to_fixed(&p, phi + c.tooth as f64 * f1.pitch());
        // The wheel point that the coast model's tooth −j has there.
        let at_c = cfp.placement(phi, c.te, -dd);
        let (_, w) = geometry::direct::gap(cfp, at_c, c.tooth, c.uv, c.uv).unwrap();
        let wp = Vector3::from(cfp.wheel.gen.eval(w[0], w[1]).pos);
        // Body teeth whose coast flank passes through x, the wheel body at
        // the drive model's angle.
        let psi = dfp.placement(phi, -op.backlash - c.te, dd).wheel;
        let through: Vec<i64> = (0..z2)
            .filter(|&t| (f2.to_member(&x, psi + t as f64 * f2.pitch()) - wp).norm() < 1e-9)
            .collect();
        let expected = (-(c.tooth as i64) + op.wheel_tooth_shift).rem_euclid(z2);
        assert_eq!(through, vec![expected], "phi {phi}: pair {}", c.tooth);
        named.insert(expected as usize);
        // Drive flanks open by the free play, well under a pitch.
        let d = direct_te(dfp, &drs, phi, dd).expect("drive contact");
        let play = d.te + op.backlash + c.te;
        assert!(
            play > 0.0 && play < 0.05 * f2.pitch(),
            "phi {phi}: free play {play} rad"
        );
    }
    assert!(
        named.iter().all(|t| listed.contains(t)),
        "{named:?} not all in {listed:?}"
    );
}
