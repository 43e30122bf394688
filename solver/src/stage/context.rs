//! What every stage of a scene loads before it solves: the scene's sweep,
//! each member's stiffness file (checked against the mesh folder's
//! manifest) as its compliance, the polar moments, and the inputs a
//! result set records. Tests, benches and validate's studies build a
//! loaded pair through these too.

use crate::element::compliance::{MemberCompliance, PairCompliance};
use crate::ltca::Sweep;
use anyhow::Context;
use formats::manifest::Manifest;
use formats::paths::MeshLevel;
use formats::result_set::ResultSet;
use formats::stiffness_plan::{self, StiffnessPlan};
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use std::path::Path;

/// The coast side's sweep over the pinion angles of the loaded side's
/// `sweep`, backwards (in the coast side's driving direction).
pub fn coast_sweep(sweep: &Sweep, g: &PairGeometry, loaded: Side) -> Sweep {
    Sweep {
        start: sweep.start + sweep.direction * sweep.step * (sweep.positions - 1) as f64,
        direction: pinion_direction(&g.data, loaded.other()),
        ..*sweep
    }
}

/// Reads the member × blank stiffness file that `scene` needs, checking its
/// hash; also returns its plan (stiffness file and mesh paths).
pub fn member_compliance(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
) -> anyhow::Result<(MemberCompliance, StiffnessPlan)> {
    member_compliance_on(scene, g, dir, member, blank, scene.scene.loaded_flank)
}

/// A member's compliance for loads on its `side` flank (the coast side's
/// stiffness file when the scene has coast-side contact).
pub fn member_compliance_on(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    side: Side,
) -> anyhow::Result<(MemberCompliance, StiffnessPlan)> {
    member_compliance_at(scene, g, dir, member, blank, side, MeshLevel::Reduced)
}

/// As [`member_compliance_on`], from the stiffness file that `preprocess
/// stiffness --level <level>` made from that level's meshes (same contact
/// grid): the mesh-level studies' LTCA.
pub fn member_compliance_at(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    side: Side,
    level: MeshLevel,
) -> anyhow::Result<(MemberCompliance, StiffnessPlan)> {
    let p = stiffness_plan::plan(scene, g, dir, member, blank, level, side)?;
    let data = stiffness_plan::check(scene, g, dir, &p, member, blank, level).with_context(|| {
        format!(
            "scene {}: stiffness file of the {} ({blank:?} blank, {} flank) is missing or stale; run `preprocess stiffness {}{}`",
            scene.scene.name,
            member.name(),
            side.flank_name(member),
            scene.path.display(),
            match level {
                MeshLevel::Reduced => String::new(),
                l => format!(" --level {}", l.name()),
            }
        )
    })?;
    Ok((
        MemberCompliance::new(data, g.data.member(member).material()),
        p,
    ))
}

/// Records in `set` the scene's misalignment (if any) and the files that
/// the pinion × wheel blanks' stiffness data rest on (design, body meshes,
/// stiffness files, with their SHA-256 from the manifest), for the loaded
/// flanks and, with `coast`, the
/// opposite ones: so that a report can tell sets made from other files
/// apart ([`formats::result_set::check_same_inputs`]).
pub fn record_stiffness_inputs(
    set: &mut ResultSet,
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    [pb, wb]: [Blank; 2],
    coast: bool,
) -> anyhow::Result<()> {
    // The misalignment is an input of the results, not of the stiffness
    // files (body-fixed): recorded so that sets of other poses tell apart.
    if let Some(sha) = formats::manifest::misalignment_sha256(&scene.scene.misalignment) {
        set.record_input("misalignment", &sha)?;
    }
    let side = scene.scene.loaded_flank;
    let sides: &[Side] = if coast {
        &[side, side.other()]
    } else {
        &[side]
    };
    for &s in sides {
        for (m, b) in [(Member::Pinion, pb), (Member::Wheel, wb)] {
            let p = stiffness_plan::plan(scene, g, dir, m, b, MeshLevel::Reduced, s)?;
            for (key, sha) in stiffness_plan::inputs_of(dir, &p)? {
                set.record_input(&key, &sha)?;
            }
        }
    }
    Ok(())
}

/// Both members' compliance for loads on the coast (opposite) flanks, the
/// wheel's teeth numbered as the coast model's (see
/// `geometry::pair::OppositePlacement`); also their plans.
pub fn coast_compliance(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    pb: Blank,
    wb: Blank,
) -> anyhow::Result<(PairCompliance, [StiffnessPlan; 2])> {
    let side = scene.scene.loaded_flank;
    let (pin, pin_plan) = member_compliance_on(scene, g, dir, Member::Pinion, pb, side.other())?;
    let (whl, whl_plan) = member_compliance_on(scene, g, dir, Member::Wheel, wb, side.other())?;
    let shift = g.opposite_placement(side).wheel_tooth_shift;
    Ok((
        PairCompliance {
            pinion: pin,
            wheel: whl.with_tooth_shift(shift),
        },
        [pin_plan, whl_plan],
    ))
}

/// The scene's sweep for a wheel blank: from the entry of tooth 0, the
/// blank's mesh cycles at the scene's step.
pub fn scene_sweep(scene: &LoadedScene, g: &PairGeometry, wheel: Blank) -> Sweep {
    let sc = &scene.scene;
    let cycles = sc.rotation.mesh_cycles(wheel);
    let step = sc.rotation.step_deg.to_radians();
    Sweep {
        start: g.side(sc.loaded_flank).roll_range[0],
        step,
        direction: pinion_direction(&g.data, sc.loaded_flank),
        positions: (cycles * g.data.mesh_cycle() / step).round() as usize + 1,
        slices: sc.ltca.slices,
        friction: sc.ltca.friction_coefficient,
    }
}

/// Polar moment of a member: the scene's value, or ∫ρr² dV over the mesh
/// that `plan`'s stiffness file is computed on (the mesh stage's value in the
/// folder's manifest).
pub fn inertia(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    plan: &StiffnessPlan,
    member: Member,
) -> anyhow::Result<(f64, &'static str)> {
    let mb = &scene.scene.multibody;
    let given = match member {
        Member::Pinion => mb.pinion_inertia_kgm2,
        Member::Wheel => mb.wheel_inertia_kgm2,
    };
    if let Some(j) = given {
        return Ok((j, "scene"));
    }
    let manifest = Manifest::read(dir)?;
    let body = manifest.mesh(dir, &plan.mesh_stem)?.body;
    let density = g.data.member(member).density;
    if body.density_kg_m3 != density {
        anyhow::bail!(
            "{}: the {} mesh's polar moment is for density {} kg/m³, the design says {density} kg/m³; run `preprocess mesh`",
            formats::paths::manifest(dir).display(),
            plan.mesh_stem,
            body.density_kg_m3
        );
    }
    Ok((body.polar_moment_kgm2, "mesh"))
}

/// Both members' compliance and polar moments (scene or mesh) for the
/// blanks `[pinion, wheel]` from the mesh folder `dir` (benches and tests
/// that set up one pair by hand).
pub fn pair_and_inertia(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    blanks: [Blank; 2],
) -> anyhow::Result<(PairCompliance, [f64; 2])> {
    let load = |m: Member, b: Blank| -> anyhow::Result<_> {
        let (c, plan) = member_compliance(scene, g, dir, m, b)?;
        Ok((c, inertia(scene, g, dir, &plan, m)?.0))
    };
    let (pinion, j1) = load(Member::Pinion, blanks[0])?;
    let (wheel, j2) = load(Member::Wheel, blanks[1])?;
    Ok((PairCompliance { pinion, wheel }, [j1, j2]))
}
