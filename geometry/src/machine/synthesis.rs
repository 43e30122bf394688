//! Local synthesis: the pinion's machine settings that cut the design's
//! ease-off to second order at the mean point.
//!
//! A design's wanted contact is its pinion ease-off E(ξ, η) (crowning,
//! bias, motion error, topography; relative to the conjugate flank). The
//! mean contact point M is where the pinion touches (the UTCA's contact)
//! at the vertex of the transmission error's parabola, the middle of the
//! active roll range. E's first and second derivatives at M fix the
//! contact there to second order: M itself (the separation's least point
//! on its contact line), the path's direction, the transmission error's
//! parabola and the contact ellipse (the conditions of Litvin's local
//! synthesis); its value at M, the tooth's thickness there. The synthesis
//! finds, for each pinion flank, settings whose cut flank has the same
//! value and five derivatives (f, f_ξ, f_η, f_ξξ, f_ξη, f_ηη) against the
//! wheel cut by the crown generation's settings (conjugate), the cut flank
//! taken as it is (no rotation removed, so that the settings cut the
//! design's tooth thickness): Gauss–Newton over six settings, each acting
//! mainly on one of them (cradle angle: the value, a turn of the flank;
//! radial setting: f_ξ, the spiral angle; blade angle: f_η, the pressure
//! angle; blade radius: f_ξξ, the lengthwise crowning; blade profile
//! curvature: f_ηη, the profile crowning; modified roll 2C: the
//! transmission error's parabola and with it f_ξη), each weighted by its
//! effect (its Jacobian column's norm), the steps halved where they do not
//! reduce the residual, starting
//! from the crown generation's settings. The derivatives are central
//! differences on a stencil of ±[`STENCIL`] in ξ and η, the same for the
//! design and the cut flank. What the settings cannot follow (the
//! ease-off's higher orders) is measured over the whole flank
//! ([`SideSynthesis::largest_difference_um`]).

use crate::design::Member;
use crate::error::GeometryError;
use crate::generation::{RawPoint, Side};
use crate::machine::deviation::{deviation, lever, normal_offset};
use crate::machine::kinematics::Machine;
use crate::machine::settings::{FlankSettings, MachineSettings};
use crate::pair::{pinion_direction, FlankPair, PairGeometry};
use crate::utca::{run, LineGrid, RollSurface};
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Half-width of the difference stencil in ξ and η.
pub const STENCIL: f64 = 0.01;
/// Gauss–Newton iterations at most.
const MAX_ITERATIONS: usize = 30;

/// The change each varied setting is scaled by, in the order [`varied`]
/// applies them: blade angle (rad), blade profile curvature (1/m), radial
/// setting (m), blade radius (m), modified roll 2C, cradle angle (rad).
const SCALES: [f64; 6] = [1e-3, 0.1, 1e-4, 1e-3, 1e-2, 1e-4];

/// One pinion flank's synthesis.
#[derive(Debug, Clone, Serialize)]
pub struct SideSynthesis {
    pub side: Side,
    /// The mean contact point's (ξ, η).
    pub mean_contact: [f64; 2],
    /// The design ease-off's (f, f_ξ, f_η, f_ξξ, f_ξη, f_ηη) at the mean
    /// contact point, µm (per unit of ξ, η).
    pub wanted_um: [f64; 6],
    /// The cut flank's, µm.
    pub achieved_um: [f64; 6],
    pub iterations: usize,
    /// Largest |cut − design| relative deviation over the flank grid of
    /// [`crate::machine::deviation`], µm: the ease-off's higher orders,
    /// which the settings do not follow.
    pub largest_difference_um: f64,
}

/// The synthesized settings of a pair (pinion synthesized, wheel the crown
/// generation's) and how each pinion flank was reached.
#[derive(Debug, Clone, Serialize)]
pub struct Synthesis {
    pub settings: MachineSettings,
    pub sides: Vec<SideSynthesis>,
}

/// The stencil's conjugate pinion points (row-major in η, then ξ; the
/// centre at index 4) and the design's ease-off there, m.
struct Stencil {
    points: Vec<RawPoint<f64>>,
    ease: Vec<f64>,
}

/// The mean contact point M of `fp` (its normalised (ξ, η)): the pinion's
/// contact in the UTCA at the middle of the active roll range.
pub fn mean_contact(fp: &FlankPair, direction: f64) -> Result<(f64, f64), GeometryError> {
    let rs = RollSurface::new(fp, LineGrid::default())?;
    let phi = 0.5 * (fp.roll_range[0] + fp.roll_range[1]);
    let u = run(fp, &rs, phi, 0.0, 1, direction);
    let c = u.teeth[0][u.contact[0]];
    Ok(fp.pinion.bounds.to_unit(c.l, c.d))
}

impl Stencil {
    fn new(fp: &FlankPair, centre: (f64, f64)) -> Result<Self, GeometryError> {
        let mut points = Vec::with_capacity(9);
        let mut ease = Vec::with_capacity(9);
        for b in [-1.0, 0.0, 1.0] {
            for a in [-1.0, 0.0, 1.0] {
                let (l, d) = fp
                    .pinion
                    .bounds
                    .from_unit(centre.0 + a * STENCIL, centre.1 + b * STENCIL);
                let uv = fp.pinion.solve_ld(l, d)?;
                points.push(fp.pinion.gen.eval(uv[0], uv[1]));
                ease.push(fp.pinion.eval_uv(uv[0], uv[1]).ease_off);
            }
        }
        Ok(Stencil { points, ease })
    }
}

/// (f, f_ξ, f_η, f_ξξ, f_ξη, f_ηη) of values on the stencil, scaled by `unit`.
fn derivatives(f: &[f64], unit: f64) -> [f64; 6] {
    let h = STENCIL;
    let at = |a: usize, b: usize| f[3 * b + a] * unit;
    [
        at(1, 1),
        (at(2, 1) - at(0, 1)) / (2.0 * h),
        (at(1, 2) - at(1, 0)) / (2.0 * h),
        (at(2, 1) - 2.0 * at(1, 1) + at(0, 1)) / (h * h),
        (at(2, 2) - at(2, 0) - at(0, 2) + at(0, 0)) / (4.0 * h * h),
        (at(1, 2) - 2.0 * at(1, 1) + at(1, 0)) / (h * h),
    ]
}

/// The pinion settings `base` changed by the scaled variables `x`.
fn varied(base: &FlankSettings, x: &[f64]) -> FlankSettings {
    let mut s = *base;
    let v = |i: usize| x[i] * SCALES[i];
    s.blade_angle += v(0);
    s.blade_profile_curvature += v(1);
    s.radial_setting += v(2);
    s.blade_radius += v(3);
    s.modified_roll_2c += v(4);
    s.cradle_angle += v(5);
    s
}

/// The cut pinion flank's value and derivatives (µm) with settings `s`
/// on `side`.
fn cut_derivatives(st: &Stencil, s: &FlankSettings, side: Side) -> Option<[f64; 6]> {
    let machine = Machine::new(s, Member::Pinion, side);
    let mut dev = Vec::with_capacity(9);
    for p in &st.points {
        dev.push(-normal_offset(&machine, p)?);
    }
    Some(derivatives(&dev, 1e6))
}

/// Local synthesis of both pinion flanks of the pair `g` (its ease-off as
/// designed).
pub fn synthesize(g: &PairGeometry) -> Result<Synthesis, GeometryError> {
    let mut settings = MachineSettings::of_crown_generation(&g.data);
    let mut sides = Vec::with_capacity(2);
    for side in [Side::Drive, Side::Coast] {
        let fp = g.side(side);
        let centre = mean_contact(fp, pinion_direction(&g.data, side))?;
        let st = Stencil::new(fp, centre)?;
        let wanted = derivatives(&st.ease, 1e6);
        let base = *settings.flank(Member::Pinion, side);
        let failed = || GeometryError::Synthesis {
            flank: side.flank_name(Member::Pinion),
        };
        let residual = |x: &[f64]| -> Option<DVector<f64>> {
            let d = cut_derivatives(&st, &varied(&base, x), side)?;
            Some(DVector::from_iterator(6, (0..6).map(|i| d[i] - wanted[i])))
        };
        let scale = wanted.iter().fold(1.0f64, |a, w| a.max(w.abs()));
        let mut x = vec![0.0; SCALES.len()];
        let mut r = residual(&x).ok_or_else(failed)?;
        let mut iterations = 0;
        while r.amax() > 1e-9 * scale && iterations < MAX_ITERATIONS {
            iterations += 1;
            let mut jac = DMatrix::zeros(6, SCALES.len());
            for k in 0..SCALES.len() {
                let (mut xp, mut xm) = (x.clone(), x.clone());
                xp[k] += 0.5;
                xm[k] -= 0.5;
                let col = residual(&xp).ok_or_else(failed)? - residual(&xm).ok_or_else(failed)?;
                jac.set_column(k, &col);
            }
            // Each setting weighted by its effect (its column's norm), so
            // that the minimum-norm step moves the settings that act.
            let norms: Vec<f64> = (0..SCALES.len())
                .map(|k| jac.column(k).norm().max(1e-300))
                .collect();
            for (k, n) in norms.iter().enumerate() {
                jac.column_mut(k).scale_mut(1.0 / n);
            }
            let step = jac
                .svd(true, true)
                .solve(&(-&r), 1e-12)
                .map_err(|_| failed())?;
            // Halve the step while it cuts no flank or does not reduce the
            // residual; where no step does, the residual is as small as
            // the differences let it be (judged below).
            let mut length = 1.0;
            let mut reduced = false;
            while length > 1e-3 {
                let trial: Vec<f64> = x
                    .iter()
                    .zip(step.iter().zip(&norms))
                    .map(|(xi, (s, n))| xi + length * s / n)
                    .collect();
                match residual(&trial) {
                    Some(rt) if rt.amax() < r.amax() => {
                        x = trial;
                        r = rt;
                        reduced = true;
                        break;
                    }
                    _ => length *= 0.5,
                }
            }
            if !reduced {
                break;
            }
        }
        if r.amax() > 1e-6 * scale {
            return Err(failed());
        }
        let synthesized = varied(&base, &x);
        settings.flanks[Member::Pinion as usize][side.index()] = synthesized;
        let achieved = cut_derivatives(&st, &synthesized, side).ok_or_else(failed)?;
        sides.push(SideSynthesis {
            side,
            mean_contact: [centre.0, centre.1],
            wanted_um: wanted,
            achieved_um: achieved,
            iterations,
            largest_difference_um: largest_difference(fp, &settings)?,
        });
    }
    Ok(Synthesis { settings, sides })
}

/// Largest |cut − design| over the deviation grid, µm, both with the
/// pinion's rotation removed at the mean node (ξ = η = ½).
fn largest_difference(fp: &FlankPair, settings: &MachineSettings) -> Result<f64, GeometryError> {
    let cut = deviation(fp, settings)?;
    let t = &cut.topography;
    let (im, jm) = (t.profile.len() / 2, t.face.len() / 2);
    let design = |eta: f64, xi: f64| -> Result<(f64, f64), GeometryError> {
        let (l, d) = fp.pinion.bounds.from_unit(xi, eta);
        let uv = fp.pinion.solve_ld(l, d)?;
        let raw = fp.pinion.gen.eval(uv[0], uv[1]);
        Ok((fp.pinion.eval_uv(uv[0], uv[1]).ease_off, lever(&raw)))
    };
    let (e0, l0) = design(t.profile[im], t.face[jm])?;
    let mut worst = 0.0f64;
    for (i, &eta) in t.profile.iter().enumerate() {
        for (j, &xi) in t.face.iter().enumerate() {
            let (e, l) = design(eta, xi)?;
            let want = (e - l * e0 / l0) * 1e6;
            worst = worst.max((t.deviation_um[i][j] - want).abs());
        }
    }
    Ok(worst)
}
