//! The FE core's dynamics against closed forms and dense linear algebra:
//! the consistent tet10 mass, natural modes by shift-invert Lanczos,
//! cantilever frequencies against beam theory, and the Craig–Bampton
//! reduction against the dense constrained model.

use faer::sparse::SparseColMat;
use fem::assembly::assemble_mass;
use fem::craig_bampton::{craig_bampton, RigidInterface};
use fem::modes::lowest_modes;
use fem::structured::{distort_interior, mapped_block, Block};
use fem::{assemble, tet10, Dofs, Material};
use nalgebra::DMatrix;

const STEEL: Material = Material::STEEL;
const DENSITY: f64 = 7850.0;

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

/// ∫ L₀ᵃ L₁ᵇ L₂ᶜ L₃ᵈ dV over the reference tetrahedron (V = 1/6):
/// a! b! c! d! 3! V / (a + b + c + d + 3)!.
fn volume_coordinate_monomial(p: [usize; 4]) -> f64 {
    p.iter().map(|&k| factorial(k)).product::<f64>() / factorial(p.iter().sum::<usize>() + 3)
}

#[test]
fn conical_rule_integrates_monomials_of_volume_coordinates_exactly() {
    // The 125-point rule is exact to degree 2·5 − 3 = 7.
    let rule = tet10::conical_rule(5);
    for a in 0..=7 {
        for b in 0..=(7 - a) {
            for c in 0..=(7 - a - b) {
                for d in 0..=(7 - a - b - c) {
                    let q: f64 = rule
                        .iter()
                        .map(|(x, w)| {
                            let l = [1.0 - x[0] - x[1] - x[2], x[0], x[1], x[2]];
                            w * l[0].powi(a as i32)
                                * l[1].powi(b as i32)
                                * l[2].powi(c as i32)
                                * l[3].powi(d as i32)
                        })
                        .sum();
                    let exact = volume_coordinate_monomial([a, b, c, d]);
                    assert!(
                        (q - exact).abs() < 1e-14 + 1e-12 * exact,
                        "L^{:?}: {q} against {exact}",
                        [a, b, c, d]
                    );
                }
            }
        }
    }
}

/// The textbook entries of the tet10 consistent mass, as multiples of ρV,
/// from the monomial integrals (V = volume): vertex N = L(2L − 1),
/// ∫ N² = 4/35 − 4/20 + 1/10 = 6/420; mid-edge N = 4 L_a L_b,
/// ∫ N² = 16 · 4/840 = 32/420; two vertices ∫ N₀N₁ = 4/210 − 4/60 + 1/20
/// = 1/420.
#[test]
fn consistent_mass_of_a_tet10_has_the_textbook_entries() {
    let x = tet10::reference_nodes();
    let v = 1.0 / 6.0;
    let m = tet10::mass(&x, 2.0).unwrap();
    let at = |a: usize, b: usize, i: usize| m[(3 * a + i) * 30 + 3 * b + i];
    for i in 0..3 {
        assert!((at(0, 0, i) - 2.0 * v * 6.0 / 420.0).abs() < 1e-15);
        assert!((at(4, 4, i) - 2.0 * v * 32.0 / 420.0).abs() < 1e-15);
        assert!((at(0, 1, i) - 2.0 * v / 420.0).abs() < 1e-15);
    }
    // No coupling between components.
    assert_eq!(m[1], 0.0);
    assert_eq!(m[30 * 4 + 3], 0.0);
}

#[test]
fn mass_of_a_curved_body_is_its_density_times_volume() {
    // A quarter of a thick ring: curved (isoparametric) elements.
    let block = mapped_block([3, 4, 2], |q| {
        let (r, t) = (0.02 + 0.01 * q[0], std::f64::consts::FRAC_PI_2 * q[1]);
        [r * t.cos(), r * t.sin(), 0.01 * q[2]]
    });
    let dofs = Dofs::new(&block.mesh, &[]).unwrap();
    let m = dense(&assemble_mass(&block.mesh, DENSITY, &dofs).unwrap());
    let n = m.nrows();
    // A rigid translation along y: uᵀ M u = ρ V.
    let u = DMatrix::from_fn(n, 1, |r, _| f64::from(u8::from(r % 3 == 1)));
    let mass = (u.transpose() * &m * &u)[(0, 0)];
    let volume: f64 = (0..block.mesh.tets.len())
        .map(|e| tet10::volume(&block.mesh.element(e)))
        .sum();
    assert!(
        (mass - DENSITY * volume).abs() < 1e-12 * DENSITY * volume,
        "{mass} against {}",
        DENSITY * volume
    );
    // Exact in closed form: a quarter annulus, (π/4)(r₂² − r₁²) t.
    let exact = DENSITY * std::f64::consts::FRAC_PI_4 * (0.03f64.powi(2) - 0.02f64.powi(2)) * 0.01;
    eprintln!(
        "quarter ring: {mass:.6} kg against {exact:.6} kg ({:+.2e})",
        (mass - exact) / exact
    );
    assert!(
        (mass - exact).abs() < 1e-4 * exact,
        "{mass} against {exact}"
    );
    assert!(assemble_mass(&block.mesh, -1.0, &dofs)
        .unwrap_err()
        .to_string()
        .contains("density_kg_m3 = -1"));
}

/// The full symmetric matrix of a lower triangle.
fn dense(a: &SparseColMat<usize, f64>) -> DMatrix<f64> {
    let n = a.ncols();
    let mut d = DMatrix::zeros(n, n);
    let (cp, ri, v) = (a.col_ptr(), a.row_idx(), a.val());
    for j in 0..n {
        for p in cp[j]..cp[j + 1] {
            d[(ri[p], j)] = v[p];
            d[(j, ri[p])] = v[p];
        }
    }
    d
}

/// ω² of the dense pencil (K, M), ascending: L⁻¹ K L⁻ᵀ with M = L Lᵀ.
fn dense_omega2(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Vec<f64> {
    let l = m.clone().cholesky().expect("M positive definite").l();
    let li = l.clone().try_inverse().unwrap();
    let c = &li * k * li.transpose();
    let c = 0.5 * (&c + c.transpose());
    let mut w: Vec<f64> = c.symmetric_eigenvalues().iter().copied().collect();
    w.sort_by(f64::total_cmp);
    w
}

/// A steel bar [0, l] × [0, b] × [0, h] of `n` cells.
fn bar(n: [usize; 3], l: f64, b: f64, h: f64) -> Block {
    mapped_block(n, |q| [l * q[0], b * q[1], h * q[2]])
}

/// Every dof of the nodes on x = 0.
fn clamped_root(block: &Block) -> Vec<usize> {
    (0..block.mesh.nodes.len())
        .filter(|&i| block.params[i][0] < 1e-12)
        .flat_map(|i| (0..3).map(move |c| 3 * i + c))
        .collect()
}

fn held(dofs: &[usize]) -> Vec<(usize, f64)> {
    dofs.iter().map(|&d| (d, 0.0)).collect()
}

#[test]
fn lanczos_modes_equal_the_dense_generalized_eigenvalues_of_a_small_cantilever() {
    let mut block = bar([4, 2, 2], 0.06, 0.01, 0.02);
    distort_interior(&mut block, 0.001, 3);
    let dofs = Dofs::new(&block.mesh, &held(&clamped_root(&block))).unwrap();
    let k = assemble(&block.mesh, &STEEL, &dofs).unwrap().matrix;
    let m = assemble_mass(&block.mesh, DENSITY, &dofs).unwrap();
    let exact = dense_omega2(&dense(&k), &dense(&m));
    let modes = lowest_modes(&k, &m, &dofs.node_of_free(), 8, 0.0).unwrap();
    let (kd, md) = (dense(&k), dense(&m));
    for (i, (w, e)) in modes.omega2.iter().zip(&exact).enumerate() {
        assert!((w - e).abs() < 1e-9 * e, "mode {i}: {w} against {e}");
        let phi = DMatrix::from_column_slice(k.ncols(), 1, &modes.shapes[i]);
        let r = &kd * &phi - *w * (&md * &phi);
        assert!(r.norm() < 1e-6 * (&kd * &phi).norm(), "mode {i} residual");
        for j in 0..=i {
            let pj = DMatrix::from_column_slice(k.ncols(), 1, &modes.shapes[j]);
            let g = (phi.transpose() * &md * pj)[(0, 0)];
            let want = f64::from(u8::from(i == j));
            assert!((g - want).abs() < 1e-9, "φ{i}ᵀ M φ{j} = {g}");
        }
    }
    // A shift above the lowest ω² is refused by name.
    let e = lowest_modes(&k, &m, &dofs.node_of_free(), 2, 1.5 * exact[0]).unwrap_err();
    assert!(e.to_string().contains("shift"), "{e}");
}

#[test]
fn free_block_has_six_rigid_modes_below_its_first_elastic_frequency() {
    let block = bar([4, 2, 2], 0.08, 0.02, 0.02);
    let dofs = Dofs::new(&block.mesh, &[]).unwrap();
    let k = assemble(&block.mesh, &STEEL, &dofs).unwrap().matrix;
    let m = assemble_mass(&block.mesh, DENSITY, &dofs).unwrap();
    // σ below zero: K − σM is positive definite although K is singular.
    let modes = lowest_modes(&k, &m, &dofs.node_of_free(), 8, -1e6).unwrap();
    let elastic = modes.omega2[6];
    assert!(elastic > 1e8, "first elastic ω² {elastic}");
    for w in &modes.omega2[..6] {
        assert!(w.abs() < 1e-8 * elastic, "rigid ω² {w} against {elastic}");
    }
    // A free-free bar's first bending frequency, Euler–Bernoulli:
    // ω = 4.7300² √(EI/(ρAL⁴)); square section, L/h = 4, so shear and
    // rotary inertia lower it by a good part: only its order is checked.
    let (l, h): (f64, f64) = (0.08, 0.02);
    let i = h.powi(4) / 12.0;
    let eb =
        4.7300f64.powi(2) * (STEEL.youngs_modulus_pa * i / (DENSITY * h * h * l.powi(4))).sqrt();
    let w = elastic.sqrt();
    eprintln!("free bar: rigid ω² at most {:.1e} of the first elastic {elastic:.4e}; ω {w:.1} against Euler–Bernoulli {eb:.1} rad/s", modes.omega2[..6].iter().fold(0.0f64, |a, x| a.max(x.abs())) / elastic);
    assert!(w < eb && w > 0.6 * eb, "ω {w} against Euler–Bernoulli {eb}");
}

/// The lowest ω of a steel cantilever bar [0, l] × [0, b] × [0, h].
fn cantilever_omega(n: [usize; 3], l: f64, b: f64, h: f64) -> f64 {
    let block = bar(n, l, b, h);
    let dofs = Dofs::new(&block.mesh, &held(&clamped_root(&block))).unwrap();
    let k = assemble(&block.mesh, &STEEL, &dofs).unwrap().matrix;
    let m = assemble_mass(&block.mesh, DENSITY, &dofs).unwrap();
    lowest_modes(&k, &m, &dofs.node_of_free(), 1, 0.0)
        .unwrap()
        .omega2[0]
        .sqrt()
}

/// A slender cantilever (l/b = 30) bending across its thin side b: the
/// frequency falls under nested refinement (Rayleigh–Ritz: each mesh's
/// space holds the coarser one's) and comes within 1 % of Euler–Bernoulli's
/// ω₁ = 1.8751² √(E I / (ρ A l⁴)), I = h b³/12, whose shear and
/// rotary-inertia corrections are of order (b/l)² here.
#[test]
fn cantilever_first_frequency_falls_under_refinement_to_euler_bernoulli() {
    let (l, b, h): (f64, f64, f64) = (0.3, 0.01, 0.02);
    let i = h * b.powi(3) / 12.0;
    let eb = 1.87510407f64.powi(2)
        * (STEEL.youngs_modulus_pa * i / (DENSITY * b * h * l.powi(4))).sqrt();
    let coarse = cantilever_omega([10, 1, 1], l, b, h);
    let fine = cantilever_omega([20, 2, 2], l, b, h);
    assert!(fine < coarse, "{fine} against {coarse}");
    assert!(fine > eb * 0.99, "{fine} below Euler–Bernoulli {eb}");
    let err = (fine - eb) / eb;
    eprintln!(
        "cantilever ω₁: {coarse:.2} / {fine:.2} rad/s against Euler–Bernoulli {eb:.2} ({:+.3} %)",
        100.0 * err
    );
    assert!(
        err.abs() < 0.01,
        "{fine} against {eb} ({:.3} %)",
        100.0 * err
    );
}

/// A cantilever bar clamped at x = 0 with its end face x = l as a rigid
/// interface about the face's centre.
fn cantilever_with_end_interface(
    n: [usize; 3],
    l: f64,
    b: f64,
    h: f64,
) -> (Block, Vec<usize>, RigidInterface) {
    let block = bar(n, l, b, h);
    let nodes: Vec<usize> = (0..block.mesh.nodes.len())
        .filter(|&i| block.params[i][0] > 1.0 - 1e-12)
        .collect();
    let fixed = clamped_root(&block);
    (
        block,
        fixed,
        RigidInterface {
            nodes,
            reference: [l, b / 2.0, h / 2.0],
        },
    )
}

/// The dense constrained model: K and M of the bar with its end face
/// following the reference point, in the coordinates (6 reference dofs;
/// the other free dofs), by an explicit transformation T₀ built here.
fn dense_constrained(
    block: &Block,
    fixed: &[usize],
    itf: &RigidInterface,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let dofs = Dofs::new(&block.mesh, &held(fixed)).unwrap();
    let k = dense(&assemble(&block.mesh, &STEEL, &dofs).unwrap().matrix);
    let m = dense(&assemble_mass(&block.mesh, DENSITY, &dofs).unwrap());
    let n = dofs.n_free();
    let on_face: std::collections::HashSet<usize> = itf.nodes.iter().copied().collect();
    let others: Vec<usize> = (0..3 * block.mesh.nodes.len())
        .filter(|d| dofs.free_index(*d).is_some() && !on_face.contains(&(d / 3)))
        .collect();
    let mut t = DMatrix::zeros(n, 6 + others.len());
    for &i in &itf.nodes {
        let r: [f64; 3] = std::array::from_fn(|a| block.mesh.nodes[i][a] - itf.reference[a]);
        // u = u_r + θ × r.
        let rows = [
            [1.0, 0.0, 0.0, 0.0, r[2], -r[1]],
            [0.0, 1.0, 0.0, -r[2], 0.0, r[0]],
            [0.0, 0.0, 1.0, r[1], -r[0], 0.0],
        ];
        for (a, row) in rows.iter().enumerate() {
            let f = dofs.free_index(3 * i + a).unwrap();
            for (c, v) in row.iter().enumerate() {
                t[(f, c)] = *v;
            }
        }
    }
    for (j, &d) in others.iter().enumerate() {
        t[(dofs.free_index(d).unwrap(), 6 + j)] = 1.0;
    }
    (t.transpose() * &k * &t, t.transpose() * &m * &t)
}

#[test]
fn craig_bampton_interface_block_is_the_dense_guyan_condensation() {
    let (block, fixed, itf) = cantilever_with_end_interface([4, 1, 2], 0.06, 0.01, 0.02);
    let cb = craig_bampton(
        &block.mesh,
        &STEEL,
        DENSITY,
        &fixed,
        std::slice::from_ref(&itf),
        4,
    )
    .unwrap();
    let (k, _) = dense_constrained(&block, &fixed, &itf);
    let r = k.nrows();
    let kbb = k.view((0, 0), (6, 6));
    let kbi = k.view((0, 6), (6, r - 6));
    let kii = k.view((6, 6), (r - 6, r - 6)).into_owned();
    let guyan = kbb - kbi * kii.cholesky().unwrap().solve(&kbi.transpose());
    let scale = guyan.abs().max();
    let kr = &cb.stiffness;
    for i in 0..6 {
        for j in 0..6 {
            assert!(
                (kr[(i, j)] - guyan[(i, j)]).abs() < 1e-8 * scale,
                "K_r[{i}][{j}] {} against {}",
                kr[(i, j)],
                guyan[(i, j)]
            );
        }
    }
    // Block-diagonal, ω² on the modal diagonal.
    for (k_mode, w) in cb.fixed_interface_omega2.iter().enumerate() {
        let d = 6 + k_mode;
        assert!((kr[(d, d)] - w).abs() < 1e-9 * w);
        assert!((cb.mass[(d, d)] - 1.0).abs() < 1e-9);
        for i in 0..6 {
            assert!(
                kr[(i, d)].abs() < 1e-9 * scale.max(*w),
                "coupling {}",
                kr[(i, d)]
            );
        }
    }
    assert_eq!(cb.interface_dofs(), 6);
}

#[test]
fn craig_bampton_frequencies_bound_the_full_model_from_above_and_converge() {
    let (block, fixed, itf) = cantilever_with_end_interface([4, 1, 2], 0.06, 0.01, 0.02);
    let (k, m) = dense_constrained(&block, &fixed, &itf);
    let exact = dense_omega2(&k, &m);
    let mut last_err = f64::INFINITY;
    for modes in [1, 4, 16] {
        let cb = craig_bampton(
            &block.mesh,
            &STEEL,
            DENSITY,
            &fixed,
            std::slice::from_ref(&itf),
            modes,
        )
        .unwrap();
        let w = dense_omega2(&cb.stiffness, &cb.mass);
        for i in 0..4 {
            assert!(
                w[i] >= exact[i] * (1.0 - 1e-9),
                "{modes} modes, mode {i}: {} below {}",
                w[i],
                exact[i]
            );
        }
        let err = (0..4)
            .map(|i| (w[i] - exact[i]) / exact[i])
            .fold(0.0, f64::max);
        eprintln!(
            "Craig–Bampton, {modes} modes: lowest four ω² at most {err:.2e} above the full model's"
        );
        assert!(err < last_err, "{modes} modes: {err} after {last_err}");
        last_err = err;
    }
    assert!(
        last_err < 1e-3,
        "16 modes: lowest four ω² within {last_err}"
    );
}

/// The reduced model's interface stiffness of a cantilever, inverted: the
/// tip deflection under a transverse force at the end face's centre is
/// Timoshenko's P l³/(3EI) + P l/(κ G A), κ = 10(1 + ν)/(12 + 11ν).
#[test]
fn craig_bampton_tip_compliance_of_a_cantilever_matches_timoshenko_beam() {
    let (l, b, h): (f64, f64, f64) = (0.2, 0.02, 0.02);
    let (block, fixed, itf) = cantilever_with_end_interface([20, 3, 3], l, b, h);
    let cb = craig_bampton(
        &block.mesh,
        &STEEL,
        DENSITY,
        &fixed,
        std::slice::from_ref(&itf),
        0,
    )
    .unwrap();
    let c = cb.stiffness.clone().try_inverse().unwrap();
    let nu = STEEL.poisson_ratio;
    let kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    let i = b * h.powi(3) / 12.0;
    let exact = l.powi(3) / (3.0 * STEEL.youngs_modulus_pa * i)
        + l / (kappa * STEEL.shear_modulus() * b * h);
    let err = (c[(2, 2)] - exact) / exact;
    eprintln!(
        "tip compliance {:.4e} against Timoshenko {exact:.4e} m/N ({:+.2} %)",
        c[(2, 2)],
        100.0 * err
    );
    assert!(
        err.abs() < 0.02,
        "tip compliance {} against {exact} ({:.2} %)",
        c[(2, 2)],
        100.0 * err
    );
    // End rotation under an end moment: l/(EI).
    let rot = l / (STEEL.youngs_modulus_pa * i);
    let err = (c[(4, 4)] - rot) / rot;
    eprintln!(
        "end rotation {:.4e} against l/(EI) {rot:.4e} rad/(N m) ({:+.2} %)",
        c[(4, 4)],
        100.0 * err
    );
    assert!(
        err.abs() < 0.02,
        "end rotation {} against {rot} ({:.2} %)",
        c[(4, 4)],
        100.0 * err
    );
}

/// The whole body with rigid interfaces, solved through the interior's
/// factor and the Guyan block (`Reduction::full_omega2`), has the dense
/// constrained model's lowest frequencies: the yardstick the housing
/// stage compares its truncated reduction with.
#[test]
fn rigid_interface_full_model_modes_equal_the_dense_constrained_model() {
    let (block, fixed, itf) = cantilever_with_end_interface([4, 1, 2], 0.06, 0.01, 0.02);
    let (k, m) = dense_constrained(&block, &fixed, &itf);
    let exact = dense_omega2(&k, &m);
    let itfs = std::slice::from_ref(&itf);
    let r = fem::craig_bampton::Reduction::new(&block.mesh, &STEEL, DENSITY, &fixed, itfs).unwrap();
    let full = r.full_omega2(6).unwrap();
    let cb = r.reduce(2).unwrap();
    assert_eq!(full.len(), 6);
    for i in 0..6 {
        assert!(
            (full[i] / exact[i] - 1.0).abs() < 1e-8,
            "mode {i}: {} against {}",
            full[i],
            exact[i]
        );
    }
    // With two fixed-interface modes the reduction is above it.
    let w = dense_omega2(&cb.stiffness, &cb.mass);
    assert!(w[3] > full[3] * (1.0 + 1e-6), "{} {}", w[3], full[3]);
}
