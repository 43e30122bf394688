//! The CAD model of a member with the gmsh OpenCASCADE API: the blank (a
//! half-section revolved about z, its seam turned away from the refined
//! teeth), the slot loft of tooth space 0 copied to every tooth, the
//! lightweight wheel's web holes, and the boolean cut that leaves one body.

use super::request::{geometry_err, gmsh_err, other_err, teeth, MeshError, MeshRequest};
use geometry::design::Member;
use geometry::gear_body::{slot_sections, BlankShape, SlotSection};
use gmsh::{DimTag, Session};
use std::time::Instant;

/// Sections of the slot loft. Four sections follow the generated flank to
/// about 16 µm (five: 25 µm at the fillet junction) and the boolean cut
/// takes about two thirds of five's time; three are faster still but 150 µm
/// off. The flank nodes are snapped onto the generated flank after meshing.
const SLOT_SECTIONS: usize = 4;

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
pub(super) fn slot_loft_sections(req: &MeshRequest) -> Result<Vec<SlotSection>, MeshError> {
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
pub(super) fn check_blank(req: &MeshRequest, shape: &BlankShape) -> Result<(), MeshError> {
    let p = &shape.polygon;
    if shape.is_body() {
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

/// A gmsh session with one thread, OCC's parallel booleans and a model named
/// after the scene and member.
pub(super) fn open_session(req: &MeshRequest) -> Result<Session, MeshError> {
    let s = Session::new().map_err(|e| gmsh_err(req, e))?;
    let g = |e| gmsh_err(req, e);
    s.option_set_number("General.NumThreads", 1.0).map_err(g)?;
    s.option_set_number("Geometry.OCCParallel", 1.0)
        .map_err(g)?;
    s.add_model(&format!("{}_{}", req.scene, req.member.name()))
        .map_err(g)?;
    Ok(s)
}

/// The body the slots and holes were cut out of.
pub(super) struct Body {
    /// Its one volume.
    pub vols: Vec<i32>,
    /// Volume of the blank before the cut (OCC, m³).
    pub blank_volume_occ: f64,
    /// Time of the boolean cut (s).
    pub time_cut: f64,
}

/// Builds the blank, cuts every tooth's slot and the web holes out of it and
/// checks that one body is left.
pub(super) fn cut_body(
    s: &Session,
    req: &MeshRequest,
    shape: &BlankShape,
) -> Result<Body, MeshError> {
    let g = |e| gmsh_err(req, e);
    let blank = add_blank(s, shape).map_err(g)?;
    // The revolved blank's seam splits the faces it crosses: turn it away
    // from the refined teeth so that their flanks stay four-sided.
    s.occ_rotate(&[blank], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, seam_angle(req))
        .map_err(g)?;
    s.occ_synchronize().map_err(g)?;
    let blank_volume_occ = s.occ_get_mass(3, blank.1).map_err(g)?;
    let tools = cutting_tools(s, req, shape)?;
    let t_cut = Instant::now();
    let (body, _) = s.occ_cut(&[blank], &tools, true, true).map_err(g)?;
    s.occ_synchronize().map_err(g)?;
    let time_cut = t_cut.elapsed().as_secs_f64();
    let vols: Vec<i32> = body.iter().filter(|d| d.0 == 3).map(|d| d.1).collect();
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
    Ok(Body {
        vols,
        blank_volume_occ,
        time_cut,
    })
}

/// The tools cut out of the blank: the slot of tooth space 0 and its copies
/// turned to every other tooth space, then the web holes (if any).
fn cutting_tools(
    s: &Session,
    req: &MeshRequest,
    shape: &BlankShape,
) -> Result<Vec<DimTag>, MeshError> {
    let g = |e| gmsh_err(req, e);
    let slot = add_slot(s, req)?;
    let z = teeth(req);
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
    Ok(tools)
}

/// Sum of the OCC volumes of `vols` (m³).
pub(super) fn total_volume(s: &Session, req: &MeshRequest, vols: &[i32]) -> Result<f64, MeshError> {
    vols.iter()
        .map(|&t| s.occ_get_mass(3, t))
        .sum::<gmsh::Result<f64>>()
        .map_err(|e| gmsh_err(req, e))
}
