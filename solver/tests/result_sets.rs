//! `solver ltca` and `solver dynamic` write `<out>/<scene>/ltca` resp.
//! `<out>/<scene>/multibody` as one set ([`formats::result_set`]), tried
//! on the checked-in stiffness fixture of `examples/02_ltca_fixture/`
//! (a second of LTCA per run).

use formats::result_set::{lock_path, ResultSet, RunInfo, RUN_FILE};
use geometry::scene::{LoadedScene, Scene};
use std::path::{Path, PathBuf};

/// A scratch folder under the target directory, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(case: &str) -> Scratch {
        let p = Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("result_sets_{case}_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        Scratch(p)
    }

    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

/// The fixture's scene, its text edited by `edit`, written into `dir`
/// (the design path made absolute).
fn scene(dir: &Path, edit: impl Fn(String) -> String) -> LoadedScene {
    let text = std::fs::read_to_string(example().join("scene.toml")).unwrap();
    let design = example()
        .join("../../reference/white_paper_20x43.toml")
        .canonicalize()
        .unwrap();
    let text = text.replace(
        "design = \"../../reference/white_paper_20x43.toml\"",
        &format!("design = {:?}", design.display().to_string()),
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, edit(text)).unwrap();
    Scene::load(&path).unwrap()
}

#[path = "../../formats/tests/support/tree.rs"]
mod tree;
use tree::{files, names};

#[test]
fn ltca_run_is_one_set_with_run_json_and_summaries_naming_the_final_paths() {
    let tmp = Scratch::new("one_set");
    let sc = scene(tmp.path(), |t| t);
    let out = tmp.path().join("out");
    let res = solver::stage::ltca::run(&sc, &example().join("meshes"), &out).unwrap();
    let set = out.join("ltca_fixture/ltca");
    assert_eq!(res[0].dir, set.join("standard_standard"));
    assert!(res[0].dir.join("te.csv").is_file());
    let info: RunInfo =
        serde_json::from_str(&std::fs::read_to_string(set.join(RUN_FILE)).unwrap()).unwrap();
    assert!(info.what.starts_with("solver ltca"), "{info:?}");
    // The set names the files it rests on, as the manifest lists them.
    let keys: Vec<&str> = info.inputs.keys().map(String::as_str).collect();
    assert!(keys.contains(&"design"), "{keys:?}");
    for m in ["pinion", "wheel"] {
        assert!(
            keys.iter().any(|k| k.starts_with(&format!("mesh:{m}_"))),
            "{keys:?}"
        );
        assert!(
            keys.iter()
                .any(|k| k.starts_with(&format!("stiffness:{m}_"))),
            "{keys:?}"
        );
    }
    assert_eq!(names(&out.join("ltca_fixture")), ["ltca"]);
}

#[test]
fn ltca_run_failing_on_its_second_blank_leaves_the_previous_set_untouched_and_no_staging_dir() {
    let tmp = Scratch::new("second_blank");
    let meshes = example().join("meshes");
    let out = tmp.path().join("out");
    solver::stage::ltca::run(&scene(tmp.path(), |t| t), &meshes, &out).unwrap();
    let set = out.join("ltca_fixture/ltca");
    let before = files(&set);

    // A second pinion blank whose stiffness file the fixture lacks: the
    // first blank combination runs (and is written to staging), the second
    // fails.
    let two = scene(tmp.path(), |t| {
        t.replace(
            "pinion = [\"standard\"]",
            "pinion = [\"standard\", \"lightweight\"]",
        )
    });
    let err = solver::stage::ltca::run(&two, &meshes, &out).unwrap_err();
    let msg = format!("{err:#}");
    assert!(msg.contains("lightweight"), "not the second blank: {msg}");
    assert_eq!(files(&set), before, "the previous set changed");
    assert_eq!(names(&out.join("ltca_fixture")), ["ltca"]);
}

#[test]
fn ltca_into_an_output_another_run_is_writing_is_refused_naming_it() {
    let tmp = Scratch::new("busy");
    let out = tmp.path().join("out");
    let set = out.join("ltca_fixture/ltca");
    let other = ResultSet::begin(&set, "solver ltca other.toml").unwrap();
    let err = solver::stage::ltca::run(&scene(tmp.path(), |t| t), &example().join("meshes"), &out)
        .unwrap_err();
    let msg = format!("{err:#}");
    for part in [
        format!("pid {}", std::process::id()),
        "solver ltca other.toml".into(),
        lock_path(&set).display().to_string(),
    ] {
        assert!(msg.contains(&part), "{part:?} not in: {msg}");
    }
    assert!(other.path().read_dir().unwrap().next().is_none());
}

#[test]
fn ltca_and_dynamic_into_an_unwritable_output_are_refused_before_work() {
    let tmp = Scratch::new("unwritable");
    // `--out` is a file: nothing can be written under it.
    let out = tmp.path().join("out");
    std::fs::write(&out, "").unwrap();
    // No meshes at all: a refusal after any work would name them instead.
    let meshes = tmp.path().join("no-meshes");
    let sc = scene(tmp.path(), |t| {
        t.replace("multibody = false", "multibody = true")
    });
    let err = solver::stage::ltca::run(&sc, &meshes, &out).unwrap_err();
    let msg = format!("{err:#}");
    assert!(
        msg.contains(&out.join("ltca_fixture").display().to_string()),
        "{msg}"
    );
    let err = solver::stage::dynamic::run(&sc, &meshes, &out).unwrap_err();
    let msg = format!("{err:#}");
    assert!(
        msg.contains(&out.join("ltca_fixture").display().to_string()),
        "{msg}"
    );
}

#[test]
fn plan_is_one_set_listing_its_checksum_and_the_scene_and_design_it_came_from() {
    let tmp = Scratch::new("plan");
    let sc = scene(tmp.path(), |t| t);
    let out = tmp.path().join("plan");
    let plans = solver::stage::plan::write_plan_set(&sc, &out).unwrap();
    assert!(!plans.is_empty());
    let info = formats::result_set::verify_files(&out).unwrap().unwrap();
    assert!(info.files.contains_key("plan.json"), "{:?}", info.files);
    assert!(info.inputs.contains_key("scene") && info.inputs.contains_key("design"));
    assert!(!lock_path(&out).exists());
    // A plan edited after the run is detected.
    let p = out.join("plan.json");
    let text = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, text.replacen("\"tooth_pairs\"", "\"tooth_pairs\" ", 1)).unwrap();
    let err = formats::result_set::verify_files(&out).unwrap_err();
    assert!(err.to_string().contains("changed since run"), "{err}");
    // A run on an edited scene replaces the set and records the new scene.
    let edited = scene(tmp.path(), |t| t + "\n# edited\n");
    solver::stage::plan::write_plan_set(&edited, &out).unwrap();
    let again = formats::result_set::verify_files(&out).unwrap().unwrap();
    assert_ne!(again.inputs["scene"], info.inputs["scene"]);
    assert_eq!(again.inputs["design"], info.inputs["design"]);
}

/// `[bearings]` for the fixture: an overhung pinion and a wheel on two
/// bearings behind their mean points, all of stiffness `k` N/m.
fn bearings_table(k: f64) -> String {
    let b = |pos: f64, axial: f64| {
        format!("{{ axial_position_mm = {pos}, radial_stiffness_n_per_m = {k:e}, axial_stiffness_n_per_m = {axial:e} }}")
    };
    format!(
        "\n[bearings]\npinion = [{}, {}]\nwheel = [{}, {}]\n",
        b(90.0, k),
        b(150.0, 0.0),
        b(80.0, k),
        b(180.0, 0.0)
    )
}

#[test]
fn ltca_with_bearings_writes_bearings_csv_and_the_deflected_loads_into_the_set() {
    let tmp = Scratch::new("bearings");
    let meshes = example().join("meshes");
    let out = tmp.path().join("out");
    // Bearings far stiffer than the mesh: the TE is the rigid one.
    let stiff = scene(tmp.path(), |t| t + &bearings_table(1e14));
    let res = solver::stage::ltca::run(&stiff, &meshes, &out).unwrap();
    let b = res[0].bearings.as_ref().expect("bearings summary");
    assert_eq!(b.len(), 2);
    for l in b {
        // About 7 kN on 1e14 N/m moves the apex by 0.1 nm: 1e-3 µrad.
        assert!(
            (l.te_mean_urad - l.rigid_te_mean_urad).abs() < 1e-2,
            "{l:?}"
        );
        assert_eq!(l.pinion_bearing_force_n.len(), 2);
        assert!(l.pinion_bearing_force_n[0] > 0.0);
    }
    let csv = std::fs::read_to_string(res[0].dir.join("bearings.csv")).unwrap();
    assert!(csv.starts_with("pinion_rotation_deg,torque_nm,te_urad"));
    assert_eq!(csv.lines().count(), 1 + 2 * res[0].positions);
    let info = formats::result_set::verify_files(&out.join("ltca_fixture/ltca"))
        .unwrap()
        .unwrap();
    assert!(info.files.contains_key("standard_standard/bearings.csv"));
    // Soft bearings add TE, more at the larger torque.
    let soft = scene(tmp.path(), |t| t + &bearings_table(3e8));
    let res = solver::stage::ltca::run(&soft, &meshes, &out).unwrap();
    let b = res[0].bearings.as_ref().unwrap();
    let added: Vec<f64> = b
        .iter()
        .map(|l| l.te_mean_urad - l.rigid_te_mean_urad)
        .collect();
    assert!(added[0] > 1.0 && added[1] > added[0], "{added:?}");
}

#[test]
fn dynamic_with_bearings_writes_the_compliant_runs_into_the_set() {
    let tmp = Scratch::new("dynamic_bearings");
    let meshes = example().join("meshes");
    let out = tmp.path().join("out");
    let sc = scene(tmp.path(), |t| {
        t.replace("multibody = false", "multibody = true")
            + &bearings_table(1e9)
            + "\n[multibody]\ntable_step_deg = 1.0\ntable_lag_nodes = 24\nrunup_time_s = 0.01\nrunup_rpm = [0.0, 300.0]\n"
    });
    let res = solver::stage::dynamic::run(&sc, &meshes, &out).unwrap();
    let c = res[0].compliant.as_ref().expect("compliant-bearing runs");
    let cases: Vec<&str> = c.runs.iter().map(|r| r.case.as_str()).collect();
    assert_eq!(cases, ["10 rpm", "10 rpm", "run-up"]);
    // The bearings add TE at 10 rpm, more at the larger torque, and every
    // bearing carries load.
    let rigid: Vec<f64> = res[0].quasi_static.iter().map(|q| q.te_mean_urad).collect();
    let added: Vec<f64> = c.runs[..2]
        .iter()
        .zip(&rigid)
        .map(|(r, t)| r.te_mean_urad - t)
        .collect();
    assert!(added[0] > 1.0 && added[1] > added[0], "{added:?}");
    assert!(c
        .runs
        .iter()
        .all(|r| r.pinion_bearing_force_n.iter().all(|&f| f > 0.0)));
    let info = formats::result_set::verify_files(&out.join("ltca_fixture/multibody"))
        .unwrap()
        .unwrap();
    for f in [
        "bearings_quasi_static_300nm.csv",
        "bearings_runup.csv",
        "bearings_runup_spectrogram.svg",
        "bearings_runup_orders.json",
    ] {
        assert!(
            info.files.contains_key(&format!("standard_standard/{f}")),
            "{f}"
        );
    }
    // The compliant run-up's order analysis covers the rigid run-up's
    // windows (the same imposed pinion speed); the summary records the
    // bearings and mass properties used.
    let orders = |f: &str| -> formats::summaries::RunupOrders {
        serde_json::from_str(&std::fs::read_to_string(res[0].dir.join(f)).unwrap()).unwrap()
    };
    let (rigid, compliant) = (
        orders("runup_orders.json"),
        orders("bearings_runup_orders.json"),
    );
    assert_eq!(rigid.windows.len(), compliant.windows.len());
    assert_eq!(rigid.samples_per_window, compliant.samples_per_window);
    let used = c.used.as_ref().expect("bearings and masses used");
    assert_eq!(
        (used.pinion_bearings.len(), used.wheel_bearings.len()),
        (2, 2)
    );
    assert_eq!(used.bodies[0].mass_kg, c.masses_kg[0]);
    let csv = std::fs::read_to_string(res[0].dir.join("bearings_runup.csv")).unwrap();
    assert!(csv.starts_with(
        "time_s,pinion_rotation_deg,pinion_rpm,te_urad,e_um,p_um,g_um,shaft_angle_urad"
    ));
    assert_eq!(csv.lines().count(), 2 + c.runs[2].steps);
}
