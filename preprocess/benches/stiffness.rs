//! `make bench` (stiffness): assembly, factorization, per-right-hand-side
//! solve and total influence time of each member × blank of the default scene
//! at the reduced level, the peak memory of the process, and the time of a
//! second run that reuses the files. Meshes come from `meshes/default/` (made
//! by `make preprocess`; built here into a temporary directory if missing).
//! Targets: all three members ≤ 10 min with peak memory ≤ 12 GB;
//! a second run with nothing changed ≤ 10 s. Then each member × blank's
//! influence fields again by pruned forward solves with Gram products (the
//! stage's path) and by full solves on the same body: time of each, their
//! ratio in the same run, and the largest relative difference of the
//! fields. Results in `bench/stiffness.json`.

use formats::output::peak_memory_gb;
use geometry::scene::Scene;
use serde_json::json;
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join(&scene.scene.name);
    std::fs::create_dir_all(&dir).unwrap();
    let src = root.join("meshes").join(&scene.scene.name);
    let mut copied = 0;
    for stem in [
        "pinion_standard_reduced",
        "wheel_standard_reduced",
        "wheel_lightweight_reduced",
    ] {
        for ext in ["msh", "inputs.json"] {
            let f = src.join(format!("{stem}.{ext}"));
            if f.exists() {
                std::fs::copy(&f, dir.join(format!("{stem}.{ext}"))).unwrap();
                copied += 1;
            }
        }
    }
    // The manifest lists the meshes with their checksums (the stiffness
    // stage reads it); entries of meshes not copied are not used.
    if copied == 6 {
        std::fs::copy(src.join("manifest.json"), dir.join("manifest.json")).unwrap();
    }
    if copied < 6 {
        eprintln!("meshes/default incomplete: meshing into a temporary directory first");
        preprocess::mesh_stage::run(&scene, tmp.path(), preprocess::mesh_stage::Level::Reduced)
            .expect("meshes");
    }
    let t = Instant::now();
    let reports = preprocess::stiffness_stage::run(&scene, tmp.path()).expect("stiffness");
    let cold = t.elapsed().as_secs_f64();
    let peak = peak_memory_gb();
    let t = Instant::now();
    let again = preprocess::stiffness_stage::run(&scene, tmp.path()).expect("stiffness reuse");
    let warm = t.elapsed().as_secs_f64();
    assert!(again.iter().all(|r| r.reused));
    println!(
        "\nstiffness benchmark (default scene, reduced level, {} cores)\n",
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    println!(
        "{:<8} {:<12} {:>8} {:>9} {:>9} {:>10} {:>6} {:>12} {:>9} {:>9} {:>9}",
        "member",
        "blank",
        "dofs",
        "asm [s]",
        "fact [s]",
        "L [M val]",
        "loads",
        "ms per load",
        "gram [s]",
        "local [s]",
        "total [s]"
    );
    let mut rows = Vec::new();
    for r in &reports {
        let s = r.stats.as_ref().expect("computed");
        let per = 1e3 * s.solve_s / s.right_hand_sides.max(1) as f64;
        println!(
            "{:<8} {:<12} {:>8} {:>9.1} {:>9.1} {:>10.0} {:>6} {:>12.1} {:>9.1} {:>9.1} {:>9.1}",
            r.member,
            r.blank,
            s.dofs,
            s.assemble_s,
            s.factor_s,
            s.factor_nnz as f64 / 1e6,
            s.right_hand_sides,
            per,
            s.gram_s,
            s.local_s,
            r.total_s
        );
        rows.push(json!({"member": r.member, "blank": r.blank, "dofs": s.dofs, "assemble_s": s.assemble_s, "factor_s": s.factor_s,
            "factor_values": s.factor_nnz, "right_hand_sides": s.right_hand_sides, "ms_per_right_hand_side": per, "gram_s": s.gram_s,
            "path_vectors_gb": s.path_vectors_gb, "backward_check": s.backward_check,
            "local_s": s.local_s, "total_s": r.total_s}));
    }
    println!("\nall members {cold:.1} s (target 600 s), peak memory {peak:.2} GB (target 12 GB); second run reusing the files {warm:.2} s (target 10 s)");
    // A standard blank's tooth k carries tooth 0's compliance within 0.5 %.
    println!("\nstandard blank, reduced level: the loaded tooth's diagonal C(p, p) with the solved tooth and with each other periodic tooth loaded, |C_b - C_a| / C_a; at = [tooth, face, profile] of the largest");
    println!(
        "{:<8} {:>26} {:>14} {:>12} {:>15} {:>15} {:>12} {:>16}",
        "member",
        "teeth (solved first)",
        "total max [%]",
        "at",
        "total mean [%]",
        "global max [%]",
        "at",
        "global mean [%]"
    );
    let mut symmetry = Vec::new();
    for member in [
        geometry::design::Member::Pinion,
        geometry::design::Member::Wheel,
    ] {
        let t = preprocess::stiffness_stage::tooth_to_tooth(
            &scene,
            tmp.path(),
            member,
            formats::paths::MeshLevel::Reduced,
        )
        .expect("tooth-to-tooth");
        println!(
            "{:<8} {:>26} {:>14.3} {:>12} {:>15.3} {:>15.3} {:>12} {:>16.3}",
            t.member,
            format!("{:?}", t.teeth),
            100.0 * t.total_max_abs,
            format!("{:?}", t.total_worst),
            100.0 * t.total_mean_abs,
            100.0 * t.global_max_abs,
            format!("{:?}", t.global_worst),
            100.0 * t.global_mean_abs
        );
        symmetry.push(t);
    }
    println!("\nsolve paths on the same body: pruned forward solves + Gram products (the stage's) against full solves per unit load");
    println!(
        "{:<8} {:<12} {:>16} {:>14} {:>9} {:>16} {:>16}",
        "member", "blank", "pruned [s]", "full [s]", "ratio", "total max rel", "global max rel"
    );
    let mut paths = Vec::new();
    for (member, blank) in [
        (
            geometry::design::Member::Pinion,
            geometry::scene::Blank::Standard,
        ),
        (
            geometry::design::Member::Wheel,
            geometry::scene::Blank::Standard,
        ),
        (
            geometry::design::Member::Wheel,
            geometry::scene::Blank::Lightweight,
        ),
    ] {
        let c = preprocess::solve_paths::compare(
            &scene,
            tmp.path(),
            member,
            blank,
            formats::paths::MeshLevel::Reduced,
        )
        .expect("solve paths");
        let (tp, tf) = (c.pruned.solve_s + c.pruned.gram_s, c.full.solve_s);
        println!(
            "{:<8} {:<12} {:>16.2} {:>14.2} {:>9.1} {:>16.1e} {:>16.1e}",
            c.member,
            c.blank,
            tp,
            tf,
            tf / tp,
            c.total_max_rel,
            c.global_max_rel
        );
        paths.push(c);
    }
    let out = root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(
        &out.join("stiffness.json"),
        &json!({"results": rows, "tooth_to_tooth": symmetry, "solve_paths": paths, "all_members_s": cold, "peak_memory_gb": peak, "reuse_s": warm,
                "targets": {"all_members_s": 600.0, "peak_memory_gb": 12.0, "reuse_s": 10.0, "tooth_to_tooth_max": 0.005}}),
    )
    .unwrap();
    println!("written to bench/stiffness.json");
}
