//! `make bench` (sensitivity): `solver sensitivity` on the default scene
//! (E, P, G, ΔΣ × the scene's 9 values × its 5 loads over the standard
//! wheel's sweep) with the stiffness files in `meshes/default/` (made by
//! `make preprocess`), into a scratch output. Target: ≤ 2 min
//! with the stiffness files cached. Results in `bench/sensitivity.json`.

use geometry::scene::Scene;
use serde_json::json;
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let sc = &scene.scene;
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("bench_sensitivity");
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let t0 = Instant::now();
    let r = solver::stage::sensitivity::run(&scene, &root.join("meshes"), &out)
        .expect("meshes/default: run `make preprocess` first");
    let wall = t0.elapsed().as_secs_f64();
    let runs: usize = r.curves.iter().map(|c| c.points.len()).sum();
    println!(
        "\nsensitivity benchmark (default scene, {cores} cores): {runs} misalignments x {} loads x {} positions in {wall:.1} s ({:.2} s per misalignment); target <= 120 s",
        r.torques_nm.len(),
        r.positions,
        wall / runs as f64
    );
    formats::output::write_json(
        &root.join("bench/sensitivity.json"),
        &json!({
            "scene": sc.name,
            "cores": cores,
            "misalignments": runs,
            "loads": r.torques_nm.len(),
            "positions": r.positions,
            "wall_s": wall,
            "target_s": 120.0,
        }),
    )
    .expect("bench/sensitivity.json");
    let _ = std::fs::remove_dir_all(&out);
    println!("written to bench/sensitivity.json");
}
