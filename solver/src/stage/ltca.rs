//! `solver ltca <scene>`: the quasi-static loaded TCA of every pinion ×
//! wheel blank of a scene with the reduced model, from the stiffness files
//! that `preprocess stiffness` wrote (their hashes are checked), to
//! `<out>/<scene>/ltca/<pinion>_<wheel>/`: `te.csv`, `pairs.csv`,
//! `slices.csv`, `wheel_torque.csv`, `root_stress.csv` (where the stiffness
//! files hold root-stress coefficients: every position's fillets in the
//! reference's layout), `ltca.h5` and `summary.json` (with
//! the ablation study: the sweep again with each of the element's modelling
//! changes switched off).
//! `<out>/<scene>/ltca/` is written as one set
//! ([`formats::result_set`]): into a staging sibling, put in place whole
//! with its `run.json` once every blank has run; a run that fails leaves
//! the previous set as it was.
use crate::bearings::system_deflection::Supports;
use crate::stage::context::coast_compliance;
use crate::stage::context::coast_sweep;
use crate::stage::context::{analysis_enabled, LoadedPair, StageContext};
use geometry::utca::RollSurface;

use crate::element::compliance::PairCompliance;
use crate::ltca::{mean_ptp, run as run_sweep, run_variant, PositionResult, Sweep, Variant};
use anyhow::Context;
use formats::columns::{te_at_urad, PINION_ROTATION_DEG, UTCA_TE_URAD};
use formats::output::{write_atomic, write_json};
use formats::result_set::ResultSet;
use formats::stiffness_file;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

pub use formats::summaries::{
    AblationVariant, BlankSummary, CoastSummary, Edge, EdgeContact, LoadSummary, LoadedPairRule,
};

/// Runs the LTCA of the scene.
pub fn run(scene: &LoadedScene, meshes: &Path, out: &Path) -> anyhow::Result<Vec<BlankSummary>> {
    if !analysis_enabled(scene, scene.scene.analyses.ltca, "ltca", "no loaded TCA") {
        return Ok(Vec::new());
    }
    let sc = &scene.scene;
    // Taken before any work: refuses an output that another run is writing
    // or that cannot be written.
    let mut set = ResultSet::begin(
        &out.join(&sc.name).join("ltca"),
        &format!("solver ltca {}", scene.path.display()),
    )?;
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    // The bearings are checked before any work.
    let supports = sc
        .bearings
        .as_ref()
        .map(|b| crate::bearings::system_deflection::supports_of(b, &g))
        .transpose()
        .with_context(|| format!("scene {}: [bearings]", sc.name))?;
    let ctx = StageContext::with_geometry(scene, g, meshes);
    let side = ctx.side();
    let rs = ctx.roll_surface(side)?;
    let coast_rs = if sc.multibody.coast_contact {
        Some(ctx.roll_surface(side.other())?)
    } else {
        None
    };
    let mut out_all = Vec::new();
    ctx.for_each_pair(|pair| {
        ctx.record_inputs(&mut set, pair.blanks, coast_rs.is_some())?;
        let t0 = Instant::now();
        let summary = blank_pair(
            &ctx,
            &pair,
            &rs,
            coast_rs.as_ref(),
            supports.as_ref(),
            &set,
            t0,
        )?;
        print_summary(&sc.name, &summary);
        out_all.push(summary);
        Ok(())
    })?;
    write_json(&set.path().join("summary.json"), &out_all)?;
    set.commit()?;
    Ok(out_all)
}

/// The LTCA of one pinion × wheel blank, its files written into `set`'s
/// staging folder; `t0` is when its work began.
fn blank_pair(
    ctx: &StageContext,
    pair: &LoadedPair,
    rs: &RollSurface,
    coast_rs: Option<&RollSurface>,
    supports: Option<&Supports>,
    set: &ResultSet,
    t0: Instant,
) -> anyhow::Result<BlankSummary> {
    let (scene, g, dir) = (ctx.scene, &ctx.g, ctx.dir.as_path());
    let sc = &scene.scene;
    let ([pb, wb], pc, sweep) = (pair.blanks, &pair.pc, pair.sweep);
    eprintln!(
        "ltca {pb:?}/{wb:?}: {} positions x {} torques, {} slices per pair",
        sweep.positions,
        sc.pinion_torque_nm.len(),
        sweep.slices
    );
    let res = crate::ltca::run_with_root_stress(ctx.fp(), rs, pc, &sweep, &sc.pinion_torque_nm)
        .with_context(|| format!("scene {}: LTCA, {wb:?} wheel blank", sc.name))?;
    let name = pair.name();
    // Written into the staging directory; the summaries name the
    // final paths.
    let odir = set.path().join(&name);
    let final_dir = set.dir().join(&name);
    std::fs::create_dir_all(&odir)?;
    write_outputs(&odir, &res, &sc.pinion_torque_nm)?;
    let (um, up) = mean_ptp(&res.iter().map(|p| p.utca_te).collect::<Vec<_>>());
    let bearings = match (supports, &sc.bearings) {
        (Some(sup), Some(bs)) => Some(
            bearing_loads(scene, g, pc, sup, bs, &sweep, &odir).with_context(|| {
                format!(
                    "scene {}: LTCA with bearing deflection, {wb:?} wheel blank",
                    sc.name
                )
            })?,
        ),
        _ => None,
    };
    let coast = match coast_rs {
        Some(crs) => Some(
            coast_loads(
                scene,
                g,
                dir,
                crs,
                pb,
                wb,
                &sweep,
                [&odir.join("coast"), &final_dir.join("coast")],
            )
            .with_context(|| format!("scene {}: coast-side LTCA, {wb:?} wheel blank", sc.name))?,
        ),
        None => None,
    };
    let summary = BlankSummary {
        pinion_blank: pb,
        wheel_blank: wb,
        positions: res.len(),
        step_deg: sc.rotation.step_deg,
        mesh_cycles: sc.rotation.mesh_cycles(wb),
        slices_per_pair: sweep.slices,
        friction_coefficient: sweep.friction,
        utca_te_mean_urad: um * 1e6,
        utca_te_ptp_urad: up * 1e6,
        stiffness_files: pair.plans.iter().map(|p| p.path.clone()).collect(),
        wall_s: t0.elapsed().as_secs_f64(),
        loads: load_summaries(&res, &sc.pinion_torque_nm),
        dir: final_dir,
        coast,
        bearings,
        ablation: ablation(ctx.fp(), rs, pc, &sweep, &sc.pinion_torque_nm)
            .with_context(|| format!("scene {}: LTCA ablation, {wb:?} wheel blank", sc.name))?,
        loaded_pair_rule: Some(loaded_pair_rule(&res)),
    };
    write_json(&odir.join("summary.json"), &summary)?;
    Ok(summary)
}

/// The loaded-pair rule's findings over a sweep.
pub fn loaded_pair_rule(res: &[PositionResult]) -> LoadedPairRule {
    let mut unchecked_pairs: Vec<i32> = res
        .iter()
        .flat_map(|p| p.neighbours.unchecked.iter().copied())
        .collect();
    unchecked_pairs.sort_unstable();
    unchecked_pairs.dedup();
    LoadedPairRule {
        positions: res.len(),
        with_candidates: res
            .iter()
            .filter(|p| !p.neighbours.pairs.is_empty())
            .count(),
        closing: res.iter().filter(|p| p.neighbours.closing).count(),
        unchecked: res
            .iter()
            .filter(|p| !p.neighbours.unchecked.is_empty())
            .count(),
        unchecked_pairs,
    }
}

/// The ablation study: the same sweep once per [`Variant::ABLATED`], each
/// with one of the element's modelling changes switched off (a fraction of
/// the stage's cost: the LTCA sweep is well under a second).
fn ablation(
    fp: &geometry::pair::FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
) -> Result<Vec<AblationVariant>, crate::SolverError> {
    Variant::ABLATED
        .iter()
        .map(|&v| {
            let res = run_variant(fp, rs, pc, sweep, torques, v)?;
            Ok(AblationVariant {
                variant: v.name().into(),
                change_off: v.change().into(),
                loads: load_summaries(&res, torques),
            })
        })
        .collect()
}

/// The edge-contact warnings and the per-torque lines of one blank pair's
/// summary, on stderr.
fn print_summary(scene: &str, summary: &BlankSummary) {
    let (pb, wb) = (summary.pinion_blank, summary.wheel_blank);
    warn_edge_contact(scene, &format!("{pb:?}/{wb:?} blanks"), &summary.loads);
    if let Some(c) = &summary.coast {
        warn_edge_contact(
            scene,
            &format!("{pb:?}/{wb:?} blanks, coast flanks"),
            &c.loads,
        );
    }
    if let Some(r) = &summary.loaded_pair_rule {
        eprintln!(
            "  loaded-pair rule: a pair beyond the active roll range lies below the largest loaded TE at {} of {} positions; it closes at {}{}",
            r.with_candidates,
            r.positions,
            r.closing,
            if r.unchecked > 0 {
                format!(
                    "; {} positions not checked (pairs {:?}: teeth not in the stiffness files)",
                    r.unchecked, r.unchecked_pairs
                )
            } else {
                String::new()
            }
        );
    }
    for l in &summary.loads {
        eprintln!(
            "  {:6.1} N·m: TE mean {:8.2} µrad, ptp {:7.2} µrad, {:.2} ms/position{}",
            l.torque_nm,
            l.te_mean_urad,
            l.te_ptp_urad,
            l.cpu_s_per_position * 1e3,
            match &l.root_stress {
                Some(r) => format!(
                    " (root stress {:.2} ms of it: largest tension pinion {:.1} MPa, wheel {:.1} MPa)",
                    l.root_stress_s_per_position * 1e3,
                    r.pinion.tension_mpa,
                    r.wheel.tension_mpa
                ),
                None => String::new(),
            }
        );
    }
    if let Some(c) = &summary.coast {
        for l in &c.loads {
            eprintln!(
                "  {:6.1} N·m on the coast flanks: TE mean {:8.2} µrad, ptp {:7.2} µrad",
                l.torque_nm, l.te_mean_urad, l.te_ptp_urad
            );
        }
    }
}

/// The scene's loads with the members on their compliant bearings
/// ([`crate::bearings::system_deflection`]; frictionless), `bearings.csv` written
/// into `odir`.
fn bearing_loads(
    scene: &LoadedScene,
    g: &PairGeometry,
    pc: &PairCompliance,
    supports: &crate::bearings::system_deflection::Supports,
    bs: &geometry::scene_bearings::BearingSettings,
    sweep: &Sweep,
    odir: &Path,
) -> anyhow::Result<Vec<formats::summaries::BearingLoadSummary>> {
    use crate::bearings::system_deflection::{
        bearing_csv, bearing_summaries, bearing_sweep, DeflectionSettings,
    };
    let sc = &scene.scene;
    let t = Instant::now();
    let m = &sc.misalignment;
    let rows = bearing_sweep(
        g,
        sc.loaded_flank,
        &sc.utca,
        pc,
        supports,
        (!m.is_zero()).then(|| m.poses(&g.data)),
        sweep,
        &sc.pinion_torque_nm,
        DeflectionSettings {
            slices: sweep.slices,
            tolerance_m: bs.tolerance_nm * 1e-9,
            max_iterations: bs.max_iterations,
        },
    )?;
    write_atomic(&odir.join("bearings.csv"), bearing_csv(&rows).as_bytes())?;
    let summaries = bearing_summaries(&rows, &sc.pinion_torque_nm);
    for l in &summaries {
        eprintln!(
            "  {:6.1} N·m on compliant bearings: TE mean {:8.2} µrad (rigid {:8.2}), ptp {:7.2} µrad (rigid {:7.2}), pinion apex moved up to {:.2} µm, {} iterations at most, settled to {:.2} nm at most",
            l.torque_nm, l.te_mean_urad, l.rigid_te_mean_urad, l.te_ptp_urad, l.rigid_te_ptp_urad, l.pinion_apex_displacement_um, l.max_iterations, l.max_change_nm
        );
    }
    eprintln!("  bearing deflection: {:.1} s", t.elapsed().as_secs_f64());
    Ok(summaries)
}

/// The scene's loads on the coast flanks of pinion blank `pb` × wheel
/// blank `wb` (see [`CoastSummary`]), written to `odir`
/// (`[where written, where it will be]`).
#[allow(clippy::too_many_arguments)]
fn coast_loads(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    crs: &geometry::utca::RollSurface,
    pb: Blank,
    wb: Blank,
    sweep: &Sweep,
    [odir, final_dir]: [&Path; 2],
) -> anyhow::Result<CoastSummary> {
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    let placement = g.opposite_placement(side);
    let (pc, [pin_plan, whl_plan]) = coast_compliance(scene, g, dir, pb, wb)?;
    let res = run_sweep(
        g.side(side.other()),
        crs,
        &pc,
        &coast_sweep(sweep, g, side),
        &sc.pinion_torque_nm,
    )?;
    std::fs::create_dir_all(odir)?;
    write_outputs(odir, &res, &sc.pinion_torque_nm)?;
    let (um, up) = mean_ptp(&res.iter().map(|p| p.utca_te).collect::<Vec<_>>());
    let summary = CoastSummary {
        backlash_urad: placement.backlash * 1e6,
        wheel_tooth_shift: placement.wheel_tooth_shift,
        utca_te_mean_urad: um * 1e6,
        utca_te_ptp_urad: up * 1e6,
        stiffness_files: vec![pin_plan.path, whl_plan.path],
        loads: load_summaries(&res, &sc.pinion_torque_nm),
        dir: final_dir.to_path_buf(),
    };
    write_json(&odir.join("summary.json"), &summary)?;
    Ok(summary)
}

/// Per-torque statistics over the sweep.
pub fn load_summaries(res: &[PositionResult], torques: &[f64]) -> Vec<LoadSummary> {
    let n = res.len().max(1) as f64;
    torques
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let te: Vec<f64> = res.iter().map(|p| p.loads[i].te).collect();
            let (m, ptp) = mean_ptp(&te);
            let solve: f64 = res.iter().map(|p| p.loads[i].solve_s).sum();
            let root: f64 = res.iter().map(|p| p.loads[i].root_stress_s).sum();
            let setup: f64 = res.iter().map(|p| p.geometry_s + p.assembly_s).sum();
            LoadSummary {
                torque_nm: t,
                te_mean_urad: m * 1e6,
                te_ptp_urad: ptp * 1e6,
                cpu_s_per_position: (setup + solve + root) / n,
                root_stress_s_per_position: root / n,
                solve_s_per_position: solve / n,
                max_pressure_mpa: res
                    .iter()
                    .map(|p| p.loads[i].max_pressure_pa)
                    .fold(0.0, f64::max)
                    * 1e-6,
                mesh_stiffness_mean_nm_per_rad: mean_ptp(
                    &res.iter()
                        .map(|p| p.loads[i].mesh_stiffness)
                        .filter(|k| k.is_finite())
                        .collect::<Vec<_>>(),
                )
                .0,
                max_pair_share: res
                    .iter()
                    .flat_map(|p| p.loads[i].pair_share.iter().copied())
                    .fold(0.0, f64::max),
                wheel_torque_mean_nm: res.iter().map(|p| p.loads[i].wheel_torque_nm).sum::<f64>()
                    / n,
                edge_contact: first_edge_contact(res, i),
                root_stress: formats::root_stress::summarize(
                    res.iter()
                        .map(|p| (p.rotation.to_degrees(), p.loads[i].root_stress.as_ref())),
                ),
            }
        })
        .collect()
}

/// The first position of `res` (sweep order) where the contact at torque
/// index `i` reaches an edge of the active flank.
pub fn first_edge_contact(res: &[PositionResult], i: usize) -> Option<EdgeContact> {
    res.iter().find_map(|p| {
        p.loads[i].edge.map(|h| EdgeContact {
            edge: h.edge,
            pinion_rotation_deg: p.rotation.to_degrees(),
            pair: h.pair,
            overshoot_mm: h.overshoot_m * 1e3,
        })
    })
}

/// A warning line on stderr for each load whose contact reaches an edge.
pub fn warn_edge_contact(scene: &str, what: &str, loads: &[LoadSummary]) {
    for l in loads {
        if let Some(e) = &l.edge_contact {
            eprintln!(
                "warning: scene {scene}, {what}: at {} N·m the contact reaches the {} (tooth pair {}, pinion rotation {:.3}°, {:.4} mm past it); the reduced model does not hold beyond the flank's edge",
                l.torque_nm,
                e.edge.name(),
                e.pair,
                e.pinion_rotation_deg,
                e.overshoot_mm
            );
        }
    }
}

fn write_outputs(dir: &Path, res: &[PositionResult], torques: &[f64]) -> anyhow::Result<()> {
    let mut te = format!("{PINION_ROTATION_DEG},{UTCA_TE_URAD}");
    for &t in torques {
        write!(te, ",{}", te_at_urad(t))?;
    }
    te.push('\n');
    // The torque driving the wheel (normal and friction forces).
    let mut wheel = String::from("pinion_rotation_deg");
    for t in torques {
        write!(wheel, ",wheel_torque_{t}nm_nm")?;
    }
    wheel.push('\n');
    let mut pairs = String::from("torque_nm,pinion_rotation_deg,pair,force_n,torque_share\n");
    let mut slices = String::from(
        "torque_nm,pinion_rotation_deg,pair,xi,eta,force_n,line_load_n_per_mm,pressure_mpa,half_width_mm\n",
    );
    for p in res {
        let deg = p.rotation.to_degrees();
        write!(te, "{deg:.4},{:.5}", p.utca_te * 1e6)?;
        write!(wheel, "{deg:.4}")?;
        for l in &p.loads {
            write!(wheel, ",{:.6}", l.wheel_torque_nm)?;
        }
        wheel.push('\n');
        for (i, l) in p.loads.iter().enumerate() {
            write!(te, ",{:.5}", l.te * 1e6)?;
            for (k, &(j, f)) in l.pair_force.iter().enumerate() {
                writeln!(
                    pairs,
                    "{},{deg:.4},{j},{f:.6},{:.6}",
                    torques[i], l.pair_share[k]
                )?;
            }
            for s in &l.slices {
                writeln!(
                    slices,
                    "{},{deg:.4},{},{:.5},{:.5},{:.6},{:.6},{:.3},{:.5}",
                    torques[i],
                    s.pair,
                    s.xi,
                    s.eta,
                    s.force_n,
                    s.line_load_n_per_m * 1e-3,
                    s.pressure_pa * 1e-6,
                    s.half_width_m * 1e3
                )?;
            }
        }
        te.push('\n');
    }
    write_atomic(&dir.join("te.csv"), te.as_bytes())?;
    write_atomic(&dir.join("pairs.csv"), pairs.as_bytes())?;
    write_atomic(&dir.join("wheel_torque.csv"), wheel.as_bytes())?;
    write_atomic(&dir.join("slices.csv"), slices.as_bytes())?;
    let fillets = res.iter().flat_map(|p| {
        p.loads.iter().zip(torques).filter_map(move |(l, &t)| {
            l.root_stress
                .as_ref()
                .map(|r| (p.rotation.to_degrees(), t, r))
        })
    });
    if let Some(csv) = formats::root_stress::fillets_csv(fillets) {
        write_atomic(&dir.join("root_stress.csv"), csv.as_bytes())?;
    }
    write_h5(&dir.join("ltca.h5"), res, torques)
}

/// Sweep arrays as HDF5 (written to a temporary file, then renamed).
fn write_h5(path: &Path, res: &[PositionResult], torques: &[f64]) -> anyhow::Result<()> {
    formats::output::write_via(path, |tmp| write_h5_to(tmp, res, torques))
}

fn write_h5_to(tmp: &Path, res: &[PositionResult], torques: &[f64]) -> anyhow::Result<()> {
    let np = res.len();
    let nl = torques.len();
    let per_load = |f: &dyn Fn(&crate::ltca::PositionLoad) -> f64| -> Vec<f64> {
        (0..nl)
            .flat_map(|i| res.iter().map(move |p| (i, p)))
            .map(|(i, p)| f(&p.loads[i]))
            .collect()
    };
    {
        let f = stiffness_file::h5().create(tmp)?;
        let put = |name: &str, shape: Vec<usize>, v: &[f64], units: &str| {
            stiffness_file::write_dataset(&f, name, &shape, v, units)
        };
        put("torque", vec![nl], torques, "N m")?;
        put(
            "pinion_rotation",
            vec![np],
            &res.iter().map(|p| p.rotation).collect::<Vec<_>>(),
            "rad",
        )?;
        put(
            "utca_te",
            vec![np],
            &res.iter().map(|p| p.utca_te).collect::<Vec<_>>(),
            "rad",
        )?;
        put("te", vec![nl, np], &per_load(&|l| l.te), "rad")?;
        put(
            "max_pressure",
            vec![nl, np],
            &per_load(&|l| l.max_pressure_pa),
            "Pa",
        )?;
        put(
            "mesh_stiffness",
            vec![nl, np],
            &per_load(&|l| l.mesh_stiffness),
            "N m/rad",
        )?;
        f.close()?;
    }
    Ok(())
}
