//! A tet10 mesh: node coordinates and element connectivity.

use crate::FemError;

/// Nodes (m) and 10-node tetrahedra (gmsh order), 0-based node indices.
#[derive(Debug, Clone, Default)]
pub struct TetMesh {
    pub nodes: Vec<[f64; 3]>,
    pub tets: Vec<[usize; 10]>,
}

impl TetMesh {
    /// Checks that every element refers to existing nodes.
    pub fn validate(&self) -> Result<(), FemError> {
        let n = self.nodes.len();
        if let Some((e, t)) = self
            .tets
            .iter()
            .enumerate()
            .find(|(_, t)| t.iter().any(|&i| i >= n))
        {
            return Err(FemError::Invalid {
                field: "tets",
                value: format!("element {e} = {t:?}"),
                limit: format!("node indices must be < {n}"),
            });
        }
        Ok(())
    }

    /// Coordinates of element `e`'s ten nodes.
    pub fn element(&self, e: usize) -> [[f64; 3]; 10] {
        self.tets[e].map(|i| self.nodes[i])
    }

    /// Total volume (sum of element volumes).
    pub fn volume(&self) -> f64 {
        (0..self.tets.len())
            .map(|e| crate::tet10::volume(&self.element(e)))
            .sum()
    }

    /// Polar moment of inertia about the z axis, ∫ ρ (x² + y²) dV, kg·m²
    /// (degree-3 rule on the isoparametric elements: exact for straight-sided
    /// ones, where the integrand is quadratic).
    pub fn polar_moment(&self, density: f64) -> f64 {
        (0..self.tets.len())
            .map(|e| {
                let x = self.element(e);
                crate::tet10::degree3()
                    .iter()
                    .map(|(xi, w)| {
                        let det =
                            crate::tet10::jacobian(&x, &crate::tet10::shape_derivatives(*xi)).1;
                        let p = crate::tet10::position(&x, *xi);
                        w * det.abs() * (p[0] * p[0] + p[1] * p[1])
                    })
                    .sum::<f64>()
            })
            .sum::<f64>()
            * density
    }

    /// For every node, the sorted node indices it shares an element with
    /// (itself included); nodes in no element get an empty list.
    pub fn node_adjacency(&self) -> Vec<Vec<u32>> {
        let mut adj: Vec<Vec<u32>> = vec![Vec::new(); self.nodes.len()];
        for t in &self.tets {
            for &a in t {
                adj[a].extend(t.iter().map(|&b| b as u32));
            }
        }
        for a in &mut adj {
            a.sort_unstable();
            a.dedup();
        }
        adj
    }

    /// The nodes on the mesh's boundary, ascending: the corner and mid-edge
    /// nodes of every face that one element only holds.
    pub fn boundary_nodes(&self) -> Vec<usize> {
        // Faces opposite each vertex, as corner triples with their mid-edge
        // nodes (crate::tet10::EDGES: 4 (0,1), 5 (1,2), 6 (2,0), 7 (3,0),
        // 8 (3,2), 9 (3,1)).
        const FACES: [[usize; 6]; 4] = [
            [1, 2, 3, 5, 8, 9],
            [0, 2, 3, 6, 8, 7],
            [0, 1, 3, 4, 9, 7],
            [0, 1, 2, 4, 5, 6],
        ];
        let mut count: std::collections::HashMap<[usize; 3], (u32, [usize; 6])> =
            std::collections::HashMap::with_capacity(2 * self.tets.len());
        for t in &self.tets {
            for f in FACES {
                let nodes = f.map(|l| t[l]);
                let mut key = [nodes[0], nodes[1], nodes[2]];
                key.sort_unstable();
                count.entry(key).or_insert((0, nodes)).0 += 1;
            }
        }
        let mut out: Vec<usize> = count
            .values()
            .filter(|(c, _)| *c == 1)
            .flat_map(|(_, n)| *n)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The sub-mesh of the listed elements, with its nodes renumbered; returns
    /// the sub-mesh and, for each of its nodes, the index in `self`.
    pub fn submesh(&self, elements: &[usize]) -> (TetMesh, Vec<usize>) {
        let mut new_of = vec![usize::MAX; self.nodes.len()];
        let mut old_of = Vec::new();
        let mut tets = Vec::with_capacity(elements.len());
        for &e in elements {
            tets.push(self.tets[e].map(|i| {
                if new_of[i] == usize::MAX {
                    new_of[i] = old_of.len();
                    old_of.push(i);
                }
                new_of[i]
            }));
        }
        let nodes = old_of.iter().map(|&i| self.nodes[i]).collect();
        (TetMesh { nodes, tets }, old_of)
    }
}
