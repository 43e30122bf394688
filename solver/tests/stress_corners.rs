//! Corners of the stress matrix that broke or misled the multibody
//! run, on the checked-in example-02 stiffness fixture (a table of 36
//! positions builds in a fraction of a second):
//! - the 10 rpm run at 0 and 1e-6 N·m (mean TE −115 and −579 µrad): the
//!   quasi-static start took a spurious root of the interpolated torque
//!   below the unloaded TE, and below the pinion's holding torque no
//!   quasi-static TE exists (refused, naming the limit);
//! - `table_lag_nodes` 8–12 (refused at load; 16 runs);
//! - `te_tolerance_urad = 1e-9` (refused at load; the step control no longer
//!   stalls on rounding noise);
//! - the run-up below the torque that holds the wheel on the flanks
//!   (refused without coast flanks, naming the limit).
use solver::stage::context::LoadedPair;

use geometry::pair::PairGeometry;
use geometry::scene::{Blank, Scene};
use geometry::utca::roll_surface;
use solver::multibody::mesh_table::{lag_grid, MeshTable, TableSpec};
use solver::multibody::model::{interpolate, wheel_driven, Model};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use solver::stage::context::scene_sweep;
use std::path::{Path, PathBuf};

fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture")
}

/// The fixture's standard pair: its table (0.5° steps) and polar moments.
struct Pair {
    table: MeshTable,
    inertia: [f64; 2],
    /// Quasi-static run: wheel speed (rad/s, 10 rpm), duration (s) and the
    /// sweep's positions (pinion rotation, rad).
    wheel_speed: f64,
    t_end: f64,
    positions: Vec<f64>,
}

fn pair(lag_nodes: usize, torque_max_nm: f64) -> Pair {
    let dir = fixture();
    let scene = Scene::load(&dir.join("scene.toml")).unwrap();
    let sc = &scene.scene;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let meshes = dir.join("meshes").join(&sc.name);
    let pair = LoadedPair::load(&scene, &g, &meshes, [Blank::Standard; 2]).unwrap();
    let [(j1, _), (j2, _)] = pair.inertia(&scene, &g, &meshes).unwrap();
    let pc = pair.pc;
    let fp = g.side(sc.loaded_flank);
    let rs = roll_surface(fp, &sc.utca).unwrap();
    let tau = g.data.mesh_cycle();
    let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
    let sweep = scene_sweep(&scene, &g, Blank::Standard);
    let per = (tau / 0.5f64.to_radians()).round() as usize;
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
            lag_nodes,
            torque_max_nm,
        },
    )
    .unwrap();
    let wheel_speed = std::f64::consts::PI / 3.0;
    let range = sweep.step * (sweep.positions - 1) as f64;
    Pair {
        table,
        inertia: [j1, j2],
        wheel_speed,
        t_end: (range + 2.0 * sweep.step) / (wheel_speed / ratio),
        positions: (0..sweep.positions)
            .map(|k| sweep.step * k as f64)
            .collect(),
    }
}

/// The 10 rpm run: TE (rad) at the sweep's positions, steps.
fn run_10rpm(
    p: &Pair,
    m: &Model,
    s: solver::multibody::model::State,
    tolerance: f64,
) -> (Vec<f64>, usize) {
    let mut integ = Integrator::new(
        Scheme::GeneralizedAlpha { rho_inf: 0.9 },
        StepControl {
            max_step: 1e-3,
            min_step: 1e-9,
            tolerance,
        },
    );
    let r = p.table.ratio;
    let (mut q1, mut te) = (Vec::new(), Vec::new());
    let (_, steps) = integrate(m, s, &mut integ, p.t_end, |s| {
        q1.push(s.q[0]);
        te.push(r * s.q[0] - s.q[1]);
        Ok(())
    })
    .unwrap();
    let sampled = p
        .positions
        .iter()
        .map(|&x| interpolate(&q1, &te, x))
        .collect();
    (sampled, steps)
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

#[test]
fn multibody_at_0_and_1e_6_nm_is_refused_and_above_the_holding_torque_follows_the_unloaded_te() {
    let p = pair(96, 2.0);
    let te0: Vec<f64> = p
        .positions
        .iter()
        .map(|&x| p.table.unloaded(x).unwrap()[0])
        .collect();
    // Light loads: no quasi-static lag below the unloaded TE (it was up to
    // 2.8 µrad below it, a spurious root of the interpolated torque, and
    // none at all at 1e-6 N·m), and the lag grows with the load.
    let (base, _) = wheel_driven(&p.table, p.inertia, p.wheel_speed, 1.0, 0.05, 0.0).unwrap();
    for k in -3..=3 {
        let q1 = k as f64 * 0.1 * p.table.spec.step;
        let t0 = p.table.unloaded(q1).unwrap()[0];
        let mut last = f64::NEG_INFINITY;
        for torque in [1e-6, 1e-5, 1e-3, 0.1, 1.0] {
            let m = Model {
                drive: solver::multibody::model::Drive::WheelSpeed {
                    speed: solver::multibody::model::Ramp {
                        from: p.wheel_speed,
                        to: p.wheel_speed,
                        duration: 0.0,
                    },
                    pinion_torque: torque,
                },
                ..base
            };
            let lag = m.static_lag(q1).unwrap();
            assert!(
                lag >= t0 - 1e-12 && lag >= last - 1e-12,
                "{torque} N·m at {q1}: lag {} µrad, unloaded {} µrad, lighter load {} µrad",
                lag * 1e6,
                t0 * 1e6,
                last * 1e6
            );
            last = lag;
        }
    }
    // 0 and 1e-6 N·m: refused, naming the field, the value and the limit.
    let holding = base.holding_torque().unwrap();
    assert!(holding > 1e-4 && holding < 0.1, "holding torque {holding}");
    for torque in [0.0, 1e-6] {
        let e = wheel_driven(&p.table, p.inertia, p.wheel_speed, torque, 0.05, 0.0)
            .err()
            .unwrap_or_else(|| panic!("{torque} N·m accepted"))
            .to_string();
        assert!(
            e.contains("pinion_torque_nm") && e.contains(&format!("{holding:.3e}")),
            "{e}"
        );
    }
    // Just above it the run rests on the unloaded TE (mean within 1 µrad,
    // never more than 1 µrad below its smallest value) instead of drifting
    // hundreds of µrad across the backlash.
    let torque = 1.2 * holding;
    let (m, s) = wheel_driven(&p.table, p.inertia, p.wheel_speed, torque, 0.05, 0.0).unwrap();
    let (te, _) = run_10rpm(&p, &m, s, 1e-9);
    let lowest = te0.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        (mean(&te) - mean(&te0)).abs() < 1e-6,
        "{torque} N·m: mean TE {} µrad, unloaded {} µrad",
        mean(&te) * 1e6,
        mean(&te0) * 1e6
    );
    assert!(te.iter().all(|&x| x > lowest - 1e-6 && x.is_finite()));
}

/// A scene with the fixture's settings and the given `[multibody]` lines.
fn scene_with(multibody: &str) -> Result<(), String> {
    let path = fixture().join("scene.toml");
    let text = std::fs::read_to_string(&path).unwrap() + "\n[multibody]\n" + multibody + "\n";
    let scene = Scene::parse(&text, &path).map_err(|e| e.to_string())?;
    scene.check(&path).map_err(|e| e.to_string())
}

#[test]
fn table_lag_nodes_8_to_12_are_refused_at_load_and_16_runs() {
    for n in [8, 9, 12, 15] {
        let e = scene_with(&format!("table_lag_nodes = {n}")).unwrap_err();
        assert!(
            e.contains("multibody.table_lag_nodes")
                && e.contains(&n.to_string())
                && e.contains("16"),
            "{e}"
        );
    }
    scene_with("table_lag_nodes = 16").unwrap();
    // The grid itself stays finite and increasing down to 4 nodes (8 gave a
    // band spacing of band / 0).
    for n in 4..=16 {
        let g = lag_grid(1e-6, 40e-6, 300e-6, n);
        assert_eq!(g.len(), n);
        assert!(g.iter().all(|x| x.is_finite()), "{n}: {g:?}");
        assert!(g.windows(2).all(|w| w[1] > w[0]), "{n}: {g:?}");
    }
    // 16 nodes: the 100 N·m run stays inside its table (12 ended beyond it)
    // and agrees with 96 nodes to 0.1 µrad.
    let te = |nodes: usize| {
        let p = pair(nodes, 200.0);
        let (m, s) = wheel_driven(&p.table, p.inertia, p.wheel_speed, 100.0, 0.05, 0.0).unwrap();
        mean(&run_10rpm(&p, &m, s, 1e-9).0)
    };
    let (coarse, fine) = (te(16), te(96));
    assert!(
        (coarse - fine).abs() < 1e-7,
        "{} vs {} µrad",
        coarse * 1e6,
        fine * 1e6
    );
}

#[test]
fn te_tolerance_1e_9_urad_is_refused_at_load_and_the_step_control_does_not_stall_on_rounding() {
    let e = scene_with("te_tolerance_urad = 1e-9").unwrap_err();
    assert!(
        e.contains("multibody.te_tolerance_urad")
            && e.contains("0.000000001")
            && e.contains("[0.000001,"),
        "{e}"
    );
    scene_with("te_tolerance_urad = 1e-6").unwrap();
    // A tolerance far below the lag's rounding floor (1e-20 rad): the run
    // ends in a bounded number of steps, at the same TE as a sane tolerance.
    let p = pair(96, 200.0);
    let (m, s) = wheel_driven(&p.table, p.inertia, p.wheel_speed, 100.0, 0.05, 0.0).unwrap();
    let (tight, steps) = run_10rpm(&p, &m, s, 1e-20);
    let (sane, _) = run_10rpm(&p, &m, s, 1e-9);
    assert!(steps < 2_000_000, "{steps} steps");
    assert!((mean(&tight) - mean(&sane)).abs() < 1e-9);
}

/// The run-up's mirror-image limit: with the pinion speed imposed the
/// flanks can only push the wheel forward, so the resisting torque must
/// hold the wheel (inertia J₂) on them up to the top speed. It grows with
/// the square of the speed (both the curvature demand J₂ θ₀″ ω² and the
/// tooth-change rebound J₂ (Δθ₀′ ω)² / 2Δθ are quadratic in ω), the
/// default run-up (300 N·m to 1,000 rpm) is above it on this pair, and a
/// run at constant top speed confirms it: the wheel keeps to the flanks at
/// twice the limit and runs ahead across the lag grid far below it.
#[test]
fn runup_holding_torque_keeps_the_wheel_on_the_flanks_above_it_and_not_far_below_it() {
    use solver::multibody::model::{Drive, Ramp};
    let p = pair(96, 600.0);
    let holding = |rpm: f64| {
        let m = Model {
            table: &p.table,
            coast: None,
            inertia: p.inertia,
            damping: 0.0,
            friction: 0.0,
            drive: Drive::PinionSpeed {
                speed: Ramp {
                    from: 0.0,
                    to: rpm * std::f64::consts::PI / 30.0,
                    duration: 0.1,
                },
                wheel_torque: 300.0 / p.table.ratio,
            },
        };
        m.holding_torque().unwrap()
    };
    let (h1, h2) = (holding(1000.0), holding(2000.0));
    println!("run-up holding torque (pinion, N·m): {h1:.4} at 1000 rpm, {h2:.4} at 2000 rpm");
    assert!(h1 > 0.0);
    assert!((h2 / h1 - 4.0).abs() < 1e-9, "ratio {}", h2 / h1);
    assert!(h1 < 300.0, "{h1} N·m");
    // At a speed where it exceeds the run-up's torque, the stage refuses
    // (without coast flanks): find that speed from the quadratic law.
    let rpm_limit = 1000.0 * (300.0 / h1).sqrt();
    assert!(holding(1.01 * rpm_limit) > 300.0 && holding(0.99 * rpm_limit) < 300.0);

    // The criterion against the dynamics: at 2,000 rpm held constant, the
    // wheel stays within one lag step of the drive flanks at twice the
    // holding torque and runs ahead further at a twentieth of it.
    let w = 2000.0 * std::f64::consts::PI / 30.0;
    let deepest_separation = |pinion_torque: f64| -> f64 {
        let m = Model {
            table: &p.table,
            coast: None,
            inertia: p.inertia,
            damping: 0.0,
            friction: 0.0,
            drive: Drive::PinionSpeed {
                speed: Ramp {
                    from: w,
                    to: w,
                    duration: 0.0,
                },
                wheel_torque: pinion_torque / p.table.ratio,
            },
        };
        let s0 = m.static_state(0.0).unwrap();
        let mut integ = Integrator::new(
            Scheme::GeneralizedAlpha { rho_inf: 0.9 },
            StepControl {
                max_step: 2e-6,
                min_step: 1e-10,
                tolerance: 1e-9,
            },
        );
        let t_end = 3.0 * p.table.span() / w;
        let mut worst: f64 = 0.0;
        integrate(&m, s0, &mut integ, t_end, |s| {
            worst = worst.min(m.contact(s.q, s.v)?.mesh.u);
            Ok(())
        })
        .unwrap();
        -worst
    };
    let du = p.table.du();
    let (held, loose) = (deepest_separation(2.0 * h2), deepest_separation(0.05 * h2));
    println!("separation at 2x / 0.05x the holding torque: {held:.3e} / {loose:.3e} rad (lag step {du:.3e})");
    assert!(held <= du, "{held} > {du}");
    assert!(loose > du, "{loose} <= {du}");
}
