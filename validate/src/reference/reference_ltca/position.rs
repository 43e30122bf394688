//! One position of the reference LTCA: the vanishing torque and then each
//! torque, the working set of constraints grown until no constraint left
//! out penetrates.

use super::working_set::WorkingSet;
use super::{
    LoadResult, PositionResult, ReferenceError, ReferencePair, TimeSplit, UNLOADED_TORQUE_NM,
};
use crate::reference::contact_surface::smoothed_pressure;
use crate::reference::penalty::{carried_load, nodal_normal_forces, solve, Constraint};
use std::collections::HashSet;

impl ReferencePair<'_> {
    /// Solves the position `phi` (pinion angle, rad) at the vanishing torque
    /// [`UNLOADED_TORQUE_NM`] and then at each torque (N·m, increasing).
    ///
    /// All two-pass constraints up to the search gap are built (geometry
    /// only). The solve starts with those within the start band of the
    /// smallest gap; after each solve the loaded gap of every constraint
    /// left out is evaluated from the contact forces (the columns of the
    /// loaded nodes hold the responses at every flank node), and the ones
    /// that penetrate join the solve, until none does at either penalty
    /// factor. Only the nodes that join get unit-load columns.
    pub fn position(
        &mut self,
        phi: f64,
        torques: &[f64],
    ) -> Result<PositionResult, ReferenceError> {
        let t0 = std::time::Instant::now();
        let mut split = TimeSplit::default();
        let lap = std::time::Instant::now();
        let (cs, at) = self.constraints(phi)?;
        split.search_s = lap.elapsed().as_secs_f64();
        let before = self.pinion.compliance.solves + self.wheel.compliance.solves;
        let g_min = cs.iter().map(|c| c.gap0).fold(f64::INFINITY, f64::min);
        let start: Vec<usize> = (0..cs.len())
            .filter(|&c| cs[c].gap0 <= g_min + self.settings.start_band_m)
            .collect();
        let mut ws = WorkingSet {
            idx: Vec::new(),
            w: Vec::new(),
            y: Vec::new(),
        };
        self.grow(&cs, &mut ws, &start, &mut split)?;
        let scale = self.settings.penalty_factor_check / self.settings.penalty_factor;
        let ratio = self.pinion.frame.teeth as f64 / self.wheel.frame.teeth as f64;
        let mut loads = Vec::new();
        let (mut first_force, mut first_idx) = (Vec::new(), Vec::new());
        let mut pattern = Vec::new();
        let mut warm: [Option<Vec<usize>>; 2] = [None, None];
        // Per loaded torque: the constraints' forces (constraint, N).
        let mut solved: Vec<Vec<(usize, f64)>> = Vec::new();
        let all: Vec<f64> = std::iter::once(UNLOADED_TORQUE_NM)
            .chain(torques.iter().copied())
            .collect();
        for (k, &t) in all.iter().enumerate() {
            let (s, sc, outside) = loop {
                let sub: Vec<Constraint> = ws.idx.iter().map(|&c| cs[c].clone()).collect();
                let check: Vec<Constraint> = sub
                    .iter()
                    .map(|c| Constraint {
                        stiffness: c.stiffness * scale,
                        ..c.clone()
                    })
                    .collect();
                let warm_of = |a: &Option<Vec<usize>>| {
                    a.as_ref().map(|on| {
                        let mut v = vec![false; ws.idx.len()];
                        for &c in on {
                            if let Ok(p) = ws.idx.binary_search(&c) {
                                v[p] = true;
                            }
                        }
                        v
                    })
                };
                let lap = std::time::Instant::now();
                let s = solve(&sub, &ws.w, t, warm_of(&warm[0]).as_deref())?;
                let sc = solve(&check, &ws.w, t, warm_of(&warm[1]).as_deref())?;
                split.contact_s += lap.elapsed().as_secs_f64();
                let lap = std::time::Instant::now();
                let mut gaps =
                    self.outside_gaps(&cs, &ws, &[(&s.force, s.psi), (&sc.force, sc.psi)])?;
                split.outside_s += lap.elapsed().as_secs_f64();
                let mut add: Vec<usize> = gaps
                    .iter()
                    .flatten()
                    .filter(|&&(_, v)| v < 0.0)
                    .map(|&(c, _)| c)
                    .collect();
                add.sort_unstable();
                add.dedup();
                let on = |sol: &crate::reference::penalty::Solution| -> Vec<usize> {
                    (0..ws.idx.len())
                        .filter(|&i| sol.active[i])
                        .map(|i| ws.idx[i])
                        .collect()
                };
                warm = [Some(on(&s)), Some(on(&sc))];
                if add.is_empty() {
                    break (s, sc, gaps.swap_remove(0));
                }
                self.grow(&cs, &mut ws, &add, &mut split)?;
            };
            let sub: Vec<Constraint> = ws.idx.iter().map(|&c| cs[c].clone()).collect();
            if k == 0 {
                first_force = s.force.clone();
                first_idx = ws.idx.clone();
            }
            let band_margin_m = outside
                .iter()
                .filter(|&&(c, _)| cs[c].gap0 > 0.5 * self.settings.search_gap_m)
                .map(|&(_, g)| g)
                .fold(f64::INFINITY, f64::min);
            let closure = outside
                .iter()
                .map(|&(c, g)| cs[c].gap0 - g)
                .chain(ws.idx.iter().zip(&s.gap).map(|(&c, &g)| cs[c].gap0 - g))
                .fold(f64::NEG_INFINITY, f64::max);
            let search_margin_m = Some(self.settings.search_gap_m - closure);
            let f = nodal_normal_forces(&sub, &s.force, 0, &self.pinion.inward);
            let p = smoothed_pressure(&self.pinion.mesh.mesh.nodes, &self.pinion.faces, &f);
            let max_pressure_pa = p.values().copied().fold(0.0, f64::max);
            if k + 1 == all.len() {
                pattern = p
                    .iter()
                    .filter(|(_, &v)| v > 0.0)
                    .map(|(&i, &v)| (self.pinion.mesh.mesh.nodes[i], v))
                    .collect();
            }
            if k > 0 {
                solved.push(
                    ws.idx
                        .iter()
                        .copied()
                        .zip(s.force.iter().copied())
                        .filter(|&(_, f)| f != 0.0)
                        .collect(),
                );
            }
            loads.push(LoadResult {
                root_stress: None,
                torque_nm: t,
                te: ratio * s.psi,
                te_check: ratio * sc.psi,
                active: s.active.iter().filter(|&&x| x).count(),
                max_pressure_pa,
                torque_balance: (carried_load(&sub, &s.force) - t) / t,
                band_margin_m,
                search_margin_m,
            });
        }
        self.root_stresses(&cs, &ws, &solved, &mut loads[1..], &mut split)?;
        // The sliding window: keep the vectors of the nodes this position
        // loaded; the next position's contact lies next to them.
        for (body, m) in [(0, &mut *self.pinion), (1, &mut *self.wheel)] {
            let keep: HashSet<usize> = ws
                .idx
                .iter()
                .flat_map(|&c| cs[c].terms.iter().filter(move |t| t.body == body))
                .map(|t| t.node)
                .collect();
            m.compliance.retain(&keep);
        }
        let unloaded = loads.remove(0);
        let unloaded_point = first_force
            .iter()
            .zip(&first_idx)
            .max_by(|a, b| a.0.total_cmp(b.0))
            .map_or([f64::NAN; 3], |(_, &c)| at[c]);
        Ok(PositionResult {
            phi,
            searched: cs.len(),
            constraints: ws.idx.len(),
            unloaded_te: unloaded.te,
            unloaded_point,
            loads,
            pattern,
            new_columns: (self.pinion.compliance.solves + self.wheel.compliance.solves - before)
                / 3,
            cpu_s: t0.elapsed().as_secs_f64(),
            time_split: Some(split),
        })
    }

    /// The root stress of each body's loaded teeth (those whose flank
    /// carries a contact force at any torque) under each torque's forces
    /// `solved`, into `loads` (the loaded torques' results, in order).
    fn root_stresses(
        &self,
        cs: &[Constraint],
        ws: &WorkingSet,
        solved: &[Vec<(usize, f64)>],
        loads: &mut [LoadResult],
        split: &mut TimeSplit,
    ) -> Result<(), ReferenceError> {
        if self.pinion.root.is_none() && self.wheel.root.is_none() {
            return Ok(());
        }
        let lap = std::time::Instant::now();
        let mut per_body = Vec::with_capacity(2);
        for (b, m) in [(0, &*self.pinion), (1, &*self.wheel)] {
            let teeth = m.teeth_of(solved.iter().flatten().flat_map(|&(c, _)| {
                cs[c]
                    .terms
                    .iter()
                    .filter(move |t| t.body == b)
                    .map(|t| t.node)
            }));
            let z: Vec<_> = solved.iter().map(|f| ws.load_vector_of(f, b)).collect();
            let zr: Vec<_> = z.iter().collect();
            per_body.push(m.root_stress(&zr, &teeth)?);
        }
        let wheel = per_body.pop().expect("two bodies");
        let pinion = per_body.pop().expect("two bodies");
        for ((l, p), w) in loads.iter_mut().zip(pinion).zip(wheel) {
            l.root_stress = Some([p, w]);
        }
        split.root_stress_s += lap.elapsed().as_secs_f64();
        Ok(())
    }
}
