//! The reference loaded TCA: both gear bodies as full elastic FE bodies
//! (their own tet10 meshes with blanks), in contact through two-pass
//! node-to-surface penalty constraints on the meshes' own quadratic flank
//! faces ([`crate::reference::contact_pairs`]), condensed exactly onto the contact
//! nodes ([`crate::reference::penalty`]).
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

use crate::reference::body_compliance::clamped;
use crate::reference::contact_pairs::{rot, two_pass, ContactBody, PenaltySettings};
use crate::reference::contact_surface::{nodal_normals, orient_outward, smoothed_pressure};
use crate::reference::path_compliance::PathCompliance;
use crate::reference::penalty::{
    carried_load, nodal_normal_forces, solve, Constraint, ContactError,
};
use fem::path_solve::{combine, gram, PathVec};
use geometry::generation::{rot_z, MemberFrame};
use geometry::misalignment::Pose;
use geometry::pair::FlankPair;
use nalgebra::Vector3;
use preprocess::body_mesh::BodyMesh;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};

type V3 = [f64; 3];

/// One member's body in the reference model.
pub struct Member {
    pub mesh: BodyMesh,
    pub frame: MemberFrame,
    /// Loaded-flank faces of the teeth that can touch, oriented outward.
    pub faces: Vec<[usize; 6]>,
    pub compliance: PathCompliance,
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
        let mut contact: Vec<usize> = faces.iter().flatten().copied().collect();
        contact.sort_unstable();
        contact.dedup();
        let compliance =
            PathCompliance::new(&mesh.mesh, material, &clamped(&bore), &contact, block)?;
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

    /// Reads member `which`'s mesh from `path` and builds it with its frame,
    /// material and loaded flank (`side`) from the pair geometry.
    pub fn load(
        path: &std::path::Path,
        g: &geometry::pair::PairGeometry,
        which: geometry::design::Member,
        side: geometry::generation::Side,
        teeth: &[usize],
        block: usize,
    ) -> Result<Member, ReferenceError> {
        let mesh = preprocess::body_mesh::read(path).map_err(|message| ReferenceError::Mesh {
            path: path.to_path_buf(),
            message,
        })?;
        let frame = match which {
            geometry::design::Member::Pinion => g.frames[0],
            geometry::design::Member::Wheel => g.frames[1],
        };
        Member::new(
            mesh,
            frame,
            &preprocess::influence::fe_material(g.data.member(which).material()),
            side.flank_name(which),
            teeth,
            block,
        )
    }

    /// Node coordinates in the fixed frame at rotation `phi`, the body
    /// then moved by `pose` (a misalignment) if any, and the fixed →
    /// member rotation.
    fn placed(&self, phi: f64, pose: Option<&Pose>) -> (Vec<V3>, [[f64; 3]; 3]) {
        let id = Pose::identity();
        let pose = pose.unwrap_or(&id);
        let r = pose.rotation * self.frame.axes * rot_z(phi);
        let t = pose.translation;
        let nodes = self
            .mesh
            .mesh
            .nodes
            .iter()
            .map(|p| {
                let x = r * Vector3::new(p[0], p[1], p[2]) + t;
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
    #[error("mesh {path}: {message}")]
    Mesh {
        path: std::path::PathBuf,
        message: String,
    },
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
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
pub struct ReferenceSettings {
    /// Penalty ε = factor · E / ℓ.
    pub penalty_factor: f64,
    /// The second penalty factor whose result is compared.
    pub penalty_factor_check: f64,
    /// Constraints whose initial gap is within this of the smallest one
    /// start in the solve, m.
    pub start_band_m: f64,
    /// Constraints are searched up to this initial gap; those outside the
    /// solve are checked after it and added when they penetrate, m.
    pub search_gap_m: f64,
}

/// The result of one position at one torque.
#[derive(Debug, Clone, Serialize, Deserialize)]
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
    /// Smallest loaded gap of the searched constraints left out of the
    /// solve that start in the outer half of the search range, m. Never
    /// negative once the working set has settled (a penetrating one would
    /// have joined): the closest call among the far constraints.
    pub band_margin_m: f64,
    /// Search gap − the largest closure (initial − loaded gap) of any
    /// searched constraint, m: how much more closure a constraint at the
    /// edge of the search range would need to touch. Positive: nothing
    /// beyond the range can have touched. (None in results cached before
    /// it was recorded.)
    #[serde(default)]
    pub search_margin_m: Option<f64>,
}

/// All torques of one position.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PositionResult {
    pub phi: f64,
    /// Constraints searched (initial gap up to the search range).
    pub searched: usize,
    /// Constraints in the solve at the end (started + added).
    pub constraints: usize,
    /// TE at the vanishing torque [`UNLOADED_TORQUE_NM`]: the meshed
    /// geometry's unloaded TE, rad.
    pub unloaded_te: f64,
    /// Where the largest force acts at that torque: the slave point, in the
    /// pinion's member frame, m.
    pub unloaded_point: V3,
    pub loads: Vec<LoadResult>,
    /// Contact pressure at the last torque: pinion node (member frame) → Pa.
    pub pattern: Vec<(V3, f64)>,
    /// Nodes whose unit-load columns this position computed.
    pub new_columns: usize,
    pub cpu_s: f64,
    /// Where `cpu_s` went (None in results cached before it was recorded).
    #[serde(default)]
    pub time_split: Option<TimeSplit>,
}

/// Wall time of one position by part, s.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct TimeSplit {
    /// Placing the bodies and building every constraint up to the search gap.
    pub search_s: f64,
    /// Unit-load vectors of new nodes (pruned forward solves).
    pub forward_s: f64,
    /// Constraint vectors and the condensed matrix W.
    pub condensation_s: f64,
    /// Dense active-set solves (both penalties, every torque).
    pub contact_s: f64,
    /// Loaded gaps of the constraints outside the working set (backward
    /// solves on their paths).
    pub outside_s: f64,
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

/// Faces whose nodes come within this of the smallest gap get face minimum
/// points: where light loads touch, m. (Under heavy loads the contact spans
/// many elements and the nodes sample it.)
pub const MINIMA_BAND_M: f64 = 10e-6;

/// The torque of the unloaded check, solved first at every position, N·m.
pub const UNLOADED_TORQUE_NM: f64 = 1e-3;

/// The constraints in the solve and their condensed matrix.
struct WorkingSet {
    idx: Vec<usize>,
    /// Row-major idx.len()².
    w: Vec<f64>,
    /// Each constraint's vector y_cb on the pinion (0) and the wheel (1),
    /// in the order of `idx`.
    y: Vec<[PathVec; 2]>,
}

impl ReferencePair<'_> {
    /// Solves the position `phi` (pinion angle, rad) at the vanishing torque
    /// [`UNLOADED_TORQUE_NM`] and then at each torque (N·m, increasing).
    ///
    /// All two-pass constraints up to the search gap are built (geometry
    /// only). The solve starts with those within the start band of the
    /// smallest gap; after each solve the loaded gap of every constraint
    /// left out is evaluated from the contact forces (the columns of the
    /// loaded nodes hold the responses at every flank node), and the ones
    /// that penetrate join the solve, until none does at either penalty
    /// factor. Only the nodes that join get unit-load columns.
    pub fn position(
        &mut self,
        phi: f64,
        torques: &[f64],
    ) -> Result<PositionResult, ReferenceError> {
        let t0 = std::time::Instant::now();
        let mut split = TimeSplit::default();
        let lap = std::time::Instant::now();
        let (cs, at) = self.constraints(phi)?;
        split.search_s = lap.elapsed().as_secs_f64();
        let before = self.pinion.compliance.solves + self.wheel.compliance.solves;
        let g_min = cs.iter().map(|c| c.gap0).fold(f64::INFINITY, f64::min);
        let start: Vec<usize> = (0..cs.len())
            .filter(|&c| cs[c].gap0 <= g_min + self.settings.start_band_m)
            .collect();
        let mut ws = WorkingSet {
            idx: Vec::new(),
            w: Vec::new(),
            y: Vec::new(),
        };
        self.grow(&cs, &mut ws, &start, &mut split)?;
        let scale = self.settings.penalty_factor_check / self.settings.penalty_factor;
        let ratio = self.pinion.frame.teeth as f64 / self.wheel.frame.teeth as f64;
        let mut loads = Vec::new();
        let (mut first_force, mut first_idx) = (Vec::new(), Vec::new());
        let mut pattern = Vec::new();
        let mut warm: [Option<Vec<usize>>; 2] = [None, None];
        let all: Vec<f64> = std::iter::once(UNLOADED_TORQUE_NM)
            .chain(torques.iter().copied())
            .collect();
        for (k, &t) in all.iter().enumerate() {
            let (s, sc, outside) = loop {
                let sub: Vec<Constraint> = ws.idx.iter().map(|&c| cs[c].clone()).collect();
                let check: Vec<Constraint> = sub
                    .iter()
                    .map(|c| Constraint {
                        stiffness: c.stiffness * scale,
                        ..c.clone()
                    })
                    .collect();
                let warm_of = |a: &Option<Vec<usize>>| {
                    a.as_ref().map(|on| {
                        let mut v = vec![false; ws.idx.len()];
                        for &c in on {
                            if let Ok(p) = ws.idx.binary_search(&c) {
                                v[p] = true;
                            }
                        }
                        v
                    })
                };
                let lap = std::time::Instant::now();
                let s = solve(&sub, &ws.w, t, warm_of(&warm[0]).as_deref())?;
                let sc = solve(&check, &ws.w, t, warm_of(&warm[1]).as_deref())?;
                split.contact_s += lap.elapsed().as_secs_f64();
                let lap = std::time::Instant::now();
                let mut gaps =
                    self.outside_gaps(&cs, &ws, &[(&s.force, s.psi), (&sc.force, sc.psi)])?;
                split.outside_s += lap.elapsed().as_secs_f64();
                let mut add: Vec<usize> = gaps
                    .iter()
                    .flatten()
                    .filter(|&&(_, v)| v < 0.0)
                    .map(|&(c, _)| c)
                    .collect();
                add.sort_unstable();
                add.dedup();
                let on = |sol: &crate::reference::penalty::Solution| -> Vec<usize> {
                    (0..ws.idx.len())
                        .filter(|&i| sol.active[i])
                        .map(|i| ws.idx[i])
                        .collect()
                };
                warm = [Some(on(&s)), Some(on(&sc))];
                if add.is_empty() {
                    break (s, sc, gaps.swap_remove(0));
                }
                self.grow(&cs, &mut ws, &add, &mut split)?;
            };
            let sub: Vec<Constraint> = ws.idx.iter().map(|&c| cs[c].clone()).collect();
            if k == 0 {
                first_force = s.force.clone();
                first_idx = ws.idx.clone();
            }
            let band_margin_m = outside
                .iter()
                .filter(|&&(c, _)| cs[c].gap0 > 0.5 * self.settings.search_gap_m)
                .map(|&(_, g)| g)
                .fold(f64::INFINITY, f64::min);
            let closure = outside
                .iter()
                .map(|&(c, g)| cs[c].gap0 - g)
                .chain(ws.idx.iter().zip(&s.gap).map(|(&c, &g)| cs[c].gap0 - g))
                .fold(f64::NEG_INFINITY, f64::max);
            let search_margin_m = Some(self.settings.search_gap_m - closure);
            let f = nodal_normal_forces(&sub, &s.force, 0, &self.pinion.inward);
            let p = smoothed_pressure(&self.pinion.mesh.mesh.nodes, &self.pinion.faces, &f);
            let max_pressure_pa = p.values().copied().fold(0.0, f64::max);
            if k + 1 == all.len() {
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
                torque_balance: (carried_load(&sub, &s.force) - t) / t,
                band_margin_m,
                search_margin_m,
            });
        }
        // The sliding window: keep the vectors of the nodes this position
        // loaded; the next position's contact lies next to them.
        for (body, m) in [(0, &mut *self.pinion), (1, &mut *self.wheel)] {
            let keep: HashSet<usize> = ws
                .idx
                .iter()
                .flat_map(|&c| cs[c].terms.iter().filter(move |t| t.body == body))
                .map(|t| t.node)
                .collect();
            m.compliance.retain(&keep);
        }
        let unloaded = loads.remove(0);
        let unloaded_point = first_force
            .iter()
            .zip(&first_idx)
            .max_by(|a, b| a.0.total_cmp(b.0))
            .map_or([f64::NAN; 3], |(_, &c)| at[c]);
        Ok(PositionResult {
            phi,
            searched: cs.len(),
            constraints: ws.idx.len(),
            unloaded_te: unloaded.te,
            unloaded_point,
            loads,
            pattern,
            new_columns: (self.pinion.compliance.solves + self.wheel.compliance.solves - before)
                / 3,
            cpu_s: t0.elapsed().as_secs_f64(),
            time_split: Some(split),
        })
    }

    /// Every two-pass constraint up to the search gap that closes as the
    /// pinion turns in its driving sense, at pinion angle `phi`, each with
    /// its slave point in the pinion's member frame.
    fn constraints(&self, phi: f64) -> Result<(Vec<Constraint>, Vec<V3>), ReferenceError> {
        let phi2 = self.flanks.conjugate_wheel_angle(phi);
        // The pinion placed with the pair's pose (misalignment) relative
        // to the wheel, which stays in the fixed frame; it turns about its
        // moved axis.
        let pose = self.flanks.pose;
        let (pn, pr) = self.pinion.placed(phi, pose.as_ref());
        let (wn, wr) = self.wheel.placed(phi2, None);
        let (axis, c) = match &pose {
            Some(p) => (p.rotation * self.pinion.frame.axis(), p.translation),
            None => (self.pinion.frame.axis(), Vector3::zeros()),
        };
        let (a, d) = ([axis[0], axis[1], axis[2]], self.direction);
        let c = [c[0], c[1], c[2]];
        let spin = move |x: V3| -> V3 {
            let x = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
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
            max_gap: self.settings.search_gap_m,
            reach: 2.0 * self.settings.search_gap_m,
            minima_band: MINIMA_BAND_M,
        };
        let (cs, at): (Vec<Constraint>, Vec<V3>) = two_pass(&body_p, &body_w, &set)
            .into_iter()
            .filter(|(c, _)| c.rigid < 0.0)
            .map(|(k, o)| (k, rot(&pr, [0, 1, 2].map(|i| o.at[i] - c[i]))))
            .unzip();
        if cs.is_empty() {
            return Err(ReferenceError::NoContact {
                phi_deg: phi.to_degrees(),
                max_gap_um: self.settings.search_gap_m * 1e6,
            });
        }
        Ok((cs, at))
    }

    /// Adds the constraints `add` (indices into `cs`, not yet in the set)
    /// to the working set: their nodes' unit-load vectors, their constraint
    /// vectors, and the new rows and columns of the condensed matrix
    /// W = Σ_b Y_bᵀ Y_b (symmetric).
    fn grow(
        &mut self,
        cs: &[Constraint],
        ws: &mut WorkingSet,
        add: &[usize],
        split: &mut TimeSplit,
    ) -> Result<(), ReferenceError> {
        let lap = std::time::Instant::now();
        let mut add_y = Vec::with_capacity(add.len());
        for (body, m) in [(0, &mut *self.pinion), (1, &mut *self.wheel)] {
            let nodes: Vec<usize> = add
                .iter()
                .flat_map(|&c| {
                    cs[c]
                        .terms
                        .iter()
                        .filter(|t| t.body == body)
                        .map(|t| t.node)
                })
                .collect();
            m.compliance.ensure(&nodes)?;
        }
        split.forward_s += lap.elapsed().as_secs_f64();
        let lap = std::time::Instant::now();
        for &c in add {
            add_y.push([
                self.pinion.compliance.constraint_vector(&cs[c].terms, 0)?,
                self.wheel.compliance.constraint_vector(&cs[c].terms, 1)?,
            ]);
        }
        let mut idx = ws.idx.clone();
        idx.extend_from_slice(add);
        idx.sort_unstable();
        idx.dedup();
        let n = idx.len();
        let pos_old: Vec<usize> = ws
            .idx
            .iter()
            .map(|c| idx.binary_search(c).expect("old constraint kept"))
            .collect();
        let pos_new: Vec<usize> = add
            .iter()
            .map(|c| idx.binary_search(c).expect("new constraint added"))
            .collect();
        let mut y: Vec<Option<[PathVec; 2]>> = (0..n).map(|_| None).collect();
        for (p, v) in pos_old.iter().zip(std::mem::take(&mut ws.y)) {
            y[*p] = Some(v);
        }
        for (p, v) in pos_new.iter().zip(add_y) {
            y[*p] = Some(v);
        }
        let y: Vec<[PathVec; 2]> = y
            .into_iter()
            .map(|v| v.expect("every constraint has its vectors"))
            .collect();
        // W(all, new): the new columns; the new rows are their transpose.
        let mut cols = vec![0.0; n * add.len()];
        for b in 0..2 {
            let all: Vec<&PathVec> = y.iter().map(|v| &v[b]).collect();
            let new: Vec<&PathVec> = pos_new.iter().map(|&p| &y[p][b]).collect();
            for (c, v) in cols.iter_mut().zip(gram(&all, &new)) {
                *c += v;
            }
        }
        let mut w = vec![0.0; n * n];
        let old = &ws.idx;
        for (a, &pa) in pos_old.iter().enumerate() {
            for (b, &pb) in pos_old.iter().enumerate() {
                w[pa * n + pb] = ws.w[a * old.len() + b];
            }
        }
        for r in 0..n {
            for (k, &pk) in pos_new.iter().enumerate() {
                let v = cols[r * add.len() + k];
                w[r * n + pk] = v;
                w[pk * n + r] = v;
            }
        }
        ws.idx = idx;
        ws.w = w;
        ws.y = y;
        split.condensation_s += lap.elapsed().as_secs_f64();
        Ok(())
    }

    /// Loaded gap of every constraint of `cs` outside the working set,
    /// under each of `loads` (forces of the working set's constraints and
    /// the rigid rotation ψ): per load, (constraint, gap). The displacements
    /// are one backward solve per body for all loads together, on the paths
    /// of the outside constraints' nodes.
    fn outside_gaps(
        &self,
        cs: &[Constraint],
        ws: &WorkingSet,
        loads: &[(&[f64], f64)],
    ) -> Result<Vec<Vec<(usize, f64)>>, ReferenceError> {
        let outside: Vec<usize> = (0..cs.len())
            .filter(|c| ws.idx.binary_search(c).is_err())
            .collect();
        let mut gaps: Vec<Vec<f64>> = loads
            .iter()
            .map(|&(_, psi)| {
                outside
                    .iter()
                    .map(|&c| cs[c].gap0 + cs[c].rigid * psi)
                    .collect()
            })
            .collect();
        for (b, body) in [&self.pinion.compliance, &self.wheel.compliance]
            .into_iter()
            .enumerate()
        {
            let mut at: Vec<usize> = outside
                .iter()
                .flat_map(|&c| cs[c].terms.iter().filter(|t| t.body == b).map(|t| t.node))
                .collect();
            at.sort_unstable();
            at.dedup();
            if at.is_empty() {
                continue;
            }
            let z: Vec<PathVec> = loads
                .iter()
                .map(|(force, _)| {
                    let parts: Vec<(&PathVec, &[f64])> =
                        ws.y.iter()
                            .zip(force.iter())
                            .filter(|(_, f)| **f != 0.0)
                            .map(|(v, f)| (&v[b], std::slice::from_ref(f)))
                            .collect();
                    combine(&parts)
                })
                .collect();
            let zr: Vec<&PathVec> = z.iter().collect();
            let u = body.displacements(&zr, &at)?;
            for (g, u) in gaps.iter_mut().zip(&u) {
                for (g, &c) in g.iter_mut().zip(&outside) {
                    for t in cs[c].terms.iter().filter(|t| t.body == b) {
                        let p = at.binary_search(&t.node).expect("node collected above");
                        *g += (0..3).map(|i| t.dir[i] * u[p][i]).sum::<f64>();
                    }
                }
            }
        }
        Ok(gaps
            .into_iter()
            .map(|g| outside.iter().copied().zip(g).collect())
            .collect())
    }
}
