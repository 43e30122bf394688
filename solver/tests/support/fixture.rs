//! The checked-in example-02 stiffness fixture (white-paper pair, standard
//! blanks, one mesh cycle in 1° steps; no gmsh) as the solver tests set it
//! up: the scene, the pair geometry, the surface of roll angles, both
//! members' compliance and the scene's sweep.

#![allow(dead_code)]

use geometry::pair::PairGeometry as Pair;
use geometry::pair::{FlankPair, PairGeometry};
use geometry::scene::{LoadedScene, Scene};
use geometry::utca::{roll_surface, RollSurface};
use solver::bearings::support::{Bearing, Support};
use solver::bearings::system_deflection::Supports;
use solver::element::compliance::PairCompliance;
use solver::ltca::Sweep;
use solver::stage::context::LoadedPair;
use std::path::PathBuf;

pub struct Fixture {
    /// The example's folder.
    pub dir: PathBuf,
    pub scene: LoadedScene,
    pub g: PairGeometry,
    /// Of the loaded flanks.
    pub rs: RollSurface,
    pub pc: PairCompliance,
    /// The scene's sweep for its first wheel blank.
    pub sweep: Sweep,
    /// Polar moments of the pinion and the wheel from the meshes, kg·m².
    pub inertia: [f64; 2],
}

impl Fixture {
    pub fn example_02() -> Fixture {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples/02_ltca_fixture");
        let dir = dir.canonicalize().unwrap_or(dir);
        let scene = Scene::load(&dir.join("scene.toml")).unwrap();
        let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
        let rs = roll_surface(g.side(scene.scene.loaded_flank), &scene.scene.utca).unwrap();
        let mdir = dir.join("meshes").join(&scene.scene.name);
        let blanks = [scene.scene.blanks.pinion[0], scene.scene.blanks.wheel[0]];
        let pair = LoadedPair::load(&scene, &g, &mdir, blanks).unwrap();
        // Polar moments from the meshes.
        let [(j1, _), (j2, _)] = pair.inertia(&scene, &g, &mdir).unwrap();
        let LoadedPair { pc, sweep, .. } = pair;
        Fixture {
            dir,
            scene,
            g,
            rs,
            pc,
            sweep,
            inertia: [j1, j2],
        }
    }

    /// The loaded flank pair.
    pub fn fp(&self) -> &FlankPair {
        self.g.side(self.scene.scene.loaded_flank)
    }

    /// The contact-element table over one mesh cycle (periodic) in steps
    /// of about `step_deg`, with `lag_nodes` lags up to `torque_max_nm`.
    pub fn table(
        &self,
        step_deg: f64,
        lag_nodes: usize,
        torque_max_nm: f64,
    ) -> solver::multibody::mesh_table::MeshTable {
        let tau = self.g.data.mesh_cycle();
        let per = (tau / step_deg.to_radians()).round() as usize;
        let spec = solver::multibody::mesh_table::TableSpec {
            start: self.sweep.start,
            direction: self.sweep.direction,
            step: tau / per as f64,
            positions: per,
            periodic: true,
            slices: self.scene.scene.ltca.slices,
            lag_nodes,
            torque_max_nm,
        };
        let d = &self.g.data;
        let ratio = d.members[0].teeth as f64 / d.members[1].teeth as f64;
        solver::multibody::mesh_table::MeshTable::build(
            self.fp(),
            &self.rs,
            &self.pc,
            &self.g.frames[0],
            ratio,
            spec,
        )
        .unwrap()
    }

    /// The LTCA over the scene's sweep at `torques`.
    pub fn ltca(&self, torques: &[f64]) -> Vec<solver::ltca::PositionResult> {
        solver::ltca::run(self.fp(), &self.rs, &self.pc, &self.sweep, torques).unwrap()
    }
}

/// An overhung pinion (bearings 40 and 100 mm behind its mean point) and a
/// wheel on bearings 20 and 120 mm behind its mean point, all of radial
/// and axial stiffness `k` (N/m; the second bearing of each floating).
pub fn supports(g: &Pair, k: f64) -> Supports {
    let one = |m: usize, near: f64, far: f64| {
        let frame = &g.frames[m];
        let s = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        Support::new(
            if m == 0 {
                "pinion.bearings"
            } else {
                "wheel.bearings"
            },
            frame.axis(),
            nalgebra::Vector3::zeros(),
            &[
                Bearing {
                    axial_position_m: s + near,
                    radial_stiffness_n_per_m: k,
                    axial_stiffness_n_per_m: k,
                },
                Bearing {
                    axial_position_m: s + far,
                    radial_stiffness_n_per_m: k,
                    axial_stiffness_n_per_m: 0.0,
                },
            ],
        )
        .unwrap()
    };
    Supports {
        pinion: one(0, 0.04, 0.10),
        wheel: one(1, 0.02, 0.12),
    }
}

/// The bearings of [`supports`] on flexible shafts: each member's gear
/// seated at its mean point, a solid shaft of diameter `diameter_m` from
/// there to its far bearing, of the design's material with Young's
/// modulus multiplied by `stiffer`.
pub fn supports_on_shafts(g: &Pair, k: f64, diameter_m: f64, stiffer: f64) -> Supports {
    use solver::bearings::flexible_shaft::{Shaft, ShaftSegment};
    let rigid = supports(g, k);
    let one = |m: usize, s: &Support| {
        let seat = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        let far = s
            .bearings()
            .iter()
            .fold(seat, |a, b| a.max(b.axial_position_m));
        let material = g.data.members[m].material();
        Support::on_shaft(
            if m == 0 {
                "pinion.bearings"
            } else {
                "wheel.bearings"
            },
            g.frames[m].axis(),
            nalgebra::Vector3::zeros(),
            s.bearings(),
            &Shaft {
                segments: vec![ShaftSegment {
                    from_m: seat,
                    to_m: far,
                    outer_diameter_m: diameter_m,
                    inner_diameter_m: 0.0,
                }],
                seat_m: seat,
                youngs_modulus_pa: material.youngs_modulus_pa * stiffer,
                poisson_ratio: material.poisson_ratio,
            },
        )
        .unwrap()
    };
    Supports {
        pinion: one(0, &rigid.pinion),
        wheel: one(1, &rigid.wheel),
    }
}
