//! Root (fillet) stress of a meshed gear body: the recovered nodal stress
//! ([`fem::stress::NodalStressAt`]) at the fillet nodes of the teeth asked
//! for ([`crate::fillet_nodes`]), reduced per fillet to what a gear
//! engineer reads: the largest first principal stress (tension, the
//! bending-fatigue stress; on the loaded flank's fillet) and the smallest
//! third principal stress (compression; on the other flank's fillet), each
//! with where it sits on the fillet (face-width position ξ, fillet height h).
//!
//! The stress is linear in the displacements of the fillet nodes' elements
//! ([`RootStressPoints::support`]); a body whose field is known only where
//! asked for (the reference's pruned backward solves) gives just those.

use crate::body_mesh::BodyMesh;
use crate::fillet_nodes::{fillet_nodes, Fillet, FilletError};
use fem::stress::{principal, NodalStressAt, Stress};
use fem::{Material, TetMesh};
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use serde::{Deserialize, Serialize};

/// One fillet's extreme stresses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilletStress {
    pub tooth: usize,
    /// Under the loaded flank (true) or the tooth's other flank.
    pub loaded_side: bool,
    /// Largest first principal stress over the fillet's nodes, Pa, and its
    /// node's face-width position and fillet height.
    pub max_principal_pa: f64,
    pub max_xi: f64,
    pub max_height: f64,
    /// Smallest third principal stress, Pa (negative: compression), and
    /// where.
    pub min_principal_pa: f64,
    pub min_xi: f64,
    pub min_height: f64,
}

/// The extremes of one fillet's nodal stresses `s` (one per node of `f`).
pub fn fillet_extremes(f: &Fillet, s: &[Stress]) -> FilletStress {
    let mut out = FilletStress {
        tooth: f.tooth,
        loaded_side: f.side == crate::fillet_nodes::FilletSide::Loaded,
        max_principal_pa: f64::NEG_INFINITY,
        max_xi: f64::NAN,
        max_height: f64::NAN,
        min_principal_pa: f64::INFINITY,
        min_xi: f64::NAN,
        min_height: f64::NAN,
    };
    for (k, s) in s.iter().enumerate() {
        let p = principal(*s);
        if p[0] > out.max_principal_pa {
            out.max_principal_pa = p[0];
            out.max_xi = f.xi[k];
            out.max_height = f.height[k];
        }
        if p[2] < out.min_principal_pa {
            out.min_principal_pa = p[2];
            out.min_xi = f.xi[k];
            out.min_height = f.height[k];
        }
    }
    out
}

/// The fillets of some teeth of one body, ready to turn displacements
/// into root stresses, tooth by tooth.
#[derive(Debug, Clone)]
pub struct RootStressPoints {
    /// Both fillets of each tooth, loaded side first, in the order of the
    /// teeth asked for.
    pub fillets: Vec<Fillet>,
    /// Per tooth: its two fillets' nodes and the support they read.
    teeth: Vec<ToothPoints>,
    material: Material,
}

#[derive(Debug, Clone)]
struct ToothPoints {
    tooth: usize,
    at: NodalStressAt,
    support: Vec<usize>,
}

impl RootStressPoints {
    /// The fillets of `teeth` of member `which` on `mesh` (its member
    /// frame), `loaded` the side whose flank carries the load.
    pub fn new(
        mesh: &BodyMesh,
        g: &PairGeometry,
        which: Member,
        loaded: Side,
        teeth: &[usize],
        material: Material,
    ) -> Result<RootStressPoints, FilletError> {
        let fillets = fillet_nodes(
            mesh,
            [g.flank(which, loaded), g.flank(which, loaded.other())],
            [loaded.flank_name(which), loaded.other().flank_name(which)],
            g.data.member(which).teeth as usize,
            teeth,
        )?;
        let teeth = teeth
            .iter()
            .map(|&tooth| {
                let nodes: Vec<usize> = fillets
                    .iter()
                    .filter(|f| f.tooth == tooth)
                    .flat_map(|f| f.nodes.iter().copied())
                    .collect();
                let at = NodalStressAt::new(&mesh.mesh, &nodes);
                let support = at.support(&mesh.mesh);
                ToothPoints { tooth, at, support }
            })
            .collect();
        Ok(RootStressPoints {
            fillets,
            teeth,
            material,
        })
    }

    /// The nodes whose displacements the root stress of the listed teeth
    /// reads (of the teeth this was built for; others are ignored),
    /// ascending.
    pub fn support(&self, teeth: &[usize]) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .teeth
            .iter()
            .filter(|t| teeth.contains(&t.tooth))
            .flat_map(|t| t.support.iter().copied())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// The teeth this was built for.
    pub fn teeth(&self) -> Vec<usize> {
        self.teeth.iter().map(|t| t.tooth).collect()
    }

    /// The fillets' extremes of the listed `teeth` under the displacements
    /// `u` (m) of `support` (= [`RootStressPoints::support`] of the same
    /// teeth, in its order).
    pub fn evaluate(
        &self,
        mesh: &TetMesh,
        teeth: &[usize],
        support: &[usize],
        u: &[[f64; 3]],
    ) -> Vec<FilletStress> {
        let mut out = Vec::new();
        for t in self.teeth.iter().filter(|t| teeth.contains(&t.tooth)) {
            let s = t.at.eval(mesh, &self.material, |n| {
                support.binary_search(&n).map_or([f64::NAN; 3], |k| u[k])
            });
            let mut from = 0;
            for f in self.fillets.iter().filter(|f| f.tooth == t.tooth) {
                out.push(fillet_extremes(f, &s[from..from + f.nodes.len()]));
                from += f.nodes.len();
            }
        }
        out
    }
}
