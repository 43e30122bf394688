//! `make bench` (influence_convergence): mesh convergence of the influence
//! fields of the default scene. The stiffness files of every member × blank
//! on the reduced-order meshes and on the medium meshes (the same contact
//! grid) are compared on the loaded tooth's diagonal, for the total, local
//! and global fields (see `preprocess::field_convergence`). The
//! global field should change by less than 3 % while the total field changes
//! much more. Meshes and files go to `meshes/default/` and are reused there.
//! Results in `bench/influence_convergence.json`.

use formats::stiffness_file;
use geometry::scene::Scene;
use preprocess::field_convergence::diagonal_change;
use preprocess::mesh_stage::Level;
use serde_json::json;
use std::path::Path;
use std::time::Instant;

const BOUND: f64 = 0.03;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let meshes = root.join("meshes");
    let t = Instant::now();
    for level in [Level::Reduced, Level::Medium] {
        preprocess::mesh_stage::run(&scene, &meshes, level).expect("meshes");
    }
    let reduced = preprocess::stiffness_stage::run_level(&scene, &meshes, Level::Reduced)
        .expect("reduced stiffness");
    let medium = preprocess::stiffness_stage::run_level(&scene, &meshes, Level::Medium)
        .expect("medium stiffness");
    let wall = t.elapsed().as_secs_f64();
    let (lr, lm) = (scene.scene.mesh.reduced_order, scene.scene.mesh.medium());
    println!(
        "\ninfluence fields, reduced mesh ({} x {} elements per active flank) against medium mesh ({} x {}), each member on its own contact grid in both; relative change of the loaded tooth's diagonal C(p, p)\n",
        lr.profile, lr.face, lm.profile, lm.face
    );
    println!(
        "{:<8} {:<12} {:<7} {:>9} {:>10} {:>9} {:>13} {:>12}  mean |r| per profile row, root first [%]",
        "member", "blank", "field", "mean [%]", "|r| mean", "max [%]", "interior max", "within 3 %"
    );
    let mut rows = Vec::new();
    for (r, m) in reduced.iter().zip(&medium) {
        let coarse = stiffness_file::read(&r.path, Some(&r.input_hash)).expect("reduced file");
        let fine = stiffness_file::read(&m.path, Some(&m.input_hash)).expect("medium file");
        let changes = diagonal_change(&coarse, &fine, BOUND).expect("comparable files");
        for c in &changes {
            println!(
                "{:<8} {:<12} {:<7} {:>+9.2} {:>10.2} {:>9.2} {:>13.2} {:>11.0}%  {}",
                r.member,
                r.blank,
                c.field,
                100.0 * c.mean,
                100.0 * c.mean_abs,
                100.0 * c.max_abs,
                100.0 * c.interior_max_abs,
                100.0 * c.share_within,
                c.row_mean_abs
                    .iter()
                    .map(|x| format!("{:.1}", 100.0 * x))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
            rows.push(json!({"member": r.member, "blank": r.blank, "grid": [coarse.grid_profile, coarse.grid_face], "file": r.path.file_name().map(|f| f.to_string_lossy().into_owned()),
                "field": c.field, "mean_percent": 100.0 * c.mean, "mean_abs_percent": 100.0 * c.mean_abs,
                "max_abs_percent": 100.0 * c.max_abs, "interior_max_abs_percent": 100.0 * c.interior_max_abs,
                "share_within_bound": c.share_within, "row_mean_abs_percent": c.row_mean_abs.iter().map(|x| 100.0 * x).collect::<Vec<_>>()}));
        }
    }
    println!("\nr = (C_medium - C_reduced) / C_medium; interior: without the root row and the toe and heel columns; {wall:.0} s (files reused where present)");
    let out = root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(
        &out.join("influence_convergence.json"),
        &json!({"reduced_elements": [lr.profile, lr.face], "medium_elements": [lm.profile, lm.face],
                "bound_percent": 100.0 * BOUND, "results": rows, "wall_s": wall}),
    )
    .unwrap();
    println!("written to bench/influence_convergence.json");
}
