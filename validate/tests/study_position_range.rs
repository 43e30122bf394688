//! The studies on one position (`validate convergence`, `validate
//! mesh-stiffness`) take a position index of the scene's sweep; one beyond
//! the sweep is refused before any FE work, with the sweep's range.
//! Example 03's scene: one mesh cycle (18° of pinion rotation) every 1°,
//! positions 0 to 18.

use geometry::scene::Scene;
use validate::studies::convergence::StudyPosition;

fn scene() -> geometry::scene::LoadedScene {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/03_reference_position");
    Scene::load(&dir.join("scene.toml")).unwrap()
}

#[test]
fn last_position_of_the_sweep_is_accepted() {
    let p = StudyPosition::new(&scene(), 18).unwrap();
    assert_eq!(p.index, 18);
}

#[test]
fn position_beyond_the_sweep_is_refused_with_its_range() {
    let Err(e) = StudyPosition::new(&scene(), 19) else {
        panic!("position 19 of a 19-position sweep must be refused")
    };
    let msg = e.to_string();
    for w in ["--position 19", "19 positions", "0 to 18"] {
        assert!(msg.contains(w), "'{w}' not in: {msg}");
    }
    assert!(StudyPosition::new(&scene(), 50_000).is_err());
}
