//! The default scene's standard pair as the multibody benches set it up
//! (stiffness files and meshes from `make preprocess`): the scene, the pair
//! geometry, both members' compliance and polar moments (from the body
//! meshes, as `solver dynamic`), the loaded flanks' surface of roll angles
//! and the scene's sweep.

#![allow(dead_code)]

use geometry::pair::{FlankPair, PairGeometry};
use geometry::scene::{Blank, LoadedScene, Scene};
use geometry::utca::{roll_surface, RollSurface};
use solver::element::compliance::PairCompliance;
use solver::ltca::Sweep;
use solver::stage::context::LoadedPair;
use std::path::{Path, PathBuf};

pub struct DefaultPair {
    /// The workspace root (`bench/` goes under it).
    pub root: PathBuf,
    pub scene: LoadedScene,
    pub g: PairGeometry,
    pub pc: PairCompliance,
    /// Polar moments, kg·m².
    pub inertia: [f64; 2],
    pub rs: RollSurface,
    pub sweep: Sweep,
    /// Mesh cycle, rad, and r = z₁/z₂.
    pub tau: f64,
    pub ratio: f64,
}

impl DefaultPair {
    pub fn load() -> DefaultPair {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let scene =
            Scene::load(&root.join("reference/scenes/default.toml")).expect("default scene");
        let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
        let dir = root.join("meshes").join(&scene.scene.name);
        let pair = LoadedPair::load(&scene, &g, &dir, [Blank::Standard; 2])
            .expect("meshes/default: run `make preprocess` first");
        let [(j1, _), (j2, _)] = pair.inertia(&scene, &g, &dir).expect("polar moments");
        let rs = roll_surface(g.side(scene.scene.loaded_flank), &scene.scene.utca).unwrap();
        let LoadedPair { pc, sweep, .. } = pair;
        let inertia = [j1, j2];
        let tau = g.data.mesh_cycle();
        let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
        DefaultPair {
            root,
            scene,
            g,
            pc,
            inertia,
            rs,
            sweep,
            tau,
            ratio,
        }
    }

    /// The loaded flank pair.
    pub fn fp(&self) -> &FlankPair {
        self.g.side(self.scene.scene.loaded_flank)
    }
}
