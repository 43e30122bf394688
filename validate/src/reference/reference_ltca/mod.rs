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

mod position;
mod working_set;

use crate::reference::body_compliance::clamped;
use crate::reference::contact_surface::{nodal_normals, orient_outward};
use crate::reference::path_compliance::PathCompliance;
use crate::reference::penalty::ContactError;
use geometry::generation::{rot_z, MemberFrame};
use geometry::misalignment::Pose;
use geometry::pair::FlankPair;
use nalgebra::Vector3;
use preprocess::body_mesh::BodyMesh;
use preprocess::fillet_nodes::FilletError;
use preprocess::root_stress::{FilletStress, RootStressPoints};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

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
    /// The fillets of the teeth that can touch, whose root stress each
    /// loaded solve gives (None: not asked for).
    pub root: Option<RootStressPoints>,
    /// The tooth of each loaded-flank node.
    tooth_of: HashMap<usize, usize>,
}

impl Member {
    /// Factors the body (bore clamped) and collects the loaded flank faces
    /// of `teeth` (`flank` = "concave"/"convex"); the factor is kept on the
    /// paths of the flank nodes and of the `root` fillets' support.
    pub fn new(
        mesh: BodyMesh,
        frame: MemberFrame,
        material: &fem::Material,
        flank: &str,
        teeth: &[usize],
        block: usize,
        root: Option<RootStressPoints>,
    ) -> Result<Member, ReferenceError> {
        let mut faces = Vec::new();
        let mut tooth_of = HashMap::new();
        for &k in teeth {
            let name = format!("tooth{k}_{flank}");
            let g = mesh.group(&name);
            if g.is_empty() {
                return Err(ReferenceError::MissingGroup(name));
            }
            faces.extend_from_slice(g);
            tooth_of.extend(g.iter().flatten().map(|&n| (n, k)));
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
        let mut keep = contact.clone();
        if let Some(r) = &root {
            keep.extend(r.support(&r.teeth()));
            keep.sort_unstable();
            keep.dedup();
        }
        let compliance = PathCompliance::new(&mesh.mesh, material, &clamped(&bore), &keep, block)?;
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
            root,
            tooth_of,
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
        let material = preprocess::influence::fe_material(g.data.member(which).material());
        let root = RootStressPoints::new(&mesh, g, which, side, teeth, material)?;
        Member::new(
            mesh,
            frame,
            &material,
            side.flank_name(which),
            teeth,
            block,
            Some(root),
        )
    }

    /// The teeth (of those that can touch) holding any of the flank
    /// `nodes`, ascending.
    pub fn teeth_of(&self, nodes: impl Iterator<Item = usize>) -> Vec<usize> {
        let mut t: Vec<usize> = nodes
            .filter_map(|n| self.tooth_of.get(&n).copied())
            .collect();
        t.sort_unstable();
        t.dedup();
        t
    }

    /// Root stress of both fillets of each of `teeth` (of [`Member::root`])
    /// under each forward-solved load of `z`: one backward solve for all
    /// loads on the paths of the fillets' support nodes. Empty without
    /// fillets.
    pub fn root_stress(
        &self,
        z: &[&fem::path_solve::PathVec],
        teeth: &[usize],
    ) -> Result<Vec<Vec<FilletStress>>, ReferenceError> {
        let Some(root) = &self.root else {
            return Ok(vec![Vec::new(); z.len()]);
        };
        let support = root.support(teeth);
        let u = self.compliance.displacements(z, &support)?;
        Ok(u.iter()
            .map(|u| root.evaluate(&self.mesh.mesh, teeth, &support, u))
            .collect())
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
    #[error("root fillets: {0}")]
    Fillet(#[from] FilletError),
}

/// Which node-to-surface passes the reference contact enforces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactPasses {
    /// Pinion nodes against the wheel's flank faces and wheel nodes
    /// against the pinion's (the reference's contact).
    #[default]
    TwoPass,
    /// Pinion nodes against the wheel's flank faces only: at a pinion tip
    /// edge the force then acts along the wheel's normal alone. The two
    /// differ where the contact runs onto an edge (the spread is the
    /// contact formulation's share of the reference's uncertainty).
    PinionSlave,
}

impl ContactPasses {
    /// Whether a constraint whose slave point lies on body `slave_body`
    /// (0 pinion, 1 wheel) is enforced.
    pub fn keeps(self, slave_body: usize) -> bool {
        match self {
            ContactPasses::TwoPass => true,
            ContactPasses::PinionSlave => slave_body == 0,
        }
    }

    /// The variant's name in folder names and options.
    pub fn name(self) -> &'static str {
        match self {
            ContactPasses::TwoPass => "two-pass",
            ContactPasses::PinionSlave => "pinion-slave",
        }
    }

    fn is_two_pass(&self) -> bool {
        *self == ContactPasses::TwoPass
    }
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
    /// The passes enforced. Left out of the serialized settings (and so of
    /// the position cache's key) when two-pass, the default.
    #[serde(default, skip_serializing_if = "ContactPasses::is_two_pass")]
    pub passes: ContactPasses,
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
    /// Root stress of each fillet of the teeth that can touch, pinion's
    /// then wheel's, at the penalty factor's solution (None where the
    /// fillets were not asked for).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_stress: Option<[Vec<FilletStress>; 2]>,
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
    /// Root stresses (backward solves on the fillets' support nodes).
    #[serde(default)]
    pub root_stress_s: f64,
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
