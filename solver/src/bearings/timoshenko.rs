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
}
