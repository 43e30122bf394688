//! `make bench` (multibody): the contact-element table and the 10 rpm run of
//! the default scene's standard pair (stiffness files from `make preprocess`):
//! run time against error over the table resolution, the error being the
//! 10 rpm run's TE against the quasi-static LTCA at the same positions, and
//! the run-up's time per step next to the white paper's ~0.4 s CPU per step
//! (its Table 6). Results in `bench/multibody.json`.

use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, Scene};
use geometry::utca::roll_surface;
use serde_json::json;
use solver::compliance::PairCompliance;
use solver::dynamic_stage::inertia;
use solver::ltca::{mean_ptp, run};
use solver::ltca_stage::{member_compliance, scene_sweep};
use solver::mesh_table::{MeshTable, TableSpec};
use solver::multibody::{interpolate, wheel_driven};
use solver::time_step::{integrate, Integrator, Scheme, StepControl};
use std::path::Path;
use std::time::Instant;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let scene = Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let dir = root.join("meshes").join(&sc.name);
    // Compliance and polar moment (from the body mesh, as `solver dynamic`) per member.
    let load = |m: Member| {
        let (c, plan) = member_compliance(&scene, &g, &dir, m, Blank::Standard)
            .expect("meshes/default: run `make preprocess` first");
        (c, inertia(&scene, &g, &dir, &plan, m).unwrap().0)
    };
    let ((pinion, j1), (wheel, j2)) = (load(Member::Pinion), load(Member::Wheel));
    let pc = PairCompliance { pinion, wheel };
    let fp = g.side(sc.loaded_flank);
    let rs = roll_surface(fp, &sc.utca).unwrap();
    let tau = g.data.mesh_cycle();
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    let sweep = scene_sweep(&scene, &g, Blank::Standard);
    let torques = [100.0, 300.0, 700.0];
    let ltca = run(fp, &rs, &pc, &sweep, &torques).unwrap();
    let inertia = [j1, j2];
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    println!("\nMultibody benchmark (default scene, standard blanks, {cores} cores)\n");
    println!(
        "{:>9} {:>5} {:>9} {:>8} {:>18} {:>18} {:>18}",
        "step[deg]",
        "lags",
        "table[s]",
        "us/step",
        "100 N·m err %ptp",
        "300 N·m err %ptp",
        "700 N·m err %ptp"
    );
    let mut rows = Vec::new();
    for (step_deg, lags) in [(0.5, 48), (0.25, 64), (0.125, 96), (0.0625, 128)] {
        let per = (tau / f64::to_radians(step_deg)).round() as usize;
        let t = Instant::now();
        let table = MeshTable::build(
            fp,
            &rs,
            &pc,
            &g.frames[0],
            ratio,
            TableSpec {
                start: sweep.start,
                direction: sweep.direction,
                step: tau / per as f64,
                positions: per,
                periodic: true,
                slices: sc.ltca.slices,
                lag_nodes: lags,
                torque_max_nm: 1400.0,
            },
        )
        .unwrap();
        let build = t.elapsed().as_secs_f64();
        let mut errs = Vec::new();
        let (mut cpu, mut steps) = (0.0, 0usize);
        for (i, &torque) in torques.iter().enumerate() {
            let wheel = std::f64::consts::PI / 3.0;
            let (m, s) = wheel_driven(
                &table,
                inertia,
                wheel,
                torque,
                sc.multibody.damping_ratio,
                sc.ltca.friction_coefficient,
            )
            .unwrap();
            let mut integ = Integrator::new(
                Scheme::GeneralizedAlpha {
                    rho_inf: sc.multibody.rho_inf,
                },
                StepControl {
                    max_step: 1e-3,
                    min_step: 1e-9,
                    tolerance: 1e-9,
                },
            );
            let range = sweep.step * (sweep.positions - 1) as f64;
            let t_end = (range + 2.0 * sweep.step) / (wheel / ratio);
            let (mut q1, mut te) = (Vec::new(), Vec::new());
            let t = Instant::now();
            let (_, n) = integrate(&m, s, &mut integ, t_end, |s| {
                q1.push(s.q[0]);
                te.push(ratio * s.q[0] - s.q[1]);
                Ok(())
            })
            .unwrap();
            cpu += t.elapsed().as_secs_f64();
            steps += n;
            let (_, ptp) = mean_ptp(&ltca.iter().map(|p| p.loads[i].te).collect::<Vec<_>>());
            let worst = ltca
                .iter()
                .map(|p| (interpolate(&q1, &te, p.rotation) - p.loads[i].te).abs())
                .fold(0.0, f64::max);
            errs.push(100.0 * worst / ptp);
        }
        let us = cpu / steps as f64 * 1e6;
        println!(
            "{:>9} {:>5} {:>9.2} {:>8.1} {:>18.3} {:>18.3} {:>18.3}",
            step_deg, lags, build, us, errs[0], errs[1], errs[2]
        );
        rows.push(
            json!({"table_step_deg": step_deg, "lag_nodes": lags, "table_build_s": build,
            "table_cpu_s_per_position": table.cpu_s_per_position, "us_per_step": us,
            "te_error_percent_of_ltca_ptp": {"100": errs[0], "300": errs[1], "700": errs[2]}}),
        );
    }
    let out = root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(
        &out.join("multibody.json"),
        &json!({"machine": format!("{cores} cores, {}", std::env::consts::ARCH),
            "case": "10 rpm wheel, standard blanks, default scene, 2 mesh cycles; error = max |TE_MB - TE_LTCA| over the LTCA positions, % of the LTCA's ptp",
            "white_paper_runup_cpu_s_per_step": 0.4, "tables": rows}),
    )
    .unwrap();
    println!("written to bench/multibody.json");
}
