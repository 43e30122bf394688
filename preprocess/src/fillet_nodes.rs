//! The root-fillet nodes of a meshed gear body: for each tooth asked for
//! and each of its two flanks, the body's surface nodes that lie on the
//! fillet the blade edge generated below that flank, each with where it
//! sits: its face-width position ξ (0 toe, 1 heel, the flank's own) and its
//! fillet height h (0 at the root, 1 at the junction with the flank).
//!
//! The mesh has no fillet group of its own (the fillet is part of the
//! `body` surface), so the nodes are found by geometry: the generated
//! fillet of tooth 0 ([`geometry::generation::GeneratedFlank::eval_fillet`])
//! is sampled on a grid of [`FACE_SAMPLES`] × [`HEIGHT_SAMPLES`] points,
//! turned onto tooth k by the whole number of pitches that brings the
//! generated flank onto the mesh group `tooth{k}_{flank}`, and a surface
//! node belongs to that fillet when its nearest sample is within
//! [`NORMAL_TOLERANCE_M`] along the sample's normal and within three
//! quarters of a sample spacing along the fillet in both directions. The
//! normal tolerance covers the CAD surfaces' fit of the generated fillet
//! (tens of µm) and the ease-off at the junction; the spacing bound lets a
//! node at most half a spacing past the root or junction row, where the
//! fillet runs tangentially into the root cone or the flank.

use crate::body_mesh::BodyMesh;
use geometry::error::GeometryError;
use geometry::flank::Flank;
use std::f64::consts::TAU;

/// Samples of the fillet across the face width.
pub const FACE_SAMPLES: usize = 61;
/// Samples of the fillet from the root to the flank junction.
pub const HEIGHT_SAMPLES: usize = 17;
/// A node's largest distance from the fillet along its normal, m.
pub const NORMAL_TOLERANCE_M: f64 = 50e-6;

/// Which flank of a tooth a fillet lies under.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FilletSide {
    /// Under the flank that carries the load.
    Loaded,
    /// Under the tooth's other flank.
    Opposite,
}

impl FilletSide {
    pub fn name(self) -> &'static str {
        match self {
            FilletSide::Loaded => "loaded",
            FilletSide::Opposite => "opposite",
        }
    }
}

/// One tooth's fillet on one side: its nodes and where each sits.
#[derive(Debug, Clone)]
pub struct Fillet {
    pub tooth: usize,
    pub side: FilletSide,
    pub nodes: Vec<usize>,
    /// Face-width position of each node (0 toe, 1 heel).
    pub xi: Vec<f64>,
    /// Fillet height of each node (0 root, 1 flank junction).
    pub height: Vec<f64>,
    /// Largest distance of a node from the sampled fillet along its
    /// normal, m.
    pub max_normal_distance_m: f64,
    /// The rotation about the member axis that brings tooth 0's fillet
    /// onto this one, rad (a whole number of pitches).
    pub turn: f64,
}

/// Errors finding the fillet nodes.
#[derive(Debug, thiserror::Error)]
pub enum FilletError {
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    #[error("mesh has no physical group {0}")]
    MissingGroup(String),
    #[error("tooth {tooth}: no surface node lies on the {side} fillet (flank group {group})")]
    Empty {
        tooth: usize,
        side: &'static str,
        group: String,
    },
}

/// A sample of the fillet: position, unit normal, (ξ, h), and its unit
/// tangents across the face and up the fillet with the spacing to the
/// next sample along each.
#[derive(Debug, Clone, Copy)]
struct Sample {
    pos: [f64; 3],
    normal: [f64; 3],
    xi: f64,
    height: f64,
    along_face: ([f64; 3], f64),
    up: ([f64; 3], f64),
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: [f64; 3]) -> ([f64; 3], f64) {
    let n = dot(a, a).sqrt();
    (a.map(|c| c / n), n)
}

fn turn(p: [f64; 3], angle: f64) -> [f64; 3] {
    let (s, c) = angle.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
}

/// The sampled fillet under `flank` (tooth 0, member frame).
fn samples(flank: &Flank) -> Result<Vec<Sample>, GeometryError> {
    let (nf, nh) = (FACE_SAMPLES, HEIGHT_SAMPLES);
    let mut raw = Vec::with_capacity(nf * nh);
    for i in 0..nf {
        let xi = i as f64 / (nf - 1) as f64;
        let (l, _) = flank.bounds.from_unit(xi, 0.0);
        let arc = flank.fillet_arc_at(l)?;
        // The meshed fillet carries the flank's ease-off at the junction,
        // fading to zero at the root (geometry::gear_body).
        let e = flank
            .at(l, flank.bounds.low.at(l, flank.bounds.rm))?
            .ease_off;
        for k in 0..nh {
            let height = k as f64 / (nh - 1) as f64;
            let q = flank.gen.eval_fillet(1.0 - height, arc);
            let pos = std::array::from_fn(|c| q.pos[c] - e * height * q.normal[c]);
            raw.push((pos, q.normal, xi, height));
        }
    }
    let at = |i: usize, k: usize| raw[i * nh + k].0;
    let mut out = Vec::with_capacity(raw.len());
    for i in 0..nf {
        for k in 0..nh {
            let (pos, normal, xi, height) = raw[i * nh + k];
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(nf - 1));
            let (k0, k1) = (k.saturating_sub(1), (k + 1).min(nh - 1));
            let (tf, lf) = unit(sub(at(i1, k), at(i0, k)));
            let (tu, lu) = unit(sub(at(i, k1), at(i, k0)));
            out.push(Sample {
                pos,
                normal,
                xi,
                height,
                along_face: (tf, lf / (i1 - i0) as f64),
                up: (tu, lu / (k1 - k0) as f64),
            });
        }
    }
    Ok(out)
}

/// Angle about the member axis of the mean of `points`.
fn mean_angle(points: impl Iterator<Item = [f64; 3]>) -> f64 {
    let (mut x, mut y) = (0.0, 0.0);
    for p in points {
        x += p[0];
        y += p[1];
    }
    y.atan2(x)
}

/// The rotation (a whole number of pitches) that brings tooth 0's `flank`
/// onto the mesh's flank faces `group`.
fn tooth_turn(
    mesh: &BodyMesh,
    group: &str,
    flank: &Flank,
    teeth: usize,
) -> Result<f64, FilletError> {
    let nodes = mesh.group_nodes(group);
    if nodes.is_empty() {
        return Err(FilletError::MissingGroup(group.to_string()));
    }
    let of_mesh = mean_angle(nodes.iter().map(|&n| mesh.mesh.nodes[n]));
    let mut pts = Vec::new();
    for i in 0..5 {
        for k in 0..5 {
            pts.push(flank.at_unit(i as f64 / 4.0, k as f64 / 4.0)?.pos);
        }
    }
    let of_flank = mean_angle(pts.into_iter());
    let pitch = TAU / teeth as f64;
    Ok(((of_mesh - of_flank) / pitch).round() * pitch)
}

/// The fillet nodes of each tooth of `teeth` on both sides, `loaded` and
/// `opposite` the member's generated flanks (tooth 0), named in the mesh
/// `loaded_name` / `opposite_name` (`concave` / `convex`), `z` the
/// member's number of teeth. In the order tooth by tooth, loaded side
/// first.
pub fn fillet_nodes(
    mesh: &BodyMesh,
    [loaded, opposite]: [&Flank; 2],
    [loaded_name, opposite_name]: [&str; 2],
    z: usize,
    teeth: &[usize],
) -> Result<Vec<Fillet>, FilletError> {
    let surface = mesh.mesh.boundary_nodes();
    let sides = [
        (FilletSide::Loaded, loaded, loaded_name, samples(loaded)?),
        (
            FilletSide::Opposite,
            opposite,
            opposite_name,
            samples(opposite)?,
        ),
    ];
    let mut out = Vec::new();
    for &tooth in teeth {
        for (side, flank, name, s0) in &sides {
            let group = format!("tooth{tooth}_{name}");
            let angle = tooth_turn(mesh, &group, flank, z)?;
            let s: Vec<Sample> = s0
                .iter()
                .map(|s| Sample {
                    pos: turn(s.pos, angle),
                    normal: turn(s.normal, angle),
                    along_face: (turn(s.along_face.0, angle), s.along_face.1),
                    up: (turn(s.up.0, angle), s.up.1),
                    ..*s
                })
                .collect();
            let reach = s
                .iter()
                .map(|s| s.along_face.1.max(s.up.1))
                .fold(0.0, f64::max);
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for p in &s {
                for c in 0..3 {
                    lo[c] = lo[c].min(p.pos[c] - reach);
                    hi[c] = hi[c].max(p.pos[c] + reach);
                }
            }
            let mut f = Fillet {
                tooth,
                side: *side,
                nodes: vec![],
                xi: vec![],
                height: vec![],
                max_normal_distance_m: 0.0,
                turn: angle,
            };
            for &n in &surface {
                let x = mesh.mesh.nodes[n];
                if (0..3).any(|c| x[c] < lo[c] || x[c] > hi[c]) {
                    continue;
                }
                let near = s
                    .iter()
                    .min_by(|a, b| {
                        let da = sub(x, a.pos);
                        let db = sub(x, b.pos);
                        dot(da, da).total_cmp(&dot(db, db))
                    })
                    .expect("samples");
                let d = sub(x, near.pos);
                let normal = dot(d, near.normal).abs();
                let across = dot(d, near.along_face.0);
                let up = dot(d, near.up.0);
                if normal > NORMAL_TOLERANCE_M
                    || across.abs() > 0.75 * near.along_face.1
                    || up.abs() > 0.75 * near.up.1
                {
                    continue;
                }
                let step_xi = 1.0 / (FACE_SAMPLES - 1) as f64;
                let step_h = 1.0 / (HEIGHT_SAMPLES - 1) as f64;
                f.nodes.push(n);
                f.xi.push((near.xi + across / near.along_face.1 * step_xi).clamp(0.0, 1.0));
                f.height
                    .push((near.height + up / near.up.1 * step_h).clamp(0.0, 1.0));
                f.max_normal_distance_m = f.max_normal_distance_m.max(normal);
            }
            if f.nodes.is_empty() {
                return Err(FilletError::Empty {
                    tooth,
                    side: side.name(),
                    group,
                });
            }
            out.push(f);
        }
    }
    Ok(out)
}
