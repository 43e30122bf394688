//! Caps: flat tets over two or three triangles of one surface, which invert
//! once their nodes are snapped onto the curved flank. They are removed and
//! the surface re-triangulated over the tet's other faces.

use super::faces::FlankFace;
use super::request::MeshRequest;
use super::snap::flank_point;
use geometry::generation::Side;
use gmsh::Session;

/// Removes the cap `tet` (nodes `el`) of volume `vol` if two or three of its
/// faces are triangles of surface `tag`: those triangles go, the tet's other
/// faces become the surface's triangles (oriented like the ones they
/// replace; on a `flank` (tooth, side) their nodes are put on the generated
/// flank), and the tet goes.
/// A vertex covered by three cap faces, and the mid-edge nodes of edges no
/// longer used, stay as nodes without elements (the FE reader drops them).
/// Returns false (nothing changed) if `tet` is not such a cap.
pub(super) fn remove_cap(
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
pub(super) fn remove_other_cap(
    s: &Session,
    req: &MeshRequest,
    vol: i32,
    tet: usize,
    el: &[usize; 10],
    faces: &[FlankFace],
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
