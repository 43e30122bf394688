//! The reduced model's tooth root stress on real meshes: example 03's pair
//! on its coarse 6 × 10 reduced-level meshes (shared with the other tests
//! that mesh it), stiffness files with root-stress coefficients made from
//! them here, then
//! - the LTCA's root stress at the sweep's first position against the
//!   reference FE's on the same meshes at the same position and torques
//!   (the two models share the meshes but not the method: slice forces on
//!   stress influence coefficients against the contact solution's own
//!   displacement field): largest fillet tension of pinion and wheel within
//!   10 %. Measured on these meshes 2026-11-29: −7.2 / −8.0 % (pinion) and
//!   −8.4 / −6.1 % (wheel) at 100 / 300 N·m, against 1.4–4.9 % on the
//!   default scene's 12 × 40 contact grid at its reduced level. Here the
//!   unit loads sit on a 6 × 10 grid; probed by hand with finer grids on
//!   the same meshes, 20 and 40 face columns give −3.2 / −2.4 % (pinion,
//!   100 N·m) and −5.2 / −4.5 % (pinion, 300 N·m), the wheel −6.2 / −6.7 %
//!   and −4.5 / −5.1 %; 12 profile rows change nothing. So the face grid's
//!   interpolation is about half of it, and a rest of 2–7 % on these meshes
//!   is not yet explained. The bound is a regression bound set from the
//!   measurement, not the 5 % target, which the report judges on the
//!   default scene against the fine reference;
//! - the misalignment sensitivity study carrying the root stress: at every
//!   misalignment's middle value (the aligned pair) it equals the LTCA's,
//!   and it grows with the torque at every value;
//! - the multibody runs: the 10 rpm runs' largest root tension over the
//!   sweep (from the contact-element table's tabulated tension) within 2 %
//!   of the LTCA's at the same loads; the run-up reports both its dynamic
//!   and its quasi-static root tension.

#[path = "support/reference_options.rs"]
mod reference_options;
#[path = "support/shared_meshes.rs"]
mod shared_meshes;

use geometry::pair::PairGeometry;
use geometry::scene::Scene;
use solver::stage::context::LoadedPair;
use std::path::Path;

/// Copies the mesh files of `scene` from the shared root into `root`, so
/// that the stiffness files made here stay out of the shared folder.
fn own_meshes(shared: &Path, name: &str, root: &Path) {
    let dir = root.join(name);
    std::fs::create_dir_all(&dir).unwrap();
    for f in std::fs::read_dir(shared.join(name)).unwrap().flatten() {
        let n = f.file_name().to_string_lossy().into_owned();
        if f.path().is_file() && !n.contains("stiffness") {
            std::fs::copy(f.path(), dir.join(&n)).unwrap();
        }
    }
}

#[test]
fn reduced_root_stress_matches_the_reference_on_the_same_meshes_and_follows_misalignment() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/03_reference_position");
    let mut scene = Scene::load(&dir.join("scene.toml")).unwrap();
    // The stiffness stage runs for scenes that ask for the LTCA.
    scene.scene.analyses.ltca = true;
    let shared = shared_meshes::reduced_meshes(&scene);
    let tmp = tempfile::tempdir().unwrap();
    let meshes = tmp.path().join("meshes");
    own_meshes(&shared, &scene.scene.name, &meshes);
    let t0 = std::time::Instant::now();
    preprocess::stiffness_stage::run(&scene, &meshes).unwrap();
    let t_stiffness = t0.elapsed().as_secs_f64();

    // The reference FE at the sweep's first position.
    let out = tmp.path().join("out");
    let reference = validate::reference::reference_stage::run(
        &scene,
        &meshes,
        &out,
        &reference_options::options(10_000, None),
    )
    .unwrap();
    let t_reference = t0.elapsed().as_secs_f64() - t_stiffness;

    // The reduced model at the same position.
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let sc = &scene.scene;
    let pair = LoadedPair::load(
        &scene,
        &g,
        &meshes.join(&sc.name),
        [sc.blanks.pinion[0], sc.blanks.wheel[0]],
    )
    .unwrap();
    let fp = g.side(sc.loaded_flank);
    let rs = geometry::utca::roll_surface(fp, &sc.utca).unwrap();
    let mut first = pair.sweep;
    first.positions = 1;
    let res = solver::ltca::run_with_root_stress(fp, &rs, &pair.pc, &first, &sc.pinion_torque_nm)
        .unwrap();
    let mut misses = Vec::new();
    for (i, r) in reference[0].loads.iter().enumerate() {
        let reduced = formats::root_stress::summarize(
            res.iter()
                .map(|p| (p.rotation.to_degrees(), p.loads[i].root_stress.as_ref())),
        )
        .expect("the stiffness files hold root-stress coefficients");
        let fe = r.root_stress.as_ref().expect("reference root stress");
        for (member, a, b) in [
            ("pinion", reduced.pinion, fe.pinion),
            ("wheel", reduced.wheel, fe.wheel),
        ] {
            let diff = (a.tension_mpa - b.tension_mpa) / b.tension_mpa;
            let line = format!(
                "{} N m, {member}: reduced {:.2} MPa at {:?}, reference {:.2} MPa at {:?}, {:+.2} %",
                r.torque_nm,
                a.tension_mpa,
                a.tension_at,
                b.tension_mpa,
                b.tension_at,
                100.0 * diff
            );
            eprintln!("{line}");
            if diff.abs() >= 0.10 {
                misses.push(line);
            }
        }
    }
    assert!(misses.is_empty(), "beyond 10 %: {misses:#?}");

    // The sensitivity study with root stress.
    let t1 = std::time::Instant::now();
    let study = solver::stage::sensitivity::run(&scene, &meshes, &out).unwrap();
    let t_study = t1.elapsed().as_secs_f64();
    let all =
        solver::ltca::run_with_root_stress(fp, &rs, &pair.pc, &pair.sweep, &sc.pinion_torque_nm)
            .unwrap();
    let sdir = out.join(&sc.name).join("sensitivity");
    for (f, _) in solver::stage::sensitivity::ROOT_STRESS_CHART_FILES {
        assert!(sdir.join(f).is_file(), "{f} missing");
    }
    for curve in &study.curves {
        let mid = &curve.points[curve.points.len() / 2];
        assert!(mid.misalignment.is_zero());
        for (i, l) in mid.loads.iter().enumerate() {
            let aligned = formats::root_stress::summarize(
                all.iter()
                    .map(|p| (p.rotation.to_degrees(), p.loads[i].root_stress.as_ref())),
            )
            .unwrap();
            assert_eq!(l.root_stress, Some(aligned), "{:?}", curve.component);
        }
        for p in &curve.points {
            let r: Vec<_> = p.loads.iter().map(|l| l.root_stress.unwrap()).collect();
            for w in r.windows(2) {
                assert!(
                    w[1].pinion.tension_mpa > w[0].pinion.tension_mpa
                        && w[1].wheel.tension_mpa > w[0].wheel.tension_mpa,
                    "{:?} {}: {w:?}",
                    curve.component,
                    p.value
                );
            }
        }
        let at = |k: usize| {
            let r = curve.points[k].loads.last().unwrap().root_stress.unwrap();
            (r.pinion.tension_mpa, r.pinion.tension_at.xi)
        };
        eprintln!(
            "{}: pinion root tension (MPa, xi) at the ends and middle {:?} {:?} {:?}",
            curve.symbol,
            at(0),
            at(curve.points.len() / 2),
            at(curve.points.len() - 1)
        );
    }

    // The multibody runs: the 10 rpm runs' largest root tension over the
    // sweep against the LTCA's at the same loads (the table interpolates
    // its nodes' largest tension over the loaded teeth in rotation and
    // lag), and the run-up's dynamic and quasi-static root tension.
    let t2 = std::time::Instant::now();
    scene.scene.analyses.multibody = true;
    scene.scene.multibody.root_stress = true;
    let dynamic = solver::stage::dynamic::run(&scene, &meshes, &out).unwrap();
    let t_dynamic = t2.elapsed().as_secs_f64();
    let d = &dynamic[0];
    for (i, q) in d.quasi_static.iter().enumerate() {
        let ltca = formats::root_stress::summarize(
            all.iter()
                .map(|p| (p.rotation.to_degrees(), p.loads[i].root_stress.as_ref())),
        )
        .unwrap();
        let mb = q.root_tension_mpa.expect("multibody root tension");
        for (k, l) in [ltca.pinion.tension_mpa, ltca.wheel.tension_mpa]
            .into_iter()
            .enumerate()
        {
            let diff = mb[k] / l - 1.0;
            eprintln!(
                "10 rpm {} N m, member {k}: multibody {:.2} MPa, LTCA {l:.2} MPa, {:+.2} %",
                q.torque_nm,
                mb[k],
                100.0 * diff
            );
            assert!(diff.abs() < 0.02, "{} N m member {k}: {diff}", q.torque_nm);
        }
    }
    let runup = d.runup.as_ref().unwrap().root_tension_mpa.unwrap();
    eprintln!("run-up root tension {runup:?}");
    for k in 0..2 {
        assert!(
            runup.dynamic[k] > 0.0 && runup.quasi_static[k] > 0.0,
            "{runup:?}"
        );
    }
    eprintln!(
        "stiffness files {t_stiffness:.1} s, reference position {t_reference:.1} s, sensitivity study {t_study:.1} s, multibody {t_dynamic:.1} s"
    );
}
