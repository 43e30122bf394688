//! The kinematic shift of the unloaded TE with the misalignments, per
//! position of a multibody table: sᵢ(q₁) = ∂θ₀/∂mᵢ, m = (E, P, G, ΔΣ) in
//! m and rad, by central differences of the misaligned UTCA,
//!
//!   sᵢ(q₁ₖ) = (θ₀(q₁ₖ; +hᵢ eᵢ) − θ₀(q₁ₖ; −hᵢ eᵢ)) / (2 hᵢ),
//!
//! at every table node k (lead-in included), and the second differences
//! κᵢ = (θ₀(+hᵢ) − 2 θ₀(0) + θ₀(−hᵢ)) / hᵢ², which estimate what the linear
//! shift leaves out: ½ Σ |κᵢ| mᵢ² ([`LagShift::nonlinearity`]). Both sides
//! ±hᵢ take the exact contact search of the misaligned pose (the aligned
//! pair's θ₀(0) is the table's own, from the surface of roll angles).
//!
//! The equivalent-lag element ([`crate::multibody::compliant`]) reads the
//! table at the lag θ − s(q₁)·m: the deflection θ − θ₀ − s·m of the
//! misaligned pair equals the aligned pair's at that lag.

use crate::ltca::geometry;
use crate::multibody::mesh_table::MeshTable;
use crate::SolverError;
use geometry::generation::Side;
use geometry::misalignment::{Component, Misalignment};
use geometry::pair::PairGeometry;
use geometry::scene::UtcaSettings;
use geometry::utca::roll_surface;
use rayon::prelude::*;

/// Difference steps: E, P, G in mm, ΔΣ in deg (the scene units).
pub const STEPS: [f64; 4] = [0.005, 0.005, 0.005, 0.002];

/// SI value (m, rad) of one scene unit (mm, deg) of component `i`.
pub fn si_per_unit(i: usize) -> f64 {
    if i == 3 {
        std::f64::consts::PI / 180.0
    } else {
        1e-3
    }
}

/// Nodes per mesh cycle of a non-periodic table whose step divides the
/// mesh cycle `tau` (pinion rad) and whose unloaded TE repeats from cycle
/// to cycle (within 1e-10 rad): the flanks' geometry repeats from tooth to
/// tooth whatever the blank, so the shifts need solving over one cycle
/// only (a lightweight wheel's table spans many). None otherwise.
fn mesh_cycle_phases(table: &MeshTable, tau: f64) -> Option<usize> {
    let spec = table.spec;
    let n = (tau / spec.step).round() as usize;
    let nodes = table.nodes();
    let divides = (n as f64 * spec.step - tau).abs() <= 1e-9 * tau;
    let repeats = (n..nodes).all(|k| (table.te0[k] - table.te0[k % n]).abs() <= 1e-10);
    (!spec.periodic && n >= 4 && nodes > n && divides && repeats).then_some(n)
}

/// sᵢ and κᵢ at the nodes of a table.
#[derive(Debug, Clone)]
pub struct LagShift {
    /// ∂θ₀/∂mᵢ per node (lead first): rad/m for E, P, G, rad/rad for ΔΣ.
    pub slope: Vec<[f64; 4]>,
    /// ∂²θ₀/∂mᵢ² per node, rad/m² (rad/rad²).
    pub curvature: Vec<[f64; 4]>,
    /// Wall time of the 8 misaligned contact searches, s (all cores).
    pub wall_s: f64,
    /// Table nodes the searches solved (one mesh cycle's where the table's
    /// unloaded TE repeats, else all).
    pub solved_nodes: usize,
}

impl LagShift {
    /// The shifts at `table`'s nodes for the pair `g` on flank `side`,
    /// about the static misalignment `base` the table was built on (±hᵢ
    /// added to it).
    pub fn build(
        g: &PairGeometry,
        side: Side,
        utca: &UtcaSettings,
        table: &MeshTable,
        base: &Misalignment,
    ) -> Result<LagShift, SolverError> {
        let t0 = std::time::Instant::now();
        let spec = table.spec;
        let lead = table.lead as i64;
        let nodes = table.nodes();
        let phases = mesh_cycle_phases(table, g.side(side).pinion.gen.frame.pitch());
        let solved = phases.unwrap_or(nodes);
        let runs: Vec<(usize, f64)> = (0..4).flat_map(|i| [(i, 1.0), (i, -1.0)]).collect();
        let te: Vec<Vec<f64>> = runs
            .par_iter()
            .map(|&(i, sign)| {
                let mut gm = g.clone();
                let c = Component::ALL[i];
                gm.misalign(&base.with(c, base.get(c) + sign * STEPS[i]));
                let fp = gm.side(side);
                let rs = roll_surface(fp, utca).map_err(|e| {
                    SolverError::Table(format!("roll surface of the misaligned pair: {e}"))
                })?;
                let tau = fp.pinion.gen.frame.pitch();
                (0..solved as i64)
                    .map(|k| {
                        let phi = spec.start + spec.direction * spec.step * (k - lead) as f64;
                        let geo = geometry(fp, &rs, phi, tau, spec.slices);
                        if geo.slices.is_empty() || !geo.utca_te.is_finite() {
                            return Err(SolverError::NoContact);
                        }
                        Ok(geo.utca_te)
                    })
                    .collect()
            })
            .collect::<Result<_, SolverError>>()?;
        let mut slope = vec![[0.0; 4]; nodes];
        let mut curvature = vec![[0.0; 4]; nodes];
        for i in 0..4 {
            let h = STEPS[i] * si_per_unit(i);
            let (plus, minus) = (&te[2 * i], &te[2 * i + 1]);
            for k in 0..nodes {
                let p = k % solved;
                slope[k][i] = (plus[p] - minus[p]) / (2.0 * h);
                curvature[k][i] = (plus[p] - 2.0 * table.te0[p] + minus[p]) / (h * h);
            }
        }
        Ok(LagShift {
            slope,
            curvature,
            wall_s: t0.elapsed().as_secs_f64(),
            solved_nodes: solved,
        })
    }

    /// s(q₁) and ds/dq₁ interpolated on `table`'s nodes.
    pub fn at(&self, table: &MeshTable, q1: f64) -> Result<([f64; 4], [f64; 4]), SolverError> {
        let mut s = [0.0; 4];
        let mut ds = [0.0; 4];
        for i in 0..4 {
            let [v, d, _] = table.along_q1(|k| self.slope[k][i], q1)?;
            s[i] = v;
            ds[i] = d;
        }
        Ok((s, ds))
    }

    /// ½ Σ |κᵢ(q₁)| mᵢ², rad: the TE the linear shift leaves out at `m`
    /// (κ at the nearest node).
    pub fn nonlinearity(&self, table: &MeshTable, q1: f64, m: &[f64; 4]) -> f64 {
        let n = table.nodes() as i64;
        let k = (q1 / table.spec.step).round() as i64 + table.lead as i64;
        let k = if table.spec.periodic {
            k.rem_euclid(n)
        } else {
            k.clamp(0, n - 1)
        } as usize;
        (0..4)
            .map(|i| 0.5 * self.curvature[k][i].abs() * m[i] * m[i])
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::mesh_table::TableSpec;

    /// A table of `nodes` nodes in steps of `step` with unloaded TE `te0(k)`.
    fn table(periodic: bool, step: f64, te0: Vec<f64>) -> MeshTable {
        let nodes = te0.len();
        MeshTable {
            spec: TableSpec {
                start: 0.0,
                direction: 1.0,
                step,
                positions: nodes - 2,
                periodic,
                slices: 10,
                lag_nodes: 8,
                torque_max_nm: 1.0,
            },
            lead: if periodic { 0 } else { 2 },
            ratio: 0.5,
            lags: vec![],
            te0,
            torque: vec![],
            force: vec![],
            wrench: vec![],
            tangential: vec![],
            friction: vec![],
            root_tension: vec![],
            cpu_s_per_position: 0.0,
            impact: None,
            moments: Default::default(),
        }
    }

    #[test]
    fn shifts_are_solved_over_one_mesh_cycle_only_where_the_unloaded_te_repeats() {
        let tau = 0.3;
        let n = 12;
        let cycle = |k: usize| 1e-5 * ((k % n) as f64).sin();
        let repeating: Vec<f64> = (0..5 * n + 3).map(cycle).collect();
        let lw = table(false, tau / n as f64, repeating.clone());
        assert_eq!(mesh_cycle_phases(&lw, tau), Some(n));
        // A periodic table is solved at its own nodes.
        assert_eq!(
            mesh_cycle_phases(&table(true, tau / n as f64, repeating.clone()), tau),
            None
        );
        // A TE that does not repeat (a 2e-10 rad drift), or a step that does
        // not divide the mesh cycle, is solved everywhere.
        let drifting: Vec<f64> = (0..5 * n + 3)
            .map(|k| cycle(k) + 2e-10 * (k / n) as f64)
            .collect();
        assert_eq!(
            mesh_cycle_phases(&table(false, tau / n as f64, drifting), tau),
            None
        );
        assert_eq!(
            mesh_cycle_phases(&table(false, tau / (n as f64 + 0.5), repeating), tau),
            None
        );
    }
}
