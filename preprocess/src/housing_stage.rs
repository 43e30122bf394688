//! `preprocess housing`: the scene's `[bearings.gearbox.housing]` laid out
//! around the gears ([`geometry::housing_layout`]), meshed with gmsh
//! ([`crate::housing_mesh`]), its tet10 stiffness and mass reduced by
//! Craig–Bampton onto the bearing seats ([`fem::craig_bampton`]) and
//! written to `<meshes>/<scene>/housing.h5` ([`formats::housing_file`]).
//!
//! The fixed-interface modes kept are those up to the housing's
//! `modes_up_to_hz`. The stage also computes the whole housing's modes
//! (feet clamped, seats rigid and free, no truncation:
//! [`fem::craig_bampton::Reduction::full_omega2`]) up to the gearbox's
//! `modes_up_to_hz` and compares the reduced model's with them: the
//! truncation error, written to the file and printed.
//!
//! A file with the same input hash (the housing's settings and layout) is
//! reused.

use anyhow::Context;
use fem::craig_bampton::{Reduction, RigidInterface};
use formats::housing_file::{self, HousingData};
use geometry::housing_layout;
use geometry::pair::PairGeometry;
use geometry::scene::LoadedScene;
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::{DMatrix, SymmetricEigen};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What the stage did.
#[derive(Debug, Clone)]
pub struct HousingReport {
    pub path: PathBuf,
    pub reused: bool,
    pub data: HousingData,
    /// Mesh volume over the CAD volume − 1 (not for a reused file).
    pub volume_error: Option<f64>,
    /// Largest relative difference of the reduced model's frequencies
    /// from the whole housing's below the gearbox's `modes_up_to_hz`.
    pub truncation_error: f64,
    pub seconds: f64,
}

/// Fewest and most fixed-interface modes computed.
const FIRST_MODES: usize = 24;
const MOST_MODES: usize = 384;

/// Natural frequencies of K x = ω² M x (dense, M positive definite), Hz,
/// ascending.
pub fn dense_frequencies_hz(k: &DMatrix<f64>, m: &DMatrix<f64>) -> Option<Vec<f64>> {
    let l = m.clone().cholesky()?.l();
    let li = l.clone().try_inverse()?;
    let a = &li * k * li.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let mut f: Vec<f64> = SymmetricEigen::new(a)
        .eigenvalues
        .iter()
        .map(|w| w.max(0.0).sqrt() / (2.0 * std::f64::consts::PI))
        .collect();
    f.sort_by(f64::total_cmp);
    Some(f)
}

/// Runs the stage for `scene`; None when it has no housing.
pub fn run(scene: &LoadedScene, root: &Path) -> anyhow::Result<Option<HousingReport>> {
    let t0 = Instant::now();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let Some(layout) = housing_layout::of_scene(scene, &g)? else {
        return Ok(None);
    };
    let gb = scene
        .scene
        .bearings
        .as_ref()
        .and_then(|b| b.gearbox.as_ref())
        .context("housing layout without [bearings.gearbox]")?;
    let h = gb
        .housing
        .context("housing layout without [bearings.gearbox.housing]")?;
    let config = housing_layout::config_json(&h, &layout, gb.modes_up_to_hz);
    let hash = housing_file::input_hash(&config);
    let path = housing_file::path(root, &scene.scene.name);
    if path.exists() {
        if let Ok(data) = housing_file::read(&path, Some(&hash)) {
            let truncation_error = data.truncation_error();
            return Ok(Some(HousingReport {
                path,
                reused: true,
                data,
                volume_error: None,
                truncation_error,
                seconds: t0.elapsed().as_secs_f64(),
            }));
        }
    }
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("housing {spinner} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar.set_message("meshing");
    let hm =
        crate::housing_mesh::mesh(&layout, h.element_mm * 1e-3).map_err(|e| anyhow::anyhow!(e))?;
    bar.set_message(format!(
        "{} nodes: factoring, constraint modes",
        hm.mesh.nodes.len()
    ));
    let volume = hm.mesh.volume();
    let material = fem::Material {
        youngs_modulus_pa: h.youngs_modulus_gpa * 1e9,
        poisson_ratio: h.poisson_ratio,
    };
    let fixed: Vec<usize> = hm
        .feet
        .iter()
        .flat_map(|&i| (0..3).map(move |c| 3 * i + c))
        .collect();
    let interfaces: Vec<RigidInterface> = layout
        .walls
        .iter()
        .zip(&hm.seats)
        .map(|(w, nodes)| RigidInterface {
            nodes: nodes.clone(),
            reference: w.seat,
        })
        .collect();
    let cutoff = h.modes_up_to_hz;
    let check_up_to = gb.modes_up_to_hz;
    let hz = |w2: f64| w2.max(0.0).sqrt() / (2.0 * std::f64::consts::PI);
    let reduction = Reduction::new(&hm.mesh, &material, h.density_kg_m3, &fixed, &interfaces)
        .context("housing: Craig–Bampton reduction")?;
    let mut count = FIRST_MODES;
    let cb = loop {
        bar.set_message(format!("{count} fixed-interface modes"));
        let cb = reduction
            .reduce(count)
            .context("housing: fixed-interface modes")?;
        let top = cb.fixed_interface_omega2.last().copied().map_or(0.0, hz);
        if top > cutoff || count >= MOST_MODES {
            break cb;
        }
        // Modes up to f grow about as f^1.5 in these plates (measured on
        // the white-paper housing); aim a quarter past the cut-off.
        let want = count as f64 * (cutoff / top.max(1.0)).powf(1.5) * 1.25;
        count = (want.ceil() as usize).clamp(count + 8, MOST_MODES);
    };
    let fixed_hz: Vec<f64> = cb.fixed_interface_omega2.iter().map(|&w| hz(w)).collect();
    let kept = fixed_hz.iter().filter(|&&f| f <= cutoff).count();
    if kept == fixed_hz.len() && cutoff > 0.0 {
        anyhow::bail!(
            "housing: {} fixed-interface modes reach only {:.0} Hz, below modes_up_to_hz = {cutoff} Hz; lower it or coarsen element_mm",
            kept,
            fixed_hz.last().copied().unwrap_or(0.0)
        );
    }
    let r = cb.interface_dofs() + kept;
    let k_r = cb.stiffness.view((0, 0), (r, r)).into_owned();
    let m_r = cb.mass.view((0, 0), (r, r)).into_owned();
    let reduced =
        dense_frequencies_hz(&k_r, &m_r).context("housing: reduced mass not positive definite")?;
    // The whole housing (no truncation) below the gearbox's range: the
    // reduced model's frequencies bound it from above, so it has at least
    // as many modes there.
    let below = reduced.iter().filter(|&&f| f <= check_up_to).count().max(1);
    bar.set_message(format!("the whole housing's {} modes", below + 2));
    let full: Vec<f64> = reduction
        .full_omega2(below + 2)
        .context("housing: modes of the whole housing")?
        .into_iter()
        .map(hz)
        .collect();
    let reduced_hz = reduced[..below].to_vec();
    let reference_hz = full[..below].to_vec();
    let row_major = |m: &DMatrix<f64>| -> Vec<f64> { m.transpose().iter().copied().collect() };
    let data = HousingData {
        input_hash: hash,
        config,
        stiffness: row_major(&k_r),
        mass: row_major(&m_r),
        seat_member: layout.walls.iter().map(|w| w.member as u32).collect(),
        seat_bearing: layout.walls.iter().map(|w| w.bearing as u32).collect(),
        seat_reference: layout.walls.iter().map(|w| w.seat).collect(),
        seat_nodes: hm.seats.iter().map(|s| s.len() as u32).collect(),
        fixed_interface_hz: fixed_hz[..kept].to_vec(),
        reference_hz,
        reduced_hz,
        mass_kg: h.density_kg_m3 * volume,
        nodes: hm.mesh.nodes.len() as u32,
        elements: hm.mesh.tets.len() as u32,
        least_gap_m: layout.least_gap,
    };
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    bar.finish_and_clear();
    housing_file::write(&path, &data)?;
    let truncation_error = data.truncation_error();
    Ok(Some(HousingReport {
        path,
        reused: false,
        data,
        volume_error: Some(volume / hm.cad_volume_m3 - 1.0),
        truncation_error,
        seconds: t0.elapsed().as_secs_f64(),
    }))
}
