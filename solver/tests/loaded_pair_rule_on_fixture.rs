//! The loaded-pair rule against a brute-force check on the checked-in
//! example-02 stiffness fixture (no gmsh): at every position of its sweep
//! and at 100, 300, 700 and 3000 N·m, the contact problem with every tooth pair
//! from two below to two above the active roll range's (all the fixture's
//! standard-blank teeth are solved) gives the same loaded TE and the same
//! forces on the rule's pairs as `ltca::run`, which takes only the pairs of
//! the active roll range and those the rule finds closing.

#[path = "support/fixture.rs"]
mod fixture;

use fixture::Fixture;
use geometry::pair::pairs_in_contact;
use solver::ltca::{add_pairs, assemble, geometry, run, solve};

const TORQUES: [f64; 4] = [100.0, 300.0, 700.0, 3000.0];

#[test]
fn loaded_pair_rule_loses_no_pair_that_every_pair_would_load() {
    let f = Fixture::example_02();
    let fp = f.fp();
    let tau = f.g.data.mesh_cycle();
    let res = run(fp, &f.rs, &f.pc, &f.sweep, &TORQUES).unwrap();
    let mut widened = 0;
    let mut loaded_beyond = 0;
    let mut worst = 0.0f64;
    for (k, p) in res.iter().enumerate() {
        let phi = f.sweep.start + f.sweep.direction * f.sweep.step * k as f64;
        let inside = pairs_in_contact(phi, fp.roll_range, tau);
        let (lo, hi) = (inside[0], inside[inside.len() - 1]);
        let mut g = geometry(fp, &f.rs, phi, tau, f.sweep.slices);
        let extra: Vec<i32> = (lo - 2..lo).chain(hi + 1..=hi + 2).collect();
        add_pairs(&mut g, fp, &f.rs, tau, f.sweep.slices, &extra);
        if g.slices.iter().any(|s| extra.contains(&s.pair)) {
            widened += 1;
        }
        let a = assemble(&g, &f.pc, f.sweep.friction).unwrap();
        for (i, &t) in TORQUES.iter().enumerate() {
            let s = solve(&a, t, None).unwrap();
            let te = p.loads[i].te;
            worst = worst.max((s.theta - te).abs() / te);
            // The force every pair carries in the brute-force problem is
            // what the rule's problem gives it (zero where it is absent).
            for j in lo - 2..=hi + 2 {
                let brute: f64 = g
                    .slices
                    .iter()
                    .zip(&s.force)
                    .filter(|(sl, _)| sl.pair == j)
                    .map(|(_, f)| f)
                    .sum();
                let rule = p.loads[i]
                    .pair_force
                    .iter()
                    .find(|q| q.0 == j)
                    .map_or(0.0, |q| q.1);
                if brute > 0.0 && !inside.contains(&j) {
                    loaded_beyond += 1;
                }
                assert!(
                    (brute - rule).abs() <= 1e-6 * t,
                    "position {k}, {t} N·m, pair {j}: {brute} N with every pair, {rule} N by the rule"
                );
            }
        }
    }
    assert!(widened > 0, "no position had a pair beyond the roll range");
    // At 3000 N·m (far beyond the fixture's loads) pairs beyond the roll
    // range do close (measured: 5 pair loads, the rule closing at 4
    // positions): both of the rule's outcomes are exercised.
    let closing = res.iter().filter(|p| p.neighbours.closing).count();
    assert!(
        loaded_beyond > 0 && closing > 0,
        "{loaded_beyond} {closing}"
    );
    assert!(worst < 1e-9, "loaded TE differs by {worst:e} (relative)");
}
