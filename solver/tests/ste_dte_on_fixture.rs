//! The white paper's first use case (static against dynamic TE,
//! [`solver::stage::ste_dte`]) on the checked-in example-02 stiffness
//! fixture (no gmsh): two slow run-ups of the same model give the same
//! TE in the angle domain and it is the static balance; a fast one
//! departs during its acceleration by the wheel's inertia torque, which
//! the static balance under that extra torque gives independently, and
//! most right after the acceleration ends.
#[path = "support/fixture.rs"]
mod fixture;

use fixture::Fixture;
use geometry::scene::Blank;
use geometry::scene_ste_dte::{rad_per_s, SteDte};
use solver::multibody::model::{interpolate, Drive, Model, Ramp};
use solver::multibody::time_step::{Scheme, StepControl};
use solver::stage::ste_dte::{ste_dte, Setup};
use std::path::PathBuf;

fn settings(rpm: [f64; 2]) -> SteDte {
    SteDte {
        wheel_blanks: vec![Blank::Standard],
        pinion_torque_nm: 300.0,
        rpm,
        acceleration_end_deg: 30.0,
        // ω t = 110° of pinion rotation: 80° after the acceleration.
        time_s: 110.0 / (rpm[1] * 6.0),
        max_step_s: 1e-5 * 1000.0 / rpm[1],
        compared_revolutions: 0.2,
    }
}

fn out(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("ste_dte_{name}_{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn control(max_step: f64) -> StepControl {
    StepControl {
        max_step,
        min_step: max_step * 1e-6,
        tolerance: 1e-9,
    }
}

fn setup<'a>(f: &Fixture, table: &'a solver::multibody::mesh_table::MeshTable) -> Setup<'a> {
    Setup {
        table,
        coast: None,
        inertia: f.inertia,
        friction: 0.0,
        impact: false,
        damping_ratio: 0.05,
        scheme: Scheme::GeneralizedAlpha { rho_inf: 0.9 },
        control: &control,
        mesh_cycle: f.g.data.mesh_cycle(),
        blanks: [Blank::Standard; 2],
    }
}

#[test]
fn run_ups_at_10_and_20_rpm_give_the_same_te_in_the_angle_domain_and_it_is_the_static_balance() {
    let f = Fixture::example_02();
    let table = f.table(0.25, 96, 600.0);
    let dir = out("slow");
    let s = ste_dte(&setup(&f, &table), &settings([10.0, 20.0]), &dir).unwrap();
    eprintln!("{s:#?}");
    // The slow runs differ only by inertia torques 1e-4 of the load and
    // below: their TEs agree to a few hundredths of a µrad at 300 N·m
    // (about 360 µrad of TE), everywhere in the window.
    assert!(s.ste_minus_static_max_urad < 0.05, "{s:#?}");
    assert!(s.departure_largest_urad.abs() < 0.05, "{s:#?}");
    assert!(s.departure_during_acceleration_urad.abs() < 0.05, "{s:#?}");
    assert!((s.ste_ptp_urad - s.dte_ptp_urad).abs() < 0.05, "{s:#?}");
    // The files of the comparison.
    for name in [
        "ste_dte.csv",
        "ste_dte.svg",
        "ste_dte_10rpm.csv",
        "ste_dte_20rpm.csv",
    ] {
        assert!(dir.join(name).is_file(), "{name}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_1000_rpm_run_up_departs_while_accelerating_by_the_wheel_inertia_torque_is_largest_where_it_ends(
) {
    let f = Fixture::example_02();
    let dir = out("fast");
    let table = f.table(0.25, 96, 1200.0);
    let sd = settings([10.0, 1000.0]);
    let s = ste_dte(&setup(&f, &table), &sd, &dir).unwrap();
    eprintln!("{s:#?}");
    // During the acceleration the wheel needs J₂ α₂ more torque than the
    // load, α₂ = (z₁/z₂) ω² / (2 φₐ): the static balance under that torque
    // lies above the balance under the load alone by the departure's mean.
    let ratio = table.ratio;
    let w = rad_per_s(1000.0);
    let phi_a = 30f64.to_radians();
    let alpha2 = ratio * w * w / (2.0 * phi_a);
    let wheel_torque = 300.0 / ratio;
    let balance = |t2: f64, q: f64| {
        Model {
            table: &table,
            coast: None,
            inertia: f.inertia,
            damping: 0.0,
            friction: 0.0,
            drive: Drive::PinionSpeed {
                speed: Ramp {
                    from: 0.0,
                    to: 0.0,
                    duration: 0.0,
                },
                wheel_torque: t2,
            },
        }
        .static_lag(q)
        .unwrap()
    };
    let n = 200;
    let expected = (0..=n)
        .map(|k| {
            let q = phi_a * k as f64 / n as f64;
            balance(wheel_torque + f.inertia[1] * alpha2, q) - balance(wheel_torque, q)
        })
        .sum::<f64>()
        / (n + 1) as f64
        * 1e6;
    eprintln!(
        "inertia torque {} N·m, expected departure {expected} µrad",
        f.inertia[1] * alpha2
    );
    assert!(expected > 1.0, "{expected}");
    let err = (s.departure_during_acceleration_urad - expected) / expected;
    assert!(
        err.abs() < 0.05,
        "{} against {expected}",
        s.departure_during_acceleration_urad
    );
    // The step out of the acceleration is the transient: the largest
    // departure after it lies within its first mesh cycle.
    let tau = f.g.data.mesh_cycle().to_degrees();
    assert!(s.departure_largest_at_deg < 30.0 + tau, "{s:#?}");
    // The DTE trace is what the CSV holds at the largest departure.
    let csv = std::fs::read_to_string(dir.join("ste_dte.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let deg: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let d: Vec<f64> = rows.iter().map(|r| r[2] - r[1]).collect();
    let at = interpolate(&deg, &d, s.departure_largest_at_deg);
    assert!((at - s.departure_largest_urad).abs() < 1e-3, "{at}");
    std::fs::remove_dir_all(&dir).ok();
}
