//! A flexible shaft: Timoshenko beam elements ([`super::timoshenko`])
//! along the member's axis between its segments' ends, its bearings and
//! the gear's seat, the bearings as springs to the ground (radial k_r on
//! both transverse translations, axial k_a), statically condensed onto the
//! seat node where the gear body (rigid) sits:
//!
//!   K_c = K_ss − K_sr K_rr⁻¹ K_rs,   x_r = −K_rr⁻¹ K_rs x_s,
//!
//! s the seat node's six degrees of freedom, r all others. K_c (6 × 6,
//! shaft frame: x along the axis) is singular about the axis alone (the
//! shaft turns; its torque is held by what drives it); the rows of x_r at
//! a bearing's node give that bearing's displacement per seat
//! displacement. The shaft is massless here (its mass belongs to the
//! member's, `[bearings] <member>_body`); nodal loads only, for which the
//! elements are exact, so no node is added between the named positions.

use super::support::Bearing;
use super::timoshenko::{element_stiffness, Section};
use nalgebra::{DMatrix, Matrix3x6, Matrix6};

/// A length of shaft of one round section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShaftSegment {
    /// Axial positions of its ends from the member's pitch apex, m
    /// (`from_m` < `to_m`).
    pub from_m: f64,
    pub to_m: f64,
    pub outer_diameter_m: f64,
    /// 0 for a solid shaft.
    pub inner_diameter_m: f64,
}

/// A member's shaft.
#[derive(Debug, Clone, PartialEq)]
pub struct Shaft {
    /// Contiguous segments in axial order.
    pub segments: Vec<ShaftSegment>,
    /// Where the gear body sits on the shaft (its node), m from the apex.
    pub seat_m: f64,
    pub youngs_modulus_pa: f64,
    pub poisson_ratio: f64,
}

/// A shaft that cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShaftError {
    #[error("{field} = {value}: {limit}")]
    Value {
        field: String,
        value: String,
        limit: String,
    },
    #[error("{field}: the shaft with its bearings is not held (its stiffness without the seat is singular); check that every bearing and the seat lie on the segments")]
    NotHeld { field: String },
}

/// The shaft condensed onto its seat.
#[derive(Debug, Clone)]
pub struct Condensed {
    /// K_c in the shaft frame (x along the axis), N/m, N, N·m.
    pub seat_stiffness: Matrix6<f64>,
    /// Each bearing's translation (shaft frame) per seat displacement
    /// [u; θ] (shaft frame), in the bearings' order.
    pub bearing_maps: Vec<Matrix3x6<f64>>,
}

fn value(field: String, v: f64, limit: &str) -> ShaftError {
    ShaftError::Value {
        field,
        value: format!("{v}"),
        limit: limit.into(),
    }
}

impl Shaft {
    /// The scene's `[bearings.<member>_shaft]` (mm) of the member's
    /// material, SI.
    pub fn of_scene(
        sh: &geometry::scene_bearings::ShaftMm,
        material: &geometry::Material,
    ) -> Shaft {
        Shaft {
            segments: sh
                .segments
                .iter()
                .map(|s| ShaftSegment {
                    from_m: s.from_mm * 1e-3,
                    to_m: s.to_mm * 1e-3,
                    outer_diameter_m: s.outer_diameter_mm * 1e-3,
                    inner_diameter_m: s.inner_diameter_mm * 1e-3,
                })
                .collect(),
            seat_m: sh.seat_mm * 1e-3,
            youngs_modulus_pa: material.youngs_modulus_pa,
            poisson_ratio: material.poisson_ratio,
        }
    }

    /// Segments contiguous and positive, diameters 0 ≤ inner < outer, the
    /// seat and every bearing on the shaft, the material physical.
    pub fn check(&self, field: &str, bearings: &[Bearing]) -> Result<(), ShaftError> {
        if self.segments.is_empty() {
            return Err(value(
                format!("{field}.segments"),
                0.0,
                "needs at least one segment",
            ));
        }
        for (i, s) in self.segments.iter().enumerate() {
            let f = |n: &str| format!("{field}.segments[{i}].{n}");
            if !(s.from_m.is_finite() && s.to_m.is_finite() && s.to_m > s.from_m) {
                return Err(value(
                    f("to_mm"),
                    s.to_m * 1e3,
                    "must be finite and beyond from_mm",
                ));
            }
            if !(s.outer_diameter_m.is_finite() && s.outer_diameter_m > 0.0) {
                return Err(value(
                    f("outer_diameter_mm"),
                    s.outer_diameter_m * 1e3,
                    "must be positive",
                ));
            }
            if !(s.inner_diameter_m >= 0.0 && s.inner_diameter_m < s.outer_diameter_m) {
                return Err(value(
                    f("inner_diameter_mm"),
                    s.inner_diameter_m * 1e3,
                    "must lie in [0, outer_diameter_mm)",
                ));
            }
            if i > 0 {
                let gap = s.from_m - self.segments[i - 1].to_m;
                if gap.abs() > 1e-9 {
                    return Err(value(
                        f("from_mm"),
                        s.from_m * 1e3,
                        "must equal the previous segment's to_mm (segments contiguous, in axial order)",
                    ));
                }
            }
        }
        let (lo, hi) = (
            self.segments[0].from_m,
            self.segments.last().expect("not empty").to_m,
        );
        let on = |x: f64| x >= lo - 1e-12 && x <= hi + 1e-12;
        if !on(self.seat_m) {
            return Err(value(
                format!("{field}.seat_mm"),
                self.seat_m * 1e3,
                "must lie on the shaft's segments",
            ));
        }
        for (i, b) in bearings.iter().enumerate() {
            if !on(b.axial_position_m) {
                return Err(value(
                    format!("{field}: bearing [{i}].axial_position_mm"),
                    b.axial_position_m * 1e3,
                    "must lie on the shaft's segments",
                ));
            }
        }
        if !(self.youngs_modulus_pa.is_finite() && self.youngs_modulus_pa > 0.0) {
            return Err(value(
                format!("{field}.youngs_modulus"),
                self.youngs_modulus_pa,
                "must be positive",
            ));
        }
        if !(self.poisson_ratio > -1.0 && self.poisson_ratio < 0.5) {
            return Err(value(
                format!("{field}.poisson_ratio"),
                self.poisson_ratio,
                "must lie in (−1, 0.5)",
            ));
        }
        Ok(())
    }

    /// The nodes' axial positions: segment ends, bearings and seat, sorted,
    /// those closer than 1 µm merged.
    pub(crate) fn nodes(&self, bearings: &[Bearing]) -> Vec<f64> {
        let mut x: Vec<f64> = self
            .segments
            .iter()
            .flat_map(|s| [s.from_m, s.to_m])
            .chain(bearings.iter().map(|b| b.axial_position_m))
            .chain([self.seat_m])
            .collect();
        x.sort_by(f64::total_cmp);
        x.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        x
    }

    pub(crate) fn node_of(nodes: &[f64], at: f64) -> usize {
        nodes
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - at).abs().total_cmp(&(b.1 - at).abs()))
            .map(|(i, _)| i)
            .expect("nodes not empty")
    }

    /// The shaft with its bearings condensed onto the seat (checked first).
    pub fn condense(&self, field: &str, bearings: &[Bearing]) -> Result<Condensed, ShaftError> {
        self.check(field, bearings)?;
        let nodes = self.nodes(bearings);
        let n = 6 * nodes.len();
        let mut k = DMatrix::<f64>::zeros(n, n);
        for (e, w) in nodes.windows(2).enumerate() {
            let mid = 0.5 * (w[0] + w[1]);
            let seg = self
                .segments
                .iter()
                .find(|s| mid >= s.from_m && mid <= s.to_m)
                .expect("checked: the nodes lie on contiguous segments");
            let sec = Section::round(
                seg.outer_diameter_m,
                seg.inner_diameter_m,
                self.youngs_modulus_pa,
                self.poisson_ratio,
            );
            let ke = element_stiffness(&sec, w[1] - w[0]);
            for i in 0..12 {
                for j in 0..12 {
                    k[(6 * e + i, 6 * e + j)] += ke[(i, j)];
                }
            }
        }
        let bearing_nodes: Vec<usize> = bearings
            .iter()
            .map(|b| Self::node_of(&nodes, b.axial_position_m))
            .collect();
        for (b, &i) in bearings.iter().zip(&bearing_nodes) {
            k[(6 * i, 6 * i)] += b.axial_stiffness_n_per_m;
            k[(6 * i + 1, 6 * i + 1)] += b.radial_stiffness_n_per_m;
            k[(6 * i + 2, 6 * i + 2)] += b.radial_stiffness_n_per_m;
        }
        let seat = Self::node_of(&nodes, self.seat_m);
        let rest: Vec<usize> = (0..n).filter(|d| d / 6 != seat).collect();
        let s: Vec<usize> = (6 * seat..6 * seat + 6).collect();
        let krr = k.select_rows(&rest).select_columns(&rest);
        let krs = k.select_rows(&rest).select_columns(&s);
        let kss = k.select_rows(&s).select_columns(&s);
        let chol = krr.cholesky().ok_or_else(|| ShaftError::NotHeld {
            field: field.into(),
        })?;
        let x = chol.solve(&krs);
        let kc = kss - krs.transpose() * &x;
        let seat_stiffness = Matrix6::from_fn(|i, j| 0.5 * (kc[(i, j)] + kc[(j, i)]));
        let bearing_maps = bearing_nodes
            .iter()
            .map(|&node| {
                Matrix3x6::from_fn(|i, j| {
                    if node == seat {
                        // A bearing at the seat moves with it.
                        f64::from(u8::from(i == j))
                    } else {
                        let row = rest
                            .iter()
                            .position(|&d| d == 6 * node + i)
                            .expect("node in rest");
                        -x[(row, j)]
                    }
                })
            })
            .collect();
        Ok(Condensed {
            seat_stiffness,
            bearing_maps,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix5, Vector6};

    fn shaft(from: f64, to: f64, d: f64, seat: f64) -> Shaft {
        Shaft {
            segments: vec![ShaftSegment {
                from_m: from,
                to_m: to,
                outer_diameter_m: d,
                inner_diameter_m: 0.0,
            }],
            seat_m: seat,
            youngs_modulus_pa: 206e9,
            poisson_ratio: 0.3,
        }
    }

    /// The seat's transverse displacement under a transverse force P there
    /// (the rotations, axial and torsion free to follow): 1 / (the
    /// condensed stiffness's Schur complement onto u_y).
    fn deflection_under(c: &Condensed, p: f64) -> f64 {
        // Solve on the five held directions (all but θ_x).
        let held = [0usize, 1, 2, 4, 5];
        let k5 = Matrix5::from_fn(|i, j| c.seat_stiffness[(held[i], held[j])]);
        let mut f = nalgebra::Vector5::zeros();
        f[1] = p;
        k5.cholesky().unwrap().solve(&f)[1]
    }

    /// A shaft simply supported on two bearings a span L apart, the gear at
    /// mid-span: Timoshenko's PL³/(48EI) + PL/(4κGA) plus each bearing's
    /// P/(2k_r).
    #[test]
    fn seat_at_mid_span_deflects_as_a_simply_supported_timoshenko_beam_on_springs() {
        let (l, d, p, kr) = (0.2, 0.04, 5000.0, 4e8);
        let sh = shaft(0.0, l, d, 0.5 * l);
        let c = sh
            .condense(
                "pinion_shaft",
                &[Bearing::at(0.0, kr, 1e9), Bearing::at(l, kr, 0.0)],
            )
            .unwrap();
        let s = Section::round(d, 0.0, 206e9, 0.3);
        let exact = p * l.powi(3) / (48.0 * s.youngs_modulus_pa * s.inertia_m4)
            + p * l / (4.0 * s.shear_coefficient * s.shear_modulus_pa * s.area_m2)
            + p / (2.0 * kr);
        let got = deflection_under(&c, p);
        assert!(
            (got - exact).abs() <= 1e-9 * exact,
            "{got:e} against {exact:e}"
        );
    }

    /// An overhung gear a beyond the outer of two bearings L apart (rigid
    /// bearings): δ = P a²(L + a)/(3EI) + P a (L + a)/(L κ G A).
    #[test]
    fn overhung_seat_deflects_as_the_closed_form_with_shear() {
        let (l, a, d, p) = (0.12, 0.06, 0.05, 8000.0);
        let sh = shaft(-a, l, d, -a);
        let rigid = 1e16;
        let c = sh
            .condense(
                "pinion_shaft",
                &[Bearing::at(0.0, rigid, rigid), Bearing::at(l, rigid, 0.0)],
            )
            .unwrap();
        let s = Section::round(d, 0.0, 206e9, 0.3);
        let exact = p * a * a * (l + a) / (3.0 * s.youngs_modulus_pa * s.inertia_m4)
            + p * a * (l + a) / (l * s.shear_coefficient * s.shear_modulus_pa * s.area_m2);
        let got = deflection_under(&c, p);
        assert!(
            (got - exact).abs() <= 1e-6 * exact,
            "{got:e} against {exact:e}"
        );
    }

    /// The bearings' reactions (spring force at their displaced node)
    /// balance the seat load; for a determinate pair they follow the lever
    /// rule, P b/L and P a/L.
    #[test]
    fn bearing_maps_give_lever_rule_reactions() {
        let (l, p, kr) = (0.3, 1000.0, 3e8);
        let sh = shaft(0.0, l, 0.05, 0.1);
        let bs = [Bearing::at(0.0, kr, 1e9), Bearing::at(l, kr, 0.0)];
        let c = sh.condense("wheel_shaft", &bs).unwrap();
        let held = [0usize, 1, 2, 4, 5];
        let k5 = Matrix5::from_fn(|i, j| c.seat_stiffness[(held[i], held[j])]);
        let mut f = nalgebra::Vector5::zeros();
        f[1] = p;
        let y = k5.cholesky().unwrap().solve(&f);
        let mut x = Vector6::zeros();
        for (i, &h) in held.iter().enumerate() {
            x[h] = y[i];
        }
        let r: Vec<f64> = c.bearing_maps.iter().map(|m| -kr * (m * x)[1]).collect();
        assert!((r[0] + p * (l - 0.1) / l).abs() < 1e-6 * p, "{r:?}");
        assert!((r[1] + p * 0.1 / l).abs() < 1e-6 * p, "{r:?}");
    }

    #[test]
    fn shaft_errors_name_the_field() {
        let mut sh = shaft(0.0, 0.2, 0.04, 0.3);
        let bs = [Bearing::at(0.0, 1e8, 1e8), Bearing::at(0.2, 1e8, 0.0)];
        assert!(
            matches!(sh.condense("pinion_shaft", &bs), Err(ShaftError::Value { field, .. }) if field == "pinion_shaft.seat_mm")
        );
        sh.seat_m = 0.1;
        sh.segments[0].inner_diameter_m = 0.05;
        assert!(
            matches!(sh.condense("pinion_shaft", &bs), Err(ShaftError::Value { field, .. }) if field.ends_with("inner_diameter_mm"))
        );
    }
}
