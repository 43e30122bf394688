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
//!
//! [`mesh_member`] runs the jobs in order, one module each: the CAD model
//! (`cad`: blank, slots, holes, the cut), the periodic sectors' split and
//! periodic faces (`sectors`), which surface is which and the physical
//! groups (`faces`), the sizes (`sizing`: structured refined flanks, size
//! fields, options), the volume mesh (`generate`), the snap onto the
//! generated flanks (`snap`) with its caps (`caps`), the report (`report`)
//! and the file (`write`). The request and its errors are in `request`.

mod cad;
mod caps;
mod faces;
pub(crate) mod generate;
mod report;
mod request;
mod sectors;
mod sizing;
mod snap;
mod write;

pub use report::{mesh_volume, MeshReport, RefinedFlank};
pub use request::{MeshError, MeshRequest};

use geometry::gear_body::{blank_shape, revolution_volume};
use std::path::Path;
use std::time::Instant;

/// Builds, meshes and writes one member. `out` is the `.msh` path; the file is
/// written to a temporary name and renamed, so nothing partial remains.
pub fn mesh_member(req: &MeshRequest, out: &Path) -> Result<MeshReport, MeshError> {
    let t0 = Instant::now();
    let shape = blank_shape(&req.geom.data, req.member, req.blank, req.dims);
    cad::check_blank(req, &shape)?;
    let s = cad::open_session(req)?;
    let body = cad::cut_body(&s, req, &shape)?;
    let vols = if req.periodic_teeth.is_empty() {
        body.vols
    } else {
        sectors::split_at_periodic_slots(&s, req, &shape, &body.vols)?
    };
    let occ_volume = cad::total_volume(&s, req, &vols)?;

    let faces = faces::classify_faces(&s, req, &shape)?;
    let physical_groups = faces::add_physical_groups(&s, req, &vols, &faces)?;
    let hole_angles_deg = faces::hole_angles_deg(&s, req, &faces.holes)?;

    // Sizes: structured loaded flanks on the refined teeth, growth away from them.
    let refined = sizing::structure_refined_flanks(&s, req, &faces.flanks)?;
    sizing::set_sizes(&s, req, &refined)?;
    let (sectors, periodic_faces) = sectors::set_periodic(&s, req, &faces.flank_faces)?;
    let time_geometry = t0.elapsed().as_secs_f64();

    let mesh = generate::generate(&s, req, &sectors, &faces.flank_faces)?;
    let stats = report::stats(&s, req)?;
    let refined_flanks = report::refined_flanks(&s, req, &refined.faces)?;
    write::write_msh(&s, req, out)?;

    Ok(MeshReport {
        scene: req.scene.to_string(),
        member: req.member.name().to_string(),
        blank: req.blank,
        level: req.level_name.to_string(),
        requested: req.level,
        nodes: stats.nodes,
        tet10_elements: stats.tets,
        occ_volume_m3: occ_volume,
        mesh_volume_m3: stats.volume,
        blank_volume_occ_m3: body.blank_volume_occ,
        blank_volume_analytic_m3: revolution_volume(&shape.polygon),
        quality_min_sicn: stats.quality_min,
        quality_mean_sicn: stats.quality_mean,
        straightened_nodes: mesh.straightened,
        snapped_nodes: mesh.snap.moved,
        snap_max_move_um: mesh.snap.max_move * 1e6,
        unsnapped_nodes: mesh.snap.kept,
        caps_removed: mesh.snap.caps_removed,
        other_caps_removed: mesh.snap.other_caps_removed,
        carried_nodes: mesh.snap.carried,
        algorithm_3d: mesh.algorithm_3d.to_string(),
        fallback_used: mesh.fallback_used,
        refined_flanks,
        physical_groups,
        hole_angles_deg,
        periodic_teeth: sectors.iter().map(|x| x.tooth).collect(),
        periodic_faces,
        periodic_copy_deviation_m: mesh.periodic_copy_deviation,
        time_geometry_s: time_geometry,
        time_mesh_s: mesh.time_mesh,
        reused: false,
        time_cut_s: body.time_cut,
        time_generate_s: mesh.time_generate,
        time_order2_s: mesh.time_order2,
        time_snap_s: mesh.time_snap,
    })
}
