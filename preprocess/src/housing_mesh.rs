//! The housing of a [`HousingLayout`] meshed with gmsh: each wall a box
//! with its bore cut out and each rib a box, turned about the housing
//! frame's Z onto its shaft, fused with the floor, tet10 of the layout's
//! element size. Nodes
//! come back in the assembly frame with each seat's bore nodes and the
//! clamped feet's nodes.

use fem::TetMesh;
use geometry::housing_layout::{HousingBox, HousingLayout};
use gmsh::{DimTag, Session};
use nalgebra::{Matrix3, Vector3};

/// A meshed housing.
#[derive(Debug, Clone)]
pub struct HousingMesh {
    /// Assembly frame, m.
    pub mesh: TetMesh,
    /// Per wall (layout order): the nodes on its bore.
    pub seats: Vec<Vec<usize>>,
    /// Nodes of the feet (clamped).
    pub feet: Vec<usize>,
    /// Volume of the CAD model, m³ (the mesh's is compared with it).
    pub cad_volume_m3: f64,
    /// Mid-edge nodes put back on their straight edges (inverted curved
    /// tets).
    pub straightened: usize,
}

/// Meshes `l` with elements of about `element_m`.
pub fn mesh(l: &HousingLayout, element_m: f64) -> Result<HousingMesh, String> {
    let g = |e: gmsh::GmshError| format!("housing mesh: {e}");
    let s = Session::new().map_err(g)?;
    s.add_model("housing").map_err(g)?;
    let frame = Matrix3::from_columns(&l.frame.map(Vector3::from));
    // Housing-frame coordinates of an assembly-frame vector.
    let h = |v: [f64; 3]| frame.transpose() * Vector3::from(v);

    // A wall's or rib's axis lies in the housing frame's XY plane at angle
    // ψ from X: its box is built along X (centre turned back by −ψ), then
    // turned by ψ about Z.
    let angle = |b: &HousingBox| {
        let a = h(b.axes[0]);
        a.y.atan2(a.x)
    };
    let back = |psi: f64, p: [f64; 3]| {
        nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), -psi) * h(p)
    };
    let add_box = |c: Vector3<f64>, [hx, hy, hz]: [f64; 3]| {
        s.occ_add_box(c.x - hx, c.y - hy, c.z - hz, 2.0 * hx, 2.0 * hy, 2.0 * hz)
            .map_err(g)
    };
    let turn = |v: &[DimTag], psi: f64| -> Result<(), String> {
        if psi != 0.0 {
            s.occ_rotate(v, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, psi)
                .map_err(g)?;
        }
        Ok(())
    };

    let mut volumes: Vec<DimTag> = Vec::new();
    for w in &l.walls {
        let psi = angle(&w.solid);
        let b = add_box(back(psi, w.solid.centre), w.solid.half)?;
        let seat = back(psi, w.seat);
        let hx = w.solid.half[0];
        let bore = s
            .occ_add_cylinder(
                seat.x - 2.0 * hx,
                seat.y,
                seat.z,
                4.0 * hx,
                0.0,
                0.0,
                w.bore_radius,
            )
            .map_err(g)?;
        let (cut, _) = s.occ_cut(&[(3, b)], &[(3, bore)], true, true).map_err(g)?;
        turn(&cut, psi)?;
        volumes.extend(cut);
    }
    for r in &l.ribs {
        let psi = angle(&r.solid);
        let b = add_box(back(psi, r.solid.centre), r.solid.half)?;
        turn(&[(3, b)], psi)?;
        volumes.push((3, b));
    }
    let floor = add_box(h(l.floor.centre), l.floor.half)?;
    let (fused, _) = s.occ_fuse(&[(3, floor)], &volumes, true, true).map_err(g)?;
    s.occ_synchronize().map_err(g)?;
    let vols = s.occ_get_entities(3).map_err(g)?;
    if vols.len() != 1 || fused.len() != 1 {
        return Err(format!(
            "housing mesh: the walls and floor fused into {} volumes, expected one (a wall off the floor?)",
            vols.len()
        ));
    }
    let cad_volume_m3 = s.occ_get_mass(3, vols[0].1).map_err(g)?;
    s.option_set_number("Mesh.MeshSizeMax", element_m)
        .map_err(g)?;
    s.option_set_number("Mesh.MeshSizeMin", 0.25 * element_m)
        .map_err(g)?;
    s.option_set_number("Mesh.MeshSizeFromCurvature", 12.0)
        .map_err(g)?;
    s.option_set_number("Mesh.Algorithm3D", 1.0).map_err(g)?;
    s.mesh_generate(3).map_err(g)?;
    s.mesh_set_order(2).map_err(g)?;
    let straightened = crate::mesh::generate::straighten_inverted(&s).map_err(g)?;

    let (tags, coords, _) = s.mesh_get_nodes(-1, -1, false, false).map_err(g)?;
    let max = tags.iter().copied().max().unwrap_or(0);
    // gmsh tag → position in its node list, then → our node index.
    let mut at = vec![usize::MAX; max + 1];
    for (i, &t) in tags.iter().enumerate() {
        at[t] = i;
    }
    let mut index = vec![usize::MAX; max + 1];
    let (types, _, conn) = s.mesh_get_elements(3, -1).map_err(g)?;
    let mut nodes: Vec<[f64; 3]> = Vec::new();
    let mut tets = Vec::new();
    for (ty, c) in types.iter().zip(&conn) {
        if *ty != 11 {
            return Err(format!(
                "housing mesh: volume element type {ty}, expected tet10 (11)"
            ));
        }
        for e in c.chunks(10) {
            let mut t = [0usize; 10];
            for (k, &n) in e.iter().enumerate() {
                let j = at
                    .get(n)
                    .copied()
                    .filter(|&j| j != usize::MAX)
                    .ok_or_else(|| format!("housing mesh: element refers to unknown node {n}"))?;
                if index[n] == usize::MAX {
                    index[n] = nodes.len();
                    let q =
                        frame * Vector3::new(coords[3 * j], coords[3 * j + 1], coords[3 * j + 2]);
                    nodes.push([q.x, q.y, q.z]);
                }
                t[k] = index[n];
            }
            tets.push(t);
        }
    }
    drop(s);
    let tol = 1e-6 * (1.0 + l.floor.half.iter().fold(0.0f64, |a, &b| a.max(b)));
    // A seat: the corner nodes on its bore and the mid-edge nodes of the
    // tet faces whose corners all are (a straightened mid-edge node lies
    // off the cylinder).
    let mut seat_of = vec![usize::MAX; nodes.len()];
    let mut feet = Vec::new();
    for t in &tets {
        for &i in &t[..4] {
            if seat_of[i] != usize::MAX {
                continue;
            }
            let p = Vector3::from(nodes[i]);
            if let Some(k) = l.walls.iter().position(|w| w.on_bore(&p, tol)) {
                seat_of[i] = k;
            }
        }
    }
    let corner_seat = seat_of.clone();
    for t in &tets {
        for face in [[0, 1, 2], [0, 1, 3], [1, 2, 3], [0, 2, 3]] {
            let k = corner_seat[t[face[0]]];
            if k == usize::MAX || face.iter().any(|&c| corner_seat[t[c]] != k) {
                continue;
            }
            for (e, [a, b]) in fem::tet10::EDGES.iter().enumerate() {
                if face.contains(a) && face.contains(b) {
                    seat_of[t[4 + e]] = k;
                }
            }
        }
    }
    let mut seats: Vec<Vec<usize>> = vec![Vec::new(); l.walls.len()];
    for (i, p) in nodes.iter().enumerate() {
        if seat_of[i] != usize::MAX {
            seats[seat_of[i]].push(i);
        }
        if l.on_foot(&Vector3::from(*p), tol) {
            feet.push(i);
        }
    }
    for (k, s) in seats.iter().enumerate() {
        if s.is_empty() {
            return Err(format!("housing mesh: no node on the bore of wall {k}"));
        }
    }
    if feet.is_empty() {
        return Err("housing mesh: no node on the feet".into());
    }
    Ok(HousingMesh {
        mesh: TetMesh { nodes, tets },
        seats,
        feet,
        cad_volume_m3,
        straightened,
    })
}
