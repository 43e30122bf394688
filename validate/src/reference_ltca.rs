//! The reference loaded TCA: both gear bodies as full elastic FE bodies
//! (their own tet10 meshes with blanks), in contact through two-pass
//! node-to-surface penalty constraints on the meshes' own quadratic flank
//! faces ([`crate::contact_pairs`]), condensed exactly onto the contact
//! nodes ([`crate::penalty`]).
//!
//! At each pinion angle φ₁ the pinion is placed at φ₁ and the wheel at its
//! conjugate angle (zero lag). The wheel's bore is clamped; the pinion's
//! bore is clamped to a rigid rotation ψ about the pinion axis (in the
//! driving sense), which carries the torque. The wheel lag that results, the
//! loaded TE in the UTCA's convention, is θ = (z₁/z₂) ψ: at a vanishing
//! torque it is the meshed geometry's own unloaded TE.
//!
//! Nothing here uses the reduced model: no surface of roll angles, no
//! slices, no influence grid, no Weber–Banaschek term.

use crate::body_compliance::{clamped, BodyCompliance};
use crate::contact_pairs::{two_pass, ContactBody, Origin, PenaltySettings};
use crate::contact_surface::{nodal_normals, orient_outward, smoothed_pressure};
use crate::penalty::{
    carried_load, condensed_matrix, nodal_normal_forces, solve, Constraint, ContactError,
};
use nalgebra::Vector3;
use preprocess::body_mesh::BodyMesh;
use preprocess::generation::{rot_z, MemberFrame};
use preprocess::pair::FlankPair;
use serde::Serialize;
use std::collections::HashMap;

type V3 = [f64; 3];

/// One member's body in the reference model.
pub struct Member {
    pub mesh: BodyMesh,
    pub frame: MemberFrame,
    /// Loaded-flank faces of the teeth that can touch, oriented outward.
    pub faces: Vec<[usize; 6]>,
    pub compliance: BodyCompliance,
    pub youngs_modulus_pa: f64,
    /// Inward unit normal at each flank node, member frame.
    inward: HashMap<usize, V3>,
}

impl Member {
    /// Factors the body (bore clamped) and collects the loaded flank faces
    /// of `teeth` (`flank` = "concave"/"convex").
    pub fn new(
        mesh: BodyMesh,
        frame: MemberFrame,
        material: &fem::Material,
        flank: &str,
        teeth: &[usize],
        block: usize,
    ) -> Result<Member, ReferenceError> {
        let mut faces = Vec::new();
        for &k in teeth {
            let name = format!("tooth{k}_{flank}");
            let g = mesh.group(&name);
            if g.is_empty() {
                return Err(ReferenceError::MissingGroup(name));
            }
            faces.extend_from_slice(g);
        }
        let unmatched = orient_outward(&mesh.mesh, &mut faces);
        if unmatched > 0 {
            return Err(ReferenceError::Faces(unmatched));
        }
        let bore = mesh.group_nodes("bore");
        if bore.is_empty() {
            return Err(ReferenceError::MissingGroup("bore".into()));
        }
        let mut universe: Vec<usize> = faces.iter().flatten().copied().collect();
        universe.sort_unstable();
        universe.dedup();
        let compliance =
            BodyCompliance::new(&mesh.mesh, material, &clamped(&bore), &universe, block)?;
        let inward = nodal_normals(&mesh.mesh.nodes, &faces)
            .into_iter()
            .map(|(i, n)| (i, n.map(|c| -c)))
            .collect();
        Ok(Member {
            inward,
            mesh,
            frame,
            faces,
            compliance,
            youngs_modulus_pa: material.youngs_modulus_pa,
        })
    }

    /// Node coordinates in the fixed frame at rotation `phi`, and the
    /// fixed → member rotation.
    fn placed(&self, phi: f64) -> (Vec<V3>, [[f64; 3]; 3]) {
        let r = self.frame.axes * rot_z(phi);
        let nodes = self
            .mesh
            .mesh
            .nodes
            .iter()
            .map(|p| {
                let x = r * Vector3::new(p[0], p[1], p[2]);
                [x[0], x[1], x[2]]
            })
            .collect();
        let rt = r.transpose();
        let to_body = [0, 1, 2].map(|i| [0, 1, 2].map(|j| rt[(i, j)]));
        (nodes, to_body)
    }
}

/// Errors of the reference model.
#[derive(Debug, thiserror::Error)]
pub enum ReferenceError {
    #[error("mesh has no physical group {0}")]
    MissingGroup(String),
    #[error("{0} flank faces belong to no tetrahedron")]
    Faces(usize),
    #[error("no flank node comes within {max_gap_um} um of the mating flank at pinion angle {phi_deg} deg")]
    NoContact { phi_deg: f64, max_gap_um: f64 },
    #[error(transparent)]
    Contact(#[from] ContactError),
}

/// Settings of the reference contact.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct ReferenceSettings {
    /// Penalty ε = factor · E / ℓ.
    pub penalty_factor: f64,
    /// The second penalty factor whose result is compared.
    pub penalty_factor_check: f64,
    /// Initial gap below which a node is a contact candidate, m.
    pub max_gap_m: f64,
}

/// The result of one position at one torque.
#[derive(Debug, Clone, Serialize)]
pub struct LoadResult {
    pub torque_nm: f64,
    /// Loaded TE (wheel lag), rad.
    pub te: f64,
    /// TE at the check penalty factor, rad.
    pub te_check: f64,
    pub active: usize,
    /// Largest contact pressure on the pinion flanks, Pa.
    pub max_pressure_pa: f64,
    /// Σ forces × levers − torque, relative.
    pub torque_balance: f64,
    /// Smallest loaded gap among candidates that start in the outer half of
    /// the candidate band (must stay open), m.
    pub band_margin_m: f64,
}

/// All torques of one position.
#[derive(Debug, Clone, Serialize)]
pub struct PositionResult {
    pub phi: f64,
    pub constraints: usize,
    pub loads: Vec<LoadResult>,
    /// Contact pressure at the last torque: pinion node (member frame) → Pa.
    #[serde(skip)]
    pub pattern: Vec<(V3, f64)>,
    pub new_columns: usize,
    /// Candidate band used, m.
    pub max_gap_m: f64,
    pub cpu_s: f64,
}

/// The pair in the reference model.
pub struct ReferencePair<'a> {
    pub pinion: &'a mut Member,
    pub wheel: &'a mut Member,
    pub flanks: &'a FlankPair,
    /// Pinion's driving direction (±1).
    pub direction: f64,
    pub settings: ReferenceSettings,
}

impl ReferencePair<'_> {
    /// Solves the position `phi` (pinion angle, rad) for each torque (N·m,
    /// increasing). The candidate band starts at the settings' gap and is
    /// doubled (up to 8×) while a candidate from its outer half penetrates
    /// under load, a sign that nodes beyond the band could touch too.
    pub fn position(
        &mut self,
        phi: f64,
        torques: &[f64],
    ) -> Result<PositionResult, ReferenceError> {
        let t0 = std::time::Instant::now();
        let mut gap = self.settings.max_gap_m;
        let mut new_columns = 0;
        loop {
            let mut r = self.position_at_gap(phi, torques, gap)?;
            new_columns += r.new_columns;
            let margin = r
                .loads
                .iter()
                .map(|l| l.band_margin_m)
                .fold(f64::INFINITY, f64::min);
            if margin >= -1e-9 || gap >= 8.0 * self.settings.max_gap_m {
                r.new_columns = new_columns;
                r.max_gap_m = gap;
                r.cpu_s = t0.elapsed().as_secs_f64();
                return Ok(r);
            }
            gap *= 2.0;
        }
    }

    fn position_at_gap(
        &mut self,
        phi: f64,
        torques: &[f64],
        max_gap: f64,
    ) -> Result<PositionResult, ReferenceError> {
        let phi2 = self.flanks.conjugate_wheel_angle(phi);
        let (pn, pr) = self.pinion.placed(phi);
        let (wn, wr) = self.wheel.placed(phi2);
        let axis = self.pinion.frame.axis();
        let (a, d) = ([axis[0], axis[1], axis[2]], self.direction);
        let spin = move |x: V3| -> V3 {
            [
                d * (a[1] * x[2] - a[2] * x[1]),
                d * (a[2] * x[0] - a[0] * x[2]),
                d * (a[0] * x[1] - a[1] * x[0]),
            ]
        };
        let fixed = |_: V3| [0.0; 3];
        let body_p = ContactBody {
            body: 0,
            nodes: pn,
            to_body: pr,
            faces: self.pinion.faces.clone(),
            rigid: &spin,
            youngs_modulus_pa: self.pinion.youngs_modulus_pa,
        };
        let body_w = ContactBody {
            body: 1,
            nodes: wn,
            to_body: wr,
            faces: self.wheel.faces.clone(),
            rigid: &fixed,
            youngs_modulus_pa: self.wheel.youngs_modulus_pa,
        };
        let set = PenaltySettings {
            factor: self.settings.penalty_factor,
            max_gap,
            reach: 4.0 * max_gap,
        };
        let pairs: Vec<(Constraint, Origin)> = two_pass(&body_p, &body_w, &set)
            .into_iter()
            .filter(|(c, _)| c.rigid < 0.0)
            .collect();
        if pairs.is_empty() {
            return Err(ReferenceError::NoContact {
                phi_deg: phi.to_degrees(),
                max_gap_um: max_gap * 1e6,
            });
        }
        let cs: Vec<Constraint> = pairs.iter().map(|p| p.0.clone()).collect();
        let before = self.pinion.compliance.computed() + self.wheel.compliance.computed();
        for (body, m) in [(0, &mut *self.pinion), (1, &mut *self.wheel)] {
            let nodes: Vec<usize> = cs
                .iter()
                .flat_map(|c| c.terms.iter().filter(|t| t.body == body).map(|t| t.node))
                .collect();
            m.compliance.ensure(&nodes)?;
        }
        let new_columns =
            self.pinion.compliance.computed() + self.wheel.compliance.computed() - before;
        let idx: Vec<usize> = (0..cs.len()).collect();
        let w = condensed_matrix(
            &cs,
            &idx,
            &idx,
            &[&self.pinion.compliance, &self.wheel.compliance],
        )?;
        let ratio = self.pinion.frame.teeth as f64 / self.wheel.frame.teeth as f64;
        let check: Vec<Constraint> = cs
            .iter()
            .map(|c| Constraint {
                stiffness: c.stiffness * self.settings.penalty_factor_check
                    / self.settings.penalty_factor,
                ..c.clone()
            })
            .collect();
        let mut loads = Vec::new();
        let mut warm: Option<Vec<bool>> = None;
        let mut warm_check: Option<Vec<bool>> = None;
        let mut pattern = Vec::new();
        for (k, &t) in torques.iter().enumerate() {
            let s = solve(&cs, &w, t, warm.as_deref())?;
            let sc = solve(&check, &w, t, warm_check.as_deref())?;
            let band_margin_m = cs
                .iter()
                .zip(&s.gap)
                .filter(|(c, _)| c.gap0 > 0.5 * max_gap)
                .map(|(_, g)| *g)
                .fold(f64::INFINITY, f64::min);
            let f = nodal_normal_forces(&cs, &s.force, 0, &self.pinion.inward);
            let p = smoothed_pressure(&self.pinion.mesh.mesh.nodes, &self.pinion.faces, &f);
            let max_pressure_pa = p.values().copied().fold(0.0, f64::max);
            if k + 1 == torques.len() {
                pattern = p
                    .iter()
                    .filter(|(_, &v)| v > 0.0)
                    .map(|(&i, &v)| (self.pinion.mesh.mesh.nodes[i], v))
                    .collect();
            }
            loads.push(LoadResult {
                torque_nm: t,
                te: ratio * s.psi,
                te_check: ratio * sc.psi,
                active: s.active.iter().filter(|&&x| x).count(),
                max_pressure_pa,
                torque_balance: (carried_load(&cs, &s.force) - t) / t,
                band_margin_m,
            });
            warm = Some(s.active);
            warm_check = Some(sc.active);
        }
        Ok(PositionResult {
            phi,
            constraints: cs.len(),
            loads,
            pattern,
            new_columns,
            max_gap_m: max_gap,
            // Set by `position`, which times the band widening too.
            cpu_s: 0.0,
        })
    }
}
