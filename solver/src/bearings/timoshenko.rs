//! The Timoshenko beam element of a shaft: 2 nodes, 6 degrees of freedom
//! each (u_x, u_y, u_z, θ_x, θ_y, θ_z), local x along the beam.
//!
//! Stiffness (Przemieniecki, *Theory of Matrix Structural Analysis*,
//! 1968: the beam element with shear deformation, exact for loads at its
//! nodes):
//!
//! - axial EA/L [1 −1; −1 1] on (u_x1, u_x2); torsion GJ/L on (θ_x1, θ_x2);
//! - bending in the x–y plane on (u_y1, θ_z1, u_y2, θ_z2), with
//!   Φ_y = 12 E I_z / (κ G A L²), the matrix below;
//! - bending in the x–z plane on (u_z1, θ_y1, u_z2, θ_y2) the same with
//!   I_y, Φ_z and the signs of the terms coupling u_z with θ_y reversed
//!   (θ_y = −du_z/dx).
//!
//! ```text
//! E I_z / ((1 + Φ_y) L³) · [  12    6L          −12   6L
//!                            6L    (4+Φ_y)L²   −6L   (2−Φ_y)L²
//!                           −12   −6L           12  −6L
//!                            6L    (2−Φ_y)L²   −6L   (4+Φ_y)L² ]
//! ```
//!
//! Section of a hollow round shaft (outer D, inner d): A = π(D² − d²)/4,
//! I_y = I_z = π(D⁴ − d⁴)/64, J = 2I, and Cowper's shear coefficient
//! κ = 6(1 + ν)(1 + m²)² / ((7 + 6ν)(1 + m²)² + (20 + 12ν)m²), m = d/D
//! (Cowper, J. Appl. Mech. 33, 1966; κ = 6(1 + ν)/(7 + 6ν) for a solid
//! shaft).
//!
//! Consistent mass of the same element (Przemieniecki, ch. 11: the
//! shape functions of the shear-deformable element, translational and
//! rotary inertia), density ρ:
//!
//! - axial ρAL/6 [2 1; 1 2]; torsion ρJL/6 [2 1; 1 2];
//! - bending in the x–y plane on (u_y1, θ_z1, u_y2, θ_z2), Φ = Φ_y:
//!   translational ρAL/(1 + Φ)² ·
//!   [m₁  m₂L  m₃  −m₄L; ·  m₅L²  m₄L  −m₆L²; ·  ·  m₁  −m₂L; ·  ·  ·  m₅L²],
//!   m₁ = 13/35 + 7Φ/10 + Φ²/3, m₂ = 11/210 + 11Φ/120 + Φ²/24,
//!   m₃ = 9/70 + 3Φ/10 + Φ²/6, m₄ = 13/420 + 3Φ/40 + Φ²/24,
//!   m₅ = 1/105 + Φ/60 + Φ²/120, m₆ = 1/140 + Φ/60 + Φ²/120;
//!   rotary ρI/((1 + Φ)² L) ·
//!   [6/5  r₁L  −6/5  r₁L; ·  r₂L²  −r₁L  r₃L²; ·  ·  6/5  −r₁L; ·  ·  ·  r₂L²],
//!   r₁ = 1/10 − Φ/2, r₂ = 2/15 + Φ/6 + Φ²/3, r₃ = −1/30 − Φ/6 + Φ²/6;
//! - bending in the x–z plane the same with the u–θ coupling signs
//!   reversed, as in the stiffness.
//!
//! At Φ = 0 it is the Euler–Bernoulli consistent mass ρAL/420 [156 22L 54
//! −13L; …]; a rigid translation carries ρAL whatever Φ.

use nalgebra::SMatrix;

/// The element stiffness, 12 × 12.
pub type ElementMatrix = SMatrix<f64, 12, 12>;

/// A round shaft's section and material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    pub area_m2: f64,
    /// Second moment about either transverse axis, m⁴.
    pub inertia_m4: f64,
    /// Polar (torsion) constant, m⁴.
    pub polar_m4: f64,
    /// Shear coefficient κ.
    pub shear_coefficient: f64,
    pub youngs_modulus_pa: f64,
    pub shear_modulus_pa: f64,
}

impl Section {
    /// A hollow round section of outer diameter `outer_m`, inner `inner_m`
    /// (0: solid), Young's modulus `e` and Poisson's ratio `nu`.
    pub fn round(outer_m: f64, inner_m: f64, e: f64, nu: f64) -> Section {
        let (d2, i2) = (outer_m * outer_m, inner_m * inner_m);
        let inertia = std::f64::consts::PI * (d2 * d2 - i2 * i2) / 64.0;
        let m2 = i2 / d2;
        let q = (1.0 + m2) * (1.0 + m2);
        Section {
            area_m2: std::f64::consts::PI * (d2 - i2) / 4.0,
            inertia_m4: inertia,
            polar_m4: 2.0 * inertia,
            shear_coefficient: 6.0 * (1.0 + nu) * q
                / ((7.0 + 6.0 * nu) * q + (20.0 + 12.0 * nu) * m2),
            youngs_modulus_pa: e,
            shear_modulus_pa: e / (2.0 * (1.0 + nu)),
        }
    }
}

/// The element stiffness of length `l` (m) in its local frame (see the
/// module documentation).
pub fn element_stiffness(s: &Section, l: f64) -> ElementMatrix {
    let (e, g) = (s.youngs_modulus_pa, s.shear_modulus_pa);
    let mut k = ElementMatrix::zeros();
    let mut put = |dofs: &[usize], m: &[f64], n: usize| {
        for (a, &i) in dofs.iter().enumerate() {
            for (b, &j) in dofs.iter().enumerate() {
                k[(i, j)] += m[a * n + b];
            }
        }
    };
    let ka = e * s.area_m2 / l;
    put(&[0, 6], &[ka, -ka, -ka, ka], 2);
    let kt = g * s.polar_m4 / l;
    put(&[3, 9], &[kt, -kt, -kt, kt], 2);
    let phi = 12.0 * e * s.inertia_m4 / (s.shear_coefficient * g * s.area_m2 * l * l);
    let c = e * s.inertia_m4 / ((1.0 + phi) * l * l * l);
    let (a, b) = ((4.0 + phi) * l * l, (2.0 - phi) * l * l);
    // x–y plane: (u_y1, θ_z1, u_y2, θ_z2).
    #[rustfmt::skip]
    let xy = [
        12.0 * c, 6.0 * l * c, -12.0 * c, 6.0 * l * c,
        6.0 * l * c, a * c, -6.0 * l * c, b * c,
        -12.0 * c, -6.0 * l * c, 12.0 * c, -6.0 * l * c,
        6.0 * l * c, b * c, -6.0 * l * c, a * c,
    ];
    put(&[1, 5, 7, 11], &xy, 4);
    // x–z plane: (u_z1, θ_y1, u_z2, θ_y2), θ_y = −du_z/dx.
    #[rustfmt::skip]
    let xz = [
        12.0 * c, -6.0 * l * c, -12.0 * c, -6.0 * l * c,
        -6.0 * l * c, a * c, 6.0 * l * c, b * c,
        -12.0 * c, 6.0 * l * c, 12.0 * c, 6.0 * l * c,
        -6.0 * l * c, b * c, 6.0 * l * c, a * c,
    ];
    put(&[2, 4, 8, 10], &xz, 4);
    k
}

/// Places the 4 × 4 bending blocks and the 2 × 2 axial and torsion
/// blocks of an element matrix (x–z block: u–θ coupling signs reversed).
fn element_matrix(axial: f64, torsion: f64, xy: &[f64; 16]) -> ElementMatrix {
    let mut k = ElementMatrix::zeros();
    let mut put = |dofs: &[usize], m: &[f64], n: usize| {
        for (a, &i) in dofs.iter().enumerate() {
            for (b, &j) in dofs.iter().enumerate() {
                k[(i, j)] += m[a * n + b];
            }
        }
    };
    put(&[0, 6], &[2.0 * axial, axial, axial, 2.0 * axial], 2);
    put(
        &[3, 9],
        &[2.0 * torsion, torsion, torsion, 2.0 * torsion],
        2,
    );
    put(&[1, 5, 7, 11], xy, 4);
    // (u_z1, θ_y1, u_z2, θ_y2): entries coupling a displacement with a
    // rotation change sign.
    let xz: [f64; 16] = std::array::from_fn(|i| {
        let (a, b) = (i / 4, i % 4);
        if (a % 2) != (b % 2) {
            -xy[i]
        } else {
            xy[i]
        }
    });
    put(&[2, 4, 8, 10], &xz, 4);
    k
}

/// The consistent element mass of length `l` (m) and density
/// `density_kg_m3` in its local frame (see the module documentation).
pub fn element_mass(s: &Section, l: f64, density_kg_m3: f64) -> ElementMatrix {
    let rho = density_kg_m3;
    let phi = 12.0 * s.youngs_modulus_pa * s.inertia_m4
        / (s.shear_coefficient * s.shear_modulus_pa * s.area_m2 * l * l);
    let q = (1.0 + phi) * (1.0 + phi);
    let t = rho * s.area_m2 * l / q;
    let m1 = 13.0 / 35.0 + 7.0 * phi / 10.0 + phi * phi / 3.0;
    let m2 = (11.0 / 210.0 + 11.0 * phi / 120.0 + phi * phi / 24.0) * l;
    let m3 = 9.0 / 70.0 + 3.0 * phi / 10.0 + phi * phi / 6.0;
    let m4 = (13.0 / 420.0 + 3.0 * phi / 40.0 + phi * phi / 24.0) * l;
    let m5 = (1.0 / 105.0 + phi / 60.0 + phi * phi / 120.0) * l * l;
    let m6 = (1.0 / 140.0 + phi / 60.0 + phi * phi / 120.0) * l * l;
    let r = rho * s.inertia_m4 / (q * l);
    let r0 = 6.0 / 5.0;
    let r1 = (0.1 - phi / 2.0) * l;
    let r2 = (2.0 / 15.0 + phi / 6.0 + phi * phi / 3.0) * l * l;
    let r3 = (-1.0 / 30.0 - phi / 6.0 + phi * phi / 6.0) * l * l;
    #[rustfmt::skip]
    let xy = [
        t * m1 + r * r0, t * m2 + r * r1, t * m3 - r * r0, -t * m4 + r * r1,
        t * m2 + r * r1, t * m5 + r * r2, t * m4 - r * r1, -t * m6 + r * r3,
        t * m3 - r * r0, t * m4 - r * r1, t * m1 + r * r0, -t * m2 - r * r1,
        -t * m4 + r * r1, -t * m6 + r * r3, -t * m2 - r * r1, t * m5 + r * r2,
    ];
    element_matrix(rho * s.area_m2 * l / 6.0, rho * s.polar_m4 * l / 6.0, &xy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    fn steel(d: f64) -> Section {
        Section::round(d, 0.0, 206e9, 0.3)
    }

    /// Cantilever clamped at node 1, tip load P at node 2: the element is
    /// exact for nodal loads, so one element gives Timoshenko's tip
    /// deflection PL³/(3EI) + PL/(κGA) and rotation PL²/(2EI), in both
    /// bending planes with their signs, the axial PL/(EA) and the twist
    /// TL/(GJ).
    #[test]
    fn cantilever_tip_matches_timoshenko_beam_theory() {
        let (s, l, p) = (steel(0.04), 0.3, 1000.0);
        let k = element_stiffness(&s, l);
        let free = DMatrix::from_fn(6, 6, |i, j| k[(6 + i, 6 + j)]);
        let lu = free.lu();
        let solve = |load: [f64; 6]| lu.solve(&DVector::from_row_slice(&load)).unwrap();
        let (e, g, i, a) = (
            s.youngs_modulus_pa,
            s.shear_modulus_pa,
            s.inertia_m4,
            s.area_m2,
        );
        let defl = p * l.powi(3) / (3.0 * e * i) + p * l / (s.shear_coefficient * g * a);
        let rot = p * l * l / (2.0 * e * i);
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-9 * y.abs();
        let y = solve([0.0, p, 0.0, 0.0, 0.0, 0.0]);
        assert!(close(y[1], defl) && close(y[5], rot), "{y}");
        let z = solve([0.0, 0.0, p, 0.0, 0.0, 0.0]);
        assert!(close(z[2], defl) && close(z[4], -rot), "{z}");
        let x = solve([p, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!(close(x[0], p * l / (e * a)));
        let t = solve([0.0, 0.0, 0.0, p, 0.0, 0.0]);
        assert!(close(t[3], p * l / (g * s.polar_m4)));
    }

    /// Rigid-body motions (translations, rotations about node 1) cost no
    /// energy: K r = 0.
    #[test]
    fn rigid_body_motions_are_free() {
        let l = 0.2;
        let k = element_stiffness(&Section::round(0.05, 0.02, 206e9, 0.3), l);
        let mut motions = Vec::new();
        for d in 0..3 {
            let mut v = [0.0; 12];
            v[d] = 1.0;
            v[6 + d] = 1.0;
            motions.push(v);
        }
        // Rotations θ about node 1: node 2 at (l, 0, 0) moves θ × (l, 0, 0).
        for d in 0..3 {
            let mut v = [0.0; 12];
            v[3 + d] = 1.0;
            v[9 + d] = 1.0;
            let mut th = nalgebra::Vector3::zeros();
            th[d] = 1.0;
            let u = th.cross(&nalgebra::Vector3::new(l, 0.0, 0.0));
            v[6] = u.x;
            v[7] = u.y;
            v[8] = u.z;
            motions.push(v);
        }
        for m in motions {
            let r = k * SMatrix::<f64, 12, 1>::from_row_slice(&m);
            assert!(r.norm() <= 1e-6 * k.norm(), "{m:?}: {}", r.norm());
        }
        assert!((k - k.transpose()).norm() <= 1e-12 * k.norm());
    }

    /// Cowper's κ: 6(1 + ν)/(7 + 6ν) for a solid section, and toward the
    /// thin tube's 2(1 + ν)/(4 + 3ν) as the wall thins.
    #[test]
    fn cowper_shear_coefficient_of_solid_and_thin_walled_shafts() {
        let nu = 0.3;
        let solid = Section::round(0.05, 0.0, 206e9, nu).shear_coefficient;
        assert!((solid - 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu)).abs() < 1e-12);
        let thin = Section::round(0.05, 0.0499, 206e9, nu).shear_coefficient;
        assert!(
            (thin - 2.0 * (1.0 + nu) / (4.0 + 3.0 * nu)).abs() < 1e-3,
            "{thin}"
        );
    }

    /// Without shear (G → ∞, Φ → 0) the mass is the Euler–Bernoulli
    /// consistent mass: translational ρAL/420 [156 22L 54 −13L; 22L 4L²
    /// 13L −3L²; …] and rotary ρI/(30L) [36 3L −36 3L; 3L 4L² −3L −L²; …].
    #[test]
    fn mass_without_shear_is_the_euler_bernoulli_consistent_mass() {
        let mut s = steel(0.04);
        s.shear_modulus_pa = 1e40;
        let (l, rho) = (0.25, 7850.0);
        let m = element_mass(&s, l, rho);
        let (t, r) = (rho * s.area_m2 * l / 420.0, rho * s.inertia_m4 / (30.0 * l));
        #[rustfmt::skip]
        let eb = [
            156.0 * t + 36.0 * r, 22.0 * l * t + 3.0 * l * r, 54.0 * t - 36.0 * r, -13.0 * l * t + 3.0 * l * r,
            22.0 * l * t + 3.0 * l * r, 4.0 * l * l * (t + r), 13.0 * l * t - 3.0 * l * r, -3.0 * l * l * t - l * l * r,
            54.0 * t - 36.0 * r, 13.0 * l * t - 3.0 * l * r, 156.0 * t + 36.0 * r, -22.0 * l * t - 3.0 * l * r,
            -13.0 * l * t + 3.0 * l * r, -3.0 * l * l * t - l * l * r, -22.0 * l * t - 3.0 * l * r, 4.0 * l * l * (t + r),
        ];
        for (a, &i) in [1, 5, 7, 11].iter().enumerate() {
            for (b, &j) in [1, 5, 7, 11].iter().enumerate() {
                let want = eb[4 * a + b];
                assert!(
                    (m[(i, j)] - want).abs() <= 1e-9 * m.norm(),
                    "({i},{j}): {} against {want}",
                    m[(i, j)]
                );
            }
        }
        assert!((m - m.transpose()).norm() <= 1e-15 * m.norm());
    }

    /// Rigid motions carry their exact kinetic energy whatever Φ (the
    /// element's shape functions hold them): a translation ρAL, a turn
    /// about the element's middle ρA l³/12 + ρ I l (translational plus
    /// rotary), a twist ρJL.
    #[test]
    fn rigid_motions_carry_their_exact_kinetic_energy() {
        let (l, rho) = (0.05, 7850.0);
        let s = Section::round(0.06, 0.02, 206e9, 0.3);
        let m = element_mass(&s, l, rho);
        let phi = 12.0 * s.youngs_modulus_pa * s.inertia_m4
            / (s.shear_coefficient * s.shear_modulus_pa * s.area_m2 * l * l);
        assert!(phi > 1.0, "a short, shear-dominated element: Φ = {phi}");
        let energy = |v: [f64; 12]| {
            let v = SMatrix::<f64, 12, 1>::from_row_slice(&v);
            (v.transpose() * m * v)[(0, 0)]
        };
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * y.abs();
        let mass = rho * s.area_m2 * l;
        for d in 0..3 {
            let mut v = [0.0; 12];
            v[d] = 1.0;
            v[6 + d] = 1.0;
            assert!(close(energy(v), mass), "translation {d}: {}", energy(v));
        }
        let turn = rho * s.area_m2 * l.powi(3) / 12.0 + rho * s.inertia_m4 * l;
        // About z: u_y = θ (x − l/2); about y: u_z = −θ (x − l/2).
        let about_z = [
            0.0,
            -l / 2.0,
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
            l / 2.0,
            0.0,
            0.0,
            0.0,
            1.0,
        ];
        let about_y = [
            0.0,
            0.0,
            l / 2.0,
            0.0,
            1.0,
            0.0,
            0.0,
            0.0,
            -l / 2.0,
            0.0,
            1.0,
            0.0,
        ];
        assert!(
            close(energy(about_z), turn),
            "{} against {turn}",
            energy(about_z)
        );
        assert!(
            close(energy(about_y), turn),
            "{} against {turn}",
            energy(about_y)
        );
        let twist = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        assert!(close(energy(twist), rho * s.polar_m4 * l));
    }

    /// The lowest bending ω² of a pinned–pinned shaft of `n` elements
    /// (dense generalized eigenproblem of the assembled K and M).
    fn pinned_shaft_omega2(s: &Section, length: f64, rho: f64, n: usize) -> f64 {
        // Pinned ends (u_y = u_z = 0), axial motion and twist held at node 0.
        shaft_omega2(s, length, rho, n, &[0, 1, 2, 3, 6 * n + 1, 6 * n + 2])[0]
    }

    /// Timoshenko beam theory, pinned–pinned, mode 1 (α = π/L, w = W sin αx,
    /// ψ = Ψ cos αx): det [κGAα² − ρAω², −κGAα; −κGAα, EIα² + κGA − ρIω²] = 0,
    /// a quadratic in ω² whose lower root is the bending mode. A thick shaft
    /// (L/D = 5), where Euler–Bernoulli's α⁴EI/(ρA) is several per cent
    /// high: the elements converge to Timoshenko's root at order 2.
    #[test]
    fn pinned_shaft_frequency_converges_to_timoshenko_beam_theory() {
        let (d, length, rho) = (0.05, 0.25, 7850.0);
        let s = steel(d);
        let (e, g, a, i, kappa) = (
            s.youngs_modulus_pa,
            s.shear_modulus_pa,
            s.area_m2,
            s.inertia_m4,
            s.shear_coefficient,
        );
        let al = std::f64::consts::PI / length;
        let (ks, kb) = (kappa * g * a, e * i * al * al);
        // (ks α² − ρA x)(kb + ks − ρI x) − ks² α² = 0, x = ω².
        let qa = rho * a * rho * i;
        let qb = -(ks * al * al * rho * i + rho * a * (kb + ks));
        let qc = ks * al * al * (kb + ks) - ks * ks * al * al;
        let exact = (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
        let euler_bernoulli = al.powi(4) * e * i / (rho * a);
        assert!(
            euler_bernoulli > 1.05 * exact,
            "shear matters here: {euler_bernoulli} against {exact}"
        );
        // From above (Rayleigh–Ritz), at order 2 (the interdependent
        // shape functions' consistent mass; measured error 3.8e-3, 8.6e-4,
        // 2.1e-4, 5.2e-5, 1.3e-5 at 4–64 elements).
        let mut last = f64::INFINITY;
        for n in [4, 8, 16, 32, 64] {
            let w2 = pinned_shaft_omega2(&s, length, rho, n);
            let err = (w2 - exact) / exact;
            assert!(err > -1e-9, "{n} elements: {err:e} below the exact root");
            assert!(err < last / 3.5, "{n} elements: {err:e} after {last:e}");
            last = err;
        }
        assert!(last < 2e-5, "64 elements: {last:e}");
    }

    /// Every ω² (ascending) of a uniform shaft of `n` elements with the
    /// global dofs `held`.
    fn shaft_omega2(s: &Section, length: f64, rho: f64, n: usize, held: &[usize]) -> Vec<f64> {
        let dofs = 6 * (n + 1);
        let (mut k, mut m) = (DMatrix::zeros(dofs, dofs), DMatrix::zeros(dofs, dofs));
        let l = length / n as f64;
        let (ke, me) = (element_stiffness(s, l), element_mass(s, l, rho));
        for e in 0..n {
            for i in 0..12 {
                for j in 0..12 {
                    k[(6 * e + i, 6 * e + j)] += ke[(i, j)];
                    m[(6 * e + i, 6 * e + j)] += me[(i, j)];
                }
            }
        }
        let free: Vec<usize> = (0..dofs).filter(|d| !held.contains(d)).collect();
        let sub = |a: &DMatrix<f64>| {
            DMatrix::from_fn(free.len(), free.len(), |i, j| a[(free[i], free[j])])
        };
        let li = sub(&m).cholesky().unwrap().l().try_inverse().unwrap();
        let c = &li * sub(&k) * li.transpose();
        let mut w: Vec<f64> = (0.5 * (&c + c.transpose()))
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .collect();
        w.sort_by(f64::total_cmp);
        w
    }

    /// A slender shaft (L/D = 50: shear and rotary inertia below 0.05 %)
    /// in 20 elements, clamped at one end and free at both: its first
    /// bending frequencies (twice, one per plane) are Euler–Bernoulli's
    /// (βL)² √(EI/(ρAL⁴)), βL = 1.87510 and 4.73004, within 0.5 %; the
    /// free shaft's six rigid modes come first, at zero.
    #[test]
    fn cantilever_and_free_free_shaft_frequencies_are_euler_bernoullis() {
        let (d, length, rho) = (0.02, 1.0_f64, 7850.0);
        let s = steel(d);
        let w0 = (s.youngs_modulus_pa * s.inertia_m4 / (rho * s.area_m2 * length.powi(4))).sqrt();
        let n = 20;
        let clamped = shaft_omega2(&s, length, rho, n, &[0, 1, 2, 3, 4, 5]);
        let free = shaft_omega2(&s, length, rho, n, &[]);
        for (w2, bl, what) in [
            (&clamped[..2], 1.875_104_07_f64, "cantilever"),
            (&free[6..8], 4.730_040_74_f64, "free–free"),
        ] {
            let exact = bl * bl * w0;
            for &x in w2 {
                let err = x.sqrt() / exact - 1.0;
                assert!(
                    err.abs() < 5e-3,
                    "{what}: {} against {exact} rad/s ({err:e})",
                    x.sqrt()
                );
            }
        }
        for &x in &free[..6] {
            assert!(x.abs() < 1e-6 * free[6], "rigid mode ω² = {x}");
        }
    }
}
