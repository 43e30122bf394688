//! Stiffness files and FE influence fields: HDF5 round trip (also read by
//! h5py), schema/hash/corruption detection, and on a real pinion mesh:
//! reciprocity within and across teeth, positive definiteness, no load-point
//! spike after the local subtraction, and rotational symmetry of a standard
//! blank.

#[path = "../../geometry/tests/common/mod.rs"]
mod common;

use formats::stiffness_file::{self, StiffnessData, StiffnessFileError};
use geometry::design::Member;
use geometry::gear_body::{BlankDimensions, BlankDimensionsMm};
use geometry::generation::Side;
use geometry::pair::{teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, FlankElements};
use geometry::teeth::periodic_teeth;
use preprocess::body_mesh::{self, BodyMesh};
use preprocess::influence::{
    compute, half_tooth, local_supports, rotate_z, FlankGrid, GridSize, Influence,
    InfluenceRequest, Solves,
};
use preprocess::mesh::{mesh_member, MeshRequest};
use preprocess::root_stress::{FilletGridPoints, RootStressPoints};
use std::sync::OnceLock;

fn synthetic() -> StiffnessData {
    let (npf, nf, ns, no) = (2, 3, 1, 3);
    let np = npf * nf;
    let seq = |n: usize, s: f64| (0..n).map(|i| s * (i as f64 + 1.0)).collect::<Vec<f64>>();
    StiffnessData {
        input_hash: "abc123".into(),
        config: "{\"k\": 1}".into(),
        member: "pinion".into(),
        blank: "standard".into(),
        level: "reduced".into(),
        teeth: 20,
        axisymmetric: true,
        grid_profile: npf,
        grid_face: nf,
        xi: seq(nf, 0.1),
        eta: seq(npf, 0.2),
        position: seq(3 * np, 1e-3),
        normal: seq(3 * np, 0.01),
        lever: seq(np, 1e-2),
        solved_teeth: vec![3],
        offsets: vec![-1, 0, 1],
        depth_h: seq(ns * np, 1e-4),
        total: seq(ns * no * np * np, 1e-10),
        local: seq(ns * np * np, 1e-11),
        global: seq(ns * no * np * np, 2e-10),
        root_stress: Some(formats::stiffness_file::RootStressBlock {
            offsets: vec![0, 1],
            xi: seq(4, 0.2),
            height: seq(4, 0.1),
            stress: seq(ns * 2 * np * 4 * 6, 1e3),
        }),
    }
}

fn tmp(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("bevel-stiffness-test-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

#[test]
fn stiffness_file_round_trips_and_h5py_reads_it() {
    let p = tmp("roundtrip.h5");
    let d = synthetic();
    stiffness_file::write(&p, &d).unwrap();
    assert!(
        !p.with_extension("tmp.h5").exists(),
        "temporary file left behind"
    );
    let back = stiffness_file::read(&p, Some("abc123")).unwrap();
    assert_eq!(back, d);
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::process::Command::new(root.join(".venv/bin/python"))
        .arg(root.join("scripts/check_stiffness_h5.py"))
        .arg(&p)
        .output()
        .expect("run the project's python");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        v["attrs"]["schema_version"],
        stiffness_file::STIFFNESS_SCHEMA
    );
    assert_eq!(v["attrs"]["input_hash"], "abc123");
    assert_eq!(
        v["shapes"]["compliance/total"],
        serde_json::json!([1, 3, 6, 6])
    );
    assert_eq!(v["units"]["compliance/global"], "m/N");
    assert_eq!(
        v["shapes"]["root_stress/stress"],
        serde_json::json!([1, 2, 6, 4, 6])
    );
    assert_eq!(v["units"]["root_stress/stress"], "Pa/N");
    let sum: f64 = d.total.iter().sum();
    assert!((v["total_sum"].as_f64().unwrap() - sum).abs() < 1e-12 * sum);
}

#[test]
fn stiffness_file_from_other_inputs_or_schema_is_rejected() {
    let p = tmp("other.h5");
    stiffness_file::write(&p, &synthetic()).unwrap();
    match stiffness_file::read(&p, Some("different")) {
        Err(StiffnessFileError::Hash {
            found, expected, ..
        }) => {
            assert_eq!((found.as_str(), expected.as_str()), ("abc123", "different"))
        }
        other => panic!("expected a hash mismatch, got {other:?}"),
    }
    {
        let f = stiffness_file::h5().open_rw(&p).unwrap();
        f.attr("schema_version")
            .unwrap()
            .write_scalar(&99u32)
            .unwrap();
    }
    let e = stiffness_file::read(&p, None).unwrap_err();
    assert!(
        matches!(
            e,
            StiffnessFileError::Schema {
                found: 99,
                expected: stiffness_file::STIFFNESS_SCHEMA,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn truncated_stiffness_file_gives_an_error_naming_the_file() {
    let p = tmp("truncated.h5");
    stiffness_file::write(&p, &synthetic()).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    std::fs::write(&p, &bytes[..bytes.len() / 2]).unwrap();
    let e = stiffness_file::read(&p, None).unwrap_err().to_string();
    assert!(e.contains("truncated.h5"), "{e}");
}

// ---- FE influence fields on a real (coarse) pinion mesh ----

const LEVEL: FlankElements = FlankElements {
    profile: 6,
    face: 10,
};
const GRID: GridSize = GridSize {
    profile: 6,
    face: 10,
};

fn geometry() -> &'static PairGeometry {
    static G: OnceLock<PairGeometry> = OnceLock::new();
    G.get_or_init(|| common::geometry(&common::white_paper()))
}

/// The coarse pinion body, its refined teeth, and influence fields of two
/// neighbouring refined teeth with responses on ±1 teeth, by the pruned
/// solves the stiffness stage uses and by full solves.
fn fields_both() -> &'static (BodyMesh, Vec<usize>, Influence, Influence) {
    static F: OnceLock<(BodyMesh, Vec<usize>, Influence, Influence)> = OnceLock::new();
    F.get_or_init(|| {
        let g = geometry();
        let dims = BlankDimensions::resolve(&BlankDimensionsMm::default(), &g.data);
        let (pt, _) = teeth_in_contact(g, Side::Drive, 1.0, 1f64.to_radians());
        let req = MeshRequest {
            scene: "test",
            geom: g,
            member: Member::Pinion,
            blank: Blank::Standard,
            dims: &dims,
            level: LEVEL,
            level_name: "reduced",
            side: Side::Drive,
            refined_teeth: pt.clone(),
            opposite_refined_teeth: Vec::new(),
            periodic_teeth: periodic_teeth(Blank::Standard, &pt, &[]),
        };
        let path = tmp("pinion.msh");
        mesh_member(&req, &path).expect("pinion mesh");
        let body = body_mesh::read(&path).unwrap();
        let grid = FlankGrid::new(g.flank(Member::Pinion, Side::Drive), GRID).unwrap();
        let (sf, sp) = grid.spacing();
        // Two neighbouring teeth a, a + 1 whose neighbours a − 1 and a + 2
        // are refined too.
        let z = g.data.member(Member::Pinion).teeth as usize;
        let a = (0..z)
            .find(|&a| {
                [z - 1, 0, 1, 2]
                    .iter()
                    .all(|&o| pt.contains(&((a + o) % z)))
            })
            .expect("four neighbouring refined teeth");
        let solved = vec![a, (a + 1) % z];
        let md = g.data.member(Member::Pinion);
        let root = RootStressPoints::new(
            &body,
            g,
            Member::Pinion,
            Side::Drive,
            &root_teeth(a, z),
            preprocess::influence::fe_material(md.material()),
        )
        .unwrap();
        let run = |solves: Solves| {
            compute(
                &InfluenceRequest {
                    body: &body,
                    material: preprocess::influence::fe_material(md.material()),
                    teeth: md.teeth as usize,
                    loaded: "concave",
                    opposite: "convex",
                    grid: &grid,
                    solved_teeth: solved.clone(),
                    offsets: vec![-1, 0, 1],
                    load_radius: 0.75 * sf.max(sp),
                    fillet_rise: preprocess::influence::FILLET_RISE,
                    block: 8,
                    solves,
                    root: Some(&root),
                },
                &["bore"],
            )
            .unwrap()
        };
        let (pruned, full) = (run(Solves::Pruned), run(Solves::Full));
        (body, pt, pruned, full)
    })
}

/// The teeth whose fillets the root stress of loaded teeth a and a + 1
/// reaches (offsets −1..1): a − 1 ..= a + 2.
fn root_teeth(a: usize, z: usize) -> Vec<usize> {
    (0..4).map(|k| (a + z - 1 + k) % z).collect()
}

/// The stiffness stage's fields (pruned solves).
fn fields() -> (&'static BodyMesh, &'static Vec<usize>, &'static Influence) {
    let (b, pt, pruned, _) = fields_both();
    (b, pt, pruned)
}

/// Forward solves along the elimination-tree paths with Gram products give
/// the fields of full forward and backward solves on the same body: every
/// block of the total (loaded tooth and both neighbours) and the global
/// field and the local part within 1e-12 of the block's largest value
/// (rounding only; the order of parallel sums may differ between runs), and the
/// stage's own check (one row against a backward solve) as small. The
/// pruned path solved each responding tooth once: 4 teeth × 60 loads
/// against 2 × 60 full solves.
#[test]
fn pruned_solves_give_the_fields_of_full_solves() {
    let (_, _, pruned, full) = fields_both();
    let np = GRID.profile * GRID.face;
    let worst = |a: &[f64], b: &[f64]| {
        a.chunks(np * np)
            .zip(b.chunks(np * np))
            .map(|(x, y)| {
                let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                x.iter()
                    .zip(y)
                    .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()))
                    / scale
            })
            .fold(0.0f64, f64::max)
    };
    let (t, gl) = (
        worst(&pruned.total, &full.total),
        worst(&pruned.global, &full.global),
    );
    println!(
        "pruned against full solves: total {t:.1e}, global {gl:.1e}; backward check {:?}; {} forward vectors, {} full solves",
        pruned.stats.backward_check, pruned.stats.right_hand_sides, full.stats.right_hand_sides
    );
    let loc = worst(&pruned.local, &full.local);
    assert!(
        t < 1e-12 && gl < 1e-12 && loc < 1e-12,
        "total {t:e}, global {gl:e}, local {loc:e}"
    );
    let check = pruned
        .stats
        .backward_check
        .expect("pruned solves check themselves");
    assert!(check < 1e-12, "backward check {check:e}");
    assert_eq!(full.stats.backward_check, None);
    assert_eq!(
        (pruned.stats.right_hand_sides, full.stats.right_hand_sides),
        (4 * np, 2 * np)
    );
}

/// The root-stress coefficients by the pruned path (the fillet points'
/// support solved backward from the forward vectors) equal the full
/// solves' (the stress of the whole field at the same points) to rounding;
/// both store the loaded tooth and its two neighbours.
#[test]
fn pruned_solves_give_the_root_stress_of_full_solves() {
    let (_, _, pruned, full) = fields_both();
    let (p, f) = (
        pruned.root_stress.as_ref().unwrap(),
        full.root_stress.as_ref().unwrap(),
    );
    assert_eq!(p.offsets, vec![-1, 0, 1]);
    assert_eq!((&p.xi, &p.height), (&f.xi, &f.height));
    let scale = f.stress.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = p
        .stress
        .iter()
        .zip(&f.stress)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    println!(
        "root stress, pruned against full: {:.1e} of the largest {scale:.3e} Pa/N; {:.2} s pruned, {:.2} s full",
        worst / scale,
        pruned.stats.root_stress_s,
        full.stats.root_stress_s
    );
    assert!(
        scale > 0.0 && worst < 1e-10 * scale,
        "{worst:e} of {scale:e}"
    );
}

/// Linearity and the file's layout: the stored coefficients of three grid
/// loads of different size on tooth a, summed, give the stress at every
/// fillet point of teeth a − 1, a, a + 1 that a direct FE solve of the
/// three loads together gives (the same bump weights, bore clamped) within
/// 1e-9 of the largest.
#[test]
fn root_stress_coefficients_superpose_to_a_direct_solve_of_the_combined_load() {
    let (body, _, inf) = fields();
    let g = geometry();
    let md = g.data.member(Member::Pinion);
    let z = md.teeth as usize;
    let material = preprocess::influence::fe_material(md.material());
    let grid = FlankGrid::new(g.flank(Member::Pinion, Side::Drive), GRID).unwrap();
    let (sf, sp) = grid.spacing();
    let k = inf.solved_teeth[0];
    let r = inf.root_stress.as_ref().unwrap();
    let np = grid.len();
    let nf = r.points();
    let loads = [(7usize, 1500.0), (np / 2, 700.0), (np - 9, 2500.0)];
    let faces = body.group(&format!("tooth{k}_concave"));
    let a = 2.0 * std::f64::consts::PI * k as f64 / z as f64;
    let fixed = fem::clamp_nodes(&body.group_nodes("bore"));
    let fe =
        fem::ClampedBody::new(&body.mesh, &material, &fixed, fem::Factorization::Auto).unwrap();
    let mut f = vec![0.0; fe.dofs.n_free()];
    for &(i, c) in &loads {
        let p = rotate_z(grid.position[i], a);
        let n = rotate_z(grid.normal[i], a);
        let w = preprocess::influence::patch_weights(
            &body.mesh,
            faces,
            p,
            n.map(|x| -x),
            0.75 * sf.max(sp),
        )
        .unwrap();
        for (d, v) in w {
            if let Some(q) = fe.dofs.free_index(d) {
                f[q] += c * v;
            }
        }
    }
    let u = fe.dofs.expand(&fe.factor.solve(&f));
    let points = RootStressPoints::new(
        body,
        g,
        Member::Pinion,
        Side::Drive,
        &root_teeth(k, z),
        material,
    )
    .unwrap();
    let (xi, h) = formats::stiffness_file::RootStressBlock::side_points();
    let mut worst = 0.0f64;
    let mut scale = 0.0f64;
    for (ri, &o) in r.offsets.iter().enumerate() {
        let tooth = (k as i64 + o as i64).rem_euclid(z as i64) as usize;
        let gp = FilletGridPoints::new(&body.mesh, &points, tooth, (&xi, &h)).unwrap();
        let direct = gp.eval(&body.mesh, |n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
        for (pt, d) in direct.iter().enumerate() {
            for (c, &dc) in d.iter().enumerate() {
                let sum: f64 = loads
                    .iter()
                    .map(|&(i, w)| w * r.stress[(((ri * np) + i) * nf + pt) * 6 + c])
                    .sum();
                worst = worst.max((sum - dc).abs());
                scale = scale.max(dc.abs());
            }
        }
    }
    println!(
        "superposed coefficients against the direct solve: {:.1e} of {scale:.3e} Pa",
        worst / scale
    );
    assert!(
        scale > 1e6 && worst < 1e-9 * scale,
        "{worst:e} of {scale:e}"
    );
}

/// The stored stress is in each tooth's own frame turned back onto tooth
/// 0, so two neighbouring teeth of the standard blank (the same mesh
/// turned by a pitch) under their own loads store nearly the same
/// coefficients at offset 0; stored in the body frame they would differ by
/// the pitch's turn (18° on this 20-tooth pinion).
#[test]
fn root_stress_of_neighbouring_teeth_is_the_same_in_their_own_frames() {
    let (_, _, inf) = fields();
    let r = inf.root_stress.as_ref().unwrap();
    let o0 = r.offsets.iter().position(|&o| o == 0).unwrap();
    let per_o = (GRID.profile * GRID.face) * r.points() * 6;
    let per_s = r.offsets.len() * per_o;
    let block = |s: usize| &r.stress[s * per_s + o0 * per_o..s * per_s + (o0 + 1) * per_o];
    let (a, b) = (block(0), block(1));
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    println!(
        "tooth a against a + 1, own frames: {:.2e} of the largest",
        worst / scale
    );
    assert!(worst < 0.02 * scale, "{worst:e} of {scale:e}");
}

/// The local half-tooth model is held where its sides join the rest of the
/// body. Under the root row the fillet curves out of the flank's tangent
/// plane; when its elements counted as beside the half tooth (fillet rise
/// 0) the supports lay 1.1–1.4 mm from the root-row points of the default
/// pinion (load radius 2 mm) and its local diagonal there changed by up to
/// 21 % between the reduced and the medium mesh. With the fillet in the
/// half tooth up to `FILLET_RISE` · h the supports are far enough that
/// reaching further hardly matters: on the default pinion the local
/// diagonal's mean moves by 0.04 % from rise 0.3 to 0.5. On this coarse mesh
/// (load radius 4 mm, twice the default's) the root row moves by 7.9 % from
/// rise 0 to 0.3 and by 1.4 % from 0.3 to 0.5.
#[test]
fn local_field_does_not_depend_on_how_far_the_half_tooth_reaches_into_the_fillet() {
    let (body, _, inf) = fields();
    let g = geometry();
    let grid = FlankGrid::new(g.flank(Member::Pinion, Side::Drive), GRID).unwrap();
    let (sf, sp) = grid.spacing();
    let md = g.data.member(Member::Pinion);
    let k = inf.solved_teeth[0];
    let local = |rise: f64| {
        let req = InfluenceRequest {
            body,
            material: preprocess::influence::fe_material(md.material()),
            teeth: md.teeth as usize,
            loaded: "concave",
            opposite: "convex",
            grid: &grid,
            solved_teeth: vec![k],
            offsets: vec![0],
            load_radius: 0.75 * sf.max(sp),
            fillet_rise: rise,
            block: 8,
            solves: Solves::default(),
            root: None,
        };
        let place = half_tooth(&req, k, &inf.depth[0]);
        let supports = local_supports(&body.mesh, &place);
        let a = 2.0 * std::f64::consts::PI * k as f64 / md.teeth as f64;
        let nearest = grid
            .position
            .iter()
            .flat_map(|&p| {
                let p = rotate_z(p, a);
                supports.iter().map(move |&i| {
                    let x = body.mesh.nodes[i];
                    ((x[0] - p[0]).powi(2) + (x[1] - p[1]).powi(2) + (x[2] - p[2]).powi(2)).sqrt()
                })
            })
            .fold(f64::INFINITY, f64::min);
        let f = compute(&req, &["bore"]).unwrap();
        let np = grid.len();
        let diag: Vec<f64> = (0..np).map(|i| f.local[i * np + i]).collect();
        (diag, nearest)
    };
    let ((d0, n0), (d3, n3), (d5, n5)) = (local(0.0), local(0.3), local(0.5));
    let change = |a: &[f64], b: &[f64], rows: &dyn Fn(usize) -> bool| {
        (0..a.len())
            .filter(|&i| rows(i % GRID.profile))
            .map(|i| ((b[i] - a[i]) / b[i]).abs())
            .fold(0.0f64, f64::max)
    };
    let all = |_: usize| true;
    let root = |p: usize| p == 0;
    println!(
        "nearest support to a grid point: {:.2} / {:.2} / {:.2} mm at rise 0 / 0.3 / 0.5; largest change of the local diagonal: root row 0 -> 0.3 {:.2} %, 0.3 -> 0.5 {:.2} % (everywhere {:.2} %)",
        n0 * 1e3,
        n3 * 1e3,
        n5 * 1e3,
        100.0 * change(&d0, &d3, &root),
        100.0 * change(&d3, &d5, &root),
        100.0 * change(&d3, &d5, &all)
    );
    assert!(n3 > n0, "the supports did not move away from the grid");
    assert!(
        change(&d3, &d5, &all) < 0.02,
        "local field still depends on where it is supported: {:.2} %",
        100.0 * change(&d3, &d5, &all)
    );
    assert!(
        change(&d3, &d5, &root) < 0.25 * change(&d0, &d3, &root),
        "reaching further into the fillet changes the root row as much as reaching into it"
    );
}

fn block(inf: &Influence, field: &[f64], s: usize, o: usize) -> Vec<f64> {
    let np = GRID.profile * GRID.face;
    let no = inf.offsets.len();
    field[(s * no + o) * np * np..(s * no + o + 1) * np * np].to_vec()
}

/// On the full solves' fields: the pruned solves' Gram products are
/// symmetric by construction, full forward and backward solves are not.
#[test]
fn influence_fields_are_reciprocal_within_and_across_teeth() {
    let (_, _, _, inf) = fields_both();
    let np = GRID.profile * GRID.face;
    for field in [&inf.total, &inf.global] {
        for s in 0..2 {
            let b = block(inf, field, s, 1);
            for i in 0..np {
                for j in 0..np {
                    let d = (b[i * np + j] - b[j * np + i]).abs();
                    assert!(d <= 1e-6 * b[i * np + i], "C({i},{j}) - C({j},{i}) = {d:e}");
                }
            }
        }
    }
    // Tooth a loaded, tooth a+1 responding equals tooth a+1 loaded, tooth a responding.
    let up = block(inf, &inf.total, 0, 2);
    let down = block(inf, &inf.total, 1, 0);
    let scale = up.iter().copied().fold(0.0f64, f64::max);
    for i in 0..np {
        for j in 0..np {
            let d = (up[i * np + j] - down[j * np + i]).abs();
            assert!(
                d <= 1e-6 * scale,
                "cross-tooth C({i},{j}) differs by {d:e} (scale {scale:e})"
            );
        }
    }
}

#[test]
fn loaded_tooth_compliance_is_positive_definite() {
    let (_, _, inf) = fields();
    let np = GRID.profile * GRID.face;
    for field in [&inf.total, &inf.global] {
        let b = block(inf, field, 0, 1);
        let m = nalgebra::DMatrix::from_row_slice(np, np, &b);
        let sym = (&m + m.transpose()) * 0.5;
        assert!(
            nalgebra::Cholesky::new(sym).is_some(),
            "not positive definite"
        );
    }
}

/// Ratio of the diagonal to the mean of its four grid neighbours' coupling,
/// over interior points: a load-point spike makes it large.
fn spike(b: &[f64]) -> f64 {
    let (npf, nf) = (GRID.profile, GRID.face);
    let np = npf * nf;
    let mut worst: f64 = 0.0;
    for f in 1..nf - 1 {
        for p in 1..npf - 1 {
            let i = f * npf + p;
            let nb = [i - 1, i + 1, i - npf, i + npf];
            let mean = nb.iter().map(|&j| b[i * np + j]).sum::<f64>() / 4.0;
            worst = worst.max(b[i * np + i] / mean);
        }
    }
    worst
}

#[test]
fn local_subtraction_removes_the_load_point_spike() {
    let (_, _, inf) = fields();
    let total = spike(&block(inf, &inf.total, 0, 1));
    let global = spike(&block(inf, &inf.global, 0, 1));
    println!("diagonal / neighbour coupling: total {total:.3}, global {global:.3}");
    assert!(global < 1.25, "global field still spikes: {global:.3}");
    assert!(total > global, "total {total:.3} vs global {global:.3}");
}

/// Two neighbouring teeth of an axisymmetric body carry the same compliance.
/// On a standard blank tooth k's compliance equals tooth 0's
/// within 0.5 %. Both teeth and their neighbours are periodic sectors (the
/// same mesh turned by a pitch), so only the far body's mesh differs. Before
/// the periodic sectors the teeth's own meshes differed and this coarse
/// (6 × 10) mesh gave 1.6 % (total) and 1.7 % (global).
#[test]
fn standard_blank_neighbouring_teeth_have_the_same_compliance() {
    let (_, _, inf) = fields();
    let np = GRID.profile * GRID.face;
    let worst = |f: &[f64]| {
        let a = block(inf, f, 0, 1);
        let b = block(inf, f, 1, 1);
        (0..np)
            .map(|i| (a[i * np + i] - b[i * np + i]).abs() / a[i * np + i])
            .fold(0.0f64, f64::max)
    };
    let (t, g) = (worst(&inf.total), worst(&inf.global));
    println!(
        "largest relative difference of the diagonal between teeth: total {:.3}%, global {:.3}%",
        100.0 * t,
        100.0 * g
    );
    assert!(t < 0.005, "total {:.3}%", 100.0 * t);
    assert!(g < 0.005, "global {:.3}%", 100.0 * g);
}

/// Fourier amplitude of order `m` of samples c_k at the tooth angles
/// θ_k = 2πk/z: (2/z)·|Σ c_k e^{−imθ_k}|.
fn order_amplitude(c: &[f64], m: usize) -> f64 {
    let z = c.len() as f64;
    let (mut re, mut im) = (0.0, 0.0);
    for (k, v) in c.iter().enumerate() {
        let a = 2.0 * std::f64::consts::PI * (m * k) as f64 / z;
        re += v * a.cos();
        im -= v * a.sin();
    }
    2.0 / z * re.hypot(im)
}

/// The three-hole lightweight wheel: a unit load on every tooth's flank
/// (all teeth meshed alike, none refined) meets a compliance that varies
/// around the wheel with order 3; orders 1, 2, 4 and 5 (mesh noise) stay
/// far below it. (A standard blank gives no order 3: its teeth differ only
/// by mesh noise, see the neighbouring-teeth test.)
#[test]
fn lightweight_wheel_compliance_varies_with_order_three_around_the_wheel() {
    let g = geometry();
    let dims = BlankDimensions::resolve(&BlankDimensionsMm::default(), &g.data);
    let req = MeshRequest {
        scene: "test",
        geom: g,
        member: Member::Wheel,
        blank: Blank::Lightweight,
        dims: &dims,
        level: LEVEL,
        level_name: "reduced",
        side: Side::Drive,
        refined_teeth: Vec::new(),
        opposite_refined_teeth: Vec::new(),
        periodic_teeth: Vec::new(),
    };
    let path = tmp("wheel_lightweight.msh");
    mesh_member(&req, &path).expect("wheel mesh");
    let body = body_mesh::read(&path).unwrap();
    let size = GridSize {
        profile: 2,
        face: 3,
    };
    let grid = FlankGrid::new(g.flank(Member::Wheel, Side::Drive), size).unwrap();
    let md = g.data.member(Member::Wheel);
    let z = md.teeth as usize;
    let flank = Side::Drive.flank_name(Member::Wheel);
    let opposite = Side::Coast.flank_name(Member::Wheel);
    let inf = compute(
        &InfluenceRequest {
            body: &body,
            material: preprocess::influence::fe_material(md.material()),
            teeth: z,
            loaded: flank,
            opposite,
            grid: &grid,
            solved_teeth: (0..z).collect(),
            offsets: vec![0],
            // Coarse flank faces (1.5 m_n): spread the load over several.
            load_radius: 1.5 * g.data.normal_module,
            fillet_rise: preprocess::influence::FILLET_RISE,
            block: 16,
            solves: Solves::default(),
            root: None,
        },
        &["bore"],
    )
    .unwrap();
    let np = size.profile * size.face;
    let c: Vec<f64> = (0..z)
        .map(|s| {
            let b = &inf.total[s * np * np..(s + 1) * np * np];
            (0..np).map(|i| b[i * np + i]).sum::<f64>() / np as f64
        })
        .collect();
    let mean = c.iter().sum::<f64>() / z as f64;
    let amp: Vec<f64> = (1..=6).map(|m| order_amplitude(&c, m) / mean).collect();
    println!(
        "mean diagonal compliance {:.4e} m/N; relative amplitude of orders 1..6: {}",
        mean,
        amp.iter()
            .map(|a| format!("{:.2}%", 100.0 * a))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let a3 = amp[2];
    // Measured: order 3 1.9 % of the mean, orders 1, 2, 4, 5 ≤ 0.05 %.
    assert!(a3 > 0.01, "order-3 amplitude only {:.2}%", 100.0 * a3);
    for m in [1usize, 2, 4, 5] {
        assert!(
            amp[m - 1] < a3 / 10.0,
            "order {m} {:.2}% against order 3 {:.2}%",
            100.0 * amp[m - 1],
            100.0 * a3
        );
    }
}
