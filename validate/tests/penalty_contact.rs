//! The reference contact machinery against independent solutions: the fully
//! assembled penalty FE system (no condensation) and Hertz line contact.

use fem::structured::{faces_where, mapped_block, Block};
use fem::{assemble, Dofs, Material};
use validate::body_compliance::BodyCompliance;
use validate::contact_pairs::{two_pass, ContactBody, PenaltySettings};
use validate::penalty::{carried_load, condensed_matrix, solve, Compliance, Constraint};

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

fn nodes_where(b: &Block, on: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
    (0..b.params.len()).filter(|&i| on(b.params[i])).collect()
}

fn contact_nodes(cs: &[Constraint], body: usize) -> Vec<usize> {
    let mut v: Vec<usize> = cs
        .iter()
        .flat_map(|c| c.terms.iter().filter(|t| t.body == body).map(|t| t.node))
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// Two blocks, the upper one with a crowned bottom face, pressed together:
/// the condensed penalty solution equals the solution of the assembled
/// system (both bodies' stiffness plus the penalty terms, rigid coordinate
/// included, active set iterated by semismooth Newton) within 1e-6.
#[test]
fn condensed_contact_equals_the_assembled_penalty_fe_solution() {
    let (l, h, kappa) = (0.01, 0.005, 0.1);
    let upper = mapped_block([3, 3, 2], |p| {
        let (x, y) = (l * (p[0] - 0.5), l * (p[1] - 0.5));
        [x, y, kappa * (x * x + y * y) + h * p[2]]
    });
    let lower = mapped_block([3, 3, 2], |p| {
        [l * (p[0] - 0.5), l * (p[1] - 0.5), -h * (1.0 - p[2])]
    });
    let mat = Material::STEEL;
    let clamp_up = nodes_where(&upper, |p| p[2] > 1.0 - 1e-12);
    let clamp_lo = nodes_where(&lower, |p| p[2] < 1e-12);
    let down = |_: [f64; 3]| [0.0, 0.0, -1.0];
    let none = |_: [f64; 3]| [0.0, 0.0, 0.0];
    let a = ContactBody {
        body: 0,
        nodes: upper.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&upper, |p| p[2] < 1e-12),
        rigid: &down,
        youngs_modulus_pa: mat.youngs_modulus_pa,
    };
    let b = ContactBody {
        body: 1,
        nodes: lower.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&lower, |p| p[2] > 1.0 - 1e-12),
        rigid: &none,
        youngs_modulus_pa: mat.youngs_modulus_pa,
    };
    let set = PenaltySettings {
        factor: 100.0,
        max_gap: 1.0,
        reach: 1e-3,
    };
    let cs: Vec<Constraint> = two_pass(&a, &b, &set).into_iter().map(|c| c.0).collect();
    assert_eq!(cs.len(), 2 * 49, "every contact node of both faces projects");
    let all_up: Vec<usize> = (0..upper.mesh.nodes.len()).collect();
    let all_lo: Vec<usize> = (0..lower.mesh.nodes.len()).collect();
    let mut ca = BodyCompliance::new(&upper.mesh, &mat, &clamp_up, &all_up, 8).unwrap();
    let mut cb = BodyCompliance::new(&lower.mesh, &mat, &clamp_lo, &all_lo, 8).unwrap();
    ca.ensure(&contact_nodes(&cs, 0)).unwrap();
    cb.ensure(&contact_nodes(&cs, 1)).unwrap();
    let idx: Vec<usize> = (0..cs.len()).collect();
    let w = condensed_matrix(&cs, &idx, &idx, &[&ca, &cb]).unwrap();
    let q = 4e4;
    let s = solve(&cs, &w, q, None).unwrap();
    let n_active = s.active.iter().filter(|&&x| x).count();
    assert!(n_active > 4 && n_active < cs.len() - 10, "partial contact: {n_active}");
    assert!((carried_load(&cs, &s.force) - q).abs() < 1e-9 * q);

    // The assembled system: unknowns [u_upper free, u_lower free, ψ].
    let fixed = |c: &[usize]| -> Vec<(usize, f64)> {
        c.iter().flat_map(|&n| (0..3).map(move |d| (3 * n + d, 0.0))).collect()
    };
    let da = Dofs::new(&upper.mesh, &fixed(&clamp_up)).unwrap();
    let db = Dofs::new(&lower.mesh, &fixed(&clamp_lo)).unwrap();
    let (na, nb) = (da.n_free(), db.n_free());
    let n = na + nb + 1;
    let mut k = faer::Mat::<f64>::zeros(n, n);
    for (dofs, off, mesh) in [(&da, 0, &upper.mesh), (&db, na, &lower.mesh)] {
        let m = assemble(mesh, &mat, dofs).unwrap().matrix;
        for j in 0..m.ncols() {
            for (i, v) in m.row_idx_of_col(j).zip(m.val_of_col(j)) {
                k[(off + i, off + j)] += v;
                if i != j {
                    k[(off + j, off + i)] += v;
                }
            }
        }
    }
    let row = |c: &Constraint| -> Vec<(usize, f64)> {
        let mut r = vec![(n - 1, c.rigid)];
        for t in &c.terms {
            let (dofs, off) = if t.body == 0 { (&da, 0) } else { (&db, na) };
            for d in 0..3 {
                if let Some(f) = dofs.free_index(3 * t.node + d) {
                    r.push((off + f, t.dir[d]));
                }
            }
        }
        r
    };
    let rows: Vec<_> = cs.iter().map(row).collect();
    let gap = |x: &[f64], c: usize| -> f64 {
        cs[c].gap0 + rows[c].iter().map(|&(i, v)| v * x[i]).sum::<f64>()
    };
    let mut active = vec![false; cs.len()];
    active[(0..cs.len())
        .min_by(|&p, &r| cs[p].gap0.total_cmp(&cs[r].gap0))
        .unwrap()] = true;
    let mut x = vec![0.0; n];
    for _ in 0..50 {
        let mut kk = k.clone();
        let mut f = vec![0.0; n];
        f[n - 1] = q;
        for c in (0..cs.len()).filter(|&c| active[c]) {
            for &(i, vi) in &rows[c] {
                f[i] -= cs[c].stiffness * cs[c].gap0 * vi;
                for &(j, vj) in &rows[c] {
                    kk[(i, j)] += cs[c].stiffness * vi * vj;
                }
            }
        }
        let rhs = faer::Mat::<f64>::from_fn(n, 1, |i, _| f[i]);
        use faer::linalg::solvers::Solve;
        let sol = kk.llt(faer::Side::Lower).unwrap().solve(&rhs);
        x = (0..n).map(|i| sol[(i, 0)]).collect();
        let next: Vec<bool> = (0..cs.len()).map(|c| gap(&x, c) < 0.0).collect();
        if next == active {
            break;
        }
        active = next;
    }
    assert_eq!(active, s.active, "same active set");
    let psi_err = (x[n - 1] - s.psi).abs() / s.psi.abs();
    assert!(psi_err < 1e-6, "rigid coordinate: {} vs {} ({psi_err:e})", x[n - 1], s.psi);
    let fmax = s.force.iter().cloned().fold(0.0, f64::max);
    for c in 0..cs.len() {
        let f_asm = cs[c].stiffness * (-gap(&x, c)).max(0.0);
        assert!(
            (f_asm - s.force[c]).abs() < 1e-6 * fmax,
            "constraint {c}: assembled {f_asm} vs condensed {}",
            s.force[c]
        );
    }
    // Displacements of the contact nodes from the condensed forces.
    for (body, dofs, off, comp) in [(0, &da, 0, &ca), (1, &db, na, &cb)] {
        let umax = contact_nodes(&cs, body)
            .iter()
            .flat_map(|&i| (0..3).filter_map(move |d| dofs.free_index(3 * i + d)))
            .map(|f| x[off + f].abs())
            .fold(0.0, f64::max);
        for i in contact_nodes(&cs, body) {
            let mut u = [0.0; 3];
            for (c, con) in cs.iter().enumerate() {
                for t in con.terms.iter().filter(|t| t.body == body) {
                    let m = comp.block(i, t.node).unwrap();
                    for r in 0..3 {
                        u[r] += (0..3).map(|q| m[r][q] * t.dir[q]).sum::<f64>() * s.force[c];
                    }
                }
            }
            for d in 0..3 {
                if let Some(f) = dofs.free_index(3 * i + d) {
                    assert!((u[d] - x[off + f]).abs() < 1e-6 * umax, "node {i} dof {d}");
                }
            }
        }
    }
}
