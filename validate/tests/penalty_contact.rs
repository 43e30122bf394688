//! The reference contact machinery against independent solutions: the fully
//! assembled penalty FE system (no condensation) and Hertz line contact.

use fem::path_solve::{combine, gram, PathVec};
use fem::structured::{faces_where, mapped_block, Block};
use fem::{assemble, Dofs, Material};
use validate::reference::body_compliance::{clamped, BodyCompliance};
use validate::reference::contact_pairs::{two_pass, ContactBody, PenaltySettings};
use validate::reference::path_compliance::PathCompliance;
use validate::reference::penalty::{carried_load, condensed_matrix, solve, Compliance, Constraint};

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

/// The crowned upper block on the flat lower one: the meshes, their
/// clamped nodes and every two-pass constraint.
fn crowned_block_pair() -> (Block, Block, Vec<usize>, Vec<usize>, Vec<Constraint>) {
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
        minima_band: 1.0,
    };
    let cs: Vec<Constraint> = two_pass(&a, &b, &set).into_iter().map(|c| c.0).collect();
    assert_eq!(
        cs.len(),
        2 * 49,
        "every contact node of both faces projects"
    );
    (upper, lower, clamp_up, clamp_lo, cs)
}

/// Two blocks, the upper one with a crowned bottom face, pressed together:
/// the condensed penalty solution equals the solution of the assembled
/// system (both bodies' stiffness plus the penalty terms, rigid coordinate
/// included, active set iterated by semismooth Newton) within 1e-6.
/// Both bodies' full-solve columns at every contact node (responses kept
/// at every node) and the condensed matrix W of all constraints.
fn full_columns(
    upper: &Block,
    lower: &Block,
    clamp_up: &[usize],
    clamp_lo: &[usize],
    cs: &[Constraint],
) -> (BodyCompliance, BodyCompliance, Vec<f64>) {
    let mat = Material::STEEL;
    let all_up: Vec<usize> = (0..upper.mesh.nodes.len()).collect();
    let all_lo: Vec<usize> = (0..lower.mesh.nodes.len()).collect();
    let mut ca = BodyCompliance::new(&upper.mesh, &mat, &clamped(clamp_up), &all_up, 8).unwrap();
    let mut cb = BodyCompliance::new(&lower.mesh, &mat, &clamped(clamp_lo), &all_lo, 8).unwrap();
    ca.ensure(&contact_nodes(cs, 0)).unwrap();
    cb.ensure(&contact_nodes(cs, 1)).unwrap();
    let idx: Vec<usize> = (0..cs.len()).collect();
    let w = condensed_matrix(cs, &idx, &idx, &[&ca, &cb]).unwrap();
    (ca, cb, w)
}

#[test]
fn condensed_contact_equals_the_assembled_penalty_fe_solution() {
    let mat = Material::STEEL;
    let (upper, lower, clamp_up, clamp_lo, cs) = crowned_block_pair();
    let (ca, cb, w) = full_columns(&upper, &lower, &clamp_up, &clamp_lo, &cs);
    let q = 4e4;
    let s = solve(&cs, &w, q, None).unwrap();
    let n_active = s.active.iter().filter(|&&x| x).count();
    assert!(
        n_active > 4 && n_active < cs.len() - 10,
        "partial contact: {n_active}"
    );
    assert!((carried_load(&cs, &s.force) - q).abs() < 1e-9 * q);

    // The assembled system: unknowns [u_upper free, u_lower free, ψ].
    let fixed = |c: &[usize]| -> Vec<(usize, f64)> {
        c.iter()
            .flat_map(|&n| (0..3).map(move |d| (3 * n + d, 0.0)))
            .collect()
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
    assert!(
        psi_err < 1e-6,
        "rigid coordinate: {} vs {} ({psi_err:e})",
        x[n - 1],
        s.psi
    );
    let fmax = s.force.iter().cloned().fold(0.0, f64::max);
    for (c, con) in cs.iter().enumerate() {
        let f_asm = con.stiffness * (-gap(&x, c)).max(0.0);
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
            for (d, ud) in u.iter().enumerate() {
                if let Some(f) = dofs.free_index(3 * i + d) {
                    assert!((ud - x[off + f]).abs() < 1e-6 * umax, "node {i} dof {d}");
                }
            }
        }
    }
}

/// The pruned-solve compliance (forward solves along elimination-tree
/// paths, W = Σ_b Y_bᵀ Y_b, displacements by a backward solve on the paths
/// of the nodes asked for) against today's full-solve columns on the
/// crowned block pair: W and the displacements within 1e-12 relative, and
/// the same contact solution.
#[test]
fn pruned_path_compliance_equals_full_solve_columns() {
    let mat = Material::STEEL;
    let (upper, lower, clamp_up, clamp_lo, cs) = crowned_block_pair();
    let (ca, cb, w_full) = full_columns(&upper, &lower, &clamp_up, &clamp_lo, &cs);

    // Blocks of 7 right-hand sides: several blocks, partial paths.
    let (near_a, near_b) = (contact_nodes(&cs, 0), contact_nodes(&cs, 1));
    let mut pa = PathCompliance::new(&upper.mesh, &mat, &clamped(&clamp_up), &near_a, 7).unwrap();
    let mut pb = PathCompliance::new(&lower.mesh, &mat, &clamped(&clamp_lo), &near_b, 7).unwrap();
    pa.ensure(&contact_nodes(&cs, 0)).unwrap();
    pb.ensure(&contact_nodes(&cs, 1)).unwrap();
    let y: Vec<[PathVec; 2]> = cs
        .iter()
        .map(|c| {
            [
                pa.constraint_vector(&c.terms, 0).unwrap(),
                pb.constraint_vector(&c.terms, 1).unwrap(),
            ]
        })
        .collect();
    let mut w_path = vec![0.0; cs.len() * cs.len()];
    for b in 0..2 {
        let v: Vec<&PathVec> = y.iter().map(|p| &p[b]).collect();
        for (x, g) in w_path.iter_mut().zip(gram(&v, &v)) {
            *x += g;
        }
    }
    let scale = w_full.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = w_full
        .iter()
        .zip(&w_path)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(worst <= 1e-12 * scale, "W: {worst:e} of {scale:e}");

    let q = 4e4;
    let s_full = solve(&cs, &w_full, q, None).unwrap();
    let s_path = solve(&cs, &w_path, q, None).unwrap();
    assert_eq!(s_full.active, s_path.active, "same active set");
    assert!((s_full.psi - s_path.psi).abs() <= 1e-10 * s_full.psi.abs());

    // Displacements at every contact node under the contact forces.
    for (body, full, path) in [(0, &ca, &pa), (1, &cb, &pb)] {
        let parts: Vec<(&PathVec, &[f64])> = y
            .iter()
            .zip(&s_path.force)
            .map(|(v, f)| (&v[body], std::slice::from_ref(f)))
            .collect();
        let z = combine(&parts);
        let nodes = contact_nodes(&cs, body);
        let u_path = path.displacements(&[&z], &nodes).unwrap().remove(0);
        let mut u_full = vec![[0.0; 3]; nodes.len()];
        for (k, &i) in nodes.iter().enumerate() {
            for (c, con) in cs.iter().enumerate() {
                for t in con.terms.iter().filter(|t| t.body == body) {
                    let m = full.block(i, t.node).unwrap();
                    for r in 0..3 {
                        u_full[k][r] +=
                            (0..3).map(|q| m[r][q] * t.dir[q]).sum::<f64>() * s_path.force[c];
                    }
                }
            }
        }
        let umax = u_full.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (a, b) in u_full.iter().flatten().zip(u_path.iter().flatten()) {
            assert!((a - b).abs() <= 1e-12 * umax, "body {body}: {a} vs {b}");
        }
    }
}

/// Vertex coordinates on [0, total]: `n_fine` equal elements up to `fine`,
/// then `n_grow` elements growing geometrically to `total`.
fn graded(fine: f64, n_fine: usize, total: f64, n_grow: usize) -> Vec<f64> {
    let h = fine / n_fine as f64;
    let rest = total - fine;
    let sum = |r: f64| (1..=n_grow).map(|k| h * r.powi(k as i32)).sum::<f64>();
    let (mut lo, mut hi) = (1.0, 3.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if sum(mid) < rest {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let r = 0.5 * (lo + hi);
    let mut v: Vec<f64> = (0..=n_fine).map(|i| i as f64 * h).collect();
    let mut x = fine;
    for k in 1..=n_grow {
        x += h * r.powi(k as i32);
        v.push(x);
    }
    *v.last_mut().unwrap() = total;
    v
}

/// The same coordinates mirrored about 0: [−total, total].
fn symmetric(half: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = half.iter().rev().map(|x| -x).collect();
    v.extend_from_slice(&half[1..]);
    v
}

/// Piecewise-linear map of a block parameter onto vertex coordinates (mid-edge
/// nodes land on element midpoints).
fn along(v: &[f64], u: f64) -> f64 {
    let n = v.len() - 1;
    let t = u * n as f64;
    let i = (t.floor() as usize).min(n - 1);
    v[i] + (t - i as f64) * (v[i + 1] - v[i])
}

/// A steel cylinder (R = 20 mm) pressed on a steel block in plane strain
/// (one element layer, axial displacement held), both meshed with tet10 at
/// about 16 nodes across the contact width and solved by the reference
/// contact machinery: the peak pressure and the half-width are within 3% of
/// Hertz, and each body's approach between its surface and a point at depth
/// h ≈ 5b is within 3% of Weber–Banaschek,
/// w = 2q(1−ν²)/(πE) [ln(2h/b) − ν/(2(1−ν))].
#[test]
fn hertz_line_contact_cylinder_on_block() {
    let mat = Material::STEEL;
    let (e, nu) = (mat.youngs_modulus_pa, mat.poisson_ratio);
    let (r, thick, q_line) = (0.02, 1e-3, 2e5);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let b = (4.0 * q_line * r / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * q_line / (std::f64::consts::PI * b);
    let xs = symmetric(&graded(3.0 * b, 12, 0.01, 14));
    let ds = graded(3.0 * b, 12, 0.01, 14);
    let (nx, nd) = (xs.len() - 1, ds.len() - 1);
    let cyl = mapped_block([nx, nd, 1], |p| {
        let (s, d) = (along(&xs, p[0]), along(&ds, p[1]));
        let (rr, th) = (r - d, s / r);
        [rr * th.sin(), r - rr * th.cos(), thick * p[2]]
    });
    let blk = mapped_block([nx, nd, 1], |p| {
        [along(&xs, p[0]), -along(&ds, 1.0 - p[1]), thick * p[2]]
    });
    let plane = |blk: &Block, clamp: &dyn Fn([f64; 3]) -> bool| -> Vec<usize> {
        let mut f: Vec<usize> = (0..blk.params.len()).map(|i| 3 * i + 2).collect();
        f.extend(clamped(&nodes_where(blk, clamp)));
        f.sort_unstable();
        f.dedup();
        f
    };
    let down = |_: [f64; 3]| [0.0, -1.0, 0.0];
    let none = |_: [f64; 3]| [0.0, 0.0, 0.0];
    let a = ContactBody {
        body: 0,
        nodes: cyl.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&cyl, |p| p[1] < 1e-12),
        rigid: &down,
        youngs_modulus_pa: e,
    };
    let bb = ContactBody {
        body: 1,
        nodes: blk.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&blk, |p| p[1] > 1.0 - 1e-12),
        rigid: &none,
        youngs_modulus_pa: e,
    };
    let set = PenaltySettings {
        factor: 100.0,
        max_gap: 30e-6,
        reach: 1e-3,
        minima_band: 1.0,
    };
    let pairs = two_pass(&a, &bb, &set);
    let cs: Vec<Constraint> = pairs.iter().map(|c| c.0.clone()).collect();
    // Probe nodes: surface centre and depth ≈ 5b on the middle layer.
    let k = (0..ds.len())
        .min_by(|&i, &j| (ds[i] - 5.0 * b).abs().total_cmp(&(ds[j] - 5.0 * b).abs()))
        .unwrap();
    let h = ds[k];
    let vk = k as f64 / nd as f64;
    let find = |blk: &Block, p: [f64; 3]| -> usize {
        (0..blk.params.len())
            .find(|&i| (0..3).all(|c| (blk.params[i][c] - p[c]).abs() < 1e-12))
            .unwrap()
    };
    let probes_c = [find(&cyl, [0.5, 0.0, 0.5]), find(&cyl, [0.5, vk, 0.5])];
    let probes_b = [
        find(&blk, [0.5, 1.0, 0.5]),
        find(&blk, [0.5, 1.0 - vk, 0.5]),
    ];
    let mut uc = contact_nodes(&cs, 0);
    uc.extend(probes_c);
    let mut ub = contact_nodes(&cs, 1);
    ub.extend(probes_b);
    let fixed_c = plane(&cyl, &|p| p[1] > 1.0 - 1e-12);
    let fixed_b = plane(&blk, &|p| p[1] < 1e-12);
    let mut cc = BodyCompliance::new(&cyl.mesh, &mat, &fixed_c, &uc, 16).unwrap();
    let mut cb = BodyCompliance::new(&blk.mesh, &mat, &fixed_b, &ub, 16).unwrap();
    cc.ensure(&contact_nodes(&cs, 0)).unwrap();
    cb.ensure(&contact_nodes(&cs, 1)).unwrap();
    let idx: Vec<usize> = (0..cs.len()).collect();
    let w = condensed_matrix(&cs, &idx, &idx, &[&cc, &cb]).unwrap();
    let load = q_line * thick;
    let s = solve(&cs, &w, load, None).unwrap();
    assert!((carried_load(&cs, &s.force) - load).abs() < 1e-9 * load);
    // No constraint at the edge of the candidate band may be active.
    let edge = cs
        .iter()
        .zip(&s.active)
        .filter(|(c, &on)| on && c.gap0 > 0.5 * set.max_gap)
        .count();
    assert_eq!(edge, 0);

    // Half-width from the second moment of the load: ⟨x²⟩ = b²/4 for Hertz.
    let (mut f0, mut f2) = (0.0, 0.0);
    for (i, (_, o)) in pairs.iter().enumerate() {
        let x = o.at[0];
        f0 += s.force[i];
        f2 += s.force[i] * x * x;
    }
    let b_fe = 2.0 * (f2 / f0).sqrt();
    // Contact pressure on the block's surface, recovered from all the
    // contact forces on its nodes (both passes).
    let inward: std::collections::HashMap<usize, [f64; 3]> =
        validate::reference::contact_surface::nodal_normals(&bb.nodes, &bb.faces)
            .into_iter()
            .map(|(i, n)| (i, n.map(|c| -c)))
            .collect();
    let fb = validate::reference::penalty::nodal_normal_forces(&cs, &s.force, 1, &inward);
    let p = validate::reference::contact_surface::smoothed_pressure(&bb.nodes, &bb.faces, &fb);
    let p_max = p.values().cloned().fold(0.0, f64::max);
    // Approaches: displacement of the surface centre relative to depth h.
    let disp = |comp: &BodyCompliance, body: usize, node: usize| -> [f64; 3] {
        let mut u = [0.0; 3];
        for (c, con) in cs.iter().enumerate() {
            for t in con.terms.iter().filter(|t| t.body == body) {
                let m = comp.block(node, t.node).unwrap();
                for r in 0..3 {
                    u[r] += (0..3).map(|q| m[r][q] * t.dir[q]).sum::<f64>() * s.force[c];
                }
            }
        }
        u
    };
    let w_cyl = disp(&cc, 0, probes_c[0])[1] - disp(&cc, 0, probes_c[1])[1];
    let w_blk = disp(&cb, 1, probes_b[1])[1] - disp(&cb, 1, probes_b[0])[1];
    let wb = 2.0 * q_line * (1.0 - nu * nu) / (std::f64::consts::PI * e)
        * ((2.0 * h / b).ln() - nu / (2.0 * (1.0 - nu)));
    let rel = |x: f64, y: f64| (x - y).abs() / y;
    eprintln!(
        "Hertz: b {:.4} mm (FE {:.4}), p0 {:.1} MPa (FE {:.1}); h {:.3} mm: WB {:.4} um, cylinder {:.4}, block {:.4}",
        b * 1e3, b_fe * 1e3, p0 * 1e-6, p_max * 1e-6, h * 1e3, wb * 1e6, w_cyl * 1e6, w_blk * 1e6
    );
    assert!(rel(b_fe, b) < 0.03, "half-width {b_fe} vs {b}");
    assert!(rel(p_max, p0) < 0.03, "peak pressure {p_max} vs {p0}");
    assert!(rel(w_blk, wb) < 0.03, "block approach {w_blk} vs {wb}");
    assert!(rel(w_cyl, wb) < 0.03, "cylinder approach {w_cyl} vs {wb}");
}

/// The unloaded limit: a cylinder (R = 20 mm) lifted 1 µm above a block,
/// its lowest line placed midway between two node rows. Under a vanishing
/// load the rigid approach must equal the lift (the first contact of the
/// meshed surfaces), which the face minimum points catch; nodes alone would
/// need the extra d²/(2R) (d: distance to the nearest node row).
#[test]
fn first_contact_between_nodes_at_vanishing_load() {
    let mat = Material::STEEL;
    let (r, thick, lift) = (0.02, 1e-3, 1e-6);
    let xs = symmetric(&graded(0.6e-3, 4, 0.01, 6));
    let ds = graded(0.6e-3, 4, 0.01, 6);
    let (nx, nd) = (xs.len() - 1, ds.len() - 1);
    // Vertex spacing near the middle is 0.15 mm, nodes every 0.075 mm; the
    // lowest line at x = 0.0375 mm is 0.0375 mm from the nearest node row.
    let h_node = 0.5 * (xs[nx / 2 + 1] - xs[nx / 2]);
    let shift = 0.5 * h_node;
    let cyl = mapped_block([nx, nd, 1], |p| {
        let (s, d) = (along(&xs, p[0]), along(&ds, p[1]));
        let (rr, th) = (r - d, (s - shift) / r);
        [
            shift + rr * th.sin(),
            lift + r - rr * th.cos(),
            thick * p[2],
        ]
    });
    let blk = mapped_block([nx, nd, 1], |p| {
        [along(&xs, p[0]), -along(&ds, 1.0 - p[1]), thick * p[2]]
    });
    let down = |_: [f64; 3]| [0.0, -1.0, 0.0];
    let none = |_: [f64; 3]| [0.0, 0.0, 0.0];
    let a = ContactBody {
        body: 0,
        nodes: cyl.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&cyl, |p| p[1] < 1e-12),
        rigid: &down,
        youngs_modulus_pa: mat.youngs_modulus_pa,
    };
    let bb = ContactBody {
        body: 1,
        nodes: blk.mesh.nodes.clone(),
        to_body: IDENTITY,
        faces: faces_where(&blk, |p| p[1] > 1.0 - 1e-12),
        rigid: &none,
        youngs_modulus_pa: mat.youngs_modulus_pa,
    };
    let set = PenaltySettings {
        factor: 100.0,
        max_gap: 5e-6,
        reach: 1e-3,
        minima_band: 1.0,
    };
    let all: Vec<Constraint> = two_pass(&a, &bb, &set).into_iter().map(|c| c.0).collect();
    let fixed = |blk: &Block, top: bool| {
        let mut f: Vec<usize> = (0..blk.params.len()).map(|i| 3 * i + 2).collect();
        f.extend(clamped(&nodes_where(blk, |p| {
            if top {
                p[1] > 1.0 - 1e-12
            } else {
                p[1] < 1e-12
            }
        })));
        f.sort_unstable();
        f.dedup();
        f
    };
    let (uc, ub) = (contact_nodes(&all, 0), contact_nodes(&all, 1));
    let mut cc = BodyCompliance::new(&cyl.mesh, &mat, &fixed(&cyl, true), &uc, 16).unwrap();
    let mut cb = BodyCompliance::new(&blk.mesh, &mat, &fixed(&blk, false), &ub, 16).unwrap();
    cc.ensure(&uc).unwrap();
    cb.ensure(&ub).unwrap();
    let approach = |cs: &[Constraint]| {
        let idx: Vec<usize> = (0..cs.len()).collect();
        let w = condensed_matrix(cs, &idx, &idx, &[&cc, &cb]).unwrap();
        solve(cs, &w, 1e-6, None).unwrap().psi
    };
    let exact = approach(&all);
    // Nodes only: the constraints whose slave terms are a single node.
    let nodes_only: Vec<Constraint> = all
        .iter()
        .filter(|c| {
            c.terms.iter().filter(|t| t.body == 0).count() == 1
                || c.terms.iter().filter(|t| t.body == 1).count() == 1
        })
        .cloned()
        .collect();
    let sampled = approach(&nodes_only);
    let d = shift.min(h_node - shift);
    eprintln!(
        "first contact: lift {:.4} um, with face minima {:.5} um, nodes only {:.5} um (d²/2R = {:.5} um)",
        lift * 1e6,
        exact * 1e6,
        sampled * 1e6,
        d * d / (2.0 * r) * 1e6
    );
    assert!(
        (exact - lift).abs() < 1e-10,
        "approach {exact} vs lift {lift}"
    );
    assert!(sampled - lift > 0.5 * d * d / (2.0 * r));
}
