//! `preprocess stiffness --level medium` on a scene whose meshes of that
//! level `preprocess mesh` would skip (no `[analyses] reference`) says so,
//! instead of sending the user to `preprocess mesh`, which would skip them
//! again. On the example-02 scene (LTCA only), before any work.

use preprocess::mesh_stage::Level;
use preprocess::stiffness_stage::run_level;
use std::path::Path;

#[test]
fn stiffness_at_a_level_no_analysis_meshes_explains_why_the_mesh_is_missing() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture");
    let scene = geometry::scene::Scene::load(&dir.join("scene.toml")).unwrap();
    assert!(!scene.scene.analyses.reference);
    let root = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("stiffness_level_messages_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    let r = run_level(&scene, &root, Level::Medium);
    let _ = std::fs::remove_dir_all(&root);
    let e = format!("{:#}", r.unwrap_err());
    assert!(
        e.contains("medium meshes only for a scene whose [analyses] has reference = true"),
        "{e}"
    );
    assert!(!e.contains("first"), "{e}");
}
