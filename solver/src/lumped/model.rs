//! The 8-degree-of-freedom lumped model of a bevel gear pair (seed 004's
//! "concentrated parameter" model): each member moves in X, Y, Z on its
//! bearings and turns by θ about its axis.
//!
//! Coordinates `q = {X₁, Y₁, Z₁, θ₁, X₂, Y₂, Z₂, θ₂}` (m, m, m, rad; 1 =
//! pinion, 2 = wheel); the origin is the intersection of the axes, the
//! pinion axis along X and the wheel axis along Y, as in seed 004. θᵢ is the
//! member's rotation away from its nominal rigid rotation (Ω₁t, Ω₂t), so it
//! stays small.
//!
//! Mesh force along the common normal, with the direction cosines
//!
//! ```text
//! a₁ = −(sin αₙ cos δ₂ + σ cos αₙ sin β₂ sin δ₂)
//! a₂ =   sin αₙ sin δ₂ − σ cos αₙ sin β₂ cos δ₂
//! a₃ = ± cos αₙ cos β₂
//! ```
//!
//! (αₙ normal pressure angle of the loaded flank, β₂ the wheel's mean
//! spiral angle, δ₂ its pitch angle). That is the normal split into
//! sin αₙ across the pitch line in the axial plane, cos αₙ sin β₂ along the
//! pitch line (X, Y = ∓ its components (sin δ₂, cos δ₂)) and
//! cos αₙ cos β₂ tangential (Z). The spiral term's sign σ belongs to the
//! loaded flank: σ = +1 with the pinion's concave flank loaded (drive),
//! −1 with its convex flank (coast); the hand sets only the sign of a₃
//! (a pair of the other hands, turning the other way on the same flanks,
//! is the mirror image in the plane of the two axes). Seed 004 prints
//! a₁ = −(sin αₙ cos δ₂ + cos αₙ sin β₂ sin δ₂) and a₂ = sin αₙ sin δ₂ ±
//! cos αₙ sin β₂ cos δ₂ with the sign by the hand; with the upper sign
//! that is not a unit vector (|a|² = 1 + sin 2αₙ sin β₂ sin 2δ₂, 1.16 for
//! its 23/86 pair), so a₂ takes the sign that makes |a| = 1; and taking σ
//! from the hand, as seed 004 does, puts our LTCA's force-weighted normal
//! 37° away from a for seed 003's right-hand wheel on the drive flank,
//! against 0.9° for seed 004's left-hand wheel (the test
//! `lumped_direction_cosines_match_our_ltca_normal` checks the rule). The
//! normal relative displacement
//!
//! ```text
//! λ = a₁(X₁ − X₂) + a₂(Y₁ − Y₂) + a₃(Z₁ − Z₂) + r₁θ₁ − r₂θ₂ − e(t)
//! Fₙ = k(t) λ + cₙ λ̇ + F_imp(t)
//! ```
//!
//! (rᵢ the lever of the normal force about member i's axis, e(t) the static
//! transmission error along the normal, F_imp the meshing-impact pulse) and
//! the equations of motion
//!
//! ```text
//! m₁ Ẍ₁ + c₁ₓ Ẋ₁ + k₁ₓ X₁ = −a₁ Fₙ      m₂ Ẍ₂ + c₂ₓ Ẋ₂ + k₂ₓ X₂ = +a₁ Fₙ
//! m₁ Ÿ₁ + c₁ᵧ Ẏ₁ + k₁ᵧ Y₁ = −a₂ Fₙ      m₂ Ÿ₂ + c₂ᵧ Ẏ₂ + k₂ᵧ Y₂ = +a₂ Fₙ
//! m₁ Z̈₁ + c₁_z Ż₁ + k₁_z Z₁ = −a₃ Fₙ    m₂ Z̈₂ + c₂_z Ż₂ + k₂_z Z₂ = +a₃ Fₙ
//! J₁ θ̈₁ = T₁ − r₁ Fₙ                     J₂ θ̈₂ = −T₂ + r₂ Fₙ
//! ```
//!
//! with T₂ = T₁ r₂/r₁, so that the rigid rotation (θ₁, θ₂) ∝ (r₂, r₁) is
//! force-free. With constant k the linear part is `M q̈ + C q̇ + K q = f`
//! with `M = diag(m₁, m₁, m₁, J₁, m₂, m₂, m₂, J₂)`, `K = K_b + k v vᵀ`,
//! `C = C_b + cₙ v vᵀ` and `v = (a₁, a₂, a₃, r₁, −a₁, −a₂, −a₃, −r₂)` (the
//! gradient of λ), K_b and C_b the diagonal bearing terms.

use super::LumpedError;
use geometry::generation::Side;
use nalgebra::{SMatrix, SVector};

/// 8 × 8 matrix of the model.
pub type Mat8 = SMatrix<f64, 8, 8>;
/// 8-vector of the model's coordinates.
pub type Vec8 = SVector<f64, 8>;

/// Hand of spiral of the wheel (member 2); it sets the signs of a₂ and a₃.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WheelHand {
    Left,
    Right,
}

/// Direction cosines (a₁, a₂, a₃) of the mesh normal (see the module doc),
/// from the loaded flank's normal pressure angle `alpha_n`, the wheel's
/// mean spiral angle `beta` and pitch angle `delta2` (rad), the wheel's
/// hand and the loaded flank `side` (drive: pinion concave). A unit vector.
pub fn direction_cosines(
    alpha_n: f64,
    beta: f64,
    delta2: f64,
    hand: WheelHand,
    side: Side,
) -> [f64; 3] {
    let t = match hand {
        WheelHand::Left => 1.0,
        WheelHand::Right => -1.0,
    };
    let s = match side {
        Side::Drive => 1.0,
        Side::Coast => -1.0,
    };
    let (sa, ca) = alpha_n.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let (sd, cd) = delta2.sin_cos();
    [
        -(sa * cd + s * ca * sb * sd),
        sa * sd - s * ca * sb * cd,
        t * ca * cb,
    ]
}

/// One member on its bearings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Member {
    pub mass_kg: f64,
    /// Polar moment about the member's axis, kg·m².
    pub inertia_kgm2: f64,
    /// Bearing stiffness in X, Y, Z, N/m.
    pub bearing_stiffness_n_per_m: [f64; 3],
    /// Bearing damping in X, Y, Z, N·s/m.
    pub bearing_damping_ns_per_m: [f64; 3],
}

/// The model's constant data.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// Pinion, wheel.
    pub members: [Member; 2],
    /// (a₁, a₂, a₃).
    pub direction: [f64; 3],
    /// Levers r₁, r₂ of the normal force about the pinion and wheel axes, m.
    pub levers_m: [f64; 2],
    /// Mesh damping cₙ, N·s/m.
    pub mesh_damping_ns_per_m: f64,
    /// Pinion torque T₁, N·m (the wheel's load torque is T₁ r₂/r₁).
    pub pinion_torque_nm: f64,
}

/// Checks that `v` is finite and > 0 (or ≥ 0 when `zero_ok`).
pub(crate) fn positive(what: &str, v: f64, zero_ok: bool) -> Result<(), LumpedError> {
    let ok = v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0));
    if ok {
        Ok(())
    } else {
        Err(LumpedError::Input(format!(
            "{what} = {v}: must be finite and {}",
            if zero_ok { "≥ 0" } else { "> 0" }
        )))
    }
}

impl Model {
    /// Natural frequencies (Hz) of the linear model at stiffness `k`, the rigid
    /// rotation left out.
    pub fn natural_frequencies(&self, k: f64) -> Vec<f64> {
        let kmat = self.stiffness(k);
        let m = self.mass_diagonal();
        let s: Vec<f64> = m.iter().map(|x| 1.0 / x.sqrt()).collect();
        let a = nalgebra::DMatrix::from_fn(8, 8, |i, j| s[i] * kmat[(i, j)] * s[j]);
        let mut w: Vec<f64> = nalgebra::SymmetricEigen::new(a)
            .eigenvalues
            .iter()
            .map(|l| l.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
            .collect();
        w.sort_by(f64::total_cmp);
        w.into_iter().skip(1).collect()
    }

    /// Checks the data: masses, moments, levers > 0; stiffness, damping,
    /// torque ≥ 0; a unit direction.
    pub fn check(&self) -> Result<(), LumpedError> {
        for (m, name) in self.members.iter().zip(["pinion", "wheel"]) {
            positive(&format!("{name} mass_kg"), m.mass_kg, false)?;
            positive(&format!("{name} inertia_kgm2"), m.inertia_kgm2, false)?;
            for d in 0..3 {
                positive(
                    &format!("{name} bearing stiffness [{d}]"),
                    m.bearing_stiffness_n_per_m[d],
                    true,
                )?;
                positive(
                    &format!("{name} bearing damping [{d}]"),
                    m.bearing_damping_ns_per_m[d],
                    true,
                )?;
            }
        }
        positive("lever r1", self.levers_m[0], false)?;
        positive("lever r2", self.levers_m[1], false)?;
        positive("mesh damping", self.mesh_damping_ns_per_m, true)?;
        positive("pinion torque", self.pinion_torque_nm, true)?;
        let n: f64 = self.direction.iter().map(|a| a * a).sum();
        if (n - 1.0).abs() > 1e-9 {
            return Err(LumpedError::Input(format!(
                "direction cosines {:?}: |a| = {} must be 1",
                self.direction,
                n.sqrt()
            )));
        }
        Ok(())
    }

    /// v = ∂λ/∂q = (a₁, a₂, a₃, r₁, −a₁, −a₂, −a₃, −r₂).
    pub fn mesh_vector(&self) -> Vec8 {
        let [a1, a2, a3] = self.direction;
        let [r1, r2] = self.levers_m;
        Vec8::from([a1, a2, a3, r1, -a1, -a2, -a3, -r2])
    }

    /// M = diag(m₁, m₁, m₁, J₁, m₂, m₂, m₂, J₂).
    pub fn mass(&self) -> Mat8 {
        Mat8::from_diagonal(&Vec8::from(self.mass_diagonal()))
    }

    pub fn mass_diagonal(&self) -> [f64; 8] {
        let [p, w] = &self.members;
        [
            p.mass_kg,
            p.mass_kg,
            p.mass_kg,
            p.inertia_kgm2,
            w.mass_kg,
            w.mass_kg,
            w.mass_kg,
            w.inertia_kgm2,
        ]
    }

    /// K = K_b + k v vᵀ for a constant mesh stiffness `k` (N/m).
    pub fn stiffness(&self, k: f64) -> Mat8 {
        let v = self.mesh_vector();
        let mut m = v * v.transpose() * k;
        for (i, b) in self.members.iter().enumerate() {
            for d in 0..3 {
                m[(4 * i + d, 4 * i + d)] += b.bearing_stiffness_n_per_m[d];
            }
        }
        m
    }

    /// C = C_b + cₙ v vᵀ.
    pub fn damping(&self) -> Mat8 {
        let v = self.mesh_vector();
        let mut m = v * v.transpose() * self.mesh_damping_ns_per_m;
        for (i, b) in self.members.iter().enumerate() {
            for d in 0..3 {
                m[(4 * i + d, 4 * i + d)] += b.bearing_damping_ns_per_m[d];
            }
        }
        m
    }

    /// Equivalent mass of the torsional mesh, mₑ = J₁J₂ / (J₂r₁² + J₁r₂²) (seed 004).
    pub fn equivalent_mass(&self) -> f64 {
        let [j1, j2] = [self.members[0].inertia_kgm2, self.members[1].inertia_kgm2];
        let [r1, r2] = self.levers_m;
        j1 * j2 / (j2 * r1 * r1 + j1 * r2 * r2)
    }

    /// Mean normal mesh force Fₘ = T₁/r₁, N.
    pub fn mean_mesh_force(&self) -> f64 {
        self.pinion_torque_nm / self.levers_m[0]
    }

    /// External generalized forces: the torques (0, 0, 0, T₁, 0, 0, 0, −T₂),
    /// T₂ = T₁ r₂/r₁.
    pub fn torques(&self) -> Vec8 {
        let t1 = self.pinion_torque_nm;
        let t2 = t1 * self.levers_m[1] / self.levers_m[0];
        Vec8::from([0.0, 0.0, 0.0, t1, 0.0, 0.0, 0.0, -t2])
    }

    /// Bearing forces on member `i` (0 pinion, 1 wheel): kᵢⱼ qᵢⱼ + cᵢⱼ q̇ᵢⱼ, N,
    /// the force the member exerts on its bearing in X, Y, Z.
    pub fn bearing_force(&self, i: usize, q: &[f64], qd: &[f64]) -> [f64; 3] {
        let b = &self.members[i];
        std::array::from_fn(|d| {
            b.bearing_stiffness_n_per_m[d] * q[4 * i + d]
                + b.bearing_damping_ns_per_m[d] * qd[4 * i + d]
        })
    }
}

/// Mesh damping from a damping ratio ζ: cₙ = 2ζ √(kₘ mₑ), mₑ the
/// equivalent mass of the torsional mesh (seed 003's eq. (29) with the
/// dimensionally consistent mₑ of seed 004: seed 003 prints
/// J₁J₂R₁²R₂²/(R₁²J₁ + R₂²J₂), which is not a mass).
pub fn mesh_damping_for_ratio(zeta: f64, k_mean: f64, equivalent_mass: f64) -> f64 {
    2.0 * zeta * (k_mean * equivalent_mass).sqrt()
}
