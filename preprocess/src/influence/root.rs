//! The root-stress influence coefficients of a body: the stress at each
//! fillet point ([`crate::root_stress::FilletGridPoints`], the
//! [`ROOT_STRESS_GRID`] of both fillets of a tooth) of the loaded tooth and
//! its neighbours ([`ROOT_STRESS_OFFSETS`]) under each grid point's unit
//! load, from the same unit-load fields as the compliance: the full
//! solve's field, or the pruned forward vector's backward solve on the
//! fillet points' support only.
//!
//! The whole field's stress is stored: no near-load part is subtracted. The
//! fillet lies below the grid's root row, outside the load's bump, and its
//! stress is the tooth's bending, which the global field carries; the
//! stored value is the mesh's answer there (a coarse fillet underestimates a
//! fine one's peak, as any recovered stress does).

use super::solves::tooth_of;
use super::{InfluenceError, InfluenceRequest};
use crate::root_stress::FilletGridPoints;
use fem::path_solve::{PathFactor, PathVec};
use fem::Dofs;
use formats::stiffness_file::{RootStressBlock, ROOT_STRESS_GRID, ROOT_STRESS_OFFSETS};
use std::collections::{BTreeMap, HashMap};

/// Grid loads per backward solve of the pruned path.
const BACKWARD_BLOCK: usize = 64;

/// Where the root stress is wanted, and the coefficients found so far.
pub(super) struct RootTargets {
    /// Offsets of the request that are root-stress offsets.
    offsets: Vec<i32>,
    /// Fillet points of every responding tooth.
    teeth: BTreeMap<usize, FilletGridPoints>,
    points: usize,
    pub(super) block: RootStressBlock,
}

impl RootTargets {
    /// The targets of `req` (None when it asks for no root stress).
    pub(super) fn new(req: &InfluenceRequest) -> Result<Option<RootTargets>, InfluenceError> {
        let Some(points) = req.root else {
            return Ok(None);
        };
        let offsets: Vec<i32> = ROOT_STRESS_OFFSETS
            .into_iter()
            .filter(|o| req.offsets.contains(o))
            .collect();
        let (xi, height) = RootStressBlock::side_points();
        let mut teeth = BTreeMap::new();
        for &k in &req.solved_teeth {
            for &o in &offsets {
                let j = tooth_of(req, k, o);
                if teeth.contains_key(&j) {
                    continue;
                }
                let g = FilletGridPoints::new(&req.body.mesh, points, j, (&xi, &height))
                    .ok_or_else(|| InfluenceError::Grid {
                        tooth: j,
                        point: 0,
                        what: "no root fillet nodes for the root-stress points".into(),
                    })?;
                teeth.insert(j, g);
            }
        }
        let n = 2 * ROOT_STRESS_GRID[0] * ROOT_STRESS_GRID[1];
        let size = req.solved_teeth.len() * offsets.len() * req.grid.len() * n * 6;
        Ok(Some(RootTargets {
            block: RootStressBlock {
                offsets: offsets.clone(),
                xi: [xi.clone(), xi].concat(),
                height: [height.clone(), height].concat(),
                stress: vec![0.0; size],
            },
            offsets,
            teeth,
            points: n,
        }))
    }

    /// Every support node of the points of `teeth` (all responding teeth
    /// when None).
    pub(super) fn support_nodes(&self, teeth: Option<&[usize]>) -> Vec<usize> {
        let mut v: Vec<usize> = self
            .teeth
            .iter()
            .filter(|(j, _)| teeth.is_none_or(|t| t.contains(j)))
            .flat_map(|(_, t)| t.support().iter().copied())
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Stores the stresses of solved tooth `s` (body tooth `k`) under its
    /// grid point `i`'s unit load, `u(n)` the field at node n.
    pub(super) fn fill(
        &mut self,
        req: &InfluenceRequest,
        s: usize,
        k: usize,
        i: usize,
        u: &dyn Fn(usize) -> [f64; 3],
    ) {
        let (np, nr, n) = (req.grid.len(), self.offsets.len(), self.points);
        for (r, &o) in self.offsets.iter().enumerate() {
            let t = &self.teeth[&tooth_of(req, k, o)];
            let at = (((s * nr + r) * np + i) * n) * 6;
            for (p, v) in t.eval(&req.body.mesh, u).into_iter().enumerate() {
                self.block.stress[at + 6 * p..at + 6 * p + 6].copy_from_slice(&v);
            }
        }
    }

    /// The pruned path: solved tooth `s`'s forward vectors `y` (one per
    /// grid point) solved backward on the fillet points' support.
    pub(super) fn fill_pruned(
        &mut self,
        req: &InfluenceRequest,
        pf: &PathFactor,
        dofs: &Dofs,
        s: usize,
        y: &[PathVec],
    ) -> Result<(), InfluenceError> {
        let k = req.solved_teeth[s];
        let mine: Vec<usize> = self.offsets.iter().map(|&o| tooth_of(req, k, o)).collect();
        let nodes = self.support_nodes(Some(&mine));
        let mut at: HashMap<usize, [Option<usize>; 3]> = HashMap::new();
        let mut list = Vec::new();
        for &n in &nodes {
            let f = [0, 1, 2].map(|c| {
                dofs.free_index(3 * n + c).map(|d| {
                    list.push(d);
                    list.len() - 1
                })
            });
            at.insert(n, f);
        }
        // Blocks of loads: the backward solves' work space is loads × the
        // rows on the support's paths.
        for (c, chunk) in y.chunks(BACKWARD_BLOCK).enumerate() {
            let refs: Vec<&PathVec> = chunk.iter().collect();
            let x = pf.backward_at(&refs, &list)?;
            for (i, xi) in x.iter().enumerate() {
                let u = |n: usize| at[&n].map(|p| p.map_or(0.0, |p| xi[p]));
                self.fill(req, s, k, c * BACKWARD_BLOCK + i, &u);
            }
        }
        Ok(())
    }
}
