//! `validate line-load`: the study's steps, from the member's
//! stiffness file and the load line to the comparison on every fine mesh
//! level and half-width, written beside the reference sweep.

use super::load_line::{strip_forces, surface_value, LoadLine, ON_FACE_REACH};
use super::{reduced_prediction, LineLoad, LineLoadCase, LineLoadLevel, LineLoadStudy};
use crate::reference::contact_surface::{norm, sub, MasterSurface};
use anyhow::Context;
use formats::stiffness_file::StiffnessData;
use formats::stiffness_plan::StiffnessPlan;
use geometry::design::Member;
use geometry::flank::Flank;
use geometry::scene::LoadedScene;

/// What every fine mesh level's comparison shares: the scene, the study,
/// the reduced model's stiffness file and the load line with its columns.
struct Setup<'a> {
    scene: &'a LoadedScene,
    study: &'a LineLoadStudy,
    /// The scene's meshes folder.
    dir: &'a std::path::Path,
    flank_name: &'a str,
    material: geometry::Material,
    data: &'a StiffnessData,
    /// The grid's profile row of the line, the solved index of tooth 0
    /// and the loaded tooth's offset index in the stiffness file.
    row: usize,
    s0: usize,
    o0: usize,
    line: &'a LoadLine,
    /// Compared columns, each column's point and inward normal, and the
    /// column forces q · Lⱼ.
    cols: &'a [usize],
    col_points: &'a [([f64; 3], [f64; 3])],
    forces: &'a [f64],
    /// Length of the flank's middle profile, m.
    profile_len: f64,
}

/// One fine mesh, read, clamped at the bore and factored.
struct FineMesh<'a> {
    level: &'a str,
    elements: geometry::scene::FlankElements,
    body: &'a preprocess::body_mesh::BodyMesh,
    faces: &'a [[usize; 6]],
    /// The responding tooth's flank.
    surface: &'a MasterSurface,
    dofs: &'a fem::Dofs,
    factor: &'a fem::Factor,
}

/// Runs the study on the scene's `study.member` with `study.blank`: its
/// reduced-level stiffness file against its fine meshes.
pub fn run(
    scene: &geometry::scene::LoadedScene,
    meshes: &std::path::Path,
    out: &std::path::Path,
    study: &LineLoadStudy,
) -> anyhow::Result<LineLoad> {
    let sc = &scene.scene;
    let g = geometry::pair::PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = sc.loaded_flank;
    let (member, blank) = (study.member, study.blank);
    let flank = g.flank(member, side);
    let flank_name = side.flank_name(member);
    let material = g.data.member(member).material();
    let dir = meshes.join(&sc.name);
    let (plan, data) = member_stiffness(scene, &g, &dir, member, blank)?;
    let (np, nf) = (data.grid_profile, data.grid_face);
    let row = compared_row(study, np, nf)?;
    let o0 = data
        .offsets
        .iter()
        .position(|&o| o == study.response_offset)
        .with_context(|| {
            format!(
                "the stiffness file holds no response on tooth offset {} (it holds {:?})",
                study.response_offset, data.offsets
            )
        })?;
    // On an axisymmetric body the solved tooth's data serve every tooth;
    // else tooth 0 must be among the solved ones.
    let s0 = match data.axisymmetric {
        true => Some(0),
        false => data.solved_teeth.iter().position(|&t| t == 0),
    };
    let s0 = s0.with_context(|| {
        format!(
            "the {} stiffness file ({} blank) does not solve tooth 0 (it solves {:?})",
            member.name(),
            blank.name(),
            data.solved_teeth
        )
    })?;
    let eta0 = data.eta[row];
    let (line, mut col_len) = load_line(flank, nf, eta0)?;
    let profile_len = profile_length(flank)?;
    let (line, cols) = match study.loaded_columns {
        None => (line, (study.end_columns..nf - study.end_columns).collect()),
        Some((a, b)) => {
            for (j, l) in col_len.iter_mut().enumerate() {
                if j < a || j > b {
                    *l = 0.0;
                }
            }
            (
                line.columns(a, b, LINE_POINTS_PER_COLUMN),
                (a..=b).collect::<Vec<usize>>(),
            )
        }
    };
    // The compared points on the responding tooth: tooth 0's turned by
    // its offset's pitches about the member axis.
    let turn = geometry::generation::rot_z(
        study.response_offset as f64 * std::f64::consts::TAU / data.teeth as f64,
    );
    let turned = |v: [f64; 3]| {
        let w = turn * nalgebra::Vector3::new(v[0], v[1], v[2]);
        [w[0], w[1], w[2]]
    };
    let col_points: Vec<([f64; 3], [f64; 3])> = (0..nf)
        .map(|j| {
            let p = flank.at_unit(data.xi[j], eta0)?;
            Ok((turned(p.pos), turned(p.normal.map(|c| -c))))
        })
        .collect::<Result<_, geometry::error::GeometryError>>()?;
    let forces: Vec<f64> = col_len.iter().map(|l| study.q * l).collect();
    let setup = Setup {
        scene,
        study,
        dir: &dir,
        flank_name,
        material,
        data: &data,
        row,
        s0,
        o0,
        line: &line,
        cols: &cols,
        col_points: &col_points,
        forces: &forces,
        profile_len,
    };
    let mut levels = Vec::new();
    for level in &study.levels {
        levels.push(level_comparison(&setup, level)?);
    }
    let result = LineLoad {
        member,
        blank,
        response_offset: study.response_offset,
        loaded_columns: study.loaded_columns,
        flank: flank_name.into(),
        stiffness_file: plan.path.display().to_string(),
        stiffness_mesh_sha256: preprocess::stiffness_stage::sha256_file(&formats::paths::msh(
            &dir,
            &plan.mesh_stem,
        ))?,
        line_load_n_per_m: study.q,
        profile_row: row,
        eta: eta0,
        line_length_mm: line.length() * 1e3,
        compared_columns: cols,
        levels,
    };
    add_beside_reference(out, &sc.name, &result)?;
    Ok(result)
}

/// The member's reduced-level stiffness file, checked against the scene as
/// the solver checks it (manifest, config, hash).
fn member_stiffness(
    scene: &LoadedScene,
    g: &geometry::pair::PairGeometry,
    dir: &std::path::Path,
    member: Member,
    blank: geometry::scene::Blank,
) -> anyhow::Result<(StiffnessPlan, StiffnessData)> {
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    let level = formats::paths::MeshLevel::Reduced;
    let plan = formats::stiffness_plan::plan(scene, g, dir, member, blank, level, side)?;
    let data = formats::stiffness_plan::check(scene, g, dir, &plan, member, blank, level).map_err(
        |e| {
            let mend = e
                .remedy()
                .advice(&scene.path, &scene.design_path, dir, level);
            anyhow::Error::new(e).context(format!(
                "scene {}: stiffness file {} cannot be used{mend}",
                sc.name,
                plan.path.display()
            ))
        },
    )?;
    Ok((plan, data))
}

/// The profile row of the line (`--row`, else the middle one), refused
/// outside the grid's `np` rows, or when `--end-columns` leaves none of the
/// `nf` columns to compare.
fn compared_row(study: &LineLoadStudy, np: usize, nf: usize) -> anyhow::Result<usize> {
    let row = study.row.unwrap_or(np / 2);
    if row >= np {
        anyhow::bail!(
            "--row {row}: the grid has {np} profile rows (0..{})",
            np - 1
        );
    }
    if let Some((a, b)) = study.loaded_columns {
        if b >= nf {
            anyhow::bail!(
                "--columns {a}-{b}: the grid has {nf} columns (0..{})",
                nf - 1
            );
        }
    } else if 2 * study.end_columns >= nf {
        anyhow::bail!(
            "--end-columns {}: leaves no column of the {nf} to compare",
            study.end_columns
        );
    }
    Ok(row)
}

/// Line points per grid column.
const LINE_POINTS_PER_COLUMN: usize = 10;

/// The load line at profile parameter `eta0`, sampled at the `nf` column
/// boundaries and ten points per column, and each column's length of it.
fn load_line(flank: &Flank, nf: usize, eta0: f64) -> anyhow::Result<(LoadLine, Vec<f64>)> {
    // The line, sampled at column boundaries and between them.
    let per_col = LINE_POINTS_PER_COLUMN;
    let m = per_col * nf;
    let mut pts = Vec::with_capacity(m + 1);
    let mut nrm = Vec::with_capacity(m + 1);
    for k in 0..=m {
        let p = flank.at_unit(k as f64 / m as f64, eta0)?;
        pts.push(p.pos);
        nrm.push(p.normal);
    }
    let towards = sub(
        flank.at_unit(0.5, eta0 + 0.01)?.pos,
        flank.at_unit(0.5, eta0)?.pos,
    );
    let line = LoadLine::new(pts, nrm, towards);
    let pts = &line.points;
    let col_len: Vec<f64> = (0..nf)
        .map(|j| {
            (j * per_col..(j + 1) * per_col)
                .map(|k| norm(sub(pts[k + 1], pts[k])))
                .sum()
        })
        .collect();
    Ok((line, col_len))
}

/// Length of the flank's middle profile (ξ = 0.5), summed over 100 chords, m.
fn profile_length(flank: &Flank) -> anyhow::Result<f64> {
    let profile_len: f64 = (0..100)
        .map(|k| {
            let a = flank.at_unit(0.5, k as f64 / 100.0).map(|p| p.pos);
            let b = flank.at_unit(0.5, (k + 1) as f64 / 100.0).map(|p| p.pos);
            a.and_then(|a| b.map(|b| norm(sub(b, a))))
        })
        .sum::<Result<f64, _>>()?;
    Ok(profile_len)
}

/// One fine mesh level's comparison: the mesh read, clamped and factored,
/// the line's length on it, and every half-width's case.
fn level_comparison(s: &Setup, level: &str) -> anyhow::Result<LineLoadLevel> {
    let (scene, study) = (s.scene, s.study);
    let sc = &scene.scene;
    let (dir, flank_name, material) = (s.dir, s.flank_name, s.material);
    let pts = &s.line.points;
    let elements = match level {
        "reduced" => sc.mesh.reduced_order,
        "medium" => sc.mesh.medium(),
        "reference" => sc.mesh.reference,
        other => anyhow::bail!("--levels: unknown level {other} (reduced, medium, reference)"),
    };
    let path = formats::paths::msh(
        dir,
        &formats::paths::stem_named(s.study.member, s.study.blank, level),
    );
    if !path.exists() {
        anyhow::bail!(
            "scene {}: no mesh {}; run `preprocess mesh {} --level {level}`",
            sc.name,
            path.display(),
            scene.path.display()
        );
    }
    eprintln!(
        "line load {level}: reading and factoring {}",
        path.display()
    );
    let body = preprocess::body_mesh::read(&path)
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let faces = body.group(&format!("tooth0_{flank_name}"));
    if faces.is_empty() {
        anyhow::bail!("{}: no face group tooth0_{flank_name}", path.display());
    }
    let t = std::time::Instant::now();
    let fem::ClampedBody { dofs, factor, .. } = fem::ClampedBody::new(
        &body.mesh,
        &preprocess::influence::fe_material(material),
        &fem::clamp_nodes(&body.group_nodes("bore")),
        fem::Factorization::Auto,
    )?;
    let factor_s = t.elapsed().as_secs_f64();
    let surface = MasterSurface::new(body.mesh.nodes.clone(), faces.to_vec());
    let on_mesh: Vec<bool> = pts
        .iter()
        .map(|&p| surface.project(p, ON_FACE_REACH).is_some())
        .collect();
    let responding = (study.response_offset).rem_euclid(s.data.teeth as i32);
    let response_faces = body.group(&format!("tooth{responding}_{flank_name}"));
    if response_faces.is_empty() {
        anyhow::bail!(
            "{}: no face group tooth{responding}_{flank_name} (the responding tooth is not refined at this level)",
            path.display()
        );
    }
    let response = MasterSurface::new(body.mesh.nodes.clone(), response_faces.to_vec());
    let line_on_mesh: f64 = pts
        .windows(2)
        .zip(on_mesh.windows(2))
        .filter(|(_, o)| o[0] && o[1])
        .map(|(w, _)| norm(sub(w[1], w[0])))
        .sum();
    let fine = FineMesh {
        level,
        elements,
        body: &body,
        faces,
        surface: &response,
        dofs: &dofs,
        factor: &factor,
    };
    let mut cases = Vec::new();
    for &b in &study.half_widths {
        cases.push(half_width_case(s, &fine, b)?);
    }
    Ok(LineLoadLevel {
        level: level.to_string(),
        mesh: path.display().to_string(),
        mesh_sha256: preprocess::stiffness_stage::sha256_file(&path)?,
        dofs: dofs.n_free(),
        factor_s,
        line_on_mesh_mm: line_on_mesh * 1e3,
        profile_element_mm: s.profile_len / elements.profile as f64 * 1e3,
        cases,
    })
}

/// The comparison at half-width `b` on one fine mesh: the strip's FE
/// approach at the compared columns against global FE + Weber–Banaschek.
fn half_width_case(s: &Setup, fine: &FineMesh, b: f64) -> anyhow::Result<LineLoadCase> {
    let (study, data, material) = (s.study, s.data, s.material);
    let (line, cols, col_points, forces) = (s.line, s.cols, s.col_points, s.forces);
    let (s0, o0, profile_len) = (s.s0, s.o0, s.profile_len);
    let (np, nf, row) = (data.grid_profile, data.grid_face, s.row);
    let idx = |j: usize| j * np + row;
    let (body, faces, surface) = (fine.body, fine.faces, fine.surface);
    let (dofs, factor, level, elements) = (fine.dofs, fine.factor, fine.level, fine.elements);
    let (f, applied) = strip_forces(&body.mesh, faces, line, study.q, b, 8);
    let mut full = vec![0.0; 3 * body.mesh.nodes.len()];
    for &(d, v) in &f {
        full[d] = v;
    }
    let u = dofs.expand(&factor.solve(&dofs.restrict(&full)));
    let fe: Vec<f64> = cols
        .iter()
        .map(|&j| {
            let (p, inward) = col_points[j];
            surface_value(surface, &u, p, inward)
                .with_context(|| format!("column {j}: point not on the flank mesh"))
        })
        .collect::<anyhow::Result<_>>()?;
    let wb: Vec<f64> = (0..nf)
        .map(|j| {
            if forces[j] == 0.0 || study.response_offset != 0 {
                return 0.0;
            }
            solver::element::weber_banaschek::body_approach(
                study.q,
                b,
                data.depth_h[idx(j)],
                material,
            )
        })
        .collect();
    let (glob, red) =
        reduced_prediction(|k, j| data.global_at(s0, o0, idx(k), idx(j)), forces, &wb);
    let diff: Vec<f64> = cols
        .iter()
        .zip(&fe)
        .map(|(&j, &w)| (red[j] / w - 1.0) * 100.0)
        .collect();
    let case = LineLoadCase {
        half_width_mm: b * 1e3,
        elements_across: 2.0 * b / (profile_len / elements.profile as f64),
        applied_load_ratio: applied / (study.q * line.length()),
        xi: cols.iter().map(|&j| data.xi[j]).collect(),
        fe_um: fe.iter().map(|w| w * 1e6).collect(),
        global_um: cols.iter().map(|&j| glob[j] * 1e6).collect(),
        weber_banaschek_um: cols.iter().map(|&j| wb[j] * 1e6).collect(),
        reduced_um: cols.iter().map(|&j| red[j] * 1e6).collect(),
        mean_abs_difference_pct: diff.iter().map(|d| d.abs()).sum::<f64>() / diff.len() as f64,
        max_abs_difference_pct: diff.iter().fold(0.0, |a, d| a.max(d.abs())),
        difference_pct: diff,
    };
    eprintln!(
        "line load {level}, b = {:.3} mm ({:.1} elements across): reduced - FE mean |{:.2}| %, max |{:.2}| %",
        case.half_width_mm,
        case.elements_across,
        case.mean_abs_difference_pct,
        case.max_abs_difference_pct
    );
    Ok(case)
}

/// Writes `line_load.json` beside the reference sweep of scene `name`,
/// recorded with its checksum (formats::added_files); valid whatever sweep
/// is committed there.
fn add_beside_reference(
    out: &std::path::Path,
    name: &str,
    result: &LineLoad,
) -> anyhow::Result<()> {
    let target = out.join(name).join("reference");
    let lock =
        formats::result_set::RunLock::shared(&target, &format!("validate line-load {name}"))?;
    formats::added_files::add_json(
        &lock,
        &super::file_name(result.member, result.blank, result.response_offset),
        result,
        formats::added_files::Dependence::Beside,
    )?;
    Ok(())
}
