//! The mesh report written next to the mesh ([`MeshReport`]) and what it
//! measures on the finished mesh: tet10 volume, node and element counts,
//! element quality, and the elements achieved along the refined flanks.

use super::request::{gmsh_err, MeshError, MeshRequest};
use super::sizing::RefinedFace;
use geometry::scene::{Blank, FlankElements};
use gmsh::Session;
use serde::Serialize;

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
    /// Flank-group nodes moved onto the generated flank
    /// ([`snap_to_flanks`](super::snap::snap_to_flanks)),
    /// the largest move (µm), and nodes left where gmsh put them (their move
    /// would have inverted a tet, or the flank has no point at their (L, d)).
    pub snapped_nodes: usize,
    pub snap_max_move_um: f64,
    pub unsnapped_nodes: usize,
    /// Flat tets over a flank's surface triangles removed before snapping
    /// ([`remove_cap`](super::caps::remove_cap)); their unused nodes stay in the
    /// file, unreferenced.
    #[serde(default)]
    pub caps_removed: usize,
    /// Caps on a surface next to a flank (a fillet) that its snapped flank
    /// edge would have inverted, removed the same way
    /// ([`remove_other_cap`](super::caps::remove_other_cap)).
    #[serde(default)]
    pub other_caps_removed: usize,
    /// Interior nodes moved by a few µm along with the snapped vertex of a
    /// sliver tet that the snap alone would have inverted
    /// ([`carry`](super::snap::carry)).
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
    /// Whether this run reused the mesh (inputs unchanged): the times are
    /// then those of the run that made it. Not written to the file.
    #[serde(skip)]
    pub reused: bool,
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

/// Size and quality of the finished mesh.
pub(super) struct Stats {
    /// Sum of the tet10 volumes (m³).
    pub volume: f64,
    pub tets: usize,
    /// Nodes the tets use.
    pub nodes: usize,
    /// Smallest and mean min SICN of the tets.
    pub quality_min: f64,
    pub quality_mean: f64,
}

/// Volume, counts and quality of the current mesh.
pub(super) fn stats(s: &Session, req: &MeshRequest) -> Result<Stats, MeshError> {
    let g = |e| gmsh_err(req, e);
    let (volume, tets, nodes) = mesh_volume(s).map_err(g)?;
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
    let quality_min = q.iter().copied().fold(f64::INFINITY, f64::min);
    let quality_mean = q.iter().sum::<f64>() / q.len().max(1) as f64;
    Ok(Stats {
        volume,
        tets,
        nodes,
        quality_min,
        quality_mean,
    })
}

/// The elements achieved along the profile and the face width of each
/// refined flank face (the most on any of its curves in either direction).
pub(super) fn refined_flanks(
    s: &Session,
    req: &MeshRequest,
    faces: &[RefinedFace],
) -> Result<Vec<RefinedFlank>, MeshError> {
    let g = |e| gmsh_err(req, e);
    let mut refined = Vec::new();
    for f in faces {
        let mut prof = Vec::new();
        let mut face = Vec::new();
        for (along_face, side) in &f.sides {
            let mut n = 0;
            for &c in side {
                n += elements_on_curve(s, c).map_err(g)?;
            }
            if *along_face {
                face.push(n);
            } else {
                prof.push(n);
            }
        }
        refined.push(RefinedFlank {
            tooth: f.tooth,
            flank: f.flank.to_string(),
            surface: f.surface,
            elements_profile: prof.iter().copied().max().unwrap_or(0),
            elements_face: face.iter().copied().max().unwrap_or(0),
        });
    }
    Ok(refined)
}
