//! The report's section "Compliant bearings (multibody)": `solver dynamic`
//! and `solver ltca` on `reference/scenes/white_paper_bearings.toml` (the
//! white-paper pair with both members on compliant bearings).
//!
//! Reads `<out>/white_paper_bearings/{multibody,ltca}/summary.json` and the
//! runs' CSV files when present: the bearings and mass properties used, TE
//! with compliant against rigid bearings, the misalignment the bearings
//! give and the bearing forces per bearing and direction over each run,
//! the 10 rpm run against the quasi-static LTCA on the same bearings
//! ([`ltca_check`], computed here from `bearings_quasi_static_<T>nm.csv`
//! and `bearings.csv`), the linearization estimate, CPU time per step and
//! the run-up's bearing-force spectrograms (copied into the report
//! directory as `compliant_<blanks>_<chart>.svg`). An absent summary is one
//! line of text, never a table of zeros. Every number is formatted from the
//! files.

use crate::report::figures::{column, copied, read_csv, Csv, Figure};
use crate::report::results::Stamp;
use formats::summaries::{BlankSummary, CompliantRunSummary, DynamicSummary};
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose runs the section reports.
pub const COMPLIANT_SCENE: &str = "white_paper_bearings";

/// The section's markdown and the figures it shows (already written into
/// the report directory).
#[derive(Debug, Clone, Default)]
pub struct CompliantSection {
    pub markdown: String,
    pub figures: Vec<Figure>,
}

/// Smallest and largest finite value of `v`; None when there is none.
pub fn range(v: &[f64]) -> Option<(f64, f64)> {
    v.iter()
        .filter(|x| x.is_finite())
        .fold(None, |r, &x| match r {
            None => Some((x, x)),
            Some((lo, hi)) => Some((lo.min(x), hi.max(x))),
        })
}

/// Mean and peak-to-peak of `v`'s finite values; None when there is none.
fn mean_ptp(v: &[f64]) -> Option<(f64, f64)> {
    let f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    (!f.is_empty()).then(|| solver::ltca::mean_ptp(&f))
}

/// `y(x)` at `at` by linear interpolation on increasing `x`; None outside.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> Option<f64> {
    (x.len() >= 2 && at >= x[0] && at <= x[x.len() - 1])
        .then(|| solver::multibody::model::interpolate(x, y, at))
}

/// The bearing-force columns both CSV files share (`<member>_bearing<k>_f<d>_n`).
fn force_columns(csv: &Csv) -> Vec<&str> {
    csv.0
        .iter()
        .filter(|h| h.contains("_bearing") && h.ends_with("_n"))
        .map(String::as_str)
        .collect()
}

/// The 10 rpm run on compliant bearings against the quasi-static LTCA on
/// the same bearings (`system_deflection`, iterated on the exact deflected
/// poses) at the LTCA's positions the run passes.
#[derive(Debug, Clone, PartialEq)]
pub struct LtcaCheck {
    pub positions: usize,
    /// Mean TE the bearings add in the LTCA (compliant − rigid), µrad.
    pub added_te_mean_urad: f64,
    /// Multibody − LTCA TE: mean and largest magnitude, µrad.
    pub te_difference_mean_urad: f64,
    pub te_difference_largest_urad: f64,
    /// Largest difference of one bearing force component, N, and the
    /// largest bearing force component of the LTCA, N.
    pub force_difference_largest_n: f64,
    pub force_largest_n: f64,
    /// A few positions: (rotation deg, LTCA TE, multibody TE, LTCA rigid TE).
    pub rows: Vec<[f64; 4]>,
}

/// [`LtcaCheck`] of the multibody CSV `mb` against the LTCA's
/// `bearings.csv` `ltca` at torque `torque_nm`, with up to `shown` rows
/// spread evenly. None when a column is missing or no position is passed.
pub fn ltca_check(mb: &Csv, ltca: &Csv, torque_nm: f64, shown: usize) -> Option<LtcaCheck> {
    let q = column(mb, "pinion_rotation_deg")?;
    let te = column(mb, "te_urad")?;
    let lq = column(ltca, "pinion_rotation_deg")?;
    let lt = column(ltca, "torque_nm")?;
    let lte = column(ltca, "te_urad")?;
    let lrig = column(ltca, "te_rigid_bearings_urad")?;
    let forces: Vec<(&[f64], &[f64])> = force_columns(ltca)
        .into_iter()
        .filter_map(|h| Some((column(mb, h)?, column(ltca, h)?)))
        .collect();
    let mut all = Vec::new();
    let (mut added, mut dsum, mut dmax, mut fmax, mut fbig) = (0.0, 0.0, 0.0f64, 0.0f64, 0.0f64);
    for i in (0..lq.len()).filter(|&i| (lt[i] - torque_nm).abs() < 1e-9) {
        let Some(m) = interpolate(q, te, lq[i]) else {
            continue;
        };
        let d = m - lte[i];
        added += lte[i] - lrig[i];
        dsum += d;
        dmax = dmax.max(d.abs());
        for (fm, fl) in &forces {
            if let Some(v) = interpolate(q, fm, lq[i]) {
                fmax = fmax.max((v - fl[i]).abs());
                fbig = fbig.max(fl[i].abs());
            }
        }
        all.push([lq[i], lte[i], m, lrig[i]]);
    }
    let n = all.len();
    if n == 0 {
        return None;
    }
    let step = n.div_ceil(shown.max(1));
    Some(LtcaCheck {
        positions: n,
        added_te_mean_urad: added / n as f64,
        te_difference_mean_urad: dsum / n as f64,
        te_difference_largest_urad: dmax,
        force_difference_largest_n: fmax,
        force_largest_n: fbig,
        rows: all.into_iter().step_by(step).collect(),
    })
}

fn absent(mut s: String, why: &str) -> CompliantSection {
    let _ = writeln!(s, "No compliant-bearing runs: {why}.\n");
    CompliantSection {
        markdown: s,
        figures: vec![],
    }
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, String> {
    std::fs::read_to_string(path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str(&t).map_err(|e| e.to_string()))
}

fn blank_name(d: &DynamicSummary) -> String {
    format!("{:?}_{:?}", d.pinion_blank, d.wheel_blank).to_lowercase()
}

/// The section from the stages' output root `out` (None: no root given),
/// its spectrograms copied into `reports`, headed with `stamp`.
pub fn section(out: Option<&Path>, reports: &Path, stamp: &Stamp) -> CompliantSection {
    let s = String::from("## Compliant bearings (multibody)\n\n");
    let Some(out) = out else {
        return absent(s, "the report was built without an output root");
    };
    let root = out.join(COMPLIANT_SCENE);
    let mb_path = root.join("multibody").join("summary.json");
    let dynamic: Vec<DynamicSummary> = match read_json(&mb_path) {
        Ok(v) => v,
        Err(e) => {
            return absent(
                s,
                &format!(
                    "`{}` cannot be read ({e}); `solver dynamic reference/scenes/{COMPLIANT_SCENE}.toml` writes it",
                    mb_path.display()
                ),
            )
        }
    };
    let ltca: Vec<BlankSummary> =
        read_json(&root.join("ltca").join("summary.json")).unwrap_or_default();
    let mut s = s;
    let info = |stage: &str| {
        formats::result_set::read_run_info(&root.join(stage))
            .ok()
            .flatten()
    };
    let run =
        info("multibody").map_or_else(|| "at an unknown time".to_string(), |r| r.committed_utc);
    let inputs = match (info("multibody"), info("ltca")) {
        (Some(_), Some(_)) => match formats::result_set::check_same_inputs(&[
            &root.join("multibody"),
            &root.join("ltca"),
        ]) {
            Ok(()) => "The LTCA and the multibody were computed from the same meshes and stiffness files.".to_string(),
            Err(e) => format!("**The LTCA and the multibody do not share their inputs** ({e})."),
        },
        _ => "The LTCA or the multibody set has no run stamp (`run.json`): their inputs are not compared.".to_string(),
    };
    let _ = writeln!(
        s,
        "`solver dynamic` and `solver ltca` on `reference/scenes/{COMPLIANT_SCENE}.toml`: the white-paper pair at its loads with each member on two compliant bearings, the contact element evaluated at the relative pose the bearings give at every step (docs/misalignment.md, \"Multibody with compliant bearings\"). Multibody run committed {run}; section built {} at commit {}. {}\n",
        stamp.date_utc,
        stamp.commit,
        inputs
    );
    used_tables(&mut s, &dynamic);
    te_table(&mut s, &dynamic, &ltca, &root);
    misalignment_table(&mut s, &dynamic, &root);
    force_table(&mut s, &dynamic, &root);
    check_table(&mut s, &dynamic, &root);
    let mut figures = Vec::new();
    for d in &dynamic {
        let b = blank_name(d);
        let dir = root.join("multibody").join(&b);
        let pair: Vec<Figure> = [
            (
                "Wheel bearing force, rigid bearings",
                "runup_spectrogram.svg",
            ),
            (
                "Wheel bearing force, compliant bearings",
                "bearings_runup_spectrogram.svg",
            ),
        ]
        .iter()
        .filter_map(|(title, file)| {
            copied(
                &format!("{title} ({b}), run-up"),
                &dir.join(file),
                reports,
                &format!("compliant_{b}_{file}"),
            )
        })
        .collect();
        if pair.len() == 2 {
            let _ = writeln!(
                s,
                "Run-up spectrograms of the wheel bearings' total force, {b}: |F| with rigid bearings (the reaction to the contact force) on the left, with compliant bearings (both wheel bearings' forces together) on the right; the tooth orders 20, 40, 60 marked (and, with the lightweight wheel, 20 ± 3·20/43).\n"
            );
            crate::report::figures::figure_lines(&mut s, &pair, true);
            figures.extend(pair);
        }
    }
    CompliantSection {
        markdown: s,
        figures,
    }
}

/// The bearings and mass properties the runs used.
fn used_tables(s: &mut String, dynamic: &[DynamicSummary]) {
    let Some((d, c)) = dynamic
        .iter()
        .find_map(|d| Some((d, d.compliant.as_ref()?)))
    else {
        s.push_str("The multibody summary has no compliant-bearing runs (the scene has no `[bearings]`).\n\n");
        return;
    };
    let Some(u) = &c.used else {
        let _ = writeln!(
            s,
            "Masses {:.3} kg (pinion) and {:.3} kg (wheel, {} blank); {}. The bearings are not recorded in this summary (written before they were); run `solver dynamic` again.\n",
            c.masses_kg[0], c.masses_kg[1], format!("{:?}", d.wheel_blank).to_lowercase(), c.mass_source
        );
        return;
    };
    s.push_str("| bearing | position from apex (mm) | radial k (N/m) | axial k (N/m) | radial c (N·s/m) | axial c (N·s/m) |\n|---|---:|---:|---:|---:|---:|\n");
    for (member, list) in [("pinion", &u.pinion_bearings), ("wheel", &u.wheel_bearings)] {
        for (k, b) in list.iter().enumerate() {
            let _ = writeln!(
                s,
                "| {member} {k} | {:.2} | {:.3e} | {:.3e} | {:.3e} | {:.3e} |",
                b.axial_position_mm,
                b.radial_stiffness_n_per_m,
                b.axial_stiffness_n_per_m,
                b.radial_damping_n_s_per_m,
                b.axial_damping_n_s_per_m
            );
        }
    }
    s.push('\n');
    s.push_str("| member (blanks) | mass (kg) | centre of mass from apex (mm) | transverse moment (kg·m²) | polar moment (kg·m²) |\n|---|---:|---:|---:|---:|\n");
    for d in dynamic {
        let Some(u) = d.compliant.as_ref().and_then(|c| c.used.as_ref()) else {
            continue;
        };
        for (m, name) in ["pinion", "wheel"].iter().enumerate() {
            let b = &u.bodies[m];
            let _ = writeln!(
                s,
                "| {name} ({}) | {:.3} | {:.2} | {:.4e} | {:.4e} |",
                blank_name(d),
                b.mass_kg,
                b.centroid_mm,
                b.transverse_inertia_kgm2,
                d.inertia_kgm2[m]
            );
        }
    }
    let _ = writeln!(
        s,
        "\nMass properties: {}. Where that says \"thin disc\", the transverse moment is an approximation (half the polar moment from the mesh), not a measured or modelled value; the bearing layout and stiffnesses are chosen (the white paper does not give its gearbox's).\n",
        c.mass_source
    );
}

fn run_csv(root: &Path, d: &DynamicSummary, file: &str) -> Option<Csv> {
    read_csv(&root.join("multibody").join(blank_name(d)).join(file))
}

/// TE with compliant against rigid bearings, the linearization estimate
/// and the cost per step, per blank and run.
fn te_table(s: &mut String, dynamic: &[DynamicSummary], ltca: &[BlankSummary], root: &Path) {
    s.push_str("### Transmission error, compliant against rigid bearings\n\nShaft TE r q₁ − q₂. The 10 rpm runs are sampled at the table's positions they pass (as the rigid runs are), the run-up over its steps (the rigid run-up from `runup.csv`); the LTCA columns are `solver ltca`'s sweep on the same bearings. The linearization estimate ½ Σ |∂²θ₀/∂mᵢ²| mᵢ² is what the linear shift of the unloaded TE leaves out (mean over the steps; largest, at the tooth changes, in brackets).\n\n");
    s.push_str("| blanks | run | rigid mean / ptp (µrad) | compliant mean / ptp (µrad) | LTCA compliant mean / ptp (µrad) | LTCA rigid mean / ptp (µrad) | linearization mean (largest) (µrad) | steps | rigid µs/step | compliant µs/step |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for d in dynamic {
        let Some(c) = &d.compliant else { continue };
        let l = ltca
            .iter()
            .find(|l| l.pinion_blank == d.pinion_blank && l.wheel_blank == d.wheel_blank);
        for r in &c.runs {
            let (rigid, rigid_cost, ltca_cols) = if r.case == "run-up" {
                let te = run_csv(root, d, "runup.csv")
                    .and_then(|csv| mean_ptp(column(&csv, "te_urad")?));
                (te, d.runup.as_ref().map(|u| u.cpu_s_per_step), None)
            } else {
                let q = d
                    .quasi_static
                    .iter()
                    .find(|q| (q.torque_nm - r.torque_nm).abs() < 1e-9);
                let b = l
                    .and_then(|l| l.bearings.as_ref())
                    .and_then(|b| b.iter().find(|b| (b.torque_nm - r.torque_nm).abs() < 1e-9));
                (
                    q.map(|q| (q.te_mean_urad, q.te_ptp_urad)),
                    q.map(|q| q.cpu_s_per_step),
                    b.map(|b| {
                        [
                            b.te_mean_urad,
                            b.te_ptp_urad,
                            b.rigid_te_mean_urad,
                            b.rigid_te_ptp_urad,
                        ]
                    }),
                )
            };
            let pair =
                |v: Option<(f64, f64)>| v.map_or("–".into(), |(a, b)| format!("{a:.2} / {b:.2}"));
            let _ = writeln!(
                s,
                "| {} | {} at {} N·m | {} | {:.2} / {:.2} | {} | {} | {:.2} ({:.2}) | {} | {} | {:.1} |",
                blank_name(d),
                r.case,
                r.torque_nm,
                pair(rigid),
                r.te_mean_urad,
                r.te_ptp_urad,
                pair(ltca_cols.map(|b| (b[0], b[1]))),
                pair(ltca_cols.map(|b| (b[2], b[3]))),
                r.mean_linearization_urad,
                r.largest_linearization_urad,
                r.steps,
                rigid_cost.map_or("–".into(), |c| format!("{:.1}", c * 1e6)),
                r.cpu_s_per_step * 1e6
            );
        }
    }
    s.push('\n');
}

fn runs(d: &DynamicSummary) -> impl Iterator<Item = &CompliantRunSummary> {
    d.compliant.iter().flat_map(|c| &c.runs)
}

/// "smallest … largest" of column `h` with `decimals`, "–" without it.
fn range_cell(csv: &Csv, h: &str, decimals: usize) -> String {
    column(csv, h).and_then(range).map_or("–".into(), |(a, b)| {
        format!("{a:.decimals$} … {b:.decimals$}")
    })
}

/// Ranges of E, P, G and ΔΣ over each run.
fn misalignment_table(s: &mut String, dynamic: &[DynamicSummary], root: &Path) {
    s.push_str("### Relative pose from the bearings\n\nThe misalignment the loaded bearings give (docs/misalignment.md's signs), smallest to largest over each run.\n\n| blanks | run | E (µm) | P (µm) | G (µm) | ΔΣ (µrad) |\n|---|---|---:|---:|---:|---:|\n");
    for (d, r, csv) in run_files(dynamic, root) {
        let cell = |h: &str| range_cell(&csv, h, 2);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            blank_name(d),
            r.case,
            cell("e_um"),
            cell("p_um"),
            cell("g_um"),
            cell("shaft_angle_urad")
        );
    }
    s.push('\n');
}

/// Every compliant run of `dynamic` with its CSV file (runs whose file
/// cannot be read are left out).
fn run_files<'a>(
    dynamic: &'a [DynamicSummary],
    root: &'a Path,
) -> impl Iterator<Item = (&'a DynamicSummary, &'a CompliantRunSummary, Csv)> + 'a {
    dynamic
        .iter()
        .flat_map(|d| runs(d).map(move |r| (d, r)))
        .filter_map(move |(d, r)| Some((d, r, run_csv(root, d, &r.csv)?)))
}

/// Ranges of every bearing's force per direction over each run.
fn force_table(s: &mut String, dynamic: &[DynamicSummary], root: &Path) {
    s.push_str("### Bearing forces\n\nEach bearing's force on the shaft in the fixed frame (x, y, z as in the CSV files), smallest to largest over each run, N.\n\n| blanks | run | bearing | x (N) | y (N) | z (N) |\n|---|---|---|---:|---:|---:|\n");
    for (d, r, csv) in run_files(dynamic, root) {
        let bearings: Vec<String> = force_columns(&csv)
            .iter()
            .filter_map(|h| h.strip_suffix("_fx_n").map(str::to_string))
            .collect();
        for b in bearings {
            let cell = |dir: &str| range_cell(&csv, &format!("{b}_f{dir}_n"), 0);
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} |",
                blank_name(d),
                r.case,
                b.replace('_', " "),
                cell("x"),
                cell("y"),
                cell("z")
            );
        }
    }
    s.push('\n');
}

/// The 10 rpm runs against the quasi-static LTCA on the same bearings.
fn check_table(s: &mut String, dynamic: &[DynamicSummary], root: &Path) {
    s.push_str("### Check: 10 rpm run against the quasi-static LTCA on the same bearings\n\n`solver ltca` iterates the contact and the bearings' deflection on the exact deflected poses (`bearings.csv`); the multibody's 10 rpm run is interpolated at the LTCA's positions it passes. The multibody leaves out what the equivalent lag's linear shift of the unloaded TE leaves out (its estimate, mean over the run, beside the difference) and the load redistribution a misalignment causes along the contact lines (the wrench is the aligned table's, docs/misalignment.md); a difference well above the estimate comes from the second or from the LTCA's own iteration. The force difference is the largest over all bearings and directions.\n\n| blanks | torque (N·m) | positions | TE the bearings add, LTCA mean (µrad) | multibody − LTCA TE mean / largest (µrad) | largest / added (%) | linearization estimate mean (µrad) | force difference largest (N) | of the largest force (%) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    let mut detail = String::new();
    for d in dynamic {
        let ltca = read_csv(&root.join("ltca").join(blank_name(d)).join("bearings.csv"));
        for r in runs(d).filter(|r| r.case != "run-up") {
            let (Some(l), Some(m)) = (&ltca, run_csv(root, d, &r.csv)) else {
                continue;
            };
            let Some(c) = ltca_check(&m, l, r.torque_nm, 6) else {
                continue;
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:.2} | {:+.2} / {:.2} | {:.1} | {:.2} | {:.0} | {:.1} |",
                blank_name(d),
                r.torque_nm,
                c.positions,
                c.added_te_mean_urad,
                c.te_difference_mean_urad,
                c.te_difference_largest_urad,
                100.0 * c.te_difference_largest_urad
                    / c.added_te_mean_urad.abs().max(f64::MIN_POSITIVE),
                r.mean_linearization_urad,
                c.force_difference_largest_n,
                100.0 * c.force_difference_largest_n / c.force_largest_n.max(f64::MIN_POSITIVE)
            );
            if detail.is_empty() {
                let _ = writeln!(
                    detail,
                    "Some of the positions ({}, {} N·m):\n\n| pinion rotation (deg) | LTCA rigid TE (µrad) | LTCA compliant TE (µrad) | multibody compliant TE (µrad) |\n|---:|---:|---:|---:|",
                    blank_name(d),
                    r.torque_nm
                );
                for row in &c.rows {
                    let _ = writeln!(
                        detail,
                        "| {:.2} | {:.2} | {:.2} | {:.2} |",
                        row[0], row[3], row[1], row[2]
                    );
                }
                detail.push('\n');
            }
        }
    }
    s.push('\n');
    s.push_str(&detail);
}
