//! Node-to-surface penalty constraints between two meshed bodies, in both
//! passes: every slave node of one body against the other body's quadratic
//! faces, then the roles swapped. Each pass carries half the penalty
//! stiffness, so that where both passes see the same contact the pair is as
//! stiff as one pass with the full penalty (the symmetric treatment).

use crate::contact_surface::{lumped_areas, MasterSurface};
use crate::penalty::{Constraint, Term};
use fem::tri6;
use std::collections::HashMap;

type V3 = [f64; 3];

/// One body as the contact sees it.
pub struct ContactBody<'a> {
    /// Index of the body (its compliance) in the problem.
    pub body: usize,
    /// All node coordinates in the common frame (indexed by node number).
    pub nodes: Vec<V3>,
    /// Common frame → body frame (row-major rotation), for load directions.
    pub to_body: [[f64; 3]; 3],
    /// Contact faces, oriented outward.
    pub faces: Vec<[usize; 6]>,
    /// Displacement per unit rigid coordinate ψ at a point of the common frame.
    pub rigid: &'a (dyn Fn(V3) -> V3 + Sync),
    /// Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
}

/// Penalty and search settings.
#[derive(Debug, Clone, Copy)]
pub struct PenaltySettings {
    /// ε = factor · E / ℓ (ℓ: local face size), N/m³.
    pub factor: f64,
    /// Largest initial gap of a constraint, m.
    pub max_gap: f64,
    /// Search reach of the projection, m.
    pub reach: f64,
}

/// Which pass a constraint belongs to and its slave node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Origin {
    /// Body of the slave node.
    pub slave_body: usize,
    pub slave_node: usize,
}

fn rot(r: &[[f64; 3]; 3], v: V3) -> V3 {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

/// Constraints of one pass: slave nodes of `s` against the faces of `m`.
pub fn one_pass(
    s: &ContactBody,
    m: &ContactBody,
    master: &MasterSurface,
    set: &PenaltySettings,
    share: f64,
) -> Vec<(Constraint, Origin)> {
    let area = lumped_areas(&s.nodes, &s.faces);
    // Local face size ℓ at each slave node: √(2 × mean adjacent face area).
    let mut face_area: HashMap<usize, (f64, usize)> = HashMap::new();
    for f in &s.faces {
        let a = tri6::area(&f.map(|i| s.nodes[i]));
        for &i in f {
            let e = face_area.entry(i).or_default();
            e.0 += a;
            e.1 += 1;
        }
    }
    let e_min = s.youngs_modulus_pa.min(m.youngs_modulus_pa);
    let mut slaves: Vec<usize> = area.keys().copied().collect();
    slaves.sort_unstable();
    let mut out = Vec::new();
    for node in slaves {
        let x = s.nodes[node];
        let Some(p) = master.project(x, set.reach) else {
            continue;
        };
        if p.gap > set.max_gap {
            continue;
        }
        let (sum, cnt) = face_area[&node];
        let ell = (2.0 * sum / cnt as f64).sqrt();
        let eps = set.factor * e_min / ell;
        let n = p.normal;
        let mut terms = vec![Term {
            body: s.body,
            node,
            dir: rot(&s.to_body, n),
        }];
        let nm = rot(&m.to_body, n);
        let sh = tri6::shape(p.st);
        for (k, &mn) in master.faces[p.face].iter().enumerate() {
            terms.push(Term {
                body: m.body,
                node: mn,
                dir: nm.map(|c| -sh[k] * c),
            });
        }
        let rs = (s.rigid)(x);
        let rm = (m.rigid)(p.point);
        let rigid = (0..3).map(|i| (rs[i] - rm[i]) * n[i]).sum();
        out.push((
            Constraint {
                terms,
                gap0: p.gap,
                rigid,
                stiffness: share * eps * area[&node],
            },
            Origin {
                slave_body: s.body,
                slave_node: node,
            },
        ));
    }
    out
}

/// Both passes between `a` and `b`, each with half the penalty.
pub fn two_pass(
    a: &ContactBody,
    b: &ContactBody,
    set: &PenaltySettings,
) -> Vec<(Constraint, Origin)> {
    let ma = MasterSurface::new(a.nodes.clone(), a.faces.clone());
    let mb = MasterSurface::new(b.nodes.clone(), b.faces.clone());
    let mut v = one_pass(a, b, &mb, set, 0.5);
    v.extend(one_pass(b, a, &ma, set, 0.5));
    v
}
