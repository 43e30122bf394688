//! `make bench` (meshing): time and size of each member × blank mesh of the
//! default scene at the reduced-order level (add the reference level with
//! `BENCH_REFERENCE=1`). Results in `bench/mesh.json` and a table.
//! Targets: reduced level ≤ 30 s, reference level ≤ 3 min per member.

use geometry::design::Member;
use geometry::gear_body::BlankDimensions;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, Scene};
use geometry::teeth::{periodic_teeth, refined_teeth};
use preprocess::mesh::{mesh_member, MeshRequest};
use serde_json::json;
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let sc = &scene.scene;
    let g = PairGeometry::new(&scene.pair).unwrap();
    let dims = BlankDimensions::resolve(&sc.blank_dimensions, &g.data);
    let mut levels = vec![("reduced", sc.mesh.reduced_order, 30.0)];
    if std::env::var_os("BENCH_REFERENCE").is_some() {
        levels.push(("reference", sc.mesh.reference, 180.0));
    }
    let dir = tempfile::tempdir().unwrap();
    let mut rows = Vec::new();
    println!(
        "\nmesh benchmark (default scene, {} cores)\n",
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    println!(
        "{:<8} {:<12} {:<10} {:>9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>7}",
        "member",
        "blank",
        "level",
        "nodes",
        "tet10",
        "cut [s]",
        "geom",
        "1-3D",
        "order 2",
        "snap",
        "total",
        "target"
    );
    for (member, blank) in [
        (Member::Pinion, Blank::Standard),
        (Member::Wheel, Blank::Standard),
        (Member::Wheel, Blank::Lightweight),
    ] {
        let refined = refined_teeth(&g, sc, member, blank);
        for &(name, level, target) in &levels {
            let req = MeshRequest {
                scene: &sc.name,
                geom: &g,
                member,
                blank,
                dims: &dims,
                level,
                level_name: name,
                side: sc.loaded_flank,
                refined_teeth: refined.clone(),
                opposite_refined_teeth: Vec::new(),
                periodic_teeth: periodic_teeth(blank, &refined, &[]),
            };
            let t = Instant::now();
            let r = mesh_member(&req, &dir.path().join("m.msh")).expect("mesh");
            let total = t.elapsed().as_secs_f64();
            println!(
                "{:<8} {:<12} {:<10} {:>9} {:>9} {:>8.1} {:>8.1} {:>8.1} {:>8.1} {:>8.1} {:>8.1} {:>7}",
                member.name(),
                format!("{blank:?}"),
                name,
                r.nodes,
                r.tet10_elements,
                r.time_cut_s,
                r.time_geometry_s,
                r.time_generate_s,
                r.time_order2_s,
                r.time_snap_s,
                total,
                target
            );
            rows.push(json!({"member": member.name(), "blank": blank, "level": name, "nodes": r.nodes, "tet10": r.tet10_elements,
                "geometry_s": r.time_geometry_s, "cut_s": r.time_cut_s, "mesh_s": r.time_mesh_s,
                "generate_s": r.time_generate_s, "order2_s": r.time_order2_s, "snap_s": r.time_snap_s, "total_s": total, "target_s": target, "min_sicn": r.quality_min_sicn}));
        }
    }
    let out = root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(&out.join("mesh.json"), &json!({"results": rows})).unwrap();
    println!("\nwritten to bench/mesh.json");
}
