//! Periodic tooth sectors: on an axisymmetric (standard) blank the refined
//! teeth get identical meshes, copied by rotation, so that a unit load on any
//! of them meets the same elements and tooth k's compliance is tooth 0's up
//! to the far body's mesh.
//!
//! The body is split along the middle of every slot next to a periodic tooth.
//! The splitting surface is θ = g(R): R the distance from the cone apex, g the
//! azimuth of the slot's root centre line at the slot loft's sections, held
//! constant beyond them; it is lofted through circular arcs about the apex
//! (R = const, θ = g(R), polar angle over the whole blank), which pass through
//! the slot sections to within (d² / 2R) ≈ 0.25 mm of depth. Each face of a
//! periodic sector is meshed as a rotated copy of the master sector's face
//! (gmsh periodic meshes); after the 3-D meshing each sector's tets are
//! replaced by the master's, rotated, and after second order its mid-edge
//! nodes are put at the master's, rotated.

use geometry::gear_body::SlotSection;
use gmsh::{DimTag, Session};
use std::collections::HashMap;

/// Failure while splitting the body into sectors or copying their meshes.
#[derive(Debug, thiserror::Error)]
pub enum SectorError {
    #[error("gmsh: {0}")]
    Gmsh(#[from] gmsh::GmshError),
    #[error("periodic sectors: {0}")]
    Mismatch(String),
}

/// The middle of a slot: azimuth of its root centre at the slot sections'
/// distances from the apex (ascending), unwrapped.
#[derive(Debug, Clone)]
pub struct SlotCentre {
    pub distance: Vec<f64>,
    pub azimuth: Vec<f64>,
}

/// The root centre line of the slot lofted through `sections`.
pub fn slot_centre(sections: &[SlotSection]) -> SlotCentre {
    let mut distance = Vec::with_capacity(sections.len());
    let mut azimuth: Vec<f64> = Vec::with_capacity(sections.len());
    for sec in sections {
        let root = &sec.edges[2];
        let p = root[root.len() / 2];
        distance.push((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt());
        let mut a = p[1].atan2(p[0]);
        if let Some(&prev) = azimuth.last() {
            a = prev + (a - prev + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
        }
        azimuth.push(a);
    }
    SlotCentre { distance, azimuth }
}

/// Distance from the apex and polar angle (from the +z axis) that bound a
/// half-section polygon in (z, ρ), widened so that the splitting surface
/// reaches through the whole body: ([R_min, R_max], [φ_min, φ_max]).
pub fn polar_extent(polygon: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let n = polygon.len();
    let mut r = [f64::INFINITY, 0.0f64];
    let mut phi = [f64::INFINITY, 0.0f64];
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        // Nearest point of the edge to the apex.
        let (dz, dr) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dz * dz + dr * dr;
        let t = if len2 > 0.0 {
            (-(a[0] * dz + a[1] * dr) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        r[0] = r[0].min((a[0] + t * dz).hypot(a[1] + t * dr));
        r[1] = r[1].max(a[0].hypot(a[1]));
        let p = a[1].atan2(a[0]);
        phi = [phi[0].min(p), phi[1].max(p)];
    }
    let margin = 0.05 * (phi[1] - phi[0]);
    (
        [0.8 * r[0], 1.1 * r[1]],
        [
            (phi[0] - margin).max(0.5 * phi[0]),
            (phi[1] + margin).min(0.5 * (phi[1] + std::f64::consts::PI)),
        ],
    )
}

/// A circular arc about the apex at distance `r`, azimuth `theta`, polar
/// angles `phi`, as a wire.
fn arc(s: &Session, apex: i32, r: f64, theta: f64, phi: [f64; 2]) -> gmsh::Result<i32> {
    let at = |ph: f64| {
        let (sp, cp) = ph.sin_cos();
        let (st, ct) = theta.sin_cos();
        s.occ_add_point(r * sp * ct, r * sp * st, r * cp, 0.0, -1)
    };
    let (a, b) = (at(phi[0])?, at(phi[1])?);
    let c = s.occ_add_circle_arc(a, apex, b)?;
    s.occ_add_wire(&[c], false)
}

/// The surface through the middle of the slot `centre` (slot 0) turned by
/// `angle` about the axis, over distances `r` and polar angles `phi`:
/// a smooth loft through the slot sections and flat (meridian) extensions
/// to `r[0]` and `r[1]`.
pub fn add_slot_surface(
    s: &Session,
    centre: &SlotCentre,
    r: [f64; 2],
    phi: [f64; 2],
    angle: f64,
) -> gmsh::Result<Vec<DimTag>> {
    let apex = s.occ_add_point(0.0, 0.0, 0.0, 0.0, -1)?;
    let n = centre.distance.len();
    let (a0, a1) = (centre.azimuth[0] + angle, centre.azimuth[n - 1] + angle);
    let mut out = Vec::new();
    let toe = [
        arc(s, apex, r[0], a0, phi)?,
        arc(s, apex, centre.distance[0], a0, phi)?,
    ];
    out.extend(s.occ_add_thru_sections(&toe, false, true, -1, "", "", false)?);
    let mid = (0..n)
        .map(|i| arc(s, apex, centre.distance[i], centre.azimuth[i] + angle, phi))
        .collect::<gmsh::Result<Vec<i32>>>()?;
    out.extend(s.occ_add_thru_sections(&mid, false, false, -1, "", "", false)?);
    let heel = [
        arc(s, apex, centre.distance[n - 1], a1, phi)?,
        arc(s, apex, r[1], a1, phi)?,
    ];
    out.extend(s.occ_add_thru_sections(&heel, false, true, -1, "", "", false)?);
    Ok(out.into_iter().filter(|d| d.0 == 2).collect())
}

/// Splits the volumes `body` with `surfaces` (OCC fragments) and removes
/// the pieces of the surfaces outside the body. Returns the volumes.
pub fn split(s: &Session, body: &[DimTag], surfaces: &[DimTag]) -> gmsh::Result<Vec<i32>> {
    s.occ_fragment(body, surfaces, true, true)?;
    s.occ_synchronize()?;
    for dim in [2, 1, 0] {
        let mut orphans = Vec::new();
        for (_, t) in s.get_entities(dim)? {
            if s.get_adjacencies(dim, t)?.0.is_empty() {
                orphans.push((dim, t));
            }
        }
        if !orphans.is_empty() {
            s.occ_remove(&orphans, false)?;
            s.occ_synchronize()?;
        }
    }
    Ok(s.get_entities(3)?.into_iter().map(|d| d.1).collect())
}

/// One periodic sector: its tooth and volume.
#[derive(Debug, Clone, Copy)]
pub struct Sector {
    pub tooth: usize,
    pub volume: i32,
}

/// `p` turned by `a` about the z axis.
pub fn rotate(p: [f64; 3], a: f64) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
}

/// The 4 × 4 affine matrix (by rows) of a turn by `a` about the z axis.
pub fn rotation_matrix(a: f64) -> [f64; 16] {
    let (s, c) = a.sin_cos();
    [
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ]
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Signed tooth offset of `tooth` from `master` on a member with `z` teeth,
/// in (−z/2, z/2].
pub fn offset(tooth: usize, master: usize, z: usize) -> i64 {
    let d = (tooth as i64 - master as i64).rem_euclid(z as i64);
    if 2 * d > z as i64 {
        d - z as i64
    } else {
        d
    }
}

/// The turn (rad) that takes the master sector onto `sec`.
fn turn(sec: &Sector, master: &Sector, teeth: usize) -> f64 {
    offset(sec.tooth, master.tooth, teeth) as f64 * 2.0 * std::f64::consts::PI / teeth as f64
}

/// A face with its centre of mass and area.
#[derive(Debug, Clone, Copy)]
struct FaceInfo {
    tag: i32,
    centre: [f64; 3],
    area: f64,
    /// Bounds two volumes: a piece of a splitting surface.
    shared: bool,
}

fn faces_of(s: &Session, volume: i32) -> gmsh::Result<Vec<FaceInfo>> {
    s.get_boundary(&[(3, volume)], false, false, false)?
        .into_iter()
        .map(|(_, t)| {
            let tag = t.abs();
            Ok(FaceInfo {
                tag,
                centre: s.occ_get_center_of_mass(2, tag)?,
                area: s.occ_get_mass(2, tag)?,
                shared: s.get_adjacencies(2, tag)?.0.len() > 1,
            })
        })
        .collect()
}

/// Two faces are copies when the centre of one turned onto the other is
/// within `tol` and their areas agree to 1e-3. (OCC integrates the mass
/// properties of a trimmed B-spline face to about 1e-5: a copy's centre
/// moves by ~0.2 µm, its area by ~5e-5.)
fn matches(f: &FaceInfo, g: &FaceInfo, a: f64, tol: f64) -> bool {
    dist(rotate(f.centre, -a), g.centre) < tol
        && (f.area - g.area).abs() <= 1e-3 * g.area.max(f.area)
}

/// Makes every face of the sectors a periodic copy of the master sector's
/// (`sectors[0]`): the faces on the splitting surfaces copy the master's
/// first splitting face pieces, the others the master's face in the same
/// place. `tol` is the match distance of face centres (m). Returns the faces
/// set periodic.
pub fn set_periodic_faces(
    s: &Session,
    sectors: &[Sector],
    teeth: usize,
    tol: f64,
) -> Result<usize, SectorError> {
    let pitch = 2.0 * std::f64::consts::PI / teeth as f64;
    let master = sectors[0];
    let mf = faces_of(s, master.volume)?;
    let (m_shared, m_own): (Vec<FaceInfo>, Vec<FaceInfo>) = mf.iter().partition(|f| f.shared);
    // The master's pieces on one splitting surface: those that turned by
    // one pitch land on another of its pieces.
    let left: Vec<FaceInfo> = m_shared
        .iter()
        .filter(|g| m_shared.iter().any(|h| matches(h, g, pitch, tol)))
        .copied()
        .collect();
    if left.is_empty() || 2 * left.len() != m_shared.len() {
        return Err(SectorError::Mismatch(format!(
            "the master sector (tooth {}) has {} faces on its splitting surfaces, {} of them on one side",
            master.tooth,
            m_shared.len(),
            left.len()
        )));
    }
    let mut done: std::collections::BTreeSet<i32> = left.iter().map(|f| f.tag).collect();
    let mut count = 0;
    for sec in sectors {
        let k = offset(sec.tooth, master.tooth, teeth);
        let faces = if sec.volume == master.volume {
            mf.clone()
        } else {
            faces_of(s, sec.volume)?
        };
        for f in &faces {
            if !done.insert(f.tag) {
                continue;
            }
            let (master_tag, a) = if f.shared {
                // On splitting surface k or k + 1 (left or right of the sector).
                [k, k + 1]
                    .into_iter()
                    .find_map(|n| {
                        let a = n as f64 * pitch;
                        left.iter().find(|g| matches(f, g, a, tol)).map(|g| (g.tag, a))
                    })
                    .ok_or_else(|| {
                        SectorError::Mismatch(format!(
                            "splitting face {} of tooth {}'s sector has no counterpart in the master sector",
                            f.tag, sec.tooth
                        ))
                    })?
            } else if sec.volume == master.volume {
                continue;
            } else {
                let a = k as f64 * pitch;
                let g = m_own.iter().find(|g| matches(f, g, a, tol)).ok_or_else(|| {
                    let near = m_own
                        .iter()
                        .map(|g| (dist(rotate(f.centre, -a), g.centre), g))
                        .min_by(|x, y| x.0.total_cmp(&y.0));
                    SectorError::Mismatch(format!(
                        "face {} of tooth {}'s sector (centre {:?}, area {:e} m²) has no counterpart in the master sector{}",
                        f.tag,
                        sec.tooth,
                        f.centre,
                        f.area,
                        near.map(|(d, g)| format!(
                            " (nearest: face {} at {d:e} m, area {:e} m²)",
                            g.tag, g.area
                        ))
                        .unwrap_or_default()
                    ))
                })?;
                (g.tag, a)
            };
            s.mesh_set_periodic(2, &[f.tag], &[master_tag], &rotation_matrix(a))?;
            count += 1;
        }
    }
    Ok(count)
}

/// A hash grid of points for lookups within a small distance.
struct PointGrid {
    cell: f64,
    map: HashMap<[i64; 3], Vec<(usize, [f64; 3])>>,
}

impl PointGrid {
    fn new(cell: f64, points: impl Iterator<Item = (usize, [f64; 3])>) -> Self {
        let mut map: HashMap<[i64; 3], Vec<(usize, [f64; 3])>> = HashMap::new();
        for (t, p) in points {
            map.entry(Self::key(cell, p)).or_default().push((t, p));
        }
        Self { cell, map }
    }

    fn key(cell: f64, p: [f64; 3]) -> [i64; 3] {
        std::array::from_fn(|i| (p[i] / cell).floor() as i64)
    }

    /// The nearest point within `tol` (≤ the cell size).
    fn find(&self, p: [f64; 3], tol: f64) -> Option<usize> {
        let k = Self::key(self.cell, p);
        let mut best: Option<(f64, usize)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(v) = self.map.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &(t, q) in v {
                            let d = dist(p, q);
                            if d <= tol && best.is_none_or(|b| d < b.0) {
                                best = Some((d, t));
                            }
                        }
                    }
                }
            }
        }
        best.map(|b| b.1)
    }
}

fn xyz(c: &[f64], i: usize) -> [f64; 3] {
    [c[3 * i], c[3 * i + 1], c[3 * i + 2]]
}

/// Replaces the first-order tets of every sector but the master
/// (`sectors[0]`) by the master's turned onto it; their boundary nodes are
/// the periodic faces' nodes, found within `tol` (m). Returns the tets copied.
pub fn copy_master_tets(
    s: &Session,
    sectors: &[Sector],
    teeth: usize,
    tol: f64,
) -> Result<usize, SectorError> {
    let master = sectors[0];
    let (inner, inner_xyz, _) = s.mesh_get_nodes(3, master.volume, false, false)?;
    let (all, all_xyz, _) = s.mesh_get_nodes(3, master.volume, true, false)?;
    let (types, _, nodes) = s.mesh_get_elements(3, master.volume)?;
    if types != [4] {
        return Err(SectorError::Mismatch(format!(
            "the master sector's volume holds element types {types:?}, not first-order tets only"
        )));
    }
    let tets = &nodes[0];
    let inner_index: HashMap<usize, usize> =
        inner.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let mut copied = 0;
    for sec in &sectors[1..] {
        let a = turn(sec, &master, teeth);
        s.mesh_clear_entities(&[(3, sec.volume)])?;
        let (bt, bx, _) = s.mesh_get_nodes(3, sec.volume, true, false)?;
        let grid = PointGrid::new(tol.max(1e-9), (0..bt.len()).map(|i| (bt[i], xyz(&bx, i))));
        let first = s.mesh_get_max_node_tag()? + 1;
        let mut map: HashMap<usize, usize> = HashMap::with_capacity(all.len());
        let mut new_xyz = Vec::with_capacity(inner_xyz.len());
        for (i, &t) in all.iter().enumerate() {
            if let Some(&j) = inner_index.get(&t) {
                map.insert(t, first + j);
                continue;
            }
            let p = rotate(xyz(&all_xyz, i), a);
            let found = grid.find(p, tol).ok_or_else(|| {
                SectorError::Mismatch(format!(
                    "tooth {}'s sector has no boundary node at {p:?} (the master's node {t} turned by {:.4} rad)",
                    sec.tooth, a
                ))
            })?;
            map.insert(t, found);
        }
        for j in 0..inner.len() {
            new_xyz.extend(rotate(xyz(&inner_xyz, j), a));
        }
        let new_tags: Vec<usize> = (0..inner.len()).map(|j| first + j).collect();
        s.mesh_add_nodes(3, sec.volume, &new_tags, &new_xyz)?;
        let conn: Vec<usize> = tets.iter().map(|t| map[t]).collect();
        s.mesh_add_elements_by_type(sec.volume, 4, &[], &conn)?;
        copied += tets.len() / 4;
    }
    Ok(copied)
}

/// Every node's coordinates, read at once (one C call, not one per node).
fn node_coords(s: &Session) -> gmsh::Result<HashMap<usize, [f64; 3]>> {
    let (tags, x, _) = s.mesh_get_nodes(-1, -1, false, false)?;
    Ok(tags
        .iter()
        .enumerate()
        .map(|(i, &t)| (t, xyz(&x, i)))
        .collect())
}

/// The tet10 connectivity of volume `vol` (ten node tags per element); an
/// error if it holds other elements.
fn tet10_of(s: &Session, vol: i32) -> Result<Vec<usize>, SectorError> {
    let (types, _, nodes) = s.mesh_get_elements(3, vol)?;
    if types != [11] {
        return Err(SectorError::Mismatch(format!(
            "volume {vol} holds element types {types:?}, not tet10 only"
        )));
    }
    Ok(nodes.into_iter().next().unwrap_or_default())
}

/// Puts the mid-edge nodes of every sector but the master (`sectors[0]`)
/// at the master's, turned: gmsh places a periodic face's mid-edge nodes
/// through that face's own parametrization, which moved them along the face
/// by up to 1.6 µm on the default pinion's reduced mesh (1.1e-8 m after).
/// The sectors' tet10 elements are the master's in the same order (copied by
/// [`copy_master_tets`] before second order); their vertices must agree
/// within `tol` (m). Returns the nodes set.
pub fn align_mid_edge_nodes(
    s: &Session,
    sectors: &[Sector],
    teeth: usize,
    tol: f64,
) -> Result<usize, SectorError> {
    let master = sectors[0];
    let m = tet10_of(s, master.volume)?;
    let coords = node_coords(s)?;
    let mut set = std::collections::BTreeSet::new();
    for sec in &sectors[1..] {
        let a = turn(sec, &master, teeth);
        let e = tet10_of(s, sec.volume)?;
        if e.len() != m.len() {
            return Err(SectorError::Mismatch(format!(
                "tooth {}'s sector has {} tet10, the master {}",
                sec.tooth,
                e.len() / 10,
                m.len() / 10
            )));
        }
        for (el, mel) in e.chunks(10).zip(m.chunks(10)) {
            for v in 0..4 {
                let d = dist(coords[&el[v]], rotate(coords[&mel[v]], a));
                if d > tol {
                    return Err(SectorError::Mismatch(format!(
                        "tooth {}'s sector: vertex node {} is {d:e} m from the master's turned",
                        sec.tooth, el[v]
                    )));
                }
            }
            for k in 4..10 {
                if set.insert(el[k]) {
                    s.mesh_set_node(el[k], rotate(coords[&mel[k]], a))?;
                }
            }
        }
    }
    Ok(set.len())
}

/// Largest distance between the tet10 nodes of each sector turned back
/// onto the master and the master's nearest tet10 element node; an error
/// if a sector's element or node count differs from the master's: the check
/// that the copies survived second order, snapping and cap removal. A
/// mid-edge node on a face a sector shares with the freely meshed rest of
/// the body moves when a tet of the rest is straightened (12.7 µm on the
/// 6 × 10 test pinion): that is what this can show beyond ~1 µm.
pub fn copy_deviation(s: &Session, sectors: &[Sector], teeth: usize) -> Result<f64, SectorError> {
    let master = sectors[0];
    let coords = node_coords(s)?;
    let points = |vol: i32| -> Result<(usize, Vec<[f64; 3]>), SectorError> {
        let nodes = tet10_of(s, vol)?;
        let mut tags = nodes.clone();
        tags.sort_unstable();
        tags.dedup();
        Ok((nodes.len() / 10, tags.iter().map(|t| coords[t]).collect()))
    };
    let (m_count, m_points) = points(master.volume)?;
    let cell = 1e-5;
    let grid = PointGrid::new(cell, m_points.iter().copied().enumerate());
    let mut worst = 0.0f64;
    for sec in &sectors[1..] {
        let a = turn(sec, &master, teeth);
        let (count, pts) = points(sec.volume)?;
        if count != m_count || pts.len() != m_points.len() {
            return Err(SectorError::Mismatch(format!(
                "tooth {}'s sector has {count} tet10 / {} nodes, the master {m_count} / {}",
                sec.tooth,
                pts.len(),
                m_points.len()
            )));
        }
        for p in pts {
            let q = rotate(p, -a);
            let d = grid.find(q, cell).map_or_else(
                || {
                    m_points
                        .iter()
                        .map(|&m| dist(q, m))
                        .fold(f64::INFINITY, f64::min)
                },
                |j| dist(q, m_points[j]),
            );
            worst = worst.max(d);
        }
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slot_centre_azimuth_is_continuous_across_the_negative_x_axis() {
        // Root centres at 179°, 181°, 183° (atan2 gives 179°, −179°, −177°).
        let sec = |deg: f64, r: f64| {
            let a = deg.to_radians();
            let p = [r * a.cos(), r * a.sin(), 0.05];
            SlotSection {
                cone_distance: r,
                edges: [
                    vec![p],
                    vec![p],
                    vec![p, p, p, p, p],
                    vec![p],
                    vec![p],
                    vec![p, p],
                ],
            }
        };
        let c = slot_centre(&[sec(179.0, 0.1), sec(181.0, 0.11), sec(183.0, 0.12)]);
        let deg: Vec<f64> = c.azimuth.iter().map(|a| a.to_degrees()).collect();
        for (got, want) in deg.iter().zip([179.0, 181.0, 183.0]) {
            assert!((got - want).abs() < 1e-9, "{deg:?}");
        }
        assert!((c.distance[1] - 0.11f64.hypot(0.05)).abs() < 1e-15);
    }

    #[test]
    fn offset_wraps_to_the_nearer_side() {
        assert_eq!(offset(1, 0, 43), 1);
        assert_eq!(offset(42, 0, 43), -1);
        assert_eq!(offset(0, 42, 43), 1);
        assert_eq!(offset(5, 5, 20), 0);
    }

    #[test]
    fn rotation_matrix_turns_points_like_rotate() {
        let a = 0.3;
        let m = rotation_matrix(a);
        let p = [0.1, -0.2, 0.05];
        let q = rotate(p, a);
        for (r, qr) in q.iter().enumerate() {
            let v: f64 = (0..3).map(|c| m[4 * r + c] * p[c]).sum::<f64>() + m[4 * r + 3];
            assert!((v - qr).abs() < 1e-15);
        }
    }

    #[test]
    fn polar_extent_of_a_ring_covers_its_corners() {
        // A ring 0.05 ≤ z ≤ 0.08, 0.03 ≤ ρ ≤ 0.1.
        let poly = [[0.05, 0.03], [0.08, 0.03], [0.08, 0.1], [0.05, 0.1]];
        let (r, phi) = polar_extent(&poly);
        for p in poly {
            let (rr, pp) = (p[0].hypot(p[1]), p[1].atan2(p[0]));
            assert!(r[0] < rr && rr < r[1]);
            assert!(phi[0] < pp && pp < phi[1]);
        }
        assert!(phi[0] > 0.0 && phi[1] < std::f64::consts::PI);
    }
}
