//! `make bench` (multibody): the contact-element table and the 10 rpm run of
//! the default scene's standard pair (stiffness files from `make preprocess`):
//! run time against error over the table resolution, the error being the
//! 10 rpm run's TE against the quasi-static LTCA at the same positions, and
//! the run-up's time per step next to the white paper's ~0.4 s CPU per step
//! (its Table 6); and the cost per step of the two force laws (the
//! FE-analytical element and the impact law) in the seeds' load
//! run: pinion at 300 rpm, the wheel load of 300 N·m at the pinion rising
//! by STEP over 20 ms, 0.1 s. Results in `bench/multibody.json`.

#[path = "support/default_pair.rs"]
mod default_pair;

use default_pair::DefaultPair;
use geometry::pair::PairGeometry;
use geometry::scene::{ImpactSettings, LoadRun};
use serde_json::json;
use solver::element::compliance::PairCompliance;
use solver::ltca::{mean_ptp, run};
use solver::multibody::impact_law::from_settings as impact_law;
use solver::multibody::load_run;
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{interpolate, wheel_driven, Drive, Model};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use std::time::Instant;

fn main() {
    let p = DefaultPair::load();
    let (scene, g, pc, rs, sweep) = (&p.scene, &p.g, &p.pc, &p.rs, &p.sweep);
    let sc = &scene.scene;
    let [j1, j2] = p.inertia;
    let fp = p.fp();
    let (tau, ratio) = (p.tau, p.ratio);
    let torques = [100.0, 300.0, 700.0];
    let ltca = run(fp, rs, pc, sweep, &torques).unwrap();
    let inertia = [j1, j2];
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    println!("\nMultibody benchmark (default scene, standard blanks, {cores} cores)\n");
    println!(
        "{:>9} {:>5} {:>9} {:>8} {:>18} {:>18} {:>18} {:>14} {:>14}",
        "step[deg]",
        "lags",
        "table[s]",
        "us/step",
        "100 N·m err %ptp",
        "300 N·m err %ptp",
        "700 N·m err %ptp",
        "state [us]",
        "V quad [us]"
    );
    let mut rows = Vec::new();
    for (step_deg, lags) in [(0.5, 48), (0.25, 64), (0.125, 96), (0.0625, 128)] {
        let per = (tau / f64::to_radians(step_deg)).round() as usize;
        let t = Instant::now();
        let table = MeshTable::build(
            fp,
            rs,
            pc,
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
        let (moments_us, quadrature_us) = path_integral_costs(&table, ratio);
        println!(
            "{:>9} {:>5} {:>9.2} {:>8.1} {:>18.3} {:>18.3} {:>18.3} {:>14.2} {:>14.2}",
            step_deg, lags, build, us, errs[0], errs[1], errs[2], moments_us, quadrature_us
        );
        rows.push(
            json!({"table_step_deg": step_deg, "lag_nodes": lags, "table_build_s": build,
            "table_cpu_s_per_position": table.cpu_s_per_position, "us_per_step": us,
            "evaluation_us": {"state_with_prefix_moments": moments_us, "path_integrals_by_quadrature": quadrature_us},
            "te_error_percent_of_ltca_ptp": {"100": errs[0], "300": errs[1], "700": errs[2]}}),
        );
    }
    let laws = force_laws(fp, rs, pc, g, sweep, sc, ratio, tau, inertia);
    let out = p.root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(
        &out.join("multibody.json"),
        &json!({"machine": format!("{cores} cores, {}", std::env::consts::ARCH),
            "case": "10 rpm wheel, standard blanks, default scene, 2 mesh cycles; error = max |TE_MB - TE_LTCA| over the LTCA positions, % of the LTCA's ptp",
            "white_paper_runup_cpu_s_per_step": 0.4, "tables": rows,
            "force_laws": {"case": "load run: pinion 300 rpm, wheel load 300 N·m at the pinion (STEP over 20 ms), 0.1 s, max step 1e-5 s, generalized-α; table 0.125° x 96 lags; impact law: Hertz K of the pair (outer pitch radii), e = 1.5, C = 50 N·s/mm, d = 0.1 mm, μ 0.08/0.05", "laws": laws}}),
    )
    .unwrap();
    println!("written to bench/multibody.json");
}

/// Wall time per evaluation at one (q₁, q₂), µs, over the same 2,000
/// points (lags up to the middle lag node), same run: the element's whole
/// state (potential, gradient, Hessian, force; its path integrals by the
/// table's prefix moments) and the path integrals alone by quadrature over
/// every crossed cell (the method the moments replaced).
fn path_integral_costs(table: &MeshTable, ratio: f64) -> (f64, f64) {
    let points: Vec<(f64, f64)> = (0..2000)
        .map(|k| {
            let q1 = table.span() * (k as f64 * 0.618_033_988_7).fract();
            let theta = table.theta_lo()
                + (table.lags[table.lags.len() / 2] - table.theta_lo())
                    * ((k * 7 + 3) as f64 * 0.381_966).fract();
            (q1, ratio * q1 - theta)
        })
        .collect();
    let time = |f: &dyn Fn(f64, f64) -> f64| {
        let t = Instant::now();
        let mut sum = 0.0;
        for &(q1, q2) in &points {
            sum += f(q1, q2);
        }
        std::hint::black_box(sum);
        t.elapsed().as_secs_f64() / points.len() as f64 * 1e6
    };
    let moments = time(&|q1, q2| table.state(q1, q2).unwrap().potential);
    let quadrature = time(&|q1, q2| table.path_integrals_by_quadrature(q1, q2).unwrap()[0]);
    (moments, quadrature)
}

/// The load run with each force law: table build and CPU time per step.
#[allow(clippy::too_many_arguments)]
fn force_laws(
    fp: &geometry::pair::FlankPair,
    rs: &geometry::utca::RollSurface,
    pc: &PairCompliance,
    g: &PairGeometry,
    sweep: &solver::ltca::Sweep,
    sc: &geometry::scene::Scene,
    ratio: f64,
    tau: f64,
    inertia: [f64; 2],
) -> Vec<serde_json::Value> {
    let per = (tau / 0.125f64.to_radians()).round() as usize;
    let spec = TableSpec {
        start: sweep.start,
        direction: sweep.direction,
        step: tau / per as f64,
        positions: per,
        periodic: true,
        slices: sc.ltca.slices,
        lag_nodes: 96,
        torque_max_nm: 600.0,
    };
    let settings = ImpactSettings {
        damping_n_s_per_mm: 50.0,
        static_friction: 0.08,
        dynamic_friction: 0.05,
        ..ImpactSettings::default()
    };
    let (law, friction, _) = impact_law(&g.data, &settings);
    let run = LoadRun {
        pinion_rpm: 300.0,
        pinion_ramp_s: 0.0,
        wheel_torque_nm: 300.0 / ratio,
        wheel_torque_rise_s: 0.02,
        time_s: 0.1,
        max_step_s: 1e-5,
        steady_from_s: 0.05,
        output_interval_s: None,
    };
    println!(
        "\nForce laws, load run 300 rpm / 300 N·m, 0.1 s\n{:>8} {:>9} {:>8} {:>9} {:>8}",
        "law", "table[s]", "steps", "rejected", "us/step"
    );
    let mut out = Vec::new();
    for name in ["element", "impact"] {
        let t = Instant::now();
        let table = if name == "element" {
            MeshTable::build(fp, rs, pc, &g.frames[0], ratio, spec)
        } else {
            solver::multibody::impact_table::build(fp, rs, &g.frames[0], ratio, spec, law, friction)
        }
        .unwrap();
        let build = t.elapsed().as_secs_f64();
        let mut m = Model {
            table: &table,
            coast: None,
            inertia,
            damping: 0.0,
            friction: 0.0,
            drive: load_run::drive(&run),
        };
        let s0 = m.static_state(0.0).unwrap();
        if name == "element" {
            let loaded = Model {
                drive: Drive::Free {
                    pinion_torque: 300.0,
                    wheel_torque: run.wheel_torque_nm,
                },
                ..m
            };
            let s = loaded.static_state(0.0).unwrap();
            m.damping = loaded
                .damping_for_ratio(sc.multibody.damping_ratio, &s)
                .unwrap();
        }
        let mut integ = Integrator::new(
            Scheme::GeneralizedAlpha {
                rho_inf: sc.multibody.rho_inf,
            },
            StepControl {
                max_step: run.max_step_s,
                min_step: run.max_step_s * 1e-6,
                tolerance: sc.multibody.te_tolerance_urad * 1e-6,
            },
        );
        let clock = solver::cpu_clock::thread_cpu_s();
        let (_, steps) = load_run::simulate(&m, s0, &mut integ, run.time_s).unwrap();
        let us = (solver::cpu_clock::thread_cpu_s() - clock) / steps as f64 * 1e6;
        println!(
            "{:>8} {:>9.2} {:>8} {:>9} {:>8.1}",
            name, build, steps, integ.rejected, us
        );
        out.push(json!({"law": name, "table_build_s": build, "steps": steps,
            "rejected_steps": integ.rejected, "us_per_step": us}));
    }
    out
}
