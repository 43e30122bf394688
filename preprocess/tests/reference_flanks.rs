//! `preprocess flanks` on the design files in `reference/`: every flank
//! grid node is a generated point, every fillet section joins its flank
//! column, and the UTCA has a finite transmission error.
//!
//! Run with `cargo test --release -p preprocess --test reference_flanks -- --nocapture`
//! to see the largest deviations per flank.

use geometry::design::Member;
use geometry::flank::Flank;
use geometry::generation::{rot_z, Side};
use geometry::pair::PairGeometry;
use nalgebra::Vector3;
use preprocess::flank_stage::{load_input, run_stage, FlankSummary};
use serde_json::Value;
use std::path::Path;

const REFERENCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../reference");

/// Runs `preprocess flanks` on a design file and checks what it wrote: every
/// flank grid node is a generated point (on its blade cone, in meshing with
/// it at the stored roll angle, at its stored (L, d)), every fillet section
/// joins its flank column, and the UTCA has a finite transmission error.
fn flanks_and_utca_of(file: &str) {
    let path = Path::new(REFERENCE).join(file);
    let input = load_input(&path).unwrap_or_else(|e| panic!("{file}: {e}"));
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("flanks");
    let summary = run_stage(&input, &out).unwrap_or_else(|e| panic!("{file}: flanks: {e}"));
    let g = PairGeometry::from_design_file(&path).unwrap();
    let grids = read(&out, "flanks.json");
    let grids = grids.as_array().unwrap();
    assert_eq!(grids.len(), 4, "{file}: four flank grids");
    for grid in grids {
        check_flank_grid(file, &g, grid);
    }
    check_utca(file, &out, &summary);
}

/// The JSON file `name` the stage wrote to `out`.
fn read(out: &Path, name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(out.join(name)).unwrap()).unwrap()
}

/// A 3-vector of a JSON array.
fn v3(v: &Value) -> Vector3<f64> {
    Vector3::from_fn(|i, _| v[i].as_f64().unwrap())
}

/// One flank grid of `flanks.json`: its nodes generated points, its fillet
/// sections joined to its columns; prints the largest deviations.
fn check_flank_grid(file: &str, g: &PairGeometry, grid: &Value) {
    let k1 = g.frames[0].roll_ratio;
    let mut worst = [0.0f64; 5];
    let m = match grid["member"].as_str().unwrap() {
        "pinion" => Member::Pinion,
        _ => Member::Wheel,
    };
    let side = match grid["side"].as_str().unwrap() {
        "drive" => Side::Drive,
        _ => Side::Coast,
    };
    let f = g.flank(m, side);
    let (n_face, n_profile) = (
        grid["n_face"].as_u64().unwrap() as usize,
        grid["n_profile"].as_u64().unwrap() as usize,
    );
    let rows = grid["fillet_rows"].as_u64().unwrap() as usize;
    let what = format!("{file}: {} {} flank", m.name(), side.flank_name(m));
    assert_eq!(
        grid["position_m"].as_array().unwrap().len(),
        n_face * n_profile
    );
    for i in 0..n_face {
        for k in 0..n_profile {
            node_deviations(f, grid, i * n_profile + k, k1, &mut worst);
        }
        fillet_junction(&what, f, grid, i, n_profile, rows, &mut worst);
    }
    println!(
        "{what}: |(L, d) - grid| {:.1e} m, |n·(e_x × r)| {:.1e} m, off the blade cone {:.1e} m, normal {:.1e}, junction height vs lower limit {:.2e} m",
        worst[0], worst[1], worst[2], worst[3], worst[4]
    );
    assert!(
        worst[0] < 1e-12,
        "{what}: grid node off its (L, d) by {} m",
        worst[0]
    );
    assert!(
        worst[1] < 1e-12,
        "{what}: equation of meshing violated by {} m",
        worst[1]
    );
    assert!(
        worst[2] < 1e-12,
        "{what}: grid node off the blade cone by {} m",
        worst[2]
    );
    assert!(
        worst[3] < 1e-12,
        "{what}: normal off the cone's by {}",
        worst[3]
    );
    // The lower limit is a parabola through the junction at toe, mean and heel.
    assert!(
        worst[4] < 5e-6,
        "{what}: junction {} m off the lower limit",
        worst[4]
    );
}

/// Grid node `at` against its generation, into `worst[0..4]`: off its
/// (L, d), off the equation of meshing, off the blade cone, and its normal
/// off the cone's (`k1` the pinion's roll ratio).
fn node_deviations(f: &Flank, grid: &Value, at: usize, k1: f64, worst: &mut [f64; 5]) {
    let gen = &f.gen;
    let cone = &gen.cone;
    let ease = grid["ease_off_um"][at].as_f64().unwrap() * 1e-6;
    let n = v3(&grid["normal"][at]);
    // The conjugate (generated) point under the ease-off.
    let r = v3(&grid["position_m"][at]) + n * ease;
    let (l, d) = gen.frame.axial(&[r[0], r[1], r[2]]);
    let (l0, d0) = (
        grid["cone_distance_mm"][at].as_f64().unwrap() * 1e-3,
        grid["height_mm"][at].as_f64().unwrap() * 1e-3,
    );
    worst[0] = worst[0].max((l - l0).abs().max((d - d0).abs()));
    // Placed at its contact roll angle: the equation of meshing
    // n · (e_x × r) = 0 in the fixed frame (the pitch line is x).
    let crown = grid["pinion_roll_deg"][at].as_f64().unwrap().to_radians() / k1;
    let phi = crown * gen.frame.roll_ratio;
    let rf = gen.frame.to_fixed(&r, phi);
    let nf = gen.frame.to_fixed(&n, phi);
    worst[1] = worst[1].max((nf.dot(&Vector3::x().cross(&rf))).abs());
    // Back in the generating crown gear at phase 0: on the blade cone,
    // with the cone's normal.
    let back = rot_z(-gen.phase) * rot_z(-crown);
    let p0 = back * rf;
    let n0 = back * nf * gen.outward;
    let (dx, dy) = (p0[0] - cone.center[0], p0[1] - cone.center[1]);
    let rho = dx.hypot(dy);
    let rho_cone = cone.radius + cone.slope * p0[2] * cone.tan_alpha;
    worst[2] = worst[2].max((rho - rho_cone).abs());
    let cone_normal = Vector3::new(
        dx / rho * cone.cos_alpha,
        dy / rho * cone.cos_alpha,
        -cone.slope * cone.sin_alpha,
    );
    worst[3] = worst[3].max((n0 - cone_normal).norm());
}

/// Column `i`'s fillet section against the flank: the junction row (ψ = 0)
/// is the column's lowest flank point (same cone distance, height on the
/// fitted lower limit into `worst[4]`, same normal), at the exact junction.
fn fillet_junction(
    what: &str,
    f: &Flank,
    grid: &Value,
    i: usize,
    n_profile: usize,
    rows: usize,
    worst: &mut [f64; 5],
) {
    let gen = &f.gen;
    // The fillet section's junction row (ψ = 0) is the column's lowest flank
    // point: same cone distance, height on the fitted lower limit, same normal.
    let j = i * rows + rows - 1;
    let q = v3(&grid["fillet_position_m"][j]);
    let (lq, dq) = gen.frame.axial(&[q[0], q[1], q[2]]);
    let at = i * n_profile;
    let l0 = grid["cone_distance_mm"][at].as_f64().unwrap() * 1e-3;
    let d0 = grid["height_mm"][at].as_f64().unwrap() * 1e-3;
    assert!(
        (lq - l0).abs() < 1e-9,
        "{what}: column {i}: fillet junction at L = {lq} m, column at {l0} m"
    );
    worst[4] = worst[4].max((dq - d0).abs());
    // Tangent continuity: the flank's normal at the junction is the fillet's.
    let flank_there = f.at(lq, dq).unwrap();
    let dn = (v3(&grid["fillet_normal"][j]) - Vector3::from(flank_there.normal)).norm();
    assert!(
        dn < 1e-6,
        "{what}: column {i}: fillet and flank normals differ by {dn}"
    );
    // The exact junction (blade at the tangency height) at the column's L,
    // within the rounding of the fillet's difference normal (~1e-11 m).
    let s = f.fillet_arc_at(l0).unwrap();
    let lj = gen.frame.axial(&gen.junction(s).pos).0;
    assert!(
        (lj - l0).abs() < 1e-10,
        "{what}: column {i}: exact junction at L = {lj} m, column at {l0} m"
    );
}

/// `utca.json`: a finite, non-negative TE at every position, its
/// peak-to-peak and the contact ratio as the summary gives them.
fn check_utca(file: &str, out: &Path, summary: &FlankSummary) {
    let u = read(out, "utca.json");
    let te: Vec<f64> = u["te_urad"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap_or(f64::NAN))
        .collect();
    assert_eq!(te.len(), summary.utca.positions, "{file}: TE samples");
    assert!(
        te.iter().all(|t| t.is_finite() && *t >= 0.0 && *t < 1e3),
        "{file}: unloaded TE not finite and in [0, 1000) urad: {te:?}"
    );
    let ptp =
        te.iter().cloned().fold(f64::MIN, f64::max) - te.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        (ptp - summary.utca.te_ptp_urad).abs() < 1e-9 && ptp > 1.0,
        "{file}: TE peak-to-peak {ptp} urad, summary {}",
        summary.utca.te_ptp_urad
    );
    let cr = summary.utca.contact_ratio;
    assert!(cr > 1.0 && cr < 4.0, "{file}: contact ratio {cr}");
    println!(
        "{file}: TE {:.2} urad peak-to-peak, contact ratio {cr:.3}",
        summary.utca.te_ptp_urad
    );
}

#[test]
fn seed001_generates_flanks_and_utca() {
    flanks_and_utca_of("seed001_9x40.toml");
}

#[test]
fn seed002_generates_flanks_and_utca() {
    flanks_and_utca_of("seed002_9x37.toml");
}

#[test]
fn seed003_generates_flanks_and_utca() {
    flanks_and_utca_of("seed003_16x27.toml");
}

#[test]
fn seed004_generates_flanks_and_utca() {
    flanks_and_utca_of("seed004_23x86.toml");
}

#[test]
fn white_paper_generates_flanks_and_utca() {
    flanks_and_utca_of("white_paper_20x43.toml");
}
