//! The line-load check of the reduced model's compliance split: a
//! Hertzian line load on one pinion tooth, solved on a fine FE mesh, against
//! the reduced-order prediction global FE + Weber–Banaschek.
//!
//! The load runs along the loaded flank of tooth 0 at a fixed profile
//! parameter η₀ (a profile row of the contact grid) over the whole active
//! face width. Across the line it is a Hertz pressure of half-width b and
//! line load q:
//!
//!   p(s) = 2q/(πb) · √(1 − s²/b²),   |s| < b,
//!
//! with s the distance from the line along the flank, pressed along the
//! flank's inward normal. The fine-mesh approach is the normal displacement
//! (into the tooth) of the line's surface points at the grid columns, the
//! bore clamped as in the stiffness files.
//!
//! The reduced model puts the same load on the grid: the force q · Lⱼ of
//! column j's stretch of line at grid point (j, η₀), and predicts the
//! approach at grid point j as
//!
//!   wⱼ = Σₖ G(k → j) q Lₖ + w_WB(q, b, hⱼ),
//!
//! G the stiffness file's global field (total − local) and w_WB the
//! half-plane approach to the stored depth hⱼ
//! ([`solver::element::weber_banaschek::body_approach`]).

use crate::reference::contact_surface::{cross, dot, norm, sub, MasterSurface};
use fem::{tri6, TetMesh};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// The load line: points C(ξ) along the flank at fixed η₀ with their
/// outward normals and the unit profile direction in the tangent plane.
#[derive(Debug, Clone)]
pub struct LoadLine {
    pub points: Vec<[f64; 3]>,
    pub normals: Vec<[f64; 3]>,
    /// Unit vector in the tangent plane, normal to the line (towards
    /// increasing η).
    pub across: Vec<[f64; 3]>,
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = norm(a);
    [a[0] / n, a[1] / n, a[2] / n]
}

impl LoadLine {
    /// A line through `points` (at least two, ordered along it) on a surface
    /// with outward `normals`; the across direction is n × t, flipped to
    /// point along `towards` (e.g. the surface's ∂x/∂η).
    pub fn new(points: Vec<[f64; 3]>, normals: Vec<[f64; 3]>, towards: [f64; 3]) -> LoadLine {
        let n = points.len();
        assert!(n >= 2 && normals.len() == n, "a load line needs two points");
        let across = (0..n)
            .map(|i| {
                let t = sub(points[(i + 1).min(n - 1)], points[i.saturating_sub(1)]);
                let a = unit(cross(normals[i], unit(t)));
                if dot(a, towards) < 0.0 {
                    a.map(|c| -c)
                } else {
                    a
                }
            })
            .collect();
        LoadLine {
            points,
            normals,
            across,
        }
    }

    /// Arc length of the line.
    pub fn length(&self) -> f64 {
        self.points.windows(2).map(|w| norm(sub(w[1], w[0]))).sum()
    }

    /// Signed distance s of `x` from the line across it, and the inward
    /// normal there; None beyond the line's ends.
    pub fn across_distance(&self, x: [f64; 3]) -> Option<(f64, [f64; 3])> {
        // (distance², segment, raw parameter, across distance, inward normal)
        let mut best: Option<(f64, usize, f64, f64, [f64; 3])> = None;
        for (k, w) in self.points.windows(2).enumerate() {
            let d = sub(w[1], w[0]);
            let raw = dot(sub(x, w[0]), d) / dot(d, d);
            let t = raw.clamp(0.0, 1.0);
            let p = [w[0][0] + t * d[0], w[0][1] + t * d[1], w[0][2] + t * d[2]];
            let r = sub(x, p);
            let dist2 = dot(r, r);
            if best.is_none_or(|b| dist2 < b.0) {
                let mix = |a: [f64; 3], b: [f64; 3]| {
                    unit([
                        a[0] + t * (b[0] - a[0]),
                        a[1] + t * (b[1] - a[1]),
                        a[2] + t * (b[2] - a[2]),
                    ])
                };
                let across = mix(self.across[k], self.across[k + 1]);
                let normal = mix(self.normals[k], self.normals[k + 1]);
                best = Some((dist2, k, raw, dot(r, across), normal.map(|c| -c)));
            }
        }
        let (_, k, raw, s, inward) = best?;
        let last = self.points.len() - 2;
        if (k == 0 && raw < 0.0) || (k == last && raw > 1.0) {
            return None; // beyond the toe or heel end
        }
        Some((s, inward))
    }
}

/// Hertz pressure of line load `q` and half-width `b` at distance `s`.
pub fn hertz_pressure(q: f64, b: f64, s: f64) -> f64 {
    let r = 1.0 - (s / b).powi(2);
    if r <= 0.0 {
        0.0
    } else {
        2.0 * q / (std::f64::consts::PI * b) * r.sqrt()
    }
}

/// Consistent nodal forces (dof 3 · node + component, value) of the Hertz
/// strip along `line` on the faces `faces`, and the applied force ∫ p dA
/// (the sum of the force magnitudes; the vector sum is smaller on a twisted
/// flank, whose normal turns along the line). Each face that the strip
/// reaches is integrated on `sub`² sub-triangles with the 6-point rule, so
/// that the strip's square-root edges are resolved inside the element.
pub fn strip_forces(
    mesh: &TetMesh,
    faces: &[[usize; 6]],
    line: &LoadLine,
    q: f64,
    b: f64,
    sub_div: usize,
) -> (Vec<(usize, f64)>, f64) {
    let mut acc: std::collections::BTreeMap<usize, f64> = Default::default();
    let mut applied = 0.0;
    let rule = tri6::dunavant6();
    let n = sub_div.max(1);
    for f in faces {
        let x = f.map(|i| mesh.nodes[i]);
        let size = (1..6).map(|k| norm(sub(x[0], x[k]))).fold(0.0, f64::max);
        match line.across_distance(x[0]) {
            Some((s, _)) if s.abs() <= b + 2.0 * size => {}
            // Beyond an end: the face may still straddle it.
            None if line.across_distance(x[1]).is_some()
                || line.across_distance(x[2]).is_some() => {}
            _ => continue,
        }
        let mut fe = [[0.0; 3]; 6];
        // Sub-triangles of the reference triangle: n² of them, each mapped
        // affinely from the reference triangle (corners a, b, c).
        for i in 0..n {
            for j in 0..n - i {
                let h = 1.0 / n as f64;
                let (s0, t0) = (i as f64 * h, j as f64 * h);
                let mut tris = vec![[[s0, t0], [s0 + h, t0], [s0, t0 + h]]];
                if i + j + 1 < n {
                    tris.push([[s0 + h, t0], [s0 + h, t0 + h], [s0, t0 + h]]);
                }
                for [a, bb, c] in tris {
                    let jac =
                        ((bb[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (bb[1] - a[1])).abs();
                    for &(st, w) in &rule {
                        let p = [
                            a[0] + st[0] * (bb[0] - a[0]) + st[1] * (c[0] - a[0]),
                            a[1] + st[0] * (bb[1] - a[1]) + st[1] * (c[1] - a[1]),
                        ];
                        let (pt, nn) = tri6::point_and_normal(&x, p);
                        let Some((s, inward)) = line.across_distance(pt) else {
                            continue;
                        };
                        let pr = hertz_pressure(q, b, s);
                        if pr == 0.0 {
                            continue;
                        }
                        let da = norm(nn);
                        applied += w * jac * da * pr;
                        let nshape = tri6::shape(p);
                        for (k, fk) in fe.iter_mut().enumerate() {
                            for c in 0..3 {
                                fk[c] += w * jac * da * nshape[k] * pr * inward[c];
                            }
                        }
                    }
                }
            }
        }
        for (&node, fk) in f.iter().zip(&fe) {
            for (c, &v) in fk.iter().enumerate() {
                if v != 0.0 {
                    *acc.entry(3 * node + c).or_default() += v;
                }
            }
        }
    }
    (acc.into_iter().collect(), applied)
}

/// How far from the flank faces a point of the load line may lie (the
/// quadratic faces' departure from the generated flank, with margin), m.
const ON_FACE_REACH: f64 = 1e-4;

/// The displacement `u` (3 per node) interpolated at the surface point
/// `p` of `surface` (its nearest face), projected on `dir`.
pub fn surface_value(
    surface: &MasterSurface,
    u: &[f64],
    p: [f64; 3],
    dir: [f64; 3],
) -> Option<f64> {
    let pr = surface.project(p, ON_FACE_REACH)?;
    let nsh = tri6::shape(pr.st);
    Some(
        surface.faces[pr.face]
            .iter()
            .zip(nsh)
            .map(|(&node, w)| w * (0..3).map(|c| dir[c] * u[3 * node + c]).sum::<f64>())
            .sum(),
    )
}

/// One half-width's comparison.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoadCase {
    pub half_width_mm: f64,
    /// Fine-mesh elements across the strip (2b over the mean flank element
    /// size along the profile).
    pub elements_across: f64,
    /// The applied force ∫ p dA over q · L (1 when the strip lies on the
    /// meshed flank and is integrated exactly).
    pub applied_load_ratio: f64,
    /// Per compared grid column: ξ, fine FE approach, global part, WB part,
    /// reduced prediction (µm), and the difference (%).
    pub xi: Vec<f64>,
    pub fe_um: Vec<f64>,
    pub global_um: Vec<f64>,
    pub weber_banaschek_um: Vec<f64>,
    pub reduced_um: Vec<f64>,
    pub difference_pct: Vec<f64>,
    pub mean_abs_difference_pct: f64,
    pub max_abs_difference_pct: f64,
}

/// The reduced model's approach at the grid columns of row `row`: the
/// global field `global(k, j)` (load at column k, response at column j)
/// under forces `forces[k]`, plus `wb[j]`.
pub fn reduced_prediction(
    global: impl Fn(usize, usize) -> f64,
    forces: &[f64],
    wb: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let g: Vec<f64> = (0..forces.len())
        .map(|j| {
            forces
                .iter()
                .enumerate()
                .map(|(k, f)| global(k, j) * f)
                .sum()
        })
        .collect();
    let total = g.iter().zip(wb).map(|(a, b)| a + b).collect();
    (g, total)
}

/// What `validate line-load` solves.
#[derive(Debug, Clone)]
pub struct LineLoadStudy {
    /// Fine mesh levels (medium, reference).
    pub levels: Vec<String>,
    /// Hertz half-widths, m.
    pub half_widths: Vec<f64>,
    /// Line load, N/m (the comparison is linear in it).
    pub q: f64,
    /// Profile row of the contact grid the line runs along (default: the
    /// middle row).
    pub row: Option<usize>,
    /// Grid columns left out at each end (toe and heel) in the statistics.
    pub end_columns: usize,
}

/// One fine mesh level's comparison.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoadLevel {
    pub level: String,
    pub mesh: String,
    pub mesh_sha256: String,
    pub dofs: usize,
    pub factor_s: f64,
    /// Length of the load line that lies on the meshed flank, to the
    /// line's sampling (ten points per grid column), mm.
    pub line_on_mesh_mm: f64,
    /// Mean flank element size along the profile, mm.
    pub profile_element_mm: f64,
    pub cases: Vec<LineLoadCase>,
}

/// The study's result (`out/<scene>/reference/line_load.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoad {
    pub member: String,
    pub flank: String,
    pub stiffness_file: String,
    /// SHA-256 of the stiffness file's mesh (the reduced level's).
    pub stiffness_mesh_sha256: String,
    pub line_load_n_per_m: f64,
    pub profile_row: usize,
    pub eta: f64,
    pub line_length_mm: f64,
    /// Columns compared in the statistics (the others lie within
    /// `end_columns` of the toe or heel).
    pub compared_columns: Vec<usize>,
    pub levels: Vec<LineLoadLevel>,
}

/// Runs the study on the scene's standard pinion: its reduced-level
/// stiffness file against its fine meshes.
pub fn run(
    scene: &geometry::scene::LoadedScene,
    meshes: &std::path::Path,
    out: &std::path::Path,
    study: &LineLoadStudy,
) -> anyhow::Result<LineLoad> {
    use anyhow::Context;
    use geometry::design::Member;
    let sc = &scene.scene;
    let g = geometry::pair::PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let side = sc.loaded_flank;
    let flank = g.flank(Member::Pinion, side);
    let flank_name = side.flank_name(Member::Pinion);
    let material = g.data.member(Member::Pinion).material();
    let dir = meshes.join(&sc.name);
    // The standard pinion's stiffness file, checked against the scene as
    // the solver checks it (manifest, config, hash).
    let (blank, level) = (
        geometry::scene::Blank::Standard,
        formats::paths::MeshLevel::Reduced,
    );
    let plan = formats::stiffness_plan::plan(scene, &g, &dir, Member::Pinion, blank, level, side)?;
    let data = formats::stiffness_plan::check(scene, &g, &dir, &plan, Member::Pinion, blank, level)
        .with_context(|| {
            format!(
                "scene {}: stiffness file {}; run `preprocess stiffness {}`",
                sc.name,
                plan.path.display(),
                scene.path.display()
            )
        })?;
    let (np, nf) = (data.grid_profile, data.grid_face);
    let row = study.row.unwrap_or(np / 2);
    if row >= np {
        anyhow::bail!(
            "--row {row}: the grid has {np} profile rows (0..{})",
            np - 1
        );
    }
    if 2 * study.end_columns >= nf {
        anyhow::bail!(
            "--end-columns {}: leaves no column of the {nf} to compare",
            study.end_columns
        );
    }
    let o0 = data
        .offsets
        .iter()
        .position(|&o| o == 0)
        .context("stiffness file has no response on the loaded tooth")?;
    let eta0 = data.eta[row];
    // The line, sampled at column boundaries and between them.
    let per_col = 10;
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
    let profile_len: f64 = (0..100)
        .map(|k| {
            let a = flank.at_unit(0.5, k as f64 / 100.0).map(|p| p.pos);
            let b = flank.at_unit(0.5, (k + 1) as f64 / 100.0).map(|p| p.pos);
            a.and_then(|a| b.map(|b| norm(sub(b, a))))
        })
        .sum::<Result<f64, _>>()?;
    let idx = |j: usize| j * np + row;
    let cols: Vec<usize> = (study.end_columns..nf - study.end_columns).collect();
    let col_points: Vec<([f64; 3], [f64; 3])> = (0..nf)
        .map(|j| {
            let p = flank.at_unit(data.xi[j], eta0)?;
            Ok((p.pos, p.normal.map(|c| -c)))
        })
        .collect::<Result<_, geometry::error::GeometryError>>()?;
    let forces: Vec<f64> = col_len.iter().map(|l| study.q * l).collect();
    let mut levels = Vec::new();
    for level in &study.levels {
        let elements = match level.as_str() {
            "reduced" => sc.mesh.reduced_order,
            "medium" => sc.mesh.medium(),
            "reference" => sc.mesh.reference,
            other => anyhow::bail!("--levels: unknown level {other} (reduced, medium, reference)"),
        };
        let path = formats::paths::msh(
            &dir,
            &formats::paths::stem_named(Member::Pinion, geometry::scene::Blank::Standard, level),
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
        let line_on_mesh: f64 = pts
            .windows(2)
            .zip(on_mesh.windows(2))
            .filter(|(_, o)| o[0] && o[1])
            .map(|(w, _)| norm(sub(w[1], w[0])))
            .sum();
        let mut cases = Vec::new();
        for &b in &study.half_widths {
            let (f, applied) = strip_forces(&body.mesh, faces, &line, study.q, b, 8);
            let mut full = vec![0.0; 3 * body.mesh.nodes.len()];
            for &(d, v) in &f {
                full[d] = v;
            }
            let u = dofs.expand(&factor.solve(&dofs.restrict(&full)));
            let fe: Vec<f64> = cols
                .iter()
                .map(|&j| {
                    let (p, inward) = col_points[j];
                    surface_value(&surface, &u, p, inward)
                        .with_context(|| format!("column {j}: point not on the flank mesh"))
                })
                .collect::<anyhow::Result<_>>()?;
            let wb: Vec<f64> = (0..nf)
                .map(|j| {
                    solver::element::weber_banaschek::body_approach(
                        study.q,
                        b,
                        data.depth_h[idx(j)],
                        material,
                    )
                })
                .collect();
            let (glob, red) =
                reduced_prediction(|k, j| data.global_at(0, o0, idx(k), idx(j)), &forces, &wb);
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
                mean_abs_difference_pct: diff.iter().map(|d| d.abs()).sum::<f64>()
                    / diff.len() as f64,
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
            cases.push(case);
        }
        levels.push(LineLoadLevel {
            level: level.clone(),
            mesh: path.display().to_string(),
            mesh_sha256: preprocess::stiffness_stage::sha256_file(&path)?,
            dofs: dofs.n_free(),
            factor_s,
            line_on_mesh_mm: line_on_mesh * 1e3,
            profile_element_mm: profile_len / elements.profile as f64 * 1e3,
            cases,
        });
    }
    let result = LineLoad {
        member: "pinion".into(),
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
    // Kept beside the reference sweep, recorded with its checksum
    // (formats::added_files); valid whatever sweep is committed there.
    let target = out.join(&sc.name).join("reference");
    let lock =
        formats::result_set::RunLock::shared(&target, &format!("validate line-load {}", sc.name))?;
    formats::added_files::add_json(
        &lock,
        "line_load.json",
        &result,
        formats::added_files::Dependence::Beside,
    )?;
    Ok(result)
}

impl LineLoad {
    /// Whether the meshes under `scene_meshes` are still the ones the study
    /// ran on.
    pub fn current(&self, scene_meshes: &std::path::Path) -> bool {
        let same = |level: &str, hash: &str| {
            let stem = formats::paths::stem_named(
                geometry::design::Member::Pinion,
                geometry::scene::Blank::Standard,
                level,
            );
            preprocess::stiffness_stage::sha256_file(&formats::paths::msh(scene_meshes, &stem))
                .is_ok_and(|h| h == hash)
        };
        same("reduced", &self.stiffness_mesh_sha256)
            && self.levels.iter().all(|l| same(&l.level, &l.mesh_sha256))
    }

    /// The report's section.
    pub fn markdown(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "\n## Line load: global FE + Weber–Banaschek against fine-mesh FE\n"
        );
        let _ = writeln!(
            s,
            "A Hertzian line load (q = {:.0} N/mm, half-width b) along the {} flank of pinion tooth 0 at profile row {} (η = {:.3}) over the whole face width ({:.1} mm), bore clamped (`validate line-load`). Fine-mesh FE: the normal approach of the line's surface points at the grid columns. Reduced model: the stiffness file's global field (total − local, reduced level) under the column forces q·L plus the Weber–Banaschek approach to the stored depth h. Compared on columns {}..={} (the end columns, where the plane-strain WB term does not hold, left out). The project's bound is 3 %.\n",
            self.line_load_n_per_m * 1e-3,
            self.flank,
            self.profile_row,
            self.eta,
            self.line_length_mm,
            self.compared_columns.first().unwrap_or(&0),
            self.compared_columns.last().unwrap_or(&0),
        );
        let _ = writeln!(s, "| FE mesh | dofs | flank element, mm | b, mm | elements across 2b | FE approach, µm (mid column) | global + WB, µm | of which WB | mean \\|diff\\| % | max \\|diff\\| % |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
        for l in &self.levels {
            for c in &l.cases {
                let mid = c.fe_um.len() / 2;
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.3} | {:.3} | {:.1} | {:.3} | {:.3} | {:.3} | {:.2} | {:.2} |",
                    l.level,
                    l.dofs,
                    l.profile_element_mm,
                    c.half_width_mm,
                    c.elements_across,
                    c.fe_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.reduced_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.weber_banaschek_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.mean_abs_difference_pct,
                    c.max_abs_difference_pct
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fem::structured::{faces_where, mapped_block};

    fn straight_line(y: f64, z: f64, len: f64) -> LoadLine {
        let pts: Vec<[f64; 3]> = (0..=40).map(|i| [len * i as f64 / 40.0, y, z]).collect();
        let nrm = vec![[0.0, 0.0, 1.0]; pts.len()];
        LoadLine::new(pts, nrm, [0.0, 1.0, 0.0])
    }

    /// Force balance: the consistent forces of the Hertz strip on a flat
    /// face add up to q · L along the inward normal, with no tangential
    /// resultant and the centre of pressure on the line.
    #[test]
    fn hertz_strip_resultant_equals_line_load_times_length() {
        let block = mapped_block([8, 8, 2], |p| [p[0] * 0.02, p[1] * 0.01, p[2] * 0.004]);
        let top = faces_where(&block, |p| p[2] > 1.0 - 1e-12);
        let line = straight_line(0.0043, 0.004, 0.015);
        let (q, b) = (2.0e5, 0.9e-3);
        let (f, applied) = strip_forces(&block.mesh, &top, &line, q, b, 8);
        assert!((applied / (q * 0.015) - 1.0).abs() < 2e-3, "{applied}");
        let mut res = [0.0; 3];
        let mut moment_y = 0.0;
        for &(d, v) in &f {
            res[d % 3] += v;
            if d % 3 == 2 {
                moment_y += v * block.mesh.nodes[d / 3][1];
            }
        }
        let expected = -q * 0.015;
        assert!(
            (res[2] / expected - 1.0).abs() < 2e-3,
            "{res:?} vs {expected}"
        );
        assert!(res[0].abs() < 1e-9 * q && res[1].abs() < 1e-9 * q);
        let y_c = moment_y / res[2];
        assert!((y_c - 0.0043).abs() < 1e-3 * b, "centre {y_c}");
    }

    /// A rigid translation read back at a surface point of a curved
    /// (mid-node displaced) quadratic face gives the translation.
    #[test]
    fn surface_value_reads_an_affine_field_exactly() {
        let block = mapped_block([3, 3, 2], |p| {
            [
                p[0] * 0.01,
                p[1] * 0.01,
                p[2] * 0.005 + 1e-4 * (3.0 * p[0]).sin(),
            ]
        });
        let top = faces_where(&block, |p| p[2] > 1.0 - 1e-12);
        let u: Vec<f64> = block
            .mesh
            .nodes
            .iter()
            .flat_map(|x| [1e-6, -2e-6, 3e-6 + 1e-4 * x[0]])
            .collect();
        let x: f64 = 0.0043;
        let p = [x, 0.0061, 0.005 + 1e-4 * (3.0 * x / 0.01).sin()];
        let surface = MasterSurface::new(block.mesh.nodes.clone(), top);
        let v = surface_value(&surface, &u, p, [0.0, 0.0, 1.0]);
        let v = v.expect("point on the top face");
        assert!((v - (3e-6 + 1e-4 * x)).abs() < 1e-9, "{v}");
    }

    /// Summation of the reduced model: global field times forces plus WB.
    #[test]
    fn reduced_prediction_adds_global_response_and_weber_banaschek() {
        let g = |k: usize, j: usize| 1.0 / (1.0 + (k as f64 - j as f64).abs());
        let (glob, tot) = reduced_prediction(g, &[1.0, 2.0], &[0.5, 0.25]);
        assert_eq!(glob, vec![1.0 + 1.0, 0.5 + 2.0]);
        assert_eq!(tot, vec![2.5, 2.75]);
    }
}
