//! The `preprocess flanks` stage: flank grids, UTCA, plots and summary of a
//! design or scene file, written into one output directory.

use crate::design::{load_pair, Member, PairData};
use crate::direct::contact_ellipse;
use crate::error::{GeometryError, InputError};
use crate::flank::Flank;
use crate::generation::Side;
use crate::output::write_json;
use crate::pair::{pinion_direction, FlankPair, PairGeometry};
use crate::plots;
use crate::scene::{Scene, UtcaSettings};
use crate::utca::{run, LineGrid, RollSurface, Utca};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What the stage needs from a design or scene file.
#[derive(Debug, Clone)]
pub struct FlankInput {
    pub name: String,
    pub design_path: PathBuf,
    pub pair: PairData,
    pub side: Side,
    pub utca: UtcaSettings,
}

impl Default for UtcaSettings {
    fn default() -> Self {
        UtcaSettings {
            step_deg: 0.1,
            mesh_cycles: 2.0,
            face_samples: 41,
            profile_samples: 41,
            marking_compound_um: 6.3,
            flank_grid_profile: 36,
            flank_grid_face: 76,
        }
    }
}

/// Reads a scene file (it has a `design` key) or a design file (drive side, default settings).
pub fn load_input(path: &Path) -> Result<FlankInput, InputError> {
    let text = std::fs::read_to_string(path).map_err(|e| InputError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let table: toml::Table = text
        .parse()
        .map_err(|e| InputError::parse(path, &text, &e))?;
    if table.contains_key("design") {
        let s = Scene::load(path)?;
        Ok(FlankInput {
            name: s.scene.name.clone(),
            design_path: s.design_path,
            pair: s.pair,
            side: s.scene.loaded_flank,
            utca: s.scene.utca,
        })
    } else {
        let pair = load_pair(path)?;
        Ok(FlankInput {
            name: pair.name.clone(),
            design_path: path.to_path_buf(),
            pair,
            side: Side::Drive,
            utca: UtcaSettings::default(),
        })
    }
}

/// Spiral and pressure angle of one flank at its mean point, degrees.
#[derive(Debug, Clone, Serialize)]
pub struct MeanPointAngles {
    pub side: &'static str,
    pub spiral_angle_deg: f64,
    pub normal_pressure_angle_deg: f64,
}

/// Mean-point angles by member ("pinion", "wheel") and flank ("concave", "convex").
pub type MeanPoint = BTreeMap<&'static str, BTreeMap<&'static str, MeanPointAngles>>;

/// A flank grid for meshing and contact: node (i face, k profile) at index i·n_profile + k.
#[derive(Debug, Clone, Serialize)]
pub struct FlankGrid {
    pub member: &'static str,
    pub flank: &'static str,
    pub side: &'static str,
    pub n_face: usize,
    pub n_profile: usize,
    pub cone_distance_mm: Vec<f64>,
    pub height_mm: Vec<f64>,
    /// Position in the member frame (axis = z, apex at the origin), m.
    pub position_m: Vec<[f64; 3]>,
    /// Outward unit normal, member frame.
    pub normal: Vec<[f64; 3]>,
    /// Principal curvatures (positive = convex), 1/m.
    pub curvature_1_per_m: Vec<[f64; 2]>,
    /// Principal directions, member frame.
    pub principal_directions: Vec<[[f64; 3]; 2]>,
    /// Surface of roll angles: pinion rotation of conjugate contact, deg.
    pub pinion_roll_deg: Vec<f64>,
    /// Ease-off (normal deviation from conjugate, + = material removed), µm.
    pub ease_off_um: Vec<f64>,
}

/// Samples a flank on a regular grid of normalised (ξ, η).
pub fn flank_grid(f: &Flank, n_face: usize, n_profile: usize) -> Result<FlankGrid, GeometryError> {
    let m = f.gen.member;
    let mut g = FlankGrid {
        member: m.name(),
        flank: f.gen.side.flank_name(m),
        side: f.gen.side.name(),
        n_face,
        n_profile,
        cone_distance_mm: vec![],
        height_mm: vec![],
        position_m: vec![],
        normal: vec![],
        curvature_1_per_m: vec![],
        principal_directions: vec![],
        pinion_roll_deg: vec![],
        ease_off_um: vec![],
    };
    let mut start = None;
    for i in 0..n_face {
        for k in 0..n_profile {
            let (l, d) = f.bounds.from_unit(
                i as f64 / (n_face - 1) as f64,
                k as f64 / (n_profile - 1) as f64,
            );
            let uv = match start {
                Some(s) => f.solve_ld_from(l, d, s).or_else(|_| f.solve_ld(l, d))?,
                None => f.solve_ld(l, d)?,
            };
            start = Some(uv);
            let p = f.eval_uv(uv[0], uv[1]);
            let c = f.curvature_uv(uv[0], uv[1]);
            g.cone_distance_mm.push(l * 1e3);
            g.height_mm.push(d * 1e3);
            g.position_m.push(p.pos);
            g.normal.push(p.normal);
            g.curvature_1_per_m.push(c.k);
            g.principal_directions.push(c.dir);
            g.pinion_roll_deg.push(p.pinion_roll.to_degrees());
            g.ease_off_um.push(p.ease_off * 1e6);
        }
    }
    Ok(g)
}

/// Contact point of the tooth in contact at one UTCA position.
#[derive(Debug, Clone, Serialize)]
pub struct PathPoint {
    pub pinion_rotation_deg: f64,
    pub tooth: i32,
    pub cone_distance_mm: f64,
    pub height_mm: f64,
    pub position_m: [f64; 3],
    /// Contact ellipse semi-axes for the marking-compound separation, mm.
    pub ellipse_semi_axes_mm: [f64; 2],
    /// Major-axis direction in the (cone distance, height) plane.
    pub ellipse_major_dir: [f64; 2],
}

/// UTCA results as written to `utca.json`.
#[derive(Debug, Clone, Serialize)]
pub struct UtcaReport {
    pub side: &'static str,
    pub convention: &'static str,
    pub mesh_cycle_deg: f64,
    pub step_deg: f64,
    pub contact_ratio: f64,
    pub te_ptp_urad: f64,
    pub te_mean_urad: f64,
    pub roll_range_deg: [f64; 2],
    pub pinion_rotation_deg: Vec<f64>,
    pub te_urad: Vec<f64>,
    /// Per tooth pair j: (pinion rotation deg, wheel lag µrad) while on its contact line.
    pub tooth_curves: Vec<(i32, Vec<(f64, f64)>)>,
    pub path: Vec<PathPoint>,
    pub marking_compound_um: f64,
}

/// Everything `summary.json` holds.
#[derive(Debug, Clone, Serialize)]
pub struct FlankSummary {
    pub name: String,
    pub design: String,
    pub loaded_flank: &'static str,
    pub mesh_cycle_deg: f64,
    pub crown_gear_teeth: f64,
    pub normal_backlash_mm: f64,
    pub mean_normal_thickness_mm: [f64; 2],
    pub mean_point: MeanPoint,
    pub utca: UtcaSummary,
    pub timing_s: Timing,
}

#[derive(Debug, Clone, Serialize)]
pub struct UtcaSummary {
    pub te_ptp_urad: f64,
    pub te_mean_urad: f64,
    pub contact_ratio: f64,
    pub positions: usize,
    pub ms_per_position: f64,
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct Timing {
    pub geometry: f64,
    pub flank_grids: f64,
    pub roll_surface: f64,
    pub utca: f64,
    pub ellipses: f64,
    pub plots: f64,
}

/// Tabulated surface of roll angles of a flank pair at the scene's sampling.
pub fn roll_surface(fp: &FlankPair, s: &UtcaSettings) -> Result<RollSurface, GeometryError> {
    RollSurface::new(
        fp,
        LineGrid {
            n_face: s.face_samples,
            n_profile: s.profile_samples,
        },
    )
}

/// UTCA over the scene's sweep, starting where tooth 0 enters the active region.
pub fn sweep(fp: &FlankPair, pair: &PairData, rs: &RollSurface, s: &UtcaSettings) -> Utca {
    let step = s.step_deg.to_radians();
    let n = (s.mesh_cycles * pair.mesh_cycle() / step).round() as usize + 1;
    run(
        fp,
        rs,
        fp.roll_range[0],
        step,
        n,
        pinion_direction(pair, fp.side),
    )
}

fn plot_err(e: plots::PlotError) -> GeometryError {
    GeometryError::Write {
        path: PathBuf::new(),
        message: e.to_string(),
    }
}

/// Runs the stage and writes `flanks.json`, `utca.json`, `summary.json` and SVG plots into `out`.
pub fn run_stage(input: &FlankInput, out: &Path) -> Result<FlankSummary, GeometryError> {
    let mut timing = Timing::default();
    let t = Instant::now();
    let g = PairGeometry::build(&input.pair, Some(&input.design_path))?;
    timing.geometry = t.elapsed().as_secs_f64();
    let pair = &g.data;

    let mut mean_point = MeanPoint::new();
    for m in [Member::Pinion, Member::Wheel] {
        for side in [Side::Drive, Side::Coast] {
            let (b, a) = g
                .flank(m, side)
                .spiral_and_pressure_angle(pair.mean_cone_distance, 0.0)?;
            mean_point.entry(m.name()).or_default().insert(
                side.flank_name(m),
                MeanPointAngles {
                    side: side.name(),
                    spiral_angle_deg: b.to_degrees(),
                    normal_pressure_angle_deg: a.to_degrees(),
                },
            );
        }
    }

    let t = Instant::now();
    let s = &input.utca;
    let mut grids = Vec::new();
    for m in [Member::Pinion, Member::Wheel] {
        for side in [Side::Drive, Side::Coast] {
            grids.push(flank_grid(
                g.flank(m, side),
                s.flank_grid_face,
                s.flank_grid_profile,
            )?);
        }
    }
    timing.flank_grids = t.elapsed().as_secs_f64();

    let fp = g.side(input.side);
    let t = Instant::now();
    let rs = roll_surface(fp, s)?;
    timing.roll_surface = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let u = sweep(fp, pair, &rs, s);
    timing.utca = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let report = utca_report(fp, pair, &u, s)?;
    timing.ellipses = t.elapsed().as_secs_f64();

    std::fs::create_dir_all(out).map_err(|e| GeometryError::Write {
        path: out.to_path_buf(),
        message: e.to_string(),
    })?;
    write_json(&out.join("flanks.json"), &grids)?;
    write_json(&out.join("utca.json"), &report)?;

    let t = Instant::now();
    write_plots(out, &g, &grids, &report, input.side).map_err(plot_err)?;
    timing.plots = t.elapsed().as_secs_f64();

    let summary = FlankSummary {
        name: input.name.clone(),
        design: input.design_path.display().to_string(),
        loaded_flank: input.side.name(),
        mesh_cycle_deg: pair.mesh_cycle().to_degrees(),
        crown_gear_teeth: pair.crown_teeth(),
        normal_backlash_mm: pair.normal_backlash() * 1e3,
        mean_normal_thickness_mm: [
            pair.normal_thickness(Member::Pinion) * 1e3,
            pair.normal_thickness(Member::Wheel) * 1e3,
        ],
        mean_point,
        utca: UtcaSummary {
            te_ptp_urad: report.te_ptp_urad,
            te_mean_urad: report.te_mean_urad,
            contact_ratio: report.contact_ratio,
            positions: u.te.len(),
            ms_per_position: timing.utca * 1e3 / u.te.len() as f64,
        },
        timing_s: timing,
    };
    write_json(&out.join("summary.json"), &summary)?;
    Ok(summary)
}

fn utca_report(
    fp: &FlankPair,
    pair: &PairData,
    u: &Utca,
    s: &UtcaSettings,
) -> Result<UtcaReport, GeometryError> {
    let start = u.pinion_angle[0];
    let rot = |phi: f64| (phi - start).abs().to_degrees();
    let dir = pinion_direction(pair, fp.side);
    let mut curves: BTreeMap<i32, Vec<(f64, f64)>> = Default::default();
    let mut path = Vec::new();
    for k in 0..u.te.len() {
        for t in &u.teeth[k] {
            curves
                .entry(t.tooth)
                .or_default()
                .push((rot(u.pinion_angle[k]), t.te * 1e6));
        }
        let Some(c) = u.teeth[k].get(u.contact[k]) else {
            continue;
        };
        let at = fp.placement(u.pinion_angle[k], u.te[k], dir);
        let e = contact_ellipse(fp, at, c.tooth, c.uv, s.marking_compound_um * 1e-6);
        path.push(PathPoint {
            pinion_rotation_deg: rot(u.pinion_angle[k]),
            tooth: c.tooth,
            cone_distance_mm: c.l * 1e3,
            height_mm: c.d * 1e3,
            position_m: c.pos,
            ellipse_semi_axes_mm: e.map_or([f64::NAN; 2], |e| {
                [e.semi_axes[0] * 1e3, e.semi_axes[1] * 1e3]
            }),
            ellipse_major_dir: e.map_or([f64::NAN; 2], |e| e.major_dir_ld),
        });
    }
    let mean = u.te.iter().sum::<f64>() / u.te.len() as f64;
    Ok(UtcaReport {
        side: fp.side.name(),
        convention: "wheel side, urad: lag of the wheel behind its conjugate position (positive = wheel behind), against pinion rotation from the start of the sweep",
        mesh_cycle_deg: pair.mesh_cycle().to_degrees(),
        step_deg: s.step_deg,
        contact_ratio: u.contact_ratio,
        te_ptp_urad: u.te_ptp() * 1e6,
        te_mean_urad: mean * 1e6,
        roll_range_deg: fp.roll_range.map(f64::to_degrees),
        pinion_rotation_deg: u.pinion_angle.iter().map(|&p| rot(p)).collect(),
        te_urad: u.te.iter().map(|t| t * 1e6).collect(),
        tooth_curves: curves.into_iter().collect(),
        path,
        marking_compound_um: s.marking_compound_um,
    })
}

fn map_of(g: &FlankGrid, value: &[f64]) -> plots::FlankMap {
    plots::FlankMap {
        n_face: g.n_face,
        n_profile: g.n_profile,
        x: g.cone_distance_mm.clone(),
        y: g.height_mm.clone(),
        value: value.to_vec(),
    }
}

fn outline(f: &Flank) -> Vec<(f64, f64)> {
    let mut pts = Vec::new();
    for (xi, eta) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
        let (l, d) = f.bounds.from_unit(xi, eta);
        pts.push((l * 1e3, d * 1e3));
    }
    pts
}

fn write_plots(
    out: &Path,
    g: &PairGeometry,
    grids: &[FlankGrid],
    r: &UtcaReport,
    side: Side,
) -> Result<(), plots::PlotError> {
    let pg = &grids[side.index()];
    let flank = pg.flank;
    plots::flank_map(
        &out.join("ease_off.svg"),
        &format!("Pinion {flank} flank: ease-off (normal deviation from conjugate)"),
        &map_of(pg, &pg.ease_off_um),
        "ease-off [um]",
    )?;
    plots::flank_map(
        &out.join("roll_angles.svg"),
        &format!("Pinion {flank} flank: surface of roll angles"),
        &map_of(pg, &pg.pinion_roll_deg),
        "pinion roll angle [deg]",
    )?;
    let mut series = vec![plots::Series {
        name: "unloaded TE".into(),
        x: r.pinion_rotation_deg.clone(),
        y: r.te_urad.clone(),
        dashed: false,
    }];
    for (_, c) in &r.tooth_curves {
        let (x, y): (Vec<f64>, Vec<f64>) = c
            .iter()
            .filter(|p| p.1 < 3.0 * r.te_ptp_urad.max(1.0))
            .cloned()
            .unzip();
        if x.len() > 1 {
            series.push(plots::Series {
                name: "single tooth pair".into(),
                x,
                y,
                dashed: true,
            });
        }
    }
    plots::te_curve(
        &out.join("te.svg"),
        &format!(
            "Unloaded transmission error ({} side), ptp {:.1} urad",
            side.name(),
            r.te_ptp_urad
        ),
        "pinion rotation [deg]",
        "TE, wheel [urad]",
        &series,
    )?;
    let fp = g.side(side);
    let path_pts: Vec<(f64, f64)> = r
        .path
        .iter()
        .map(|p| (p.cone_distance_mm, p.height_mm))
        .collect();
    let every = (r.path.len() / 12).max(1);
    let ellipses: Vec<plots::Ellipse> = r
        .path
        .iter()
        .step_by(every)
        .filter(|p| p.ellipse_semi_axes_mm.iter().all(|a| a.is_finite()))
        .map(|p| plots::Ellipse {
            center: (p.cone_distance_mm, p.height_mm),
            semi_axes: (p.ellipse_semi_axes_mm[0], p.ellipse_semi_axes_mm[1]),
            angle_rad: p.ellipse_major_dir[1].atan2(p.ellipse_major_dir[0]),
        })
        .collect();
    plots::contact_path(
        &out.join("contact_path.svg"),
        &format!(
            "Pinion {flank} flank: path of contact and {} um contact ellipses",
            r.marking_compound_um
        ),
        &outline(&fp.pinion),
        &[plots::PathSeries {
            name: "path of contact".into(),
            points: path_pts,
        }],
        &ellipses,
    )?;
    // Tooth section at the mean cone distance: arc length around the axis vs height.
    let mut curves = Vec::new();
    for m in [Member::Pinion, Member::Wheel] {
        for s in [Side::Drive, Side::Coast] {
            let f = g.flank(m, s);
            let l = g.data.mean_cone_distance;
            let pts: Vec<(f64, f64)> = (0..=30)
                .filter_map(|k| {
                    let eta = k as f64 / 30.0;
                    let (_, d) = f.bounds.from_unit(0.5, eta);
                    let p = f.at(l, d).ok()?;
                    let rho = p.pos[0].hypot(p.pos[1]);
                    let arc = rho * p.pos[1].atan2(p.pos[0]);
                    let off = if m == Member::Wheel { 25.0 } else { 0.0 };
                    Some((arc * 1e3 + off, d * 1e3))
                })
                .collect();
            curves.push(plots::PathSeries {
                name: format!("{} {}", m.name(), s.flank_name(m)),
                points: pts,
            });
        }
    }
    plots::tooth_section(
        &out.join("tooth_section.svg"),
        "Tooth sections at the mean cone distance (wheel shifted by 25 mm)",
        &curves,
    )
}
