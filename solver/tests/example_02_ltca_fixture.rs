//! Example 02 (`examples/02_ltca_fixture/`): the loaded TCA of the reduced
//! model from a checked-in stiffness fixture (the mesh folder's
//! `manifest.json` and the two `*.stiffness.h5` files; no meshes, no gmsh,
//! no FE), in numbered steps through the solver's library, against
//! `examples/02_ltca_fixture/golden.json`; then `solver ltca` on the same
//! scene, whose files and numbers must be the steps' own. `BLESS=1`
//! rewrites the golden file; `regenerate.sh` in the example remakes the
//! fixture with the preprocess stages.
//!
//! Tolerance: relative 1e-9 (absolute 1e-9 on the torque balance, which is
//! zero to rounding). Two runs on the same machine agree bit for bit.

#[path = "../../examples/golden.rs"]
mod golden;

use geometry::pair::PairGeometry;
use geometry::scene::Scene;
use geometry::utca::roll_surface;
use golden::Quantity;
use solver::ltca::{assemble, geometry, mean_ptp, solve};
use solver::stage::context::LoadedPair;
use solver::stage::ltca::load_summaries;
use std::path::{Path, PathBuf};

const REL: f64 = 1e-9;

/// A scratch folder under the target directory, removed when dropped.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Every file of the fixture folder with its bytes.
fn fixture_files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

#[test]
fn example_02_ltca_in_steps_matches_its_golden_output() {
    let dir = golden::example_dir(env!("CARGO_MANIFEST_DIR"), "02_ltca_fixture");

    // 1. The scene: design file, blanks, torques, sweep and slicing settings.
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let sc = &scene.scene;

    // 2. The pair: both members' flanks generated from the design.
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let fp = g.side(sc.loaded_flank);

    // 3. The unloaded TCA: the surface of roll angles of the loaded flanks.
    let rs = roll_surface(fp, &sc.utca).unwrap();

    // 4. The loaded pair: both stiffness files, checked against the mesh
    //    folder's manifest, as the pair compliance C = C_pinion + C_wheel,
    //    and the scene's sweep (one mesh cycle in 1° steps).
    let blanks = [sc.blanks.pinion[0], sc.blanks.wheel[0]];
    let pair = LoadedPair::load(&scene, &g, &dir.join("meshes").join(&sc.name), blanks).unwrap();
    let sweep = pair.sweep;

    // 5. One position by hand: the slices of every tooth pair in contact,
    //    their compliance and line contacts, the contact problem at the
    //    first torque (slice forces ≥ 0 and the loaded TE θ).
    let tau = g.data.mesh_cycle();
    let slices = geometry(fp, &rs, sweep.start, tau, sweep.slices);
    let assembled = assemble(&slices, &pair.pc, sweep.friction).unwrap();
    let torque = sc.pinion_torque_nm[0];
    let contact = solve(&assembled, torque, None).unwrap();
    assert!(contact.force.iter().all(|f| *f >= 0.0));
    assert!(
        contact.theta > slices.utca_te,
        "the load turns the wheel back"
    );

    // 6. The sweep: every position, every torque (positions in parallel);
    //    its first position is step 5's.
    let res = solver::ltca::run(fp, &rs, &pair.pc, &sweep, &sc.pinion_torque_nm).unwrap();
    assert_eq!(res[0].loads[0].te, contact.theta);

    // 7. Per torque: TE mean and peak-to-peak, pressure, stiffness, shares,
    //    wheel torque; checked against the golden file.
    let loads = load_summaries(&res, &sc.pinion_torque_nm);
    let (utca_mean, utca_ptp) = mean_ptp(&res.iter().map(|p| p.utca_te).collect::<Vec<_>>());
    let ratio = scene.pair.members[0].teeth as f64 / scene.pair.members[1].teeth as f64;
    let mut q = vec![
        Quantity::new("positions", res.len() as f64, "", 0.0, 0.0),
        Quantity::new("utca_te_mean_urad", utca_mean * 1e6, "urad", REL, 1e-9),
        Quantity::new("utca_te_ptp_urad", utca_ptp * 1e6, "urad", REL, 1e-9),
    ];
    q.extend(load_quantities(&loads, ratio));
    // Frictionless: the wheel torque balances the pinion torque × z₂/z₁ at
    // every position.
    for p in &res {
        for (l, &t) in p.loads.iter().zip(&sc.pinion_torque_nm) {
            let off = (l.wheel_torque_nm * ratio / t - 1.0).abs();
            assert!(off < 1e-9, "balance {off:e} at {} rad, {t} N m", p.rotation);
        }
    }
    golden::check(
        &dir.join("golden.json"),
        "examples/02_ltca_fixture: the numbered steps of solver/tests/example_02_ltca_fixture.rs (scene, pair, UTCA, LoadedPair::load, one position by hand, ltca::run, load_summaries) on examples/02_ltca_fixture/scene.toml from the stiffness fixture in its meshes/",
        &q,
    );
}

/// The golden quantities of each torque's summary.
fn load_quantities(loads: &[solver::stage::ltca::LoadSummary], ratio: f64) -> Vec<Quantity> {
    let mut q = Vec::new();
    for l in loads {
        let t = l.torque_nm;
        let mut add = |name: &str, v: f64, unit: &'static str, abs: f64| {
            q.push(Quantity::new(format!("{t}nm.{name}"), v, unit, REL, abs))
        };
        add("te_mean_urad", l.te_mean_urad, "urad", 1e-9);
        add("te_ptp_urad", l.te_ptp_urad, "urad", 1e-9);
        add("max_pressure_mpa", l.max_pressure_mpa, "MPa", 0.0);
        add(
            "mesh_stiffness_mean_nm_per_rad",
            l.mesh_stiffness_mean_nm_per_rad,
            "N m/rad",
            0.0,
        );
        add("max_pair_share", l.max_pair_share, "", 0.0);
        add("wheel_torque_mean_nm", l.wheel_torque_mean_nm, "N m", 0.0);
        // Frictionless: the wheel torque is the pinion torque times z2/z1.
        q.push(Quantity::new(
            format!("{t}nm.wheel_torque_balance"),
            l.wheel_torque_mean_nm * ratio / t - 1.0,
            "",
            0.0,
            1e-9,
        ));
    }
    q
}

#[test]
fn example_02_solver_ltca_writes_the_steps_numbers_and_leaves_the_fixture_alone() {
    let dir = golden::example_dir(env!("CARGO_MANIFEST_DIR"), "02_ltca_fixture");
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let meshes = dir.join("meshes");
    let fixture = meshes.join(&scene.scene.name);

    // The fixture holds the manifest and stiffness files only, well under 2 MB.
    let before = fixture_files(&fixture);
    let names: Vec<&str> = before.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"manifest.json"), "{names:?}");
    assert!(
        names
            .iter()
            .all(|n| *n == "manifest.json" || n.ends_with(".stiffness.h5")),
        "only manifest.json and *.stiffness.h5 belong in {}: {names:?}",
        fixture.display()
    );
    let bytes: usize = before.iter().map(|(_, b)| b.len()).sum();
    assert!(bytes < 2_000_000, "fixture is {bytes} bytes");

    let scratch = Scratch(
        Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("example_02_{}", std::process::id())),
    );
    let res = solver::stage::ltca::run(&scene, &meshes, &scratch.0).unwrap_or_else(|e| {
        panic!(
            "{e:#}\n(if the stiffness fixture is stale, run examples/02_ltca_fixture/regenerate.sh)"
        )
    });
    assert_eq!(
        fixture_files(&fixture),
        before,
        "the solver changed its input fixture"
    );
    assert_eq!(res.len(), 1, "one pinion x wheel blank");
    let b = &res[0];
    for f in [
        "te.csv",
        "pairs.csv",
        "slices.csv",
        "wheel_torque.csv",
        "ltca.h5",
        "summary.json",
    ] {
        assert!(
            b.dir.join(f).is_file(),
            "{f} missing in {}",
            b.dir.display()
        );
    }

    let ratio = scene.pair.members[0].teeth as f64 / scene.pair.members[1].teeth as f64;
    // The stage's numbers are the library's (steps 2-7 above) to the bit.
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let fp = g.side(scene.scene.loaded_flank);
    let rs = roll_surface(fp, &scene.scene.utca).unwrap();
    let pair = LoadedPair::load(&scene, &g, &fixture, [b.pinion_blank, b.wheel_blank]).unwrap();
    let torques = &scene.scene.pinion_torque_nm;
    let res = solver::ltca::run(fp, &rs, &pair.pc, &pair.sweep, torques).unwrap();
    assert_eq!(b.positions, res.len());
    let steps = load_quantities(&load_summaries(&res, torques), ratio);
    let stage = load_quantities(&b.loads, ratio);
    for (s, t) in stage.iter().zip(&steps) {
        assert_eq!(
            (&s.name, s.value),
            (&t.name, t.value),
            "stage against steps"
        );
    }
    assert_eq!(stage.len(), steps.len());

    // The balance at every position (wheel_torque.csv, 6 decimals).
    let csv = std::fs::read_to_string(b.dir.join("wheel_torque.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        for (l, w) in b.loads.iter().zip(&v[1..]) {
            let off = (w * ratio / l.torque_nm - 1.0).abs();
            assert!(
                off < 1e-6,
                "wheel torque balance {off:e} at {} deg, {} N m",
                v[0],
                l.torque_nm
            );
        }
    }
}
