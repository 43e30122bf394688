//! The lumped section's part for seed 003 (16/27 pair, W–M roughness,
//! friction, test-rig vibration): `solver lumped` on
//! `reference/scenes/seed003_lumped.toml`, read from
//! `<out>/seed003_lumped/lumped/summary.json` (one [`LumpedSummary`] per
//! roughness grade and torque). Every number of ours is formatted from the
//! summaries; seed 003's are read from
//! `reference/published/seed003_test_rig.toml` ([`seed003`]).
//! An absent summary is one line of text.

use crate::report::published::seed003;
use formats::lumped_summary::LumpedSummary;
use std::fmt::Write as _;
use std::path::Path;

/// The scene whose runs this part reports.
pub const SEED003_SCENE: &str = "seed003_lumped";

fn grade(r: &LumpedSummary) -> String {
    r.roughness
        .as_ref()
        .map_or("smooth".to_string(), |g| format!("Ra {:.1} µm", g.ra_um))
}

/// The runs at the loader torque `t2` (matched by the pinion torque T₂z₁/z₂
/// within 0.01 N·m), in the summaries' order.
fn at_load(all: &[LumpedSummary], t2: f64) -> Vec<&LumpedSummary> {
    let [z1, z2] = seed003().teeth;
    let t1 = t2 * z1 / z2;
    all.iter()
        .filter(|r| (r.pinion_torque_nm - t1).abs() < 0.01)
        .collect()
}

/// The markdown of seed 003's part from the output root `out`.
pub fn markdown(out: &Path) -> String {
    let mut s = String::from(
        "### Seed 003: 16/27 pair, W–M roughness and friction, test-rig vibration\n\n",
    );
    let path = out.join(SEED003_SCENE).join("lumped").join("summary.json");
    let all: Vec<LumpedSummary> = match std::fs::read_to_string(&path)
        .map_err(|e| e.to_string())
        .and_then(|t| serde_json::from_str::<Vec<LumpedSummary>>(&t).map_err(|e| e.to_string()))
    {
        Ok(v) if !v.is_empty() => v,
        Ok(_) => {
            let _ = writeln!(s, "No seed 003 run: `{}` lists no run.\n", path.display());
            return s;
        }
        Err(e) => {
            let _ = writeln!(
                s,
                "No seed 003 run: `{}` cannot be read ({e}); `solver lumped reference/scenes/seed003_lumped.toml` writes it.\n",
                path.display()
            );
            return s;
        }
    };
    let r0 = &all[0];
    let _ = writeln!(
        s,
        "The scene `{SEED003_SCENE}` runs the 8-DOF model at {:.0} rpm (mesh frequency {:.1} Hz), {:.0} mesh cycles with the first {:.0} dropped, for the smooth flanks and each W–M roughness grade at both of seed 003's loads. Seed 003's loads are the loader's set torques on the output side; we take them as the wheel torque (pinion T₂ × {:.0}/{:.0}). Friction: seed 003's μ = μ₀ + μ_r R with μ₀ = {}, μ_r = {} per µm; its R is C L^(1−D) (its Eqs. (31) and (35), C = 1, L the characteristic scale), which with its Table 2's L and D is {} (L in m), no roughness in µm, so we take R = √2 Ra, the composite roughness of two flanks of roughness Ra (our choice, not the seed's); the friction force's direction and moment arms come from our LTCA's slices (sliding direction and friction levers, force-weighted), its size from the dynamic normal force. Seed 003 calls μ₀ = 0.6 the value for good lubrication; a lubricated steel gear mesh usually has 0.04–0.08. Bearings {:.2e} N/m with {:.0} % damping are our choice (seed 003 publishes none), mesh damping ratio 0.1 is seed 003's. The mesh normal's direction comes from our LTCA's force-weighted flank normal, {:.1}° from seed 004's formula with the spiral sign of the loaded flank.\n",
        r0.pinion_speed_rpm,
        r0.mesh_frequency_hz,
        r0.mesh_cycles,
        r0.dropped_mesh_cycles,
        seed003().teeth[0],
        seed003().teeth[1],
        seed003().friction_mu0,
        seed003().friction_mur,
        eq31_values(),
        r0.bearing_stiffness_n_per_m[0][0],
        100.0 * r0.bearing_damping_ratio,
        r0.friction_normal_angle_deg
    );
    velocity_table(&mut s, &all);
    stiffness_table(&mut s, &all);
    roughness_table(&mut s, &all);
    dimension_table(&mut s);
    s
}

/// "agree" when every printed value equals its recomputed mean to the
/// printed digits (within 5e-4, the half unit of three decimals), else
/// "do not agree".
pub fn agree_word(printed: &[f64], recomputed: &[f64]) -> &'static str {
    if printed
        .iter()
        .zip(recomputed)
        .all(|(a, b)| (a - b).abs() <= 5e-4 + 1e-12)
    {
        "agree"
    } else {
        "do not agree"
    }
}

/// Seed 003's Eq. (31) R = C L^(1−D) with C = 1 and its Table 2's L and D
/// per grade, as "Ra 0.8: 823, …".
fn eq31_values() -> String {
    seed003()
        .table2
        .iter()
        .map(|r| {
            format!(
                "{:.0} at Ra {}",
                r.scale_coefficient.powf(1.0 - r.dimension),
                r.ra_um
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Seed 003's two fits of D against its Table 2, and which one runs.
fn dimension_table(s: &mut String) {
    let _ = writeln!(
        s,
        "Fractal dimension D per grade: seed 003's Table 2 against its two fits, Eq. (33) D = 1.515/Ra^0.088 and Eq. (41) D = 1.528/Ra^0.042. The runs use Eq. (41), the fit that reproduces the table (our choice between the seed's two):
"
    );
    let _ = writeln!(s, "| Ra (µm) | Table 2 | Eq. (33) | Eq. (41), used |");
    let _ = writeln!(s, "|---|---|---|---|");
    for r in &seed003().table2 {
        match geometry::roughness::seed003_fractal(r.ra_um) {
            Ok(f) => {
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.3} ({:+.3}) | {:.3} ({:+.3}) |",
                    r.ra_um,
                    r.dimension,
                    f.dimension_eq33,
                    f.dimension_eq33 - r.dimension,
                    f.dimension,
                    f.dimension - r.dimension
                );
            }
            Err(e) => {
                let _ = writeln!(s, "| {} | {} | {e} | |", r.ra_um, r.dimension);
            }
        }
    }
    s.push('\n');
}

fn velocity_table(s: &mut String, all: &[LumpedSummary]) {
    let rig = seed003();
    let m = &rig.measured;
    let measured_source = &rig.measured_source;
    let grades: Vec<String> = at_load(all, m[0].loader_torque_nm)
        .iter()
        .map(|r| grade(r))
        .collect();
    let _ = writeln!(
        s,
        "Vibration velocity, RMS of the pinion's resultant translational velocity on its bearings (mm/s), against the test rig:\n"
    );
    let _ = write!(s, "| loader torque (N·m) | pinion torque (N·m) |");
    for g in &grades {
        let _ = write!(s, " ours, {g} |");
    }
    let _ = writeln!(
        s,
        " measured, text / Table 4 mean | seed 003's simulation, text / Table 4 mean |"
    );
    let _ = writeln!(s, "|---|---|{}---|---|", "---|".repeat(grades.len()));
    let means = rig.table4_means();
    for (k, row) in m.iter().enumerate() {
        let [sim_mean, meas_mean] = means.get(k).copied().unwrap_or([f64::NAN; 2]);
        let (t2, measured, simulated) = (
            row.loader_torque_nm,
            row.measured_velocity_mm_s,
            row.simulated_velocity_mm_s,
        );
        let runs = at_load(all, t2);
        let Some(first) = runs.first() else {
            let _ = writeln!(s, "| {t2:.0} | no run | | |");
            continue;
        };
        let _ = write!(s, "| {t2:.0} | {:.2} |", first.pinion_torque_nm);
        for r in &runs {
            let _ = write!(s, " {:.3} |", 1e3 * r.member_velocity_rms_m_s[0]);
        }
        let _ = writeln!(
            s,
            " {measured:.3} / {meas_mean:.3} | {simulated:.3} / {sim_mean:.3} |"
        );
    }
    let ratios: Vec<f64> = m
        .iter()
        .flat_map(|row| {
            at_load(all, row.loader_torque_nm)
                .into_iter()
                .map(move |r| 1e3 * r.member_velocity_rms_m_s[0] / row.measured_velocity_mm_s)
        })
        .collect();
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let _ = writeln!(
        s,
        "\nSource: {measured_source}. The seed's text gives the means {:.3} / {:.3} mm/s (measured) and {:.3} / {:.3} mm/s (simulated) at 77 / 105 N·m; the 30 rows of its Table 4 average {:.3} / {:.3} and {:.3} / {:.3}: the two {}; the comparison below uses the text's. Ours are {:.0}–{:.0} % of the measured values. What the comparison can carry: seed 003's sensor sits on the rig (a vibration sensor at the input coupling; the paper does not give its position, direction or frequency band); the nearest quantity of our model is the pinion's velocity on its bearings, since the model has no housing, shafts, coupling, motor or loader, and its bearings are assumed. The measured signal also holds the shaft orders, the motor and the loader, which the model does not. So the comparison checks the order of magnitude and the rise with load (ours {:+.0} % from 77 to 105 N·m for the smooth flanks, measured {:+.1} %), not a level; it is neither a calibration nor a validation.\n",
        m[0].measured_velocity_mm_s,
        m[1].measured_velocity_mm_s,
        m[0].simulated_velocity_mm_s,
        m[1].simulated_velocity_mm_s,
        means[0][1],
        means[1][1],
        means[0][0],
        means[1][0],
        agree_word(
            &[
                m[0].measured_velocity_mm_s,
                m[1].measured_velocity_mm_s,
                m[0].simulated_velocity_mm_s,
                m[1].simulated_velocity_mm_s
            ],
            &[means[0][1], means[1][1], means[0][0], means[1][0]]
        ),
        100.0 * lo,
        100.0 * hi,
        rise(all),
        100.0 * (m[1].measured_velocity_mm_s / m[0].measured_velocity_mm_s - 1.0)
    );
}

/// Rise of the smooth pinion velocity from the first to the second load, %.
fn rise(all: &[LumpedSummary]) -> f64 {
    let smooth = |t2: f64| {
        at_load(all, t2)
            .into_iter()
            .find(|r| r.roughness.is_none())
            .map_or(f64::NAN, |r| r.member_velocity_rms_m_s[0])
    };
    let m = &seed003().measured;
    100.0 * (smooth(m[1].loader_torque_nm) / smooth(m[0].loader_torque_nm) - 1.0)
}

/// How a quantity changes over the grades in the order given (smooth
/// first, then rougher): "rises with every grade", "falls with every
/// grade", or "has no monotone trend".
pub fn roughness_trend(values: &[f64]) -> &'static str {
    use crate::report::trend::{trend, Trend};
    match trend(values) {
        Trend::Rises => "rises with every grade",
        Trend::Falls => "falls with every grade",
        Trend::Single | Trend::Neither => "has no monotone trend",
    }
}

/// The runs at pinion torque `t1` from smooth to the roughest grade.
fn by_roughness(all: &[LumpedSummary], t1: f64) -> Vec<&LumpedSummary> {
    let mut v: Vec<&LumpedSummary> = all.iter().filter(|r| r.pinion_torque_nm == t1).collect();
    v.sort_by(|a, b| {
        let ra = |r: &LumpedSummary| r.roughness.as_ref().map_or(0.0, |g| g.ra_um);
        ra(a).total_cmp(&ra(b))
    });
    v
}

/// The grades' Ra in the order of [`by_roughness`], as "0.2, 0.4, 0.8 µm".
fn grades_text(all: &[LumpedSummary]) -> String {
    let Some(first) = all.first() else {
        return String::new();
    };
    let ra: Vec<String> = by_roughness(all, first.pinion_torque_nm)
        .iter()
        .filter_map(|r| r.roughness.as_ref().map(|g| format!("{}", g.ra_um)))
        .collect();
    format!("{} µm", ra.join(", "))
}

/// The mean stiffness's trend over the grades at each load.
fn stiffness_trends(all: &[LumpedSummary]) -> String {
    let mut loads: Vec<f64> = all.iter().map(|r| r.pinion_torque_nm).collect();
    loads.sort_by(f64::total_cmp);
    loads.dedup();
    loads
        .iter()
        .map(|&t| {
            let k: Vec<f64> = by_roughness(all, t)
                .iter()
                .map(|r| r.mesh_stiffness_n_per_m.mean)
                .collect();
            format!("{} at {t:.2} N·m", roughness_trend(&k))
        })
        .collect::<Vec<_>>()
        .join(" and ")
}

fn stiffness_table(s: &mut String, all: &[LumpedSummary]) {
    let _ = writeln!(
        s,
        "Mesh stiffness and response per roughness grade (tangent k = dF/dδ from our LTCA with the grade's topography):\n"
    );
    let _ = writeln!(
        s,
        "| pinion torque (N·m) | flanks | μ | mean k (N/m) | k vs smooth (%) | pinion / wheel velocity RMS (mm/s) | RMS acceleration along the normal (m/s²) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for r in all {
        let smooth = all
            .iter()
            .find(|x| x.roughness.is_none() && x.pinion_torque_nm == r.pinion_torque_nm)
            .map_or(f64::NAN, |x| x.mesh_stiffness_n_per_m.mean);
        let _ = writeln!(
            s,
            "| {:.2} | {} | {:.3} | {:.4e} | {:+.2} | {:.3} / {:.3} | {:.1} |",
            r.pinion_torque_nm,
            grade(r),
            r.friction_coefficient,
            r.mesh_stiffness_n_per_m.mean,
            100.0 * (r.mesh_stiffness_n_per_m.mean / smooth - 1.0),
            1e3 * r.member_velocity_rms_m_s[0],
            1e3 * r.member_velocity_rms_m_s[1],
            r.rms_acceleration_m_s2.mesh_normal
        );
    }
    let _ = writeln!(
        s,
        "\nSeed 003 finds the mesh stiffness falling as the roughness grows (its Figure 12) and the vibration rising. In our model, from the smooth flanks through Ra {}, the mean stiffness {}: the topography moves each slice's first-touch lag and so the load sharing, but the slices' load–deflection law is that of smooth flanks on the FE compliance of smooth flanks. Asperity contact compliance, the mechanism of seed 003's account, is not in the model. Differences in velocity between grades come from the one drawn W–M realization (seed 3) as much as from Ra.\n",
        grades_text(all),
        stiffness_trends(all)
    );
}

fn roughness_table(s: &mut String, all: &[LumpedSummary]) {
    let _ = writeln!(
        s,
        "What of the roughness the model carries (per grade at the first load):\n"
    );
    let _ = writeln!(
        s,
        "| Ra (µm) | composite Ra (µm) | D | G (m) | W–M terms carried / total | Rq carried / total (µm) | shortest wavelength carried (mm) | topography node spacing (mm) | FE element along the profile (mm) | Hertz half-width (mm) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    let t1 = all[0].pinion_torque_nm;
    for g in all
        .iter()
        .filter(|r| r.pinion_torque_nm == t1)
        .filter_map(|r| r.roughness.as_ref())
    {
        let _ = writeln!(
            s,
            "| {:.1} | {:.3} | {:.3} | {:.2e} | {} / {} | {:.3} / {:.3} ({:.0} %) | {:.3} | {:.3} | {:.3} | {:.3} |",
            g.ra_um,
            g.composite_ra_um,
            g.dimension,
            g.scale_m,
            g.terms_resolved,
            g.terms,
            1e6 * g.rq_resolved_m,
            1e6 * g.rq_m,
            100.0 * g.rq_resolved_m / g.rq_m,
            1e3 * g.shortest_resolved_wavelength_m,
            1e3 * g.node_spacing_m,
            1e3 * g.mesh_element_profile_m,
            1e3 * g.hertz_half_width_m
        );
    }
    let _ = writeln!(
        s,
        "\nThe W–M profile runs from λ_c = 0.8 mm down to λ_s = 2.5 µm along the profile; the topography grid carries only the terms longer than two node spacings, the profile's longest wavelengths. Because a W–M spectrum puts most of its power there, those few terms hold the share of Rq given above, but they are a waviness of about the contact's own width, not roughness: everything shorter, the asperities that decide real contact area and contact compliance, is left out. The FE meshes (6 × 10 flank elements) carry none of it; they are the smooth flanks' meshes, and their element along the profile is longer than every wavelength of the profile. D from seed 003's Eq. (41) (see the table below) and G set for the composite Ra, since its Eq. (34) does not reproduce its own Ra.\n\n"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roughness_trend_reads_every_step() {
        assert_eq!(
            roughness_trend(&[6.0, 6.1, 6.2, 6.3]),
            "rises with every grade"
        );
        assert_eq!(roughness_trend(&[6.3, 6.2, 6.1]), "falls with every grade");
        assert_eq!(
            roughness_trend(&[6.04, 6.05, 6.08, 6.06]),
            "has no monotone trend"
        );
    }

    #[test]
    fn printed_means_agree_only_to_their_digits() {
        assert_eq!(agree_word(&[4.123, 4.413], &[4.1232, 4.4128]), "agree");
        assert_eq!(agree_word(&[4.195, 4.384], &[4.123, 4.413]), "do not agree");
    }
}
