//! Geometry of the gear bodies for meshing, independent of the CAD kernel:
//! the blank as a body of revolution (a polygon in the axial half-plane),
//! the tooth-space (slot) sections whose loft is cut out of the blank, and
//! the lightweight wheel's holes.
//!
//! Axial half-plane coordinates: z along the member axis from the apex, ρ
//! radial; a point at cone distance L and height d above the pitch cone has
//! z = L cos γ − d sin γ, ρ = L sin γ + d cos γ.

use crate::design::{Member, MemberData, PairData};
use crate::error::GeometryError;
use crate::flank::Flank;
use crate::generation::Side;
use crate::pair::PairGeometry;
use serde::{Deserialize, Serialize};

/// Gear blank variant of a member.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Blank {
    /// Solid web.
    Standard,
    /// Thin web with three equally spaced holes.
    Lightweight,
}

impl Blank {
    /// The blank's name in scene files and file names: `standard`, `lightweight`.
    pub fn name(self) -> &'static str {
        match self {
            Blank::Standard => "standard",
            Blank::Lightweight => "lightweight",
        }
    }
}

/// Blank dimensions. Every field is optional in the scene file; missing ones
/// get defaults from the design ([`BlankDimensions::resolve`]).
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlankDimensionsMm {
    /// Pinion bore radius.
    pub pinion_bore_radius_mm: Option<f64>,
    /// Depth of the pinion body below the root cone at toe and heel.
    pub pinion_rim_depth_mm: Option<f64>,
    /// Length of the pinion's shaft seat behind the heel.
    pub pinion_shaft_length_mm: Option<f64>,
    pub wheel_bore_radius_mm: Option<f64>,
    pub wheel_hub_radius_mm: Option<f64>,
    /// Depth of the wheel rim below the root cone at toe and heel.
    pub wheel_rim_depth_mm: Option<f64>,
    /// Axial web thickness, standard blank.
    pub wheel_web_thickness_mm: Option<f64>,
    /// Axial web thickness, lightweight blank.
    pub wheel_lightweight_web_thickness_mm: Option<f64>,
    /// Diameter of the three web holes, lightweight blank.
    pub wheel_hole_diameter_mm: Option<f64>,
}

/// Resolved blank dimensions, m.
#[derive(Debug, Clone, Serialize)]
pub struct BlankDimensions {
    pub pinion_bore_radius: f64,
    pub pinion_rim_depth: f64,
    pub pinion_shaft_length: f64,
    pub wheel_bore_radius: f64,
    pub wheel_hub_radius: f64,
    pub wheel_rim_depth: f64,
    pub wheel_web_thickness: f64,
    pub wheel_lightweight_web_thickness: f64,
    pub wheel_hole_diameter: f64,
}

/// A point of the axial half-plane from (L, d) of a member with pitch angle γ.
pub fn axial_point(l: f64, d: f64, gamma: f64) -> [f64; 2] {
    let (s, c) = gamma.sin_cos();
    [l * c - d * s, l * s + d * c]
}

impl BlankDimensions {
    /// Defaults: rims 2 m_n deep; pinion bore at 40% of the toe's rim-bottom
    /// radius, shaft seat 0.5 b; wheel bore at 25% of the toe's rim-bottom
    /// radius, hub radius 1.8 × bore; web 0.35 b (standard) or 0.065 b
    /// (lightweight), holes filling 85% of the radial web height. The
    /// lightweight web is chosen for the white paper's ratio of mean TEs,
    /// about 3× the standard blank's (Tables 3/4: 3.3× at 100 N·m, 4.2× at
    /// 300 N·m): with the white-paper pair this one gives ~3× at 300 N·m.
    pub fn resolve(d: &BlankDimensionsMm, pair: &PairData) -> Self {
        let mn = pair.normal_module;
        let b = pair.face_width;
        let mm = |v: Option<f64>, default: f64| v.map_or(default, |x| x * 1e-3);
        let toe_bottom = |m: Member, depth: f64| {
            let md = pair.member(m);
            let ri = pair.inner_cone_distance();
            let root = -md.mean_dedendum
                + (ri - pair.mean_cone_distance) * (md.root_angle - md.pitch_angle).tan();
            axial_point(ri, root - depth, md.pitch_angle)[1]
        };
        let pinion_rim_depth = mm(d.pinion_rim_depth_mm, 2.0 * mn);
        let wheel_rim_depth = mm(d.wheel_rim_depth_mm, 2.0 * mn);
        let wheel_bore_radius = mm(
            d.wheel_bore_radius_mm,
            0.25 * toe_bottom(Member::Wheel, wheel_rim_depth),
        );
        let wheel_hub_radius = mm(d.wheel_hub_radius_mm, 1.8 * wheel_bore_radius);
        let web_height = toe_bottom(Member::Wheel, wheel_rim_depth) - wheel_hub_radius;
        BlankDimensions {
            pinion_bore_radius: mm(
                d.pinion_bore_radius_mm,
                0.4 * toe_bottom(Member::Pinion, pinion_rim_depth),
            ),
            pinion_rim_depth,
            pinion_shaft_length: mm(d.pinion_shaft_length_mm, 0.5 * b),
            wheel_bore_radius,
            wheel_hub_radius,
            wheel_rim_depth,
            wheel_web_thickness: mm(d.wheel_web_thickness_mm, 0.35 * b),
            wheel_lightweight_web_thickness: mm(d.wheel_lightweight_web_thickness_mm, 0.065 * b),
            wheel_hole_diameter: mm(d.wheel_hole_diameter_mm, 0.85 * web_height),
        }
    }
}

/// Web holes of the lightweight wheel, equally spaced.
pub const WHEEL_WEB_HOLES: usize = 3;

/// The blank of one member: the polygon of its half-section (counter-clockwise
/// in (z, ρ)), the bore radius, and for the lightweight wheel the web holes.
#[derive(Debug, Clone, Serialize)]
pub struct BlankShape {
    pub polygon: Vec<[f64; 2]>,
    pub bore_radius: f64,
    /// Axial extent of the bore (z range).
    pub bore_z: [f64; 2],
    /// Web holes: axis parallel to the member axis at this radius, diameter,
    /// z range to cut through; three holes at 0°, 120°, 240°.
    pub holes: Option<Holes>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Holes {
    pub count: usize,
    pub circle_radius: f64,
    pub diameter: f64,
    pub z: [f64; 2],
}

/// Volume of the body of revolution of a simple polygon in (z, ρ) about the
/// z axis, by Pappus: V = 2π Σ over edges of the signed area moment,
/// V = (π/3) Σ (z_i − z_{i+1}) (ρ_i² + ρ_i ρ_{i+1} + ρ_{i+1}²) · sign.
pub fn revolution_volume(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    let mut v = 0.0;
    for i in 0..n {
        let [z0, r0] = poly[i];
        let [z1, r1] = poly[(i + 1) % n];
        v += (z1 - z0) * (r0 * r0 + r0 * r1 + r1 * r1);
    }
    (std::f64::consts::PI / 3.0 * v).abs()
}

impl BlankShape {
    /// Whether the half-section is a body: a simple polygon (no two edges
    /// cross) wholly off the axis, with an area. Bore or hub dimensions
    /// wider than the body make it cross itself.
    pub fn is_body(&self) -> bool {
        let p = &self.polygon;
        let n = p.len();
        let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
            (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        };
        let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]| {
            orient(a, b, c) * orient(a, b, d) < 0.0 && orient(c, d, a) * orient(c, d, b) < 0.0
        };
        let simple = (0..n).all(|i| {
            (i + 2..n).all(|j| {
                (i == 0 && j == n - 1) || !cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])
            })
        });
        let twice_area: f64 = (0..n)
            .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
            .sum();
        simple && p.iter().all(|q| q[1] > 0.0) && twice_area.abs() > 0.0
    }
}

/// The blank of `member` with blank type `blank`.
pub fn blank_shape(
    pair: &PairData,
    member: Member,
    blank: Blank,
    dims: &BlankDimensions,
) -> BlankShape {
    let md = pair.member(member);
    let g = md.pitch_angle;
    let (ri, re, rm) = (
        pair.inner_cone_distance(),
        pair.outer_cone_distance(),
        pair.mean_cone_distance,
    );
    let face = |l: f64| md.mean_addendum + (l - rm) * (md.face_angle - g).tan();
    let root = |l: f64| -md.mean_dedendum + (l - rm) * (md.root_angle - g).tan();
    let a = axial_point(ri, face(ri), g);
    let bpt = axial_point(re, face(re), g);
    match member {
        Member::Pinion => {
            let depth = dims.pinion_rim_depth;
            let c = axial_point(re, root(re) - depth, g);
            let d = axial_point(ri, root(ri) - depth, g);
            let rb = dims.pinion_bore_radius;
            let z_back = c[0] + dims.pinion_shaft_length;
            // Shaft seat behind the heel at the heel's rim-bottom radius.
            BlankShape {
                polygon: vec![d, a, bpt, c, [z_back, c[1]], [z_back, rb], [d[0], rb]],
                bore_radius: rb,
                bore_z: [d[0], z_back],
                holes: None,
            }
        }
        Member::Wheel => {
            let depth = dims.wheel_rim_depth;
            let c = axial_point(re, root(re) - depth, g);
            let d = axial_point(ri, root(ri) - depth, g);
            let web = match blank {
                Blank::Standard => dims.wheel_web_thickness,
                Blank::Lightweight => dims.wheel_lightweight_web_thickness,
            }
            // The web stays under the rim.
            .min(0.9 * (c[0] - d[0]).abs());
            // Web centred under the rim; the rim bottom runs from D (toe) to C (heel).
            let zmid = 0.5 * (c[0] + d[0]);
            let (zw0, zw1) = (zmid - 0.5 * web, zmid + 0.5 * web);
            let on_rim = |z: f64| [z, d[1] + (z - d[0]) / (c[0] - d[0]) * (c[1] - d[1])];
            let (rh, rb) = (dims.wheel_hub_radius, dims.wheel_bore_radius);
            let (zh0, zh1) = (d[0], c[0]);
            let w0 = on_rim(zw0);
            let w1 = on_rim(zw1);
            let holes = (blank == Blank::Lightweight).then(|| Holes {
                count: WHEEL_WEB_HOLES,
                circle_radius: 0.5 * (rh + w0[1].min(w1[1])),
                diameter: dims.wheel_hole_diameter,
                z: [zh0 - 1e-3, zh1 + 1e-3],
            });
            BlankShape {
                polygon: vec![
                    d,
                    a,
                    bpt,
                    c,
                    w1,
                    [zw1, rh],
                    [zh1, rh],
                    [zh1, rb],
                    [zh0, rb],
                    [zh0, rh],
                    [zw0, rh],
                    w0,
                ],
                bore_radius: rb,
                bore_z: [zh0, zh1],
                holes,
            }
        }
    }
}

/// One tooth-space section: 3-D points (member frame) of its six edges, in
/// order around the section: flank of the lower tooth from above the face
/// cone to the fillet, its fillet to the root, the root between the two
/// fillets, the upper tooth's fillet, its flank up to above the face cone,
/// and the top back to the first point: the straight line (two points)
/// where it clears the face cone, else out along the face cone's normal, an
/// arc about the axis and back in (the corners and the
/// [`SLOT_TOP_ARC_POINTS`] arc points between them, see [`slot_sections`]).
#[derive(Debug, Clone, Serialize)]
pub struct SlotSection {
    pub cone_distance: f64,
    pub edges: [Vec<[f64; 3]>; 6],
}

/// Points of a slot section's top arc about the axis (between the two
/// raised corners, which it includes).
pub const SLOT_TOP_ARC_POINTS: usize = 7;

/// How far the flanks reach above the face cone, as a fraction of `top`,
/// in slot sections closed with an arc over the top.
pub const SLOT_FLANK_REACH_ARC_TOP: f64 = 1.0 / 12.0;

/// Smallest clearance of a straight slot top over the face cone, as a
/// fraction of the flanks' reach `top` above it: below it every section of
/// the member closes over the top with an arc about the axis instead.
pub const SLOT_TOP_MIN_CLEARANCE: f64 = 0.5;

/// Signed distance (m) of `p` (member frame) from the face cone of `md`,
/// positive outside the blank, in the meridian plane.
pub fn face_cone_clearance(md: &MemberData, mean_cone_distance: f64, p: [f64; 3]) -> f64 {
    let rm = mean_cone_distance;
    let d = |l: f64| md.mean_addendum + (l - rm) * (md.face_angle - md.pitch_angle).tan();
    let f0 = axial_point(rm, d(rm), md.pitch_angle);
    let f1 = axial_point(2.0 * rm, d(2.0 * rm), md.pitch_angle);
    let (tz, tr) = (f1[0] - f0[0], f1[1] - f0[1]);
    let (z, r) = (p[2], p[0].hypot(p[1]));
    ((r - f0[1]) * tz - (z - f0[0]) * tr) / tz.hypot(tr)
}

/// Smallest clearance (m) over the face cone of the polyline `pts`
/// (each segment sampled at 20 points).
pub fn polyline_clearance(md: &MemberData, mean_cone_distance: f64, pts: &[[f64; 3]]) -> f64 {
    let mut worst = f64::INFINITY;
    for w in pts.windows(2) {
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            let q = std::array::from_fn(|i| w[0][i] + t * (w[1][i] - w[0][i]));
            worst = worst.min(face_cone_clearance(md, mean_cone_distance, q));
        }
    }
    worst
}

/// The arc about the axis from `b` to `a` (azimuth, radius and axial
/// position interpolated linearly, the short way round), `n` points.
fn arc_about_axis(b: [f64; 3], a: [f64; 3], n: usize) -> Points {
    let (ta, tb) = (a[1].atan2(a[0]), b[1].atan2(b[0]));
    let dt = (ta - tb + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    let (ra, rb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
    (0..n)
        .map(|k| {
            let w = k as f64 / (n - 1) as f64;
            if k == 0 {
                return b;
            }
            if k == n - 1 {
                return a;
            }
            let (t, r) = (tb + w * dt, rb + w * (ra - rb));
            [r * t.cos(), r * t.sin(), b[2] + w * (a[2] - b[2])]
        })
        .collect()
}

/// Wheel teeth (fractional, in [0, z₂)) whose `side` flank lies at the
/// angle of a web hole's centre: hole k at 2πk/n in the body frame (as the
/// mesh stage cuts them, n = [`WHEEL_WEB_HOLES`]), tooth t's flank at
/// α₀ + 2πt/z₂ with α₀ the angle of tooth 0's flank at the mean cone
/// distance (the slots are copies of tooth 0's turned by t pitches).
pub fn hole_wheel_teeth(g: &PairGeometry, side: Side) -> Result<Vec<f64>, GeometryError> {
    let z = g.data.member(Member::Wheel).teeth as f64;
    let p = g
        .flank(Member::Wheel, side)
        .at(g.data.mean_cone_distance, 0.0)?;
    let a0 = p.pos[1].atan2(p.pos[0]);
    let tau = 2.0 * std::f64::consts::PI;
    Ok((0..WHEEL_WEB_HOLES)
        .map(|k| {
            let a = tau * k as f64 / WHEEL_WEB_HOLES as f64;
            ((a - a0) / tau * z).rem_euclid(z)
        })
        .collect())
}

/// Which flank side bounds the slot between tooth 0 and tooth 1 on each
/// side: (side of tooth 0 at the larger angle, side of tooth 1 at the smaller).
pub fn slot_sides(g: &PairGeometry, m: Member) -> Result<(Side, Side), GeometryError> {
    let ang = |s: Side| -> Result<f64, GeometryError> {
        let p = g.flank(m, s).at(g.data.mean_cone_distance, 0.0)?;
        Ok(p.pos[1].atan2(p.pos[0]))
    };
    let (a, c) = (ang(Side::Drive)?, ang(Side::Coast)?);
    let wrap = |x: f64| {
        (x + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
    };
    Ok(if wrap(c - a) > 0.0 {
        (Side::Coast, Side::Drive)
    } else {
        (Side::Drive, Side::Coast)
    })
}

/// A polyline of 3-D points.
type Points = Vec<[f64; 3]>;

fn rot(p: [f64; 3], a: f64) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
}

/// Flank points from the fillet junction up to `d_top`, and fillet points from
/// the junction down to the root, at cone distance `l`.
fn flank_and_fillet(
    f: &Flank,
    l: f64,
    d_top: f64,
    n_flank: usize,
    n_fillet: usize,
) -> Result<(Points, Points), GeometryError> {
    let d_low = f.bounds.low.at(l, f.bounds.rm);
    let flank = (0..n_flank)
        .map(|k| {
            let d = d_low + (d_top - d_low) * k as f64 / (n_flank - 1) as f64;
            f.at(l, d).map(|p| p.pos)
        })
        .collect::<Result<Vec<_>, _>>()?;
    // The fillet carries the flank's ease-off at the junction, fading to
    // zero at the root, so that flank and fillet meet without a step.
    let e_junction = f.at(l, d_low)?.ease_off;
    let arc = f.fillet_arc_at(l)?;
    let fillet = (0..n_fillet)
        .map(|k| {
            let psi = k as f64 / (n_fillet - 1) as f64;
            let q = f.gen.eval_fillet(psi, arc);
            let e = e_junction * (1.0 - psi);
            std::array::from_fn(|i| q.pos[i] - e * q.normal[i])
        })
        .collect();
    Ok((flank, fillet))
}

/// Slot sections between tooth 0 and tooth 1 of `m`, at `n` cone distances
/// from `margin` before the toe to `margin` beyond the heel; the flanks reach
/// `top` above the face cone and the top closes with straight lines when
/// every one clears the face cone by [`SLOT_TOP_MIN_CLEARANCE`] × `top`.
/// Otherwise (a wide slot next to a narrow top land: on the 9-tooth pinions
/// these chords dip up to 1 mm below the face cone at the heel, and the cut
/// left a sliver of the blank floating in every slot) the flanks reach only
/// [`SLOT_FLANK_REACH_ARC_TOP`] × `top` above it and every section closes
/// out along the face cone's normal to `top` above it, across on an arc
/// about the axis and back in.
pub fn slot_sections(
    g: &PairGeometry,
    m: Member,
    n: usize,
    margin: f64,
    top: f64,
) -> Result<Vec<SlotSection>, GeometryError> {
    let (lo_side, hi_side) = slot_sides(g, m)?;
    let pitch = 2.0 * std::f64::consts::PI / g.data.member(m).teeth as f64;
    let (fa, fb) = (g.flank(m, lo_side), g.flank(m, hi_side));
    let md = g.data.member(m);
    let rm = g.data.mean_cone_distance;
    let (l0, l1) = (
        g.data.inner_cone_distance() - margin,
        g.data.outer_cone_distance() + margin,
    );
    let build = |reach: f64| {
        (0..n)
            .map(|i| {
                let l = l0 + (l1 - l0) * i as f64 / (n - 1) as f64;
                let d_top =
                    md.mean_addendum + (l - rm) * (md.face_angle - md.pitch_angle).tan() + reach;
                let (fl_a, fi_a) = flank_and_fillet(fa, l, d_top, 13, 7)?;
                let (fl_b, fi_b) = flank_and_fillet(fb, l, d_top, 13, 7)?;
                let fl_b: Vec<[f64; 3]> = fl_b.into_iter().map(|p| rot(p, pitch)).collect();
                let fi_b: Vec<[f64; 3]> = fi_b.into_iter().map(|p| rot(p, pitch)).collect();
                // Root between the fillet ends, on the root cone.
                let (pa, pb) = (fi_a[fi_a.len() - 1], fi_b[fi_b.len() - 1]);
                let (la, _) = fa.gen.frame.axial(&pa);
                let (lb, _) = fa.gen.frame.axial(&pb);
                let (ta, tb) = (pa[1].atan2(pa[0]), pb[1].atan2(pb[0]));
                let tb = ta + (tb - ta).rem_euclid(2.0 * std::f64::consts::PI);
                let root: Vec<[f64; 3]> = (0..5)
                    .map(|k| {
                        let w = k as f64 / 4.0;
                        let ll = la + w * (lb - la);
                        let d =
                            -md.mean_dedendum + (ll - rm) * (md.root_angle - md.pitch_angle).tan();
                        let [z, r] = axial_point(ll, d, md.pitch_angle);
                        let t = ta + w * (tb - ta);
                        [r * t.cos(), r * t.sin(), z]
                    })
                    .collect();
                let mut root = root;
                root[0] = pa;
                root[4] = pb;
                // Shared section corners: the fillet starts exactly where its flank ends.
                let mut fi_a = fi_a;
                fi_a[0] = fl_a[0];
                let mut fi_b = fi_b;
                fi_b[0] = fl_b[0];
                let mut e0 = fl_a;
                e0.reverse();
                let mut e3 = fi_b;
                e3.reverse();
                let close = vec![fl_b[fl_b.len() - 1], e0[0]];
                Ok(SlotSection {
                    cone_distance: l,
                    edges: [e0, fi_a, root, e3, fl_b, close],
                })
            })
            .collect::<Result<Vec<_>, GeometryError>>()
    };
    let secs = build(top)?;
    if secs
        .iter()
        .all(|s| polyline_clearance(md, rm, &s.edges[5]) >= SLOT_TOP_MIN_CLEARANCE * top)
    {
        return Ok(secs);
    }
    // The flanks reach only a little above the face cone (extended further,
    // a narrow top land's flanks cross: by 5–7.5 mm at 0.6 m_n on the
    // 9 × 40 pinion, and OCC's cut of such overlapping slots trimmed the
    // teeth's top lands differently, tens of µm apart), then the top goes
    // out along the face cone's normal by `top` and across on an arc about
    // the axis.
    let mut secs = build(SLOT_FLANK_REACH_ARC_TOP * top)?;
    let (sg, cg) = md.face_angle.sin_cos();
    let rise = (1.0 - SLOT_FLANK_REACH_ARC_TOP) * top;
    for s in &mut secs {
        let raise = |p: [f64; 3]| {
            let r = p[0].hypot(p[1]);
            let f = (r + rise * cg) / r;
            [p[0] * f, p[1] * f, p[2] - rise * sg]
        };
        let [b, a] = [s.edges[5][0], s.edges[5][1]];
        let mut top_edge = vec![b];
        top_edge.extend(arc_about_axis(raise(b), raise(a), SLOT_TOP_ARC_POINTS));
        top_edge.push(a);
        s.edges[5] = top_edge;
    }
    Ok(secs)
}
