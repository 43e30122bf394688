//! Tetrahedral (tet10) meshes of the gear bodies with gmsh (OpenCASCADE).
//!
//! The blank is a body of revolution; one tooth space (slot) is lofted
//! through sections of the generated flanks and root fillets, extended beyond
//! toe, heel and face cone, copied to every tooth and cut out of the blank
//! (with the lightweight wheel's holes). Loaded flanks of the teeth that the
//! scene brings into contact get a structured (transfinite) surface mesh with
//! the requested elements along the profile × face width; sizes grow away
//! from them. On a standard (axisymmetric) blank the refined teeth are
//! periodic sectors: the body is split along the middle of their slots and
//! each sector's mesh is the solved tooth's turned by whole pitches
//! ([`crate::periodic_sectors`]), so that the compliance solved on one tooth
//! holds for the others up to the far body's mesh.

use crate::periodic_sectors::{
    add_slot_surface, align_mid_edge_nodes, copy_deviation, copy_master_tets, polar_extent,
    set_periodic_faces, slot_centre, split, Sector,
};
use geometry::design::Member;
use geometry::error::GeometryError;
use geometry::gear_body::{
    blank_shape, revolution_volume, slot_sections, BlankDimensions, BlankShape, SlotSection,
};
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, FlankElements};
use gmsh::{DimTag, Session};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Failure while building or meshing one member.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    #[error("scene {scene}, {member} ({blank:?} blank): gmsh: {source}")]
    Gmsh {
        scene: String,
        member: &'static str,
        blank: Blank,
        #[source]
        source: Box<gmsh::GmshError>,
    },
    #[error("scene {scene}, {member}: {source}")]
    Geometry {
        scene: String,
        member: &'static str,
        #[source]
        source: Box<GeometryError>,
    },
    #[error("scene {scene}, {member}: {message}")]
    Other {
        scene: String,
        member: &'static str,
        message: String,
    },
}

/// What to mesh.
#[derive(Debug, Clone)]
pub struct MeshRequest<'a> {
    pub scene: &'a str,
    pub geom: &'a PairGeometry,
    pub member: Member,
    pub blank: Blank,
    pub dims: &'a BlankDimensions,
    /// Elements along the profile × face width of the refined flanks.
    pub level: FlankElements,
    pub level_name: &'a str,
    /// Loaded flank side.
    pub side: Side,
    /// Teeth whose loaded flank is refined.
    pub refined_teeth: Vec<usize>,
    /// Teeth whose opposite flank is refined too (coast-side contact:
    /// backlash and rattle); empty when only the loaded side is analysed.
    pub opposite_refined_teeth: Vec<usize>,
    /// Teeth meshed as identical sectors copied by rotation
    /// ([`crate::periodic_sectors`]), the master (the tooth the influence
    /// solves load) first; empty for no periodic sectors (lightweight blank).
    pub periodic_teeth: Vec<usize>,
}

/// A refined flank and the elements achieved on it.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct RefinedFlank {
    pub tooth: usize,
    pub flank: String,
    pub surface: i32,
    pub elements_profile: usize,
    pub elements_face: usize,
}

/// The mesh report written next to the mesh.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct MeshReport {
    pub scene: String,
    pub member: String,
    pub blank: Blank,
    pub level: String,
    pub requested: FlankElements,
    /// Nodes the tets use (the file may hold a few more: see `caps_removed`).
    pub nodes: usize,
    pub tet10_elements: usize,
    pub occ_volume_m3: f64,
    pub mesh_volume_m3: f64,
    pub blank_volume_occ_m3: f64,
    pub blank_volume_analytic_m3: f64,
    pub quality_min_sicn: f64,
    pub quality_mean_sicn: f64,
    /// Mid-edge nodes put back on straight edges to undo inverted curved tets.
    pub straightened_nodes: usize,
    /// Flank-group nodes moved onto the generated flank ([`snap_to_flanks`]),
    /// the largest move (µm), and nodes left where gmsh put them (their move
    /// would have inverted a tet, or the flank has no point at their (L, d)).
    pub snapped_nodes: usize,
    pub snap_max_move_um: f64,
    pub unsnapped_nodes: usize,
    /// Flat tets over a flank's surface triangles removed before snapping
    /// ([`remove_cap`]); their unused nodes stay in the file, unreferenced.
    #[serde(default)]
    pub caps_removed: usize,
    /// Caps on a surface next to a flank (a fillet) that its snapped flank
    /// edge would have inverted, removed the same way ([`remove_other_cap`]).
    #[serde(default)]
    pub other_caps_removed: usize,
    /// Interior nodes moved by a few µm along with the snapped vertex of a
    /// sliver tet that the snap alone would have inverted ([`carry`]).
    #[serde(default)]
    pub carried_nodes: usize,
    pub algorithm_3d: String,
    pub fallback_used: bool,
    pub refined_flanks: Vec<RefinedFlank>,
    /// Physical groups (dim, tag, name).
    pub physical_groups: Vec<(i32, i32, String)>,
    /// Angular positions of the web holes, degrees.
    pub hole_angles_deg: Vec<f64>,
    /// Teeth meshed as rotated copies of the first one's sector, the faces
    /// set periodic, and the largest distance of a copied tet10 node from
    /// its master node turned onto it (m).
    #[serde(default)]
    pub periodic_teeth: Vec<usize>,
    #[serde(default)]
    pub periodic_faces: usize,
    #[serde(default)]
    pub periodic_copy_deviation_m: f64,
    pub time_geometry_s: f64,
    pub time_mesh_s: f64,
    /// Phases: the OCC cut (part of the geometry time); gmsh's 1-D to 3-D
    /// meshing, second order, and straightening + snapping (the mesh time).
    #[serde(default)]
    pub time_cut_s: f64,
    #[serde(default)]
    pub time_generate_s: f64,
    #[serde(default)]
    pub time_order2_s: f64,
    #[serde(default)]
    pub time_snap_s: f64,
}

/// Sections of the slot loft. Four sections follow the generated flank to
/// about 16 µm (five: 25 µm at the fillet junction) and the boolean cut
/// takes about two thirds of five's time; three are faster still but 150 µm
/// off. The flank nodes are snapped onto the generated flank after meshing.
const SLOT_SECTIONS: usize = 4;

/// A model face is a flank when its midpoint lies within this distance of
/// the generated flank (the loft's deviation, with margin) and its normal
/// is within about 25° of the flank normal.
const FLANK_FACE_TOLERANCE: f64 = 1e-4;

fn point(s: &Session, p: [f64; 3]) -> gmsh::Result<i32> {
    s.occ_add_point(p[0], p[1], p[2], 0.0, -1)
}

/// The blank: polygon revolved about z. Returns the volume.
fn add_blank(s: &Session, shape: &BlankShape) -> gmsh::Result<DimTag> {
    let pts: Vec<i32> = shape
        .polygon
        .iter()
        .map(|&[z, r]| point(s, [r, 0.0, z]))
        .collect::<gmsh::Result<_>>()?;
    let n = pts.len();
    let lines: Vec<i32> = (0..n)
        .map(|i| s.occ_add_line(pts[i], pts[(i + 1) % n]))
        .collect::<gmsh::Result<_>>()?;
    let cl = s.occ_add_curve_loop(&lines)?;
    let surf = s.occ_add_plane_surface(&[cl])?;
    let rev = s.occ_revolve(
        &[(2, surf)],
        0.0,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
        2.0 * std::f64::consts::PI,
    )?;
    Ok(*rev
        .iter()
        .find(|d| d.0 == 3)
        .expect("revolve makes a volume"))
}

/// Keeps every `k`-th point of an edge and its last one.
fn thin(e: &[[f64; 3]], keep: usize) -> Vec<[f64; 3]> {
    let step = ((e.len() - 1) as f64 / (keep - 1) as f64).max(1.0);
    (0..keep)
        .map(|k| e[((k as f64 * step).round() as usize).min(e.len() - 1)])
        .collect()
}

/// Sections of the slot loft of tooth space 0: from a tenth of the face
/// width before the toe to as far beyond the heel, 0.6 m_n above the face cone.
fn slot_loft_sections(req: &MeshRequest) -> Result<Vec<SlotSection>, MeshError> {
    let d = &req.geom.data;
    slot_sections(
        req.geom,
        req.member,
        SLOT_SECTIONS,
        0.1 * d.face_width,
        0.6 * d.normal_module,
    )
    .map_err(|e| geometry_err(req, e))
}

/// The slot loft of tooth space 0.
fn add_slot(s: &Session, req: &MeshRequest) -> Result<DimTag, MeshError> {
    let secs = slot_loft_sections(req)?;
    let mut wires = Vec::new();
    for sec in &secs {
        let keep = [7, 5, 3, 5, 7];
        let mut curves = Vec::new();
        let mut first = None;
        let mut prev: Option<i32> = None;
        for (e, &k) in sec.edges[..5].iter().zip(&keep) {
            let pts = thin(e, k);
            let mut tags = Vec::with_capacity(pts.len());
            for (i, p) in pts.iter().enumerate() {
                match (i, prev) {
                    (0, Some(t)) => tags.push(t),
                    _ => tags.push(point(s, *p).map_err(|e| gmsh_err(req, e))?),
                }
            }
            first.get_or_insert(tags[0]);
            prev = Some(tags[tags.len() - 1]);
            let c = if tags.len() > 2 {
                s.occ_add_spline(&tags)
            } else {
                s.occ_add_line(tags[0], tags[1])
            };
            curves.push(c.map_err(|e| gmsh_err(req, e))?);
        }
        // The top: a straight line back, or out, across on an arc about the
        // axis and back in.
        let top = &sec.edges[5];
        if top.len() > 2 {
            let mut tags = Vec::with_capacity(top.len() - 2);
            for p in &top[1..top.len() - 1] {
                tags.push(point(s, *p).map_err(|e| gmsh_err(req, e))?);
            }
            let (rb, ra) = (tags[0], tags[tags.len() - 1]);
            for c in [
                s.occ_add_line(prev.unwrap(), rb),
                s.occ_add_spline(&tags),
                s.occ_add_line(ra, first.unwrap()),
            ] {
                curves.push(c.map_err(|e| gmsh_err(req, e))?);
            }
        } else {
            let close = s
                .occ_add_line(prev.unwrap(), first.unwrap())
                .map_err(|e| gmsh_err(req, e))?;
            curves.push(close);
        }
        wires.push(
            s.occ_add_wire(&curves, true)
                .map_err(|e| gmsh_err(req, e))?,
        );
    }
    let out = s
        .occ_add_thru_sections(&wires, true, false, -1, "", "", false)
        .map_err(|e| gmsh_err(req, e))?;
    out.into_iter()
        .find(|d| d.0 == 3)
        .ok_or_else(|| other_err(req, "the slot loft made no volume".into()))
}

/// Distance within which the centre of a periodic sector's face turned onto
/// the master sector counts as the master face's (m): OCC's mass properties
/// of copies differ by ~0.2 µm; distinct faces are millimetres apart.
const SECTOR_FACE_TOLERANCE: f64 = 1e-5;

/// Distance within which a master node turned onto a periodic sector
/// counts as the sector's boundary node (m): gmsh puts a periodic copy's
/// nodes on the copied face's geometry, which OCC's boolean pieces hold only
/// to about the 0.2 µm their face centres differ by; distinct nodes are
/// ≥ 10 µm apart.
const SECTOR_NODE_TOLERANCE: f64 = 2e-6;

/// Splits the cut body along the middle of the slots on either side of the
/// periodic teeth. Returns the volumes.
fn split_at_periodic_slots(
    s: &Session,
    req: &MeshRequest,
    shape: &BlankShape,
    vols: &[i32],
) -> Result<Vec<i32>, MeshError> {
    let d = &req.geom.data;
    let centre = slot_centre(&slot_loft_sections(req)?);
    let (r, phi) = polar_extent(&shape.polygon);
    let z = d.member(req.member).teeth as usize;
    let pitch = 2.0 * std::f64::consts::PI / z as f64;
    // Slot k lies between tooth k and tooth k + 1.
    let mut slots = std::collections::BTreeSet::new();
    for &t in &req.periodic_teeth {
        slots.insert((t + z - 1) % z);
        slots.insert(t);
    }
    let g = |e| gmsh_err(req, e);
    let mut surfaces = Vec::new();
    for k in slots {
        surfaces.extend(add_slot_surface(s, &centre, r, phi, k as f64 * pitch).map_err(g)?);
    }
    let body: Vec<DimTag> = vols.iter().map(|&v| (3, v)).collect();
    let out = split(s, &body, &surfaces).map_err(g)?;
    let expected = req.periodic_teeth.len() + 1;
    if out.len() < expected {
        return Err(other_err(
            req,
            format!(
                "splitting the body at the slots of the periodic teeth {:?} gave {} volumes, expected at least {expected}",
                req.periodic_teeth,
                out.len()
            ),
        ));
    }
    Ok(out)
}

/// The periodic teeth's sectors (master first): the volume next to each
/// one's loaded flank. Empty without periodic teeth.
fn periodic_sectors(
    s: &Session,
    req: &MeshRequest,
    flank_faces: &[(usize, Side, i32)],
) -> Result<Vec<Sector>, MeshError> {
    let mut out: Vec<Sector> = Vec::new();
    for &tooth in &req.periodic_teeth {
        let face = flank_faces
            .iter()
            .find(|f| f.0 == tooth && f.1 == req.side)
            .ok_or_else(|| {
                other_err(
                    req,
                    format!("periodic tooth {tooth} has no loaded flank face"),
                )
            })?;
        let (up, _) = s.get_adjacencies(2, face.2).map_err(|e| gmsh_err(req, e))?;
        let volume = match up[..] {
            [v] => v,
            _ => {
                return Err(other_err(
                    req,
                    format!(
                        "the loaded flank of periodic tooth {tooth} bounds {} volumes",
                        up.len()
                    ),
                ))
            }
        };
        if out.iter().any(|x| x.volume == volume) {
            return Err(other_err(
                req,
                format!("periodic tooth {tooth} shares its sector with another tooth: the slot surfaces did not split the body"),
            ));
        }
        out.push(Sector { tooth, volume });
    }
    Ok(out)
}

fn gmsh_err(req: &MeshRequest, e: gmsh::GmshError) -> MeshError {
    MeshError::Gmsh {
        scene: req.scene.to_string(),
        member: req.member.name(),
        blank: req.blank,
        source: Box::new(e),
    }
}

fn geometry_err(req: &MeshRequest, e: GeometryError) -> MeshError {
    MeshError::Geometry {
        scene: req.scene.to_string(),
        member: req.member.name(),
        source: Box::new(e),
    }
}

fn other_err(req: &MeshRequest, message: String) -> MeshError {
    MeshError::Other {
        scene: req.scene.to_string(),
        member: req.member.name(),
        message,
    }
}

/// Classification of a model surface.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Face {
    Flank { tooth: usize, side: Side },
    Bore,
    Hole,
    Other,
}

fn classify(
    s: &Session,
    req: &MeshRequest,
    shape: &BlankShape,
    tag: i32,
) -> Result<Face, MeshError> {
    let (lo, hi) = s
        .get_parametrization_bounds(2, tag)
        .map_err(|e| gmsh_err(req, e))?;
    let mid: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
    let v = s.get_value(2, tag, &mid).map_err(|e| gmsh_err(req, e))?;
    let p = [v[0], v[1], v[2]];
    let kind = s.get_type(2, tag).map_err(|e| gmsh_err(req, e))?;
    let rho = p[0].hypot(p[1]);
    if kind == "Cylinder" && (rho - shape.bore_radius).abs() < 1e-6 {
        return Ok(Face::Bore);
    }
    if let Some(h) = &shape.holes {
        if kind == "Cylinder" {
            for k in 0..h.count {
                let a = 2.0 * std::f64::consts::PI * k as f64 / h.count as f64;
                let (cx, cy) = (h.circle_radius * a.cos(), h.circle_radius * a.sin());
                if ((p[0] - cx).hypot(p[1] - cy) - 0.5 * h.diameter).abs() < 1e-6 {
                    return Ok(Face::Hole);
                }
            }
        }
    }
    let z = req.geom.data.member(req.member).teeth as usize;
    let pitch = 2.0 * std::f64::consts::PI / z as f64;
    for side in [Side::Drive, Side::Coast] {
        let f = req.geom.flank(req.member, side);
        let (l, d) = f.gen.frame.axial(&p);
        if d < f.bounds.low.at(l, f.bounds.rm) + 1e-4 || d > f.bounds.face.at(l, f.bounds.rm) {
            continue;
        }
        let Ok(q) = f.at(l, d) else { continue };
        let k = ((p[1].atan2(p[0]) - q.pos[1].atan2(q.pos[0])) / pitch).round() as i64;
        let a = -(k as f64) * pitch;
        let (sa, ca) = a.sin_cos();
        let pr = [ca * p[0] - sa * p[1], sa * p[0] + ca * p[1], p[2]];
        let dist =
            ((pr[0] - q.pos[0]).powi(2) + (pr[1] - q.pos[1]).powi(2) + (pr[2] - q.pos[2]).powi(2))
                .sqrt();
        // A sliver of the top land or heel split off at the blank's seam
        // can have its midpoint near a flank edge: the face normal tells.
        let n = s.get_normal(tag, &mid).map_err(|e| gmsh_err(req, e))?;
        let nr = [ca * n[0] - sa * n[1], sa * n[0] + ca * n[1], n[2]];
        let cos: f64 = (0..3).map(|i| nr[i] * q.normal[i]).sum();
        if dist < FLANK_FACE_TOLERANCE && cos.abs() > 0.9 {
            return Ok(Face::Flank {
                tooth: k.rem_euclid(z as i64) as usize,
                side,
            });
        }
    }
    Ok(Face::Other)
}

/// A Threshold size field on the distance to `surfaces`: `size` within half
/// of it, growing to `coarse` at `dist_max`. Returns the field tag.
fn size_near(
    s: &Session,
    surfaces: &[i32],
    size: f64,
    coarse: f64,
    dist_max: f64,
) -> gmsh::Result<i32> {
    let dist = s.mesh_field_add("Distance")?;
    let list: Vec<f64> = surfaces.iter().map(|&t| t as f64).collect();
    s.mesh_field_set_numbers(dist, "SurfacesList", &list)?;
    s.mesh_field_set_number(dist, "Sampling", 30.0)?;
    let th = s.mesh_field_add("Threshold")?;
    s.mesh_field_set_number(th, "InField", dist as f64)?;
    s.mesh_field_set_number(th, "SizeMin", size)?;
    s.mesh_field_set_number(th, "SizeMax", coarse)?;
    s.mesh_field_set_number(th, "DistMin", 0.5 * size)?;
    s.mesh_field_set_number(th, "DistMax", dist_max)?;
    Ok(th)
}

/// Sum of the tet10 volumes of the current mesh, the number of tets and
/// the number of nodes they use.
pub fn mesh_volume(s: &Session) -> gmsh::Result<(f64, usize, usize)> {
    let (tags, coord, _) = s.mesh_get_nodes(-1, -1, false, false)?;
    let max = tags.iter().copied().max().unwrap_or(0);
    let mut idx = vec![usize::MAX; max + 1];
    for (i, &t) in tags.iter().enumerate() {
        idx[t] = i;
    }
    let (types, _, nodes) = s.mesh_get_elements(3, -1)?;
    let mut vol = 0.0;
    let mut count = 0;
    let mut used = vec![false; tags.len()];
    for (ty, nn) in types.iter().zip(&nodes) {
        if *ty != 11 {
            continue;
        }
        for el in nn.chunks(10) {
            for &t in el {
                used[idx[t]] = true;
            }
            let x: [[f64; 3]; 10] = std::array::from_fn(|k| {
                let i = idx[el[k]];
                [coord[3 * i], coord[3 * i + 1], coord[3 * i + 2]]
            });
            vol += fem::tet10::volume(&x);
            count += 1;
        }
    }
    Ok((vol, count, used.iter().filter(|&&u| u).count()))
}

/// Elements along a curve of a second-order mesh: (nodes − 1) / 2.
fn elements_on_curve(s: &Session, curve: i32) -> gmsh::Result<usize> {
    let (t, _, _) = s.mesh_get_nodes(1, curve, true, false)?;
    Ok(t.len().saturating_sub(1) / 2)
}

/// Cone distance of the two end points of a curve.
fn curve_span(s: &Session, req: &MeshRequest, curve: i32) -> gmsh::Result<f64> {
    let ends = s.get_boundary(&[(1, curve)], false, false, false)?;
    let f = req.geom.flank(req.member, req.side);
    let mut ls = Vec::new();
    for (_, t) in ends {
        let v = s.get_value(0, t.abs(), &[])?;
        ls.push(f.gen.frame.axial(&[v[0], v[1], v[2]]).0);
    }
    Ok(if ls.len() == 2 {
        (ls[0] - ls[1]).abs()
    } else {
        0.0
    })
}

/// Curved tets along the fillet–root junction can invert when their
/// mid-edge nodes are put on the curved geometry. Their mid-edge nodes go back
/// to the edge midpoints (a straight tet with valid vertices is valid); this
/// is repeated while neighbours are still inverted. Returns the nodes moved.
/// (gmsh's high-order optimiser is not used: it can throw through the C API.)
fn straighten_inverted(s: &Session) -> gmsh::Result<usize> {
    let mut moved = std::collections::BTreeSet::new();
    for _ in 0..4 {
        let (types, tags, nodes) = s.mesh_get_elements(3, -1)?;
        let Some(i) = types.iter().position(|&t| t == 11) else {
            return Ok(0);
        };
        let q = s.mesh_get_element_qualities(&tags[i], "minSICN")?;
        let bad: Vec<usize> = q
            .iter()
            .enumerate()
            .filter(|(_, &v)| v <= 1e-3)
            .map(|(k, _)| k)
            .collect();
        if bad.is_empty() {
            break;
        }
        let (ntags, coord, _) = s.mesh_get_nodes(-1, -1, false, false)?;
        let max = ntags.iter().copied().max().unwrap_or(0);
        let mut idx = vec![usize::MAX; max + 1];
        for (k, &t) in ntags.iter().enumerate() {
            idx[t] = k;
        }
        let x = |t: usize| {
            [
                coord[3 * idx[t]],
                coord[3 * idx[t] + 1],
                coord[3 * idx[t] + 2],
            ]
        };
        for k in bad {
            let el = &nodes[i][10 * k..10 * k + 10];
            for (e, &[a, b]) in fem::tet10::EDGES.iter().enumerate() {
                let (pa, pb) = (x(el[a]), x(el[b]));
                s.mesh_set_node(el[4 + e], std::array::from_fn(|c| 0.5 * (pa[c] + pb[c])))?;
                moved.insert(el[4 + e]);
            }
        }
    }
    Ok(moved.len())
}

/// Largest normal distance of a flank-group node that [`snap_to_flanks`]
/// moves: loft errors are µm, straightened mid-edge nodes of coarse teeth
/// ~0.15 mm; a node farther off is not on the generated flank (the face
/// reaches into the top land or toe at the blank's seam) and stays.
const MAX_SNAP: f64 = 0.5e-3;

/// A tet whose min SICN after snapping is at or below this is checked for
/// being a cap ([`remove_cap`]).
const CAP_QUALITY: f64 = 1e-3;

/// Snap moves are µm, so they may lower the quality of a tet that was poor
/// already (min SICN 1.7e-3 → 6e-4 on one tet of the reduced-level pinion)
/// but not below this floor: min SICN > 0 keeps the Jacobian positive at
/// every point, and the floor keeps a margin. A move that goes below it is
/// undone.
const SNAP_MIN_QUALITY: f64 = 1e-4;

/// What [`snap_to_flanks`] did.
struct Snap {
    moved: usize,
    max_move: f64,
    kept: usize,
    caps_removed: usize,
    other_caps_removed: usize,
    /// Interior nodes moved along with a poor tet's snapped nodes ([`carry`]).
    carried: usize,
}

/// The point of `side`'s generated flank of `tooth` at `p`'s axial-section
/// coordinates (L, d), reached by three steps along the flank normal; `None`
/// when the flank has no point there or `p` lies farther than [`MAX_SNAP`]
/// from it (a sliver of the top land or toe cut into the flank face).
fn flank_point(req: &MeshRequest, tooth: usize, side: Side, p: [f64; 3]) -> Option<[f64; 3]> {
    let f = req.geom.flank(req.member, side);
    let z = req.geom.data.member(req.member).teeth as f64;
    let (sa, ca) = (tooth as f64 * 2.0 * std::f64::consts::PI / z).sin_cos();
    // Tooth-0 frame; three steps converge to well below 1 nm.
    let mut r = [ca * p[0] + sa * p[1], -sa * p[0] + ca * p[1], p[2]];
    for step in 0..3 {
        let (l, d) = f.gen.frame.axial(&r);
        let q = f.at(l, d).ok()?;
        let dist: f64 = (0..3).map(|i| (r[i] - q.pos[i]) * q.normal[i]).sum();
        if step == 0 && dist.abs() > MAX_SNAP {
            return None;
        }
        for (ri, ni) in r.iter_mut().zip(q.normal) {
            *ri -= dist * ni;
        }
    }
    Some([ca * r[0] - sa * r[1], sa * r[0] + ca * r[1], r[2]])
}

/// The lofted slot follows the generated flank only to about 0.5 µm (more
/// near the fillet junction), and the TE is measured in fractions of a µm.
/// So every node of a flank surface (vertex and mid-edge, boundary included)
/// is moved onto the generated flank at its own axial-section coordinates
/// (L, d) ([`flank_point`]); loft errors are a few µm, straightened mid-edge
/// nodes of coarse teeth ~0.2 mm.
///
/// A tet whose four vertices all lie on one flank and which covers two or
/// three of its surface triangles (a *cap*: a flat tet over a surface vertex
/// of valence 3, or over an edge) has almost no volume, and on the exact
/// curved flank it inverts. Such caps are removed ([`remove_cap`]), and so
/// are caps on a fillet that a snapped flank edge inverts
/// ([`remove_other_cap`]). A sliver the snap inverts otherwise is translated
/// with its snapped nodes ([`carry`]). Any move that still takes a tet below
/// [`SNAP_MIN_QUALITY`] is undone, node by node of the bad tets.
fn snap_to_flanks(
    s: &Session,
    req: &MeshRequest,
    faces: &[(usize, Side, i32)],
) -> gmsh::Result<Snap> {
    let mut old: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
    let mut max_move: f64 = 0.0;
    let mut kept = std::collections::BTreeSet::new();
    // Flank face of each flank node (the first one, for shared edges).
    let mut face_of: std::collections::BTreeMap<usize, usize> = Default::default();
    for (fi, &(tooth, side, tag)) in faces.iter().enumerate() {
        let (tags, xyz, _) = s.mesh_get_nodes(2, tag, true, false)?;
        for (&t, p) in tags.iter().zip(xyz.chunks(3)) {
            face_of.entry(t).or_insert(fi);
            if old.contains_key(&t) || kept.contains(&t) {
                continue;
            }
            let p = [p[0], p[1], p[2]];
            let Some(x) = flank_point(req, tooth, side, p) else {
                kept.insert(t);
                continue;
            };
            let mv = (0..3).map(|i| (x[i] - p[i]).powi(2)).sum::<f64>().sqrt();
            max_move = max_move.max(mv);
            old.insert(t, p);
            s.mesh_set_node(t, x)?;
        }
    }
    let mut caps_removed = 0;
    let mut other_caps_removed = 0;
    // Interior nodes carried along with a poor tet's snapped nodes: node →
    // (position before, the tet that carried it).
    let mut carried: std::collections::BTreeMap<usize, ([f64; 3], usize)> = Default::default();
    let mut carry_tried = std::collections::BTreeSet::new();
    // Remove caps; carry the interior nodes of other poor tets along with
    // their snapped nodes; undo the moves where that fails too.
    for _ in 0..8 {
        let mut changed = false;
        for (_, vol) in s.get_entities(3)? {
            let (types, etags, enodes) = s.mesh_get_elements(3, vol)?;
            let Some(i) = types.iter().position(|&t| t == 11) else {
                continue;
            };
            let q = s.mesh_get_element_qualities(&etags[i], "minSICN")?;
            for (k, &qk) in q.iter().enumerate().filter(|(_, &v)| v <= CAP_QUALITY) {
                let tet = etags[i][k];
                let el: [usize; 10] = std::array::from_fn(|j| enodes[i][10 * k + j]);
                let fi = face_of.get(&el[0]).copied();
                let on_one_flank =
                    fi.is_some() && el[..4].iter().all(|n| face_of.get(n).copied() == fi);
                if let (true, Some(fi)) = (on_one_flank, fi) {
                    let (tooth, side, tag) = faces[fi];
                    if remove_cap(s, req, vol, tet, &el, (tag, Some((tooth, side))), &mut old)? {
                        caps_removed += 1;
                        changed = true;
                        continue;
                    }
                }
                if qk > SNAP_MIN_QUALITY {
                    continue;
                }
                // A cap on a neighbouring surface (a fillet, whose edge with
                // the flank moved): its nodes stay where gmsh put them.
                if remove_other_cap(s, req, vol, tet, &el, faces, &mut old)? {
                    other_caps_removed += 1;
                    changed = true;
                    continue;
                }
                // A carry that made this tet poor is taken back (its
                // origin is then undone below on the next pass).
                let origins: std::collections::BTreeSet<usize> = el
                    .iter()
                    .filter_map(|n| carried.get(n).map(|c| c.1))
                    .collect();
                if !origins.is_empty() {
                    let back: Vec<usize> = carried
                        .iter()
                        .filter(|(_, c)| origins.contains(&c.1))
                        .map(|(&n, _)| n)
                        .collect();
                    for n in back {
                        let (p, _) = carried.remove(&n).expect("listed above");
                        s.mesh_set_node(n, p)?;
                    }
                    changed = true;
                    continue;
                }
                if carry_tried.insert(tet) {
                    let skip = |n: &usize| face_of.contains_key(n) || carried.contains_key(n);
                    if let Some(moves) = carry(s, &el, &old, skip)? {
                        for (n, p) in moves {
                            carried.insert(n, (p, tet));
                        }
                        changed = true;
                        continue;
                    }
                }
                for n in &el {
                    if let Some(p) = old.remove(n) {
                        s.mesh_set_node(*n, p)?;
                        kept.insert(*n);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    Ok(Snap {
        moved: old.len(),
        max_move,
        kept: kept.len(),
        caps_removed,
        other_caps_removed,
        carried: carried.len(),
    })
}

/// A node tag and a position of it.
type NodeAt = (usize, [f64; 3]);

/// Moves the nodes of tet `el` for which `skip` is false (flank nodes and
/// nodes carried already are skipped) by the mean snap move of its snapped
/// nodes, so that the tet is translated rather than flattened: a sliver
/// with one vertex on the flank and its other three just inside inverts when that vertex alone moves a few µm, while the
/// well-shaped tets around its interior nodes hardly notice the same µm.
/// Returns the nodes moved with their old positions, or `None` if the tet
/// has no snapped node or no interior node.
fn carry(
    s: &Session,
    el: &[usize; 10],
    old: &std::collections::BTreeMap<usize, [f64; 3]>,
    skip: impl Fn(&usize) -> bool,
) -> gmsh::Result<Option<Vec<NodeAt>>> {
    let mut d = [0.0; 3];
    let mut snapped = 0;
    for n in el {
        if let Some(p) = old.get(n) {
            let (x, _) = s.mesh_get_node(*n)?;
            for c in 0..3 {
                d[c] += x[c] - p[c];
            }
            snapped += 1;
        }
    }
    let interior: Vec<usize> = el.iter().copied().filter(|n| !skip(n)).collect();
    if snapped == 0 || interior.is_empty() {
        return Ok(None);
    }
    let d = d.map(|v| v / snapped as f64);
    let mut moves = Vec::with_capacity(interior.len());
    for n in interior {
        let (x, _) = s.mesh_get_node(n)?;
        s.mesh_set_node(n, std::array::from_fn(|c| x[c] + d[c]))?;
        moves.push((n, x));
    }
    Ok(Some(moves))
}

/// Removes the cap `tet` (nodes `el`) of volume `vol` if two or three of its
/// faces are triangles of surface `tag`: those triangles go, the tet's other
/// faces become the surface's triangles (oriented like the ones they
/// replace; on a `flank` (tooth, side) their nodes are put on the generated
/// flank), and the tet goes.
/// A vertex covered by three cap faces, and the mid-edge nodes of edges no
/// longer used, stay as nodes without elements (the FE reader drops them).
/// Returns false (nothing changed) if `tet` is not such a cap.
fn remove_cap(
    s: &Session,
    req: &MeshRequest,
    vol: i32,
    tet: usize,
    el: &[usize; 10],
    (tag, flank): (i32, Option<(usize, Side)>),
    old: &mut std::collections::BTreeMap<usize, [f64; 3]>,
) -> gmsh::Result<bool> {
    let (types, ftags, fnodes) = s.mesh_get_elements(2, tag)?;
    let Some(ti) = types.iter().position(|&t| t == 9) else {
        return Ok(false);
    };
    let key = |mut v: [usize; 3]| {
        v.sort_unstable();
        v
    };
    let tris: std::collections::HashMap<[usize; 3], (usize, [usize; 6])> = ftags[ti]
        .iter()
        .zip(fnodes[ti].chunks(6))
        .map(|(&t, n)| (key([n[0], n[1], n[2]]), (t, std::array::from_fn(|j| n[j]))))
        .collect();
    // Face opposite vertex v: the other three vertices.
    let opposite = |v: usize| -> [usize; 3] {
        let o: Vec<usize> = (0..4).filter(|&j| j != v).collect();
        [o[0], o[1], o[2]]
    };
    let (on, inner): (Vec<usize>, Vec<usize>) =
        (0..4).partition(|&v| tris.contains_key(&key(opposite(v).map(|j| el[j]))));
    if on.len() < 2 || inner.is_empty() {
        return Ok(false);
    }
    // The tet's own nodes are all that is looked at.
    let mut at = std::collections::HashMap::new();
    for &n in el {
        at.insert(n, s.mesh_get_node(n)?.0);
    }
    let x = |t: usize| -> [f64; 3] { at[&t] };
    let normal = |a: usize, b: usize, c: usize| -> [f64; 3] {
        let (pa, pb, pc) = (x(a), x(b), x(c));
        let u: [f64; 3] = std::array::from_fn(|i| pb[i] - pa[i]);
        let w: [f64; 3] = std::array::from_fn(|i| pc[i] - pa[i]);
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    };
    let (_, reference) = tris[&key(opposite(on[0]).map(|j| el[j]))];
    let n_ref = normal(reference[0], reference[1], reference[2]);
    let mid = |a: usize, b: usize| -> usize {
        let e = fem::tet10::EDGES
            .iter()
            .position(|&[p, q]| (p, q) == (a, b) || (p, q) == (b, a))
            .expect("two distinct tet vertices span an edge");
        el[4 + e]
    };
    let mut new_nodes = Vec::new();
    for &v in &inner {
        let [a, b, c] = opposite(v);
        let n = normal(el[a], el[b], el[c]);
        let (b, c) = if (0..3).map(|i| n[i] * n_ref[i]).sum::<f64>() >= 0.0 {
            (b, c)
        } else {
            (c, b)
        };
        new_nodes.extend([el[a], el[b], el[c], mid(a, b), mid(b, c), mid(c, a)]);
    }
    if let Some((tooth, side)) = flank {
        for &n in &new_nodes {
            if let std::collections::btree_map::Entry::Vacant(e) = old.entry(n) {
                let p = x(n);
                if let Some(q) = flank_point(req, tooth, side, p) {
                    e.insert(p);
                    s.mesh_set_node(n, q)?;
                }
            }
        }
    }
    let removed: Vec<usize> = on
        .iter()
        .map(|&v| tris[&key(opposite(v).map(|j| el[j]))].0)
        .collect();
    s.mesh_remove_elements(3, vol, &[tet])?;
    s.mesh_remove_elements(2, tag, &removed)?;
    let first = s.mesh_get_max_element_tag()? + 1;
    let new_tags: Vec<usize> = (0..inner.len()).map(|k| first + k).collect();
    s.mesh_add_elements_by_type(tag, 9, &new_tags, &new_nodes)?;
    Ok(true)
}

/// Removes `tet` if it is a cap ([`remove_cap`]) on a surface other than a
/// flank that its nodes lie on: the fillet next to a flank, on the reference
/// level's pinion, whose caps invert when their flank edge is snapped (a
/// sliver 0.4 mm wide and 0.4 µm thin, its flank edge moved 7 µm).
fn remove_other_cap(
    s: &Session,
    req: &MeshRequest,
    vol: i32,
    tet: usize,
    el: &[usize; 10],
    faces: &[(usize, Side, i32)],
    old: &mut std::collections::BTreeMap<usize, [f64; 3]>,
) -> gmsh::Result<bool> {
    let mut surfaces = std::collections::BTreeSet::new();
    for &n in el {
        let (_, (dim, tag)) = s.mesh_get_node(n)?;
        if dim == 2 && !faces.iter().any(|f| f.2 == tag) {
            surfaces.insert(tag);
        }
    }
    for tag in surfaces {
        if remove_cap(s, req, vol, tet, el, (tag, None), old)? {
            return Ok(true);
        }
    }
    Ok(false)
}

/// Angle of the blank's seam: opposite the circular mean of the refined teeth.
fn seam_angle(req: &MeshRequest) -> f64 {
    let z = req.geom.data.member(req.member).teeth as f64;
    let pitch = 2.0 * std::f64::consts::PI / z;
    let (sx, sy) = req.refined_teeth.iter().fold((0.0, 0.0), |(x, y), &k| {
        (x + (k as f64 * pitch).cos(), y + (k as f64 * pitch).sin())
    });
    let base = req
        .geom
        .flank(req.member, req.side)
        .at(req.geom.data.mean_cone_distance, 0.0)
        .map(|p| p.pos[1].atan2(p.pos[0]))
        .unwrap_or(0.0);
    if sx == 0.0 && sy == 0.0 {
        0.0
    } else {
        base + sy.atan2(sx) + std::f64::consts::PI
    }
}

/// Rejects blank dimensions whose half-section is not a simple polygon off
/// the axis (bore or hub wider than the body, web outside the rim).
fn check_blank(req: &MeshRequest, shape: &BlankShape) -> Result<(), MeshError> {
    let p = &shape.polygon;
    let n = p.len();
    let cross = |a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]| {
        let o = |p: [f64; 2], q: [f64; 2], r: [f64; 2]| {
            (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        };
        o(a, b, c) * o(a, b, d) < 0.0 && o(c, d, a) * o(c, d, b) < 0.0
    };
    let simple = (0..n).all(|i| {
        (i + 2..n)
            .all(|j| (i == 0 && j == n - 1) || !cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]))
    });
    if simple && p.iter().all(|q| q[1] > 0.0) && revolution_volume_signed(p).abs() > 0.0 {
        return Ok(());
    }
    let (field, value) = match req.member {
        Member::Pinion => (
            "blank_dimensions.pinion_bore_radius_mm",
            req.dims.pinion_bore_radius,
        ),
        Member::Wheel => (
            "blank_dimensions.wheel_hub_radius_mm",
            req.dims.wheel_hub_radius,
        ),
    };
    Err(other_err(
        req,
        format!(
            "{field} = {}: the blank half-section crosses itself; the bore and hub must stay inside the body (rim bottom radius at the toe {:.1} mm)",
            value * 1e3,
            p[0][1] * 1e3
        ),
    ))
}

/// Twice the signed area of the polygon in (z, ρ).
fn revolution_volume_signed(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|i| p[i][0] * p[(i + 1) % n][1] - p[(i + 1) % n][0] * p[i][1])
        .sum()
}

/// Builds, meshes and writes one member. `out` is the `.msh` path; the file is
/// written to a temporary name and renamed, so nothing partial remains.
pub fn mesh_member(req: &MeshRequest, out: &Path) -> Result<MeshReport, MeshError> {
    let t0 = Instant::now();
    let shape = blank_shape(&req.geom.data, req.member, req.blank, req.dims);
    check_blank(req, &shape)?;
    let s = Session::new().map_err(|e| gmsh_err(req, e))?;
    let g = |e| gmsh_err(req, e);
    s.option_set_number("General.NumThreads", 1.0).map_err(g)?;
    s.option_set_number("Geometry.OCCParallel", 1.0)
        .map_err(g)?;
    s.add_model(&format!("{}_{}", req.scene, req.member.name()))
        .map_err(g)?;
    let shape = blank_shape(&req.geom.data, req.member, req.blank, req.dims);
    let blank = add_blank(&s, &shape).map_err(g)?;
    // The revolved blank's seam splits the faces it crosses: turn it away
    // from the refined teeth so that their flanks stay four-sided.
    s.occ_rotate(&[blank], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, seam_angle(req))
        .map_err(g)?;
    s.occ_synchronize().map_err(g)?;
    let blank_volume_occ = s.occ_get_mass(3, blank.1).map_err(g)?;
    let slot = add_slot(&s, req)?;
    let z = req.geom.data.member(req.member).teeth as usize;
    let pitch = 2.0 * std::f64::consts::PI / z as f64;
    let mut tools = vec![slot];
    for k in 1..z {
        let c = s.occ_copy(&[slot]).map_err(g)?;
        s.occ_rotate(&c, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, pitch * k as f64)
            .map_err(g)?;
        tools.extend(c);
    }
    if let Some(h) = &shape.holes {
        for k in 0..h.count {
            let a = 2.0 * std::f64::consts::PI * k as f64 / h.count as f64;
            let c = s
                .occ_add_cylinder(
                    h.circle_radius * a.cos(),
                    h.circle_radius * a.sin(),
                    h.z[0],
                    0.0,
                    0.0,
                    h.z[1] - h.z[0],
                    0.5 * h.diameter,
                )
                .map_err(g)?;
            tools.push((3, c));
        }
    }
    let t_cut = Instant::now();
    let (body, _) = s.occ_cut(&[blank], &tools, true, true).map_err(g)?;
    s.occ_synchronize().map_err(g)?;
    let time_cut = t_cut.elapsed().as_secs_f64();
    let mut vols: Vec<i32> = body.iter().filter(|d| d.0 == 3).map(|d| d.1).collect();
    // A piece of the blank the slots left apart from the body would float
    // free in the FE model (and broke the periodic sectors' meshing).
    if vols.len() != 1 {
        let volumes = vols
            .iter()
            .map(|&t| s.occ_get_mass(3, t))
            .collect::<gmsh::Result<Vec<f64>>>()
            .map_err(g)?;
        return Err(other_err(
            req,
            format!(
                "cutting the slots left {} solids (volumes {volumes:?} m³), not one body",
                vols.len()
            ),
        ));
    }
    if !req.periodic_teeth.is_empty() {
        vols = split_at_periodic_slots(&s, req, &shape, &vols)?;
    }
    let occ_volume: f64 = vols
        .iter()
        .map(|&t| s.occ_get_mass(3, t))
        .sum::<gmsh::Result<f64>>()
        .map_err(g)?;

    // Physical groups.
    let mut bore = Vec::new();
    let mut holes = Vec::new();
    let mut flanks: std::collections::BTreeMap<(usize, &'static str), Vec<i32>> =
        Default::default();
    let mut flank_faces = Vec::new();
    for (_, tag) in s.get_entities(2).map_err(g)? {
        match classify(&s, req, &shape, tag)? {
            Face::Bore => bore.push(tag),
            Face::Hole => holes.push(tag),
            Face::Flank { tooth, side } => {
                flank_faces.push((tooth, side, tag));
                flanks
                    .entry((tooth, side.flank_name(req.member)))
                    .or_default()
                    .push(tag)
            }
            Face::Other => {}
        }
    }
    let mut groups = Vec::new();
    let mut add = |dim: i32, tags: &[i32], name: String| -> Result<(), MeshError> {
        if !tags.is_empty() {
            let t = s
                .add_physical_group(dim, tags, -1, &name)
                .map_err(|e| gmsh_err(req, e))?;
            groups.push((dim, t, name));
        }
        Ok(())
    };
    add(3, &vols, "body".into())?;
    add(2, &bore, "bore".into())?;
    add(2, &holes, "holes".into())?;
    for ((tooth, flank), tags) in &flanks {
        add(2, tags, format!("tooth{tooth}_{flank}"))?;
    }
    let hole_angles_deg = holes
        .iter()
        .map(|&t| {
            let c = s.occ_get_center_of_mass(2, t).map_err(g)?;
            Ok(c[1].atan2(c[0]).to_degrees().rem_euclid(360.0))
        })
        .collect::<Result<Vec<f64>, MeshError>>()?;

    // Sizes: structured loaded flanks on the refined teeth, growth away from them.
    let d = &req.geom.data;
    let loaded = req.side.flank_name(req.member);
    let opposite = req.side.other().flank_name(req.member);
    let mut refined = Vec::new();
    let mut refined_tags = Vec::new();
    let mut edge_faces = Vec::new();
    let wanted = req
        .refined_teeth
        .iter()
        .map(|&t| (t, loaded))
        .chain(req.opposite_refined_teeth.iter().map(|&t| (t, opposite)));
    for (tooth, name) in wanted {
        let Some(tags) = flanks.get(&(tooth, name)) else {
            continue;
        };
        for &tag in tags {
            let curves = s
                .get_boundary(&[(2, tag)], false, false, false)
                .map_err(g)?;
            if curves.len() != 4 {
                continue;
            }
            for &(_, c) in &curves {
                let c = c.abs();
                let along_face = curve_span(&s, req, c).map_err(g)? > 0.5 * d.face_width;
                if along_face {
                    // The root fillet and top land along this flank.
                    let (up, _) = s.get_adjacencies(1, c).map_err(g)?;
                    edge_faces.extend(up.into_iter().filter(|&f| f != tag));
                }
                let n = if along_face {
                    req.level.face
                } else {
                    req.level.profile
                };
                s.mesh_set_transfinite_curve(c, n as i32 + 1, "Progression", 1.0)
                    .map_err(g)?;
            }
            s.mesh_set_transfinite_surface(tag, "Left", &[])
                .map_err(g)?;
            refined_tags.push((tooth, name, tag, curves));
        }
    }
    // Away from the refined flanks the body only has to carry the load path:
    // 1.5 m_n keeps the FE compliance solve near 0.25 M dofs per member.
    let coarse = 1.5 * d.normal_module;
    let fine = (d.face_width / req.level.face as f64)
        .min(d.normal_module * 2.2 / req.level.profile as f64);
    s.option_set_number("Mesh.MeshSizeMax", coarse).map_err(g)?;
    s.option_set_number("Mesh.MeshSizeMin", 0.2 * fine)
        .map_err(g)?;
    if !refined_tags.is_empty() {
        let flanks: Vec<i32> = refined_tags.iter().map(|r| r.2).collect();
        let th = size_near(&s, &flanks, fine, coarse, 4.0 * d.normal_module).map_err(g)?;
        // Fillets and top lands of the refined flanks: elements small enough
        // to follow the fillet radius, so their curved mid-edge nodes (shared
        // with the flank) need no straightening.
        let edge_size = (0.8 * d.edge_radius).min(fine);
        let th2 =
            size_near(&s, &edge_faces, edge_size, coarse, 2.0 * d.normal_module).map_err(g)?;
        let min = s.mesh_field_add("Min").map_err(g)?;
        s.mesh_field_set_numbers(min, "FieldsList", &[th as f64, th2 as f64])
            .map_err(g)?;
        s.mesh_field_set_as_background_mesh(min).map_err(g)?;
    }
    s.option_set_number("Mesh.MeshSizeExtendFromBoundary", 0.0)
        .map_err(g)?;
    s.option_set_number("Mesh.MeshSizeFromPoints", 0.0)
        .map_err(g)?;
    // No curvature-driven sizes: they refined the fillets of every tooth
    // (3× the nodes). Coarse curved tets that would invert on the fillets of
    // unloaded teeth are straightened instead (reported).
    s.option_set_number("Mesh.MeshSizeFromCurvature", 0.0)
        .map_err(g)?;
    s.option_set_number("Mesh.Algorithm", 6.0).map_err(g)?;
    // gmsh integrates the size field along each curve to 1e-9 by default;
    // 1e-5 changes the node counts by 0.1–0.3 % and cuts the 1-D meshing of
    // every curve of every tooth from 3–3.6 s to about 0.5 s per member.
    s.option_set_number("Mesh.LcIntegrationPrecision", 1e-5)
        .map_err(g)?;
    let sectors = periodic_sectors(&s, req, &flank_faces)?;
    let periodic_faces = if sectors.len() > 1 {
        set_periodic_faces(&s, &sectors, z, SECTOR_FACE_TOLERANCE)
            .map_err(|e| other_err(req, e.to_string()))?
    } else {
        0
    };
    let time_geometry = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let mut algorithm_3d = "Delaunay";
    let mut fallback_used = false;
    s.option_set_number("Mesh.Algorithm3D", 1.0).map_err(g)?;
    if s.mesh_generate(3).is_err() {
        s.mesh_clear().map_err(g)?;
        s.option_set_number("Mesh.Algorithm3D", 4.0).map_err(g)?;
        algorithm_3d = "Frontal";
        fallback_used = true;
        s.mesh_generate(3).map_err(g)?;
    }
    if sectors.len() > 1 {
        copy_master_tets(&s, &sectors, z, SECTOR_NODE_TOLERANCE)
            .map_err(|e| other_err(req, e.to_string()))?;
    }
    let time_generate = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    s.mesh_set_order(2).map_err(g)?;
    if sectors.len() > 1 {
        align_mid_edge_nodes(&s, &sectors, z, SECTOR_NODE_TOLERANCE)
            .map_err(|e| other_err(req, e.to_string()))?;
    }
    let time_order2 = t2.elapsed().as_secs_f64();
    let t3 = Instant::now();
    let straightened = straighten_inverted(&s).map_err(g)?;
    let snap = snap_to_flanks(&s, req, &flank_faces).map_err(g)?;
    let time_snap = t3.elapsed().as_secs_f64();
    let periodic_copy_deviation = if sectors.len() > 1 {
        copy_deviation(&s, &sectors, z).map_err(|e| other_err(req, e.to_string()))?
    } else {
        0.0
    };
    let time_mesh = t1.elapsed().as_secs_f64();

    let (mesh_volume, tets, nodes) = mesh_volume(&s).map_err(g)?;
    let (etypes, etags, _) = s.mesh_get_elements(3, -1).map_err(g)?;
    let tet_tags: Vec<usize> = etypes
        .iter()
        .zip(&etags)
        .filter(|(t, _)| **t == 11)
        .flat_map(|(_, v)| v.iter().copied())
        .collect();
    let q = s
        .mesh_get_element_qualities(&tet_tags, "minSICN")
        .map_err(g)?;
    let qmin = q.iter().copied().fold(f64::INFINITY, f64::min);
    let qmean = q.iter().sum::<f64>() / q.len().max(1) as f64;
    for (tooth, name, tag, curves) in &refined_tags {
        let mut prof = Vec::new();
        let mut face = Vec::new();
        for &(_, c) in curves {
            let n = elements_on_curve(&s, c.abs()).map_err(g)?;
            if curve_span(&s, req, c.abs()).map_err(g)? > 0.5 * d.face_width {
                face.push(n);
            } else {
                prof.push(n);
            }
        }
        refined.push(RefinedFlank {
            tooth: *tooth,
            flank: name.to_string(),
            surface: *tag,
            elements_profile: prof.iter().copied().max().unwrap_or(0),
            elements_face: face.iter().copied().max().unwrap_or(0),
        });
    }

    // Write atomically.
    let dir = out.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)
        .map_err(|e| other_err(req, format!("cannot create {}: {e}", dir.display())))?;
    let tmp: PathBuf = dir.join(format!(
        ".{}.tmp.msh",
        out.file_stem().and_then(|x| x.to_str()).unwrap_or("mesh")
    ));
    s.option_set_number("Mesh.MshFileVersion", 4.1).map_err(g)?;
    s.option_set_number("Mesh.Binary", 0.0).map_err(g)?;
    s.write(&tmp).map_err(g)?;
    std::fs::rename(&tmp, out)
        .map_err(|e| other_err(req, format!("cannot rename {}: {e}", tmp.display())))?;

    Ok(MeshReport {
        scene: req.scene.to_string(),
        member: req.member.name().to_string(),
        blank: req.blank,
        level: req.level_name.to_string(),
        requested: req.level,
        nodes,
        tet10_elements: tets,
        occ_volume_m3: occ_volume,
        mesh_volume_m3: mesh_volume,
        blank_volume_occ_m3: blank_volume_occ,
        blank_volume_analytic_m3: revolution_volume(&shape.polygon),
        quality_min_sicn: qmin,
        quality_mean_sicn: qmean,
        straightened_nodes: straightened,
        snapped_nodes: snap.moved,
        snap_max_move_um: snap.max_move * 1e6,
        unsnapped_nodes: snap.kept,
        caps_removed: snap.caps_removed,
        other_caps_removed: snap.other_caps_removed,
        carried_nodes: snap.carried,
        algorithm_3d: algorithm_3d.to_string(),
        fallback_used,
        refined_flanks: refined,
        physical_groups: groups,
        hole_angles_deg,
        periodic_teeth: sectors.iter().map(|x| x.tooth).collect(),
        periodic_faces,
        periodic_copy_deviation_m: periodic_copy_deviation,
        time_geometry_s: time_geometry,
        time_mesh_s: time_mesh,
        time_cut_s: time_cut,
        time_generate_s: time_generate,
        time_order2_s: time_order2,
        time_snap_s: time_snap,
    })
}
