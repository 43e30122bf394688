//! Periodic sectors of a standard blank in the CAD model: the cut body split
//! along the middle of the slots either side of the periodic teeth, each
//! tooth's sector found by its loaded flank, and their faces set periodic
//! (the mesh side is [`crate::periodic_sectors`]).

use super::cad::slot_loft_sections;
use super::faces::FlankFace;
use super::request::{gmsh_err, other_err, teeth, MeshError, MeshRequest};
use crate::periodic_sectors::{
    add_slot_surface, polar_extent, set_periodic_faces, slot_centre, split, Sector,
};
use geometry::gear_body::BlankShape;
use gmsh::{DimTag, Session};

/// Distance within which the centre of a periodic sector's face turned onto
/// the master sector counts as the master face's (m): OCC's mass properties
/// of copies differ by ~0.2 µm; distinct faces are millimetres apart.
const SECTOR_FACE_TOLERANCE: f64 = 1e-5;

/// Distance within which a master node turned onto a periodic sector
/// counts as the sector's boundary node (m): gmsh puts a periodic copy's
/// nodes on the copied face's geometry, which OCC's boolean pieces hold only
/// to about the 0.2 µm their face centres differ by; distinct nodes are
/// ≥ 10 µm apart.
pub(super) const SECTOR_NODE_TOLERANCE: f64 = 2e-6;

/// Splits the cut body along the middle of the slots on either side of the
/// periodic teeth. Returns the volumes.
pub(super) fn split_at_periodic_slots(
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
    flank_faces: &[FlankFace],
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

/// The periodic teeth's sectors (master first) and the number of their
/// faces set periodic; no sectors and no faces without periodic teeth.
pub(super) fn set_periodic(
    s: &Session,
    req: &MeshRequest,
    flank_faces: &[FlankFace],
) -> Result<(Vec<Sector>, usize), MeshError> {
    let sectors = periodic_sectors(s, req, flank_faces)?;
    let periodic_faces = if sectors.len() > 1 {
        set_periodic_faces(s, &sectors, teeth(req), SECTOR_FACE_TOLERANCE)
            .map_err(|e| other_err(req, e.to_string()))?
    } else {
        0
    };
    Ok((sectors, periodic_faces))
}
