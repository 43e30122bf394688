//! How much of seed 003's W–M roughness the LTCA's topography grid and the
//! FE meshes can carry, counted as `lumped_roughness_resolution` counts it:
//! a W–M term of wavelength λₙ = λ_c γ⁻ⁿ is resolved by a grid of spacing s
//! when λₙ ≥ 2s (two samples per wavelength). For the LTCA, s is the
//! lumped scene's topography node spacing along the profile
//! ([`solver::lumped::roughness::roughened`], the same call the lumped runs
//! make); for an FE level, s is the profile length over the level's
//! elements along the profile. The FE meshes carry no roughness at all
//! (their flanks are the smooth generated ones): their count is only what a
//! mesh of that element length could represent.

use anyhow::Context;
use geometry::pair::FlankPair;
use geometry::roughness::WmProfile;
use geometry::scene::{LoadedScene, Scene};
use serde::{Deserialize, Serialize};

/// One FE level's element length along the profile.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FeElement {
    pub level: String,
    pub profile_elements: u32,
    pub element_mm: f64,
}

/// One roughness grade against the LTCA grid and the FE levels.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct GradeResolution {
    pub ra_um: f64,
    /// √2 Ra: the one relative topography of two rough flanks.
    pub composite_ra_um: f64,
    pub dimension: f64,
    /// W–M terms of the ISO band and their longest and shortest wavelength, mm.
    pub terms: usize,
    pub wavelengths_mm: [f64; 2],
    /// Terms the LTCA's topography carries, its shortest wavelength, mm.
    pub ltca_terms: usize,
    pub ltca_shortest_wavelength_mm: f64,
    /// Rq of the whole profile and of the carried terms, µm.
    pub rq_um: f64,
    pub ltca_rq_um: f64,
    /// Terms an FE mesh of each level could carry (same order as
    /// [`Resolution::fe`]).
    pub fe_terms: Vec<usize>,
}

/// The roughness grades of the lumped scene against what resolves them.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Resolution {
    pub lumped_scene: String,
    pub profile_length_mm: f64,
    /// Topography nodes along the profile and their spacing, mm.
    pub profile_nodes: usize,
    pub node_spacing_mm: f64,
    /// Slices across the face width per tooth pair (the LTCA's contact lines).
    pub slices: usize,
    pub fe: Vec<FeElement>,
    pub grades: Vec<GradeResolution>,
}

/// Terms of `wm` with wavelength ≥ 2 `spacing_m`.
fn resolved(wm: &WmProfile, spacing_m: f64) -> usize {
    wm.frequencies_per_m()
        .iter()
        .filter(|w| 1.0 / **w >= 2.0 * spacing_m)
        .count()
}

/// The lumped scene's grades on `smooth` (the pair's loaded flanks),
/// against its topography grid and the FE levels of `fe_scene`; None when
/// the lumped scene has no `[lumped.roughness]`.
pub fn resolution(
    lumped: &LoadedScene,
    smooth: &FlankPair,
    fe_scene: &Scene,
) -> anyhow::Result<Option<Resolution>> {
    let Some(r) = lumped
        .scene
        .lumped
        .as_ref()
        .and_then(|l| l.roughness.as_ref())
    else {
        return Ok(None);
    };
    let m = &fe_scene.mesh;
    let levels = [
        ("reduced", m.reduced_order),
        ("medium", m.medium()),
        ("reference", m.reference),
    ];
    let length = solver::lumped::roughness::profile_length(smooth)?;
    let fe: Vec<FeElement> = levels
        .iter()
        .map(|(name, e)| FeElement {
            level: name.to_string(),
            profile_elements: e.profile,
            element_mm: length / e.profile as f64 * 1e3,
        })
        .collect();
    let mut grades = Vec::new();
    let mut spacing_mm = 0.0;
    for &ra in &r.ra_um {
        let (_, s) = solver::lumped::roughness::roughened(
            &lumped.pair,
            smooth,
            ra,
            r.seed,
            [r.profile_nodes, r.face_nodes],
            lumped.scene.mesh.reduced_order.profile as usize,
        )
        .with_context(|| format!("roughness grade Ra {ra} µm"))?;
        spacing_mm = s.node_spacing_m * 1e3;
        let wm = WmProfile::with_ra(
            *WmProfile::seed003(ra, r.seed)?.spec(),
            s.composite_ra_um * 1e-6,
            r.seed,
        )?;
        let w = wm.frequencies_per_m();
        grades.push(GradeResolution {
            ra_um: ra,
            composite_ra_um: s.composite_ra_um,
            dimension: s.dimension,
            terms: s.terms,
            wavelengths_mm: [1e3 / w[0], 1e3 / w[w.len() - 1]],
            ltca_terms: s.terms_resolved,
            ltca_shortest_wavelength_mm: s.shortest_resolved_wavelength_m * 1e3,
            rq_um: s.rq_m * 1e6,
            ltca_rq_um: s.rq_resolved_m * 1e6,
            fe_terms: fe
                .iter()
                .map(|f| resolved(&wm, f.element_mm * 1e-3))
                .collect(),
        });
    }
    Ok(Some(Resolution {
        lumped_scene: lumped.scene.name.clone(),
        profile_length_mm: length * 1e3,
        profile_nodes: r.profile_nodes,
        node_spacing_mm: spacing_mm,
        slices: lumped.scene.ltca.slices,
        fe,
        grades,
    }))
}
