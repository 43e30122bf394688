//! The parametric gearbox housing of `[bearings.gearbox.housing]` as
//! boxes, independent of the CAD kernel: a wall per bearing and a floor
//! under both shafts, placed around the gears' envelopes.
//!
//! Housing frame: X along the pinion's axis a₁, Z = a₁ × a₂ / |a₁ × a₂|
//! (normal to both axes, "up"), Y = Z × X; origin at the pitch apex, which
//! both axes pass through. Both shafts therefore run level at Z = 0.
//!
//! - A bearing of member m at axial position s gets a wall normal to a_m:
//!   axially s ± w/2, laterally (along Z × a_m) ± (r_b + rim), from the
//!   floor's top up to r_b + rim, with a bore of radius r_b about the axis.
//! - A member's walls are joined by a rib under its shaft, `wall` thick
//!   in the plane of the shaft and Z, from the floor to half a rim below
//!   the bores.
//! - The floor's top lies `clearance` below the lowest envelope (the
//!   largest radius of any blank or shaft, since both axes are level); it
//!   is `floor` thick and spans the walls' footprints. Its feet are the
//!   squares of side `foot` at the four corners of its bottom face.
//!
//! Envelopes: each blank of the scene as the body of revolution of its
//! half-section polygon (the teeth lie inside it), each flexible shaft as
//! its segments' cylinders. The gap of a point to an envelope is its signed
//! distance to the polygon in the point's own axial half-plane (exact for a
//! body of revolution; negative inside). A wall's own shaft is not checked
//! against it (the bearing fills the bore); every other pair is.

use crate::error::InputError;
use crate::limits::bearings as lim;
use crate::scene_bearings::{BearingMm, HousingMm, ShaftMm};
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use std::path::Path;

/// A body of revolution the housing must clear.
#[derive(Debug, Clone, Serialize)]
pub struct Envelope {
    /// 0 pinion, 1 wheel.
    pub member: usize,
    /// What it is (`pinion standard blank`, `wheel shaft`), for refusals.
    pub name: String,
    /// Whether it is the member's shaft (walls of the member do not
    /// check it).
    pub shaft: bool,
    /// Half-section polygon (z along the member's axis from the apex, ρ),
    /// m.
    pub polygon: Vec<[f64; 2]>,
}

/// A box in the housing frame's rotated copy: its centre and axes in the
/// assembly (fixed) frame, half extents along them, m.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct HousingBox {
    pub centre: [f64; 3],
    /// Unit axes (columns): along the shaft (walls) or X (floor), lateral,
    /// up.
    pub axes: [[f64; 3]; 3],
    pub half: [f64; 3],
}

impl HousingBox {
    fn axis(&self, k: usize) -> Vector3<f64> {
        Vector3::from(self.axes[k])
    }

    /// The point at local coordinates `l` (along the axes from the centre).
    pub fn point(&self, l: [f64; 3]) -> Vector3<f64> {
        Vector3::from(self.centre) + (0..3).map(|k| self.axis(k) * l[k]).sum::<Vector3<f64>>()
    }

    /// Local coordinates of `p`.
    pub fn local(&self, p: &Vector3<f64>) -> [f64; 3] {
        let d = p - Vector3::from(self.centre);
        std::array::from_fn(|k| d.dot(&self.axis(k)))
    }

    /// Whether `p` lies in the box (within `tol`).
    pub fn contains(&self, p: &Vector3<f64>, tol: f64) -> bool {
        let l = self.local(p);
        (0..3).all(|k| l[k].abs() <= self.half[k] + tol)
    }
}

/// One bearing's wall with its bore.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Wall {
    pub member: usize,
    /// The bearing's index in `[bearings] <member>`.
    pub bearing: usize,
    /// The bearing's centre (the seat's reference point), m.
    pub seat: [f64; 3],
    /// The member's axis.
    pub axis: [f64; 3],
    pub bore_radius: f64,
    pub solid: HousingBox,
}

impl Wall {
    /// Whether `p` is on the bore's surface (radius within `tol` of the
    /// bore's, axially within the wall).
    pub fn on_bore(&self, p: &Vector3<f64>, tol: f64) -> bool {
        let a = Vector3::from(self.axis);
        let d = p - Vector3::from(self.seat);
        let t = d.dot(&a);
        let rho = (d - a * t).norm();
        (rho - self.bore_radius).abs() <= tol && t.abs() <= self.solid.half[0] + tol
    }
}

/// A member's rib: a plate under its shaft in the plane of the shaft and
/// Z, joining its walls.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Rib {
    pub member: usize,
    pub solid: HousingBox,
}

/// The housing's boxes, where they are, and how close they come to the
/// envelopes.
#[derive(Debug, Clone, Serialize)]
pub struct HousingLayout {
    /// Housing frame (columns X, Y, Z) in the assembly frame.
    pub frame: [[f64; 3]; 3],
    pub walls: Vec<Wall>,
    /// One per member with two walls or more.
    pub ribs: Vec<Rib>,
    pub floor: HousingBox,
    /// Side of the clamped feet, m.
    pub foot: f64,
    /// Least gap from housing to an envelope at the sampled points, m, and
    /// what it is between.
    pub least_gap: f64,
    pub least_gap_between: String,
    /// Spacing of the sampled points on the boxes' faces, m.
    pub sample_spacing: f64,
}

impl HousingLayout {
    /// Whether `p` (on the floor's bottom face) is on a foot.
    pub fn on_foot(&self, p: &Vector3<f64>, tol: f64) -> bool {
        let l = self.floor.local(p);
        let h = self.floor.half;
        (l[2] + h[2]).abs() <= tol
            && (0..2).all(|k| l[k].abs() >= h[k] - self.foot - tol && l[k].abs() <= h[k] + tol)
    }
}

/// Signed distance of (z, ρ) to a simple polygon: negative inside.
pub fn polygon_distance(poly: &[[f64; 2]], q: [f64; 2]) -> f64 {
    let n = poly.len();
    let mut d2 = f64::INFINITY;
    let mut inside = false;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        let ab = [b[0] - a[0], b[1] - a[1]];
        let aq = [q[0] - a[0], q[1] - a[1]];
        let len2 = ab[0] * ab[0] + ab[1] * ab[1];
        let t = if len2 > 0.0 {
            ((aq[0] * ab[0] + aq[1] * ab[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let e = [aq[0] - t * ab[0], aq[1] - t * ab[1]];
        d2 = d2.min(e[0] * e[0] + e[1] * e[1]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if q[0] < x {
                inside = !inside;
            }
        }
    }
    if inside {
        -d2.sqrt()
    } else {
        d2.sqrt()
    }
}

/// A shaft's envelope: its segments' outer cylinders as one polygon.
pub fn shaft_polygon(shaft: &ShaftMm) -> Vec<[f64; 2]> {
    let mut top: Vec<[f64; 2]> = Vec::new();
    for s in &shaft.segments {
        let r = 0.5e-3 * s.outer_diameter_mm;
        top.push([s.from_mm * 1e-3, r]);
        top.push([s.to_mm * 1e-3, r]);
    }
    let first = shaft.segments.first().map_or(0.0, |s| s.from_mm * 1e-3);
    let last = shaft.segments.last().map_or(0.0, |s| s.to_mm * 1e-3);
    // Counter-clockwise in (z, ρ): along the axis, then back over the top.
    let mut p = vec![[first, 0.0], [last, 0.0]];
    p.extend(top.into_iter().rev());
    p
}

/// Outer radius of `shaft` at axial position `z_mm`, m (the larger one at
/// a shoulder).
fn shaft_radius_at(shaft: &ShaftMm, z_mm: f64) -> Option<f64> {
    shaft
        .segments
        .iter()
        .filter(|s| z_mm >= s.from_mm && z_mm <= s.to_mm)
        .map(|s| 0.5e-3 * s.outer_diameter_mm)
        .reduce(f64::max)
}

/// The housing around `envelopes` for members with axes `axes` (assembly
/// frame, through the origin), bearings `bearings` and shafts `shafts`;
/// refusals name the scene's fields (`path` is the scene file).
pub fn layout(
    path: &Path,
    h: &HousingMm,
    axes: [Vector3<f64>; 2],
    bearings: [&[BearingMm]; 2],
    shafts: [Option<&ShaftMm>; 2],
    envelopes: &[Envelope],
) -> Result<HousingLayout, InputError> {
    h.check(path)?;
    let names = ["pinion", "wheel"];
    let a1 = axes[0].normalize();
    let up = a1.cross(&axes[1]);
    if up.norm() < 1e-6 {
        return Err(lim::HOUSING_FITS.refuse(
            path,
            "bearings.gearbox.housing",
            "parallel axes".into(),
            "the housing needs the members' axes at an angle".into(),
        ));
    }
    let z = up.normalize();
    let y = z.cross(&a1);
    let frame = Matrix3::from_columns(&[a1, y, z]);
    let col = |v: Vector3<f64>| [v.x, v.y, v.z];
    let rim = h.rim_mm * 1e-3;
    let wall = h.wall_mm * 1e-3;
    let clearance = h.clearance_mm * 1e-3;
    let lowest = envelopes
        .iter()
        .flat_map(|e| e.polygon.iter().map(|p| p[1]))
        .fold(0.0, f64::max);
    let floor_top = -(lowest + clearance);

    let mut walls = Vec::new();
    for m in 0..2 {
        let a = axes[m].normalize();
        let lateral = z.cross(&a);
        let bore = 0.5e-3 * [h.pinion_bore_diameter_mm, h.wheel_bore_diameter_mm][m];
        for (i, b) in bearings[m].iter().enumerate() {
            if let Some(r) = shafts[m].and_then(|s| shaft_radius_at(s, b.axial_position_mm)) {
                if bore <= r {
                    return Err(lim::HOUSING_FITS.refuse(
                        path,
                        &format!("bearings.gearbox.housing.{}_bore_diameter_mm", names[m]),
                        format!("{} mm", 2e3 * bore),
                        format!(
                            "must exceed the {} shaft's diameter at bearing {i}, {} mm",
                            names[m],
                            2e3 * r
                        ),
                    ));
                }
            }
            let s = b.axial_position_mm * 1e-3;
            let top = bore + rim;
            let centre = a * s + z * (0.5 * (top + floor_top));
            walls.push(Wall {
                member: m,
                bearing: i,
                seat: col(a * s),
                axis: col(a),
                bore_radius: bore,
                solid: HousingBox {
                    centre: col(centre),
                    axes: [col(a), col(lateral), col(z)],
                    half: [0.5 * wall, top, 0.5 * (top - floor_top)],
                },
            });
        }
    }
    // A rib per member under its shaft, from its first wall to its last,
    // tying them together along the shaft (without it a wall bends out of
    // its plane under the axial bearing's load), its top half a rim below
    // the bores.
    let mut ribs = Vec::new();
    for (m, axis) in axes.iter().enumerate() {
        let mine: Vec<&Wall> = walls.iter().filter(|w| w.member == m).collect();
        if mine.len() < 2 {
            continue;
        }
        let a = axis.normalize();
        let lateral = z.cross(&a);
        let t: Vec<f64> = mine.iter().map(|w| Vector3::from(w.seat).dot(&a)).collect();
        let (t0, t1) = (
            t.iter().copied().fold(f64::INFINITY, f64::min),
            t.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        );
        let top = -(mine[0].bore_radius + 0.5 * rim);
        ribs.push(Rib {
            member: m,
            solid: HousingBox {
                centre: col(a * (0.5 * (t0 + t1)) + z * (0.5 * (top + floor_top))),
                axes: [col(a), col(lateral), col(z)],
                half: [0.5 * (t1 - t0), 0.5 * wall, 0.5 * (top - floor_top)],
            },
        });
    }
    // The floor under the walls' footprints.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for w in &walls {
        for sa in [-1.0, 1.0] {
            for sl in [-1.0, 1.0] {
                let p = w
                    .solid
                    .point([sa * w.solid.half[0], sl * w.solid.half[1], 0.0]);
                let hp = frame.transpose() * p;
                for k in 0..2 {
                    lo[k] = lo[k].min(hp[k]);
                    hi[k] = hi[k].max(hp[k]);
                }
            }
        }
    }
    let floor_t = h.floor_mm * 1e-3;
    let floor_centre = frame
        * Vector3::new(
            0.5 * (lo[0] + hi[0]),
            0.5 * (lo[1] + hi[1]),
            floor_top - 0.5 * floor_t,
        );
    let floor = HousingBox {
        centre: col(floor_centre),
        axes: [col(a1), col(y), col(z)],
        half: [0.5 * (hi[0] - lo[0]), 0.5 * (hi[1] - lo[1]), 0.5 * floor_t],
    };
    let foot = h.foot_mm * 1e-3;
    if 2.0 * foot > (hi[0] - lo[0]).min(hi[1] - lo[1]) {
        return Err(lim::HOUSING_FITS.refuse(
            path,
            "bearings.gearbox.housing.foot_mm",
            format!("{} mm", h.foot_mm),
            format!(
                "two feet must fit along the floor's shorter side, {:.1} mm",
                1e3 * (hi[0] - lo[0]).min(hi[1] - lo[1])
            ),
        ));
    }

    // Clearance at points sampled on every face.
    let spacing = (0.25 * clearance).min(2e-3);
    let mut least = (f64::INFINITY, String::new());
    let mut boxes: Vec<(Option<&Wall>, &HousingBox, String)> = walls
        .iter()
        .map(|w| {
            (
                Some(w),
                &w.solid,
                format!("the wall of bearings.{}[{}]", names[w.member], w.bearing),
            )
        })
        .collect();
    for r in &ribs {
        boxes.push((None, &r.solid, format!("the {} rib", names[r.member])));
    }
    boxes.push((None, &floor, "the floor".into()));
    for (w, b, what) in boxes {
        for p in face_samples(b, spacing) {
            if let Some(w) = w {
                let a = Vector3::from(w.axis);
                let d = p - Vector3::from(w.seat);
                if (d - a * d.dot(&a)).norm() < w.bore_radius {
                    continue;
                }
            }
            for e in envelopes {
                if e.shaft && w.is_some_and(|w| w.member == e.member) {
                    continue;
                }
                let a = axes[e.member].normalize();
                let t = p.dot(&a);
                let rho = (p - a * t).norm();
                let gap = polygon_distance(&e.polygon, [t, rho]);
                if gap < least.0 {
                    least = (gap, format!("{what} and the {}", e.name));
                }
            }
        }
    }
    let tolerance = spacing * std::f64::consts::FRAC_1_SQRT_2;
    if least.0 < clearance - tolerance {
        return Err(lim::HOUSING_FITS.refuse(
            path,
            "bearings.gearbox.housing",
            format!("{}: {:.2} mm apart", least.1, 1e3 * least.0),
            format!(
                "the housing keeps clearance_mm = {} mm from every gear blank and shaft (move the bearings, or change wall_mm, rim_mm or the bores)",
                h.clearance_mm
            ),
        ));
    }
    Ok(HousingLayout {
        frame: [col(a1), col(y), col(z)],
        walls,
        ribs,
        floor,
        foot,
        least_gap: least.0,
        least_gap_between: least.1,
        sample_spacing: spacing,
    })
}

/// Points on the six faces of `b`, no farther apart than `spacing`.
fn face_samples(b: &HousingBox, spacing: f64) -> Vec<Vector3<f64>> {
    let n: [usize; 3] =
        std::array::from_fn(|k| ((2.0 * b.half[k] / spacing).ceil() as usize).max(1));
    let at = |k: usize, i: usize| -b.half[k] + 2.0 * b.half[k] * i as f64 / n[k] as f64;
    let mut out = Vec::new();
    for k in 0..3 {
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        for side in [-1.0, 1.0] {
            for i in 0..=n[u] {
                for j in 0..=n[v] {
                    let mut l = [0.0; 3];
                    l[k] = side * b.half[k];
                    l[u] = at(u, i);
                    l[v] = at(v, j);
                    out.push(b.point(l));
                }
            }
        }
    }
    out
}

/// The text the housing file's input hash is taken of: the settings, the
/// layout and the range its modes are checked over (the gearbox's
/// `modes_up_to_hz`), JSON; not the damping, which the file does not hold.
pub fn config_json(h: &HousingMm, l: &HousingLayout, check_up_to_hz: f64) -> String {
    // The damping acts in the solver only: not part of the file.
    let h = HousingMm {
        damping_ratio: 0.0,
        ..*h
    };
    serde_json::json!({ "housing": h, "layout": l, "check_up_to_hz": check_up_to_hz }).to_string()
}

/// The housing of `scene` (None without `[bearings.gearbox.housing]`):
/// the envelopes are the scene's blanks of both members and its flexible
/// shafts.
pub fn of_scene(
    scene: &crate::scene::LoadedScene,
    g: &crate::pair::PairGeometry,
) -> Result<Option<HousingLayout>, InputError> {
    use crate::design::Member;
    use crate::gear_body::{blank_shape, BlankDimensions};
    let sc = &scene.scene;
    let Some(b) = sc.bearings.as_ref() else {
        return Ok(None);
    };
    let Some(h) = b.gearbox.as_ref().and_then(|gb| gb.housing.as_ref()) else {
        return Ok(None);
    };
    let dims = BlankDimensions::resolve(&sc.blank_dimensions, &g.data);
    let mut envelopes = Vec::new();
    for (m, member, blanks) in [
        (0, Member::Pinion, &sc.blanks.pinion),
        (1, Member::Wheel, &sc.blanks.wheel),
    ] {
        for &blank in blanks {
            envelopes.push(Envelope {
                member: m,
                name: format!("{} {} blank", ["pinion", "wheel"][m], blank.name()),
                shaft: false,
                polygon: blank_shape(&g.data, member, blank, &dims).polygon,
            });
        }
    }
    let shafts = [b.pinion_shaft.as_ref(), b.wheel_shaft.as_ref()];
    for (m, s) in shafts.iter().enumerate() {
        if let Some(s) = s {
            envelopes.push(Envelope {
                member: m,
                name: format!("{} shaft", ["pinion", "wheel"][m]),
                shaft: true,
                polygon: shaft_polygon(s),
            });
        }
    }
    layout(
        &scene.path,
        h,
        [g.frames[0].axis(), g.frames[1].axis()],
        [&b.pinion, &b.wheel],
        shafts,
        &envelopes,
    )
    .map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_distance_of_a_unit_square() {
        let sq = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!((polygon_distance(&sq, [0.5, 0.5]) + 0.5).abs() < 1e-15);
        assert!((polygon_distance(&sq, [2.0, 0.5]) - 1.0).abs() < 1e-15);
        assert!((polygon_distance(&sq, [2.0, 2.0]) - 2f64.sqrt()).abs() < 1e-15);
    }
}
