//! The report's loaded-contact figures from minimal stage outputs: both
//! methods' series end up in the SVG, and a missing input leaves the figure
//! out instead of failing.

use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("gear_figures_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(path: PathBuf, text: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, text).unwrap();
}

#[test]
fn te_and_pattern_figures_from_stage_outputs() {
    let out = scratch("out");
    let reports = scratch("reports");
    let run = out.join("demo");
    write(
        run.join("reference/standard_standard/te.csv"),
        "pinion_rotation_deg,utca_te_urad,te_unloaded_urad,unloaded_xi,unloaded_eta,te_300nm_urad\n0,1,1,0.5,0.5,350\n3,1,1,0.5,0.5,360\n6,1,1,0.5,0.5,352\n",
    );
    write(
        run.join("multibody/standard_standard/quasi_static_300nm.csv"),
        "time_s,pinion_rotation_deg,te_urad\n0,0,351\n0.1,2,355\n0.2,4,361\n0.3,6,353\n",
    );
    write(
        run.join("reference/standard_standard/pattern_300nm.csv"),
        "x_m,y_m,z_m,xi,eta,pressure_mpa\n0,0,0,0.4,0.5,900\n0,0,0,0.5,0.5,1200\n",
    );
    write(
        run.join("ltca/standard_standard/slices.csv"),
        "torque_nm,pinion_rotation_deg,pair,xi,eta,force_n,line_load_n_per_mm,pressure_mpa,half_width_mm\n300,0,1,0.45,0.5,10,1,1000,0.1\n100,0,1,0.45,0.5,10,1,700,0.1\n",
    );
    let te = validate::report::sections::loaded_contact::te_figures(
        &out,
        "demo",
        &reports,
        &[300.0, 500.0],
    );
    assert_eq!(te.len(), 1, "one figure: 500 N·m has no data");
    let svg = &te[0].svg;
    assert!(svg.contains("multibody 10 rpm") && svg.contains("reference FE contact"));
    assert!(reports
        .join("te_loaded_standard_standard_300nm.svg")
        .exists());
    let pat = validate::report::sections::loaded_contact::pattern_figure(
        &out,
        "demo",
        "standard_standard",
        300.0,
        &reports,
    )
    .expect("pattern figure");
    assert!(
        pat.title.contains("1200 MPa"),
        "colour scale up to the largest pressure: {}",
        pat.title
    );
    assert!(validate::report::sections::loaded_contact::pattern_figure(
        &out,
        "demo",
        "standard_lightweight",
        300.0,
        &reports
    )
    .is_none());
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_dir_all(&reports);
}
