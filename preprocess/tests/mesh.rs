//! Gear body meshes with gmsh: volumes, flank fidelity, element counts,
//! holes, failures, determinism. The pinion of the small scene is meshed once
//! and shared by the tests of this binary; the finer levels are in
//! `mesh_levels.rs` (`make test-long`).

#[path = "../../geometry/tests/common/mod.rs"]
mod common;
#[path = "support/flank_fidelity.rs"]
mod flank_fidelity;

use fem::tet10::volume as tet10_volume;
use geometry::design::Member;
use geometry::gear_body::{BlankDimensions, BlankDimensionsMm};
use geometry::generation::Side;
use geometry::pair::{teeth_in_contact, PairGeometry};
use geometry::scene::{Blank, FlankElements};
use geometry::teeth::periodic_teeth;
use preprocess::mesh::{mesh_member, MeshReport, MeshRequest};
use std::path::PathBuf;
use std::sync::OnceLock;

const LEVEL: FlankElements = FlankElements {
    profile: 6,
    face: 10,
};

fn geometry() -> &'static PairGeometry {
    static G: OnceLock<PairGeometry> = OnceLock::new();
    G.get_or_init(|| common::geometry(&common::white_paper()))
}

fn request(member: Member, blank: Blank, dims: &BlankDimensions) -> MeshRequest<'_> {
    let g = geometry();
    let (pt, wt) = teeth_in_contact(g, Side::Drive, 1.0, 1f64.to_radians());
    MeshRequest {
        scene: "test",
        geom: g,
        member,
        blank,
        dims,
        level: LEVEL,
        level_name: "reduced",
        side: Side::Drive,
        periodic_teeth: periodic_teeth(
            blank,
            if member == Member::Pinion { &pt } else { &wt },
            &[],
        ),
        refined_teeth: if member == Member::Pinion { pt } else { wt },
        opposite_refined_teeth: Vec::new(),
    }
}

fn dims() -> &'static BlankDimensions {
    static D: OnceLock<BlankDimensions> = OnceLock::new();
    D.get_or_init(|| BlankDimensions::resolve(&BlankDimensionsMm::default(), &geometry().data))
}

/// The pinion mesh of this test binary: (report, .msh path).
fn pinion() -> &'static (MeshReport, PathBuf) {
    static M: OnceLock<(MeshReport, PathBuf)> = OnceLock::new();
    M.get_or_init(|| {
        let dir = std::env::temp_dir().join(format!("bevel-mesh-test-{}", std::process::id()));
        let path = dir.join("pinion.msh");
        let r = mesh_member(&request(Member::Pinion, Blank::Standard, dims()), &path)
            .expect("pinion mesh");
        (r, path)
    })
}

#[test]
fn tet10_volume_of_a_straight_tetrahedron_is_a_sixth_of_the_box() {
    let v = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 3.0, 0.0],
        [0.0, 0.0, 4.0],
    ];
    let mid = |a: usize, b: usize| std::array::from_fn(|k| 0.5 * (v[a][k] + v[b][k]));
    let x = [
        v[0],
        v[1],
        v[2],
        v[3],
        mid(0, 1),
        mid(1, 2),
        mid(2, 0),
        mid(3, 0),
        mid(3, 2),
        mid(3, 1),
    ];
    assert!((tet10_volume(&x) - 4.0).abs() < 1e-12);
}

#[test]
fn blank_volume_from_cad_equals_the_analytic_body_of_revolution() {
    let (r, _) = pinion();
    let rel =
        (r.blank_volume_occ_m3 - r.blank_volume_analytic_m3).abs() / r.blank_volume_analytic_m3;
    assert!(
        rel < 1e-6,
        "blank volume: CAD {} vs Pappus {} (rel {rel:e})",
        r.blank_volume_occ_m3,
        r.blank_volume_analytic_m3
    );
}

#[test]
fn meshed_volume_equals_the_cad_volume_within_a_tenth_of_a_percent() {
    let (r, _) = pinion();
    let rel = (r.mesh_volume_m3 - r.occ_volume_m3).abs() / r.occ_volume_m3;
    assert!(
        rel < 1e-3,
        "mesh {} vs CAD {} (rel {rel:e})",
        r.mesh_volume_m3,
        r.occ_volume_m3
    );
    // The teeth took material away: the gear is lighter than its blank.
    assert!(r.occ_volume_m3 < 0.95 * r.blank_volume_occ_m3);
    assert!(
        r.quality_min_sicn > 0.0,
        "inverted elements: min SICN {}",
        r.quality_min_sicn
    );
}

#[test]
fn refined_flanks_have_the_requested_element_counts() {
    let (r, _) = pinion();
    let (pt, _) = teeth_in_contact(geometry(), Side::Drive, 1.0, 1f64.to_radians());
    assert_eq!(r.refined_flanks.len(), pt.len(), "{:?}", r.refined_flanks);
    for f in &r.refined_flanks {
        let ok = |n: usize, want: u32| (n as f64 - want as f64).abs() <= 0.15 * want as f64;
        assert!(
            ok(f.elements_profile, LEVEL.profile) && ok(f.elements_face, LEVEL.face),
            "{f:?}"
        );
    }
    // Every tooth has both flanks as physical groups, plus the bore and the body.
    let names: Vec<&str> = r.physical_groups.iter().map(|g| g.2.as_str()).collect();
    assert!(
        names.contains(&"body") && names.contains(&"bore"),
        "{names:?}"
    );
    for t in 0..20 {
        for f in ["concave", "convex"] {
            assert!(
                names.contains(&format!("tooth{t}_{f}").as_str()),
                "tooth{t}_{f} missing: {names:?}"
            );
        }
    }
}

fn s_name(s: &gmsh::Session, dim: i32, tag: i32) -> String {
    s.get_physical_name(dim, tag).unwrap()
}

#[test]
fn lightweight_wheel_has_three_holes_120_degrees_apart_and_standard_none() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("w.msh");
    let r = mesh_member(&request(Member::Wheel, Blank::Lightweight, dims()), &path).unwrap();
    // The nodes of the "holes" group, clustered by angle about the axis (the
    // blank's seam may split a hole's face), and a least-squares circle
    // through each cluster: x² + y² = 2 a x + 2 b y + c, centre (a, b).
    let s = gmsh::Session::new().unwrap();
    s.open(&path).unwrap();
    let mut pts = Vec::new();
    for (dim, tag) in s.get_physical_groups(2).unwrap() {
        if s_name(&s, dim, tag) == "holes" {
            for e in s.get_entities_for_physical_group(dim, tag).unwrap() {
                let (_, xyz, _) = s.mesh_get_nodes(2, e, true, false).unwrap();
                pts.extend(
                    xyz.chunks(3)
                        .map(|p| (p[1].atan2(p[0]).to_degrees(), p[0], p[1])),
                );
            }
        }
    }
    drop(s);
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let n = pts.len();
    assert!(n > 30, "{n} hole nodes");
    // Start after the largest angular gap, split at gaps over 10°.
    let gap = |i: usize| (pts[(i + 1) % n].0 - pts[i].0).rem_euclid(360.0);
    let start = (0..n).max_by(|&i, &j| gap(i).total_cmp(&gap(j))).unwrap() + 1;
    let mut clusters: Vec<Vec<(f64, f64, f64)>> = vec![Vec::new()];
    for k in 0..n {
        let i = (start + k) % n;
        clusters.last_mut().unwrap().push(pts[i]);
        if k + 1 < n && gap(i) > 10.0 {
            clusters.push(Vec::new());
        }
    }
    assert_eq!(clusters.len(), 3, "hole node clusters");
    let mut centres = Vec::new();
    for c in &clusters {
        let mut ata = nalgebra::Matrix3::<f64>::zeros();
        let mut atb = nalgebra::Vector3::<f64>::zeros();
        for &(_, x, y) in c {
            let row = nalgebra::Vector3::new(2.0 * x, 2.0 * y, 1.0);
            ata += row * row.transpose();
            atb += row * (x * x + y * y);
        }
        let sol = ata.lu().solve(&atb).unwrap();
        let radius = (sol[2] + sol[0] * sol[0] + sol[1] * sol[1]).sqrt();
        assert!(
            (2.0 * radius - dims().wheel_hole_diameter).abs() < 1e-4,
            "hole diameter {:.3} mm",
            2e3 * radius
        );
        centres.push(sol[1].atan2(sol[0]).to_degrees().rem_euclid(360.0));
    }
    centres.sort_by(f64::total_cmp);
    for k in 0..3 {
        let d = (centres[(k + 1) % 3] - centres[k]).rem_euclid(360.0);
        assert!((d - 120.0).abs() < 0.01, "hole centres {centres:?}");
    }
    assert!(r.mesh_volume_m3 > 0.0 && r.quality_min_sicn > 0.0);
    let (p, _) = pinion();
    assert!(p.hole_angles_deg.is_empty());
}

#[test]
fn meshing_failure_names_scene_member_and_gmsh_message_and_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    // gmsh refuses a model name with a NUL byte: the error must say where it happened.
    let mut req = request(Member::Pinion, Blank::Standard, dims());
    req.scene = "bad\0scene";
    let out = dir.path().join("bad.msh");
    let err = mesh_member(&req, &out).unwrap_err().to_string();
    assert!(
        err.contains("scene bad") && err.contains("pinion") && err.contains("gmsh"),
        "{err}"
    );
    assert!(
        std::fs::read_dir(dir.path()).unwrap().next().is_none(),
        "files left behind"
    );
}

#[test]
fn blank_dimensions_that_do_not_fit_are_rejected_before_meshing() {
    let mut d = dims().clone();
    d.pinion_bore_radius = 0.2;
    let err = mesh_member(
        &request(Member::Pinion, Blank::Standard, &d),
        &std::env::temp_dir().join("never.msh"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("pinion_bore_radius_mm") && err.contains("200"),
        "{err}"
    );
}

#[test]
fn two_runs_give_identical_meshes() {
    let (_, first) = pinion();
    let dir = tempfile::tempdir().unwrap();
    let second = dir.path().join("again.msh");
    mesh_member(&request(Member::Pinion, Blank::Standard, dims()), &second).unwrap();
    let a = std::fs::read(first).unwrap();
    let b = std::fs::read(&second).unwrap();
    assert!(a == b, "meshes differ ({} vs {} bytes)", a.len(), b.len());
}

/// Points `p` turned by `a` about the z axis; for each, the distance to the
/// nearest of `q` (brute force: a few thousand points).
fn nearest_after_turn(p: &[[f64; 3]], a: f64, q: &[[f64; 3]]) -> f64 {
    let (s, c) = a.sin_cos();
    p.iter()
        .map(|x| {
            let y = [c * x[0] - s * x[1], s * x[0] + c * x[1], x[2]];
            q.iter()
                .map(|z| {
                    ((y[0] - z[0]).powi(2) + (y[1] - z[1]).powi(2) + (y[2] - z[2]).powi(2)).sqrt()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// On a standard blank every periodic tooth's sector is the solved tooth's
/// turned by whole pitches: read back from the file, the nodes of both
/// flanks and the centres of the tets touching the loaded flank of each
/// periodic tooth coincide with the solved tooth's turned onto it.
#[test]
fn standard_blank_periodic_teeth_are_meshed_as_turned_copies_of_the_solved_tooth() {
    let (r, path) = pinion();
    let g = geometry();
    let (pt, _) = teeth_in_contact(g, Side::Drive, 1.0, 1f64.to_radians());
    assert_eq!(r.periodic_teeth, periodic_teeth(Blank::Standard, &pt, &[]));
    assert!(r.periodic_teeth.len() >= 3, "{:?}", r.periodic_teeth);
    assert!(r.periodic_faces > 0);
    // A mid-edge node on a face shared with the freely meshed rest of the
    // body may be straightened there (12.7 µm here, see `copy_deviation`).
    assert!(
        r.periodic_copy_deviation_m < 5e-5,
        "{}",
        r.periodic_copy_deviation_m
    );
    flank_fidelity::assert_flank_nodes_on_the_generated_flank(geometry(), r, path);
    let body = preprocess::body_mesh::read(path).unwrap();
    let x = &body.mesh.nodes;
    let z = g.data.member(Member::Pinion).teeth as usize;
    let pitch = 2.0 * std::f64::consts::PI / z as f64;
    let master = r.periodic_teeth[0];
    let points = |tooth: usize| {
        let flank: Vec<[f64; 3]> = ["concave", "convex"]
            .iter()
            .flat_map(|f| body.group_nodes(&format!("tooth{tooth}_{f}")))
            .map(|n| x[n])
            .collect();
        let loaded: std::collections::BTreeSet<usize> = body
            .group_nodes(&format!("tooth{tooth}_concave"))
            .into_iter()
            .collect();
        let centres: Vec<[f64; 3]> = body
            .mesh
            .tets
            .iter()
            .filter(|t| t.iter().any(|n| loaded.contains(n)))
            .map(|t| std::array::from_fn(|c| t[..4].iter().map(|&n| x[n][c]).sum::<f64>() / 4.0))
            .collect();
        (flank, centres)
    };
    let (mf, mc) = points(master);
    for &t in &r.periodic_teeth[1..] {
        let (f, c) = points(t);
        assert_eq!((f.len(), c.len()), (mf.len(), mc.len()), "tooth {t}");
        let k = (t as i64 - master as i64).rem_euclid(z as i64) as f64;
        let a = -k * pitch;
        let df = nearest_after_turn(&f, a, &mf);
        let dc = nearest_after_turn(&c, a, &mc);
        assert!(
            df < 5e-6 && dc < 5e-6,
            "tooth {t}: flank nodes {df:e} m, tet centres {dc:e} m off"
        );
    }
    // Teeth outside the periodic set are meshed freely: no such match.
    if let Some(t) = (0..z).find(|t| !r.periodic_teeth.contains(t)) {
        let (f, _) = points(t);
        let k = (t as i64 - master as i64).rem_euclid(z as i64) as f64;
        assert!(f.len() != mf.len() || nearest_after_turn(&f, -k * pitch, &mf) > 1e-5);
    }
}
