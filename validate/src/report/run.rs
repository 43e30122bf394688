//! `validate report`: the stages' result sets checked to come from the
//! same inputs, the UTCA cross-check, the loaded-TE comparison, every
//! section gathered ([`crate::report::gather`]) and the report files
//! written ([`crate::report::write`]).

use anyhow::Context;
use std::path::Path;

/// What `validate report` reads and where it writes.
pub struct ReportInputs<'a> {
    /// Scene or design file.
    pub scene: &'a Path,
    /// Output folder of `preprocess flanks` (for the plots).
    pub flanks: &'a Path,
    /// Report folder.
    pub reports: &'a Path,
    /// Positions per mesh cycle of the UTCA cross-check's direct search.
    pub positions: usize,
    /// Output root of the solver and `validate reference`: with it, the
    /// report also compares their loaded TE.
    pub out: Option<&'a Path>,
    /// Mesh root (the convergence study's mesh check).
    pub meshes: &'a Path,
    /// README whose results table is replaced.
    pub readme: &'a Path,
}

/// What a report run made.
pub struct Made {
    /// The design's (or scene's) name.
    pub scene: String,
    pub loaded_te_rows: usize,
    pub figures: usize,
    pub readme_updated: bool,
}

/// Makes the report of `i`.
pub fn run(i: &ReportInputs) -> anyhow::Result<Made> {
    let input = preprocess::flank_stage::load_input(i.scene)?;
    // The flank stage's set unchanged since written, and made from the same
    // design as the solver's and the reference's sets.
    formats::result_set::verify_files(i.flanks)?;
    if let Some(o) = i.out {
        let name = &input.name;
        let mut sets = vec![
            i.flanks.to_path_buf(),
            o.join(name).join("ltca"),
            o.join(name).join("multibody"),
        ];
        sets.extend(
            crate::reference::reference_stage::LEVELS_FINEST_FIRST
                .iter()
                .map(|l| crate::reference::reference_stage::reference_dir(o, name, l)),
        );
        formats::result_set::check_same_inputs(
            &sets.iter().map(|p| p.as_path()).collect::<Vec<_>>(),
        )?;
    }
    let c = crate::studies::utca_check::check(&input, i.positions).context("UTCA cross-check")?;
    let published = crate::report::published::te_ptp_1nm(&input.pair.published)?;
    let sc = geometry::scene::Scene::load(i.scene).ok();
    let loaded = match (i.out, sc.as_ref()) {
        (Some(o), Some(sc)) => {
            crate::report::comparison::compare(o, &sc.scene.name, &input.pair.published, i.meshes)?
        }
        _ => None,
    };
    let mut figures = crate::report::gather::report_figures(
        i.out,
        sc.as_ref().map(|s| &s.scene),
        i.flanks,
        i.reports,
    );
    if let (Some(o), Some(sc), Some(l)) = (i.out, sc.as_ref(), loaded.as_ref()) {
        figures.reference_uncertainty =
            crate::report::sections::reference_uncertainty::build(o, &sc.scene, &l.rows)?;
        figures.ablation = crate::report::sections::ablation::build(o, &sc.scene.name, &l.rows)?;
        figures.grid_convergence =
            crate::report::sections::grid_convergence::build(o, &sc.scene.name, &l.rows)?;
    }
    if let (Some(o), Some(sc)) = (i.out, sc.as_ref()) {
        figures.calibrated_variant = crate::report::sections::calibrated_variant::build(
            o,
            sc,
            loaded.as_ref().map_or(&[][..], |l| l.rows.as_slice()),
        )?;
    }
    if let (Some(o), Some(sc)) = (i.out, sc.as_ref()) {
        figures.root_stress = crate::report::sections::root_stress::build(o, sc, i.reports)?;
    }
    if let Some(o) = i.out {
        figures.contact_laws = Some(crate::report::sections::contact_laws::build(
            o,
            i.scene.parent(),
            i.reports,
        )?);
    }
    let written = crate::report::write(
        i.reports,
        &c,
        published.as_ref(),
        loaded.as_ref(),
        &figures,
        i.readme,
    )?;
    Ok(Made {
        scene: c.name.clone(),
        loaded_te_rows: loaded.as_ref().map_or(0, |l| l.rows.len()),
        figures: figures.all().count(),
        readme_updated: written.readme_updated,
    })
}
