//! The one gatherer of the report's figures and sections: every section's
//! `section(..)` called with the stages' output root, the result gathered
//! in [`ReportFigures`] by the section that shows it.

use crate::report::figures::{copied, Figure};
use crate::report::sections::loaded_contact::{pattern_figure, te_figures};
use std::path::Path;

/// The report's figures by the section that shows them.
#[derive(Debug, Clone, Default)]
pub struct ReportFigures {
    /// Loaded TE against pinion rotation, per load (ascending) and blank
    /// combination (standard wheel first).
    pub loaded_te: Vec<Figure>,
    /// Contact patterns at [`ReportFigures::pattern_torque_nm`].
    pub patterns: Vec<Figure>,
    pub pattern_torque_nm: Option<f64>,
    /// The contact patterns as numbers, one line per blank combination
    /// (markdown list items).
    pub pattern_numbers: String,
    /// The reduced model's error to the reference against its run time.
    pub tradeoff: Option<Figure>,
    /// The flank stage's plots: unloaded TE, path of contact, ease-off.
    pub unloaded: Vec<Figure>,
    /// The reference's mesh levels and penalty against the reduced model's
    /// differences (no figures).
    pub reference_uncertainty: crate::report::sections::reference_uncertainty::ReferenceUncertainty,
    /// The ablation study of the element's modelling changes (markdown, no
    /// figures).
    pub ablation: String,
    /// The reduced model at its stiffness grid's limit (markdown).
    pub grid_convergence: String,
    /// The reference FE's tooth root stresses over the mesh cycle.
    pub root_stress: crate::report::sections::root_stress::RootStressSection,
    /// The calibrated variant of the design (no figures).
    pub calibrated_variant: crate::report::sections::calibrated_variant::CalibratedSection,
    /// The "Contact laws" section with its load-run charts (seeds 001/002).
    pub contact_laws: Option<crate::report::sections::contact_laws::ContactLaws>,
    /// The lumped model's section with its charts.
    pub lumped: super::sections::lumped::LumpedSection,
    /// The misalignment sensitivity section with its charts.
    pub sensitivity: super::sections::sensitivity::SensitivitySection,
    /// The compliant-bearing multibody section with its spectrograms.
    pub compliant: super::sections::compliant_bearings::CompliantSection,
    /// The flexible gearbox's modes, crossings and run-up.
    pub gearbox: super::sections::gearbox::GearboxSection,
    /// Static against dynamic TE (the white paper's first use case).
    pub ste_dte: super::sections::ste_dte::SteDteSection,
    /// The rattle run, its impacts and wedging.
    pub rattle: super::sections::rattle::RattleSection,
    /// The stress matrix's section and outcome grid.
    pub stress: crate::report::sections::stress::StressSection,
    /// Run time against error for every stage, with its Pareto charts.
    pub stage_tradeoffs: crate::report::sections::stage_tradeoffs::TradeoffSection,
}

impl ReportFigures {
    /// Every figure.
    pub fn all(&self) -> impl Iterator<Item = &Figure> {
        self.loaded_te
            .iter()
            .chain(&self.patterns)
            .chain(&self.tradeoff)
            .chain(&self.unloaded)
            .chain(self.contact_laws.iter().flat_map(|c| &c.figures))
            .chain(&self.lumped.figures)
            .chain(&self.sensitivity.figures)
            .chain(&self.compliant.figures)
            .chain(&self.gearbox.figures)
            .chain(&self.ste_dte.figures)
            .chain(&self.rattle.figures)
            .chain(&self.stress.figure)
            .chain(&self.stage_tradeoffs.figures)
            .chain(&self.root_stress.figures)
    }
}

/// The flank stage's plots that the report shows, copied from `flanks`
/// into `reports` (so that `report.md` links them next to it).
pub const UNLOADED_PLOTS: [(&str, &str, &str); 3] = [
    ("Unloaded transmission error", "te.svg", "unloaded_te.svg"),
    ("Path of contact", "contact_path.svg", "contact_path.svg"),
    ("Ease-off", "ease_off.svg", "ease_off.svg"),
];

/// Every figure of the report: the flank stage's plots from `flanks`, and,
/// with the stages' output root `out` and the scene, the loaded TE curves,
/// the contact patterns at the largest torque and the run-time trade-off.
/// SVG files are written to (or copied into) `reports`.
pub fn report_figures(
    out: Option<&Path>,
    scene: Option<&geometry::scene::Scene>,
    flanks: &Path,
    reports: &Path,
) -> ReportFigures {
    // The plots below write into it.
    let _ = std::fs::create_dir_all(reports);
    let mut f = ReportFigures {
        unloaded: UNLOADED_PLOTS
            .iter()
            .filter_map(|(title, from, to)| copied(title, &flanks.join(from), reports, to))
            .collect(),
        lumped: super::sections::lumped::section(out, reports),
        sensitivity: super::sections::sensitivity::section(
            out,
            scene.map(|s| s.name.as_str()),
            reports,
        ),
        compliant: super::sections::compliant_bearings::section(
            out,
            reports,
            &super::results::Stamp::now(),
        ),
        gearbox: super::sections::gearbox::section(out, reports),
        ste_dte: super::sections::ste_dte::section(out, reports),
        rattle: super::sections::rattle::section(out, reports),
        ..Default::default()
    };
    let (Some(o), Some(s)) = (out, scene) else {
        return f;
    };
    f.loaded_te = te_figures(o, &s.name, reports, &s.pinion_torque_nm);
    f.stress = crate::report::sections::stress::section(o, &s.name, reports);
    f.stage_tradeoffs = crate::report::sections::stage_tradeoffs::section(o, &s.name, reports);
    // Only the plot the trade-off study recorded, of the sweep there now.
    let ref_dir = o.join(&s.name).join("reference");
    f.tradeoff = matches!(
        formats::added_files::read_added(&ref_dir, "tradeoff.svg"),
        Ok(formats::added_files::AddedState::Current(_))
    )
    .then(|| {
        copied(
            "Reduced model: error to the reference against run time",
            &ref_dir.join("tradeoff.svg"),
            reports,
            "tradeoff.svg",
        )
    })
    .flatten();
    // The contact pressure at every load, both models (read once); the
    // largest load's also as sentences beside its pattern figures.
    let mut pressure_rows = Vec::new();
    for wb in &s.blanks.wheel {
        for pb in &s.blanks.pinion {
            let blank = format!("{pb:?}_{wb:?}").to_lowercase();
            for &t in &s.pinion_torque_nm {
                if let Some(n) =
                    crate::report::sections::loaded_contact::pattern_points(o, &s.name, &blank, t)
                        .and_then(|(a, b)| {
                            crate::report::sections::pattern_numbers::numbers(&a, &b)
                        })
                {
                    pressure_rows.push((blank.clone(), t, n));
                }
            }
        }
    }
    if let Some(&t) = s.pinion_torque_nm.last() {
        for wb in &s.blanks.wheel {
            for pb in &s.blanks.pinion {
                let blank = format!("{pb:?}_{wb:?}").to_lowercase();
                f.patterns
                    .extend(pattern_figure(o, &s.name, &blank, t, reports));
            }
        }
        for (blank, _, n) in pressure_rows.iter().filter(|r| r.1 == t) {
            f.pattern_numbers.push_str(&format!(
                "- {}\n",
                crate::report::sections::pattern_numbers::sentence(
                    &blank.replace('_', " / "),
                    t,
                    n
                )
            ));
        }
        f.pattern_torque_nm = (!f.patterns.is_empty()).then_some(t);
    }
    let table = crate::report::sections::pattern_numbers::table(&pressure_rows);
    if !table.is_empty() {
        f.pattern_numbers.push('\n');
        f.pattern_numbers.push_str(&table);
    }
    f
}
