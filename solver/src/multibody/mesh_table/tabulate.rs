//! Computing the table: per position the slices and compliance, then the
//! lag-controlled contact problem at every lag node, laid out position-major;
//! on request ([`MeshTable::build_with_root_stress`]) also the loaded teeth's
//! largest root tension of both members at every node.

use super::{
    check_spec, columns_and_lags, Column, ImpactFields, MeshTable, PathMoments, TableSpec,
};
use crate::element::compliance::PairCompliance;
use crate::element::contact_problem::ContactProblem;
use crate::ltca::{assemble, geometry, Assembled, Geometry};
use crate::SolverError;
use geometry::generation::MemberFrame;
use geometry::pair::FlankPair;
use geometry::utca::RollSurface;
use rayon::prelude::*;

/// The wrench on the wheel about the pitch apex, [N; N·m], of normal force
/// `f` (N) at slice `sl` with the pinion turned by `turn` (rad):
/// F [n; x × n], x and n the pinion's contact point and outward normal in
/// the fixed frame, the pair's relative `pose` (misalignment) applied.
pub fn slice_wrench(
    frame: &MemberFrame,
    pose: Option<&geometry::misalignment::Pose>,
    sl: &crate::element::slices::Slice,
    turn: f64,
    f: f64,
) -> [f64; 6] {
    let mut x = frame.to_fixed(&nalgebra::Vector3::from(sl.pos), turn);
    let mut n = frame.to_fixed(&nalgebra::Vector3::from(sl.normal), turn);
    if let Some(p) = pose {
        x = p.apply(&x);
        n = p.rotation * n;
    }
    let m = x.cross(&n) * f;
    [f * n.x, f * n.y, f * n.z, m.x, m.y, m.z]
}

impl MeshTable {
    /// The table from its columns (lead first), laid out position-major.
    pub(crate) fn from_columns(
        spec: TableSpec,
        lead: usize,
        ratio: f64,
        lags: Vec<f64>,
        cols: &[&Column],
        impact: Option<ImpactFields>,
    ) -> MeshTable {
        let torque: Vec<f64> = cols.iter().flat_map(|c| c.torque.iter().copied()).collect();
        let moments = PathMoments::new(&lags, &torque);
        MeshTable {
            spec,
            lead,
            ratio,
            lags,
            te0: cols.iter().map(|c| c.te0).collect(),
            torque,
            moments,
            force: cols.iter().flat_map(|c| c.force.iter().copied()).collect(),
            wrench: cols.iter().flat_map(|c| c.wrench.iter().copied()).collect(),
            friction: cols
                .iter()
                .flat_map(|c| c.friction.iter().copied())
                .collect(),
            tangential: cols
                .iter()
                .flat_map(|c| c.tangential.iter().copied())
                .collect(),
            // Every column or none (they share the stiffness files).
            root_tension: if cols.iter().all(|c| !c.root_tension.is_empty()) {
                cols.iter()
                    .flat_map(|c| c.root_tension.iter().copied())
                    .collect()
            } else {
                Vec::new()
            },
            cpu_s_per_position: cols.iter().map(|c| c.cpu).sum::<f64>() / cols.len() as f64,
            impact,
        }
    }

    /// Computes the table: per position the slices and compliance, then the
    /// lag-controlled contact problem at every lag node.
    pub fn build(
        fp: &FlankPair,
        rs: &RollSurface,
        pc: &PairCompliance,
        frame: &MemberFrame,
        ratio: f64,
        spec: TableSpec,
    ) -> Result<Self, SolverError> {
        Self::build_as(fp, rs, pc, frame, ratio, spec, false)
    }

    /// [`MeshTable::build`], and at every node the loaded teeth's largest
    /// root tension of both members where the stiffness files hold
    /// root-stress coefficients ([`MeshTable::root_tension`]; the scene's
    /// `[multibody] root_stress`), from the loaded fillets alone
    /// ([`crate::element::root_stress::largest_loaded_tension`]). Measured
    /// 2026-11-29 in the multibody bench on the default scene's 0.125° × 96
    /// table, back to back (2 cores, a reference sweep running beside it):
    /// build 2.2 s without root stress, 9.3 s with the full kernel, 6.5 s
    /// with the loaded fillets alone; hence off by default.
    pub fn build_with_root_stress(
        fp: &FlankPair,
        rs: &RollSurface,
        pc: &PairCompliance,
        frame: &MemberFrame,
        ratio: f64,
        spec: TableSpec,
    ) -> Result<Self, SolverError> {
        Self::build_as(fp, rs, pc, frame, ratio, spec, true)
    }

    fn build_as(
        fp: &FlankPair,
        rs: &RollSurface,
        pc: &PairCompliance,
        frame: &MemberFrame,
        ratio: f64,
        spec: TableSpec,
        root_stress: bool,
    ) -> Result<Self, SolverError> {
        check_spec(&spec)?;
        let tau = fp.pinion.gen.frame.pitch();
        let phi = |i: i64| spec.start + spec.direction * spec.step * i as f64;
        // Pass 1: geometry, compliance and the lag at the largest torque.
        let pass1 = |range: std::ops::Range<i64>| -> Result<Vec<_>, SolverError> {
            range
                .into_par_iter()
                .map(|i| {
                    let t = std::time::Instant::now();
                    let g = geometry(fp, rs, phi(i), tau, spec.slices);
                    if g.slices.is_empty() {
                        return Err(SolverError::NoContact);
                    }
                    // Normal forces only: the potential is conservative;
                    // friction is tabulated on its own.
                    let a = assemble(&g, pc, 0.0)?;
                    let s = crate::ltca::solve(&a, spec.torque_max_nm, None)?;
                    Ok((g, a, s.theta, t.elapsed().as_secs_f64()))
                })
                .collect()
        };
        let (columns, lead, lags) = columns_and_lags(
            &spec,
            ratio,
            pass1,
            |p: &(Geometry, Assembled, f64, f64)| (p.0.utca_te, p.2),
        )?;
        // Pass 2: the lag-controlled solves.
        let cols: Vec<Column> = columns
            .into_par_iter()
            .map(|(g, a, _, cpu0)| {
                let t = std::time::Instant::now();
                let p = ContactProblem {
                    compliance: &a.compliance,
                    lag: &a.lag,
                    lever_wheel: &a.lever_wheel,
                    lever_pinion: &a.lever_pinion,
                    line: &a.line,
                    torque: 0.0,
                };
                let mut torque = Vec::with_capacity(spec.lag_nodes);
                let mut force = Vec::with_capacity(spec.lag_nodes);
                let mut wrench = Vec::with_capacity(spec.lag_nodes);
                let mut friction = Vec::with_capacity(spec.lag_nodes);
                let mut tangential = Vec::with_capacity(spec.lag_nodes);
                let mut root_tension = Vec::new();
                let mut warm: Option<Vec<bool>> = None;
                for &lag in &lags {
                    let s = p.solve_at_lag(lag, warm.as_deref())?;
                    torque.push(p.pinion_torque(&s.force));
                    // Force on the wheel: along the pinion's outward normal,
                    // slice k of pair j at pinion rotation φ + jτ.
                    let mut f = [0.0; 3];
                    for (k, sl) in g.slices.iter().enumerate() {
                        if s.force[k] > 0.0 {
                            let n = frame.to_fixed(
                                &nalgebra::Vector3::from(sl.normal),
                                g.phi + sl.pair as f64 * tau,
                            );
                            for c in 0..3 {
                                f[c] += s.force[k] * n[c];
                            }
                        }
                    }
                    force.push(f);
                    let mut w = [0.0; 6];
                    for (sl, &fk) in g.slices.iter().zip(&s.force) {
                        if fk > 0.0 {
                            let turn = g.phi + sl.pair as f64 * tau;
                            let wk = slice_wrench(frame, fp.pose.as_ref(), sl, turn, fk);
                            for (a, b) in w.iter_mut().zip(wk) {
                                *a += b;
                            }
                        }
                    }
                    wrench.push(w);
                    friction.push([0, 1].map(|i| {
                        g.slices
                            .iter()
                            .zip(&s.force)
                            .map(|(sl, f)| f * sl.friction_lever[i])
                            .sum::<f64>()
                    }));
                    tangential.push(
                        g.slices
                            .iter()
                            .zip(&s.force)
                            .map(|(sl, &f)| sl.wheel_tangential(f))
                            .sum::<f64>(),
                    );
                    if root_stress {
                        if let Some(r) = crate::element::root_stress::largest_loaded_tension(
                            pc, &g.slices, &s.force,
                        )? {
                            root_tension.push(r);
                        }
                    }
                    if s.active.iter().any(|&x| x) {
                        warm = Some(s.active);
                    }
                }
                Ok(Column {
                    te0: g.utca_te,
                    torque,
                    force,
                    wrench,
                    friction,
                    tangential,
                    root_tension,
                    cpu: cpu0 + t.elapsed().as_secs_f64(),
                })
            })
            .collect::<Result<_, SolverError>>()?;
        let cols: Vec<&Column> = cols.iter().collect();
        Ok(MeshTable::from_columns(
            spec, lead, ratio, lags, &cols, None,
        ))
    }
}
