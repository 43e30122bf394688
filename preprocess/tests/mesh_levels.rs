//! Gear body meshes at the finer levels of the default scene (medium
//! 20 × 39 and reference 35 × 75 elements per flank, the pinion meshed
//! freely): gmsh's caps and slivers removed or carried, every flank node on
//! the generated flank, the FE reader's view of the surgery. Part of `make
//! test-long` (the `long-tests` feature): about a minute and a half of
//! meshing.

#[path = "../../geometry/tests/common/mod.rs"]
mod common;
#[path = "support/flank_fidelity.rs"]
mod flank_fidelity;

use fem::tet10::volume as tet10_volume;
use flank_fidelity::assert_flank_nodes_on_the_generated_flank;
use geometry::design::Member;
use geometry::gear_body::{BlankDimensions, BlankDimensionsMm};
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, FlankElements, LoadedScene, Scene};
use geometry::teeth::{opposite_refined_teeth, refined_teeth};
use preprocess::mesh::{mesh_member, MeshReport, MeshRequest};
use std::path::PathBuf;
use std::sync::OnceLock;

/// The medium level of the default scene: gmsh makes caps (flat tets over a
/// flank's surface triangles) on the pinion's coast flanks at this level.
const MEDIUM: FlankElements = FlankElements {
    profile: 20,
    face: 39,
};

fn geometry() -> &'static PairGeometry {
    static G: OnceLock<PairGeometry> = OnceLock::new();
    G.get_or_init(|| common::geometry(&common::white_paper()))
}

fn dims() -> &'static BlankDimensions {
    static D: OnceLock<BlankDimensions> = OnceLock::new();
    D.get_or_init(|| BlankDimensions::resolve(&BlankDimensionsMm::default(), &geometry().data))
}

fn default_scene() -> &'static LoadedScene {
    static SCENE: OnceLock<LoadedScene> = OnceLock::new();
    SCENE.get_or_init(|| {
        Scene::load(&common::reference("scenes/default.toml")).expect("default scene")
    })
}

/// The default scene's pinion request at `level`, refined on the teeth
/// `preprocess mesh` refines (both flanks), without periodic sectors: every
/// tooth meshed freely, as on the lightweight wheel. gmsh makes the poor
/// tets that the snapping must handle (flank and fillet caps, slivers) at
/// these levels only when meshing freely.
fn default_scene_pinion(level: FlankElements, level_name: &'static str) -> MeshRequest<'static> {
    let sc = &default_scene().scene;
    let g = geometry();
    MeshRequest {
        scene: &sc.name,
        geom: g,
        member: Member::Pinion,
        blank: Blank::Standard,
        dims: dims(),
        level,
        level_name,
        side: sc.loaded_flank,
        refined_teeth: refined_teeth(g, sc, Member::Pinion, Blank::Standard),
        opposite_refined_teeth: opposite_refined_teeth(g, sc, Member::Pinion, Blank::Standard),
        periodic_teeth: Vec::new(),
    }
}

/// The pinion of the default scene at the [`MEDIUM`] level: (report, .msh path).
fn pinion_medium() -> &'static (MeshReport, PathBuf) {
    static M: OnceLock<(MeshReport, PathBuf)> = OnceLock::new();
    M.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("bevel-mesh-test-{}", std::process::id()));
        let path = dir.join("pinion_medium.msh");
        let r = mesh_member(&default_scene_pinion(MEDIUM, "medium"), &path)
            .expect("pinion mesh, medium level");
        (r, path)
    })
}

#[test]
fn flank_group_nodes_lie_on_the_generated_flank_within_half_a_micrometre_caps_removed_slivers_carried(
) {
    let (report, path) = pinion_medium();
    assert_flank_nodes_on_the_generated_flank(geometry(), report, path);
    // This scene and level were chosen because gmsh makes both kinds of
    // poor tet there, so that both paths run (gmsh is pinned): caps on a
    // flank, and a sliver whose snapped vertex alone would invert it.
    assert!(report.caps_removed > 0, "no flank cap to remove");
    assert!(report.carried_nodes > 0, "no sliver carried");
}

/// At the reference level (35 × 75) gmsh puts two caps on the fillets of the
/// default scene's pinion, next to a refined flank: its snapped flank edge
/// inverted them, and six flank nodes stayed off the flank before they were
/// removed.
#[test]
fn reference_level_flank_nodes_lie_on_the_generated_flank_fillet_caps_removed() {
    let dir = std::env::temp_dir().join(format!("bevel-mesh-test-{}", std::process::id()));
    let path = dir.join("pinion_reference.msh");
    let level = default_scene().scene.mesh.reference;
    let report = mesh_member(&default_scene_pinion(level, "reference"), &path).unwrap();
    assert_flank_nodes_on_the_generated_flank(geometry(), &report, &path);
    assert!(report.other_caps_removed > 0, "no fillet cap to remove");
}

#[test]
fn fe_reader_drops_the_nodes_of_removed_caps_and_keeps_the_volume() {
    let (report, path) = pinion_medium();
    let body = preprocess::body_mesh::read(path).unwrap();
    let mut used = vec![false; body.mesh.nodes.len()];
    for t in &body.mesh.tets {
        for &n in t {
            used[n] = true;
        }
    }
    assert!(used.iter().all(|&u| u), "a node without a tetrahedron");
    assert_eq!(body.mesh.nodes.len(), report.nodes);
    assert_eq!(body.mesh.tets.len(), report.tet10_elements);
    let v: f64 = body
        .mesh
        .tets
        .iter()
        .map(|t| tet10_volume(&t.map(|n| body.mesh.nodes[n])))
        .sum();
    assert!((v / report.mesh_volume_m3 - 1.0).abs() < 1e-12);
    // Each flank face's nodes are tet nodes (read would fail otherwise) and
    // the flank groups survived the surgery.
    assert!(body.groups.keys().any(|k| k.starts_with("tooth")));
}
