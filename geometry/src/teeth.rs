//! Which teeth a scene's sweep brings into contact, per member and blank:
//! the teeth the mesh refines, the tooth whose unit loads the stiffness file
//! solves, and the teeth meshed as periodic sectors. Shared by the mesh and
//! stiffness stages and by the stiffness files' readers.

use crate::design::Member;
use crate::gear_body::Blank;
use crate::generation::Side;
use crate::pair::{opposite_teeth_in_contact, teeth_in_contact_at, PairGeometry};
use crate::scene::Scene;

/// Smallest mesh stiffness per unit face width the stiffness plan assumes
/// of a steel pair when it bounds the multibody table's lead-in, N/m²
/// (2 N/(mm·µm)): a tenth of the 20 N/(mm·µm) ISO 6336 gives as the
/// typical mesh stiffness of steel gears; scaled by the softer member's
/// Young's modulus over [`STEEL_YOUNGS_MODULUS`]. Our choice: the default
/// scene's lightweight pair lags at 700 N·m as about 5 N/(mm·µm) would
/// make it under this bound's formula, so the bound is about 2.7 times its
/// elastic lag.
pub const MIN_MESH_STIFFNESS_STEEL: f64 = 2e9;
/// Young's modulus the stiffness bound refers to, Pa.
pub const STEEL_YOUNGS_MODULUS: f64 = 206e9;
/// Largest range of unloaded TE the lead-in bound allows for, rad of wheel
/// rotation: about 30 times the white-paper pair's 35 µrad.
pub const UNLOADED_TE_RANGE_BOUND: f64 = 1e-3;

/// Mesh cycles of pinion rotation the multibody contact table of wheel
/// blank `wheel` covers from the sweep's start (before its end margin):
/// the sweep, the run-up's rotation if the blank runs up, the rattle
/// run's with coast-side contact, and the STE/DTE run-ups' if they
/// compare the blank.
pub fn table_mesh_cycles(sc: &Scene, wheel: Blank, mesh_cycle_rad: f64) -> f64 {
    let mb = &sc.multibody;
    let mut cycles = sc.rotation.mesh_cycles(wheel);
    if mb.runup_wheel_blanks.contains(&wheel) {
        cycles = cycles.max(mb.runup_rotation() / mesh_cycle_rad);
    }
    if mb.coast_contact && mb.rattle_time_s > 0.0 {
        cycles = cycles.max(mb.rattle_rotation() / mesh_cycle_rad);
    }
    if let Some(sd) = mb.ste_dte_of(wheel) {
        cycles = cycles.max(sd.rotation() / mesh_cycle_rad);
    }
    cycles
}

/// Positions per mesh cycle (`mesh_cycle_rad`) of the multibody contact
/// table: `multibody.table_step_deg` rounded to a whole number per cycle,
/// at least 8.
pub fn table_positions_per_cycle(sc: &Scene, mesh_cycle_rad: f64) -> usize {
    (mesh_cycle_rad / sc.multibody.table_step_deg.to_radians())
        .round()
        .max(8.0) as usize
}

/// Largest pinion torque the multibody table of wheel blank `wheel`
/// covers, N·m: the largest of the scene's torques, the STE/DTE runs' (if
/// they compare the blank), the run-up's (if the
/// blank runs up) and the load run's (as pinion torque), times
/// `multibody.table_torque_factor`.
pub fn table_torque_nm(sc: &Scene, wheel: Blank, ratio: f64) -> f64 {
    let mb = &sc.multibody;
    sc.pinion_torque_nm
        .iter()
        .copied()
        .chain(
            mb.runup_wheel_blanks
                .contains(&wheel)
                .then_some(mb.runup_pinion_torque_nm),
        )
        .chain(mb.load_run.as_ref().map(|r| r.wheel_torque_nm * ratio))
        .chain(mb.ste_dte_of(wheel).map(|sd| sd.pinion_torque_nm))
        .fold(0.0, f64::max)
        * mb.table_torque_factor
}

/// Pinion rotation the multibody contact table of a pair that does not
/// repeat every mesh cycle (a lightweight member) spans around the sweep's
/// start, rad: `[before, after]`. Before: a bound on the table's lead-in,
/// which starts where the first position's loaded lag was first reached,
/// (θ_hi − θ_lo)/r plus two table steps, with θ_hi − θ_lo at most
/// [`UNLOADED_TE_RANGE_BOUND`] plus the elastic lag at the table's torque
/// T under [`MIN_MESH_STIFFNESS_STEEL`] c over the face width b,
/// 4 T / (r₁ r₂ c b) (r₁, r₂ the mean pitch radii; the 4 covers the
/// normal and spiral angles); the table refuses a lead-in beyond it. After:
/// [`table_mesh_cycles`] plus three sweep steps and three table steps.
pub fn table_span(g: &PairGeometry, sc: &Scene, wheel: Blank, sweep_step: f64) -> [f64; 2] {
    let d = &g.data;
    let tau = d.mesh_cycle();
    let ratio = d.members[0].teeth as f64 / d.members[1].teeth as f64;
    let table_step = tau / table_positions_per_cycle(sc, tau) as f64;
    let [r1, r2] = [0, 1].map(|i| d.mean_cone_distance * d.members[i].pitch_angle.sin());
    let e_min = d.members[0].youngs_modulus.min(d.members[1].youngs_modulus);
    let c = MIN_MESH_STIFFNESS_STEEL * e_min / STEEL_YOUNGS_MODULUS;
    let elastic = 4.0 * table_torque_nm(sc, wheel, ratio) / (r1 * r2 * c * d.face_width);
    let before = (UNLOADED_TE_RANGE_BOUND + elastic) / ratio + 2.0 * table_step;
    let after = table_mesh_cycles(sc, wheel, tau) * tau + 3.0 * sweep_step + 3.0 * table_step;
    [before, after]
}

/// Teeth of `member` whose loaded flank the scene brings into contact: the
/// wheel blank sets the rotation range (the pinion takes the longest of the
/// scene's wheel blanks).
pub fn refined_teeth(g: &PairGeometry, sc: &Scene, member: Member, blank: Blank) -> Vec<usize> {
    refined_teeth_on(g, sc, member, blank, sc.loaded_flank)
}

/// The tooth whose flank the influence solves of an axisymmetric (standard)
/// blank load: the middle one of the refined teeth.
pub fn solved_tooth(refined: &[usize]) -> Option<usize> {
    refined.get(refined.len() / 2).copied()
}

/// Teeth meshed as periodic sectors (rotated copies of the solved tooth's
/// sector, the mesh stage's periodic sectors): on a standard blank the solved tooth
/// first, then every other refined tooth whose opposite flank is refined
/// alike; none on a lightweight blank (its holes break the symmetry) or
/// with fewer than two such teeth.
pub fn periodic_teeth(blank: Blank, refined: &[usize], opposite: &[usize]) -> Vec<usize> {
    let Some(master) = solved_tooth(refined) else {
        return Vec::new();
    };
    if blank != Blank::Standard {
        return Vec::new();
    }
    let alike = |t: usize| opposite.contains(&t) == opposite.contains(&master);
    let mut out = vec![master];
    out.extend(refined.iter().copied().filter(|&t| t != master && alike(t)));
    if out.len() < 2 {
        out.clear();
    }
    out
}

/// Teeth whose opposite (coast) flank is refined: those the same rotation
/// brings into contact on that side, when the scene asks for coast-side
/// contact; none otherwise.
pub fn opposite_refined_teeth(
    g: &PairGeometry,
    sc: &Scene,
    member: Member,
    blank: Blank,
) -> Vec<usize> {
    if sc.multibody.coast_contact {
        refined_teeth_on(g, sc, member, blank, sc.loaded_flank.other())
    } else {
        Vec::new()
    }
}

/// Teeth of `member` whose `side` flank the scene's rotation brings into contact.
pub fn refined_teeth_on(
    g: &PairGeometry,
    sc: &Scene,
    member: Member,
    blank: Blank,
    side: Side,
) -> Vec<usize> {
    // A standard pinion's loads repeat from tooth to tooth: its range is the
    // loaded sweep's. A lightweight wheel needs every tooth a run-up meets.
    let cycles_of = |b: Blank| sc.rotation.mesh_cycles(b);
    let cycles = match member {
        Member::Wheel => sc.contact_mesh_cycles(blank, g.data.mesh_cycle()),
        Member::Pinion => sc
            .blanks
            .wheel
            .iter()
            .map(|&b| cycles_of(b))
            .fold(0.0, f64::max),
    };
    let step = sc.rotation.step_deg.to_radians();
    let n = (cycles * g.data.mesh_cycle() / step).round() as i64;
    // A lightweight member's stiffness file serves only the teeth it
    // solves: with multibody runs it covers the table's whole span, its
    // lead-in before the sweep included (a standard member's one solved
    // tooth serves every tooth).
    let wheels: &[Blank] = match member {
        Member::Wheel => std::slice::from_ref(&blank),
        Member::Pinion => &sc.blanks.wheel,
    };
    let ks = match blank == Blank::Lightweight && sc.analyses.multibody {
        true => wheels.iter().fold(0..=n, |ks, &wb| {
            let [before, after] = table_span(g, sc, wb, step);
            let lo = -(before / step).ceil() as i64;
            let hi = (after / step).ceil() as i64;
            (*ks.start()).min(lo)..=(*ks.end()).max(hi)
        }),
        false => 0..=n,
    };
    // The opposite flanks are numbered as the body's teeth over the loaded
    // side's sweep (both sides share the pinion angle).
    let (pt, wt) = if side == sc.loaded_flank {
        teeth_in_contact_at(g, side, ks, step)
    } else {
        opposite_teeth_in_contact(g, sc.loaded_flank, cycles, step)
    };
    match member {
        Member::Pinion => pt,
        Member::Wheel => wt,
    }
}
