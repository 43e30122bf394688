//! What to mesh ([`MeshRequest`]) and how meshing fails ([`MeshError`]),
//! with the helpers that attach the scene and member to an error.

use geometry::design::Member;
use geometry::error::GeometryError;
use geometry::gear_body::BlankDimensions;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, FlankElements};

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

pub(super) fn gmsh_err(req: &MeshRequest, e: gmsh::GmshError) -> MeshError {
    MeshError::Gmsh {
        scene: req.scene.to_string(),
        member: req.member.name(),
        blank: req.blank,
        source: Box::new(e),
    }
}

pub(super) fn geometry_err(req: &MeshRequest, e: GeometryError) -> MeshError {
    MeshError::Geometry {
        scene: req.scene.to_string(),
        member: req.member.name(),
        source: Box::new(e),
    }
}

pub(super) fn other_err(req: &MeshRequest, message: String) -> MeshError {
    MeshError::Other {
        scene: req.scene.to_string(),
        member: req.member.name(),
        message,
    }
}

/// Number of teeth of the member being meshed.
pub(super) fn teeth(req: &MeshRequest) -> usize {
    req.geom.data.member(req.member).teeth as usize
}
