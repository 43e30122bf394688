//! Coast-side contact: the backlash between the drive and the coast flanks,
//! the coast flanks' table placed in the drive coordinates, and rattle
//! between the two flank pairs at zero torque.

mod fe_fixtures;
use fe_fixtures as common;

use geometry::design::Member;
use geometry::generation::Side;
use geometry::pair::{pinion_direction, teeth_in_contact, PairGeometry};
use geometry::utca::{LineGrid, RollSurface};
use solver::element::compliance::PairCompliance;
use solver::ltca::Sweep;
use solver::multibody::backlash::{conjugate_backlash, Coast};
use solver::multibody::mesh_table::{MeshTable, TableSpec};
use solver::multibody::model::{Drive, Fluctuation, Impacts, Model, State};
use solver::multibody::time_step::{integrate, Integrator, Scheme, StepControl};
use solver::stage::context::coast_sweep;
use std::sync::OnceLock;

/// Circular backlash at the wheel's mean pitch radius: the normal backlash
/// j_n = π m_n − s_n1 − s_n2 (design data) over cos β_m gives the transverse
/// circular backlash, and over R_m sin δ₂ the wheel's angle.
#[test]
fn conjugate_backlash_is_the_designs_normal_backlash_at_the_wheels_mean_radius() {
    let g = common::white_paper();
    let d = &g.data;
    let b = conjugate_backlash(
        g.side(Side::Drive),
        g.side(Side::Coast),
        pinion_direction(d, Side::Drive),
    );
    let r_m2 = d.mean_cone_distance * d.members[1].pitch_angle.sin();
    let closed = d.normal_backlash() / (d.spiral_angle.cos() * r_m2);
    eprintln!(
        "backlash: flanks {:.3} µrad, design {:.3} µrad (j_n {:.4} mm)",
        b * 1e6,
        closed * 1e6,
        d.normal_backlash() * 1e3
    );
    assert!(b > 0.0, "{b}");
    assert!((b - closed).abs() < 0.02 * closed, "{b} vs {closed}");
}

const INERTIA: [f64; 2] = [2e-3, 2.5e-2];

struct Fixture {
    g: PairGeometry,
    drive: MeshTable,
    coast: Coast,
    /// The coast flanks' compliance that built the coast table.
    coast_compliance: PairCompliance,
}

fn rolls(g: &PairGeometry, side: Side) -> RollSurface {
    RollSurface::new(
        g.side(side),
        LineGrid {
            n_face: 41,
            n_profile: 41,
        },
    )
    .unwrap()
}

/// Both members meshed with drive and coast flanks refined, influence
/// fields on both flanks, and a periodic table per side.
fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let g = common::white_paper();
        let step = 0.5f64.to_radians();
        let (pd, wd) = teeth_in_contact(&g, Side::Drive, 1.0, step);
        let (pc, wc) = teeth_in_contact(&g, Side::Coast, 1.0, step);
        let pinion = common::mesh(&g, Member::Pinion, &pd, &pc, "both");
        let wheel = common::mesh(&g, Member::Wheel, &wd, &wc, "both");
        let tau = g.data.mesh_cycle();
        let ratio = g.data.members[0].teeth as f64 / g.data.members[1].teeth as f64;
        let table = |side: Side, pt: &[usize], wt: &[usize]| {
            let fp = g.side(side);
            let pc = PairCompliance {
                pinion: common::compliance(&g, &pinion, Member::Pinion, side, pt[pt.len() / 2]),
                wheel: common::compliance(&g, &wheel, Member::Wheel, side, wt[wt.len() / 2]),
            };
            let t = MeshTable::build(
                fp,
                &rolls(&g, side),
                &pc,
                &g.frames[0],
                ratio,
                TableSpec {
                    start: fp.roll_range[0],
                    direction: pinion_direction(&g.data, side),
                    step: tau / 72.0,
                    positions: 72,
                    periodic: true,
                    slices: 20,
                    lag_nodes: 64,
                    torque_max_nm: 600.0,
                },
            )
            .unwrap();
            (t, pc)
        };
        let (drive, _) = table(Side::Drive, &pd, &wd);
        let (coast, coast_compliance) = table(Side::Coast, &pc, &wc);
        let coast = Coast::place(g.side(Side::Drive), &drive, g.side(Side::Coast), coast).unwrap();
        Fixture {
            g,
            drive,
            coast,
            coast_compliance,
        }
    })
}

fn model<'a>(f: &'a Fixture, damping: f64, drive: Drive) -> Model<'a> {
    Model {
        table: &f.drive,
        coast: Some(&f.coast),
        inertia: INERTIA,
        damping,
        friction: 0.0,
        drive,
    }
}

/// Both bodies free, no torque, no damping.
fn free_undamped(f: &Fixture) -> Model<'_> {
    model(
        f,
        0.0,
        Drive::Free {
            pinion_torque: 0.0,
            wheel_torque: 0.0,
        },
    )
}

/// The coast flanks touch where an independent geometric contact search on
/// the coast side (at the same absolute pinion angle) says they do: just
/// past that lag the pinion's mesh torque is negative (the wheel pushes it
/// back), just before it the element is open, and between the two contact
/// limits (the free play) it carries no torque.
#[test]
fn coast_flanks_touch_where_the_direct_contact_search_finds_them() {
    let f = fixture();
    let cfp = f.g.side(Side::Coast);
    let crs = rolls(&f.g, Side::Coast);
    let m = free_undamped(f);
    let r = f.drive.ratio;
    // 3 µrad either side of the contact lag: the table's cubics smear the
    // onset of contact over about a µrad (a few hundredths of a N·m).
    let eps = 3e-6;
    for k in 0..12 {
        let q1 = f.drive.span() * (k as f64 + 0.37) / 12.0;
        let phi = f.drive.spec.start + f.drive.spec.direction * q1;
        let dc = geometry::direct::direct_te(cfp, &crs, phi, f.coast.table.spec.direction)
            .expect("coast contact");
        // Coast contact at lag θᶜ = te: drive lag θ = −B − te.
        let theta = -f.coast.backlash - dc.te;
        let torque = |th: f64| m.mesh([q1, r * q1 - th]).unwrap().0.grad[0];
        let (open, closed) = (torque(theta + eps), torque(theta - eps));
        assert!(closed < -0.2, "q1 {q1}: coast contact {closed} N m");
        assert!(open.abs() < 0.1 * closed.abs(), "q1 {q1}: open {open} N m");
        let hi = f.drive.unloaded(q1).unwrap()[0];
        let play = [0.25, 0.5, 0.75].map(|x| torque(theta + x * (hi - theta)));
        assert!(play.iter().all(|&t| t == 0.0), "free play {play:?}");
        // The drive contact on the other side of the play.
        let (open, closed) = (torque(hi - eps), torque(hi + eps));
        assert!(closed > 0.2, "q1 {q1}: drive contact {closed} N m");
        assert!(open.abs() < 0.1 * closed, "q1 {q1}: open {open} N m");
    }
}

/// Two paths to one loaded coast contact: the coast-loaded LTCA (coast
/// flanks, the drive sweep's pinion angles run backwards) gives lag θᶜ
/// under torque T; at drive lag −B − θᶜ the multibody element (the coast
/// table placed across the backlash) must then carry a pinion torque of −T.
#[test]
fn coast_loaded_ltca_and_the_elements_coast_contact_carry_the_same_torque() {
    let f = fixture();
    let m = free_undamped(f);
    let r = f.drive.ratio;
    let positions = 9;
    let drive_sweep = Sweep {
        start: f.drive.spec.start,
        step: f.drive.span() / positions as f64,
        direction: f.drive.spec.direction,
        positions,
        slices: f.drive.spec.slices,
        friction: 0.0,
    };
    let sweep = coast_sweep(&drive_sweep, &f.g, Side::Drive);
    let torques = [50.0, 200.0, 500.0];
    let res = solver::ltca::run(
        f.g.side(Side::Coast),
        &rolls(&f.g, Side::Coast),
        &f.coast_compliance,
        &sweep,
        &torques,
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for (k, p) in res.iter().enumerate() {
        let q1 = drive_sweep.step * (positions - 1 - k) as f64;
        for (l, &t) in p.loads.iter().zip(&torques) {
            let theta = -f.coast.backlash - l.te;
            let torque = m.mesh([q1, r * q1 - theta]).unwrap().0.grad[0];
            let e = (torque + t).abs() / t;
            worst = worst.max(e);
            assert!(e < 0.01, "q1 {q1}: {torque} N m against -{t} N m");
        }
    }
    eprintln!("worst relative torque difference {worst:.2e}");
}

fn energy_run(f: &Fixture, relative_speed: f64, t_end: f64) -> (f64, Impacts, usize) {
    let m = free_undamped(f);
    let r = f.drive.ratio;
    let [hi, lo] = f.coast.contact_lags(&f.drive, 0.0).unwrap();
    let w = 30.0 * std::f64::consts::PI / 30.0;
    // Mid-play, the wheel slower than conjugate: it lags, closes the drive
    // flanks, bounces back across the play onto the coast flanks, ...
    let s0 = State {
        t: 0.0,
        q: [0.0, -0.5 * (hi + lo)],
        v: [w, r * w - relative_speed],
        a: [0.0; 2],
    };
    let mut integ = Integrator::new(
        Scheme::EnergyConserving,
        StepControl {
            max_step: 2e-5,
            min_step: 1e-11,
            tolerance: 1e-3 * 1e-6,
        },
    );
    let e0 = m.energy(&s0).unwrap();
    let mut drift: f64 = 0.0;
    let mut impacts = Impacts::default();
    let (_, steps) = integrate(&m, s0, &mut integ, t_end, |s| {
        drift = drift.max((m.energy(s)? - e0).abs() / e0);
        impacts.record(m.contact(s.q, s.v)?.touching());
        Ok(())
    })
    .unwrap();
    (drift, impacts, steps)
}

/// Zero torque, no damping, both members free and the wheel started across
/// the backlash: it rattles between the drive and the coast flanks, and the
/// energy-conserving scheme keeps kinetic + mesh energy through every
/// impact.
#[test]
fn undamped_zero_torque_rattle_keeps_its_energy_through_drive_and_coast_impacts() {
    let f = fixture();
    let (drift, impacts, steps) = energy_run(f, 0.05, 0.2);
    eprintln!("rattle: {impacts:?} drive/coast impacts, {steps} steps, energy drift {drift:.2e}");
    assert!(impacts.drive >= 3 && impacts.coast >= 3, "{impacts:?}");
    assert!(drift < 1e-6, "{drift}");
}

/// The rattle drive: pinion speed fluctuating ±20 % at 30 Hz, zero load on
/// the wheel, mesh damping 5 %, generalized-α: the wheel hits both flank
/// pairs again and again, and the run stays bounded (lag within the play
/// plus the deflection of the table's largest torque, wheel speed within the
/// pinion's range).
#[test]
fn damped_rattle_under_a_fluctuating_pinion_speed_stays_bounded() {
    let f = fixture();
    let r = f.drive.ratio;
    let w = 300.0 * std::f64::consts::PI / 30.0;
    let speed = Fluctuation {
        mean: w,
        amplitude: 0.2,
        omega: 2.0 * std::f64::consts::PI * 30.0,
    };
    // Damping for 5 % of the mesh mode at 300 N·m.
    let loaded = solver::multibody::model::wheel_driven(&f.drive, INERTIA, 10.0, 300.0, 0.05, 0.0)
        .unwrap()
        .0
        .damping;
    let m = model(
        f,
        loaded,
        Drive::PinionFluctuating {
            speed,
            wheel_torque: 0.0,
        },
    );
    let [hi, lo] = f.coast.contact_lags(&f.drive, 0.0).unwrap();
    let s0 = State {
        t: 0.0,
        q: [0.0, -0.5 * (hi + lo)],
        v: [w, r * w],
        a: [0.0; 2],
    };
    let mut integ = Integrator::new(
        Scheme::GeneralizedAlpha { rho_inf: 0.9 },
        StepControl {
            max_step: 1e-5,
            min_step: 1e-11,
            tolerance: 1e-3 * 1e-6,
        },
    );
    let top = *f.drive.lags.last().unwrap();
    let mut impacts = Impacts::default();
    let mut theta_range = [f64::INFINITY, f64::NEG_INFINITY];
    let mut wheel = [f64::INFINITY, f64::NEG_INFINITY];
    let (_, steps) = integrate(&m, s0, &mut integ, 0.1, |s| {
        impacts.record(m.contact(s.q, s.v)?.touching());
        let th = r * s.q[0] - s.q[1];
        theta_range = [theta_range[0].min(th), theta_range[1].max(th)];
        wheel = [wheel[0].min(s.v[1]), wheel[1].max(s.v[1])];
        Ok(())
    })
    .unwrap();
    eprintln!(
        "rattle: {impacts:?} impacts, {steps} steps ({} rejected), lag {:.1}..{:.1} µrad (play {:.1}..{:.1}), wheel {:.1}..{:.1} rad/s",
        integ.rejected,
        theta_range[0] * 1e6,
        theta_range[1] * 1e6,
        lo * 1e6,
        hi * 1e6,
        wheel[0],
        wheel[1]
    );
    assert!(impacts.drive >= 2 && impacts.coast >= 2, "{impacts:?}");
    let coast_top = -f.coast.backlash - *f.coast.table.lags.last().unwrap();
    assert!(
        theta_range[0] > coast_top && theta_range[1] < top,
        "{theta_range:?}"
    );
    let (wlo, whi) = (r * w * (1.0 - 0.2), r * w * (1.0 + 0.2));
    assert!(wheel[0] > 0.9 * wlo && wheel[1] < 1.1 * whi, "{wheel:?}");
}
