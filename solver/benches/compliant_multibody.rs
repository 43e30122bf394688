//! `make bench` (compliant bearings): the multibody with compliant
//! bearings on the default scene's standard pair (stiffness files from
//! `make preprocess`): the cost of the unloaded TE's shift per misalignment
//! (8 misaligned contact searches over the table's positions), and the CPU
//! time per step of the run-up (pinion 0 → 1000 rpm in 0.15 s at 300 N·m,
//! steps up to 1e-5 s, the default scene's multibody settings) and of the
//! 10 rpm run, with the rigid-bearing model on the same table beside them,
//! and the flexible gearbox (`solver::gearbox`) on the same bearings: with
//! rigid shafts (the compliant model's physics on its general structure:
//! the overhead of the general code) and with 40 / 50 mm steel shafts from
//! each gear's mean point to its far bearing in 10 mm elements, and with
//! those shafts on the white-paper gearbox's FE housing (its reduced
//! matrices from `meshes/white_paper_gearbox/housing.h5`, made by
//! `make validate`; left out where absent).
//! Target: ≤ 1 ms per step (the white paper ~0.4 s per step).
//! Results in `bench/compliant_multibody.json`.

#[path = "support/default_pair.rs"]
mod default_pair;

use default_pair::DefaultPair;
use geometry::generation::trace_sign;
use geometry::misalignment::Misalignment;
use geometry::pair::PairGeometry;
use serde_json::json;
use solver::bearings::flexible_shaft::{Shaft, ShaftSegment};
use solver::bearings::support::{Bearing, Support};
use solver::gearbox::dynamics::{integrate as g_integrate, GearboxIntegrator, GearboxModel};
use solver::gearbox::structure::{modal_damping, Housing};
use solver::gearbox::{assemble, MemberParts};
use solver::multibody::compliant::{
    integrate as c_integrate, CompliantIntegrator, CompliantModel, MemberBody,
};
use solver::multibody::lag_shift::LagShift;
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{wheel_driven, Drive, Model, Ramp};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use std::f64::consts::PI;
use std::time::Instant;

/// Bearings of 1 GN/m (radial and axial, the second of each floating),
/// damping 2 kN·s/m: the pinion overhung on bearings 40 and 100 mm behind
/// its mean point, the wheel on bearings 20 and 120 mm behind its mean
/// point; masses 1.5 and 12 kg at the mean points, transverse moments
/// half the polar ones.
fn bodies(g: &PairGeometry, inertia: [f64; 2]) -> [MemberBody; 2] {
    let one = |m: usize, near: f64, far: f64, mass: f64| {
        let s = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        let b = |x: f64, ka: f64| Bearing {
            axial_position_m: s + x,
            radial_stiffness_n_per_m: 1e9,
            axial_stiffness_n_per_m: ka,
        };
        MemberBody {
            support: Support::new(
                "bench.bearings",
                g.frames[m].axis(),
                nalgebra::Vector3::zeros(),
                &[b(near, 1e9), b(far, 0.0)],
            )
            .unwrap(),
            damping: vec![(2e3, 2e3); 2],
            mass_kg: mass,
            centroid_m: s,
            transverse_inertia_kgm2: 0.5 * inertia[m],
        }
    };
    [one(0, 0.04, 0.10, 1.5), one(1, 0.02, 0.12, 12.0)]
}

/// Solid steel shafts from each gear's mean point to its far bearing
/// (pinion 40 mm, wheel 50 mm) and their density.
fn shafts(g: &PairGeometry, b: &[MemberBody; 2]) -> [(Shaft, f64); 2] {
    std::array::from_fn(|m| {
        let seat = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        let far = b[m]
            .support
            .bearings()
            .iter()
            .fold(seat, |a, x| a.max(x.axial_position_m));
        let data = &g.data.members[m];
        (
            Shaft {
                segments: vec![ShaftSegment {
                    from_m: seat,
                    to_m: far,
                    outer_diameter_m: [0.04, 0.05][m],
                    inner_diameter_m: 0.0,
                }],
                seat_m: seat,
                youngs_modulus_pa: data.youngs_modulus,
                poisson_ratio: data.poisson_ratio,
            },
            data.density,
        )
    })
}

/// Runs `run` (which records the shaft TE and returns its steps) on one
/// thread's CPU clock: (steps, µs per step, TE peak-to-peak in µrad).
fn timed(run: impl FnOnce(&mut Vec<f64>) -> usize) -> (usize, f64, f64) {
    let mut te = Vec::new();
    let clock = solver::cpu_clock::thread_cpu_s();
    let steps = run(&mut te);
    let us = (solver::cpu_clock::thread_cpu_s() - clock) / steps as f64 * 1e6;
    (steps, us, solver::ltca::mean_ptp(&te).1 * 1e6)
}

/// Prints and returns one row of the table.
fn row(
    run: &str,
    bearings: &str,
    steps: usize,
    rejected: usize,
    us: f64,
    ptp: f64,
) -> serde_json::Value {
    println!("{run:>8} {bearings:>22} {steps:>8} {rejected:>9} {us:>10.1} {ptp:>10.2}");
    json!({"run": run, "bearings": bearings, "steps": steps, "rejected_steps": rejected, "us_per_step": us, "te_ptp_urad": ptp})
}

fn main() {
    let p = DefaultPair::load();
    let (scene, g, pc, rs, sweep) = (&p.scene, &p.g, &p.pc, &p.rs, &p.sweep);
    let sc = &scene.scene;
    let mb = &sc.multibody;
    let [j1, j2] = p.inertia;
    let fp = p.fp();
    let (tau, ratio) = (p.tau, p.ratio);
    let per = (tau / mb.table_step_deg.to_radians()).round() as usize;
    let spec = TableSpec {
        start: sweep.start,
        direction: sweep.direction,
        step: tau / per as f64,
        positions: per,
        periodic: true,
        slices: sc.ltca.slices,
        lag_nodes: mb.table_lag_nodes,
        torque_max_nm: 1400.0,
    };
    let t = Instant::now();
    let table = MeshTable::build(fp, rs, pc, &g.frames[0], ratio, spec).unwrap();
    let table_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let shift = LagShift::build(
        g,
        sc.loaded_flank,
        &sc.utca,
        &table,
        &Misalignment::default(),
    )
    .unwrap();
    let shift_s = t.elapsed().as_secs_f64();
    let inertia = [j1, j2];
    let hand = trace_sign(g.data.members[0].hand);
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    println!(
        "\nCompliant-bearing multibody (default scene, standard blanks, {cores} cores): table {per} positions x {} lags in {table_s:.1} s, lag shift (8 misaligned contact searches) in {shift_s:.1} s\n",
        mb.table_lag_nodes
    );
    println!(
        "{:>8} {:>22} {:>8} {:>9} {:>10} {:>10}",
        "run", "bearings", "steps", "rejected", "us/step", "TE ptp µrad"
    );
    let control = |max_step: f64| StepControl {
        max_step,
        min_step: max_step * 1e-6,
        tolerance: mb.te_tolerance_urad * 1e-6,
    };
    let w = |rpm: f64| rpm * PI / 30.0;
    let torque = mb.runup_pinion_torque_nm;
    let mut runup = Model {
        table: &table,
        coast: None,
        inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::PinionSpeed {
            speed: Ramp {
                from: w(mb.runup_rpm[0]),
                to: w(mb.runup_rpm[1]),
                duration: mb.runup_time_s,
            },
            wheel_torque: torque / ratio,
        },
    };
    let s0 = runup.static_state(0.0).unwrap();
    runup.damping = runup.damping_for_ratio(mb.damping_ratio, &s0).unwrap();
    let (ten, _) = wheel_driven(
        &table,
        inertia,
        w(mb.quasi_static_wheel_rpm),
        torque,
        mb.damping_ratio,
        0.0,
    )
    .unwrap();
    let cases = [
        ("run-up", runup, mb.runup_time_s, mb.runup_max_step_s),
        (
            "10 rpm",
            ten,
            tau / (w(mb.quasi_static_wheel_rpm) / ratio),
            mb.quasi_static_max_step_s,
        ),
    ];
    let mut rows = Vec::new();
    for (name, m, t_end, max_step) in cases {
        // Rigid bearings, then compliant ones.
        let mut integ = Integrator::new(
            Scheme::GeneralizedAlpha {
                rho_inf: mb.rho_inf,
            },
            control(max_step),
        );
        let s0 = m.static_state(0.0).unwrap();
        let (steps, us, ptp) = timed(|te| {
            integrate(&m, s0, &mut integ, t_end, |s| {
                te.push(ratio * s.q[0] - s.q[1]);
                Ok(())
            })
            .unwrap()
            .1
        });
        rows.push(row(name, "rigid", steps, integ.rejected, us, ptp));
        let cm = CompliantModel::new(m, &shift, bodies(g, inertia), hand).unwrap();
        let s0 = cm.static_state(0.0).unwrap();
        let mut ci = CompliantIntegrator::new(mb.rho_inf, control(max_step));
        let (steps, us, ptp) = timed(|te| {
            c_integrate(&cm, s0, &mut ci, t_end, |s, _| {
                te.push(ratio * s.x[0] - s.x[1]);
                Ok(())
            })
            .unwrap()
            .1
        });
        rows.push(row(name, "compliant", steps, ci.rejected, us, ptp));
        let b = bodies(g, inertia);
        let sh = shafts(g, &b);
        // The white-paper gearbox's housing where `make validate` has made
        // it: its reduced matrices (seats on both members' two bearings),
        // for the cost of its coordinates.
        let housing = formats::housing_file::read(
            &p.root.join("meshes/white_paper_gearbox/housing.h5"),
            None,
        )
        .ok()
        .map(|d| {
            let r = d.coordinates();
            let k = nalgebra::DMatrix::from_row_slice(r, r, &d.stiffness);
            let m = nalgebra::DMatrix::from_row_slice(r, r, &d.mass);
            Housing {
                damping: modal_damping(&k, &m, 6 * d.seat_member.len(), 0.02),
                stiffness: k,
                mass: m,
                seats: d
                    .seat_member
                    .iter()
                    .zip(&d.seat_bearing)
                    .map(|(&m, &b)| (m as usize, b as usize))
                    .collect(),
            }
        });
        if housing.is_none() {
            eprintln!("no meshes/white_paper_gearbox/housing.h5 (make validate makes it): the gearbox with a housing is not timed");
        }
        let mut cases = vec![
            ("gearbox, rigid shafts", false, None),
            ("gearbox, shafts", true, None),
        ];
        if let Some(h) = housing.as_ref() {
            cases.push(("gearbox, shafts, FE housing", true, Some(h)));
        }
        for (label, with_shafts, housing) in cases {
            let parts: [MemberParts; 2] = std::array::from_fn(|k| MemberParts {
                body: &b[k],
                polar_inertia_kgm2: inertia[k],
                shaft: with_shafts.then(|| (&sh[k].0, sh[k].1)),
            });
            let st = assemble(parts, housing, 0.01).unwrap();
            let gm = GearboxModel::new(&cm, &st).unwrap();
            let s0 = gm.static_state(0.0).unwrap();
            let mut gi = GearboxIntegrator::new(mb.rho_inf, control(max_step));
            let (steps, us, ptp) = timed(|te| {
                g_integrate(&gm, s0, &mut gi, t_end, |s, _| {
                    te.push(ratio * s.x[0] - s.x[1]);
                    Ok(())
                })
                .unwrap()
                .1
            });
            let mut r = row(name, label, steps, gi.rejected, us, ptp);
            r["coordinates"] = json!(gm.dofs());
            rows.push(r);
        }
    }
    let out = p.root.join("bench");
    std::fs::create_dir_all(&out).unwrap();
    formats::output::write_json(
        &out.join("compliant_multibody.json"),
        &json!({"machine": format!("{cores} cores, {}", std::env::consts::ARCH),
            "case": format!("default scene, standard blanks, table {}° x {} lags, {torque} N·m; run-up {}..{} rpm in {} s (max step {} s), 10 rpm one mesh cycle (max step {} s); bearings 1 GN/m, 2 kN·s/m, pinion overhung (40/100 mm behind its mean point), wheel 20/120 mm; CPU time of one thread per accepted step", mb.table_step_deg, mb.table_lag_nodes, mb.runup_rpm[0], mb.runup_rpm[1], mb.runup_time_s, mb.runup_max_step_s, mb.quasi_static_max_step_s),
            "target_us_per_step": 1000.0, "table_build_s": table_s, "lag_shift_s": shift_s, "runs": rows}),
    )
    .unwrap();
    println!("written to bench/compliant_multibody.json");
}
