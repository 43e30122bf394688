//! The gearbox's linear structure: both members' gear bodies, their
//! shafts as Timoshenko beam elements with mass, the bearings as springs
//! and dampers, and optionally a housing reduced onto its bearing seats.
//!
//! Coordinates x, in this order:
//! - q₁, q₂: the members' turns about their axes (the contact element's);
//! - d₁, d₂: each gear body's five small displacements about its pitch
//!   apex in its support's basis ([`Support::basis`]: translations along
//!   e₁, e₂, a, tilts about e₁, e₂), as in [`crate::multibody::compliant`];
//! - each flexible shaft's nodes but the seat, five each in the same basis
//!   (the shaft's twist is not modelled: it turns with q);
//! - the housing's reduced coordinates (6 per seat, then modal).
//!
//! The gear body is rigid and sits on its shaft's seat node:
//! [u; θ]_seat = B(s a) Q d, B(r) = [[I, −[r]ₓ], [0, I]]. A beam element
//! between nodes i, j (local x along a, y along e₁, z along a × e₁) adds
//! Tᵀ K_e T and Tᵀ M_e T, T = diag(R₆ᵀ N_i, R₆ᵀ N_j), N the node's
//! [u; θ] per x; its twist row is zero since no coordinate turns a node
//! about a. A bearing adds Gᵀ K_b G and Gᵀ C_b G, G the bearing point's
//! translation minus its seat's (the housing interface's translation, or
//! nothing on a rigid housing), K_b = k_r (I − a aᵀ) + k_a a aᵀ. The
//! member's polar moment (the contact element's) and its shaft's ρJL go on
//! q. Without shafts and housing this is the compliant-bearing model's
//! M, C_b, K_b ([`crate::multibody::compliant::CompliantModel::matrices`]).

use crate::bearings::flexible_shaft::Shaft;
use crate::bearings::timoshenko::{element_mass, element_stiffness, Section};
use crate::multibody::compliant::MemberBody;
use nalgebra::{DMatrix, Matrix3, Matrix6, Vector3};

/// A gearbox that cannot be assembled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GearboxError {
    #[error("{field} = {value}: {limit}")]
    Value {
        field: String,
        value: String,
        limit: String,
    },
    #[error(transparent)]
    Shaft(#[from] crate::bearings::flexible_shaft::ShaftError),
}

fn invalid(
    field: impl Into<String>,
    value: impl ToString,
    limit: impl Into<String>,
) -> GearboxError {
    GearboxError::Value {
        field: field.into(),
        value: value.to_string(),
        limit: limit.into(),
    }
}

/// One member's parts.
#[derive(Debug, Clone)]
pub struct MemberParts<'a> {
    /// The gear body on its support (axis, bearings, basis) with its mass.
    pub body: &'a MemberBody,
    /// Polar moment of the gear body, kg·m² (the contact element's).
    pub polar_inertia_kgm2: f64,
    /// The flexible shaft and its density, kg/m³ (None: a rigid shaft, the
    /// bearings on the gear body).
    pub shaft: Option<(&'a Shaft, f64)>,
}

/// A housing reduced onto its bearing seats (e.g. by
/// `fem::craig_bampton`): 6 coordinates per seat (translations and
/// rotations of its reference point, the bearing's centre, fixed frame),
/// then its modal coordinates.
#[derive(Debug, Clone)]
pub struct Housing {
    pub stiffness: DMatrix<f64>,
    pub mass: DMatrix<f64>,
    /// Viscous damping, same coordinates (e.g. modal damping on the
    /// fixed-interface coordinates, [`modal_damping`]).
    pub damping: DMatrix<f64>,
    /// The bearing each seat holds, in seat order: (member, bearing index).
    pub seats: Vec<(usize, usize)>,
}

/// Modal damping of a Craig–Bampton housing with `interface` coordinates
/// first: c_kk = 2 ζ ω_k m_kk on each fixed-interface coordinate k
/// (ω_k² = K_kk / M_kk, the fixed-interface mode's), nothing on the seats'
/// (they are damped through what they carry).
pub fn modal_damping(
    stiffness: &DMatrix<f64>,
    mass: &DMatrix<f64>,
    interface: usize,
    ratio: f64,
) -> DMatrix<f64> {
    let r = stiffness.nrows();
    DMatrix::from_fn(r, r, |i, j| {
        if i == j && i >= interface {
            2.0 * ratio * (stiffness[(i, i)] * mass[(i, i)]).max(0.0).sqrt()
        } else {
            0.0
        }
    })
}

/// What a coordinate belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// A member's turn q.
    Spin(usize),
    /// A member's gear body d.
    Body(usize),
    /// A node of a member's shaft.
    Shaft(usize),
    Housing,
}

/// One bearing between its shaft and its seat.
#[derive(Debug, Clone)]
pub struct BearingLink {
    pub member: usize,
    pub index: usize,
    /// Axial position from the member's apex, m.
    pub axial_position_m: f64,
    /// Bearing point's translation minus its seat's, per x (3 × n, fixed
    /// frame).
    pub relative: DMatrix<f64>,
    pub stiffness: Matrix3<f64>,
    pub damping: Matrix3<f64>,
}

impl BearingLink {
    /// The force the bearing puts on its seat (the housing; on the shaft
    /// the opposite) at (x, v), N.
    pub fn force_on_seat(&self, x: &[f64], v: &[f64]) -> Vector3<f64> {
        let mul = |m: &DMatrix<f64>, y: &[f64]| -> Vector3<f64> {
            Vector3::from_fn(|i, _| (0..y.len()).map(|j| m[(i, j)] * y[j]).sum())
        };
        self.stiffness * mul(&self.relative, x) + self.damping * mul(&self.relative, v)
    }
}

/// The assembled structure.
#[derive(Debug, Clone)]
pub struct GearboxStructure {
    pub mass: DMatrix<f64>,
    pub stiffness: DMatrix<f64>,
    pub damping: DMatrix<f64>,
    /// Each coordinate's part.
    pub parts: Vec<Part>,
    pub bearings: Vec<BearingLink>,
}

/// [r]ₓ.
fn skew(r: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -r.z, r.y, r.z, 0.0, -r.x, -r.y, r.x, 0.0)
}

/// B(r): [u; θ] at a point r from the reference per [u; θ] there.
fn transfer(r: &Vector3<f64>) -> Matrix6<f64> {
    let mut b = Matrix6::identity();
    b.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-skew(r)));
    b
}

/// A member's shaft nodes (axial positions), subdivided so that no element
/// is longer than `max_element_m`, and the seat's index.
fn shaft_nodes(shaft: &Shaft, body: &MemberBody, max_element_m: f64) -> (Vec<f64>, usize) {
    let named = shaft.nodes(body.support.bearings());
    let mut nodes = vec![named[0]];
    for w in named.windows(2) {
        let parts = ((w[1] - w[0]) / max_element_m).ceil().max(1.0) as usize;
        for p in 1..=parts {
            nodes.push(w[0] + (w[1] - w[0]) * p as f64 / parts as f64);
        }
    }
    let seat = Shaft::node_of(&nodes, shaft.seat_m);
    (nodes, seat)
}

/// Assembles the structure; shaft elements no longer than `max_element_m`.
pub fn assemble(
    members: [MemberParts; 2],
    housing: Option<&Housing>,
    max_element_m: f64,
) -> Result<GearboxStructure, GearboxError> {
    if !(max_element_m > 0.0 && max_element_m.is_finite()) {
        return Err(invalid(
            "max_element_m",
            max_element_m,
            "must be finite and > 0",
        ));
    }
    // Coordinates.
    let mut parts = vec![Part::Spin(0), Part::Spin(1)];
    parts.extend([Part::Body(0); 5]);
    parts.extend([Part::Body(1); 5]);
    let mut shafts = Vec::new();
    for (k, mp) in members.iter().enumerate() {
        let name = ["pinion", "wheel"][k];
        if !(mp.polar_inertia_kgm2 > 0.0 && mp.polar_inertia_kgm2.is_finite()) {
            return Err(invalid(
                format!("{name} polar_inertia_kgm2"),
                mp.polar_inertia_kgm2,
                "must be finite and > 0",
            ));
        }
        shafts.push(match mp.shaft {
            None => None,
            Some((shaft, density)) => {
                if !(density > 0.0 && density.is_finite()) {
                    return Err(invalid(
                        format!("{name} shaft density_kg_m3"),
                        density,
                        "must be finite and > 0",
                    ));
                }
                shaft.check(&format!("{name}_shaft"), mp.body.support.bearings())?;
                let (nodes, seat) = shaft_nodes(shaft, mp.body, max_element_m);
                let first = parts.len();
                parts.extend(std::iter::repeat_n(Part::Shaft(k), 5 * (nodes.len() - 1)));
                Some((nodes, seat, first, shaft, density))
            }
        });
    }
    let housing_first = parts.len();
    if let Some(h) = housing {
        let r = h.stiffness.nrows();
        if h.stiffness.ncols() != r
            || h.mass.shape() != (r, r)
            || h.damping.shape() != (r, r)
            || r < 6 * h.seats.len()
        {
            return Err(invalid(
                "housing matrices",
                format!(
                    "{:?}, {:?} and {:?}",
                    h.stiffness.shape(),
                    h.mass.shape(),
                    h.damping.shape()
                ),
                format!(
                    "must be square, equal, with at least 6 rows per seat ({})",
                    6 * h.seats.len()
                ),
            ));
        }
        for (s, &(k, i)) in h.seats.iter().enumerate() {
            if k > 1
                || i >= members[k].body.support.bearings().len()
                || h.seats[..s].contains(&(k, i))
            {
                return Err(invalid(
                    format!("housing seat {s}"),
                    format!("(member {k}, bearing {i})"),
                    "must name a bearing of the pinion (0) or the wheel (1), each once",
                ));
            }
        }
        parts.extend(std::iter::repeat_n(Part::Housing, r));
    }
    let n = parts.len();
    let mut mass = DMatrix::zeros(n, n);
    let mut stiffness = DMatrix::zeros(n, n);
    let mut damping = DMatrix::zeros(n, n);
    let mut bearings = Vec::new();

    for (k, mp) in members.iter().enumerate() {
        let support = &mp.body.support;
        let q = support.basis();
        let a = support.axis();
        let o = 2 + 5 * k;
        // [u; θ] (fixed frame) of the point at axial position p on the
        // rigid body, per x.
        let body_point = |p: f64| -> DMatrix<f64> {
            let mut m = DMatrix::zeros(6, n);
            m.view_mut((0, o), (6, 5))
                .copy_from(&(transfer(&(a * p)) * q));
            m
        };
        let mut spin = mp.polar_inertia_kgm2;
        let m6 = mp.body.mass_matrix(0.0);
        let body = q.transpose() * m6 * q;
        mass.view_mut((o, o), (5, 5)).add_assign(&body);
        // Bearing points (before the seats are known).
        let mut bearing_point: Vec<DMatrix<f64>> = support
            .bearings()
            .iter()
            .map(|b| body_point(b.axial_position_m).rows(0, 3).into_owned())
            .collect();
        if let Some((nodes, seat, first, shaft, density)) = &shafts[k] {
            let node_map = |i: usize| -> DMatrix<f64> {
                if i == *seat {
                    return body_point(nodes[i]);
                }
                let j = if i < *seat { i } else { i - 1 };
                let mut m = DMatrix::zeros(6, n);
                m.view_mut((0, first + 5 * j), (6, 5)).copy_from(&q);
                m
            };
            let e1: Vector3<f64> = q.fixed_view::<3, 1>(0, 0).into_owned();
            let r = Matrix3::from_columns(&[a, e1, a.cross(&e1)]);
            let mut r6 = Matrix6::zeros();
            r6.fixed_view_mut::<3, 3>(0, 0).copy_from(&r);
            r6.fixed_view_mut::<3, 3>(3, 3).copy_from(&r);
            for (e, w) in nodes.windows(2).enumerate() {
                let mid = 0.5 * (w[0] + w[1]);
                let seg = shaft
                    .segments
                    .iter()
                    .find(|s| mid >= s.from_m && mid <= s.to_m)
                    .expect("checked: contiguous segments");
                let sec = Section::round(
                    seg.outer_diameter_m,
                    seg.inner_diameter_m,
                    shaft.youngs_modulus_pa,
                    shaft.poisson_ratio,
                );
                let l = w[1] - w[0];
                let mut t = DMatrix::zeros(12, n);
                t.rows_mut(0, 6).copy_from(&(r6.transpose() * node_map(e)));
                t.rows_mut(6, 6)
                    .copy_from(&(r6.transpose() * node_map(e + 1)));
                let ke = DMatrix::from_iterator(12, 12, element_stiffness(&sec, l).iter().copied());
                let me =
                    DMatrix::from_iterator(12, 12, element_mass(&sec, l, *density).iter().copied());
                stiffness += t.transpose() * ke * &t;
                mass += t.transpose() * me * &t;
                spin += density * sec.polar_m4 * l;
            }
            for (b, point) in support.bearings().iter().zip(bearing_point.iter_mut()) {
                let i = Shaft::node_of(nodes, b.axial_position_m);
                *point = node_map(i).rows(0, 3).into_owned();
            }
        }
        mass[(k, k)] = spin;
        let aat = a * a.transpose();
        for (i, (b, point)) in support.bearings().iter().zip(bearing_point).enumerate() {
            let mut relative = point;
            if let Some(h) = housing {
                if let Some(s) = h.seats.iter().position(|&(m, j)| (m, j) == (k, i)) {
                    for c in 0..3 {
                        relative[(c, housing_first + 6 * s + c)] -= 1.0;
                    }
                }
            }
            let kb = (Matrix3::identity() - aat) * b.radial_stiffness_n_per_m
                + aat * b.axial_stiffness_n_per_m;
            let (cr, ca) = mp.body.damping.get(i).copied().unwrap_or((0.0, 0.0));
            let cb = (Matrix3::identity() - aat) * cr + aat * ca;
            let kb_d = DMatrix::from_iterator(3, 3, kb.iter().copied());
            let cb_d = DMatrix::from_iterator(3, 3, cb.iter().copied());
            stiffness += relative.transpose() * kb_d * &relative;
            damping += relative.transpose() * cb_d * &relative;
            bearings.push(BearingLink {
                member: k,
                index: i,
                axial_position_m: b.axial_position_m,
                relative,
                stiffness: kb,
                damping: cb,
            });
        }
    }
    if let Some(h) = housing {
        let r = h.stiffness.nrows();
        stiffness
            .view_mut((housing_first, housing_first), (r, r))
            .add_assign(&h.stiffness);
        mass.view_mut((housing_first, housing_first), (r, r))
            .add_assign(&h.mass);
        damping
            .view_mut((housing_first, housing_first), (r, r))
            .add_assign(&h.damping);
    }
    let sym = |m: DMatrix<f64>| (&m + m.transpose()) * 0.5;
    Ok(GearboxStructure {
        mass: sym(mass),
        stiffness: sym(stiffness),
        damping: sym(damping),
        parts,
        bearings,
    })
}

use std::ops::AddAssign;
