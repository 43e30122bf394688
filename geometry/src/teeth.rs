//! Which teeth a scene's sweep brings into contact, per member and blank:
//! the teeth the mesh refines, the tooth whose unit loads the stiffness file
//! solves, and the teeth meshed as periodic sectors. Shared by the mesh and
//! stiffness stages and by the stiffness files' readers.

use crate::design::Member;
use crate::gear_body::Blank;
use crate::generation::Side;
use crate::pair::{opposite_teeth_in_contact, teeth_in_contact, PairGeometry};
use crate::scene::Scene;

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
    // The opposite flanks are numbered as the body's teeth over the loaded
    // side's sweep (both sides share the pinion angle).
    let (pt, wt) = if side == sc.loaded_flank {
        teeth_in_contact(g, side, cycles, step)
    } else {
        opposite_teeth_in_contact(g, sc.loaded_flank, cycles, step)
    };
    match member {
        Member::Pinion => pt,
        Member::Wheel => wt,
    }
}
