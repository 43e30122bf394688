//! The fixture of these tests: the white-paper pair's FE compliance, its
//! LTCA sweeps, the multibody tables built on it and the quasi-static runs.

use crate::common;
use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::utca::{LineGrid, RollSurface};
use solver::element::compliance::PairCompliance;
use solver::ltca::Sweep;
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::wheel_driven;
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use std::sync::OnceLock;

pub struct Fixture {
    pub g: PairGeometry,
    pub rs: RollSurface,
    pub pc: PairCompliance,
}

pub fn member(
    g: &PairGeometry,
    m: Member,
    refined: Vec<usize>,
) -> solver::element::compliance::MemberCompliance {
    let body = common::mesh(g, m, &refined, &[], "drive");
    common::compliance(g, &body, m, Side::Drive, refined[refined.len() / 2])
}

pub fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let g = common::white_paper();
        let (pt, wt) = teeth_in_contact(&g, Side::Drive, 2.0, 0.5f64.to_radians());
        let pc = PairCompliance {
            pinion: member(&g, Member::Pinion, pt),
            wheel: member(&g, Member::Wheel, wt),
        };
        let rs = RollSurface::new(
            g.side(Side::Drive),
            LineGrid {
                n_face: 41,
                n_profile: 41,
            },
        )
        .unwrap();
        Fixture { g, rs, pc }
    })
}

/// One mesh cycle in `n` steps from the entry of tooth 0.
pub fn sweep(f: &Fixture, n: usize, slices: usize) -> Sweep {
    let tau = f.g.data.mesh_cycle();
    Sweep {
        start: f.g.side(Side::Drive).roll_range[0],
        step: tau / n as f64,
        direction: pinion_direction(&f.g.data, Side::Drive),
        positions: n,
        slices,
        friction: 0.0,
    }
}

pub const TABLE_SLICES: usize = 20;
/// Polar moments of inertia of the test bodies, kg·m² (test values; the
/// stage computes the real ones from the body meshes).
pub const INERTIA: [f64; 2] = [2e-3, 2.5e-2];

/// One mesh cycle, periodic, `per_cycle` positions.
pub fn table(per_cycle: usize) -> MeshTable {
    let f = fixture();
    let fp = f.g.side(Side::Drive);
    let tau = f.g.data.mesh_cycle();
    let ratio = f.g.data.members[0].teeth as f64 / f.g.data.members[1].teeth as f64;
    MeshTable::build(
        fp,
        &f.rs,
        &f.pc,
        &f.g.frames[0],
        ratio,
        TableSpec {
            start: fp.roll_range[0],
            direction: pinion_direction(&f.g.data, Side::Drive),
            step: tau / per_cycle as f64,
            positions: per_cycle,
            periodic: true,
            slices: TABLE_SLICES,
            lag_nodes: 96,
            torque_max_nm: 1000.0,
        },
    )
    .unwrap()
}

/// 0.125° steps in q₁.
pub fn table_fine() -> &'static MeshTable {
    static T: OnceLock<MeshTable> = OnceLock::new();
    T.get_or_init(|| table(144))
}

/// TE (rad) against pinion rotation of a quasi-static run.
/// Pinion rotations and TE (rad) of a quasi-static run.
pub fn quasi_static_run(
    t: &MeshTable,
    torque: f64,
    cycles: f64,
    scheme: Scheme,
    friction: f64,
) -> [Vec<f64>; 2] {
    let wheel = 10.0 * std::f64::consts::PI / 30.0;
    let (m, s) = wheel_driven(t, INERTIA, wheel, torque, 0.1, friction).unwrap();
    let mut integ = Integrator::new(
        scheme,
        StepControl {
            max_step: 1e-3,
            min_step: 1e-9,
            tolerance: 1e-9,
        },
    );
    let t_end = cycles * t.span() / (wheel / t.ratio);
    let (mut q1, mut te) = (Vec::new(), Vec::new());
    integrate(&m, s, &mut integ, t_end, |s| {
        q1.push(s.q[0]);
        te.push(t.ratio * s.q[0] - s.q[1]);
        Ok(())
    })
    .unwrap();
    [q1, te]
}

/// The LTCA at 24 positions over the table's mesh cycle, with its slices.
pub fn table_sweep(t: &MeshTable, friction: f64) -> Sweep {
    Sweep {
        start: t.spec.start,
        step: t.span() / 24.0,
        direction: t.spec.direction,
        positions: 24,
        slices: TABLE_SLICES,
        friction,
    }
}
