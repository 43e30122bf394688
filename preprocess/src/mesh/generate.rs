//! The volume mesh: gmsh's 3-D meshing (Delaunay, Frontal as fallback), the
//! periodic sectors' tets copied from the master, second order, inverted
//! curved tets straightened, and the flank nodes snapped onto the generated
//! flank ([`super::snap`]); each phase timed.

use super::faces::FlankFace;
use super::request::{gmsh_err, other_err, teeth, MeshError, MeshRequest};
use super::sectors::SECTOR_NODE_TOLERANCE;
use super::snap::{snap_to_flanks, Snap};
use crate::periodic_sectors::{align_mid_edge_nodes, copy_deviation, copy_master_tets, Sector};
use gmsh::Session;
use std::time::Instant;

/// What meshing did and how long it took.
pub(super) struct Generated {
    pub algorithm_3d: &'static str,
    pub fallback_used: bool,
    /// Mid-edge nodes put back on straight edges ([`straighten_inverted`]).
    pub straightened: usize,
    pub snap: Snap,
    /// Largest distance of a copied tet10 node from its master node turned
    /// onto it (m); 0 without periodic sectors.
    pub periodic_copy_deviation: f64,
    /// 1-D to 3-D meshing, second order, straightening + snapping, and all
    /// of it (s).
    pub time_generate: f64,
    pub time_order2: f64,
    pub time_snap: f64,
    pub time_mesh: f64,
}

/// Meshes the model with second-order tets and snaps the flank nodes.
pub(super) fn generate(
    s: &Session,
    req: &MeshRequest,
    sectors: &[Sector],
    flank_faces: &[FlankFace],
) -> Result<Generated, MeshError> {
    let g = |e| gmsh_err(req, e);
    let sector_err = |e: crate::periodic_sectors::SectorError| other_err(req, e.to_string());
    let z = teeth(req);
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
        copy_master_tets(s, sectors, z, SECTOR_NODE_TOLERANCE).map_err(sector_err)?;
    }
    let time_generate = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    s.mesh_set_order(2).map_err(g)?;
    if sectors.len() > 1 {
        align_mid_edge_nodes(s, sectors, z, SECTOR_NODE_TOLERANCE).map_err(sector_err)?;
    }
    let time_order2 = t2.elapsed().as_secs_f64();
    let t3 = Instant::now();
    let straightened = straighten_inverted(s).map_err(g)?;
    let snap = snap_to_flanks(s, req, flank_faces).map_err(g)?;
    let time_snap = t3.elapsed().as_secs_f64();
    let periodic_copy_deviation = if sectors.len() > 1 {
        copy_deviation(s, sectors, z).map_err(sector_err)?
    } else {
        0.0
    };
    let time_mesh = t1.elapsed().as_secs_f64();
    Ok(Generated {
        algorithm_3d,
        fallback_used,
        straightened,
        snap,
        periodic_copy_deviation,
        time_generate,
        time_order2,
        time_snap,
        time_mesh,
    })
}

/// Curved tets along the fillet–root junction can invert when their
/// mid-edge nodes are put on the curved geometry. Their mid-edge nodes go back
/// to the edge midpoints (a straight tet with valid vertices is valid); this
/// is repeated while neighbours are still inverted. Returns the nodes moved.
/// (gmsh's high-order optimiser is not used: it can throw through the C API.)
pub(crate) fn straighten_inverted(s: &Session) -> gmsh::Result<usize> {
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
