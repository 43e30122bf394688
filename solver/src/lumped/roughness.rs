//! Seed 003's rough flanks for the lumped runs: a W–M profile
//! ([`geometry::roughness`]) as the pair's topography, and how much of it
//! our LTCA can see.
//!
//! Both flanks carry a W–M profile of roughness Ra along the profile
//! direction (seed 003's cutting model). Our contact element sees only the
//! relative geometry of the two flanks (the ease-off lives on the pinion
//! flank), so the pair is given one relative topography on the pinion
//! flank: a W–M profile with D of Ra (seed 003's Eq. (41), which reproduces its Table 2) and G set for
//! the composite roughness √2 Ra of two independent flanks. It enters as
//! the design's `[ease_off.topography]`, sampled on the scene's node
//! count along the profile; terms shorter than two node spacings are left
//! out ([`geometry::roughness::WmProfile::topography`]). What that leaves
//! is reported beside the roughness: terms and Rq carried, the node
//! spacing, the FE mesh's element length along the profile, and the
//! contact's Hertz half-width.
//!
//! What the model does with it, said plainly: each slice's first-touch lag
//! moves with the topography at its contact point, so the load sharing and
//! the loaded TE change; the slices' load–deflection law (Weber–Banaschek
//! line contact on the smooth flanks' FE compliance) does not. Asperity
//! contact compliance, the mechanism by which roughness lowers the mesh
//! stiffness in seed 003's account, is not in the model at all.

use formats::lumped_summary::RoughnessSummary;
use geometry::design::PairData;
use geometry::pair::FlankPair;
use geometry::roughness::WmProfile;

/// Profile length of the pinion flank at mid-face (normalised profile 0 →
/// 1, 40 chords), m.
pub fn profile_length(fp: &FlankPair) -> anyhow::Result<f64> {
    let n = 40;
    let pts = (0..=n)
        .map(|k| fp.pinion.at_unit(0.5, k as f64 / n as f64).map(|p| p.pos))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(pts
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|i| (w[1][i] - w[0][i]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .sum())
}

/// The pair with the roughness topography of grade `ra_um` (seed `seed`)
/// on `profile_nodes` × `face_nodes` nodes, and the roughness summary (its
/// Hertz half-width left at 0 for the caller); `smooth` the smooth pair's
/// flanks, `mesh_profile_elements` the FE mesh's elements along the profile.
pub fn roughened(
    pair: &PairData,
    smooth: &FlankPair,
    ra_um: f64,
    seed: u64,
    [profile_nodes, face_nodes]: [usize; 2],
    mesh_profile_elements: usize,
) -> anyhow::Result<(PairData, RoughnessSummary)> {
    if pair.ease_off.topography.is_some() {
        anyhow::bail!(
            "design {}: has an [ease_off.topography] already; the lumped roughness grades replace it, so give the design without one",
            pair.name
        );
    }
    let composite = std::f64::consts::SQRT_2 * ra_um;
    let grade = WmProfile::seed003(ra_um, seed)?;
    let wm = WmProfile::with_ra(*grade.spec(), composite * 1e-6, seed)?;
    let length = profile_length(smooth)?;
    let topo = wm.topography(length, profile_nodes, face_nodes)?;
    let spacing = length / (profile_nodes - 1) as f64;
    let max_w = 1.0 / (2.0 * spacing);
    let kept: Vec<(f64, f64)> = wm
        .frequencies_per_m()
        .iter()
        .zip(wm.amplitudes_m())
        .filter(|(w, _)| **w <= max_w)
        .map(|(w, a)| (*w, *a))
        .collect();
    let rq_kept = (kept.iter().map(|(_, a)| a * a).sum::<f64>() / 2.0).sqrt();
    let shortest = kept
        .iter()
        .map(|(w, _)| 1.0 / w)
        .fold(f64::INFINITY, f64::min);
    let mut out = pair.clone();
    out.ease_off.topography = Some(topo);
    Ok((
        out,
        RoughnessSummary {
            ra_um,
            composite_ra_um: composite,
            dimension: wm.spec().dimension,
            scale_m: wm.spec().scale_m,
            terms: wm.frequencies_per_m().len(),
            terms_resolved: kept.len(),
            rq_m: wm.rq_m(),
            rq_resolved_m: rq_kept,
            shortest_resolved_wavelength_m: if kept.is_empty() { 0.0 } else { shortest },
            node_spacing_m: spacing,
            profile_length_m: length,
            mesh_element_profile_m: length / mesh_profile_elements.max(1) as f64,
            hertz_half_width_m: 0.0,
        },
    ))
}
