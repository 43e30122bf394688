//! The local (near-load) part of the influence fields: the half tooth
//! between the loaded flank and its mid-surface, cut through its elements
//! at the depth h, tied there by Nitsche's method and clamped at its sides.

use super::{dist, dot, gather, InfluenceError, InfluenceRequest, Weights};
use fem::cholesky::Ordering;
use fem::{Dofs, Factor, TetMesh};
use geometry::contact_grid::rotate_z;
use rayon::prelude::*;

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
pub(super) fn local_field(
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
