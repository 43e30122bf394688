//! `make bench` (lumped): the 8-DOF lumped run of 50 mesh cycles (seed
//! 004's run: 5,900 rpm pinion, first 10 cycles dropped, rtol 1e-6, its
//! meshing impact on) driven by the LTCA of example 02's checked-in
//! stiffness fixture (white-paper pair, standard blanks; no gmsh), timed
//! against the budget of 2 s for the integration, next to the LTCA
//! at the three torques of the tangent stiffness and the whole
//! `solver lumped` stage. Results in `bench/lumped.json`.

use geometry::scene::Scene;
use geometry::scene_lumped::{ImpactModel, LumpedSettings};
use serde_json::json;
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = root.join("examples/02_ltca_fixture");
    let mut scene = Scene::load(&dir.join("scene.toml")).expect("example 02 scene");
    scene.scene.lumped = Some(LumpedSettings {
        pinion_speed_rpm: 5900.0,
        pinion_torque_nm: 300.0,
        impact: ImpactModel::Seed004,
        pinion_bearing_stiffness_n_per_m: [1e9; 3],
        wheel_bearing_stiffness_n_per_m: [1e9; 3],
        ..LumpedSettings::default()
    });
    let out =
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bench_lumped_{}", std::process::id()));
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let mut rows = Vec::new();
    println!("\nLumped 8-DOF benchmark (example 02 fixture, 50 mesh cycles at 5,900 rpm, {cores} cores)\n");
    println!(
        "{:>4} {:>10} {:>12} {:>8} {:>14}",
        "run", "stage[s]", "integrate[s]", "steps", "RMS normal"
    );
    for k in 0..3 {
        let t = Instant::now();
        let s = solver::stage::lumped::run(&scene, &dir.join("meshes"), &out).expect("lumped run");
        let stage = t.elapsed().as_secs_f64();
        let b = &s[0];
        println!(
            "{:>4} {:>10.3} {:>12.3} {:>8} {:>14.2}",
            k, stage, b.integration_wall_s, b.steps[0], b.rms_acceleration_m_s2.mesh_normal
        );
        rows.push(
            json!({"stage_s": stage, "integration_s": b.integration_wall_s,
            "steps": b.steps, "evaluations": b.evaluations,
            "rms_mesh_normal_m_s2": b.rms_acceleration_m_s2.mesh_normal}),
        );
    }
    let _ = std::fs::remove_dir_all(&out);
    let best = rows
        .iter()
        .map(|r| r["integration_s"].as_f64().unwrap_or(f64::INFINITY))
        .fold(f64::INFINITY, f64::min);
    println!(
        "\nbest integration {best:.3} s (budget 2 s): {}",
        if best <= 2.0 { "within" } else { "OVER" }
    );
    let bench = root.join("bench");
    std::fs::create_dir_all(&bench).unwrap();
    formats::output::write_json(
        &bench.join("lumped.json"),
        &json!({"machine": format!("{cores} cores, {}", std::env::consts::ARCH),
            "case": "solver lumped on examples/02_ltca_fixture with [lumped] at seed 004's run: 5900 rpm, 300 N m, 50 mesh cycles, 10 dropped, rtol 1e-6, seed004 impact",
            "budget_integration_s": 2.0, "best_integration_s": best, "runs": rows}),
    )
    .unwrap();
    println!("written to bench/lumped.json");
}
