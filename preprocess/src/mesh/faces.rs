//! Which model surface is which: the flanks of each tooth (by their
//! distance from the generated flank and their normal), the bore and the web
//! holes; their physical groups and the angular positions of the holes.

use super::request::{gmsh_err, MeshError, MeshRequest};
use geometry::gear_body::BlankShape;
use geometry::generation::Side;
use gmsh::Session;
use std::collections::BTreeMap;

/// A model face is a flank when its midpoint lies within this distance of
/// the generated flank (the loft's deviation, with margin) and its normal
/// is within about 25° of the flank normal.
const FLANK_FACE_TOLERANCE: f64 = 1e-4;

/// Classification of a model surface.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Face {
    Flank { tooth: usize, side: Side },
    Bore,
    Hole,
    Other,
}

/// What surface `tag` is, from its midpoint, type and normal.
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

/// A flank surface: (tooth, side, surface tag).
pub(super) type FlankFace = (usize, Side, i32);

/// The classified surfaces of the model.
pub(super) struct Faces {
    pub bore: Vec<i32>,
    pub holes: Vec<i32>,
    /// Flank surfaces by (tooth, flank name).
    pub flanks: BTreeMap<(usize, &'static str), Vec<i32>>,
    /// Every flank surface, in the order of the model's surfaces.
    pub flank_faces: Vec<FlankFace>,
}

/// Classifies every surface of the model.
pub(super) fn classify_faces(
    s: &Session,
    req: &MeshRequest,
    shape: &BlankShape,
) -> Result<Faces, MeshError> {
    let mut bore = Vec::new();
    let mut holes = Vec::new();
    let mut flanks: BTreeMap<(usize, &'static str), Vec<i32>> = Default::default();
    let mut flank_faces = Vec::new();
    for (_, tag) in s.get_entities(2).map_err(|e| gmsh_err(req, e))? {
        match classify(s, req, shape, tag)? {
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
    Ok(Faces {
        bore,
        holes,
        flanks,
        flank_faces,
    })
}

/// Physical groups: the body's volumes, the bore, the holes and each
/// tooth's flanks (`tooth{k}_{flank}`); empty groups are left out. Returns
/// (dim, tag, name) of each.
pub(super) fn add_physical_groups(
    s: &Session,
    req: &MeshRequest,
    vols: &[i32],
    faces: &Faces,
) -> Result<Vec<(i32, i32, String)>, MeshError> {
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
    add(3, vols, "body".into())?;
    add(2, &faces.bore, "bore".into())?;
    add(2, &faces.holes, "holes".into())?;
    for ((tooth, flank), tags) in &faces.flanks {
        add(2, tags, format!("tooth{tooth}_{flank}"))?;
    }
    Ok(groups)
}

/// Angular positions of the hole surfaces' centres, degrees in [0, 360).
pub(super) fn hole_angles_deg(
    s: &Session,
    req: &MeshRequest,
    holes: &[i32],
) -> Result<Vec<f64>, MeshError> {
    holes
        .iter()
        .map(|&t| {
            let c = s
                .occ_get_center_of_mass(2, t)
                .map_err(|e| gmsh_err(req, e))?;
            Ok(c[1].atan2(c[0]).to_degrees().rem_euclid(360.0))
        })
        .collect()
}
