//! One function per `validate` subcommand: its options checked, then the
//! library's stage or study, then a line or table on stdout.

use super::args::*;
use anyhow::Context;

pub fn report(
    ReportArgs {
        scene,
        flanks,
        reports,
        positions,
        out,
        meshes,
        readme,
    }: ReportArgs,
) -> anyhow::Result<()> {
    let made = validate::report::run::run(&validate::report::run::ReportInputs {
        scene: &scene,
        flanks: &flanks,
        reports: &reports,
        positions,
        out: out.as_deref(),
        meshes: &meshes,
        readme: &readme,
    })?;
    println!(
        "report of scene {}: {} loaded TE rows, {} figures; reports in {}{}",
        made.scene,
        made.loaded_te_rows,
        made.figures,
        reports.display(),
        if made.readme_updated {
            format!("; results table in {}", readme.display())
        } else {
            String::new()
        }
    );
    Ok(())
}

pub fn utca(
    UtcaArgs {
        scene,
        positions,
        out,
    }: UtcaArgs,
) -> anyhow::Result<()> {
    let input = preprocess::flank_stage::load_input(&scene)?;
    let c = validate::studies::utca_check::check(&input, positions).context("UTCA cross-check")?;
    println!("pinion rotation, deg | fast TE, urad | direct TE, urad | difference, urad");
    for r in &c.rows {
        println!(
            "{:20.2} | {:13.4} | {:15.4} | {:+16.4}",
            r.pinion_rotation_deg, r.fast_te_urad, r.direct_te_urad, r.difference_urad
        );
    }
    println!(
        "UTCA cross-check, scene {} ({} flank): {} positions, max |fast - direct| = {:.4} urad, smallest gap {:.2e} um; TE ptp {:.2} urad, mean {:.2} urad; {:.3} ms/position (direct search {:.1} ms)",
        c.name,
        c.side,
        c.rows.len(),
        c.max_abs_difference_urad,
        c.min_gap_um,
        c.fast_te_ptp_urad,
        c.fast_te_mean_urad,
        c.fast_ms_per_position,
        c.direct_ms_per_position
    );
    if let Some(dir) = out {
        validate::studies::utca_check::write_set(&c, &scene, &input.design_path, &dir)?;
        println!("written {}", dir.join("utca_check.json").display());
    }
    Ok(())
}

pub fn reference(
    ReferenceArgs {
        scene,
        meshes,
        out,
        level,
        penalty,
        penalty_check,
        start_band_um,
        search_gap_um,
        stride,
        stride_lightweight,
        block,
        compare_cache,
        shard,
        memory_gb,
        contact,
    }: ReferenceArgs,
) -> anyhow::Result<()> {
    if !["reduced", "medium", "reference"].contains(&level.as_str()) {
        anyhow::bail!("--level {level}: must be reduced, medium or reference");
    }
    check_block(block)?;
    let shard = shard.map(|s| parse_shard(&s)).transpose()?;
    let memory_bytes = memory_bytes(memory_gb)?;
    let mut settings = penalty_settings(penalty, penalty_check, start_band_um, search_gap_um)?;
    settings.passes = contact_passes(&contact)?;
    let scenes = scene
        .iter()
        .map(|p| geometry::scene::Scene::load(p))
        .collect::<Result<Vec<_>, _>>()?;
    let opt = validate::reference::reference_options::StageOptions {
        level,
        settings,
        stride,
        stride_lightweight,
        block,
        compare_cache,
        shard,
        memory_bytes,
    };
    if out.len() != 1 && out.len() != scenes.len() {
        anyhow::bail!(
            "--out: {} given for {} scenes; give one output root for all or one per scene",
            out.len(),
            scenes.len()
        );
    }
    let cases: Vec<(&geometry::scene::LoadedScene, &std::path::Path)> = scenes
        .iter()
        .enumerate()
        .map(|(i, s)| (s, out[i.min(out.len() - 1)].as_path()))
        .collect();
    validate::reference::reference_stage::run_scenes(&cases, &meshes, &opt)?;
    Ok(())
}

pub fn stress(
    StressArgs {
        scene,
        meshes,
        out,
        grid_scene,
        coast_scene,
    }: StressArgs,
) -> anyhow::Result<()> {
    let sc = geometry::scene::Scene::load(&scene)?;
    let s = validate::studies::stress::run(&sc, &meshes, &out, &grid_scene, &coast_scene)?;
    let n = |k: usize| s.cells.iter().filter(|c| c.outcome.class() == k).count();
    println!(
        "stress {}: {} cells, {} converged, {} refused, {} failed, {} skipped, {:.0} s",
        s.scene,
        s.cells.len(),
        n(0),
        n(1),
        n(2),
        n(3),
        s.wall_s
    );
    for d in &s.designs {
        match &d.edge_contact {
            Some(e) => println!(
                "  {}: edge contact from {} N·m ({}, pinion rotation {:.2}°)",
                d.design,
                d.edge_contact_torque_nm.unwrap_or(f64::NAN),
                e.edge.name(),
                e.pinion_rotation_deg
            ),
            None => println!(
                "  {}: no edge contact up to {} N·m",
                d.design, d.largest_load_nm
            ),
        }
    }
    Ok(())
}

pub fn stage_tradeoffs(
    StageTradeoffsArgs {
        scene,
        meshes,
        out,
        grid_scene,
    }: StageTradeoffsArgs,
) -> anyhow::Result<()> {
    let sc = geometry::scene::Scene::load(&scene)?;
    let s = validate::studies::stage_tradeoffs::run(&sc, &meshes, &out, &grid_scene)?;
    for st in &s.stages {
        println!(
            "{:24} {} points, {} not run: {}",
            st.stage,
            st.points.len(),
            st.not_run.len(),
            st.verdict()
        );
    }
    for (stage, why) in &s.missing {
        println!("{stage:24} not run: {why}");
    }
    println!("trade-off {}: {:.0} s", s.scene, s.wall_s);
    Ok(())
}

pub fn grid_convergence(
    GridConvergenceArgs {
        scene,
        meshes,
        out,
        grid_scene,
    }: GridConvergenceArgs,
) -> anyhow::Result<()> {
    if grid_scene.len() < 2 {
        anyhow::bail!(
            "--grid-scene: {} given; the extrapolation needs at least two finer grids beside the scene's own",
            grid_scene.len()
        );
    }
    let sc = geometry::scene::Scene::load(&scene)?;
    let r = validate::studies::grid_convergence::run(&sc, &meshes, &out, &grid_scene)?;
    for run in &r.runs {
        let loads: Vec<String> = run
            .loads
            .iter()
            .map(|(t, m, p)| format!("{t} N·m {m:.2} / {p:.2}"))
            .collect();
        println!(
            "{:>3} x {:<3} mean / ptp µrad: {}; {:.2} ms/position",
            run.grid[0],
            run.grid[1],
            loads.join(", "),
            run.cpu_s_per_position * 1e3
        );
    }
    Ok(())
}

pub fn tradeoff(
    TradeoffArgs {
        scene,
        meshes,
        out,
        slices,
    }: TradeoffArgs,
) -> anyhow::Result<()> {
    if let Some(n) = slices.iter().find(|n| !(4..=400).contains(*n)) {
        anyhow::bail!("--slices {n}: must lie in [4, 400] (as ltca.slices)");
    }
    let sc = geometry::scene::Scene::load(&scene)?;
    let pts = validate::studies::tradeoff::run(&sc, &meshes, &out, &slices)?;
    for p in &pts {
        println!(
            "{:11} {:3} slices {:5} N m: mean {:+.3} %, ptp {:+.2} %, {:.2} ms/position",
            p.wheel_blank,
            p.slices,
            p.torque_nm,
            p.mean_error_pct,
            p.ptp_error_pct,
            p.s_per_position * 1e3
        );
    }
    Ok(())
}

pub fn convergence(
    ConvergenceArgs {
        study: args,
        position,
        torque_nm,
    }: ConvergenceArgs,
) -> anyhow::Result<()> {
    // The torques given are checked before the scene is read (the
    // scene's own loads were checked when it loaded).
    if let Some(t) = torque_nm.iter().find(|t| !(t.is_finite() && **t > 0.0)) {
        anyhow::bail!("--torque-nm {t}: must be a positive number");
    }
    if let Some(w) = torque_nm.windows(2).find(|w| w[1] <= w[0]) {
        anyhow::bail!(
            "--torque-nm {}: each load once, in increasing order ({} follows {})",
            torque_nm
                .iter()
                .map(|t| t.to_string())
                .collect::<Vec<_>>()
                .join(","),
            w[1],
            w[0]
        );
    }
    let (sc, settings, block) = args.checked()?;
    let torques_nm = if torque_nm.is_empty() {
        sc.scene.pinion_torque_nm.clone()
    } else {
        torque_nm
    };
    let study = validate::studies::convergence::Study {
        levels: args.levels.clone(),
        position,
        torques_nm,
        settings,
        block,
    };
    let c = validate::studies::convergence::run(&sc, &args.meshes, &args.out, &study)?;
    for (i, t) in c.torques.iter().enumerate() {
        println!("{} N m:", t.torque_nm);
        for (l, e) in c.levels.iter().zip(&t.error_to_extrapolation_pct) {
            println!(
                "  {:9} {:3} x {:3}: TE {:.3} urad, {} vs extrapolation",
                l.level,
                l.profile_elements,
                l.face_elements,
                l.te_urad[i],
                e.map_or("-".into(), |e| format!("{e:+.3} %"))
            );
        }
        match (t.observed_order, t.extrapolated_te_urad) {
            (Some(p), Some(x)) => println!(
                "  observed order {p:.2}, extrapolated TE {x:.3} urad; reduced model {:.3} urad ({:+.3} %)",
                t.reduced_model_te_urad,
                t.reduced_model_error_pct.unwrap_or(f64::NAN)
            ),
            _ => println!(
                "  no monotone convergence over these levels: no extrapolation; reduced model {:.3} urad",
                t.reduced_model_te_urad
            ),
        }
    }
    Ok(())
}

pub fn mesh_stiffness(
    MeshStiffnessArgs {
        study: args,
        position,
        memory_gb,
        lumped_scene,
    }: MeshStiffnessArgs,
) -> anyhow::Result<()> {
    let memory_bytes = memory_bytes(memory_gb)?;
    let (sc, settings, block) = args.checked()?;
    let study = validate::studies::mesh_stiffness::StiffnessStudy {
        levels: args.levels.clone(),
        position,
        settings,
        block,
        memory_bytes,
        lumped_scene,
    };
    let s = validate::studies::mesh_stiffness::run(&sc, &args.meshes, &args.out, &study)?;
    println!(
        "mesh stiffness {}: position {} ({:.2} deg), {}",
        s.scene, s.position_index, s.pinion_rotation_deg, s.position_choice
    );
    for t in &s.torques {
        println!(
            "{} N m (levers {:.2} / {:.2} mm):",
            t.torque_nm,
            t.levers_m[0] * 1e3,
            t.levers_m[1] * 1e3
        );
        for m in &t.models {
            println!(
                "  {:4} {:9} {:2} x {:2}: k = dF/dd {:.4e} N/m, F/d {:.4e} N/m, vs finest FE {}",
                m.model,
                m.level,
                m.elements[0],
                m.elements[1],
                m.tangent_n_per_m,
                m.secant_n_per_m,
                m.tangent_vs_finest_fe_pct
                    .map_or("-".into(), |p| format!("{p:+.2} %"))
            );
        }
    }
    for (l, why) in s.fe_levels_skipped.iter().chain(&s.ltca_levels_skipped) {
        println!("  skipped {l}: {why}");
    }
    println!("{:.0} s, peak {:.2} GB", s.wall_s, s.peak_memory_gb);
    Ok(())
}

pub fn line_load(
    LineLoadArgs {
        scene,
        meshes,
        out,
        levels,
        half_width_mm,
        line_load_n_per_mm,
        row,
        end_columns,
        columns,
        response_tooth,
        member,
        blank,
    }: LineLoadArgs,
) -> anyhow::Result<()> {
    if let Some(b) = half_width_mm.iter().find(|b| !(b.is_finite() && **b > 0.0)) {
        anyhow::bail!("--half-width-mm {b}: must be a positive number");
    }
    if !(line_load_n_per_mm.is_finite() && line_load_n_per_mm > 0.0) {
        anyhow::bail!("--line-load-n-per-mm {line_load_n_per_mm}: must be a positive number");
    }
    let sc = geometry::scene::Scene::load(&scene)?;
    let study = validate::studies::line_load::LineLoadStudy {
        member: if member == "wheel" {
            geometry::design::Member::Wheel
        } else {
            geometry::design::Member::Pinion
        },
        blank: if blank == "lightweight" {
            geometry::scene::Blank::Lightweight
        } else {
            geometry::scene::Blank::Standard
        },
        levels,
        half_widths: half_width_mm.iter().map(|b| b * 1e-3).collect(),
        q: line_load_n_per_mm * 1e3,
        row,
        end_columns,
        loaded_columns: columns,
        response_offset: response_tooth,
    };
    let r = validate::studies::line_load::run(&sc, &meshes, &out, &study)?;
    for l in &r.levels {
        for c in &l.cases {
            println!(
                "{:9} b = {:.3} mm ({:.1} elements across): global FE + WB against FE: mean |{:.2}| %, max |{:.2}| % over columns {}..={}",
                l.level,
                c.half_width_mm,
                c.elements_across,
                c.mean_abs_difference_pct,
                c.max_abs_difference_pct,
                r.compared_columns[0],
                r.compared_columns[r.compared_columns.len() - 1]
            );
        }
    }
    Ok(())
}

pub fn calibrate(a: CalibrateArgs) -> anyhow::Result<()> {
    let scene = geometry::scene::Scene::load(&a.scene)?;
    let r = validate::studies::calibration::run(
        &scene,
        &a.meshes,
        &a.out.join("calibration"),
        &validate::studies::calibration::Targets {
            design: &a.design_out,
            scene: &a.scene_out,
            record: &a.record_out,
        },
    )?;
    println!("calibrated ease-off (base -> calibrated):");
    for v in r.ease_off.iter().chain(std::iter::once(&r.web)) {
        println!("  {:28} {:9.3} -> {:9.3}", v.name, v.base, v.calibrated);
    }
    println!("fitted rows (published NLFEA | model at the fit):");
    for f in &r.fitted_rows {
        println!(
            "  {:11} {:5} N·m {:4}: {:8.2} | {:8.2} urad",
            f.blank, f.load_nm, f.quantity, f.published_nlfea_urad, f.model_at_fit_urad
        );
    }
    println!(
        "{} + {} evaluations, {:.0} s CPU (this process); written {}, {}, {}",
        r.ease_off_evaluations,
        r.web_evaluations,
        r.cpu_s,
        a.design_out.display(),
        a.scene_out.display(),
        a.record_out.display()
    );
    Ok(())
}

pub fn export_inp(a: ExportInpArgs) -> anyhow::Result<()> {
    use geometry::scene::{Blank, MeshLevel};
    use validate::deck::{DeckContact, DeckOptions};
    if !(a.penalty.is_finite() && a.penalty > 0.0) {
        anyhow::bail!("--penalty {}: must be a positive number", a.penalty);
    }
    let sc = geometry::scene::Scene::load(&a.scene)?;
    let blank = |given: &Option<String>, listed: &[Blank], field: &str| -> anyhow::Result<Blank> {
        match given {
            None => listed
                .first()
                .copied()
                .with_context(|| format!("scene {}: no {field} blank", sc.scene.name)),
            Some(name) => listed
                .iter()
                .copied()
                .find(|b| b.name() == name)
                .with_context(|| {
                    format!(
                        "--{field}-blank {name}: the scene's {field} blanks are {:?}",
                        listed.iter().map(|b| b.name()).collect::<Vec<_>>()
                    )
                }),
        }
    };
    let opt = DeckOptions {
        level: MeshLevel::from_name(&a.level).with_context(|| {
            format!("--level {}: must be reduced, medium or reference", a.level)
        })?,
        pinion_blank: blank(&a.pinion_blank, &sc.scene.blanks.pinion, "pinion")?,
        wheel_blank: blank(&a.wheel_blank, &sc.scene.blanks.wheel, "wheel")?,
        position: a.position,
        contact: DeckContact::parse(&a.contact)?,
        penalty_factor: a.penalty,
    };
    let e = validate::deck::export::export(&sc, &a.meshes, &a.out, &opt, a.run, a.threads)?;
    println!(
        "deck {}: {} + {} C3D10 elements, {} + {} flank faces, start rotation {:.4e} rad",
        e.inp.display(),
        e.deck.bodies[0].elements.len(),
        e.deck.bodies[1].elements.len(),
        e.deck.bodies[0].flank.len(),
        e.deck.bodies[1].flank.len(),
        e.deck.start_rotation
    );
    if let Some(s) = &e.solution {
        println!(
            "CalculiX ({}, {:.1} s CPU): step 1 TE {:.4} urad, moment {:.4e} N m",
            s.contact, s.cpu_s, s.start_te_urad, s.start_moment_nm
        );
        for l in &s.loads {
            println!(
                "  {} N m: TE {:.4} urad (moment at the rotation node {:.4} N m)",
                l.torque_nm, l.te_urad, l.moment_nm
            );
        }
    }
    Ok(())
}
