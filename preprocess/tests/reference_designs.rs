//! The design files in `reference/`: every one loads and passes the loader's
//! checks (the seed pairs' published values: `seed_published_data.rs`; their
//! flanks and UTCA: `reference_flanks.rs`).
//!
//! Run with `cargo test --release -p preprocess --test reference_designs -- --nocapture`
//! to see the derived numbers.

use geometry::design::{Member, PairData};
use geometry::design_file::{load_pair, min_cutter_radius};
use std::path::{Path, PathBuf};

const REFERENCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../reference");

/// `reference/*.toml` files with a `[pair]` table (design files; scene and
/// published-table files have none), sorted by name.
fn design_files() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(REFERENCE)
        .expect("reference/ is readable")
        .map(|e| e.expect("directory entry").path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == "toml"))
        .filter(|p| {
            let text = std::fs::read_to_string(p).expect("readable file");
            let table: toml::Table = text
                .parse()
                .unwrap_or_else(|e| panic!("{}: not TOML: {e}", p.display()));
            table.get("pair").is_some_and(|v| v.is_table())
        })
        .collect();
    files.sort();
    files
}

#[test]
fn every_reference_design_file_loads_and_passes_its_checks() {
    let files = design_files();
    assert!(
        files.len() >= 5,
        "expected the white-paper pair and the four seed pairs in {REFERENCE}, found {files:?}"
    );
    let mut failures = Vec::new();
    for path in &files {
        match load_pair(path) {
            Ok(p) => println!("{}", describe(path, &p)),
            Err(e) => failures.push(e.to_string()),
        }
        // The tooth checks too: top land and undercut on the generated flanks.
        if let Err(e) = geometry::pair::PairGeometry::from_design_file(path) {
            failures.push(e.to_string());
        }
    }
    assert!(
        failures.is_empty(),
        "design files rejected:\n{}",
        failures.join("\n")
    );
}

/// The pair's data and derived numbers, one block of text.
fn describe(path: &Path, p: &PairData) -> String {
    use std::fmt::Write;
    let (pin, whl) = (p.member(Member::Pinion), p.member(Member::Wheel));
    let mm = 1e3;
    let deg = f64::to_degrees;
    let mut s = String::new();
    writeln!(
        s,
        "{} ({})",
        p.name,
        path.file_name().unwrap().to_string_lossy()
    )
    .unwrap();
    writeln!(
        s,
        "  teeth {}/{}  hands {:?}/{:?}  shaft {:.3} deg  spiral {:.3} deg  pressure {:.2}/{:.2} deg",
        pin.teeth,
        whl.teeth,
        pin.hand,
        whl.hand,
        deg(p.shaft_angle),
        deg(p.spiral_angle),
        deg(p.pressure_angle[0]),
        deg(p.pressure_angle[1])
    )
    .unwrap();
    writeln!(
        s,
        "  m_n {:.4} mm  R_m {:.3} mm  R_e {:.3} mm  R_i {:.3} mm  b {:.3} mm  crown teeth {:.3}  mesh cycle {:.3} deg",
        p.normal_module * mm,
        p.mean_cone_distance * mm,
        p.outer_cone_distance() * mm,
        p.inner_cone_distance() * mm,
        p.face_width * mm,
        p.crown_teeth(),
        deg(p.mesh_cycle())
    )
    .unwrap();
    for (n, m) in [("pinion", Member::Pinion), ("wheel", Member::Wheel)] {
        let d = p.member(m);
        writeln!(
            s,
            "  {n:6}: pitch/root/face {:.3}/{:.3}/{:.3} deg  h_a {:.3}  h_f {:.3}  W {:.3}  s_n {:.3} mm  E {:.0} GPa  nu {:.3}",
            deg(d.pitch_angle),
            deg(d.root_angle),
            deg(d.face_angle),
            d.mean_addendum * mm,
            d.mean_dedendum * mm,
            d.point_width * mm,
            p.normal_thickness(m) * mm,
            d.youngs_modulus * 1e-9,
            d.poisson_ratio
        )
        .unwrap();
    }
    write!(
        s,
        "  backlash {:.3} mm  cutter radius {:.2} mm (minimum {:.2} mm)  edge radius {:.2} mm",
        p.normal_backlash() * mm,
        p.cutter_radius * mm,
        min_cutter_radius(p) * mm,
        p.edge_radius * mm
    )
    .unwrap();
    s
}
