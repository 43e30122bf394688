//! The reference LTCA's working set: the two-pass constraints of a
//! position, growing the set with their unit-load vectors and condensed
//! matrix, and the loaded gaps of the constraints left out.

use super::{ReferenceError, ReferencePair, TimeSplit, MINIMA_BAND_M, V3};
use crate::reference::contact_pairs::{rot, two_pass, ContactBody, PenaltySettings};
use crate::reference::penalty::Constraint;
use fem::path_solve::{combine, gram, PathVec};
use nalgebra::Vector3;

/// The constraints in the solve and their condensed matrix.
pub(super) struct WorkingSet {
    pub(super) idx: Vec<usize>,
    /// Row-major idx.len()².
    pub(super) w: Vec<f64>,
    /// Each constraint's vector y_cb on the pinion (0) and the wheel (1),
    /// in the order of `idx`.
    pub(super) y: Vec<[PathVec; 2]>,
}

impl WorkingSet {
    /// z_b = Σ_c λ_c y_cb: body `body`'s forward-solved load under the
    /// constraint forces `force` (in the order of `idx`).
    pub(super) fn load_vector(&self, force: &[f64], body: usize) -> PathVec {
        let parts: Vec<(&PathVec, &[f64])> = self
            .y
            .iter()
            .zip(force.iter())
            .filter(|(_, f)| **f != 0.0)
            .map(|(v, f)| (&v[body], std::slice::from_ref(f)))
            .collect();
        combine(&parts)
    }
}

impl WorkingSet {
    /// [`WorkingSet::load_vector`] for forces given per constraint (indices
    /// into the position's constraints, each in the set).
    pub(super) fn load_vector_of(&self, forces: &[(usize, f64)], body: usize) -> PathVec {
        let parts: Vec<(&PathVec, &[f64])> = forces
            .iter()
            .map(|(c, f)| {
                let p = self
                    .idx
                    .binary_search(c)
                    .expect("a solved constraint stays in the set");
                (&self.y[p][body], std::slice::from_ref(f))
            })
            .collect();
        combine(&parts)
    }
}

impl ReferencePair<'_> {
    /// Every two-pass constraint up to the search gap that closes as the
    /// pinion turns in its driving sense, at pinion angle `phi`, each with
    /// its slave point in the pinion's member frame.
    pub(super) fn constraints(
        &self,
        phi: f64,
    ) -> Result<(Vec<Constraint>, Vec<V3>), ReferenceError> {
        let phi2 = self.flanks.conjugate_wheel_angle(phi);
        // The pinion placed with the pair's pose (misalignment) relative
        // to the wheel, which stays in the fixed frame; it turns about its
        // moved axis.
        let pose = self.flanks.pose;
        let (pn, pr) = self.pinion.placed(phi, pose.as_ref());
        let (wn, wr) = self.wheel.placed(phi2, None);
        let (axis, c) = match &pose {
            Some(p) => (p.rotation * self.pinion.frame.axis(), p.translation),
            None => (self.pinion.frame.axis(), Vector3::zeros()),
        };
        let (a, d) = ([axis[0], axis[1], axis[2]], self.direction);
        let c = [c[0], c[1], c[2]];
        let spin = move |x: V3| -> V3 {
            let x = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
            [
                d * (a[1] * x[2] - a[2] * x[1]),
                d * (a[2] * x[0] - a[0] * x[2]),
                d * (a[0] * x[1] - a[1] * x[0]),
            ]
        };
        let fixed = |_: V3| [0.0; 3];
        let body_p = ContactBody {
            body: 0,
            nodes: pn,
            to_body: pr,
            faces: self.pinion.faces.clone(),
            rigid: &spin,
            youngs_modulus_pa: self.pinion.youngs_modulus_pa,
        };
        let body_w = ContactBody {
            body: 1,
            nodes: wn,
            to_body: wr,
            faces: self.wheel.faces.clone(),
            rigid: &fixed,
            youngs_modulus_pa: self.wheel.youngs_modulus_pa,
        };
        let set = PenaltySettings {
            factor: self.settings.penalty_factor,
            max_gap: self.settings.search_gap_m,
            reach: 2.0 * self.settings.search_gap_m,
            minima_band: MINIMA_BAND_M,
        };
        let (cs, at): (Vec<Constraint>, Vec<V3>) = two_pass(&body_p, &body_w, &set)
            .into_iter()
            .filter(|(c, o)| c.rigid < 0.0 && self.settings.passes.keeps(o.slave_body))
            .map(|(k, o)| (k, rot(&pr, [0, 1, 2].map(|i| o.at[i] - c[i]))))
            .unzip();
        if cs.is_empty() {
            return Err(ReferenceError::NoContact {
                phi_deg: phi.to_degrees(),
                max_gap_um: self.settings.search_gap_m * 1e6,
            });
        }
        Ok((cs, at))
    }

    /// Adds the constraints `add` (indices into `cs`, not yet in the set)
    /// to the working set: their nodes' unit-load vectors, their constraint
    /// vectors, and the new rows and columns of the condensed matrix
    /// W = Σ_b Y_bᵀ Y_b (symmetric).
    pub(super) fn grow(
        &mut self,
        cs: &[Constraint],
        ws: &mut WorkingSet,
        add: &[usize],
        split: &mut TimeSplit,
    ) -> Result<(), ReferenceError> {
        let lap = std::time::Instant::now();
        let mut add_y = Vec::with_capacity(add.len());
        for (body, m) in [(0, &mut *self.pinion), (1, &mut *self.wheel)] {
            let nodes: Vec<usize> = add
                .iter()
                .flat_map(|&c| {
                    cs[c]
                        .terms
                        .iter()
                        .filter(|t| t.body == body)
                        .map(|t| t.node)
                })
                .collect();
            m.compliance.ensure(&nodes)?;
        }
        split.forward_s += lap.elapsed().as_secs_f64();
        let lap = std::time::Instant::now();
        for &c in add {
            add_y.push([
                self.pinion.compliance.constraint_vector(&cs[c].terms, 0)?,
                self.wheel.compliance.constraint_vector(&cs[c].terms, 1)?,
            ]);
        }
        let mut idx = ws.idx.clone();
        idx.extend_from_slice(add);
        idx.sort_unstable();
        idx.dedup();
        let n = idx.len();
        let pos_old: Vec<usize> = ws
            .idx
            .iter()
            .map(|c| idx.binary_search(c).expect("old constraint kept"))
            .collect();
        let pos_new: Vec<usize> = add
            .iter()
            .map(|c| idx.binary_search(c).expect("new constraint added"))
            .collect();
        let mut y: Vec<Option<[PathVec; 2]>> = (0..n).map(|_| None).collect();
        for (p, v) in pos_old.iter().zip(std::mem::take(&mut ws.y)) {
            y[*p] = Some(v);
        }
        for (p, v) in pos_new.iter().zip(add_y) {
            y[*p] = Some(v);
        }
        let y: Vec<[PathVec; 2]> = y
            .into_iter()
            .map(|v| v.expect("every constraint has its vectors"))
            .collect();
        // W(all, new): the new columns; the new rows are their transpose.
        let mut cols = vec![0.0; n * add.len()];
        for b in 0..2 {
            let all: Vec<&PathVec> = y.iter().map(|v| &v[b]).collect();
            let new: Vec<&PathVec> = pos_new.iter().map(|&p| &y[p][b]).collect();
            for (c, v) in cols.iter_mut().zip(gram(&all, &new)) {
                *c += v;
            }
        }
        let mut w = vec![0.0; n * n];
        let old = &ws.idx;
        for (a, &pa) in pos_old.iter().enumerate() {
            for (b, &pb) in pos_old.iter().enumerate() {
                w[pa * n + pb] = ws.w[a * old.len() + b];
            }
        }
        for r in 0..n {
            for (k, &pk) in pos_new.iter().enumerate() {
                let v = cols[r * add.len() + k];
                w[r * n + pk] = v;
                w[pk * n + r] = v;
            }
        }
        ws.idx = idx;
        ws.w = w;
        ws.y = y;
        split.condensation_s += lap.elapsed().as_secs_f64();
        Ok(())
    }

    /// Loaded gap of every constraint of `cs` outside the working set,
    /// under each of `loads` (forces of the working set's constraints and
    /// the rigid rotation ψ): per load, (constraint, gap). The displacements
    /// are one backward solve per body for all loads together, on the paths
    /// of the outside constraints' nodes.
    pub(super) fn outside_gaps(
        &self,
        cs: &[Constraint],
        ws: &WorkingSet,
        loads: &[(&[f64], f64)],
    ) -> Result<Vec<Vec<(usize, f64)>>, ReferenceError> {
        let outside: Vec<usize> = (0..cs.len())
            .filter(|c| ws.idx.binary_search(c).is_err())
            .collect();
        let mut gaps: Vec<Vec<f64>> = loads
            .iter()
            .map(|&(_, psi)| {
                outside
                    .iter()
                    .map(|&c| cs[c].gap0 + cs[c].rigid * psi)
                    .collect()
            })
            .collect();
        for (b, body) in [&self.pinion.compliance, &self.wheel.compliance]
            .into_iter()
            .enumerate()
        {
            let mut at: Vec<usize> = outside
                .iter()
                .flat_map(|&c| cs[c].terms.iter().filter(|t| t.body == b).map(|t| t.node))
                .collect();
            at.sort_unstable();
            at.dedup();
            if at.is_empty() {
                continue;
            }
            let z: Vec<PathVec> = loads
                .iter()
                .map(|(force, _)| ws.load_vector(force, b))
                .collect();
            let zr: Vec<&PathVec> = z.iter().collect();
            let u = body.displacements(&zr, &at)?;
            for (g, u) in gaps.iter_mut().zip(&u) {
                for (g, &c) in g.iter_mut().zip(&outside) {
                    for t in cs[c].terms.iter().filter(|t| t.body == b) {
                        let p = at.binary_search(&t.node).expect("node collected above");
                        *g += (0..3).map(|i| t.dir[i] * u[p][i]).sum::<f64>();
                    }
                }
            }
        }
        Ok(gaps
            .into_iter()
            .map(|g| outside.iter().copied().zip(g).collect())
            .collect())
    }
}
