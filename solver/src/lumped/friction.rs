//! Sliding friction in the 8-DOF model (seed 003's Eqs. (30), (32), (36)).
//!
//! Seed 003 adds to each member's translations the components of the
//! friction force F_f = μFₙ and to its torsion the moment F_f r_f, with
//! μ = μ₀ + μ_r R (R the effective roughness of the contact), but gives
//! neither the friction direction nor the arms r_f. Here both come from
//! our LTCA's load distribution at the operating torque: at every position
//! the slices' normal forces Fₛ, their unit sliding directions ûₛ and
//! friction levers (ℓ₁, ℓ₂)ₛ ([`crate::element::slices::friction_levers`]; the
//! friction pushes the pinion along −û and the wheel along +û) give the
//! friction per unit total normal force
//!
//! ```text
//! g = Σ Fₛ (D ûₛ, ℓ₁ₛ, −D ûₛ, −ℓ₂ₛ) / Σ Fₛ          (8 components)
//! f_friction = −μ max(Fₙ, 0) g(t)
//! ```
//!
//! ûₛ in the model's axes (X along the pinion axis, Y along the wheel axis,
//! Z = X × Y up to sign): its components on the pinion axis, the wheel axis
//! and their cross product, with the sign D of each axis chosen so that the
//! force-weighted flank normal maps onto the model's (a₁, a₂, a₃) (the
//! model takes its direction cosines from seed 004's formula, and the
//! angle between the two is reported). g is interpolated linearly between
//! the positions, periodic over the mesh cycle. The LTCA that gives the
//! load distribution runs without friction: k(t) and e(t) stay those of
//! the normal compliance.
//!
//! R: the composite roughness √(Ra₁² + Ra₂²) of the two flanks in µm (the
//! usual effective roughness of a contact; seed 003 does not say which).

use super::LumpedError;
use crate::element::slices::friction_direction;
use serde::Serialize;

/// Seed 003's μ = μ₀ + μ_r R with R = √(Ra_pinion² + Ra_wheel²) in µm.
pub fn seed003_coefficient(base: f64, per_um: f64, ra_um: [f64; 2]) -> f64 {
    base + per_um * ra_um[0].hypot(ra_um[1])
}

/// g(t) over one mesh cycle and the coefficient μ.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrictionExcitation {
    pub coefficient: f64,
    /// Sample times inside one period, increasing, s.
    pub time_s: Vec<f64>,
    /// g at each sample (m for the torsional entries, 1 for the others).
    pub per_unit_force: Vec<[f64; 8]>,
    pub period_s: f64,
}

impl FrictionExcitation {
    pub fn new(
        coefficient: f64,
        time_s: Vec<f64>,
        per_unit_force: Vec<[f64; 8]>,
        period_s: f64,
    ) -> Result<Self, LumpedError> {
        let ok = coefficient.is_finite()
            && coefficient >= 0.0
            && period_s > 0.0
            && !time_s.is_empty()
            && time_s.len() == per_unit_force.len()
            && time_s.windows(2).all(|w| w[1] > w[0])
            && time_s[0] >= 0.0
            && time_s[time_s.len() - 1] < period_s
            && per_unit_force.iter().flatten().all(|v| v.is_finite());
        if !ok {
            return Err(LumpedError::Input(format!(
                "friction: μ = {coefficient}, {} times, {} vectors, period {period_s} s: need μ ≥ 0, increasing times inside one period, one finite vector each",
                time_s.len(),
                per_unit_force.len()
            )));
        }
        Ok(Self {
            coefficient,
            time_s,
            per_unit_force,
            period_s,
        })
    }

    /// g(t), linear between the samples, periodic.
    pub fn at(&self, t: f64) -> [f64; 8] {
        let n = self.time_s.len();
        let s = t.rem_euclid(self.period_s);
        let k = self.time_s.partition_point(|x| *x <= s);
        let (i, j, t0, t1) = if k == 0 {
            (n - 1, 0, self.time_s[n - 1] - self.period_s, self.time_s[0])
        } else if k == n {
            (n - 1, 0, self.time_s[n - 1], self.time_s[0] + self.period_s)
        } else {
            (k - 1, k, self.time_s[k - 1], self.time_s[k])
        };
        let w = if t1 > t0 { (s - t0) / (t1 - t0) } else { 0.0 };
        std::array::from_fn(|c| {
            (1.0 - w) * self.per_unit_force[i][c] + w * self.per_unit_force[j][c]
        })
    }

    /// Mean of g over the samples.
    pub fn mean(&self) -> [f64; 8] {
        let n = self.per_unit_force.len() as f64;
        std::array::from_fn(|c| self.per_unit_force.iter().map(|g| g[c]).sum::<f64>() / n)
    }
}

/// One position's slices: normal force, unit sliding direction and flank
/// normal (both on the pinion axis, the wheel axis and their cross
/// product), friction levers (ℓ₁, ℓ₂).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SliceFriction {
    pub force_n: f64,
    pub direction: [f64; 3],
    pub normal: [f64; 3],
    pub levers_m: [f64; 2],
}

/// What [`per_unit_force`] finds.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionGeometry {
    /// g at each position.
    pub per_unit_force: Vec<[f64; 8]>,
    /// The force-weighted flank normal (unit, axes signed as the model's).
    pub normal: [f64; 3],
    /// Its angle to the model's direction cosines, deg.
    pub angle_deg: f64,
}

/// g at each position from its slices, the force-weighted flank normal
/// and its angle to the model's direction cosines `a`.
pub fn per_unit_force(
    positions: &[Vec<SliceFriction>],
    a: [f64; 3],
) -> Result<FrictionGeometry, LumpedError> {
    let mut mean_n = [0.0; 3];
    for s in positions.iter().flatten() {
        for (m, n) in mean_n.iter_mut().zip(s.normal) {
            *m += s.force_n * n;
        }
    }
    let sign: [f64; 3] = std::array::from_fn(|i| if mean_n[i] * a[i] < 0.0 { -1.0 } else { 1.0 });
    let mapped: [f64; 3] = std::array::from_fn(|i| sign[i] * mean_n[i]);
    let len = mapped.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len.is_nan() || len <= 0.0 {
        return Err(LumpedError::Input(
            "friction: the LTCA positions carry no normal force".into(),
        ));
    }
    let cos = (mapped.iter().zip(a).map(|(m, x)| m * x).sum::<f64>() / len).clamp(-1.0, 1.0);
    let g = positions
        .iter()
        .map(|sl| {
            let total: f64 = sl.iter().map(|s| s.force_n).sum();
            let mut g = [0.0; 8];
            if total > 0.0 {
                for s in sl {
                    let w = s.force_n / total;
                    for d in 0..3 {
                        g[d] += w * sign[d] * s.direction[d];
                        g[4 + d] -= w * sign[d] * s.direction[d];
                    }
                    g[3] += w * s.levers_m[0];
                    g[7] -= w * s.levers_m[1];
                }
            }
            g
        })
        .collect();
    Ok(FrictionGeometry {
        per_unit_force: g,
        normal: mapped.map(|m| m / len),
        angle_deg: cos.acos().to_degrees(),
    })
}

/// The friction data of one position: each loaded slice's force, sliding
/// direction and normal on the pinion axis, the wheel axis and their cross
/// product, and its friction levers (the loaded slice matched to the
/// geometry's by tooth pair and (ξ, η), which the LTCA copies from it).
/// Slices carry tooth 0's point and normal: pair j's are seen at pinion
/// angle φ + jτ, as the slicing does.
pub fn slice_friction(
    fp: &geometry::pair::FlankPair,
    phi: f64,
    tau: f64,
    geo: &[crate::element::slices::Slice],
    loaded: &[crate::ltca::SliceLoad],
) -> Vec<SliceFriction> {
    let (pf, wf) = (&fp.pinion.gen.frame, &fp.wheel.gen.frame);
    loaded
        .iter()
        .filter_map(|l| {
            let s = geo
                .iter()
                .find(|s| s.pair == l.pair && s.xi == l.xi && s.eta == l.eta)?;
            let target = phi + s.pair as f64 * tau;
            let a2 = pf.to_member(&wf.axis(), target);
            let ey = [a2[0], a2[1], a2[2]].map(|c| c / a2.norm());
            let ex = [0.0, 0.0, 1.0];
            let ez = [-ey[1], ey[0], 0.0];
            let zn = ez[0].hypot(ez[1]);
            let ez = ez.map(|c| c / zn);
            let on = |v: [f64; 3]| [ex, ey, ez].map(|e| e.iter().zip(v).map(|(a, b)| a * b).sum());
            let u = friction_direction(fp, s.pos, s.normal, target).unwrap_or([0.0; 3]);
            Some(SliceFriction {
                force_n: l.force_n,
                direction: on(u),
                normal: on(s.normal),
                levers_m: s.friction_lever,
            })
        })
        .collect()
}
