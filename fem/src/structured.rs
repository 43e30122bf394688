//! Structured tet10 meshes of mapped blocks, for verification and examples.
//!
//! A block of n₀ × n₁ × n₂ cells in the unit cube (u, v, w), each cell split
//! into six tetrahedra around its main diagonal (Kuhn), is mapped to space by
//! a function; vertex and mid-edge nodes are both mapped, so curved maps give
//! curved (isoparametric) elements.

use crate::TetMesh;

/// A mapped block mesh and the parameters (u, v, w) of its nodes.
pub struct Block {
    pub mesh: TetMesh,
    pub params: Vec<[f64; 3]>,
}

/// Meshes the unit cube with `n` cells per direction and maps it by `map`.
/// Elements are oriented with positive volume.
pub fn mapped_block(n: [usize; 3], map: impl Fn([f64; 3]) -> [f64; 3]) -> Block {
    let m = [2 * n[0] + 1, 2 * n[1] + 1, 2 * n[2] + 1];
    let id = |g: [usize; 3]| (g[2] * m[1] + g[1]) * m[0] + g[0];
    let mut params = Vec::with_capacity(m[0] * m[1] * m[2]);
    for k in 0..m[2] {
        for j in 0..m[1] {
            for i in 0..m[0] {
                params.push([
                    i as f64 / (m[0] - 1) as f64,
                    j as f64 / (m[1] - 1) as f64,
                    k as f64 / (m[2] - 1) as f64,
                ]);
            }
        }
    }
    let nodes: Vec<[f64; 3]> = params.iter().map(|&p| map(p)).collect();
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut tets = Vec::with_capacity(6 * n[0] * n[1] * n[2]);
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let base = [2 * i, 2 * j, 2 * k];
                for p in perms {
                    let mut v = [base; 4];
                    for s in 1..4 {
                        v[s] = v[s - 1];
                        v[s][p[s - 1]] += 2;
                    }
                    let x = v.map(|g| nodes[id(g)]);
                    let sub = |a: usize, b: usize| {
                        [x[a][0] - x[b][0], x[a][1] - x[b][1], x[a][2] - x[b][2]]
                    };
                    let det = crate::tet10::det3(&[sub(1, 0), sub(2, 0), sub(3, 0)]);
                    if det < 0.0 {
                        v.swap(2, 3);
                    }
                    let mut t = [0usize; 10];
                    for (s, g) in v.iter().enumerate() {
                        t[s] = id(*g);
                    }
                    for (e, [a, b]) in crate::tet10::EDGES.iter().enumerate() {
                        let g = [0, 1, 2].map(|c| (v[*a][c] + v[*b][c]) / 2);
                        t[4 + e] = id(g);
                    }
                    tets.push(t);
                }
            }
        }
    }
    Block {
        mesh: TetMesh { nodes, tets },
        params,
    }
}

/// Moves every vertex node strictly inside the unit parameter cube by a
/// deterministic pseudo-random offset of up to `amplitude` (in space) and puts
/// the mid-edge nodes back at their edge midpoints: straight-sided, distorted
/// elements, as used in patch tests.
pub fn distort_interior(block: &mut Block, amplitude: f64, seed: u64) {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut rand = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let mut is_vertex = vec![false; block.mesh.nodes.len()];
    for t in &block.mesh.tets {
        for &v in &t[..4] {
            is_vertex[v] = true;
        }
    }
    for (i, p) in block.params.iter().enumerate() {
        let inside = p.iter().all(|&c| c > 1e-12 && c < 1.0 - 1e-12);
        if is_vertex[i] && inside {
            for c in 0..3 {
                block.mesh.nodes[i][c] += amplitude * rand();
            }
        }
    }
    let tets = block.mesh.tets.clone();
    for t in &tets {
        for (e, [a, b]) in crate::tet10::EDGES.iter().enumerate() {
            let (xa, xb) = (block.mesh.nodes[t[*a]], block.mesh.nodes[t[*b]]);
            block.mesh.nodes[t[4 + e]] = [0, 1, 2].map(|c| 0.5 * (xa[c] + xb[c]));
        }
    }
}

/// Boundary faces (tri6, outward node order) of the block's elements whose
/// nodes all satisfy `on(params)`.
pub fn faces_where(block: &Block, on: impl Fn([f64; 3]) -> bool) -> Vec<[usize; 6]> {
    // Faces of a tet10 as (vertex a, b, c, mid ab, bc, ca), outward for a
    // positively oriented tetrahedron.
    const FACES: [[usize; 6]; 4] = [
        [0, 2, 1, 6, 5, 4],
        [0, 1, 3, 4, 9, 7],
        [0, 3, 2, 7, 8, 6],
        [1, 2, 3, 5, 8, 9],
    ];
    let mut out = Vec::new();
    for t in &block.mesh.tets {
        for f in FACES {
            let face = f.map(|l| t[l]);
            if face.iter().all(|&i| on(block.params[i])) {
                out.push(face);
            }
        }
    }
    out
}
