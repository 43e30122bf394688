//! `solver dynamic` with `[bearings.gearbox]`: the flexible gearbox
//! ([`crate::gearbox`]) beside the compliant-bearing runs. The shafts of
//! `[bearings.<member>_shaft]` (rigid where absent) carry their mass as
//! Timoshenko beam elements (the design's density), the gears are rigid
//! bodies on their seats (the compliant runs' masses: the gear alone), the
//! bearings join the shafts to a rigid housing, or with
//! `[bearings.gearbox.housing]` to the FE housing of `preprocess housing`
//! (`<meshes>/<scene>/housing.h5`, read and checked by [`load_housing`]
//! before any run). Files, in the blank pair's folder:
//!
//! - `gearbox_modes.csv`: the loaded modes up to `modes_up_to_hz` (the
//!   contact element linearized at the run-up torque's quasi-static state)
//!   with each one's kinetic energy by part;
//! - `gearbox_runup.csv`: per run-up step the time, pinion rotation and
//!   speed, shaft TE, every bearing's force on its seat and, with a
//!   housing, each seat's acceleration;
//! - `gearbox_runup_spectrogram.svg`: the wheel bearings' total force |F|
//!   with the order lines and the modes (dashed): a Campbell diagram over
//!   the spectrogram; with a housing `gearbox_runup_housing_spectrogram.svg`
//!   the same of the wheel's first seat's |a|; `gearbox_runup_orders.json`
//!   as the other run-ups'.

use crate::bearings::flexible_shaft::Shaft;
use crate::gearbox::dynamics::{integrate, GearboxIntegrator, GearboxModel};
use crate::gearbox::structure::{modal_damping, Housing, Part};
use crate::gearbox::system_modes::{campbell_crossings, system_modes, ENERGY_PARTS};
use crate::gearbox::{assemble, MemberParts};
use crate::ltca::mean_ptp;
use crate::multibody::compliant::{CompliantModel, MemberBody, X};
use crate::multibody::lag_shift::LagShift;
use crate::stage::compliant::Setup;
use anyhow::Context;
use formats::housing_file::HousingData;
use formats::summaries::{
    CompliantRunSummary, GearboxCrossing, GearboxMode, GearboxSummary, HousingSummary,
};
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene};
use geometry::scene_bearings::GearboxMm;
use nalgebra::DMatrix;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// A scene's housing as its file holds it.
#[derive(Debug, Clone)]
pub struct LoadedHousing {
    pub housing: Housing,
    pub data: HousingData,
    /// The scene's cut-off of the kept fixed-interface modes, Hz.
    pub modes_up_to_hz: f64,
}

/// The reduced housing of `scene` from `<dir>/housing.h5` (None without
/// `[bearings.gearbox.housing]`), refused unless the file's input hash is
/// that of the scene's housing settings and layout. Read before any run.
pub fn load_housing(scene: &LoadedScene, dir: &Path) -> anyhow::Result<Option<LoadedHousing>> {
    let Some(gb) = scene
        .scene
        .bearings
        .as_ref()
        .and_then(|b| b.gearbox.as_ref())
    else {
        return Ok(None);
    };
    let Some(h) = gb.housing else {
        return Ok(None);
    };
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
    let layout = geometry::housing_layout::of_scene(scene, &g)?
        .context("[bearings.gearbox.housing] without a layout")?;
    let hash = formats::housing_file::input_hash(&geometry::housing_layout::config_json(
        &h,
        &layout,
        gb.modes_up_to_hz,
    ));
    let path = dir.join("housing.h5");
    if !path.exists() {
        anyhow::bail!(
            "{}: no housing file; run `preprocess housing {}` first",
            path.display(),
            scene.path.display()
        );
    }
    let data = formats::housing_file::read(&path, Some(&hash)).with_context(|| {
        format!(
            "the housing file does not hold this scene's housing; run `preprocess housing {}`",
            scene.path.display()
        )
    })?;
    let r = data.coordinates();
    let stiffness = DMatrix::from_row_slice(r, r, &data.stiffness);
    let mass = DMatrix::from_row_slice(r, r, &data.mass);
    let housing = Housing {
        damping: modal_damping(
            &stiffness,
            &mass,
            6 * data.seat_member.len(),
            h.damping_ratio,
        ),
        stiffness,
        mass,
        seats: data
            .seat_member
            .iter()
            .zip(&data.seat_bearing)
            .map(|(&m, &b)| (m as usize, b as usize))
            .collect(),
    };
    Ok(Some(LoadedHousing {
        housing,
        data,
        modes_up_to_hz: h.modes_up_to_hz,
    }))
}

/// The housing's summary (the run-up's seat accelerations added later).
fn housing_summary(h: &LoadedHousing) -> HousingSummary {
    let d = &h.data;
    HousingSummary {
        mass_kg: d.mass_kg,
        nodes: d.nodes as usize,
        elements: d.elements as usize,
        least_gap_mm: d.least_gap_m * 1e3,
        seat_nodes: d.seat_nodes.iter().map(|&n| n as usize).collect(),
        seats: h.housing.seats.clone(),
        fixed_interface_modes: d.fixed_interface_hz.len(),
        highest_fixed_interface_hz: d.fixed_interface_hz.last().copied().unwrap_or(0.0),
        modes_up_to_hz: h.modes_up_to_hz,
        reduced_hz: d.reduced_hz.clone(),
        reference_hz: d.reference_hz.clone(),
        truncation_error: d.truncation_error(),
        seat_acceleration_m_s2: Vec::new(),
    }
}

/// The excitation orders of the pinion's speed drawn and met: the mesh
/// order z₁ and its harmonics, and on a lightweight wheel the holes' order
/// 3r and the side bands z₁ ± 3r (r = z₁/z₂).
pub fn excitation_orders(z1: f64, ratio: f64, wheel: Blank) -> Vec<f64> {
    let mut o = vec![z1, 2.0 * z1, 3.0 * z1];
    if wheel == Blank::Lightweight {
        let h = 3.0 * ratio;
        o.extend([h, z1 - h, z1 + h]);
    }
    o
}

/// The gearbox of `s` with the compliant runs' `members`: modes, and the
/// run-up where the scene runs one.
pub fn run(
    s: &Setup,
    gb: &GearboxMm,
    shift: &LagShift,
    members: &[MemberBody; 2],
    hand: f64,
    housing: Option<&LoadedHousing>,
) -> anyhow::Result<GearboxSummary> {
    let sc = &s.scene.scene;
    let mb = &sc.multibody;
    let bearings = sc.bearings.as_ref().context("gearbox without [bearings]")?;
    let shafts: Vec<Option<(Shaft, f64)>> = [&bearings.pinion_shaft, &bearings.wheel_shaft]
        .iter()
        .enumerate()
        .map(|(m, sh)| {
            sh.as_ref().map(|sh| {
                let data = &s.g.data.members[m];
                (Shaft::of_scene(sh, &data.material()), data.density)
            })
        })
        .collect();
    let parts: [MemberParts; 2] = std::array::from_fn(|k| MemberParts {
        body: &members[k],
        polar_inertia_kgm2: s.inertia[k],
        shaft: shafts[k].as_ref().map(|(sh, rho)| (sh, *rho)),
    });
    let structure = assemble(
        parts,
        housing.map(|h| &h.housing),
        gb.shaft_element_mm * 1e-3,
    )?;
    let shaft_mass_kg: [f64; 2] = std::array::from_fn(|k| {
        shafts[k].as_ref().map_or(0.0, |(sh, rho)| {
            sh.segments
                .iter()
                .map(|g| {
                    rho * std::f64::consts::FRAC_PI_4
                        * (g.outer_diameter_m.powi(2) - g.inner_diameter_m.powi(2))
                        * (g.to_m - g.from_m)
                })
                .sum()
        })
    });
    let torque = mb.runup_pinion_torque_nm;
    let m = crate::stage::compliant::runup_model(s)?;
    let cm = CompliantModel::new(m, shift, members.clone(), hand)?;
    let gm = GearboxModel::new(&cm, &structure)?;
    let s0 = gm
        .static_state(0.0)
        .context("flexible gearbox, quasi-static start")?;

    // Loaded modes.
    let x12 = X::from_fn(|i, _| s0.x[i]);
    let mesh = cm.mesh(&x12, &X::zeros())?;
    let free = cm.free();
    let modes = system_modes(&structure, &mesh.stiffness, [!free[0], !free[1]])
        .context("flexible gearbox modes: mass matrix not positive definite")?;
    let modes: Vec<_> = modes
        .into_iter()
        .filter(|m| m.frequency_hz <= gb.modes_up_to_hz)
        .collect();
    let z1 = s.g.data.members[0].teeth as f64;
    let orders = excitation_orders(z1, s.table.ratio, s.blanks[1]);
    let top_rpm = crate::stage::runup::runup_ramp(mb).to * 30.0 / std::f64::consts::PI;
    let crossings: Vec<GearboxCrossing> = campbell_crossings(&modes, &orders, top_rpm)
        .into_iter()
        .map(|c| GearboxCrossing {
            mode: c.mode,
            frequency_hz: modes[c.mode].frequency_hz,
            order: c.order,
            pinion_rpm: c.pinion_rpm,
        })
        .collect();
    let mut csv = String::from("mode,frequency_hz");
    for p in ENERGY_PARTS {
        let _ = write!(csv, ",{}", p.replace(' ', "_"));
    }
    csv.push('\n');
    for (i, md) in modes.iter().enumerate() {
        let _ = write!(csv, "{i},{:.3}", md.frequency_hz);
        for e in md.energy_share {
            let _ = write!(csv, ",{e:.4}");
        }
        csv.push('\n');
    }
    formats::output::write_atomic(&s.odir.join("gearbox_modes.csv"), csv.as_bytes())?;
    eprintln!(
        "  gearbox: {} coordinates, shafts {:.2} / {:.2} kg, {} modes up to {} Hz (lowest {:.1} Hz), {} order crossings below {top_rpm:.0} rpm",
        structure.parts.len(),
        shaft_mass_kg[0],
        shaft_mass_kg[1],
        modes.len(),
        gb.modes_up_to_hz,
        modes.first().map_or(f64::NAN, |m| m.frequency_hz),
        crossings.len()
    );

    let mut housing_summary = housing.map(housing_summary);
    let run = if s.runs_up {
        let (run, seat_acc) = run_up(
            s,
            &gm,
            s0,
            &modes.iter().map(|m| m.frequency_hz).collect::<Vec<_>>(),
            housing.map_or(&[][..], |h| &h.housing.seats),
        )?;
        if let Some(h) = housing_summary.as_mut() {
            h.seat_acceleration_m_s2 = seat_acc;
        }
        Some(run)
    } else {
        None
    };
    let mut notes = Vec::new();
    if housing.is_none() {
        notes.push("rigid housing: the bearings' outer rings are held".to_string());
    }
    notes.extend([
        "the shafts' twist is not modelled: each turns with its gear".to_string(),
        "gyroscopic coupling of the spin with the tilts is not modelled".to_string(),
    ]);
    for (k, sh) in shafts.iter().enumerate() {
        if sh.is_none() {
            notes.push(format!(
                "{}: rigid shaft (no [bearings.{}_shaft]), the bearings on the gear body",
                ["pinion", "wheel"][k],
                ["pinion", "wheel"][k]
            ));
        }
    }
    Ok(GearboxSummary {
        coordinates: structure.parts.len(),
        shaft_mass_kg,
        shaft_element_mm: gb.shaft_element_mm,
        modes_torque_nm: torque,
        energy_parts: ENERGY_PARTS.iter().map(|s| s.to_string()).collect(),
        modes: modes
            .iter()
            .map(|m| GearboxMode {
                frequency_hz: m.frequency_hz,
                energy_share: m.energy_share.to_vec(),
            })
            .collect(),
        crossings,
        run,
        housing: housing_summary,
        notes,
    })
}

/// The run-up on the gearbox and its wheel bearings' spectrogram with the
/// modes drawn.
fn run_up(
    s: &Setup,
    gm: &GearboxModel,
    s0: crate::gearbox::dynamics::GState,
    modes_hz: &[f64],
    seats: &[(usize, usize)],
) -> anyhow::Result<(CompliantRunSummary, Vec<f64>)> {
    let mb = &s.scene.scene.multibody;
    let r = s.table.ratio;
    let links = &gm.structure.bearings;
    let mut rows = String::from("time_s,pinion_rotation_deg,pinion_rpm,te_urad");
    for b in links {
        let m = ["pinion", "wheel"][b.member];
        let i = b.index;
        let _ = write!(
            rows,
            ",{m}_bearing{i}_fx_n,{m}_bearing{i}_fy_n,{m}_bearing{i}_fz_n"
        );
    }
    // The housing's seats: their reference points' translations follow
    // the structure's turns, bodies and shafts.
    let seat0 = gm
        .structure
        .parts
        .iter()
        .position(|p| *p == Part::Housing)
        .unwrap_or(0);
    for &(m, i) in seats {
        let m = ["pinion", "wheel"][m];
        let _ = write!(
            rows,
            ",{m}_seat{i}_ax_m_s2,{m}_seat{i}_ay_m_s2,{m}_seat{i}_az_m_s2"
        );
    }
    // The seat whose acceleration gets a spectrogram: the wheel's first.
    let shown = seats.iter().position(|&(m, _)| m == 1);
    let mut seat_most = vec![0.0f64; seats.len()];
    let mut seat_series = Vec::new();
    rows.push('\n');
    let (mut t, mut q1, mut te, mut wheel) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut most = vec![0.0f64; links.len()];
    let (mut most_m, mut most_linear, mut sum_linear) = ([0.0f64; 4], 0.0f64, 0.0);
    let cm = gm.contact;
    let mut integ = GearboxIntegrator::new(mb.rho_inf, (s.control)(mb.runup_max_step_s));
    let clock = Instant::now();
    let (_, steps) = integrate(gm, s0, &mut integ, mb.runup_time_s, |st, _| {
        let e = r * st.x[0] - st.x[1];
        let c = cm.contact_map() * X::from_fn(|i, _| st.x[i]);
        let m = [c[2], c[3], c[4], c[5]];
        for (most, v) in most_m.iter_mut().zip(m) {
            *most = most.max(v.abs());
        }
        let linear = cm.shift.nonlinearity(cm.rigid.table, c[0], &m);
        most_linear = most_linear.max(linear);
        sum_linear += linear;
        t.push(st.t);
        q1.push(st.x[0]);
        te.push(e);
        let _ = write!(
            rows,
            "{:.9},{:.6},{:.4},{:.5}",
            st.t,
            st.x[0].to_degrees(),
            st.v[0] * 30.0 / std::f64::consts::PI,
            e * 1e6
        );
        let mut w = nalgebra::Vector3::zeros();
        for (j, (b, f)) in links
            .iter()
            .zip(gm.bearing_forces(&st.x, &st.v))
            .enumerate()
        {
            let _ = write!(rows, ",{:.4},{:.4},{:.4}", f.x, f.y, f.z);
            most[j] = most[j].max(f.norm());
            if b.member == 1 {
                w += f;
            }
        }
        for (k, most) in seat_most.iter_mut().enumerate() {
            let a = nalgebra::Vector3::from_fn(|c, _| st.a[seat0 + 6 * k + c]);
            let _ = write!(rows, ",{:.5},{:.5},{:.5}", a.x, a.y, a.z);
            *most = most.max(a.norm());
            if shown == Some(k) {
                seat_series.push(a.norm());
            }
        }
        rows.push('\n');
        wheel.push([w.x, w.y, w.z]);
        Ok(())
    })
    .context("flexible gearbox, run-up")?;
    let cpu = clock.elapsed().as_secs_f64();
    let csv = "gearbox_runup.csv";
    formats::output::write_atomic(&s.odir.join(csv), rows.as_bytes())?;
    let magnitude: Vec<f64> = wheel
        .iter()
        .map(|f| f.iter().map(|c| c * c).sum::<f64>().sqrt())
        .collect();
    let torque = mb.runup_pinion_torque_nm;
    crate::stage::runup::runup_spectrogram(
        &s.odir.join("gearbox_runup_spectrogram.svg"),
        &format!(
            "Wheel bearings' force |F|, flexible gearbox, run-up at {torque} N·m ({:?}/{:?}); dashed: modes",
            s.blanks[0], s.blanks[1]
        ),
        (&t, &magnitude),
        mb,
        s.g.data.members[0].teeth as f64,
        r,
        s.blanks[1],
        modes_hz,
    )?;
    if let Some(k) = shown {
        let (m, i) = seats[k];
        crate::stage::runup::runup_spectrogram(
            &s.odir.join("gearbox_runup_housing_spectrogram.svg"),
            &format!(
                "Housing acceleration |a| at the seat of {} bearing {i}, run-up at {} N·m ({:?}/{:?}); dashed: modes",
                ["pinion", "wheel"][m],
                mb.runup_pinion_torque_nm,
                s.blanks[0],
                s.blanks[1]
            ),
            (&t, &seat_series),
            mb,
            s.g.data.members[0].teeth as f64,
            r,
            s.blanks[1],
            modes_hz,
        )?;
    }
    // The bearings' forces on the wheel, as the other run-ups' order files.
    let on_wheel: Vec<[f64; 3]> = wheel.iter().map(|f| f.map(|c| -c)).collect();
    crate::stage::runup::write_runup_orders(
        &s.odir.join("gearbox_runup_orders.json"),
        s.blanks,
        s.g.data.members[0].teeth as f64,
        r,
        (&t, &q1, &on_wheel),
    )?;
    let (mean, ptp) = mean_ptp(&te);
    eprintln!(
        "  gearbox run-up: {steps} steps ({} rejected), {:.1} µs/step, {} coordinates, {} Newton iterations, {} step matrices",
        integ.rejected,
        cpu / steps.max(1) as f64 * 1e6,
        gm.dofs(),
        integ.newton_iterations,
        integ.matrices.built
    );
    let split = |k: usize| -> Vec<f64> {
        links
            .iter()
            .zip(&most)
            .filter(|(b, _)| b.member == k)
            .map(|(_, f)| *f)
            .collect()
    };
    Ok((
        CompliantRunSummary {
            case: "gearbox run-up".into(),
            torque_nm: torque,
            steps,
            rejected_steps: integ.rejected,
            cpu_s: cpu,
            cpu_s_per_step: cpu / steps.max(1) as f64,
            te_mean_urad: mean * 1e6,
            te_ptp_urad: ptp * 1e6,
            largest_misalignment: most_m.map(|v| v * 1e6),
            largest_linearization_urad: most_linear * 1e6,
            mean_linearization_urad: sum_linear / te.len().max(1) as f64 * 1e6,
            pinion_bearing_force_n: split(0),
            wheel_bearing_force_n: split(1),
            csv: csv.into(),
        },
        seat_most,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mesh order and its harmonics; a lightweight wheel of three holes
    /// adds 3 z₁/z₂ and the side bands z₁ ± 3 z₁/z₂ (20/43: 1.395, 18.60,
    /// 21.40).
    #[test]
    fn excitation_orders_of_both_wheel_blanks() {
        let r = 20.0 / 43.0;
        assert_eq!(
            excitation_orders(20.0, r, Blank::Standard),
            vec![20.0, 40.0, 60.0]
        );
        let o = excitation_orders(20.0, r, Blank::Lightweight);
        assert_eq!(o.len(), 6);
        for (got, want) in o[3..].iter().zip([1.395349, 18.604651, 21.395349]) {
            assert!((got - want).abs() < 1e-6, "{got} against {want}");
        }
    }
}
