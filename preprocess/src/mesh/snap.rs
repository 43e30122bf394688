//! Snapping the flank nodes of the finished mesh onto the generated flank
//! (the lofted slot follows it only to a few µm), with the repairs that keep
//! every tet valid: caps removed ([`super::caps`]), slivers carried along,
//! moves undone where they would still invert a tet.

use super::caps::{remove_cap, remove_other_cap};
use super::faces::FlankFace;
use super::request::MeshRequest;
use geometry::generation::Side;
use gmsh::Session;

/// Largest normal distance of a flank-group node that [`snap_to_flanks`]
/// moves: loft errors are µm, straightened mid-edge nodes of coarse teeth
/// ~0.15 mm; a node farther off is not on the generated flank (the face
/// reaches into the top land or toe at the blank's seam) and stays.
const MAX_SNAP: f64 = 0.5e-3;

/// A tet whose min SICN after snapping is at or below this is checked for
/// being a cap ([`remove_cap`]).
const CAP_QUALITY: f64 = 1e-3;

/// Snap moves are µm, so they may lower the quality of a tet that was poor
/// already (min SICN 1.7e-3 → 6e-4 on one tet of the reduced-level pinion)
/// but not below this floor: min SICN > 0 keeps the Jacobian positive at
/// every point, and the floor keeps a margin. A move that goes below it is
/// undone.
const SNAP_MIN_QUALITY: f64 = 1e-4;

/// What [`snap_to_flanks`] did.
pub(super) struct Snap {
    pub moved: usize,
    pub max_move: f64,
    pub kept: usize,
    pub caps_removed: usize,
    pub other_caps_removed: usize,
    /// Interior nodes moved along with a poor tet's snapped nodes ([`carry`]).
    pub carried: usize,
}

/// The point of `side`'s generated flank of `tooth` at `p`'s axial-section
/// coordinates (L, d), reached by three steps along the flank normal; `None`
/// when the flank has no point there or `p` lies farther than [`MAX_SNAP`]
/// from it (a sliver of the top land or toe cut into the flank face).
pub(super) fn flank_point(
    req: &MeshRequest,
    tooth: usize,
    side: Side,
    p: [f64; 3],
) -> Option<[f64; 3]> {
    let f = req.geom.flank(req.member, side);
    let z = req.geom.data.member(req.member).teeth as f64;
    let (sa, ca) = (tooth as f64 * 2.0 * std::f64::consts::PI / z).sin_cos();
    // Tooth-0 frame; three steps converge to well below 1 nm.
    let mut r = [ca * p[0] + sa * p[1], -sa * p[0] + ca * p[1], p[2]];
    for step in 0..3 {
        let (l, d) = f.gen.frame.axial(&r);
        let q = f.at(l, d).ok()?;
        let dist: f64 = (0..3).map(|i| (r[i] - q.pos[i]) * q.normal[i]).sum();
        if step == 0 && dist.abs() > MAX_SNAP {
            return None;
        }
        for (ri, ni) in r.iter_mut().zip(q.normal) {
            *ri -= dist * ni;
        }
    }
    Some([ca * r[0] - sa * r[1], sa * r[0] + ca * r[1], r[2]])
}

/// The lofted slot follows the generated flank only to about 0.5 µm (more
/// near the fillet junction), and the TE is measured in fractions of a µm.
/// So every node of a flank surface (vertex and mid-edge, boundary included)
/// is moved onto the generated flank at its own axial-section coordinates
/// (L, d) ([`flank_point`]); loft errors are a few µm, straightened mid-edge
/// nodes of coarse teeth ~0.2 mm.
///
/// A tet whose four vertices all lie on one flank and which covers two or
/// three of its surface triangles (a *cap*: a flat tet over a surface vertex
/// of valence 3, or over an edge) has almost no volume, and on the exact
/// curved flank it inverts. Such caps are removed ([`remove_cap`]), and so
/// are caps on a fillet that a snapped flank edge inverts
/// ([`remove_other_cap`]). A sliver the snap inverts otherwise is translated
/// with its snapped nodes ([`carry`]). Any move that still takes a tet below
/// [`SNAP_MIN_QUALITY`] is undone, node by node of the bad tets.
pub(super) fn snap_to_flanks(
    s: &Session,
    req: &MeshRequest,
    faces: &[FlankFace],
) -> gmsh::Result<Snap> {
    let mut old: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
    let mut max_move: f64 = 0.0;
    let mut kept = std::collections::BTreeSet::new();
    // Flank face of each flank node (the first one, for shared edges).
    let mut face_of: std::collections::BTreeMap<usize, usize> = Default::default();
    for (fi, &(tooth, side, tag)) in faces.iter().enumerate() {
        let (tags, xyz, _) = s.mesh_get_nodes(2, tag, true, false)?;
        for (&t, p) in tags.iter().zip(xyz.chunks(3)) {
            face_of.entry(t).or_insert(fi);
            if old.contains_key(&t) || kept.contains(&t) {
                continue;
            }
            let p = [p[0], p[1], p[2]];
            let Some(x) = flank_point(req, tooth, side, p) else {
                kept.insert(t);
                continue;
            };
            let mv = (0..3).map(|i| (x[i] - p[i]).powi(2)).sum::<f64>().sqrt();
            max_move = max_move.max(mv);
            old.insert(t, p);
            s.mesh_set_node(t, x)?;
        }
    }
    let mut caps_removed = 0;
    let mut other_caps_removed = 0;
    // Interior nodes carried along with a poor tet's snapped nodes: node →
    // (position before, the tet that carried it).
    let mut carried: std::collections::BTreeMap<usize, ([f64; 3], usize)> = Default::default();
    let mut carry_tried = std::collections::BTreeSet::new();
    // Remove caps; carry the interior nodes of other poor tets along with
    // their snapped nodes; undo the moves where that fails too.
    for _ in 0..8 {
        let mut changed = false;
        for (_, vol) in s.get_entities(3)? {
            let (types, etags, enodes) = s.mesh_get_elements(3, vol)?;
            let Some(i) = types.iter().position(|&t| t == 11) else {
                continue;
            };
            let q = s.mesh_get_element_qualities(&etags[i], "minSICN")?;
            for (k, &qk) in q.iter().enumerate().filter(|(_, &v)| v <= CAP_QUALITY) {
                let tet = etags[i][k];
                let el: [usize; 10] = std::array::from_fn(|j| enodes[i][10 * k + j]);
                let fi = face_of.get(&el[0]).copied();
                let on_one_flank =
                    fi.is_some() && el[..4].iter().all(|n| face_of.get(n).copied() == fi);
                if let (true, Some(fi)) = (on_one_flank, fi) {
                    let (tooth, side, tag) = faces[fi];
                    if remove_cap(s, req, vol, tet, &el, (tag, Some((tooth, side))), &mut old)? {
                        caps_removed += 1;
                        changed = true;
                        continue;
                    }
                }
                if qk > SNAP_MIN_QUALITY {
                    continue;
                }
                // A cap on a neighbouring surface (a fillet, whose edge with
                // the flank moved): its nodes stay where gmsh put them.
                if remove_other_cap(s, req, vol, tet, &el, faces, &mut old)? {
                    other_caps_removed += 1;
                    changed = true;
                    continue;
                }
                // A carry that made this tet poor is taken back (its
                // origin is then undone below on the next pass).
                let origins: std::collections::BTreeSet<usize> = el
                    .iter()
                    .filter_map(|n| carried.get(n).map(|c| c.1))
                    .collect();
                if !origins.is_empty() {
                    let back: Vec<usize> = carried
                        .iter()
                        .filter(|(_, c)| origins.contains(&c.1))
                        .map(|(&n, _)| n)
                        .collect();
                    for n in back {
                        let (p, _) = carried.remove(&n).expect("listed above");
                        s.mesh_set_node(n, p)?;
                    }
                    changed = true;
                    continue;
                }
                if carry_tried.insert(tet) {
                    let skip = |n: &usize| face_of.contains_key(n) || carried.contains_key(n);
                    if let Some(moves) = carry(s, &el, &old, skip)? {
                        for (n, p) in moves {
                            carried.insert(n, (p, tet));
                        }
                        changed = true;
                        continue;
                    }
                }
                for n in &el {
                    if let Some(p) = old.remove(n) {
                        s.mesh_set_node(*n, p)?;
                        kept.insert(*n);
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    Ok(Snap {
        moved: old.len(),
        max_move,
        kept: kept.len(),
        caps_removed,
        other_caps_removed,
        carried: carried.len(),
    })
}

/// A node tag and a position of it.
type NodeAt = (usize, [f64; 3]);

/// Moves the nodes of tet `el` for which `skip` is false (flank nodes and
/// nodes carried already are skipped) by the mean snap move of its snapped
/// nodes, so that the tet is translated rather than flattened: a sliver
/// with one vertex on the flank and its other three just inside inverts when that vertex alone moves a few µm, while the
/// well-shaped tets around its interior nodes hardly notice the same µm.
/// Returns the nodes moved with their old positions, or `None` if the tet
/// has no snapped node or no interior node.
fn carry(
    s: &Session,
    el: &[usize; 10],
    old: &std::collections::BTreeMap<usize, [f64; 3]>,
    skip: impl Fn(&usize) -> bool,
) -> gmsh::Result<Option<Vec<NodeAt>>> {
    let mut d = [0.0; 3];
    let mut snapped = 0;
    for n in el {
        if let Some(p) = old.get(n) {
            let (x, _) = s.mesh_get_node(*n)?;
            for c in 0..3 {
                d[c] += x[c] - p[c];
            }
            snapped += 1;
        }
    }
    let interior: Vec<usize> = el.iter().copied().filter(|n| !skip(n)).collect();
    if snapped == 0 || interior.is_empty() {
        return Ok(None);
    }
    let d = d.map(|v| v / snapped as f64);
    let mut moves = Vec::with_capacity(interior.len());
    for n in interior {
        let (x, _) = s.mesh_get_node(n)?;
        s.mesh_set_node(n, std::array::from_fn(|c| x[c] + d[c]))?;
        moves.push((n, x));
    }
    Ok(Some(moves))
}
