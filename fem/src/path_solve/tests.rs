use super::*;
use crate::cholesky::Ordering;
use crate::structured::mapped_block;
use crate::{assemble, Dofs, Factor, Material};

fn body() -> (Factor, PathFactor, Dofs) {
    let (_, f, p, dofs) = body_with_mesh();
    (f, p, dofs)
}

/// The block clamped at z = 0, its full factor, the factor kept on every
/// free dof's path, its dofs and its mesh.
fn body_with_mesh() -> (crate::TetMesh, Factor, PathFactor, Dofs) {
    let b = mapped_block([3, 2, 4], |p| [p[0] * 0.03, p[1] * 0.02, p[2] * 0.04]);
    let fixed: Vec<(usize, f64)> = (0..b.mesh.nodes.len())
        .filter(|&n| b.mesh.nodes[n][2] < 1e-12)
        .flat_map(|n| (0..3).map(move |c| (3 * n + c, 0.0)))
        .collect();
    let dofs = Dofs::new(&b.mesh, &fixed).unwrap();
    let mat = Material {
        youngs_modulus_pa: 2.1e11,
        poisson_ratio: 0.3,
    };
    let sys = assemble(&b.mesh, &mat, &dofs).unwrap();
    let f = Factor::new_supernodal(&sys.matrix, &dofs.node_of_free(), Ordering::Metis).unwrap();
    let all: Vec<usize> = (0..dofs.n_free()).collect();
    let p = PathFactor::new(
        Factor::new_supernodal(&sys.matrix, &dofs.node_of_free(), Ordering::Metis).unwrap(),
        &all,
    )
    .unwrap();
    (b.mesh, f, p, dofs)
}

/// y_iᵀ y_j from pruned forward solves equals K⁻¹ from full solves.
#[test]
fn pruned_forward_solves_reproduce_the_inverse_stiffness() {
    let (f, pf, dofs) = body();
    let n = dofs.n_free();
    let picks: Vec<usize> = (0..n).step_by(7).collect();
    let groups: Vec<[Option<usize>; 1]> = picks.iter().map(|&d| [Some(d)]).collect();
    let y = pf.forward_units(&groups, 5).unwrap();
    let refs: Vec<&PathVec> = y.iter().collect();
    let g = gram(&refs, &refs);
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for (a, &i) in picks.iter().enumerate() {
        let mut e = vec![0.0; n];
        e[i] = 1.0;
        let x = f.solve(&e);
        for (b, &j) in picks.iter().enumerate() {
            worst = worst.max((g[a * picks.len() + b] - x[j]).abs());
            scale = scale.max(x[j].abs());
        }
    }
    assert!(worst <= 1e-12 * scale, "worst {worst:e}, scale {scale:e}");
    // Paths are shorter than the whole factor.
    let longest = y.iter().map(PathVec::rows).max().unwrap();
    assert!(longest < n, "a path holds {longest} of {n} rows");
}

/// The backward solve restricted to a few dofs' paths gives the full
/// solve's displacements there, for a load combined from unit loads.
#[test]
fn backward_solve_on_paths_equals_full_solve_at_those_dofs() {
    let (f, pf, dofs) = body();
    let n = dofs.n_free();
    let loads = [(3usize, 1.5), (40, -0.7), (n - 2, 2.0)];
    let groups: Vec<[Option<usize>; 3]> = vec![
        [Some(loads[0].0), None, Some(loads[1].0)],
        [Some(loads[2].0), None, None],
    ];
    let y = pf.forward_units(&groups, 1).unwrap();
    let z = combine(&[(&y[0], &[1.5, 0.0, -0.7]), (&y[1], &[2.0, 0.0, 0.0])]);
    let at: Vec<usize> = (0..n).step_by(11).collect();
    let u = pf.backward_at(&[&z], &at).unwrap();
    let mut b = vec![0.0; n];
    for (d, v) in loads {
        b[d] += v;
    }
    let x = f.solve(&b);
    let scale = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (k, &d) in at.iter().enumerate() {
        assert!(
            (u[0][k] - x[d]).abs() <= 1e-12 * scale,
            "dof {d}: {} vs {}",
            u[0][k],
            x[d]
        );
    }
}

/// A factor kept on the paths of a few dofs (one corner node's) gives
/// the same compliances there as the whole factor, holds fewer values,
/// and refuses a dof off its paths.
#[test]
fn factor_kept_on_a_few_paths_solves_those_alike_and_refuses_others() {
    let (_, whole, dofs) = body();
    let b = mapped_block([3, 2, 4], |p| [p[0] * 0.03, p[1] * 0.02, p[2] * 0.04]);
    let fixed: Vec<(usize, f64)> = (0..b.mesh.nodes.len())
        .filter(|&n| b.mesh.nodes[n][2] < 1e-12)
        .flat_map(|n| (0..3).map(move |c| (3 * n + c, 0.0)))
        .collect();
    let d2 = Dofs::new(&b.mesh, &fixed).unwrap();
    let sys = assemble(
        &b.mesh,
        &Material {
            youngs_modulus_pa: 2.1e11,
            poisson_ratio: 0.3,
        },
        &d2,
    )
    .unwrap();
    // The top corner node at the largest x and y.
    let corner = (0..b.mesh.nodes.len())
        .max_by(|&m, &n| {
            let s = |k: usize| b.mesh.nodes[k].iter().sum::<f64>();
            s(m).total_cmp(&s(n))
        })
        .unwrap();
    let few: Vec<usize> = (0..3)
        .filter_map(|c| dofs.free_index(3 * corner + c))
        .collect();
    let kept = PathFactor::new(
        Factor::new_supernodal(&sys.matrix, &d2.node_of_free(), Ordering::Metis).unwrap(),
        &few,
    )
    .unwrap();
    let (k, full) = kept.nnz();
    assert!(k < full, "kept {k} of {full}");
    let groups: Vec<[Option<usize>; 1]> = few.iter().map(|&d| [Some(d)]).collect();
    let (ya, yb) = (
        whole.forward_units(&groups, 2).unwrap(),
        kept.forward_units(&groups, 2).unwrap(),
    );
    let ga = gram(
        &ya.iter().collect::<Vec<_>>(),
        &ya.iter().collect::<Vec<_>>(),
    );
    let gb = gram(
        &yb.iter().collect::<Vec<_>>(),
        &yb.iter().collect::<Vec<_>>(),
    );
    let scale = ga.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (x, y) in ga.iter().zip(&gb) {
        assert!((x - y).abs() <= 1e-12 * scale, "{x} vs {y}");
    }
    let on = kept.tree().paths(&few);
    let off = (0..dofs.n_free())
        .find(|&d| !on.contains(&kept.tree().supernode_of(d)))
        .expect("some dof lies off the kept paths");
    assert!(kept.forward_units(&[[Some(off)]], 1).is_err());
    assert!(kept.backward_at(&[&yb[0]], &[off]).is_err());
}

/// Compliances between spread loads (a bump over a few dofs, as a contact
/// grid point's patch weights are) from pruned forward solves equal
/// w_aᵀ K⁻¹ w_b from full solves; a dof given twice adds its values.
#[test]
fn pruned_solves_of_spread_loads_give_their_mutual_compliance() {
    let (f, pf, dofs) = body();
    let n = dofs.n_free();
    let loads: Vec<Vec<(usize, f64)>> = (0..n)
        .step_by(13)
        .map(|d| vec![(d, 0.5), ((d + 3) % n, 0.3), ((d + 17) % n, -0.2), (d, 0.1)])
        .collect();
    let y = pf.forward_sparse(&loads, 4).unwrap();
    let refs: Vec<&PathVec> = y.iter().collect();
    let g = gram(&refs, &refs);
    let dense = |l: &[(usize, f64)]| {
        let mut b = vec![0.0; n];
        for &(d, v) in l {
            b[d] += v;
        }
        b
    };
    let (mut worst, mut scale) = (0.0_f64, 0.0_f64);
    for (a, la) in loads.iter().enumerate() {
        let x = f.solve(&dense(la));
        for (b, lb) in loads.iter().enumerate() {
            let c: f64 = dense(lb).iter().zip(&x).map(|(p, q)| p * q).sum();
            worst = worst.max((g[a * loads.len() + b] - c).abs());
            scale = scale.max(c.abs());
        }
    }
    assert!(worst <= 1e-12 * scale, "worst {worst:e}, scale {scale:e}");
}

/// Stress influence coefficients: the recovered stress at nodes per load
/// from forward solves of the stress functionals and of the loads,
/// (L⁻¹ P g) · (L⁻¹ P f), equals the stress of the load's full solve
/// (`stress::nodal_stress` of K⁻¹ f) within 1e-9 of the largest.
#[test]
fn stress_at_nodes_by_pruned_forward_solves_equals_the_full_solves() {
    let (mesh, f, pf, dofs) = body_with_mesh();
    let mat = Material {
        youngs_modulus_pa: 2.1e11,
        poisson_ratio: 0.3,
    };
    let n = dofs.n_free();
    // Nodes near the clamp (the "root") and sparse loads at the top.
    let nodes: Vec<usize> = (0..mesh.nodes.len())
        .filter(|&k| mesh.nodes[k][2] < 0.011)
        .step_by(3)
        .collect();
    let g = crate::stress::nodal_stress_functionals(&mesh, &mat, &nodes);
    let free = |row: &[(usize, f64)]| -> Vec<(usize, f64)> {
        row.iter()
            .filter_map(|&(d, c)| dofs.free_index(d).map(|i| (i, c)))
            .collect()
    };
    let rows: Vec<Vec<(usize, f64)>> = g.iter().flatten().map(|r| free(r)).collect();
    let loads: Vec<Vec<(usize, f64)>> = (0..mesh.nodes.len())
        .filter(|&k| mesh.nodes[k][2] > 0.04 - 1e-12)
        .take(4)
        .enumerate()
        .map(|(j, k)| free(&[(3 * k, 1.0 + j as f64), (3 * k + 2, -0.5)]))
        .collect();
    let yg = pf.forward_sparse(&rows, 4).unwrap();
    let yf = pf.forward_sparse(&loads, 4).unwrap();
    let c = gram(
        &yg.iter().collect::<Vec<_>>(),
        &yf.iter().collect::<Vec<_>>(),
    );
    let (mut worst, mut scale) = (0.0_f64, 0.0_f64);
    for (j, load) in loads.iter().enumerate() {
        let mut b = vec![0.0; n];
        for &(d, v) in load {
            b[d] += v;
        }
        let u = dofs.expand(&f.solve(&b));
        let s = crate::stress::nodal_stress(&mesh, &mat, &u);
        for (k, &node) in nodes.iter().enumerate() {
            for comp in 0..6 {
                let direct = s[node][comp];
                let pruned = c[(6 * k + comp) * loads.len() + j];
                worst = worst.max((pruned - direct).abs());
                scale = scale.max(direct.abs());
            }
        }
    }
    assert!(scale > 0.0 && nodes.len() >= 6);
    assert!(worst <= 1e-9 * scale, "worst {worst:e}, scale {scale:e}");
}
