//! The quasi-static LTCA: the unloaded limit against the UTCA, torque
//! balance and complementarity, slice convergence, and the assembled
//! compliance.

use crate::fixture::{fixture, sweep};
use geometry::generation::Side;
use geometry::pair::pinion_direction;
use solver::ltca::{assemble, geometry, mean_ptp, run, solve};

#[test]
fn vanishing_torque_reproduces_the_unloaded_te() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let sw = sweep(f, 12, 30);
    let res = run(fp, &f.rs, &f.pc, &sw, &[1e-3]).unwrap();
    // The UTCA's own sweep over the same angles (preprocess, independent of the slices).
    let utca = geometry::utca::run(fp, &f.rs, sw.start, sw.step, sw.positions, sw.direction);
    let mut worst: f64 = 0.0;
    for (p, te0) in res.iter().zip(&utca.te) {
        assert!(
            (p.utca_te - te0).abs() < 1e-12,
            "slices' UTCA {} vs {}",
            p.utca_te,
            te0
        );
        worst = worst.max((p.loads[0].te - te0).abs());
    }
    eprintln!("largest |TE(1e-3 N m) - TE_UTCA| = {:.4} µrad", worst * 1e6);
    assert!(worst < 0.01e-6, "{} µrad", worst * 1e6);
}

#[test]
fn slice_forces_balance_the_pinion_torque_and_are_complementary_to_the_gaps() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let sw = sweep(f, 6, 30);
    for k in 0..sw.positions {
        let phi = sw.start + sw.direction * sw.step * k as f64;
        let g = geometry(fp, &f.rs, phi, tau, 30);
        let a = assemble(&g, &f.pc, 0.0).unwrap();
        for torque in [100.0, 700.0] {
            let s = solve(&a, torque, None).unwrap();
            // Levers recomputed from the slice points: |(r × n)·z|.
            let moment: f64 = g
                .slices
                .iter()
                .zip(&s.force)
                .map(|(sl, &fk)| fk * (sl.pos[0] * sl.normal[1] - sl.pos[1] * sl.normal[0]).abs())
                .sum();
            assert!(
                ((moment - torque) / torque).abs() < 1e-9,
                "position {k}: {moment} vs {torque}"
            );
            let n = g.slices.len();
            let fmax = s.force.iter().copied().fold(0.0, f64::max);
            for i in 0..n {
                assert!(s.force[i] >= 0.0);
                let gap = g.slices[i].lever_wheel * (g.slices[i].lag - s.theta)
                    + (0..n)
                        .map(|j| a.compliance[i * n + j] * s.force[j])
                        .sum::<f64>()
                    + a.line[i].approach(s.force[i]);
                assert!(gap > -1e-12, "position {k}, slice {i}: gap {gap:e}");
                if s.force[i] > 1e-9 * fmax {
                    assert!(gap.abs() < 1e-11, "loaded slice {i} open by {gap:e}");
                }
            }
        }
    }
}

#[test]
fn mean_te_changes_less_than_half_a_percent_when_the_slices_double() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let torques = [100.0, 300.0, 700.0];
    let te = |slices: usize| {
        let res = run(fp, &f.rs, &f.pc, &sweep(f, 18, slices), &torques).unwrap();
        (0..torques.len())
            .map(|i| mean_ptp(&res.iter().map(|p| p.loads[i].te).collect::<Vec<_>>()))
            .collect::<Vec<_>>()
    };
    let (a, b) = (te(30), te(60));
    for (i, t) in torques.iter().enumerate() {
        let rel = (a[i].0 - b[i].0).abs() / b[i].0;
        eprintln!(
            "{t} N m: mean TE {:.3} / {:.3} µrad ({:.3} %), ptp {:.3} / {:.3} µrad",
            a[i].0 * 1e6,
            b[i].0 * 1e6,
            rel * 100.0,
            a[i].1 * 1e6,
            b[i].1 * 1e6
        );
        assert!(rel < 0.005, "{t} N m: {:.3} %", rel * 100.0);
    }
}

#[test]
fn slice_compliance_is_symmetric_positive_definite_and_load_sharing_adds_up() {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let phi = fp.roll_range[0] + 0.3 * tau * pinion_direction(&f.g.data, Side::Drive);
    let g = geometry(fp, &f.rs, phi, tau, 30);
    let a = assemble(&g, &f.pc, 0.0).unwrap();
    let n = g.slices.len();
    let pairs: std::collections::BTreeSet<i32> = g.slices.iter().map(|s| s.pair).collect();
    assert!(pairs.len() >= 2, "pairs {pairs:?}");
    let m = nalgebra::DMatrix::from_row_slice(n, n, &a.compliance);
    assert!((&m - m.transpose()).norm() <= 1e-14 * m.norm());
    assert!(
        m.clone().cholesky().is_some(),
        "C of {n} slices is not positive definite"
    );
    let s = solve(&a, 300.0, None).unwrap();
    let res = run(fp, &f.rs, &f.pc, &sweep(f, 6, 30), &[300.0]).unwrap();
    for p in &res {
        let share: f64 = p.loads[0].pair_share.iter().sum();
        assert!((share - 1.0).abs() < 1e-9, "shares add to {share}");
    }
    assert!(s.theta > g.utca_te);
}

#[test]
fn relative_curvature_from_the_separation_field_matches_the_flanks_principal_curvatures() {
    // The slices take ρ from the second derivative of the model's own gap
    // along the profile; compare with κ₁(t) + κ₂(t) from the two generated
    // flanks' principal curvatures across the contact line.
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let phi = fp.roll_range[0] + 1.4 * tau * pinion_direction(&f.g.data, Side::Drive);
    let g = geometry(fp, &f.rs, phi, tau, 30);
    let lag_min = g.slices.iter().map(|s| s.lag).fold(f64::INFINITY, f64::min);
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    for w in g.slices.windows(3) {
        let [a, s, b] = [&w[0], &w[1], &w[2]];
        // Slices of one pair near its contact (within 60 µrad of touching).
        if a.pair != s.pair || b.pair != s.pair || s.lag > lag_min + 60e-6 || s.rho >= 0.999 {
            continue;
        }
        let line = [
            b.pos[0] - a.pos[0],
            b.pos[1] - a.pos[1],
            b.pos[2] - a.pos[2],
        ];
        let p = fp.pinion.eval_uv(s.uv[0], s.uv[1]);
        let k_geo = solver::element::slices::geometric_curvature(fp, &p, line);
        let rel = (1.0 / s.rho - k_geo).abs() / k_geo;
        worst = worst.max(rel);
        checked += 1;
    }
    eprintln!(
        "{checked} slices, largest relative difference {:.2} %",
        worst * 100.0
    );
    assert!(checked >= 8, "only {checked} slices near contact");
    assert!(worst < 0.05, "{:.2} %", worst * 100.0);
}
