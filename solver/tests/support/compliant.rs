//! The compliant-bearing multibody on the example-02 fixture, as its tests
//! and the bench set it up: a periodic table over one mesh cycle in 1°
//! steps, its lag shift, and both members on two bearings each (the
//! supports of `bearing_deflection_on_fixture.rs`: an overhung pinion on
//! bearings 40 and 100 mm behind its mean point, the wheel on bearings 20
//! and 120 mm behind its mean point, the second of each floating).

#![allow(dead_code)]

pub use super::fixture::supports;
use super::fixture::Fixture;
use geometry::generation::trace_sign;
use geometry::pair::PairGeometry;
use solver::bearings::support::Support;
use solver::bearings::system_deflection::Supports;
use solver::multibody::compliant::MemberBody;
use solver::multibody::lag_shift::LagShift;
use solver::multibody::mesh_table::MeshTable;

pub struct Compliant {
    pub f: Fixture,
    pub table: MeshTable,
    pub shift: LagShift,
    /// Polar moments from the fixture's meshes, kg·m².
    pub inertia: [f64; 2],
    pub ratio: f64,
    pub hand: f64,
}

impl Compliant {
    pub fn example_02(lag_nodes: usize, torque_max_nm: f64) -> Compliant {
        let f = Fixture::example_02();
        let table = f.table(1.0, lag_nodes, torque_max_nm);
        let ratio = table.ratio;
        let shift = LagShift::build(
            &f.g,
            f.scene.scene.loaded_flank,
            &f.scene.scene.utca,
            &table,
            &geometry::misalignment::Misalignment::default(),
        )
        .unwrap();
        let inertia = f.inertia;
        let hand = trace_sign(f.g.data.members[0].hand);
        Compliant {
            f,
            table,
            shift,
            inertia,
            ratio,
            hand,
        }
    }
}

/// The members as bodies on `supports` with bearing damping `c` (N·s/m,
/// radial and axial): steel bodies of plausible size for the white-paper
/// pair (pinion 1.5 kg, wheel 12 kg, centres at the mean point).
pub fn bodies(
    g: &PairGeometry,
    s: &Supports,
    c: f64,
) -> [solver::multibody::compliant::MemberBody; 2] {
    let body = |m: usize, support: &Support, mass: f64, jt: f64| MemberBody {
        support: support.clone(),
        damping: vec![(c, c); support.bearings().len()],
        mass_kg: mass,
        centroid_m: g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos(),
        transverse_inertia_kgm2: jt,
    };
    [body(0, &s.pinion, 1.5, 2e-3), body(1, &s.wheel, 12.0, 0.1)]
}

/// The rigid model of `c` with the pinion at a constant `rpm` against
/// `pinion_torque_nm` (the wheel resisting through the ratio), mesh
/// damping ratio 0.05 at the quasi-static start.
pub fn pinion_at(
    c: &Compliant,
    rpm: f64,
    pinion_torque_nm: f64,
) -> solver::multibody::model::Model<'_> {
    use solver::multibody::model::{Drive, Model, Ramp};
    let w1 = rpm * std::f64::consts::PI / 30.0;
    let mut rigid = Model {
        table: &c.table,
        coast: None,
        inertia: c.inertia,
        damping: 0.0,
        friction: 0.0,
        drive: Drive::PinionSpeed {
            speed: Ramp {
                from: w1,
                to: w1,
                duration: 0.0,
            },
            wheel_torque: pinion_torque_nm / c.ratio,
        },
    };
    let s = rigid.static_state(0.0).unwrap();
    rigid.damping = rigid.damping_for_ratio(0.05, &s).unwrap();
    rigid
}

/// Solid shafts of `diameter_m`, each gear seated at its mean point, the
/// shaft from there to its far bearing (the design's steel).
pub fn shafts_from_mean_points(
    g: &PairGeometry,
    s: &[MemberBody; 2],
    diameter_m: f64,
) -> [solver::bearings::flexible_shaft::Shaft; 2] {
    use solver::bearings::flexible_shaft::{Shaft, ShaftSegment};
    std::array::from_fn(|m| {
        let seat = g.data.mean_cone_distance * g.data.members[m].pitch_angle.cos();
        let far = s[m]
            .support
            .bearings()
            .iter()
            .fold(seat, |a, b| a.max(b.axial_position_m));
        let material = g.data.members[m].material();
        Shaft {
            segments: vec![ShaftSegment {
                from_m: seat,
                to_m: far,
                outer_diameter_m: diameter_m,
                inner_diameter_m: 0.0,
            }],
            seat_m: seat,
            youngs_modulus_pa: material.youngs_modulus_pa,
            poisson_ratio: material.poisson_ratio,
        }
    })
}

/// The gearbox parts of `b`: the shafts (with `density`) or rigid ones.
pub fn parts<'a>(
    b: &'a [MemberBody; 2],
    inertia: [f64; 2],
    shafts: Option<&'a [solver::bearings::flexible_shaft::Shaft; 2]>,
    density: f64,
) -> [solver::gearbox::MemberParts<'a>; 2] {
    std::array::from_fn(|k| solver::gearbox::MemberParts {
        body: &b[k],
        polar_inertia_kgm2: inertia[k],
        shaft: shafts.map(|s| (&s[k], density)),
    })
}

/// Fixed steps of `h`.
pub fn fixed(h: f64) -> solver::multibody::time_step::StepControl {
    solver::multibody::time_step::StepControl {
        max_step: h,
        min_step: h,
        tolerance: 1.0,
    }
}
