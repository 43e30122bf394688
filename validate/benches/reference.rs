//! `make bench` (reference): the cost of the reference FE contact.
//!
//! 1. Unit-load right-hand sides on the reduced-level pinion: the full
//!    forward + backward solves with responses kept over every flank node
//!    (`BodyCompliance`, the path before the pruned solves) against the
//!    pruned forward solves along each node's elimination-tree path
//!    (`PathCompliance`), for the same nodes of one flank: time per
//!    right-hand side.
//! 2. Consecutive positions of the sweep of each wheel blank (the pinion
//!    factored once for both, as in `validate reference`) at the reduced
//!    level and, with `BENCH_FINE=1`, at the reference level (35 × 75; needs
//!    its meshes): factor sizes and times, wall time per position (the first
//!    pays for a cold window) and where it goes, peak memory.
//!
//! Target: ≤ 30 s per position amortized over a reference-level
//! sweep, peak ≤ 16 GB; the white paper's reference took 1,020–1,150 s per
//! step. Results in `bench/reference.json`. Meshes come from `meshes/default/`
//! (`make preprocess`; `preprocess mesh --level reference` for the fine part).

use formats::output::peak_memory_gb;
use geometry::design::Member as Which;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, Scene};
use serde_json::json;
use std::path::Path;
use std::time::Instant;
use validate::reference::body_compliance::{clamped, BodyCompliance};
use validate::reference::path_compliance::PathCompliance;
use validate::reference::reference_ltca::{Member, ReferencePair, ReferenceSettings};

/// Flank nodes loaded per solve comparison.
const NODES: usize = 96;
/// Right-hand sides per block: today's default for each path.
const BLOCK_FULL: usize = 16;
const BLOCK_PATH: usize = 96;

/// The default scene's pair and sweep, shared by both parts.
struct Bench<'a> {
    sc: &'a geometry::scene::Scene,
    g: &'a PairGeometry,
    /// The scene's meshes folder.
    dir: &'a Path,
    side: geometry::generation::Side,
    direction: f64,
    step: f64,
}

/// Part 1's timings: the flank nodes loaded, their right-hand sides, and
/// the full and pruned solves' wall times, s.
struct RightHandSides {
    nodes: usize,
    rhs: usize,
    full_s: f64,
    path_s: f64,
}

/// Part 2's measures of one blank pair's consecutive positions.
struct Positions {
    cpu: Vec<f64>,
    new_nodes: Vec<usize>,
    /// Mean time per position after the first, by part: search, forward
    /// solves, condensation, active-set solves, outside gaps.
    split: [f64; 5],
    window_gb: f64,
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let sc = &scene.scene;
    let dir = root.join("meshes").join(&sc.name);
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let side = sc.loaded_flank;
    let direction = pinion_direction(&g.data, side);
    let step = sc.rotation.step_deg.to_radians();
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    println!("\nReference FE contact benchmark (default scene, {cores} cores)\n");

    let b = Bench {
        sc,
        g: &g,
        dir: &dir,
        side,
        direction,
        step,
    };
    let rhs = right_hand_sides(&b);
    let sweeps = consecutive_positions(&b);
    let out = json!({
        "machine_cores": cores,
        "right_hand_sides": {
            "member": "pinion_standard_reduced",
            "nodes": rhs.nodes,
            "full_block": BLOCK_FULL,
            "full_ms_per_rhs": rhs.full_s / rhs.rhs as f64 * 1e3,
            "path_block": BLOCK_PATH,
            "path_ms_per_rhs": rhs.path_s / rhs.rhs as f64 * 1e3,
        },
        "sweeps": sweeps,
        "peak_memory_gb": peak_memory_gb(),
    });
    formats::output::write_json(&root.join("bench/reference.json"), &out).unwrap();
    println!("\nwritten to bench/reference.json");
}

/// Part 1: unit-load right-hand sides on the reduced-level pinion, full
/// solves against pruned forward solves for the same flank nodes.
fn right_hand_sides(b: &Bench) -> RightHandSides {
    let (sc, g, dir, side, step) = (b.sc, b.g, b.dir, b.side, b.step);
    let pm = dir.join("pinion_standard_reduced.msh");
    let mesh = preprocess::body_mesh::read(&pm)
        .expect("meshes/default/pinion_standard_reduced.msh: run `make preprocess` first");
    let mat = preprocess::influence::fe_material(g.data.member(Which::Pinion).material());
    let fixed = clamped(&mesh.group_nodes("bore"));
    let (teeth, _) = teeth_in_contact(g, side, sc.rotation.mesh_cycles_standard, step);
    let flank = mesh.group(&format!(
        "tooth{}_{}",
        teeth[0],
        side.flank_name(Which::Pinion)
    ));
    let mut universe: Vec<usize> = flank.iter().flatten().copied().collect();
    universe.sort_unstable();
    universe.dedup();
    let nodes: Vec<usize> = universe
        .iter()
        .step_by((universe.len() / NODES).max(1))
        .copied()
        .take(NODES)
        .collect();
    let mut full = BodyCompliance::new(&mesh.mesh, &mat, &fixed, &universe, BLOCK_FULL).unwrap();
    let t = Instant::now();
    full.ensure(&nodes).unwrap();
    let full_s = t.elapsed().as_secs_f64();
    let mut path = PathCompliance::new(&mesh.mesh, &mat, &fixed, &universe, BLOCK_PATH).unwrap();
    let t = Instant::now();
    path.ensure(&nodes).unwrap();
    let path_s = t.elapsed().as_secs_f64();
    let rhs = 3 * nodes.len();
    println!(
        "reduced pinion ({} free dofs), {} flank nodes of tooth {} ({rhs} right-hand sides):",
        path.dofs_free,
        nodes.len(),
        teeth[0]
    );
    println!(
        "  factor: full {:.1} s, supernodal {:.1} s",
        full.factor_s, path.factor_s
    );
    println!(
        "  full solves, blocks of {BLOCK_FULL}:    {:7.2} ms per right-hand side",
        full_s / rhs as f64 * 1e3
    );
    println!(
        "  pruned forward, blocks of {BLOCK_PATH}: {:7.2} ms per right-hand side ({:.0}x less), {:.1} MB per node kept",
        path_s / rhs as f64 * 1e3,
        full_s / path_s,
        path.bytes() as f64 / nodes.len() as f64 / 1e6
    );
    drop(full);
    drop(path);
    RightHandSides {
        nodes: nodes.len(),
        rhs,
        full_s,
        path_s,
    }
}

/// Part 2: consecutive positions of each wheel blank's sweep at the reduced
/// level (and the reference level with `BENCH_FINE=1`), the pinion factored
/// once for both; one JSON record per level and blank.
fn consecutive_positions(b: &Bench) -> Vec<serde_json::Value> {
    let dir = b.dir;
    let settings = ReferenceSettings {
        penalty_factor: 100.0,
        penalty_factor_check: 200.0,
        start_band_m: 2e-6,
        search_gap_m: 60e-6,
        passes: Default::default(),
    };
    let mut levels = vec![("reduced", 12usize)];
    if std::env::var("BENCH_FINE").is_ok_and(|v| v == "1") {
        levels.push(("reference", 6));
    } else {
        println!("\n(BENCH_FINE=1 adds consecutive positions at the reference level, 35 x 75)");
    }
    let mut sweeps = Vec::new();
    for (level, n) in levels {
        let msh = |m: &str, b: &str| dir.join(format!("{m}_{b}_{level}.msh"));
        if !msh("pinion", "standard").exists() {
            println!(
                "\n{level}: no meshes in {}; `preprocess mesh --level {level}` makes them",
                dir.display()
            );
            continue;
        }
        // The pinion is factored once for both wheel blanks, as in the stage.
        let mut pinion: Option<Member> = None;
        for (blank, wb) in [
            ("standard", Blank::Standard),
            ("lightweight", Blank::Lightweight),
        ] {
            if !msh("wheel", blank).exists() {
                continue;
            }
            sweeps.push(blank_pair(
                b,
                settings,
                (level, n),
                (blank, wb),
                &mut pinion,
            ));
        }
    }
    sweeps
}

/// The standard pinion (loaded and factored at its first use) and the
/// `blank` wheel at `level`: `n` consecutive positions, printed and as one
/// JSON record.
fn blank_pair(
    b: &Bench,
    settings: ReferenceSettings,
    (level, n): (&str, usize),
    (blank, wb): (&str, Blank),
    pinion: &mut Option<Member>,
) -> serde_json::Value {
    let (sc, g, dir, side, step) = (b.sc, b.g, b.dir, b.side, b.step);
    let msh = |m: &str, b: &str| dir.join(format!("{m}_{b}_{level}.msh"));
    let gb = |m: &Member, k: usize| m.compliance.factor_nnz[k] as f64 * 8.0 / 1e9;
    let (pinion_teeth, _) =
        teeth_in_contact(g, side, sc.rotation.mesh_cycles(Blank::Lightweight), step);
    let (_, wheel_teeth) = teeth_in_contact(g, side, sc.rotation.mesh_cycles(wb), step);
    let t = Instant::now();
    let pinion = pinion.get_or_insert_with(|| {
        Member::load(
            &msh("pinion", "standard"),
            g,
            Which::Pinion,
            side,
            &pinion_teeth,
            BLOCK_PATH,
        )
        .unwrap()
    });
    let mut wheel = Member::load(
        &msh("wheel", blank),
        g,
        Which::Wheel,
        side,
        &wheel_teeth,
        BLOCK_PATH,
    )
    .unwrap();
    let load_s = t.elapsed().as_secs_f64();
    let mut pair = ReferencePair {
        pinion,
        wheel: &mut wheel,
        flanks: g.side(side),
        direction: b.direction,
        settings,
    };
    let Positions {
        cpu,
        new_nodes,
        split,
        window_gb,
    } = positions(b, &mut pair, n);
    let warm = &cpu[1..];
    let warm_mean = warm.iter().sum::<f64>() / warm.len().max(1) as f64;
    println!(
        "\n{level} level, standard pinion / {blank} wheel, {} + {} dofs: read + factor {:.0} s ({:.0} + {:.0} s factoring); factors {:.2} + {:.2} GB, kept on the contact nodes' paths {:.2} + {:.2} GB",
        pair.pinion.compliance.dofs_free,
        pair.wheel.compliance.dofs_free,
        load_s,
        pair.pinion.compliance.factor_s,
        pair.wheel.compliance.factor_s,
        gb(pair.pinion, 1),
        gb(pair.wheel, 1),
        gb(pair.pinion, 0),
        gb(pair.wheel, 0)
    );
    println!(
        "  {n} positions: first {:.2} s ({} new nodes), then {:.2} s per position ({:.0} new nodes each); window {:.2} GB; peak memory so far {:.1} GB",
        cpu[0],
        new_nodes[0],
        warm_mean,
        new_nodes[1..].iter().sum::<usize>() as f64 / warm.len().max(1) as f64,
        window_gb,
        peak_memory_gb()
    );
    println!(
        "  after the first, per position: search {:.2} s, forward solves {:.2} s, W {:.2} s, active-set solves {:.2} s, outside gaps {:.2} s",
        split[0], split[1], split[2], split[3], split[4]
    );
    json!({
        "level": level,
        "wheel_blank": blank,
        "time_split_s_after_first": {
            "search": split[0],
            "forward": split[1],
            "condensation": split[2],
            "contact": split[3],
            "outside": split[4],
        },
        "dofs": [pair.pinion.compliance.dofs_free, pair.wheel.compliance.dofs_free],
        "read_and_factor_s": load_s,
        "factor_s": [pair.pinion.compliance.factor_s, pair.wheel.compliance.factor_s],
        "factor_gb": [gb(pair.pinion, 1), gb(pair.wheel, 1)],
        "factor_kept_gb": [gb(pair.pinion, 0), gb(pair.wheel, 0)],
        "positions": n,
        "cpu_s_per_position": cpu,
        "new_nodes_per_position": new_nodes,
        "cpu_s_per_position_after_first": warm_mean,
        "window_gb": window_gb,
        "peak_memory_gb_so_far": peak_memory_gb(),
    })
}

/// `n` consecutive positions of `pair`'s sweep: their CPU times, new nodes,
/// the mean time split after the first, and the largest window.
fn positions(b: &Bench, pair: &mut ReferencePair, n: usize) -> Positions {
    let (sc, fp, direction, step) = (b.sc, b.g.side(b.side), b.direction, b.step);
    let mut cpu = Vec::new();
    let mut new_nodes = Vec::new();
    let mut split = [0.0; 5];
    let mut window_gb: f64 = 0.0;
    for i in 0..n {
        let phi = fp.roll_range[0] + direction * step * i as f64;
        let r = pair.position(phi, &sc.pinion_torque_nm).unwrap();
        cpu.push(r.cpu_s);
        new_nodes.push(r.new_columns);
        if let (true, Some(t)) = (i > 0, r.time_split) {
            for (a, b) in split.iter_mut().zip([
                t.search_s,
                t.forward_s,
                t.condensation_s,
                t.contact_s,
                t.outside_s,
            ]) {
                *a += b / (n - 1) as f64;
            }
        }
        window_gb = window_gb
            .max((pair.pinion.compliance.bytes() + pair.wheel.compliance.bytes()) as f64 / 1e9);
    }
    Positions {
        cpu,
        new_nodes,
        split,
        window_gb,
    }
}
