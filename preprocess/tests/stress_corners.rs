//! The stress matrix, flank grid: `utca.flank_grid_face` at 77–80,
//! 100, 200, 500 and 1,000 columns failed with "Newton did not converge"
//! (21–76 worked). Every column count the scene check admits up to 1,000
//! gives a complete grid of finite points on each of the four flanks of the
//! small scene's pair, inside the flank's cone-distance and height bounds.

use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::Scene;
use preprocess::flank_stage::flank_grid;
use std::path::Path;

#[test]
fn flank_grid_face_77_to_1000_columns_converges_on_every_flank() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/small.toml")).unwrap();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let profile = scene.scene.utca.flank_grid_profile;
    for n_face in [21, 76, 77, 78, 79, 80, 100, 200, 500, 1000] {
        for m in [Member::Pinion, Member::Wheel] {
            for side in [Side::Drive, Side::Coast] {
                let grid = flank_grid(g.flank(m, side), n_face, profile)
                    .unwrap_or_else(|e| panic!("{n_face} columns, {m:?} {side:?}: {e}"));
                assert_eq!(grid.position_m.len(), n_face * profile);
                assert!(grid
                    .position_m
                    .iter()
                    .chain(&grid.normal)
                    .flatten()
                    .all(|x| x.is_finite()));
            }
        }
    }
}
