//! The reference as an input deck for CalculiX: both gear bodies of one
//! blank pair at one position of the reference sweep, so that a user can
//! rerun our reference in their own nonlinear FE code, and so that an
//! independent code checks it. Nodes, elements, sets, surfaces, material,
//! steps and loads are written in the Abaqus syntax CalculiX shares; two
//! keywords are CalculiX's own and need adapting for Abaqus: `*RIGID BODY`
//! with a `ROT NODE` (Abaqus: a reference node with rotational degrees of
//! freedom) and the `TYPE=` of `*CONTACT PAIR`.
//!
//! The deck ([`build`], then [`inp::write`]):
//! - both bodies as C3D10 elements from the meshes of one level, placed as
//!   the reference places them at the position (the pinion at its angle
//!   with the scene's misalignment, the wheel at the conjugate angle: zero
//!   lag), in the **pinion frame**: the pinion axis is z through the
//!   origin, so that the pinion's rotation is one degree of freedom;
//! - the wheel's bore clamped (node set `WBORE`); the pinion's bore
//!   (`PBORE`) a rigid body on a reference node at the origin and a
//!   rotation node whose z rotation is free (the others held): the
//!   reference's rigid rotation ψ carrying the torque;
//! - the loaded flanks of the teeth that can touch at the position as
//!   element-face surfaces `PFLANK` (slave) and `WFLANK` (master), in
//!   frictionless contact with a linear pressure–overclosure law of slope
//!   ε = factor · E / ℓ (the reference's penalty, ℓ the mean face size of
//!   the pinion's flank faces; the reference takes ℓ per node);
//! - step 1 turns the pinion to where its first node overlaps the wheel by
//!   [`START_OVERCLOSURE_M`] (found by our contact search: only a start,
//!   the deck's own contact decides what follows); each further step
//!   releases the rotation and applies one torque of the scene, in
//!   increasing order.
//!
//! The loaded TE of step k is (z₁/z₂) · d · u_z(rotation node), d the
//! driving direction (±1): the wheel lag in the UTCA's convention, as the
//! reference gives it ([`ccx`] runs CalculiX and reads it back).

pub mod c3d10;
pub mod ccx;
pub mod export;
pub mod inp;

use crate::reference::contact_pairs::{one_pass, ContactBody, PenaltySettings};
use crate::reference::contact_surface::MasterSurface;
use formats::paths::MeshLevel;
use formats::stiffness_plan;
use geometry::design::Member as Which;
use geometry::generation::rot_z;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use nalgebra::{Matrix3, Vector3};
use std::path::{Path, PathBuf};

type V3 = [f64; 3];

/// Overlap of the first pinion node with the wheel at the end of step 1,
/// m: enough that the contact holds the pinion when step 2 frees it.
pub const START_OVERCLOSURE_M: f64 = 0.5e-6;

/// Contact formulation of the deck.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeckContact {
    /// Pinion flank nodes against the wheel's flank faces (the reference's
    /// pinion-slave pass; CalculiX `NODE TO SURFACE`).
    NodeToSurface,
    /// Pinion flank faces against the wheel's (CalculiX `SURFACE TO
    /// SURFACE`: the penalty integrated over the slave faces).
    SurfaceToSurface,
    /// No contact: the pinion turned by step 1 alone, whose reaction
    /// moment must vanish (the deck's rigid-rotation check).
    None,
}

impl DeckContact {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            DeckContact::NodeToSurface => "node-to-surface",
            DeckContact::SurfaceToSurface => "surface-to-surface",
            DeckContact::None => "none",
        }
    }

    /// The contact of a command-line name.
    pub fn parse(s: &str) -> Result<DeckContact, DeckError> {
        [
            DeckContact::NodeToSurface,
            DeckContact::SurfaceToSurface,
            DeckContact::None,
        ]
        .into_iter()
        .find(|c| c.name() == s)
        .ok_or_else(|| DeckError::Input {
            field: "contact",
            value: s.to_string(),
            limit: "node-to-surface, surface-to-surface or none".into(),
        })
    }
}

/// What to export.
#[derive(Debug, Clone)]
pub struct DeckOptions {
    /// Mesh level of both bodies.
    pub level: MeshLevel,
    pub pinion_blank: Blank,
    pub wheel_blank: Blank,
    /// Index of the position in the reference sweep (step 0 = its start).
    pub position: usize,
    pub contact: DeckContact,
    /// Penalty ε = factor · E / ℓ.
    pub penalty_factor: f64,
}

/// Errors of the export.
#[derive(Debug, thiserror::Error)]
pub enum DeckError {
    #[error("{field} = {value}: must be {limit}")]
    Input {
        field: &'static str,
        value: String,
        limit: String,
    },
    #[error("no mesh {path}: run `preprocess mesh {scene} --level {level}`")]
    NoMesh {
        path: PathBuf,
        scene: PathBuf,
        level: String,
    },
    #[error(transparent)]
    Check(#[from] stiffness_plan::CheckError),
    #[error("mesh {path}: {message}")]
    Mesh { path: PathBuf, message: String },
    #[error(
        "mesh {path}: element {element} is inverted (scaled Jacobian {jacobian:.3e} as C3D10)"
    )]
    Inverted {
        path: PathBuf,
        element: usize,
        jacobian: f64,
    },
    #[error("mesh {path}: no physical group {group}")]
    MissingGroup { path: PathBuf, group: String },
    #[error("mesh {path}: {faces} faces of group {group} belong to no element")]
    LooseFaces {
        path: PathBuf,
        group: String,
        faces: usize,
    },
    #[error("no pinion flank node comes within {search_um} um of the wheel's flanks at position {position}")]
    NoContact { position: usize, search_um: f64 },
    #[error(transparent)]
    Geometry(#[from] geometry::error::GeometryError),
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// One body of the deck.
#[derive(Debug, Clone)]
pub struct DeckBody {
    /// Node coordinates in the pinion frame, m.
    pub nodes: Vec<V3>,
    /// Elements, node indices in C3D10 order.
    pub elements: Vec<[usize; 10]>,
    /// The loaded flank faces of the teeth that can touch: (element, face
    /// label 1..=4).
    pub flank: Vec<(usize, u8)>,
    /// Bore nodes.
    pub bore: Vec<usize>,
    pub youngs_modulus_pa: f64,
    pub poisson_ratio: f64,
    /// The mesh file and its SHA-256.
    pub mesh: PathBuf,
    pub mesh_sha256: String,
}

/// A deck of one position.
#[derive(Debug, Clone)]
pub struct Deck {
    /// [pinion, wheel].
    pub bodies: [DeckBody; 2],
    pub contact: DeckContact,
    /// Slope of the pressure–overclosure law, Pa/m.
    pub penalty_slope: f64,
    /// The pinion's z rotation at the end of step 1 (its driving sense
    /// included), rad.
    pub start_rotation: f64,
    /// Pinion torques of the later steps, N·m (increasing).
    pub torques_nm: Vec<f64>,
    /// Pinion driving direction (±1) and z₁/z₂.
    pub direction: f64,
    pub ratio: f64,
    /// Pinion angle of the position, rad; the scene's name and position.
    pub phi: f64,
    pub scene: String,
    pub position: usize,
    pub level: MeshLevel,
}

impl Deck {
    /// The loaded TE (rad) of a pinion z rotation `u_z` (rad) read from the
    /// rotation node.
    pub fn te_of_rotation(&self, u_z: f64) -> f64 {
        self.ratio * self.direction * u_z
    }
}

/// Builds the deck of `opt.position` of the scene's reference sweep from
/// the meshes under `meshes` (the mesh root of `preprocess mesh`).
pub fn build(scene: &LoadedScene, meshes: &Path, opt: &DeckOptions) -> Result<Deck, DeckError> {
    let sc = &scene.scene;
    if !(opt.penalty_factor.is_finite() && opt.penalty_factor > 0.0) {
        return Err(DeckError::Input {
            field: "penalty",
            value: opt.penalty_factor.to_string(),
            limit: "a positive number".into(),
        });
    }
    let mut g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    g.misalign(&sc.misalignment);
    let side = sc.loaded_flank;
    let direction = pinion_direction(&g.data, side);
    let step = sc.rotation.step_deg.to_radians();
    let cycles = sc.rotation.mesh_cycles(opt.wheel_blank);
    let n_pos = (cycles * g.data.mesh_cycle() / step).round() as usize + 1;
    if opt.position >= n_pos {
        return Err(DeckError::Input {
            field: "position",
            value: opt.position.to_string(),
            limit: format!("below {n_pos}, the positions of the scene's sweep"),
        });
    }
    let fp = g.side(side);
    let phi = fp.roll_range[0] + direction * step * opt.position as f64;
    let phi2 = fp.conjugate_wheel_angle(phi);
    let (pinion_teeth, wheel_teeth) = teeth_in_contact(&g, side, cycles, step);

    // The pinion frame: x_deck = Aᵀ (x_fixed − t).
    let (a, t) = match &fp.pose {
        Some(p) => (p.rotation * g.frames[0].axes, p.translation),
        None => (g.frames[0].axes, Vector3::zeros()),
    };
    let place_pinion = rot_z(phi);
    let place_wheel = a.transpose() * g.frames[1].axes * rot_z(phi2);
    let dir = meshes.join(&sc.name);
    let pinion = body(
        scene,
        &g,
        &dir,
        opt,
        Which::Pinion,
        opt.pinion_blank,
        &pinion_teeth,
        &place_pinion,
        &Vector3::zeros(),
    )?;
    let wheel = body(
        scene,
        &g,
        &dir,
        opt,
        Which::Wheel,
        opt.wheel_blank,
        &wheel_teeth,
        &place_wheel,
        &(-(a.transpose() * t)),
    )?;
    let e_min = pinion.youngs_modulus_pa.min(wheel.youngs_modulus_pa);
    let ell = mean_face_size(&pinion);
    let start_rotation = direction * start_angle(&pinion, &wheel, direction, opt)?;
    Ok(Deck {
        penalty_slope: opt.penalty_factor * e_min / ell,
        bodies: [pinion, wheel],
        contact: opt.contact,
        start_rotation,
        torques_nm: sc.pinion_torque_nm.clone(),
        direction,
        ratio: g.frames[0].teeth as f64 / g.frames[1].teeth as f64,
        phi,
        scene: sc.name.clone(),
        position: opt.position,
        level: opt.level,
    })
}

/// One member's body: its mesh (checked against the mesh stage's
/// manifest), placed by `r`, `t`, in C3D10 order, with its flank faces and
/// bore.
#[allow(clippy::too_many_arguments)]
fn body(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    opt: &DeckOptions,
    which: Which,
    blank: Blank,
    teeth: &[usize],
    r: &Matrix3<f64>,
    t: &Vector3<f64>,
) -> Result<DeckBody, DeckError> {
    let stem = formats::paths::mesh_stem(which, blank, opt.level);
    let path = formats::paths::msh(dir, &stem);
    if !path.exists() {
        return Err(DeckError::NoMesh {
            path,
            scene: scene.path.clone(),
            level: opt.level.name().into(),
        });
    }
    let entry = stiffness_plan::check_mesh(scene, g, dir, &stem, which, blank, opt.level)?;
    let sha = preprocess::stiffness_stage::sha256_file(&path).map_err(|e| DeckError::Mesh {
        path: path.clone(),
        message: e.to_string(),
    })?;
    if sha != entry.msh_sha256 {
        return Err(stiffness_plan::CheckError::MeshChanged {
            path,
            found: sha,
            listed: entry.msh_sha256,
        }
        .into());
    }
    let mesh = preprocess::body_mesh::read(&path).map_err(|message| DeckError::Mesh {
        path: path.clone(),
        message,
    })?;
    let nodes: Vec<V3> = mesh
        .mesh
        .nodes
        .iter()
        .map(|p| {
            let x = r * Vector3::new(p[0], p[1], p[2]) + t;
            [x[0], x[1], x[2]]
        })
        .collect();
    let elements: Vec<[usize; 10]> = mesh.mesh.tets.iter().map(c3d10::c3d10_order).collect();
    for (k, e) in elements.iter().enumerate() {
        let x = e.map(|i| nodes[i]);
        let jacobian = c3d10::min_scaled_jacobian(&x);
        if jacobian.is_nan() || jacobian <= 0.0 {
            return Err(DeckError::Inverted {
                path,
                element: k,
                jacobian,
            });
        }
    }
    let flank_name = scene.scene.loaded_flank.flank_name(which);
    let mut faces = Vec::new();
    for &k in teeth {
        let group = format!("tooth{k}_{flank_name}");
        let f = mesh.group(&group);
        if f.is_empty() {
            return Err(DeckError::MissingGroup { path, group });
        }
        faces.extend_from_slice(f);
    }
    let flank = element_faces(&elements, &faces).map_err(|n| DeckError::LooseFaces {
        path: path.clone(),
        group: format!("tooth*_{flank_name}"),
        faces: n,
    })?;
    let bore = mesh.group_nodes("bore");
    if bore.is_empty() {
        return Err(DeckError::MissingGroup {
            path,
            group: "bore".into(),
        });
    }
    let material = preprocess::influence::fe_material(g.data.member(which).material());
    Ok(DeckBody {
        nodes,
        elements,
        flank,
        bore,
        youngs_modulus_pa: material.youngs_modulus_pa,
        poisson_ratio: material.poisson_ratio,
        mesh: path,
        mesh_sha256: sha,
    })
}

/// The (element, face label) of each tri6 face; Err(count) when faces
/// belong to no element.
pub fn element_faces(
    elements: &[[usize; 10]],
    faces: &[[usize; 6]],
) -> Result<Vec<(usize, u8)>, usize> {
    let key = |mut k: [usize; 3]| {
        k.sort_unstable();
        k
    };
    let mut want: std::collections::HashMap<[usize; 3], Option<(usize, u8)>> = faces
        .iter()
        .map(|f| (key([f[0], f[1], f[2]]), None))
        .collect();
    for (e, el) in elements.iter().enumerate() {
        for label in 1..=4u8 {
            let v = c3d10::face_vertices(label).map(|i| el[i]);
            if let Some(slot) = want.get_mut(&key(v)) {
                *slot = Some((e, label));
            }
        }
    }
    let mut out: Vec<(usize, u8)> = Vec::with_capacity(faces.len());
    let mut loose = 0;
    for f in faces {
        match want[&key([f[0], f[1], f[2]])] {
            Some(x) => out.push(x),
            None => loose += 1,
        }
    }
    if loose > 0 {
        return Err(loose);
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// Tri6 faces of a body's flank in mesh node numbers, from its element
/// faces (vertices and mid-edge nodes, C3D10 numbering).
fn flank_tri6(b: &DeckBody) -> Vec<[usize; 6]> {
    b.flank
        .iter()
        .map(|&(e, label)| {
            let el = &b.elements[e];
            let [p, q, r] = c3d10::face_vertices(label);
            [
                el[p],
                el[q],
                el[r],
                c3d10::mid_edge(el, p, q),
                c3d10::mid_edge(el, q, r),
                c3d10::mid_edge(el, r, p),
            ]
        })
        .collect()
}

/// Mean face size ℓ = √(2 × mean area) of the pinion's flank faces, m
/// (the reference takes the same size per node).
fn mean_face_size(b: &DeckBody) -> f64 {
    let faces = flank_tri6(b);
    let area: f64 = faces
        .iter()
        .map(|f| fem::tri6::area(&f.map(|i| b.nodes[i])))
        .sum();
    (2.0 * area / faces.len().max(1) as f64).sqrt()
}

/// The pinion rotation (rad, driving sense) at which its first flank node
/// overlaps the wheel's flank by [`START_OVERCLOSURE_M`]: the least closing
/// angle g/(−ρ) over the pinion's flank nodes, plus that overlap over the
/// node's lever.
fn start_angle(
    pinion: &DeckBody,
    wheel: &DeckBody,
    direction: f64,
    opt: &DeckOptions,
) -> Result<f64, DeckError> {
    let wf = flank_tri6(wheel);
    closings(pinion, &wheel.nodes, wf, direction)
        .into_iter()
        .map(|(gap, rigid)| (gap + START_OVERCLOSURE_M) / -rigid)
        .min_by(f64::total_cmp)
        .ok_or(DeckError::NoContact {
            position: opt.position,
            search_um: SEARCH_M * 1e6,
        })
}

/// Reach of the deck's own contact search (start and facet offset), m.
const SEARCH_M: f64 = 60e-6;

/// (gap, ∂gap/∂ψ) of every pinion flank node that closes when the pinion
/// turns in its driving sense, against the master `faces` (tri6, outward)
/// on `nodes`.
fn closings(
    pinion: &DeckBody,
    nodes: &[V3],
    faces: Vec<[usize; 6]>,
    direction: f64,
) -> Vec<(f64, f64)> {
    let spin = move |x: V3| [-direction * x[1], direction * x[0], 0.0];
    let fixed = |_: V3| [0.0; 3];
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    // Face labels give outward faces of positive elements (checked).
    let s = ContactBody {
        body: 0,
        nodes: pinion.nodes.clone(),
        to_body: identity,
        faces: flank_tri6(pinion),
        rigid: &spin,
        youngs_modulus_pa: pinion.youngs_modulus_pa,
    };
    let m = ContactBody {
        body: 1,
        nodes: nodes.to_vec(),
        to_body: identity,
        faces: faces.clone(),
        rigid: &fixed,
        youngs_modulus_pa: pinion.youngs_modulus_pa,
    };
    let master = MasterSurface::new(nodes.to_vec(), faces);
    let set = PenaltySettings {
        factor: 1.0,
        max_gap: SEARCH_M,
        reach: 2.0 * SEARCH_M,
        minima_band: 0.0,
    };
    one_pass(&s, &m, &master, &set, 1.0)
        .into_iter()
        .map(|(c, _)| (c.gap0, c.rigid))
        .filter(|&(_, rigid)| rigid < 0.0)
        .collect()
}

/// How much later (rad of wheel lag, the TE's unit) the pinion's first
/// flank node touches the wheel when each quadratic wheel face is replaced
/// by the four flat triangles between its vertices and mid-edge nodes, as
/// CalculiX's node-to-surface contact does with the master surface: the
/// geometric offset of that contact formulation against the reference's
/// quadratic faces (the facets' chords lie a sag ≈ h²/(8R) off the curved
/// flank). `None` when no node closes.
pub fn facet_offset(deck: &Deck) -> Option<f64> {
    let [pinion, wheel] = &deck.bodies;
    let quadratic = flank_tri6(wheel);
    let mut nodes = wheel.nodes.clone();
    let mut facets = Vec::with_capacity(4 * quadratic.len());
    for f in &quadratic {
        for t in [
            [f[0], f[3], f[5]],
            [f[3], f[1], f[4]],
            [f[5], f[4], f[2]],
            [f[3], f[4], f[5]],
        ] {
            // A flat tri6: its mid-edge nodes at the straight midpoints.
            let mids = [0, 1, 2].map(|k| {
                let (a, b) = (nodes[t[k]], nodes[t[(k + 1) % 3]]);
                nodes.push([0, 1, 2].map(|c| 0.5 * (a[c] + b[c])));
                nodes.len() - 1
            });
            facets.push([t[0], t[1], t[2], mids[0], mids[1], mids[2]]);
        }
    }
    let first = |nodes: &[V3], faces| {
        closings(pinion, nodes, faces, deck.direction)
            .into_iter()
            .map(|(gap, rigid)| gap / -rigid)
            .min_by(f64::total_cmp)
    };
    let q = first(&wheel.nodes, quadratic)?;
    let f = first(&nodes, facets)?;
    Some(deck.ratio * (f - q))
}
