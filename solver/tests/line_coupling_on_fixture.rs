//! The local coupling along the contact line
//! ([`solver::element::line_coupling`]) in the element, on the example-02
//! stiffness fixture (white-paper pair, standard blanks; no gmsh): it makes
//! a short, light-load contact stiffer than the plane-strain strips alone,
//! leaves the unloaded TE and the torque balance as they are, and its
//! matrix has the shape the kernel promises on every contact line.

#[path = "support/fixture.rs"]
mod fixture;

use solver::ltca::{assemble, geometry, run_variant, Variant};

fn elastic_mean_urad(res: &[solver::ltca::PositionResult], load: usize) -> f64 {
    res.iter()
        .map(|p| (p.loads[load].te - p.utca_te) * 1e6)
        .sum::<f64>()
        / res.len() as f64
}

#[test]
fn a_light_load_contact_is_stiffer_with_its_unloaded_neighbours() {
    let f = fixture::Fixture::example_02();
    let torques = [1.0, 300.0];
    let with = run_variant(f.fp(), &f.rs, &f.pc, &f.sweep, &torques, Variant::Element).unwrap();
    let without = run_variant(
        f.fp(),
        &f.rs,
        &f.pc,
        &f.sweep,
        &torques,
        Variant::WithoutLineCoupling,
    )
    .unwrap();
    let (w1, wo1) = (elastic_mean_urad(&with, 0), elastic_mean_urad(&without, 0));
    let (w3, wo3) = (elastic_mean_urad(&with, 1), elastic_mean_urad(&without, 1));
    eprintln!("elastic mean TE: 1 N·m {w1:.4} against {wo1:.4} µrad, 300 N·m {w3:.4} against {wo3:.4} µrad");
    // At 1 N·m the contact covers a few slices of each line: the
    // coupling takes away the unloaded neighbours' share of the strips.
    assert!(w1 < wo1, "{w1} {wo1}");
    // Relative to its elastic TE the light-load contact gains more than
    // the one spread over the face at 300 N·m.
    assert!((wo1 - w1) / wo1 > (wo3 - w3).abs() / wo3);
    for p in &with {
        for l in &p.loads {
            assert!(l.finite && l.torque_residual_nm.abs() < 1e-9 * 300.0);
        }
    }
}

#[test]
fn every_contact_line_couples_its_slices_as_a_negative_semi_definite_matrix() {
    // K (local_coupling): zero between pairs, symmetric, positive between
    // neighbouring slices (the kernel turns negative only beyond about
    // twice the depth), negative on the diagonal of the coupled slices
    // and Σ_j K_ij L_j = 0 on every row of a line with no short slice (one
    // depth per body and line); each line contact's floor is the sum of
    // its row's magnitudes.
    let f = fixture::Fixture::example_02();
    let tau = f.g.data.mesh_cycle();
    for k in 0..f.sweep.positions {
        let phi = f.sweep.start + f.sweep.direction * f.sweep.step * k as f64;
        let g = geometry(f.fp(), &f.rs, phi, tau, f.sweep.slices);
        let a = assemble(&g, &f.pc, 0.0).unwrap();
        let n = g.slices.len();
        let kk = &a.local_coupling;
        for i in 0..n {
            assert_eq!(a.line[i].neighbours, kk[i * n + i]);
            let mut magnitudes = 0.0;
            for j in 0..n {
                let v = kk[i * n + j];
                assert_eq!(v, kk[j * n + i]);
                if g.slices[i].pair != g.slices[j].pair {
                    assert_eq!(v, 0.0);
                } else if j == i + 1 && v != 0.0 {
                    assert!(v > 0.0);
                }
                if j != i {
                    magnitudes += v.abs();
                }
            }
            assert!((a.line[i].coupled - magnitudes).abs() <= 1e-12 * magnitudes);
        }
        let mut pairs: Vec<i32> = g.slices.iter().map(|s| s.pair).collect();
        pairs.dedup();
        for j in pairs {
            let rows: Vec<usize> = (0..n).filter(|&i| g.slices[i].pair == j).collect();
            let widest = rows
                .iter()
                .map(|&i| g.slices[i].band[1] - g.slices[i].band[0])
                .fold(0.0, f64::max);
            let contiguous = rows
                .windows(2)
                .all(|w| g.slices[w[1]].band[0] == g.slices[w[0]].band[1]);
            let short = rows.iter().any(|&i| {
                g.slices[i].band[1] - g.slices[i].band[0]
                    < solver::element::line_coupling::SHORT * widest
            });
            if !contiguous || short {
                continue;
            }
            for &i in &rows {
                assert!(kk[i * n + i] < 0.0);
                let sum: f64 = rows
                    .iter()
                    .map(|&l| kk[i * n + l] * g.slices[l].length)
                    .sum();
                assert!(
                    sum.abs() < 1e-9 * (kk[i * n + i] * g.slices[i].length).abs(),
                    "position {k}, pair {j}, slice {i}: {sum}"
                );
            }
        }
    }
}
