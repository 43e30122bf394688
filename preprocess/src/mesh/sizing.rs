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
    /// The four sides in loop order.
    pub sides: Vec<Side>,
}

/// A side of a refined flank: whether it runs along the face width, and
/// its curves (more than one where the blank's seam splits it).
pub(super) type Side = (bool, Vec<i32>);

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
            let curves = s.get_boundary(&[(2, tag)], false, true, false).map_err(g)?;
            let Some(sides) = flank_sides(s, req, &curves).map_err(g)? else {
                eprintln!(
                    "{} {:?}: tooth {tooth} {name} flank (surface {tag}) has {} boundary curves that do not form four sides; left unstructured",
                    req.member.name(),
                    req.blank,
                    curves.len()
                );
                continue;
            };
            for (along_face, side) in &sides {
                if *along_face {
                    // The root fillet and top land along this flank.
                    for &c in side {
                        let (up, _) = s.get_adjacencies(1, c).map_err(g)?;
                        edge_faces.extend(up.into_iter().filter(|&f| f != tag));
                    }
                }
                let n = if *along_face {
                    req.level.face
                } else {
                    req.level.profile
                };
                let lengths = side
                    .iter()
                    .map(|&c| curve_chord(s, c))
                    .collect::<gmsh::Result<Vec<f64>>>()
                    .map_err(g)?;
                for (&c, k) in side.iter().zip(split_elements(n as usize, &lengths)) {
                    s.mesh_set_transfinite_curve(c, k as i32 + 1, "Progression", 1.0)
                        .map_err(g)?;
                }
            }
            // Corners only where a seam split a side (four curves: gmsh
            // takes the curves' ends): the point each side shares with the next.
            let corner_points = if curves.len() == 4 {
                Vec::new()
            } else {
                let ends = |c: i32| -> gmsh::Result<Vec<i32>> {
                    Ok(s.get_boundary(&[(1, c)], false, false, false)?
                        .into_iter()
                        .map(|(_, p)| p.abs())
                        .collect())
                };
                let mut pts = Vec::new();
                for i in 0..4 {
                    let a = ends(*sides[i].1.last().unwrap_or(&0)).map_err(g)?;
                    let b = ends(sides[(i + 1) % 4].1[0]).map_err(g)?;
                    if let Some(&p) = a.iter().find(|p| b.contains(p)) {
                        pts.push(p);
                    }
                }
                pts
            };
            s.mesh_set_transfinite_surface(tag, "Left", &corner_points)
                .map_err(g)?;
            faces.push(RefinedFace {
                tooth,
                flank: name,
                surface: tag,
                sides,
            });
        }
    }
    Ok(Refined { faces, edge_faces })
}

/// The sides of a flank face from its oriented boundary loop: each curve
/// runs along the face width when its ends lie further apart in cone
/// distance than half their distance (a profile curve of a bevel tooth
/// stays at nearly one cone distance; a face-width curve is mostly along
/// it, the spiral making it at most 1/cos β longer); consecutive curves of
/// one kind form a side. None unless that gives four sides, alternating.
fn flank_sides(
    s: &Session,
    req: &MeshRequest,
    curves: &[DimTag],
) -> gmsh::Result<Option<Vec<Side>>> {
    let mut sides: Vec<Side> = Vec::new();
    for &(_, c) in curves {
        let c = c.abs();
        let along = curve_span(s, req, c)? > 0.5 * curve_chord(s, c)?;
        match sides.last_mut() {
            Some((kind, list)) if *kind == along => list.push(c),
            _ => sides.push((along, vec![c])),
        }
    }
    // The loop may start inside a side.
    if sides.len() > 1 && sides[0].0 == sides[sides.len() - 1].0 {
        let (_, mut last) = sides.pop().unwrap_or_default();
        last.extend(sides[0].1.iter().copied());
        sides[0].1 = last;
    }
    let alternating = sides.len() == 4 && (0..4).all(|i| sides[i].0 != sides[(i + 1) % 4].0);
    Ok(alternating.then_some(sides))
}

/// `n` elements over curves of chord lengths `lengths` in proportion, at
/// least one each (largest remainders first), summing to `n` when `n` is at
/// least the number of curves.
pub(super) fn split_elements(n: usize, lengths: &[f64]) -> Vec<usize> {
    let total: f64 = lengths.iter().sum();
    if lengths.len() <= 1 || total <= 0.0 {
        return vec![n; lengths.len()];
    }
    let exact: Vec<f64> = lengths.iter().map(|l| n as f64 * l / total).collect();
    let mut k: Vec<usize> = exact.iter().map(|x| (x.floor() as usize).max(1)).collect();
    let mut order: Vec<usize> = (0..k.len()).collect();
    order.sort_by(|&a, &b| (exact[b] - exact[b].floor()).total_cmp(&(exact[a] - exact[a].floor())));
    let mut i = 0;
    while k.iter().sum::<usize>() < n {
        k[order[i % order.len()]] += 1;
        i += 1;
    }
    while k.iter().sum::<usize>() > n {
        let Some(j) = (0..k.len()).filter(|&j| k[j] > 1).max_by_key(|&j| k[j]) else {
            break;
        };
        k[j] -= 1;
    }
    k
}

/// Distance between a curve's two end points, m.
fn curve_chord(s: &Session, curve: i32) -> gmsh::Result<f64> {
    let ends = s.get_boundary(&[(1, curve)], false, false, false)?;
    let mut p = Vec::new();
    for (_, t) in ends {
        p.push(s.get_value(0, t.abs(), &[])?);
    }
    Ok(if p.len() == 2 {
        ((p[0][0] - p[1][0]).powi(2) + (p[0][1] - p[1][1]).powi(2) + (p[0][2] - p[1][2]).powi(2))
            .sqrt()
    } else {
        0.0
    })
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

#[cfg(test)]
mod tests {
    use super::split_elements;

    #[test]
    fn split_side_elements_sum_to_the_side_and_follow_the_lengths() {
        // A face-width side of 20 elements split by the seam at 30 %.
        assert_eq!(split_elements(20, &[3.0, 7.0]), vec![6, 14]);
        // Unsplit side: all of them.
        assert_eq!(split_elements(20, &[5.0]), vec![20]);
        // A sliver still gets one element; the sum stays.
        let k = split_elements(12, &[0.01, 5.0, 4.99]);
        assert_eq!(k.iter().sum::<usize>(), 12);
        assert_eq!(k[0], 1);
        // Largest remainders first: 10 × (1/3, 1/3, 1/3) = 4, 3, 3 in some order.
        let mut k = split_elements(10, &[1.0, 1.0, 1.0]);
        k.sort();
        assert_eq!(k, vec![3, 3, 4]);
    }
}
