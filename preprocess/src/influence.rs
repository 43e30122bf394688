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

use crate::body_mesh::BodyMesh;
use fem::cholesky::Ordering;
use fem::{clamp_nodes, tri6, ClampedBody, Dofs, Factor, Factorization, Material, TetMesh};
pub use geometry::contact_grid::{rotate_z, FlankGrid, GridSize};
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

/// The bump's consistent nodal forces on `faces` (node → force) and their sum.
fn bump_forces(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    center: [f64; 3],
    radius: f64,
) -> (std::collections::BTreeMap<usize, f64>, f64) {
    let bump = |p: [f64; 3]| {
        let r2 = (0..3).map(|c| (p[c] - center[c]).powi(2)).sum::<f64>() / (radius * radius);
        if r2 < 1.0 {
            (1.0 - r2).powi(2)
        } else {
            0.0
        }
    };
    let mut acc: std::collections::BTreeMap<usize, f64> = Default::default();
    let mut total = 0.0;
    for f in faces {
        let x = f.map(|i| mesh.nodes[i]);
        let size = (1..6).map(|k| dist(x[0], x[k])).fold(0.0, f64::max);
        if dist(x[0], center) > radius + size {
            continue;
        }
        let fe = tri6::consistent_forces(&x, |p, _| [bump(p), 0.0, 0.0]);
        for (l, &node) in f.iter().enumerate() {
            if fe[l][0] != 0.0 {
                *acc.entry(node).or_default() += fe[l][0];
                total += fe[l][0];
            }
        }
    }
    (acc, total)
}

/// Weights of a unit force along `dir` at `center`, spread over `faces` by the
/// bump q(r) ∝ (1 − r²/ρ²)² (r < ρ) and integrated consistently (6-point rule
/// per tri6 face). The weights sum to `dir` (1 N).
///
/// Where the faces near `center` are so coarse that no quadrature point lies
/// within ρ (a fine contact grid's small patch on a tooth the mesh did not
/// refine: only its far-field response is used), ρ is widened to the
/// nearest face's size, the smallest patch that face's quadrature can carry.
pub fn patch_weights(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    center: [f64; 3],
    dir: [f64; 3],
    radius: f64,
) -> Option<Weights> {
    let (mut acc, mut total) = bump_forces(mesh, faces, center, radius);
    if total <= 0.0 {
        let nearest = faces
            .iter()
            .map(|f| {
                let x = f.map(|i| mesh.nodes[i]);
                let size = (1..6).map(|k| dist(x[0], x[k])).fold(0.0, f64::max);
                (dist(x[0], center), size)
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))?;
        if nearest.0 <= radius + nearest.1 {
            (acc, total) = bump_forces(mesh, faces, center, radius.max(nearest.1));
        }
    }
    if total <= 0.0 {
        return None;
    }
    Some(
        acc.into_iter()
            .flat_map(|(node, w)| (0..3).map(move |c| (3 * node + c, w / total * dir[c])))
            .collect(),
    )
}

/// Half the tooth thickness along −n from `p`: the distance to the first hit
/// on the opposite flank's faces, halved (the mid-surface depth h).
pub fn mid_surface_depth(
    mesh: &TetMesh,
    opposite: &[[usize; 6]],
    p: [f64; 3],
    n: [f64; 3],
) -> Option<f64> {
    let d = n.map(|c| -c);
    let mut best: Option<f64> = None;
    const SUB: [[usize; 3]; 4] = [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]];
    for f in opposite {
        for t in SUB {
            let [a, b, c] = t.map(|l| mesh.nodes[f[l]]);
            if let Some(s) = ray_triangle(p, d, a, b, c) {
                if s > 0.0 && best.is_none_or(|b| s < b) {
                    best = Some(s);
                }
            }
        }
    }
    best.map(|s| 0.5 * s)
}

/// Möller–Trumbore ray/triangle intersection: distance along `d` or None.
fn ray_triangle(o: [f64; 3], d: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<f64> {
    let sub = |x: [f64; 3], y: [f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let cross = |x: [f64; 3], y: [f64; 3]| {
        [
            x[1] * y[2] - x[2] * y[1],
            x[2] * y[0] - x[0] * y[2],
            x[0] * y[1] - x[1] * y[0],
        ]
    };
    let (e1, e2) = (sub(b, a), sub(c, a));
    let pv = cross(d, e2);
    let det = dot(e1, pv);
    if det.abs() < 1e-30 {
        return None;
    }
    let tv = sub(o, a);
    let u = dot(tv, pv) / det;
    if !(-1e-9..=1.0 + 1e-9).contains(&u) {
        return None;
    }
    let qv = cross(tv, e1);
    let v = dot(d, qv) / det;
    if v < -1e-9 || u + v > 1.0 + 1e-9 {
        return None;
    }
    Some(dot(e2, qv) / det)
}

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
    /// Right-hand sides per sequential solve block.
    pub block: usize,
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
    pub stats: InfluenceStats,
}

/// Sizes and timings.
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct InfluenceStats {
    pub dofs: usize,
    pub factor_nnz: usize,
    pub assemble_s: f64,
    pub factor_s: f64,
    pub solve_s: f64,
    pub right_hand_sides: usize,
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

fn gather(w: &Weights, dofs: &Dofs, u: &[f64]) -> f64 {
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
    } = ClampedBody::new(mesh, &req.material, &fixed, Factorization::Auto)?;
    stats.assemble_s = assemble_s;
    stats.dofs = dofs.n_free();
    stats.factor_s = factor_s;
    stats.factor_nnz = factor.factor_nnz();

    let z = req.teeth as i64;
    let np = req.grid.len();
    let no = req.offsets.len();
    let ns = req.solved_teeth.len();
    let mut total = vec![0.0; ns * no * np * np];
    let mut local = vec![0.0; ns * np * np];
    let mut depth = Vec::new();
    let mut weights: std::collections::BTreeMap<usize, Vec<Weights>> = Default::default();
    let n = dofs.n_free();
    let batch = (2 * req.block).max(1);
    let t = Instant::now();
    for (s, &k) in req.solved_teeth.iter().enumerate() {
        for &o in &req.offsets {
            let j = (k as i64 + o as i64).rem_euclid(z) as usize;
            if let std::collections::btree_map::Entry::Vacant(e) = weights.entry(j) {
                e.insert(tooth_weights(req, j)?);
            }
        }
        let wk = &weights[&k];
        for start in (0..np).step_by(batch) {
            let cols: Vec<usize> = (start..(start + batch).min(np)).collect();
            let mut rhs = vec![0.0; n * cols.len()];
            for (c, &i) in cols.iter().enumerate() {
                for &(d, v) in &wk[i] {
                    if let Some(f) = dofs.free_index(d) {
                        rhs[c * n + f] += v;
                    }
                }
            }
            factor.solve_many(&mut rhs, req.block);
            stats.right_hand_sides += cols.len();
            for (c, &i) in cols.iter().enumerate() {
                let u = &rhs[c * n..(c + 1) * n];
                for (oi, &o) in req.offsets.iter().enumerate() {
                    let j = (k as i64 + o as i64).rem_euclid(z) as usize;
                    let row = ((s * no + oi) * np + i) * np;
                    for (q, w) in weights[&j].iter().enumerate() {
                        total[row + q] = gather(w, &dofs, u);
                    }
                }
            }
        }
    }
    stats.solve_s = t.elapsed().as_secs_f64();

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
        stats,
    })
}

/// Nitsche parameter of the local model's tie on its far side: α_T = γ λ_T
/// per cut element ([`fem::cut_cell::Tie::Nitsche`]; γ > 2 keeps it
/// coercive, 4 leaves a(v, v)/2 + 2 λ_T ‖v‖²). The penalty tie it replaces
/// (α = 1e4 E/ℓ) locked the cut elements: on the default scene's standard
/// wheel the reduced mesh's local field grew 2.3–3.2 % stiffer per decade of
/// α (1e2 to 1e5), and its global diagonal changed by up to 3.24 % (mean 0.44 %) between
/// the reduced and the medium mesh, against 2.31 % (0.22 %) with Nitsche's
/// tie at γ = 4; γ = 3 and 10 give 2.13 and 2.87 %.
pub const NITSCHE_GAMMA: f64 = 4.0;

/// Ghost stiffness of the cut elements' outside parts, relative.
const GHOST: f64 = 1e-9;

/// One-line description of the local model with its fillet rise (see
/// [`FILLET_RISE`]), part of the stiffness files' configuration (and so of
/// their hash).
pub fn local_model(fillet_rise: f64) -> String {
    format!(
        "half tooth to depth h (half the thickness along the normal; where the normal leaves through toe or heel, the nearest point's of the same profile row) cut through its elements (cut cells), far side tied by Nitsche's method (gamma {NITSCHE_GAMMA} times the element's trace-inverse bound), sides clamped, reaching 0.6 grid spacings + the load radius beyond the grid and up to {fillet_rise} h above the flank's tangent plane (the fillet)"
    )
}

/// How far above a grid point's tangent plane (outside the tooth, as a
/// share of its depth h) an element's centroid may lie and still belong to
/// the half tooth. The flank's own surface lies below its tangent planes
/// (convex profile) or a few µm above them (lengthwise curvature); the
/// fillet under the root row curves out of the tangent plane. With 0 the
/// fillet elements next to the root row were supports, 1.1–1.4 mm from the
/// root-row points (load radius 2 mm) on the default scene's pinion, and
/// the local diagonal there changed by up to 21 % between the reduced and
/// the medium mesh; with 0.3 the supports move 2.2–2.5 mm away and the
/// root row's global diagonal changes by at most 1.4 % (0.5 gives the same
/// fields within 0.04 % on the mean; both measured with the penalty tie that
/// [`NITSCHE_GAMMA`]'s tie replaced). Along the root-row normals the facing flank
/// of the neighbouring tooth is 4.6 mm away on the default pinion (h =
/// 4.5 mm) and 4.85 mm on its wheel (h = 4.3 mm), so 0.3 h keeps to the
/// loaded tooth's own half of the space.
pub const FILLET_RISE: f64 = 0.3;

/// Where an element stands with respect to the half tooth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HalfTooth {
    /// In the half tooth (whole or cut), with the level set at its vertices.
    Kept([f64; 4]),
    /// Below the half tooth: beyond the depth h, under the loaded flank.
    Deep,
    /// Beside it (or far away).
    Beside,
}

/// Every element's place in the half tooth under tooth k's loaded flank,
/// with the level set φ = h_g − t at the vertices of those kept: t the depth
/// below grid point g (the nearest to the element's centroid) along its
/// inward normal, h_g that point's mid-surface depth. Kept: elements whose
/// centroid lies below the flank's tangent plane at g or at most
/// `fillet_rise` · h_g above it (t ≥ −fillet_rise · h_g), within 0.6 grid spacings + the
/// load radius of g sideways, and that have a vertex with φ > 0 (some of
/// their material above the depth h). The depth h itself cuts through
/// elements: it does not move with the mesh.
pub fn half_tooth(req: &InfluenceRequest, k: usize, h: &[f64]) -> Vec<HalfTooth> {
    let a = 2.0 * std::f64::consts::PI * k as f64 / req.teeth as f64;
    let pts: Vec<[f64; 3]> = req.grid.position.iter().map(|&p| rotate_z(p, a)).collect();
    let nrm: Vec<[f64; 3]> = req.grid.normal.iter().map(|&p| rotate_z(p, a)).collect();
    let (sf, sp) = req.grid.spacing();
    let lateral_max = 0.6 * sf.max(sp) + req.load_radius;
    let hmax = h.iter().copied().fold(0.0, f64::max);
    let center = pts
        .iter()
        .fold([0.0; 3], |c, p| [c[0] + p[0], c[1] + p[1], c[2] + p[2]])
        .map(|c| c / pts.len() as f64);
    let reach = pts.iter().map(|&p| dist(p, center)).fold(0.0, f64::max) + hmax + lateral_max;
    let mesh = &req.body.mesh;
    (0..mesh.tets.len())
        .into_par_iter()
        .map(|e| {
            let t = &mesh.tets[e];
            let c = (0..4).fold([0.0; 3], |c, l| {
                let x = mesh.nodes[t[l]];
                [c[0] + 0.25 * x[0], c[1] + 0.25 * x[1], c[2] + 0.25 * x[2]]
            });
            if dist(c, center) > reach {
                return HalfTooth::Beside;
            }
            let (g, _) = pts
                .iter()
                .enumerate()
                .map(|(g, &p)| (g, dist(p, c)))
                .fold((0, f64::INFINITY), |b, x| if x.1 < b.1 { x } else { b });
            let depth = |x: [f64; 3]| {
                dot(
                    [pts[g][0] - x[0], pts[g][1] - x[1], pts[g][2] - x[2]],
                    nrm[g],
                )
            };
            let dc = depth(c);
            let lat = [0, 1, 2].map(|i| c[i] - pts[g][i] + dc * nrm[g][i]);
            let phi: [f64; 4] = std::array::from_fn(|l| h[g] - depth(mesh.nodes[t[l]]));
            if dc < -req.fillet_rise * h[g] || dot(lat, lat).sqrt() > lateral_max {
                HalfTooth::Beside
            } else if phi.iter().any(|&p| p > 0.0) {
                HalfTooth::Kept(phi)
            } else {
                HalfTooth::Deep
            }
        })
        .collect()
}

/// Nodes of the half tooth that are held fixed where its sides join the
/// rest of the body: those of kept elements that also belong to an element
/// beside it.
pub fn local_supports(mesh: &TetMesh, place: &[HalfTooth]) -> Vec<usize> {
    let mut inside = vec![false; mesh.nodes.len()];
    let mut beside = vec![false; mesh.nodes.len()];
    for (e, p) in place.iter().enumerate() {
        let mark = match p {
            HalfTooth::Kept(_) => &mut inside,
            HalfTooth::Beside => &mut beside,
            HalfTooth::Deep => continue,
        };
        mesh.tets[e].iter().for_each(|&i| mark[i] = true);
    }
    (0..mesh.nodes.len())
        .filter(|&i| inside[i] && beside[i])
        .collect()
}

/// The local field of tooth k: the half-tooth model, tied to zero
/// displacement on its far side (the depth-h surface, through the elements
/// it cuts) and clamped where its sides join the rest of the body, under the
/// same loads, measured with the same weights on tooth k. Returns the
/// np × np block and the element count.
fn local_field(
    req: &InfluenceRequest,
    k: usize,
    h: &[f64],
    w: &[Weights],
) -> Result<(Vec<f64>, usize), InfluenceError> {
    let mesh = &req.body.mesh;
    let place = half_tooth(req, k, h);
    let mut elements = Vec::new();
    let mut phi = Vec::new();
    let mut inside = vec![false; mesh.nodes.len()];
    for (e, p) in place.iter().enumerate() {
        if let HalfTooth::Kept(f) = p {
            elements.push(e);
            phi.push(*f);
            mesh.tets[e].iter().for_each(|&i| inside[i] = true);
        }
    }
    let mut support = vec![false; mesh.nodes.len()];
    for i in local_supports(mesh, &place) {
        support[i] = true;
    }
    // Every loaded node must be a free node of the half tooth: a load on a
    // support or outside it would be lost from the local field.
    for (i, wi) in w.iter().enumerate() {
        if let Some(&(d, _)) = wi.iter().find(|(d, _)| !inside[d / 3] || support[d / 3]) {
            return Err(InfluenceError::Grid {
                tooth: k,
                point: i,
                what: format!(
                    "its load patch reaches node {} {} the local half-tooth model",
                    d / 3,
                    if inside[d / 3] {
                        "on a support of"
                    } else {
                        "outside"
                    }
                ),
            });
        }
    }
    let (sub, old_of) = mesh.submesh(&elements);
    let mut new_of = vec![usize::MAX; mesh.nodes.len()];
    for (new, &old) in old_of.iter().enumerate() {
        new_of[old] = new;
    }
    let fixed: Vec<(usize, f64)> = old_of
        .iter()
        .enumerate()
        .filter(|(_, &old)| support[old])
        .flat_map(|(new, _)| (0..3).map(move |c| (3 * new + c, 0.0)))
        .collect();
    let dofs = Dofs::new(&sub, &fixed)?;
    req.material.validate()?;
    let (lambda, mu) = req.material.lame();
    let tie = fem::cut_cell::Tie::Nitsche {
        gamma: NITSCHE_GAMMA,
    };
    let sys = fem::assemble_with(&sub, &dofs, |e, x| {
        fem::cut_cell::cut_stiffness(x, lambda, mu, phi[e], tie, GHOST)
    })?;
    let factor = Factor::new(&sys.matrix, &dofs.node_of_free(), Ordering::Metis)?;
    let map_w = |w: &Weights| -> Weights {
        w.iter()
            .map(|&(d, v)| (3 * new_of[d / 3] + d % 3, v))
            .collect()
    };
    let wl: Vec<Weights> = w.iter().map(map_w).collect();
    let np = w.len();
    let n = dofs.n_free();
    let mut rhs = vec![0.0; n * np];
    for (i, wi) in wl.iter().enumerate() {
        for &(d, v) in wi {
            if let Some(f) = dofs.free_index(d) {
                rhs[i * n + f] += v;
            }
        }
    }
    factor.solve_many(&mut rhs, req.block);
    let mut out = vec![0.0; np * np];
    for i in 0..np {
        let u = &rhs[i * n..(i + 1) * n];
        for (q, wq) in wl.iter().enumerate() {
            out[i * np + q] = gather(wq, &dofs, u);
        }
    }
    Ok((out, elements.len()))
}

#[cfg(test)]
mod patch_tests {
    use super::*;

    /// One flat tri6 face of 10 mm legs in z = 0 (corners, then mid-edges).
    fn coarse_face() -> (TetMesh, Vec<[usize; 6]>) {
        let h = 0.01;
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [h, 0.0, 0.0],
            [0.0, h, 0.0],
            [h / 2.0, 0.0, 0.0],
            [h / 2.0, h / 2.0, 0.0],
            [0.0, h / 2.0, 0.0],
        ];
        (
            TetMesh {
                nodes,
                tets: Vec::new(),
            },
            vec![[0, 1, 2, 3, 4, 5]],
        )
    }

    #[test]
    fn patch_smaller_than_a_coarse_face_is_widened_and_carries_one_newton() {
        let (mesh, faces) = coarse_face();
        let dir = [0.0, 0.0, -1.0];
        // 0.1 mm patch inside a 10 mm face: no quadrature point within it.
        let w = patch_weights(&mesh, &faces, [0.003, 0.003, 0.0], dir, 1e-4)
            .expect("widened to the face");
        let fz: f64 = w.iter().filter(|(d, _)| d % 3 == 2).map(|(_, v)| v).sum();
        assert!((fz + 1.0).abs() < 1e-12, "sum of weights {fz}");
        // Far from every face: still refused.
        assert!(patch_weights(&mesh, &faces, [0.5, 0.5, 0.0], dir, 1e-4).is_none());
    }
}
