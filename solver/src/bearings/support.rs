//! A member's shaft on compliant bearings: the rigid-body support that turns
//! a mesh force into bearing reactions and a small displacement of the
//! member (translation and tilt), from which the pair's relative pose, its
//! load-dependent misalignment, follows.
//!
//! Bearing i sits on the shaft axis a at pᵢ = o + sᵢ a (o: the member's
//! pitch apex, sᵢ its axial position). A small rigid displacement of the
//! member, translation u and rotation θ about o, moves the bearing point by
//!
//! dᵢ = u + θ × rᵢ,  rᵢ = pᵢ − o,
//!
//! and the bearing pushes back with fᵢ = −Kᵢ dᵢ,
//! Kᵢ = k_r,i (I − a aᵀ) + k_a,i a aᵀ (radial and axial stiffness).
//! With Bᵢ = [I | −[rᵢ]ₓ] (dᵢ = Bᵢ [u; θ]) the support stiffness is
//!
//! K = Σᵢ Bᵢᵀ Kᵢ Bᵢ  (6 × 6, symmetric),
//!
//! singular along the rotation about a alone: that is the gear's own
//! turning, held by the torque the shaft carries, not by the bearings.
//! A force F applied at x (generalized load g = [F; rₓ × F], rₓ = x − o)
//! is carried in the five other directions: with Q an orthonormal basis of
//! them, K_Q = QᵀKQ, [u; θ] = Q K_Q⁻¹ Qᵀ g; the reactions then balance F
//! and its moment about every axis but a, whose moment −a·(rₓ × F) is the
//! shaft torque.
//!
//! Two bearings with radial stiffness at distinct positions and one with
//! axial stiffness make the support statically determinate in the radial
//! plane (the reactions follow from the lever rule whatever the
//! stiffnesses), which the tests check against the closed forms.

use nalgebra::{Matrix3, Matrix6, Matrix6x5, Vector3, Vector6};

/// One bearing on the shaft axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bearing {
    /// Position along the shaft axis from the member's pitch apex, m
    /// (positive along the axis direction of the member frame).
    pub axial_position_m: f64,
    /// Radial stiffness, N/m (the same in every radial direction).
    pub radial_stiffness_n_per_m: f64,
    /// Axial stiffness, N/m (0: a floating bearing).
    pub axial_stiffness_n_per_m: f64,
}

/// Why a support cannot carry a load in every direction but the turning.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BearingError {
    #[error("{field} = {value}: must be {limit}")]
    Value {
        field: String,
        value: f64,
        limit: &'static str,
    },
    #[error("the shaft needs two bearings with radial stiffness at different axial positions (to hold tilt); it has {0}")]
    Tilt(usize),
    #[error("no bearing has axial stiffness: the shaft would slide along its axis; give one bearing `axial_stiffness_n_per_m` > 0")]
    Axial,
    #[error(transparent)]
    Shaft(#[from] super::flexible_shaft::ShaftError),
}

/// A small rigid displacement of a member about its pitch apex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Displacement {
    /// Translation of the apex, m.
    pub translation: Vector3<f64>,
    /// Small rotation vector, rad (none about the shaft axis).
    pub rotation: Vector3<f64>,
}

/// A member's shaft on its bearings, in the fixed frame.
#[derive(Debug, Clone)]
pub struct Support {
    axis: Vector3<f64>,
    apex: Vector3<f64>,
    bearings: Vec<Bearing>,
    /// Orthonormal basis of the five directions the bearings hold.
    held: Matrix6x5<f64>,
    /// Each bearing's displacement per member displacement [u; θ]: Bᵢ for
    /// a rigid shaft, the condensed shaft's map for a flexible one.
    maps: Vec<nalgebra::Matrix3x6<f64>>,
    /// The support stiffness about the apex.
    k: Matrix6<f64>,
}

/// The skew matrix [r]ₓ with [r]ₓ v = r × v.
fn skew(r: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -r.z, r.y, r.z, 0.0, -r.x, -r.y, r.x, 0.0)
}

impl Support {
    /// `axis`: the shaft axis (any length), `apex`: the member's pitch apex,
    /// both in the fixed frame; `bearings` named `<member>.bearings[i]` in
    /// messages through `field`.
    pub fn new(
        field: &str,
        axis: Vector3<f64>,
        apex: Vector3<f64>,
        bearings: &[Bearing],
    ) -> Result<Support, BearingError> {
        let n = axis.norm();
        if !(n.is_finite() && n > 0.0) {
            return Err(BearingError::Value {
                field: format!("{field}.axis"),
                value: n,
                limit: "a finite, non-zero direction",
            });
        }
        for (i, b) in bearings.iter().enumerate() {
            for (name, v, positive) in [
                ("axial_position_m", b.axial_position_m, false),
                ("radial_stiffness_n_per_m", b.radial_stiffness_n_per_m, true),
                ("axial_stiffness_n_per_m", b.axial_stiffness_n_per_m, true),
            ] {
                if !v.is_finite() || (positive && v < 0.0) {
                    return Err(BearingError::Value {
                        field: format!("{field}[{i}].{name}"),
                        value: v,
                        limit: if positive {
                            "finite and ≥ 0"
                        } else {
                            "finite"
                        },
                    });
                }
            }
        }
        let radial: Vec<f64> = bearings
            .iter()
            .filter(|b| b.radial_stiffness_n_per_m > 0.0)
            .map(|b| b.axial_position_m)
            .collect();
        let span = radial.iter().fold(f64::NEG_INFINITY, |m, &s| m.max(s))
            - radial.iter().fold(f64::INFINITY, |m, &s| m.min(s));
        if radial.len() < 2 || span <= 0.0 {
            return Err(BearingError::Tilt(radial.len()));
        }
        if bearings.iter().all(|b| b.axial_stiffness_n_per_m <= 0.0) {
            return Err(BearingError::Axial);
        }
        let a = axis / n;
        // Two radial directions, then the held basis: translations along
        // e1, e2, a and rotations about e1, e2.
        let helper = if a.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let e1 = a.cross(&helper).normalize();
        let e2 = a.cross(&e1);
        let z = Vector3::zeros();
        let col = |t: Vector3<f64>, r: Vector3<f64>| Vector6::new(t.x, t.y, t.z, r.x, r.y, r.z);
        let held =
            Matrix6x5::from_columns(&[col(e1, z), col(e2, z), col(a, z), col(z, e1), col(z, e2)]);
        let mut s = Support {
            axis: a,
            apex,
            bearings: bearings.to_vec(),
            held,
            maps: Vec::new(),
            k: Matrix6::zeros(),
        };
        s.maps = s.bearings.iter().map(|b| s.kinematics(b)).collect();
        s.k = s
            .bearings
            .iter()
            .zip(&s.maps)
            .map(|(b, bi)| bi.transpose() * s.bearing_matrix(b) * bi)
            .sum();
        Ok(s)
    }

    /// The member on a flexible `shaft` (Timoshenko beam elements,
    /// [`super::flexible_shaft`]) carried by `bearings`: the shaft with its
    /// bearings condensed onto the gear's seat, then moved to the apex. With
    /// the seat at s on the axis a, the seat moves by
    /// [u + θ × (s a); θ] when the member moves by [u; θ] about the apex
    /// (B_s), and in the shaft frame (x = a, y = e₁, z = e₂; R = [a e₁ e₂])
    ///
    ///   K = (R₆ᵀ B_s)ᵀ K_c (R₆ᵀ B_s),   Dᵢ = R Dᵢˡ R₆ᵀ B_s,
    ///
    /// Dᵢˡ the condensation's map of bearing i. A very stiff shaft gives
    /// the rigid support of [`Support::new`].
    pub fn on_shaft(
        field: &str,
        axis: Vector3<f64>,
        apex: Vector3<f64>,
        bearings: &[Bearing],
        shaft: &super::flexible_shaft::Shaft,
    ) -> Result<Support, BearingError> {
        let mut s = Support::new(field, axis, apex, bearings)?;
        let c = shaft.condense(&format!("{field}_shaft"), bearings)?;
        let a = s.axis;
        let (e1, e2) = (
            s.held.fixed_view::<3, 1>(0, 0).into_owned(),
            s.held.fixed_view::<3, 1>(0, 1).into_owned(),
        );
        let r = Matrix3::from_columns(&[a, e1, e2]);
        let mut r6 = Matrix6::zeros();
        r6.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
        r6.fixed_view_mut::<3, 3>(3, 3).copy_from(&r);
        let mut bs = Matrix6::identity();
        bs.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-skew(&(a * shaft.seat_m))));
        let t = r6.transpose() * bs;
        s.k = t.transpose() * c.seat_stiffness * t;
        s.k = 0.5 * (s.k + s.k.transpose());
        s.maps = c.bearing_maps.iter().map(|d| r * d * t).collect();
        Ok(s)
    }

    /// The unit shaft axis.
    pub fn axis(&self) -> Vector3<f64> {
        self.axis
    }

    /// Kᵢ of bearing `b`.
    fn bearing_matrix(&self, b: &Bearing) -> Matrix3<f64> {
        let aat = self.axis * self.axis.transpose();
        (Matrix3::identity() - aat) * b.radial_stiffness_n_per_m + aat * b.axial_stiffness_n_per_m
    }

    /// rᵢ = pᵢ − o of bearing `b`.
    fn arm(&self, b: &Bearing) -> Vector3<f64> {
        self.axis * b.axial_position_m
    }

    /// Bᵢ: bearing-point displacement per rigid displacement [u; θ].
    fn kinematics(&self, b: &Bearing) -> nalgebra::Matrix3x6<f64> {
        let mut m = nalgebra::Matrix3x6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::identity());
        m.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-skew(&self.arm(b))));
        m
    }

    /// The support stiffness about the apex, N/m, N, N·m: K = Σ Bᵢᵀ Kᵢ Bᵢ
    /// on a rigid shaft, the condensed shaft's on a flexible one.
    pub fn stiffness(&self) -> Matrix6<f64> {
        self.k
    }

    /// The support damping C = Σ Bᵢᵀ Cᵢ Bᵢ about the apex (Bᵢ the bearing's
    /// map, [`Support::on_shaft`] for a flexible shaft), with
    /// Cᵢ = c_r,i (I − a aᵀ) + c_a,i a aᵀ from `damping[i]` =
    /// (radial, axial) viscous damping of bearing i, N·s/m (bearings
    /// without an entry: none).
    pub fn damping(&self, damping: &[(f64, f64)]) -> Matrix6<f64> {
        let aat = self.axis * self.axis.transpose();
        self.maps
            .iter()
            .zip(damping)
            .map(|(bi, &(cr, ca))| {
                let ci = (Matrix3::identity() - aat) * cr + aat * ca;
                bi.transpose() * ci * bi
            })
            .sum()
    }

    /// Orthonormal basis (columns) of the five directions the bearings
    /// hold, as [u; θ]: translations along e₁, e₂, a, rotations about e₁,
    /// e₂ (e₁, e₂ ⊥ a).
    pub fn basis(&self) -> Matrix6x5<f64> {
        self.held
    }

    /// The bearings, in the order given.
    pub fn bearings(&self) -> &[Bearing] {
        &self.bearings
    }

    /// The force each bearing exerts on the member moving at velocity `v`
    /// ([u̇; θ̇]) with `damping` as in [`Support::damping`], N.
    pub fn damping_reactions(&self, v: &Vector6<f64>, damping: &[(f64, f64)]) -> Vec<Vector3<f64>> {
        let aat = self.axis * self.axis.transpose();
        self.maps
            .iter()
            .enumerate()
            .map(|(i, bi)| {
                let (cr, ca) = damping.get(i).copied().unwrap_or((0.0, 0.0));
                let ci = (Matrix3::identity() - aat) * cr + aat * ca;
                -(ci * (bi * v))
            })
            .collect()
    }

    /// The bearing point of `b` relative to the apex, m.
    pub fn arm_of(&self, b: &Bearing) -> Vector3<f64> {
        self.arm(b)
    }

    /// The generalized load [F; (x − o) × F] of force `force` (N) applied
    /// at `point` (m, fixed frame).
    pub fn load(&self, force: Vector3<f64>, point: Vector3<f64>) -> Vector6<f64> {
        let m = (point - self.apex).cross(&force);
        Vector6::new(force.x, force.y, force.z, m.x, m.y, m.z)
    }

    /// The member's displacement under the generalized load `g` (the part
    /// about the shaft axis, the torque, is the shaft's, not the bearings').
    pub fn displacement(&self, g: &Vector6<f64>) -> Displacement {
        let q = &self.held;
        let kq = q.transpose() * self.stiffness() * q;
        // K_Q is positive definite by the checks of `new`.
        let y = kq
            .cholesky()
            .expect("support stiffness positive definite (checked in Support::new)")
            .solve(&(q.transpose() * g));
        let x = q * y;
        Displacement {
            translation: Vector3::new(x[0], x[1], x[2]),
            rotation: Vector3::new(x[3], x[4], x[5]),
        }
    }

    /// The force each bearing exerts on the member at displacement `d`, N.
    pub fn reactions(&self, d: &Displacement) -> Vec<Vector3<f64>> {
        let x = Vector6::new(
            d.translation.x,
            d.translation.y,
            d.translation.z,
            d.rotation.x,
            d.rotation.y,
            d.rotation.z,
        );
        self.bearings
            .iter()
            .zip(&self.maps)
            .map(|(b, bi)| -(self.bearing_matrix(b) * (bi * x)))
            .collect()
    }

    /// The torque about the shaft axis that the shaft must carry for the
    /// load `g` to be in equilibrium, N·m (the bearings carry none).
    pub fn shaft_torque(&self, g: &Vector6<f64>) -> f64 {
        -self.axis.dot(&Vector3::new(g[3], g[4], g[5]))
    }

    /// Residual of the member's equilibrium under load `g`, the bearings'
    /// reactions at `d` and the shaft torque: force (N) and moment about
    /// the apex (N·m).
    pub fn residual(&self, g: &Vector6<f64>, d: &Displacement) -> (Vector3<f64>, Vector3<f64>) {
        let mut f = Vector3::new(g[0], g[1], g[2]);
        let mut m = Vector3::new(g[3], g[4], g[5]) + self.axis * self.shaft_torque(g);
        for (b, r) in self.bearings.iter().zip(self.reactions(d)) {
            f += r;
            m += self.arm(b).cross(&r);
        }
        (f, m)
    }
}

#[cfg(test)]
impl Bearing {
    /// A bearing at `s` (m from the apex) of radial and axial stiffness
    /// `kr`, `ka` (N/m): the tests' shorthand.
    pub(crate) fn at(s: f64, kr: f64, ka: f64) -> Bearing {
        Bearing {
            axial_position_m: s,
            radial_stiffness_n_per_m: kr,
            axial_stiffness_n_per_m: ka,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn z_shaft(bearings: &[Bearing]) -> Support {
        Support::new("pinion.bearings", Vector3::z(), Vector3::zeros(), bearings).unwrap()
    }

    /// Relative size of the equilibrium residual.
    fn balance(s: &Support, g: &Vector6<f64>) -> f64 {
        let d = s.displacement(g);
        let (f, m) = s.residual(g, &d);
        let scale = Vector3::new(g[0], g[1], g[2]).norm();
        let arm = s
            .bearings
            .iter()
            .fold(0.0_f64, |a, b| a.max(b.axial_position_m.abs()));
        (f.norm() / scale).max(m.norm() / (scale * arm))
    }

    #[test]
    fn straddle_mounted_shaft_reactions_follow_the_lever_rule() {
        // Bearings at 0 and L, a radial load F at c between them: reactions
        // F (L − c)/L and F c/L whatever the (unequal) stiffnesses.
        let (l, c, f) = (0.2, 0.05, 1.0e4);
        let s = z_shaft(&[Bearing::at(0.0, 3e8, 1e8), Bearing::at(l, 7e8, 0.0)]);
        let g = s.load(Vector3::new(f, 0.0, 0.0), Vector3::new(0.04, 0.0, c));
        let r = s.reactions(&s.displacement(&g));
        assert!((r[0].x + f * (l - c) / l).abs() < 1e-9 * f, "{r:?}");
        assert!((r[1].x + f * c / l).abs() < 1e-9 * f, "{r:?}");
    }

    #[test]
    fn overhung_pinion_reactions_follow_the_lever_rule() {
        // Load at −c outside the bearings at 0 and L: near bearing carries
        // F (L + c)/L, the far one −F c/L.
        let (l, c, f) = (0.12, 0.05, 2.0e4);
        let s = z_shaft(&[Bearing::at(0.0, 5e8, 2e8), Bearing::at(l, 5e8, 0.0)]);
        let g = s.load(Vector3::new(0.0, f, 0.0), Vector3::new(0.0, 0.0, -c));
        let r = s.reactions(&s.displacement(&g));
        assert!((r[0].y + f * (l + c) / l).abs() < 1e-9 * f, "{r:?}");
        assert!((r[1].y - f * c / l).abs() < 1e-9 * f, "{r:?}");
    }

    #[test]
    fn axial_load_at_a_radius_goes_to_the_locating_bearing_with_a_radial_couple() {
        // Axial force F at radius ρ (x = ρ): the locating bearing takes −F
        // axially; the moment F ρ is a radial couple ±F ρ / L.
        let (l, rho, f) = (0.15, 0.06, 5.0e3);
        let s = z_shaft(&[Bearing::at(0.0, 4e8, 3e8), Bearing::at(l, 4e8, 0.0)]);
        let g = s.load(Vector3::new(0.0, 0.0, f), Vector3::new(rho, 0.0, 0.0));
        let r = s.reactions(&s.displacement(&g));
        assert!(
            (r[0].z + f).abs() < 1e-9 * f && r[1].z.abs() < 1e-9 * f,
            "{r:?}"
        );
        assert!((r[0].x + r[1].x).abs() < 1e-9 * f, "{r:?}");
        assert!((r[1].x.abs() - f * rho / l).abs() < 1e-9 * f, "{r:?}");
    }

    #[test]
    fn equal_bearings_symmetric_about_the_load_translate_without_tilt() {
        let (l, k, f) = (0.2, 6e8, 1.0e4);
        let s = z_shaft(&[Bearing::at(-l / 2.0, k, k), Bearing::at(l / 2.0, k, 0.0)]);
        let d = s.displacement(&s.load(Vector3::new(f, 0.0, 0.0), Vector3::zeros()));
        assert!((d.translation.x - f / (2.0 * k)).abs() < 1e-12 * f / k);
        assert!(d.rotation.norm() < 1e-12 * f / (k * l));
    }

    #[test]
    fn spiral_bevel_mesh_force_is_balanced_within_1e_9_on_a_skew_shaft() {
        // A shaft along a skew axis with three bearings (a statically
        // indeterminate support), forces of every direction at points off
        // the axis: forces and moments (but the shaft torque) balance.
        let axis = Vector3::new(0.3, -0.5, 0.81);
        let apex = Vector3::new(0.01, -0.02, 0.005);
        let s = Support::new(
            "wheel.bearings",
            axis,
            apex,
            &[
                Bearing::at(0.05, 8e8, 0.0),
                Bearing::at(0.11, 3e8, 5e8),
                Bearing::at(0.19, 9e8, 1e8),
            ],
        )
        .unwrap();
        for k in 0..20 {
            let t = k as f64;
            let force = Vector3::new((t * 1.3).sin(), (t * 0.7).cos(), 0.4 - 0.05 * t) * 3e4;
            let point = apex + Vector3::new(0.06 * (t * 0.9).cos(), 0.05 * t.sin(), 0.03);
            let g = s.load(force, point);
            assert!(balance(&s, &g) < 1e-9, "load {k}: {}", balance(&s, &g));
        }
    }

    fn one_segment(
        from: f64,
        to: f64,
        d: f64,
        seat: f64,
        e: f64,
    ) -> super::super::flexible_shaft::Shaft {
        super::super::flexible_shaft::Shaft {
            segments: vec![super::super::flexible_shaft::ShaftSegment {
                from_m: from,
                to_m: to,
                outer_diameter_m: d,
                inner_diameter_m: 0.0,
            }],
            seat_m: seat,
            youngs_modulus_pa: e,
            poisson_ratio: 0.3,
        }
    }

    /// A shaft a million times stiffer than steel gives the rigid
    /// support: the same stiffness about the apex and the same bearing
    /// maps (skew axis, apex off the origin, three bearings).
    #[test]
    fn very_stiff_flexible_shaft_gives_the_rigid_support() {
        let axis = Vector3::new(0.3, -0.5, 0.81);
        let apex = Vector3::new(0.01, -0.02, 0.005);
        let bs = [
            Bearing::at(0.05, 8e8, 0.0),
            Bearing::at(0.11, 3e8, 5e8),
            Bearing::at(0.19, 9e8, 1e8),
        ];
        let rigid = Support::new("wheel.bearings", axis, apex, &bs).unwrap();
        let shaft = one_segment(0.03, 0.2, 0.06, 0.08, 206e9 * 1e6);
        let flex = Support::on_shaft("wheel.bearings", axis, apex, &bs, &shaft).unwrap();
        let q = rigid.basis();
        let (kr, kf) = (
            q.transpose() * rigid.stiffness() * q,
            q.transpose() * flex.stiffness() * q,
        );
        assert!((kr - kf).norm() < 1e-5 * kr.norm(), "{kr} {kf}");
        for (a, b) in rigid.maps.iter().zip(&flex.maps) {
            assert!((a - b).norm() < 1e-5 * a.norm(), "{a} {b}");
        }
    }

    /// On a steel shaft along a skew axis the load at the seat moves the
    /// seat by the simply supported Timoshenko beam's deflection on its
    /// springs (the transform to the apex and back is exact), and every
    /// load is balanced by the bearings' reactions.
    #[test]
    fn flexible_shaft_moves_the_seat_as_the_beam_and_balances_every_load() {
        let axis = Vector3::new(0.3, -0.5, 0.81);
        let apex = Vector3::new(0.01, -0.02, 0.005);
        let (l, d, p, k) = (0.2, 0.04, 5000.0, 4e8);
        let bs = [Bearing::at(0.05, k, 1e9), Bearing::at(0.05 + l, k, 0.0)];
        let shaft = one_segment(0.05, 0.05 + l, d, 0.05 + 0.5 * l, 206e9);
        let s = Support::on_shaft("pinion.bearings", axis, apex, &bs, &shaft).unwrap();
        let a = s.axis();
        let radial = a.cross(&Vector3::x()).normalize();
        let seat = apex + a * shaft.seat_m;
        let dsp = s.displacement(&s.load(radial * p, seat));
        let moved = dsp.translation + dsp.rotation.cross(&(a * shaft.seat_m));
        let sec = super::super::timoshenko::Section::round(d, 0.0, 206e9, 0.3);
        let exact = p * l.powi(3) / (48.0 * sec.youngs_modulus_pa * sec.inertia_m4)
            + p * l / (4.0 * sec.shear_coefficient * sec.shear_modulus_pa * sec.area_m2)
            + p / (2.0 * k);
        assert!(
            (moved.dot(&radial) - exact).abs() < 1e-8 * exact,
            "{} {exact}",
            moved.dot(&radial)
        );
        assert!((moved - radial * moved.dot(&radial)).norm() < 1e-8 * exact);
        for t in 0..10 {
            let t = t as f64;
            let force = Vector3::new((t * 1.3).sin(), (t * 0.7).cos(), 0.4 - 0.05 * t) * 3e4;
            let point = apex + Vector3::new(0.06 * (t * 0.9).cos(), 0.05 * t.sin(), 0.03);
            let g = s.load(force, point);
            assert!(balance(&s, &g) < 1e-9, "load {t}: {}", balance(&s, &g));
        }
    }

    #[test]
    fn support_stiffness_is_symmetric_and_singular_only_about_the_shaft_axis() {
        let s = z_shaft(&[Bearing::at(0.0, 3e8, 1e8), Bearing::at(0.2, 7e8, 0.0)]);
        let k = s.stiffness();
        assert!((k - k.transpose()).norm() < 1e-6 * k.norm());
        let turning = Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
        assert!((k * turning).norm() < 1e-9 * k.norm());
        let eig = k.symmetric_eigen().eigenvalues;
        let positive = eig.iter().filter(|&&e| e > 1e-9 * k.norm()).count();
        assert_eq!(positive, 5, "{eig}");
    }

    #[test]
    fn support_that_cannot_hold_tilt_or_axial_load_is_refused_naming_the_field() {
        let one = Support::new(
            "pinion.bearings",
            Vector3::z(),
            Vector3::zeros(),
            &[Bearing::at(0.0, 1e8, 1e8)],
        );
        assert_eq!(one.unwrap_err(), BearingError::Tilt(1));
        let same = Support::new(
            "pinion.bearings",
            Vector3::z(),
            Vector3::zeros(),
            &[Bearing::at(0.1, 1e8, 1e8), Bearing::at(0.1, 1e8, 0.0)],
        );
        assert_eq!(same.unwrap_err(), BearingError::Tilt(2));
        let floating = Support::new(
            "pinion.bearings",
            Vector3::z(),
            Vector3::zeros(),
            &[Bearing::at(0.0, 1e8, 0.0), Bearing::at(0.1, 1e8, 0.0)],
        );
        assert_eq!(floating.unwrap_err(), BearingError::Axial);
        let e = Support::new(
            "wheel.bearings",
            Vector3::z(),
            Vector3::zeros(),
            &[Bearing::at(0.0, -1e8, 1e8), Bearing::at(0.1, 1e8, 0.0)],
        )
        .unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("wheel.bearings[0].radial_stiffness_n_per_m")
                && msg.contains("-100000000"),
            "{msg}"
        );
    }
}
