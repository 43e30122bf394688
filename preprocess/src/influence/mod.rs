//! FE unit-load influence fields of one gear body (the reduced model's global
//! compliance), with the local near-load part subtracted.
//!
//! For every grid point p of a loaded flank, a unit normal force pressed into
//! the tooth is spread over the flank faces around p by a smooth bump
//! q(r) ∝ (1 − r²/ρ²)², r < ρ, and the normal displacement at grid point q is
//! measured with the same weights. So C_pq = w_pᵀ K⁻¹ w_q is symmetric by
//! construction. The local part is the same load on the half tooth between
//! the flank and its mid-surface (depth h), held fixed on that surface and
//! where its sides join the rest of the body; global = total − local. The depth-h surface runs
//! through the elements it cuts ([`fem::cut_cell`]), so the local model's
//! support does not move with the mesh. Below the grid's root row the half
//! tooth follows the fillet up to [`FILLET_RISE`] · h above the flank's
//! tangent plane, so its supports there do not crowd the root-row loads.

mod local;
mod patch;
mod root;
mod solves;

pub use local::{half_tooth, local_model, local_supports, HalfTooth, FILLET_RISE, NITSCHE_GAMMA};
pub use patch::{mid_surface_depth, patch_weights};
pub use solves::Solves;

use crate::body_mesh::BodyMesh;
use fem::{clamp_nodes, ClampedBody, Material};
pub use geometry::contact_grid::{rotate_z, FlankGrid, GridSize};
use local::local_field;
use rayon::prelude::*;
use std::time::Instant;

/// The FE material of a member's elastic constants (design data, [`geometry::Material`]).
pub fn fe_material(m: geometry::Material) -> Material {
    Material {
        youngs_modulus_pa: m.youngs_modulus_pa,
        poisson_ratio: m.poisson_ratio,
    }
}

/// Errors of the influence computation.
#[derive(Debug, thiserror::Error)]
pub enum InfluenceError {
    #[error(transparent)]
    Fem(#[from] fem::FemError),
    #[error(transparent)]
    Geometry(#[from] geometry::error::GeometryError),
    #[error("mesh has no face group `{0}`")]
    MissingGroup(String),
    #[error("grid point {point} of tooth {tooth}: {what}")]
    Grid {
        tooth: usize,
        point: usize,
        what: String,
    },
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A sparse weight vector over global dofs (3 · node + component).
pub type Weights = Vec<(usize, f64)>;

/// What to compute for one member.
#[derive(Debug, Clone)]
pub struct InfluenceRequest<'a> {
    pub body: &'a BodyMesh,
    pub material: Material,
    /// Teeth on the member.
    pub teeth: usize,
    /// Loaded flank name ("concave" or "convex") and the opposite one.
    pub loaded: &'a str,
    pub opposite: &'a str,
    /// Tooth 0's grid (rotated by k · 2π/z for tooth k).
    pub grid: &'a FlankGrid,
    /// Teeth whose loaded flank is solved.
    pub solved_teeth: Vec<usize>,
    /// Responding teeth relative to the loaded one (e.g. −2..=2).
    pub offsets: Vec<i32>,
    /// Bump radius ρ, m.
    pub load_radius: f64,
    /// How far above the flank's tangent plane the local half-tooth model
    /// reaches, as a share of h ([`FILLET_RISE`] in the stiffness files).
    pub fillet_rise: f64,
    /// Right-hand sides per sequential solve block (full solves), or loads
    /// per forward block (pruned solves).
    pub block: usize,
    /// How the unit-load fields are solved.
    pub solves: Solves,
    /// The fillets whose root-stress coefficients are wanted (None: none).
    pub root: Option<&'a crate::root_stress::RootStressPoints>,
}

/// Influence fields: `total[s][o][i][j]` is the normal approach (m/N) at
/// point j of tooth solved[s] + offsets[o] under the unit load at point i of
/// tooth solved[s]; `local[s][i][j]` the local part on the loaded tooth;
/// `global` = total − local (on offset 0).
#[derive(Debug, Clone)]
pub struct Influence {
    pub solved_teeth: Vec<usize>,
    pub offsets: Vec<i32>,
    /// Mid-surface depth h of every grid point of every solved tooth, m.
    pub depth: Vec<Vec<f64>>,
    pub total: Vec<f64>,
    pub local: Vec<f64>,
    pub global: Vec<f64>,
    /// Root-stress coefficients, when asked for.
    pub root_stress: Option<formats::stiffness_file::RootStressBlock>,
    pub stats: InfluenceStats,
}

/// Sizes and timings.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct InfluenceStats {
    pub dofs: usize,
    pub factor_nnz: usize,
    pub assemble_s: f64,
    pub factor_s: f64,
    /// Full solves, or the pruned forward solves, s.
    pub solve_s: f64,
    /// Gram products of the pruned forward vectors, s (0 with full solves).
    pub gram_s: f64,
    /// Root-stress coefficients (backward solves on the fillet points'
    /// support, or the full fields' stresses), s.
    #[serde(default)]
    pub root_stress_s: f64,
    /// Unit loads solved (pruned: one per grid point of every loaded or
    /// responding tooth; full: one per grid point of every loaded tooth).
    pub right_hand_sides: usize,
    /// Largest memory the pruned forward vectors held at once, GB.
    pub path_vectors_gb: f64,
    /// Pruned solves: the largest relative difference, over the loaded
    /// teeth, between the middle grid point's influence row from the Gram
    /// products and from a backward solve (None with full solves).
    pub backward_check: Option<f64>,
    pub local_s: f64,
    pub local_elements_mean: f64,
}

fn group<'a>(body: &'a BodyMesh, name: &str) -> Result<&'a [[usize; 6]], InfluenceError> {
    body.groups
        .get(name)
        .map(|v| v.as_slice())
        .ok_or_else(|| InfluenceError::MissingGroup(name.to_string()))
}

/// Weights of every grid point of tooth `k`.
fn tooth_weights(req: &InfluenceRequest, k: usize) -> Result<Vec<Weights>, InfluenceError> {
    let faces = group(req.body, &format!("tooth{k}_{}", req.loaded))?;
    let a = 2.0 * std::f64::consts::PI * k as f64 / req.teeth as f64;
    (0..req.grid.len())
        .into_par_iter()
        .map(|i| {
            let p = rotate_z(req.grid.position[i], a);
            let n = rotate_z(req.grid.normal[i], a);
            patch_weights(&req.body.mesh, faces, p, n.map(|c| -c), req.load_radius).ok_or_else(
                || InfluenceError::Grid {
                    tooth: k,
                    point: i,
                    what: format!(
                        "no flank face within the load radius {:.3} mm",
                        req.load_radius * 1e3
                    ),
                },
            )
        })
        .collect()
}

/// Mid-surface depths of tooth k's grid points. A ray that leaves the tooth
/// through its toe or heel face instead of the opposite flank takes the
/// value of the nearest grid point of the same profile row whose ray meets
/// the opposite flank (the depth varies little along the face). Taking the
/// nearest point of any row put steps of up to 1 mm between neighbouring
/// rows into the end columns' depths, and so into the local model's support
/// surface; which elements fell on either side of a step depended on the
/// mesh, and the local field at the default pinion's heel differed by 20 %
/// between two teeth (global diagonal tooth to tooth: 7.2 % at most, 1.9 %
/// with the row-wise fallback).
fn tooth_depths(req: &InfluenceRequest, k: usize) -> Result<Vec<f64>, InfluenceError> {
    let opp = group(req.body, &format!("tooth{k}_{}", req.opposite))?;
    let a = 2.0 * std::f64::consts::PI * k as f64 / req.teeth as f64;
    let raw: Vec<Option<f64>> = (0..req.grid.len())
        .into_par_iter()
        .map(|i| {
            mid_surface_depth(
                &req.body.mesh,
                opp,
                rotate_z(req.grid.position[i], a),
                rotate_z(req.grid.normal[i], a),
            )
        })
        .collect();
    let np = req.grid.size.profile as i64;
    let mut out = vec![0.0; raw.len()];
    for (i, o) in out.iter_mut().enumerate() {
        let (fi, pi) = (i as i64 / np, i as i64 % np);
        let best = raw
            .iter()
            .enumerate()
            .filter_map(|(j, h)| {
                let (fj, pj) = (j as i64 / np, j as i64 % np);
                h.map(|h| (((pi - pj).abs(), (fi - fj).abs()), h))
            })
            .min_by_key(|x| x.0);
        *o = best
            .ok_or_else(|| InfluenceError::Grid {
                tooth: k,
                point: i,
                what: "no normal ray of this flank meets the opposite flank".into(),
            })?
            .1;
    }
    Ok(out)
}

fn gather(w: &Weights, dofs: &fem::Dofs, u: &[f64]) -> f64 {
    w.iter()
        .filter_map(|&(d, c)| dofs.free_index(d).map(|i| c * u[i]))
        .sum()
}

/// Computes the influence fields. `fixed_groups` are clamped (all components).
pub fn compute(req: &InfluenceRequest, fixed_groups: &[&str]) -> Result<Influence, InfluenceError> {
    let mesh = &req.body.mesh;
    let mut stats = InfluenceStats::default();
    let mut fixed = Vec::new();
    for g in fixed_groups {
        group(req.body, g)?;
        fixed.extend(clamp_nodes(&req.body.group_nodes(g)));
    }
    let ClampedBody {
        dofs,
        factor,
        assemble_s,
        factor_s,
    } = ClampedBody::new(mesh, &req.material, &fixed, req.solves.factorization())?;
    stats.assemble_s = assemble_s;
    stats.dofs = dofs.n_free();
    stats.factor_s = factor_s;
    stats.factor_nnz = factor.factor_nnz();

    let np = req.grid.len();
    let no = req.offsets.len();
    let ns = req.solved_teeth.len();
    let mut local = vec![0.0; ns * np * np];
    let mut depth = Vec::new();
    let mut weights: std::collections::BTreeMap<usize, Vec<Weights>> = Default::default();
    for &k in &req.solved_teeth {
        for &o in &req.offsets {
            let j = solves::tooth_of(req, k, o);
            if let std::collections::btree_map::Entry::Vacant(e) = weights.entry(j) {
                e.insert(tooth_weights(req, j)?);
            }
        }
    }
    let mut targets = root::RootTargets::new(req)?;
    formats::stop_point::at("solving");
    let total = match req.solves {
        Solves::Full => solves::full(req, &dofs, &factor, &weights, &mut stats, &mut targets),
        Solves::Pruned => solves::pruned(req, &dofs, factor, &weights, &mut stats, &mut targets)?,
    };

    let t = Instant::now();
    let mut elements = 0usize;
    for (s, &k) in req.solved_teeth.iter().enumerate() {
        let h = tooth_depths(req, k)?;
        let (loc, ne) = local_field(req, k, &h, &weights[&k])?;
        elements += ne;
        local[s * np * np..(s + 1) * np * np].copy_from_slice(&loc);
        depth.push(h);
    }
    stats.local_s = t.elapsed().as_secs_f64();
    stats.local_elements_mean = elements as f64 / ns.max(1) as f64;

    let mut global = total.clone();
    if let Some(o0) = req.offsets.iter().position(|&o| o == 0) {
        for s in 0..ns {
            for ij in 0..np * np {
                global[(s * no + o0) * np * np + ij] -= local[s * np * np + ij];
            }
        }
    }
    Ok(Influence {
        solved_teeth: req.solved_teeth.clone(),
        offsets: req.offsets.clone(),
        depth,
        total,
        local,
        global,
        root_stress: targets.map(|t| t.block),
        stats,
    })
}
