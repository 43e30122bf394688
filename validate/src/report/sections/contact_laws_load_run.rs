//! The load-run table of the "Contact laws" section and what it says about
//! the tangential force: both runs of a seed beside the values the seed
//! prints, and the seed's own explanation of its tangential-force
//! difference checked against where our contact acts.
//!
//! The tangential force is the circumferential component of the contact
//! forces on the wheel at their contact points (Σ F λ₂ / ρ₂, see
//! `solver::element::slices::Slice::wheel_tangential`), not the mesh torque
//! over the outer pitch radius: its mean equals 2T/d only when the contact
//! acts on the outer pitch circle, so the comparison with 2T/d can fail.

use crate::report::published::{Quoted, SeedContactLaw};
use formats::summaries::{LoadRunSummary, SampledLoadRun};
use std::fmt::Write as _;

/// Signed relative difference in percent (in powers of ten below
/// 0.001 %, so that a small difference does not print as zero).
pub fn pct(x: f64) -> String {
    let v = 100.0 * x;
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:+.1e} %")
    } else {
        format!("{v:+.3} %")
    }
}

/// |x| in percent for differences near zero.
pub fn small_pct(x: f64) -> String {
    format!("{:.1e} %", 100.0 * x.abs())
}

/// A seed's value as it prints it (its own digits), and where.
fn quoted(v: Option<&Quoted>, unit: &str) -> String {
    v.map_or_else(
        || "not given".to_string(),
        |p| format!("{}{unit} ({})", p.value, p.source),
    )
}

fn pair(a: Option<&Quoted>, b: Option<&Quoted>) -> String {
    match (a, b) {
        (Some(a), Some(b)) if a.source == b.source => {
            format!("{} / {} ({})", a.value, b.value, a.source)
        }
        (None, None) => "not given".into(),
        (a, b) => format!("{} / {}", quoted(a, ""), quoted(b, "")),
    }
}

/// What the seed's printed mean tangential force F and its 2T/d imply
/// for a load T: the relative difference on the base of 2T/d
/// (F / (2T/d) − 1), the radius T / F where its contact acts on average
/// and the outer pitch radius T / (2T/d), mm. None without both values.
pub fn seed_tangential(p: &SeedContactLaw, load_nm: f64) -> Option<SeedTangential> {
    let (f, t) = (
        p.tangential_force_n.as_ref()?,
        p.tangential_force_theory_n.as_ref()?,
    );
    Some(SeedTangential {
        error_of_theory: f.value / t.value - 1.0,
        contact_radius_mm: load_nm / f.value * 1e3,
        outer_pitch_radius_mm: load_nm / t.value * 1e3,
        source: f.source.clone(),
    })
}

/// See [`seed_tangential`].
#[derive(Debug, Clone, PartialEq)]
pub struct SeedTangential {
    pub error_of_theory: f64,
    pub contact_radius_mm: f64,
    pub outer_pitch_radius_mm: f64,
    pub source: String,
}

/// "above" for a positive difference, "below" for a negative one, "at"
/// for none.
pub fn above_below(x: f64) -> &'static str {
    if x > 0.0 {
        "above"
    } else if x < 0.0 {
        "below"
    } else {
        "at"
    }
}

/// "inside" when `radius` is below `reference`, "outside" above, "on" at
/// it.
pub fn inside_outside(radius: f64, reference: f64) -> &'static str {
    if radius < reference {
        "inside"
    } else if radius > reference {
        "outside"
    } else {
        "on"
    }
}

/// The load-run table of one seed.
pub fn table(s: &mut String, p: &SeedContactLaw, i: &LoadRunSummary, e: &LoadRunSummary) {
    let _ = writeln!(
        s,
        "| quantity | impact law | FE-analytical element | seed {} |",
        p.id
    );
    let _ = writeln!(s, "|---|---|---|---|");
    let mut t = Rows { s, i, e };
    speed_torque_and_tangential_rows(&mut t, p);
    fluctuation_rows(&mut t, p);
    mesh_force_and_cost_rows(&mut t, p);
    t.s.push('\n');
}

/// The table being written: each row shows the impact-law run `i` and the
/// FE-analytical element's run `e` beside the seed's value.
struct Rows<'a> {
    s: &'a mut String,
    i: &'a LoadRunSummary,
    e: &'a LoadRunSummary,
}

impl Rows<'_> {
    fn row(&mut self, q: &str, f: &dyn Fn(&LoadRunSummary) -> String, seed: String) {
        let _ = writeln!(self.s, "| {q} | {} | {} | {seed} |", f(self.i), f(self.e));
    }
}

/// The steady window, the mean wheel speed and mesh torque, the tangential
/// force against 2T/d, and where the contact acts.
fn speed_torque_and_tangential_rows(t: &mut Rows, p: &SeedContactLaw) {
    let i = t.i;
    t.row(
        "steady window, s (mesh cycles)",
        &|l| {
            format!(
                "{:.3} – {:.3} ({})",
                l.window_s[0], l.window_s[1], l.window_mesh_cycles
            )
        },
        String::new(),
    );
    t.row(
        &format!(
            "mean wheel speed, °/s (kinematic {:.3})",
            i.wheel_speed_kinematic_deg_s
        ),
        &|l| format!("{:.3}", l.wheel_speed_mean_deg_s),
        quoted(p.wheel_speed_deg_s.as_ref(), ""),
    );
    t.row(
        "mean wheel speed against kinematic",
        &|l| pct(l.wheel_speed_error),
        quoted(p.wheel_speed_error_percent.as_ref(), " %"),
    );
    t.row(
        "mean wheel mesh torque against the load",
        &|l| pct(l.torque_balance_error),
        String::new(),
    );
    t.row(
        &format!(
            "mean tangential force (contact forces at their points), N (2T/d = {:.1})",
            i.tangential_force_theory_n
        ),
        &|l| format!("{:.1}", l.tangential_force_mean_n),
        match (
            p.tangential_force_n.as_ref(),
            p.tangential_force_theory_n.as_ref(),
        ) {
            (Some(f), Some(t)) if f.source == t.source => {
                format!("{} against 2T/d = {} ({})", f.value, t.value, f.source)
            }
            (f, _) => quoted(f, ""),
        },
    );
    t.row(
        "largest tangential force, N",
        &|l| format!("{:.1}", l.tangential_force_max_n),
        quoted(p.tangential_force_max_n.as_ref(), ""),
    );
    t.row(
        "mean tangential force against 2T/d, (mean − 2T/d) / mean",
        &|l| pct(l.tangential_force_error_of_mean),
        quoted(p.tangential_force_error_percent.as_ref(), " %"),
    );
    let seed = seed_tangential(p, i.wheel_torque_nm);
    t.row(
        "mean tangential force against 2T/d, mean / (2T/d) − 1",
        &|l| pct(l.tangential_force_error),
        seed.as_ref().map_or_else(String::new, |t| {
            format!(
                "{} (from {}'s two values)",
                pct(t.error_of_theory),
                t.source
            )
        }),
    );
    t.row(
        &format!(
            "where the contact acts: mean wheel torque / mean tangential force, mm (outer pitch radius d/2 = {:.2})",
            i.outer_pitch_radius_mm
        ),
        &|l| format!("{:.2}", l.contact_radius_mm),
        seed.as_ref().map_or_else(String::new, |t| {
            format!(
                "{:.2} (the load / {}'s mean; d/2 = {:.2} from its 2T/d)",
                t.contact_radius_mm, t.source, t.outer_pitch_radius_mm
            )
        }),
    );
}

/// The wheel speed and tangential force fluctuations, every step and as
/// sampled; the seed's on the row sampled as the seed sampled.
fn fluctuation_rows(t: &mut Rows, p: &SeedContactLaw) {
    let (i, e) = (t.i, t.e);
    // The seed's fluctuations sit on the row sampled as the seed sampled,
    // or on the every-step row when neither run is sampled.
    let sampled = i.sampled.as_ref().or(e.sampled.as_ref());
    let seed_speed = pair(
        p.speed_fluctuation_mean_deg_s.as_ref(),
        p.speed_fluctuation_max_deg_s.as_ref(),
    );
    let seed_force = pair(
        p.force_fluctuation_mean_n.as_ref(),
        p.force_fluctuation_max_n.as_ref(),
    );
    let every = |seed: &String| {
        if sampled.is_some() {
            String::new()
        } else {
            seed.clone()
        }
    };
    t.row(
        "wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s, every step",
        &|l| {
            format!(
                "{:.2} / {:.2}",
                l.wheel_speed_fluctuation_mean_deg_s, l.wheel_speed_fluctuation_max_deg_s
            )
        },
        every(&seed_speed),
    );
    if let Some(sm) = sampled {
        t.row(
            &sampled_label(
                "wheel speed fluctuation \\|ω₂ − kinematic\\| mean / max, °/s",
                sm,
            ),
            &|l| {
                l.sampled.as_ref().map_or("not sampled".into(), |x| {
                    format!(
                        "{:.2} / {:.2}",
                        x.wheel_speed_fluctuation_mean_deg_s, x.wheel_speed_fluctuation_max_deg_s
                    )
                })
            },
            seed_speed.clone(),
        );
    }
    t.row(
        "tangential force fluctuation \\|F_t − mean\\| mean / max, N, every step",
        &|l| {
            format!(
                "{:.1} / {:.1}",
                l.tangential_force_fluctuation_mean_n, l.tangential_force_fluctuation_max_n
            )
        },
        every(&seed_force),
    );
    if let Some(sm) = sampled {
        t.row(
            &sampled_label(
                "tangential force fluctuation \\|F_t − mean\\| mean / max, N",
                sm,
            ),
            &|l| {
                l.sampled.as_ref().map_or("not sampled".into(), |x| {
                    format!(
                        "{:.1} / {:.1}",
                        x.tangential_force_fluctuation_mean_n, x.tangential_force_fluctuation_max_n
                    )
                })
            },
            seed_force.clone(),
        );
    }
}

/// The meshing force against theory, TE, efficiency and the runs' cost.
fn mesh_force_and_cost_rows(t: &mut Rows, p: &SeedContactLaw) {
    let i = t.i;
    t.row(
        &format!(
            "meshing force mean / max, N (theory T / (r_m cos α_n cos β_m) = {:.0})",
            i.mesh_force_theory_n
        ),
        &|l| format!("{:.0} / {:.0}", l.mesh_force_mean_n, l.mesh_force_max_n),
        p.mesh_force_statement
            .as_deref()
            .unwrap_or("not given")
            .to_string(),
    );
    t.row(
        "meshing force mean against theory",
        &|l| pct(l.mesh_force_mean_n / l.mesh_force_theory_n - 1.0),
        String::new(),
    );
    t.row(
        "TE mean / peak-to-peak, µrad",
        &|l| format!("{:.1} / {:.1}", l.te_mean_urad, l.te_ptp_urad),
        "not given".into(),
    );
    t.row(
        "mesh efficiency mean(T₂ω₂) / mean(T₁ω₁)",
        &|l| format!("{:.4}", l.mesh_efficiency),
        "not given".into(),
    );
    t.row(
        "steps (rejected)",
        &|l| format!("{} ({})", l.steps, l.rejected_steps),
        String::new(),
    );
    t.row(
        "CPU per step, µs (whole run, s)",
        &|l| format!("{:.1} ({:.1})", l.cpu_s_per_step * 1e6, l.cpu_s),
        String::new(),
    );
}

fn sampled_label(what: &str, sm: &SampledLoadRun) -> String {
    format!(
        "{what}, samples every {} ms ({} samples)",
        sm.interval_s * 1e3,
        sm.samples
    )
}

/// The means and the tangential force, as a list item of the section's
/// "Where the differences come from": the means of speed and torque
/// balance in a steady run; the tangential force lies above or below 2T/d
/// by where the contact acts, against the outer pitch radius, and the
/// seed's printed values are set beside ours on the same terms.
pub fn tangential_paragraph(
    s: &mut String,
    p: &SeedContactLaw,
    li: &LoadRunSummary,
    le: &LoadRunSummary,
) {
    let _ = writeln!(
        s,
        "- Means: both laws hold the mean wheel speed within {} and {} of kinematic and the mean wheel mesh torque within {} and {} of the load over whole mesh cycles of the steady window: in a steady run the time means have to balance, whatever the contact law.",
        small_pct(li.wheel_speed_error),
        small_pct(le.wheel_speed_error),
        small_pct(li.torque_balance_error),
        small_pct(le.torque_balance_error),
    );
    let _ = write!(
        s,
        "- Tangential force: the wheel torque is the tangential force times the radius where the contact acts, so the mean tangential force equals 2T/d only where that radius is the outer pitch radius d/2 = {:.2} mm. The contact acts on average at {:.2} mm (impact law) and {:.2} mm (element), {} and {} the outer pitch circle, so the mean tangential force lies {:.2} % {} and {:.2} % {} 2T/d (relative to the mean, the base on which seed 002 states its difference).",
        li.outer_pitch_radius_mm,
        li.contact_radius_mm,
        le.contact_radius_mm,
        inside_outside(li.contact_radius_mm, li.outer_pitch_radius_mm),
        inside_outside(le.contact_radius_mm, le.outer_pitch_radius_mm),
        100.0 * li.tangential_force_error_of_mean.abs(),
        above_below(li.tangential_force_error_of_mean),
        100.0 * le.tangential_force_error_of_mean.abs(),
        above_below(le.tangential_force_error_of_mean),
    );
    match (
        seed_tangential(p, li.wheel_torque_nm),
        p.tangential_force_error_percent.as_ref(),
    ) {
        (Some(t), Some(q)) => {
            let _ = writeln!(
                s,
                " Seed {}'s {} % ({}) puts its contact at {:.2} mm on average (the load over its mean tangential force), {} its outer pitch circle of {:.2} mm; the seed gives the same cause itself (the theoretical value takes the contact point on the outer pitch circle, the real contact is not there). Our element's contact lies {:.2} mm {} the seed's.",
                p.id,
                q.value,
                q.source,
                t.contact_radius_mm,
                inside_outside(t.contact_radius_mm, t.outer_pitch_radius_mm),
                t.outer_pitch_radius_mm,
                (le.contact_radius_mm - t.contact_radius_mm).abs(),
                inside_outside(le.contact_radius_mm, t.contact_radius_mm),
            );
        }
        _ => s.push('\n'),
    }
}

/// One quantity of a load run.
type Quantity = fn(&LoadRunSummary) -> f64;

/// Seed 001's impact law with its damping ramped in by the haversine
/// step it names against ADAMS's cubic STEP (the run above): the same
/// quantities side by side and their relative differences.
pub fn step_shape_table(s: &mut String, cubic: &LoadRunSummary, haversine: &LoadRunSummary) {
    let _ = writeln!(
        s,
        "The damping ramp's shape: seed 001 names STEP a haversine step; ADAMS's STEP, which the impact-law run above uses, is a cubic. The same run with the haversine ramp (scene `seed001_impact_haversine`):\n"
    );
    let _ = writeln!(s, "| quantity | cubic STEP | haversine | difference |");
    let _ = writeln!(s, "|---|---|---|---|");
    let rows: [(&str, Quantity); 7] = [
        ("mean wheel speed, °/s", |l| l.wheel_speed_mean_deg_s),
        ("wheel speed fluctuation mean, °/s", |l| {
            l.wheel_speed_fluctuation_mean_deg_s
        }),
        ("wheel speed fluctuation max, °/s", |l| {
            l.wheel_speed_fluctuation_max_deg_s
        }),
        ("mean tangential force, N", |l| l.tangential_force_mean_n),
        ("tangential force fluctuation max, N", |l| {
            l.tangential_force_fluctuation_max_n
        }),
        ("meshing force max, N", |l| l.mesh_force_max_n),
        ("mesh efficiency", |l| l.mesh_efficiency),
    ];
    for (q, f) in rows {
        let (a, b) = (f(cubic), f(haversine));
        let _ = writeln!(
            s,
            "| {q} | {a:.4} | {b:.4} | {} |",
            if a != 0.0 {
                pct(b / a - 1.0)
            } else {
                "–".into()
            }
        );
    }
    s.push('\n');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn above_and_below_follow_the_sign_of_the_difference() {
        assert_eq!(above_below(0.05), "above");
        assert_eq!(above_below(-0.05), "below");
        assert_eq!(above_below(0.0), "at");
    }

    #[test]
    fn inside_and_outside_compare_the_radius_with_its_reference() {
        assert_eq!(inside_outside(79.2, 83.3), "inside");
        assert_eq!(inside_outside(85.0, 83.3), "outside");
        assert_eq!(inside_outside(83.3, 83.3), "on");
    }

    /// Seed 002's Table 2: 24,799.9 N against 2T/d = 23,603.5 N at
    /// 1,964.99 N·m is 5.07 % on the base of 2T/d (4.82 % on the base of
    /// the mean, as printed), the contact at 79.23 mm against 83.25 mm.
    #[test]
    fn seed_002_table_2_gives_its_contact_radius_and_the_difference_on_either_base() {
        let p = &crate::report::published::seed_contact_laws()[1];
        let t = seed_tangential(p, 1964.99).unwrap();
        assert!((100.0 * t.error_of_theory - 5.069).abs() < 1e-3, "{t:?}");
        assert!((t.contact_radius_mm - 79.234).abs() < 1e-3, "{t:?}");
        assert!((t.outer_pitch_radius_mm - 83.250).abs() < 1e-3, "{t:?}");
        let f = p.tangential_force_n.as_ref().unwrap().value;
        let printed = p.tangential_force_error_percent.as_ref().unwrap().value;
        let of_mean = 100.0 * (f - p.tangential_force_theory_n.as_ref().unwrap().value) / f;
        assert!((of_mean - printed).abs() < 5e-3, "{of_mean} vs {printed}");
    }
}
