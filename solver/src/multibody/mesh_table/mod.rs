//! The contact element as a force element between two rigid gear bodies.
//!
//! Generalized coordinates: q₁ the pinion rotation from the sweep start and
//! q₂ the wheel rotation, both in their drive directions, rad, with q₂ = r q₁
//! (r = z₁/z₂) for conjugate motion. The wheel lag (TE) is θ = r q₁ − q₂.
//!
//! At each pinion position the contact element under lag control gives the
//! pinion torque T₁(q₁, θ) = Σ λ₁ F (zero while θ is below the unloaded TE
//! θ₀(q₁)). The mesh's potential is the work of that torque while the
//! pinion turns against the held wheel from first contact:
//!
//!   V(q₁, q₂) = ∫_{s*}^{q₁} T₁(s, r s − q₂) ds,
//!
//! so that ∂V/∂q₁ = T₁ (the quasi-static pinion balance is the LTCA's) and
//! ∂V/∂q₂ = −∫ ∂T₁/∂θ ds (the wheel torque, ≈ T₁/r). T₁ is tabulated on a
//! grid of q₁ × θ and interpolated by cubics in both directions:
//! Catmull–Rom in q₁ (uniform), cubic Hermite with central-difference
//! slopes in θ, whose nodes are fine over the band of unloaded TEs (light
//! loads) and grow geometrically above it ([`lag_grid`]). Along the integration path (a straight line in q₁, θ) that
//! interpolant is a polynomial of degree 6 between grid lines, so its
//! integral is exact from prefix moments of each node's lag interpolant
//! tabulated once ([`PathMoments`]; a few terms per q₁ cell the path
//! crosses; measured 2026-11-28 in the multibody bench, the whole state
//! takes 1.5–2.7 µs where 4-point Gauss–Legendre in every crossed cell
//! took 9–28 µs for the integrals alone): V, its gradient and its Hessian are exact for the
//! interpolated T₁, and the element is conservative (a run without damping keeps V + kinetic energy
//! − work of the torques). The grid is in θ, not in the deflection θ − θ₀:
//! the unloaded TE has kinks where the contact passes from one tooth pair to
//! the next, and T₁ is smooth across them only at fixed θ.

mod evaluate;
mod interpolation;
mod path_moments;
mod tabulate;

pub use interpolation::lag_grid;
pub use path_moments::PathMoments;
pub use tabulate::slice_wrench;

use crate::multibody::impact_law::{Friction, ImpactLaw};
use crate::SolverError;

/// Where and how finely the table is computed.
#[derive(Debug, Clone, Copy)]
pub struct TableSpec {
    /// Pinion angle at q₁ = 0, rad, and its drive direction (±1).
    pub start: f64,
    pub direction: f64,
    /// q₁ step, rad, and number of positions.
    pub step: f64,
    pub positions: usize,
    /// Periodic over `positions · step` (standard blanks: one angular pitch).
    pub periodic: bool,
    pub slices: usize,
    /// Lag nodes from below the smallest unloaded TE up to the largest lag
    /// under `torque_max_nm`.
    pub lag_nodes: usize,
    pub torque_max_nm: f64,
}

/// The tabulated force element.
#[derive(Debug, Clone)]
pub struct MeshTable {
    pub spec: TableSpec,
    /// Nodes before q₁ = 0 (non-periodic tables): the potential's path
    /// integral starts at first contact, up to (θ_max − θ_lo)/r before q₁.
    pub lead: usize,
    /// r = z₁/z₂.
    pub ratio: f64,
    /// Lag nodes θ_m, rad ([`lag_grid`]: fine over the band of unloaded TEs
    /// where light loads act, growing geometrically above it).
    pub lags: Vec<f64>,
    /// Unloaded TE θ₀ per position, rad.
    pub te0: Vec<f64>,
    /// Pinion torque T₁ (N·m) and the contact force on the wheel in the
    /// fixed frame (N): row-major positions × lag nodes.
    pub torque: Vec<f64>,
    pub force: Vec<[f64; 3]>,
    /// The contact's wrench on the wheel about the pitch apex, [N; N·m],
    /// in the frame of the wheel's bearings (the pair's relative pose
    /// applied to the pinion's points and normals): Σ F [n; x × n], same
    /// layout ([`slice_wrench`]).
    pub wrench: Vec<[f64; 6]>,
    /// Friction moments per unit friction coefficient (Φ₁, Φ₂) = (Σ F ℓ₁,
    /// Σ F ℓ₂), N·m (see [`crate::element::slices::friction_levers`]), same layout.
    pub friction: Vec<[f64; 2]>,
    /// Tangential (circumferential) component of the contact force on the
    /// wheel, Σ F λ₂ / ρ₂ (N, [`crate::element::slices::Slice::wheel_tangential`]),
    /// same layout.
    pub tangential: Vec<f64>,
    /// Largest first principal stress in a loaded flank's fillet over the
    /// loaded teeth, [pinion, wheel], Pa, same layout; empty unless the
    /// table was built with root stress and the stiffness files hold
    /// root-stress coefficients ([`MeshTable::build_with_root_stress`]).
    pub root_tension: Vec<[f64; 2]>,
    /// Geometry + assembly + lag-controlled solves, s per position (one core).
    pub cpu_s_per_position: f64,
    /// The impact law's own fields when the table holds that law instead of
    /// the element ([`crate::multibody::impact_table`]); None for the element.
    pub impact: Option<ImpactFields>,
    /// Prefix moments of the torque's lag interpolants, for the potential's
    /// path integral ([`PathMoments`]); empty: integrated by quadrature.
    pub moments: PathMoments,
}

/// Fields of an impact-law table ([`crate::multibody::impact_table`]), same layout as
/// the torque.
#[derive(Debug, Clone)]
pub struct ImpactFields {
    pub law: ImpactLaw,
    pub friction: Option<Friction>,
    /// Damping levers A = (Σ w λ₁ λ₂, Σ w λ₂²) and E = (Σ w λ₁ ε,
    /// Σ w λ₂ ε), ε = λ₁ − r λ₂, m²: generalized damping forces
    /// −C (A₁ θ̇ + E₁ q̇₁) on q₁ and +C (A₂ θ̇ + E₂ q̇₁) on q₂.
    pub damping: Vec<[f64; 4]>,
    /// Force-weighted mean slip speed per unit pinion speed, m/rad.
    pub slip: Vec<f64>,
}

/// The impact law's non-conservative fields at (q₁, q₂).
#[derive(Debug, Clone, Copy, Default)]
pub struct ImpactState {
    /// Damping levers (A₁, A₂, E₁, E₂) and their derivatives ∂/∂q_j.
    pub damping: [f64; 4],
    pub damping_grad: [[f64; 2]; 4],
    /// Mean slip speed per unit pinion speed, m/rad.
    pub slip: f64,
}

/// The element's state at (q₁, q₂).
#[derive(Debug, Clone, Copy, Default)]
pub struct MeshState {
    /// Wheel lag θ and its distance above the unloaded TE, rad.
    pub theta: f64,
    pub u: f64,
    /// Potential V (J), gradient ∂V/∂q (N·m), Hessian (N·m/rad).
    pub potential: f64,
    pub grad: [f64; 2],
    pub hess: [[f64; 2]; 2],
    /// Contact force on the wheel, fixed frame, N (interpolated; output only).
    pub force: [f64; 3],
}

/// Refuses a table spec too small to interpolate (both force laws).
pub(crate) fn check_spec(spec: &TableSpec) -> Result<(), SolverError> {
    let min_lags = geometry::scene_checks::MIN_TABLE_LAG_NODES;
    if spec.positions < 4 || spec.lag_nodes < min_lags {
        return Err(SolverError::Table(format!(
            "{} positions × {} lag nodes: need at least 4 positions and {min_lags} lag nodes (multibody.table_lag_nodes)",
            spec.positions, spec.lag_nodes
        )));
    }
    Ok(())
}

/// The table's columns and lag grid, shared by both force laws: `pass1`
/// computes the columns of a range of position indices, `lags_of` gives a
/// column's unloaded TE and its lag at the largest torque. A non-periodic
/// table starts `lead` positions before q₁ = 0, (θ_hi − θ_lo)/r plus two
/// steps, since V at q₁ integrates T₁ from first contact, q₁ − (θ − θ_lo)/r.
/// Returns the columns (lead first), `lead` and the lag grid.
pub(crate) fn columns_and_lags<C>(
    spec: &TableSpec,
    ratio: f64,
    pass1: impl Fn(std::ops::Range<i64>) -> Result<Vec<C>, SolverError>,
    lags_of: impl Fn(&C) -> (f64, f64),
) -> Result<(Vec<C>, usize, Vec<f64>), SolverError> {
    let range = |c: &[C]| {
        c.iter().map(&lags_of).fold(
            (f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
            |(lo, hi, te_max), (te0, lag)| (lo.min(te0), hi.max(lag), te_max.max(te0)),
        )
    };
    let mut columns = pass1(0..spec.positions as i64)?;
    let lead = if spec.periodic {
        0
    } else {
        let (lo, hi, _) = range(&columns);
        ((hi - lo) / ratio / spec.step).ceil() as usize + 2
    };
    if lead > 0 {
        let mut before = pass1(-(lead as i64)..0)?;
        before.append(&mut columns);
        columns = before;
    }
    let (lo, hi, te0_max) = range(&columns);
    let lags = lag_grid(lo, te0_max, hi, spec.lag_nodes);
    Ok((columns, lead, lags))
}

/// One position's column of the table (both force laws): the unloaded TE,
/// and per lag node the pinion torque, contact force and friction moments.
pub(crate) struct Column {
    pub(crate) te0: f64,
    pub(crate) torque: Vec<f64>,
    pub(crate) force: Vec<[f64; 3]>,
    pub(crate) wrench: Vec<[f64; 6]>,
    pub(crate) friction: Vec<[f64; 2]>,
    pub(crate) tangential: Vec<f64>,
    /// Empty without root-stress coefficients.
    pub(crate) root_tension: Vec<[f64; 2]>,
    pub(crate) cpu: f64,
}
