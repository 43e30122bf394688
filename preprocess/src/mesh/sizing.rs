//! Element sizes: structured (transfinite) surface meshes on the refined
//! flanks with the requested elements along profile × face width, size
//! fields that grow away from them and their fillets and top lands, and
//! gmsh's global size and algorithm options.

use super::request::{gmsh_err, MeshError, MeshRequest};
use gmsh::{DimTag, Session};
use std::collections::BTreeMap;

/// A refined flank surface with its four boundary curves.
pub(super) struct RefinedFace {
    pub tooth: usize,
    pub flank: &'static str,
    pub surface: i32,
    pub curves: Vec<DimTag>,
}

/// The refined flank surfaces and the surfaces along their edges (root
/// fillets and top lands).
pub(super) struct Refined {
    pub faces: Vec<RefinedFace>,
    pub edge_faces: Vec<i32>,
}

/// Makes the four-sided loaded flanks of the refined teeth (and the
/// opposite flanks of `opposite_refined_teeth`) transfinite: the requested
/// elements along the face width and the profile.
pub(super) fn structure_refined_flanks(
    s: &Session,
    req: &MeshRequest,
    flanks: &BTreeMap<(usize, &'static str), Vec<i32>>,
) -> Result<Refined, MeshError> {
    let g = |e| gmsh_err(req, e);
    let loaded = req.side.flank_name(req.member);
    let opposite = req.side.other().flank_name(req.member);
    let mut faces = Vec::new();
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
                let along_face = runs_along_face(s, req, c).map_err(g)?;
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
            faces.push(RefinedFace {
                tooth,
                flank: name,
                surface: tag,
                curves,
            });
        }
    }
    Ok(Refined { faces, edge_faces })
}

/// Sizes away from the refined flanks and the meshing options.
pub(super) fn set_sizes(
    s: &Session,
    req: &MeshRequest,
    refined: &Refined,
) -> Result<(), MeshError> {
    let g = |e| gmsh_err(req, e);
    let d = &req.geom.data;
    // Away from the refined flanks the body only has to carry the load path:
    // 1.5 m_n keeps the FE compliance solve near 0.25 M dofs per member.
    let coarse = 1.5 * d.normal_module;
    let fine = (d.face_width / req.level.face as f64)
        .min(d.normal_module * 2.2 / req.level.profile as f64);
    s.option_set_number("Mesh.MeshSizeMax", coarse).map_err(g)?;
    s.option_set_number("Mesh.MeshSizeMin", 0.2 * fine)
        .map_err(g)?;
    if !refined.faces.is_empty() {
        let flanks: Vec<i32> = refined.faces.iter().map(|r| r.surface).collect();
        let th = size_near(s, &flanks, fine, coarse, 4.0 * d.normal_module).map_err(g)?;
        // Fillets and top lands of the refined flanks: elements small enough
        // to follow the fillet radius, so their curved mid-edge nodes (shared
        // with the flank) need no straightening.
        let edge_size = (0.8 * d.edge_radius).min(fine);
        let th2 = size_near(
            s,
            &refined.edge_faces,
            edge_size,
            coarse,
            2.0 * d.normal_module,
        )
        .map_err(g)?;
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
    Ok(())
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

/// Whether a curve of a flank runs along the face width (its ends more than
/// half the face width apart in cone distance) rather than along the profile.
pub(super) fn runs_along_face(s: &Session, req: &MeshRequest, curve: i32) -> gmsh::Result<bool> {
    Ok(curve_span(s, req, curve)? > 0.5 * req.geom.data.face_width)
}
