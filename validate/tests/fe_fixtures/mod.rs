//! FE fixtures of the solver's integration tests (here, beside the FE,
//! since the solver crate builds without gmsh): the white-paper
//! pair with FE influence fields computed here on coarse meshes (6 × 10
//! elements per refined flank, standard blanks).

#![allow(dead_code)]

use geometry::design::Member;
use geometry::design_file::load_pair;
use geometry::gear_body::{BlankDimensions, BlankDimensionsMm};
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, FlankElements};
use geometry::teeth::periodic_teeth;
use preprocess::body_mesh;
use preprocess::influence::{compute, FlankGrid, GridSize, InfluenceRequest, Solves};
use preprocess::mesh::{mesh_member, MeshRequest};
use solver::element::compliance::MemberCompliance;

pub const LEVEL: FlankElements = FlankElements {
    profile: 6,
    face: 10,
};
pub const GRID: GridSize = GridSize {
    profile: 6,
    face: 10,
};

/// The white-paper pair's geometry.
pub fn white_paper() -> PairGeometry {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../reference/white_paper_20x43.toml"
    );
    PairGeometry::new(&load_pair(std::path::Path::new(path)).unwrap()).unwrap()
}

/// Meshes member `m` (standard blank) with the `refined` teeth's drive
/// flanks and the `opposite` teeth's coast flanks refined; `tag` keeps the
/// mesh files of different fixtures apart.
pub fn mesh(
    g: &PairGeometry,
    m: Member,
    refined: &[usize],
    opposite: &[usize],
    tag: &str,
) -> body_mesh::BodyMesh {
    let dir = std::env::temp_dir().join(format!("bevel-solver-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{tag}-{}.msh", m.name()));
    let dims = BlankDimensions::resolve(&BlankDimensionsMm::default(), &g.data);
    mesh_member(
        &MeshRequest {
            scene: "solver-test",
            geom: g,
            member: m,
            blank: Blank::Standard,
            dims: &dims,
            level: LEVEL,
            level_name: "reduced",
            side: Side::Drive,
            refined_teeth: refined.to_vec(),
            opposite_refined_teeth: opposite.to_vec(),
            periodic_teeth: periodic_teeth(Blank::Standard, refined, opposite),
        },
        &path,
    )
    .expect("mesh");
    body_mesh::read(&path).unwrap()
}

/// Member `m`'s compliance for unit loads on its `side` flank of tooth
/// `solved` (responses on ±2 teeth).
pub fn compliance(
    g: &PairGeometry,
    body: &body_mesh::BodyMesh,
    m: Member,
    side: Side,
    solved: usize,
) -> MemberCompliance {
    let grid = FlankGrid::new(g.flank(m, side), GRID).unwrap();
    let (sf, sp) = grid.spacing();
    let md = g.data.member(m);
    let inf = compute(
        &InfluenceRequest {
            body,
            material: preprocess::influence::fe_material(md.material()),
            teeth: md.teeth as usize,
            loaded: side.flank_name(m),
            opposite: side.other().flank_name(m),
            grid: &grid,
            solved_teeth: vec![solved],
            offsets: (-2..=2).collect(),
            load_radius: 0.75 * sf.max(sp),
            fillet_rise: preprocess::influence::FILLET_RISE,
            block: 8,
            solves: Solves::default(),
            root: None,
        },
        &["bore"],
    )
    .unwrap();
    let data = formats::stiffness_file::StiffnessData {
        member: m.name().into(),
        ..preprocess::stiffness_stage::stiffness_data(&grid, inf, md.teeth as usize, true)
    };
    MemberCompliance::new(data, md.material())
}
