//! What every stage of a scene loads before it solves. A [`StageContext`]
//! is the scene with its pair geometry (placed with the scene's
//! misalignment) and its mesh folder; a [`LoadedPair`] is one pinion ×
//! wheel blank loaded from it: both members' stiffness files (checked
//! against the mesh folder's manifest) as the pair compliance, their plans
//! and the scene's sweep for the wheel blank. Tests, benches and validate's
//! studies build a loaded pair through these too; the free functions below
//! are the pieces, for the studies that vary one of them (another mesh
//! level, the coast flanks, a misaligned pose).

use crate::element::compliance::{MemberCompliance, PairCompliance};
use crate::ltca::Sweep;
use formats::manifest::Manifest;
use formats::paths::MeshLevel;
use formats::result_set::ResultSet;
use formats::stiffness_plan::{self, StiffnessPlan};
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, FlankPair, PairGeometry};
use geometry::scene::{Blank, LoadedScene};
use geometry::utca::{roll_surface, RollSurface};
use std::path::{Path, PathBuf};

/// A scene ready for a stage: the scene, its pair geometry placed with the
/// scene's misalignment, and the scene's folder of meshes and stiffness
/// files (`<meshes>/<scene name>`).
pub struct StageContext<'s> {
    pub scene: &'s LoadedScene,
    pub g: PairGeometry,
    pub dir: PathBuf,
}

impl<'s> StageContext<'s> {
    /// Builds the pair geometry of `scene` and places it with the scene's
    /// misalignment.
    pub fn new(scene: &'s LoadedScene, meshes: &Path) -> anyhow::Result<Self> {
        let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
        Ok(Self::with_geometry(scene, g, meshes))
    }

    /// The pair as designed, without the scene's misalignment: the lumped
    /// model's stages, whose LTCA drives the 8-DOF model of the aligned
    /// pair.
    pub fn aligned(scene: &'s LoadedScene, meshes: &Path) -> anyhow::Result<Self> {
        Ok(Self {
            scene,
            g: PairGeometry::build(&scene.pair, Some(&scene.design_path))?,
            dir: meshes.join(&scene.scene.name),
        })
    }

    /// As [`StageContext::new`] from an aligned geometry `g` that the
    /// caller has built (and checked what needs the aligned pair).
    pub fn with_geometry(scene: &'s LoadedScene, mut g: PairGeometry, meshes: &Path) -> Self {
        g.misalign(&scene.scene.misalignment);
        Self {
            scene,
            g,
            dir: meshes.join(&scene.scene.name),
        }
    }

    /// The loaded flank side.
    pub fn side(&self) -> Side {
        self.scene.scene.loaded_flank
    }

    /// The loaded flank pair.
    pub fn fp(&self) -> &FlankPair {
        self.g.side(self.side())
    }

    /// The surface of roll angles (unloaded TCA) of the `side` flanks.
    pub fn roll_surface(&self, side: Side) -> anyhow::Result<RollSurface> {
        Ok(roll_surface(self.g.side(side), &self.scene.scene.utca)?)
    }

    /// Calls `f` on every pinion × wheel blank of the scene in turn, each
    /// pinion blank's stiffness file read once.
    pub fn for_each_pair(
        &self,
        mut f: impl FnMut(LoadedPair) -> anyhow::Result<()>,
    ) -> anyhow::Result<()> {
        let (scene, g, dir) = (self.scene, &self.g, self.dir.as_path());
        for &pb in &scene.scene.blanks.pinion {
            let (pin, pin_plan) = member_compliance(scene, g, dir, Member::Pinion, pb)?;
            for &wb in &scene.scene.blanks.wheel {
                let (whl, whl_plan) = member_compliance(scene, g, dir, Member::Wheel, wb)?;
                f(LoadedPair {
                    blanks: [pb, wb],
                    pc: PairCompliance {
                        pinion: pin.clone(),
                        wheel: whl,
                    },
                    plans: [pin_plan.clone(), whl_plan],
                    sweep: scene_sweep(scene, g, wb),
                })?;
            }
        }
        Ok(())
    }

    /// Records in `set` the inputs of the pair `blanks` (see
    /// [`record_stiffness_inputs`]).
    pub fn record_inputs(
        &self,
        set: &mut ResultSet,
        blanks: [Blank; 2],
        coast: bool,
    ) -> anyhow::Result<()> {
        record_stiffness_inputs(set, self.scene, &self.g, &self.dir, blanks, coast)
    }

    /// Both members' polar moments of `pair` (see [`inertia`]).
    pub fn inertia(&self, pair: &LoadedPair) -> anyhow::Result<[(f64, &'static str); 2]> {
        pair.inertia(self.scene, &self.g, &self.dir)
    }
}

/// One pinion × wheel blank of a scene, loaded: the pair compliance from
/// both members' stiffness files, their plans (stiffness file and mesh
/// paths), and the scene's sweep for the wheel blank.
#[derive(Clone)]
pub struct LoadedPair {
    /// `[pinion, wheel]` blanks.
    pub blanks: [Blank; 2],
    pub pc: PairCompliance,
    /// `[pinion, wheel]` stiffness plans.
    pub plans: [StiffnessPlan; 2],
    pub sweep: Sweep,
}

impl LoadedPair {
    /// Reads both members' stiffness files for `blanks` from `dir` (hashes
    /// checked) and sets up the scene's sweep.
    pub fn load(
        scene: &LoadedScene,
        g: &PairGeometry,
        dir: &Path,
        blanks: [Blank; 2],
    ) -> anyhow::Result<Self> {
        let (pinion, pin_plan) = member_compliance(scene, g, dir, Member::Pinion, blanks[0])?;
        let (wheel, whl_plan) = member_compliance(scene, g, dir, Member::Wheel, blanks[1])?;
        Ok(Self {
            blanks,
            pc: PairCompliance { pinion, wheel },
            plans: [pin_plan, whl_plan],
            sweep: scene_sweep(scene, g, blanks[1]),
        })
    }

    /// Both members' polar moments and where each comes from ([`inertia`]).
    pub fn inertia(
        &self,
        scene: &LoadedScene,
        g: &PairGeometry,
        dir: &Path,
    ) -> anyhow::Result<[(f64, &'static str); 2]> {
        Ok([
            inertia(scene, g, dir, &self.plans[0], Member::Pinion)?,
            inertia(scene, g, dir, &self.plans[1], Member::Wheel)?,
        ])
    }

    /// The pair's folder name, `<pinion>_<wheel>` in lower case.
    pub fn name(&self) -> String {
        let [pb, wb] = self.blanks;
        format!("{pb:?}_{wb:?}").to_lowercase()
    }
}

/// Whether the scene's `[analyses] <key>` switch runs its stage; when it
/// does not, says so on stderr (`what`: what is skipped).
pub fn analysis_enabled(scene: &LoadedScene, on: bool, key: &str, what: &str) -> bool {
    if !on {
        eprintln!(
            "scene {}: `[analyses] {key} = false`, {what}; skipped",
            scene.scene.name
        );
    }
    on
}

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
    let data = stiffness_plan::check(scene, g, dir, &p, member, blank, level).map_err(|e| {
        let what = format!(
            "scene {}: the stiffness file of the {} ({} blank, {} flank) cannot be used",
            scene.scene.name,
            member.name(),
            blank.name(),
            side.flank_name(member),
        );
        let mend = e
            .remedy()
            .advice(&scene.path, &scene.design_path, dir, level);
        anyhow::Error::new(e).context(what + &mend)
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
