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
use crate::fillet_nodes::{fillet_nodes, Fillet, FilletError, FilletSide};
use fem::stress::{NodalStressAt, Stress};
use fem::{Material, TetMesh};
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::PairGeometry;

pub use formats::root_stress::FilletStress;

/// The extremes of one fillet's nodal stresses `s` (one per node of `f`).
pub fn fillet_extremes(f: &Fillet, s: &[Stress]) -> FilletStress {
    formats::root_stress::fillet_extremes(
        f.tooth,
        f.side == FilletSide::Loaded,
        &f.xi,
        &f.height,
        s,
    )
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

/// The stress tensor `s` of a tooth turned by `turn` (rad) about the
/// member axis, expressed in the frame turned back onto tooth 0:
/// σ₀ = Rᵀ σ R with R the rotation about z by `turn`.
pub fn turned_back(s: Stress, turn: f64) -> Stress {
    let m = nalgebra::Matrix3::new(s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]);
    let r = nalgebra::Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), turn);
    let b = r.matrix().transpose() * m * r.matrix();
    [
        b[(0, 0)],
        b[(1, 1)],
        b[(2, 2)],
        b[(1, 2)],
        b[(0, 2)],
        b[(0, 1)],
    ]
}

/// One tooth's fillet points on a fixed (ξ, height) grid: at each grid
/// point of each side the fillet node nearest in (ξ, height), where the
/// reduced model stores its root-stress coefficients (the same points on
/// every tooth whatever its mesh).
#[derive(Debug, Clone)]
pub struct FilletGridPoints {
    pub tooth: usize,
    turn: f64,
    at: NodalStressAt,
    support: Vec<usize>,
    material: Material,
    /// Each point's face-width position and fillet height (the grid's,
    /// loaded side first).
    pub xi: Vec<f64>,
    pub height: Vec<f64>,
}

impl FilletGridPoints {
    /// Tooth `tooth`'s points (one of `points`' teeth) at the grid
    /// `(xi, height)` of one side, repeated for both sides.
    pub fn new(
        mesh: &TetMesh,
        points: &RootStressPoints,
        tooth: usize,
        (xi, height): (&[f64], &[f64]),
    ) -> Option<FilletGridPoints> {
        let mut nodes = Vec::with_capacity(2 * xi.len());
        let mut turn = None;
        for side in [FilletSide::Loaded, FilletSide::Opposite] {
            let f = points
                .fillets
                .iter()
                .find(|f| f.tooth == tooth && f.side == side)?;
            turn = Some(f.turn);
            for (&x, &h) in xi.iter().zip(height) {
                let k = (0..f.nodes.len()).min_by(|&a, &b| {
                    let d = |k: usize| (f.xi[k] - x).powi(2) + (f.height[k] - h).powi(2);
                    d(a).total_cmp(&d(b))
                })?;
                nodes.push(f.nodes[k]);
            }
        }
        let at = NodalStressAt::new(mesh, &nodes);
        let support = at.support(mesh);
        Some(FilletGridPoints {
            tooth,
            turn: turn?,
            at,
            support,
            material: points.material,
            xi: [xi, xi].concat(),
            height: [height, height].concat(),
        })
    }

    /// The nodes whose displacements [`FilletGridPoints::eval`] reads,
    /// ascending.
    pub fn support(&self) -> &[usize] {
        &self.support
    }

    /// The stress at each point (Pa) in the tooth's own frame turned back
    /// onto tooth 0, `u(n)` the displacement of support node n.
    pub fn eval(&self, mesh: &TetMesh, u: impl Fn(usize) -> [f64; 3]) -> Vec<Stress> {
        self.at
            .eval(mesh, &self.material, u)
            .into_iter()
            .map(|s| turned_back(s, self.turn))
            .collect()
    }
}
