//! The report's "Contact laws" section: the Hertz impact-function
//! law (ADAMS `IMPACT`, NX 3D contact) against the FE-analytical contact
//! element, on the load runs of seeds 001 and 002, beside the values the
//! seeds publish.
//!
//! For each seed it reads `<out>/seed00N_impact/multibody/summary.json` and
//! `<out>/seed00N_element/multibody/summary.json` (written by
//! `solver dynamic`); a seed without both is named as absent in one line.
//! Every number of ours is formatted from those summaries; the seeds'
//! numbers are read from `reference/published/seed00{1,2}_contact_law.toml`
//! ([`seed_contact_laws`]), each with where the seed prints it. The load-run charts next to the summaries are
//! copied into the report directory.

use crate::report::figures::{copied, Figure};
use crate::report::published::{seed_contact_laws, SeedContactLaw};
use formats::summaries::{DynamicSummary, ImpactLawSummary, LoadRunSummary};
use solver::multibody::impact_law::{
    seed_001_stiffness, seed_002_back_cone_stiffness, SeedStiffness,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// A summary file of a seed scene that is there but cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum ContactLawsError {
    #[error("{}: cannot read the multibody summary: {source}", .path.display())]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: not a multibody summary: {source}", .path.display())]
    Parse {
        path: PathBuf,
        source: serde_json::Error,
    },
    #[error("{}: no run with a load run (`[multibody.load_run]`) in the multibody summary", .path.display())]
    NoLoadRun { path: PathBuf },
    #[error("{}: the load run used the {found:?} force law, the scene name says {expected:?}", .path.display())]
    WrongLaw {
        path: PathBuf,
        found: String,
        expected: &'static str,
    },
}

/// One scene's load run: the run's summary, its load run and where its
/// charts are.
#[derive(Debug, Clone)]
pub struct LawRun {
    pub scene: String,
    pub run: DynamicSummary,
    pub load_run: LoadRunSummary,
    /// `<out>/<scene>/multibody/<blanks>/`.
    pub dir: PathBuf,
}

/// A seed's two runs, or the summary files that are missing.
#[derive(Debug, Clone)]
pub enum SeedRuns {
    Present {
        impact: Box<LawRun>,
        element: Box<LawRun>,
        /// The scenes' reduced meshes (profile × face), when the scene file
        /// could be read.
        mesh: Option<[u32; 2]>,
    },
    Absent {
        missing: Vec<PathBuf>,
    },
}

/// The section: its markdown and its figures (SVG files already in the
/// report directory).
#[derive(Debug, Clone, Default)]
pub struct ContactLaws {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

/// `out/<scene>/multibody/summary.json`.
pub fn summary_path(out: &Path, scene: &str) -> PathBuf {
    out.join(scene).join("multibody").join("summary.json")
}

/// The load run of `<out>/<scene>/multibody/summary.json` with force law
/// `law`; Ok(None) when the file does not exist.
pub fn read_run(
    out: &Path,
    scene: &str,
    law: &'static str,
) -> Result<Option<LawRun>, ContactLawsError> {
    let path = summary_path(out, scene);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(ContactLawsError::Read { path, source }),
    };
    let runs: Vec<DynamicSummary> =
        serde_json::from_str(&text).map_err(|source| ContactLawsError::Parse {
            path: path.clone(),
            source,
        })?;
    let Some(run) = runs.into_iter().find(|r| r.load_run.is_some()) else {
        return Err(ContactLawsError::NoLoadRun { path });
    };
    if run.force_law != law {
        return Err(ContactLawsError::WrongLaw {
            found: run.force_law,
            expected: law,
            path,
        });
    }
    // The charts: the run's blank directory under this `out` (the summary's
    // `dir` is relative to where the solver ran).
    let mut dir = out.join(scene).join("multibody");
    if let Some(blanks) = run.dir.file_name() {
        dir.push(blanks);
    }
    let load_run = run
        .load_run
        .clone()
        .ok_or(ContactLawsError::NoLoadRun { path: path.clone() })?;
    Ok(Some(LawRun {
        scene: scene.to_string(),
        run,
        load_run,
        dir,
    }))
}

/// Both runs of `seed`, with the scenes' reduced meshes from
/// `<scenes>/seed00N_element.toml` when it can be read.
pub fn seed_runs(
    out: &Path,
    scenes: Option<&Path>,
    seed: &SeedContactLaw,
) -> Result<SeedRuns, ContactLawsError> {
    let (si, se) = (
        format!("seed{}_impact", seed.id),
        format!("seed{}_element", seed.id),
    );
    let impact = read_run(out, &si, "impact")?;
    let element = read_run(out, &se, "element")?;
    match (impact, element) {
        (Some(impact), Some(element)) => {
            let mesh = scenes
                .and_then(|d| geometry::scene::Scene::load(&d.join(format!("{se}.toml"))).ok())
                .map(|l| {
                    let m = l.scene.mesh.reduced_order;
                    [m.profile, m.face]
                });
            Ok(SeedRuns::Present {
                impact: Box::new(impact),
                element: Box::new(element),
                mesh,
            })
        }
        (i, e) => Ok(SeedRuns::Absent {
            missing: [(i.is_none(), si), (e.is_none(), se)]
                .into_iter()
                .filter(|(m, _)| *m)
                .map(|(_, s)| summary_path(out, &s))
                .collect(),
        }),
    }
}

/// The impact law's parameters as used, beside the seed's printed values,
/// and the Hertz K recomputed from the pair's pitch radii.
fn parameter_table(
    s: &mut String,
    p: &SeedContactLaw,
    law: &ImpactLawSummary,
    element_mu: f64,
    hertz: &[(&str, SeedStiffness)],
) {
    let _ = writeln!(
        s,
        "| impact-law parameter | used here | seed {} ({}) |",
        p.id, p.parameters_source
    );
    let _ = writeln!(s, "|---|---|---|");
    let _ = writeln!(
        s,
        "| K, N/mm^e | {:.4e} (from the {}) | {:.4e}, {} |",
        law.stiffness_n_per_mm_e, law.stiffness_source, p.stiffness.value, p.stiffness.source
    );
    let _ = writeln!(
        s,
        "| Hertz K = 4/3 √R E*, N/mm^1.5, R from the pitch radii {:.2} and {:.2} mm | {:.4e} | printed / recomputed = {:.3} |",
        law.hertz_radii_mm[0],
        law.hertz_radii_mm[1],
        law.hertz_stiffness_n_per_mm_1_5,
        p.stiffness.value / law.hertz_stiffness_n_per_mm_1_5
    );
    // Only the values that differ from the pitch-radius row above.
    let pitch = law.hertz_stiffness_n_per_mm_1_5;
    for (what, k) in hertz
        .iter()
        .filter(|(_, k)| (k.recomputed / pitch - 1.0).abs() > 1e-6)
    {
        let _ = writeln!(
            s,
            "| Hertz K, {what}, R₁, R₂ = {:.2}, {:.2} mm, E* = {:.4e} N/mm² | {:.4e} | printed / recomputed = {:.3} |",
            k.radii_mm[0],
            k.radii_mm[1],
            k.modulus_n_per_mm2,
            k.recomputed,
            k.ratio()
        );
    }
    let _ = writeln!(s, "| exponent e | {} | {} |", law.exponent, p.exponent);
    let _ = writeln!(
        s,
        "| damping C, N·s/mm, full at d, mm | {} at {} | {} at {} |",
        law.damping_n_s_per_mm, law.penetration_depth_mm, p.damping_n_s_per_mm, p.depth_mm
    );
    let _ = writeln!(
        s,
        "| friction μs / μd (stiction / transition speed, mm/s) | {} / {} ({} / {}) | {} / {} |",
        law.static_friction,
        law.dynamic_friction,
        law.stiction_speed_mm_s,
        law.friction_transition_speed_mm_s,
        p.static_friction,
        p.dynamic_friction
    );
    let _ = writeln!(
        s,
        "| element runs: constant Coulomb μ | {} | |\n",
        element_mu
    );
}

/// The Hertz stiffness recomputed from each seed's own inputs (its
/// materials; for seed 002 also the back-cone radii), see
/// `solver::multibody::impact_law`.
fn seed_hertz(p: &SeedContactLaw) -> Vec<(&'static str, SeedStiffness)> {
    match p.id.as_str() {
        "001" => vec![("the seed's own inputs", seed_001_stiffness())],
        "002" => vec![(
            "back-cone (Tredgold) radii r / cos δ",
            seed_002_back_cone_stiffness(),
        )],
        _ => Vec::new(),
    }
}

/// What the stiffness findings are, numbers from `law` and `hertz`.
fn stiffness_finding(
    s: &mut String,
    p: &SeedContactLaw,
    law: &ImpactLawSummary,
    hertz: &[(&str, SeedStiffness)],
) {
    let pitch = law.hertz_stiffness_n_per_mm_1_5;
    match (p.id.as_str(), hertz.first()) {
        ("001", Some((_, k))) => {
            // The seed's rounded E* (its printed 1.1e5 N/mm²).
            let rounded = solver::multibody::impact_law::hertz_point_stiffness(k.radius_mm, 1.1e5);
            let _ = writeln!(
                s,
                "Stiffness: 4/3 √R E* with the seed's inputs is {:.4e} N/mm^1.5 (R = {:.3} mm, E* = {:.4e} N/mm²); the printed {:.4e} differs by {:+.2} %; with E* rounded to 1.1e5 N/mm² as the seed prints it, {:.4e} ({:+.3} %: {}). The seed derives K for F = K δ^1.5 and uses it with the exponent {}: with δ in mm that is a different law, weaker below 1 mm penetration. This run uses the printed K with the printed exponent, as the seed did.\n",
                k.recomputed,
                k.radius_mm,
                k.modulus_n_per_mm2,
                p.stiffness.value,
                100.0 * (k.ratio() - 1.0),
                rounded,
                100.0 * (p.stiffness.value / rounded - 1.0),
                if (p.stiffness.value / rounded - 1.0).abs() < 5e-4 {
                    "the printed value to its digits"
                } else {
                    "not the printed value either"
                },
                p.exponent
            );
        }
        ("002", Some((_, k))) => {
            let _ = writeln!(
                s,
                "Stiffness: the printed k = {:.3e} (no unit) is {:.0} times the Hertz value with the back-cone radii of the outer transverse section ({:.3e} N/mm^1.5) and {:.0} times the value with the pitch radii ({:.3e}); no choice of R with α ≤ 1 and E in N/mm² reproduces it (E in N/cm² with R in mm would). This run uses the printed k as N/mm^1.5, as the seed's units imply: a contact about {:.0} times stiffer than Hertz.\n",
                p.stiffness.value,
                k.ratio(),
                k.recomputed,
                p.stiffness.value / pitch,
                pitch,
                law.stiffness_n_per_mm_e / pitch
            );
        }
        _ => {}
    }
}

/// Where the differences come from, for one seed.
fn differences(s: &mut String, p: &SeedContactLaw, i: &LawRun, e: &LawRun, mesh: Option<[u32; 2]>) {
    let (li, le) = (&i.load_run, &e.load_run);
    let mesh = mesh.map_or("coarse reduced".to_string(), |m| {
        format!("coarse {} × {}", m[0], m[1])
    });
    let _ = writeln!(s, "Where the differences come from:\n");
    super::contact_laws_load_run::tangential_paragraph(s, p, li, le);
    let _ = writeln!(
        s,
        "- The element runs use the FE-analytical contact on the {mesh} reduced meshes (profile × face per flank) of the seed pairs: their TE mean ({:.0} µrad against {:.0} µrad with the impact law) holds the tooth and body compliance of these coarse meshes, which the impact law does not have, and their force and speed fluctuations follow the mesh stiffness variation that these meshes resolve.",
        le.te_mean_urad, li.te_mean_urad
    );
    let _ = writeln!(
        s,
        "- The impact law works on rigid geometry: the bodies do not deform, the only compliance is K δ^e at each pair's deepest point, and a pair comes into contact at once at its rigid first contact, so the speed and force fluctuations come from the impacts at mesh entry and the jump between pairs (largest tangential-force fluctuation {:.0} N against {:.0} N with the element).",
        li.tangential_force_fluctuation_max_n, le.tangential_force_fluctuation_max_n
    );
    let _ = writeln!(
        s,
        "- Friction: the element runs use a constant Coulomb μ = {} (the seed's dynamic coefficient); the impact law switches between μs = {} and μd = {} with the sliding speed, and adds its contact damping C δ̇. The mesh efficiency, {:.4} (impact) against {:.4} (element), reflects both.\n",
        e.run.friction_coefficient,
        i.run.impact_law.as_ref().map_or(f64::NAN, |l| l.static_friction),
        i.run.impact_law.as_ref().map_or(f64::NAN, |l| l.dynamic_friction),
        li.mesh_efficiency,
        le.mesh_efficiency
    );
}

/// The load-run charts of both runs (impact | element side by side per
/// chart), copied to `reports` as `contact_laws_<scene>_<chart>.svg`.
fn seed_figures(p: &SeedContactLaw, i: &LawRun, e: &LawRun, reports: &Path) -> Vec<Figure> {
    let charts = [
        ("load_run_speed.svg", "wheel speed"),
        ("load_run_force.svg", "tangential force"),
        ("load_run_torque.svg", "wheel torque"),
    ];
    let mut figs = Vec::new();
    for (file, what) in charts {
        for (run, law) in [(i, "impact law"), (e, "FE-analytical element")] {
            let to = format!("contact_laws_{}_{}", run.scene, file);
            let title = format!("Seed {}, {law}: {what} over the load run", p.id);
            figs.extend(copied(&title, &run.dir.join(file), reports, &to));
        }
    }
    figs
}

/// The section for the seeds' runs under `out`: `scenes` is the directory
/// of the seed scene files (for their mesh sizes), `reports` where the
/// charts are copied.
pub fn build(
    out: &Path,
    scenes: Option<&Path>,
    reports: &Path,
) -> Result<ContactLaws, ContactLawsError> {
    let runs = seed_contact_laws()
        .iter()
        .map(|p| seed_runs(out, scenes, p).map(|r| (p, r)))
        .collect::<Result<Vec<_>, _>>()?;
    // Seed 001's impact law with the haversine damping ramp it names.
    let mut haversine = std::collections::BTreeMap::new();
    if let Some(h) = read_run(out, HAVERSINE_SCENE, "impact")? {
        haversine.insert("001".to_string(), h);
    }
    Ok(section(&runs, &haversine, reports))
}

/// The scene of seed 001's impact law with the haversine damping ramp.
pub const HAVERSINE_SCENE: &str = "seed001_impact_haversine";

/// The section's markdown from the seeds' runs; `haversine` holds, by
/// seed id, the impact-law run with the haversine damping ramp.
pub fn section(
    runs: &[(&SeedContactLaw, SeedRuns)],
    haversine: &std::collections::BTreeMap<String, LawRun>,
    reports: &Path,
) -> ContactLaws {
    let mut s = String::new();
    let mut figures = Vec::new();
    let _ = writeln!(s, "## Contact laws: Hertz impact function against the FE-analytical contact element (seeds 001 and 002)\n");
    let _ = writeln!(
        s,
        "The impact-function law of general-purpose multibody codes (ADAMS IMPACT, NX 3D contact: F = K δ^e + C δ̇ STEP(δ, 0, 0, d, 1), friction switching between μs and μd) and the FE-analytical contact element, each on the seeds' load runs (imposed pinion speed, wheel load), beside the numbers the seeds publish. Means and fluctuations are over whole mesh cycles of the steady window.\n"
    );
    for (p, r) in runs {
        match r {
            SeedRuns::Absent { missing } => {
                let names: Vec<String> = missing
                    .iter()
                    .map(|m| format!("`{}`", m.display()))
                    .collect();
                let _ = writeln!(
                    s,
                    "Seed {} ({}): not run, {} absent (`make validate CONTACT_LAWS=1` runs it).\n",
                    p.id,
                    p.title,
                    names.join(" and ")
                );
            }
            SeedRuns::Present {
                impact,
                element,
                mesh,
            } => {
                let _ = writeln!(s, "### Seed {} ({})\n", p.id, p.title);
                let (li, le) = (&impact.load_run, &element.load_run);
                let _ = writeln!(
                    s,
                    "Pinion at {:.1} rpm (ramp {} s), wheel load {} N·m (rise {} s), {} s simulated.\n",
                    li.pinion_rpm, li.pinion_ramp_s, li.wheel_torque_nm, li.wheel_torque_rise_s, li.sim_time_s
                );
                super::contact_laws_load_run::table(&mut s, p, li, le);
                let hertz = seed_hertz(p);
                if let Some(law) = &impact.run.impact_law {
                    parameter_table(&mut s, p, law, element.run.friction_coefficient, &hertz);
                    stiffness_finding(&mut s, p, law, &hertz);
                }
                differences(&mut s, p, impact, element, *mesh);
                if let Some(h) = haversine.get(p.id.as_str()) {
                    super::contact_laws_load_run::step_shape_table(
                        &mut s,
                        &impact.load_run,
                        &h.load_run,
                    );
                }
                let figs = seed_figures(p, impact, element, reports);
                for f in &figs {
                    let _ = writeln!(s, "![{}]({})", f.title.replace(['[', ']'], ""), f.file);
                }
                if !figs.is_empty() {
                    s.push('\n');
                }
                figures.extend(figs);
            }
        }
    }
    ContactLaws {
        markdown: s,
        figures,
    }
}
