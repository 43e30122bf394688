//! Reads a gear-body mesh (`.msh` 4.1 from the mesh stage) into the FE core's
//! data: tet10 elements and the named tri6 face groups (bore, holes,
//! `tooth{k}_{concave|convex}`, body).

use fem::TetMesh;
use gmsh::Session;
use std::collections::BTreeMap;
use std::path::Path;

/// A meshed gear body.
#[derive(Debug, Clone)]
pub struct BodyMesh {
    pub mesh: TetMesh,
    /// Physical surface groups by name: tri6 faces (node indices, gmsh order).
    pub groups: BTreeMap<String, Vec<[usize; 6]>>,
}

impl BodyMesh {
    /// Faces of the group `name`, or an empty slice.
    pub fn group(&self, name: &str) -> &[[usize; 6]] {
        self.groups.get(name).map_or(&[], |v| v.as_slice())
    }

    /// Distinct nodes of a group, sorted.
    pub fn group_nodes(&self, name: &str) -> Vec<usize> {
        let mut v: Vec<usize> = self.group(name).iter().flatten().copied().collect();
        v.sort_unstable();
        v.dedup();
        v
    }
}

/// Reads `path` with gmsh (one session per process).
pub fn read(path: &Path) -> Result<BodyMesh, String> {
    let ctx = |e: gmsh::GmshError| format!("reading mesh {}: {e}", path.display());
    let s = Session::new().map_err(ctx)?;
    s.open(path).map_err(ctx)?;
    let (tags, coords, _) = s.mesh_get_nodes(-1, -1, false, false).map_err(ctx)?;
    let max = tags.iter().copied().max().unwrap_or(0);
    let mut index = vec![usize::MAX; max + 1];
    for (i, &t) in tags.iter().enumerate() {
        index[t] = i;
    }
    let nodes: Vec<[f64; 3]> = coords.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let map = |t: usize| -> Result<usize, String> {
        index
            .get(t)
            .copied()
            .filter(|&i| i != usize::MAX)
            .ok_or_else(|| {
                format!(
                    "mesh {}: element refers to unknown node {t}",
                    path.display()
                )
            })
    };
    let (types, _, conn) = s.mesh_get_elements(3, -1).map_err(ctx)?;
    let mut tets = Vec::new();
    for (ty, c) in types.iter().zip(&conn) {
        if *ty != 11 {
            return Err(format!(
                "mesh {}: volume element type {ty} found, only 10-node tetrahedra (type 11) are supported",
                path.display()
            ));
        }
        for e in c.chunks(10) {
            let mut t = [0usize; 10];
            for (k, &n) in e.iter().enumerate() {
                t[k] = map(n)?;
            }
            tets.push(t);
        }
    }
    // Nodes no tet uses (left by the mesh stage's cap removal) would be
    // free degrees of freedom: renumber the used ones, in file order.
    let mut used = vec![usize::MAX; nodes.len()];
    for t in &tets {
        for &n in t {
            used[n] = 0;
        }
    }
    let mut kept = Vec::with_capacity(nodes.len());
    for (i, u) in used.iter_mut().enumerate() {
        if *u == 0 {
            *u = kept.len();
            kept.push(nodes[i]);
        }
    }
    let nodes = kept;
    for t in &mut tets {
        for n in t.iter_mut() {
            *n = used[*n];
        }
    }
    let map = |t: usize| -> Result<usize, String> {
        map(t).and_then(|i| {
            Some(used[i]).filter(|&u| u != usize::MAX).ok_or_else(|| {
                format!(
                    "mesh {}: face node {t} belongs to no tetrahedron",
                    path.display()
                )
            })
        })
    };
    let mut groups = BTreeMap::new();
    for (dim, tag) in s.get_physical_groups(2).map_err(ctx)? {
        let name = s.get_physical_name(dim, tag).map_err(ctx)?;
        let mut faces: Vec<[usize; 6]> = Vec::new();
        for ent in s.get_entities_for_physical_group(dim, tag).map_err(ctx)? {
            let (types, _, conn) = s.mesh_get_elements(2, ent).map_err(ctx)?;
            for (ty, c) in types.iter().zip(&conn) {
                if *ty != 9 {
                    continue;
                }
                for e in c.chunks(6) {
                    let mut f = [0usize; 6];
                    for (k, &n) in e.iter().enumerate() {
                        f[k] = map(n)?;
                    }
                    faces.push(f);
                }
            }
        }
        groups.insert(name, faces);
    }
    s.clear().map_err(ctx)?;
    Ok(BodyMesh {
        mesh: TetMesh { nodes, tets },
        groups,
    })
}
