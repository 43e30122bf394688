//! The flexible gearbox's linear structure against the static shaft
//! condensation, beam theory's frequencies and series springs.

use nalgebra::{DMatrix, SMatrix, Vector3};
use solver::bearings::flexible_shaft::{Shaft, ShaftSegment};
use solver::bearings::support::{Bearing, Support};
use solver::bearings::timoshenko::Section;
use solver::gearbox::system_modes::{campbell_crossings, system_modes, ENERGY_PARTS};
use solver::gearbox::{assemble, Housing, MemberParts, Part};
use solver::multibody::compliant::MemberBody;

const E: f64 = 206e9;
const NU: f64 = 0.3;
const RHO: f64 = 7850.0;

fn bearing(at: f64, radial: f64, axial: f64) -> Bearing {
    Bearing {
        axial_position_m: at,
        radial_stiffness_n_per_m: radial,
        axial_stiffness_n_per_m: axial,
    }
}

fn shaft(from: f64, to: f64, d: f64, seat: f64) -> Shaft {
    Shaft {
        segments: vec![ShaftSegment {
            from_m: from,
            to_m: to,
            outer_diameter_m: d,
            inner_diameter_m: 0.0,
        }],
        seat_m: seat,
        youngs_modulus_pa: E,
        poisson_ratio: NU,
    }
}

fn body(axis: Vector3<f64>, bearings: &[Bearing], mass: f64) -> MemberBody {
    MemberBody {
        support: Support::new("pinion.bearings", axis, Vector3::zeros(), bearings).unwrap(),
        damping: vec![(0.0, 0.0); bearings.len()],
        mass_kg: mass,
        centroid_m: 0.0,
        transverse_inertia_kgm2: mass * 1e-4,
    }
}

/// The pair's parts: the pinion on `shaft` (None: rigid), the wheel on a
/// rigid shaft.
fn parts<'a>(
    pinion: &'a MemberBody,
    shaft: Option<&'a Shaft>,
    wheel: &'a MemberBody,
) -> [MemberParts<'a>; 2] {
    [
        MemberParts {
            body: pinion,
            polar_inertia_kgm2: 1e-3,
            shaft: shaft.map(|s| (s, RHO)),
        },
        MemberParts {
            body: wheel,
            polar_inertia_kgm2: 1e-2,
            shaft: None,
        },
    ]
}

/// Schur complement of `k` onto the coordinates `keep` (the turns q₁, q₂,
/// which carry no stiffness, left out).
fn condense(k: &DMatrix<f64>, keep: &[usize]) -> DMatrix<f64> {
    let rest: Vec<usize> = (2..k.nrows()).filter(|i| !keep.contains(i)).collect();
    let kk = k.select_rows(keep).select_columns(keep);
    if rest.is_empty() {
        return kk;
    }
    let kr = k.select_rows(&rest).select_columns(&rest);
    let krk = k.select_rows(&rest).select_columns(keep);
    kk - krk.transpose() * kr.cholesky().unwrap().solve(&krk)
}

fn close(a: &DMatrix<f64>, b: &DMatrix<f64>, tol: f64) -> bool {
    (a - b).amax() <= tol * b.amax()
}

/// The structure with a flexible shaft, statically condensed onto the gear
/// body's five coordinates, is the support of the shaft condensed by
/// `flexible_shaft` (Qᵀ K Q): two codes, one by transformations of the
/// beam elements and the bearing springs in the fixed frame, the other in
/// the shaft's frame; the extra nodes of the subdivision change nothing
/// (the element is exact under nodal loads).
#[test]
fn shaft_condensed_onto_the_gear_body_is_the_flexible_shaft_support() {
    let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
    let bearings = [bearing(0.05, 4e8, 2e8), bearing(0.16, 3e8, 0.0)];
    let sh = shaft(0.02, 0.2, 0.035, 0.09);
    let pinion = body(axis, &bearings, 2.0);
    let wheel = body(
        Vector3::new(0.0, 1.0, 0.0),
        &[bearing(-0.05, 5e8, 1e8), bearing(0.05, 5e8, 0.0)],
        4.0,
    );
    let s = assemble(parts(&pinion, Some(&sh), &wheel), None, 0.01).unwrap();
    assert!(s.parts.iter().filter(|p| **p == Part::Shaft(0)).count() >= 5 * 17);
    let on_body = condense(&s.stiffness, &(2..7).collect::<Vec<_>>());
    let flexible =
        Support::on_shaft("pinion.bearings", axis, Vector3::zeros(), &bearings, &sh).unwrap();
    let q = flexible.basis();
    let want = q.transpose() * flexible.stiffness() * q;
    let want = DMatrix::from_iterator(5, 5, want.iter().copied());
    assert!(close(&on_body, &want, 1e-8), "{on_body} against {want}");
    // The rigid-shaft member is the rigid support's Qᵀ K Q.
    let rigid = &wheel.support;
    let want = rigid.basis().transpose() * rigid.stiffness() * rigid.basis();
    let want = DMatrix::from_iterator(5, 5, want.iter().copied());
    let got = s.stiffness.view((7, 7), (5, 5)).into_owned();
    assert!(close(&got, &want, 1e-12));
    // The turns carry no stiffness; their inertia is the body's polar
    // moment plus the shaft's ρJL.
    assert!(s.stiffness.row(0).amax() == 0.0 && s.stiffness.row(1).amax() == 0.0);
    let j = Section::round(0.035, 0.0, E, NU).polar_m4;
    assert!((s.mass[(0, 0)] - (1e-3 + RHO * j * 0.18)).abs() < 1e-12);
}

/// Timoshenko beam theory, pinned–pinned, lowest bending ω² (see
/// `solver::bearings::timoshenko`'s test).
fn pinned_timoshenko_omega2(d: f64, length: f64) -> f64 {
    let s = Section::round(d, 0.0, E, NU);
    let (a, i) = (s.area_m2, s.inertia_m4);
    let al = std::f64::consts::PI / length;
    let (ks, kb) = (
        s.shear_coefficient * s.shear_modulus_pa * a,
        E * i * al * al,
    );
    let qa = RHO * a * RHO * i;
    let qb = -(ks * al * al * RHO * i + RHO * a * (kb + ks));
    let qc = ks * al * al * (kb + ks) - ks * ks * al * al;
    (-qb - (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa)
}

/// A shaft on two very stiff bearings at its ends (pinned) with a gear of
/// negligible mass: the gearbox's lowest mode is the shaft's first bending
/// mode, twice (both planes), at Timoshenko's frequency; its energy is in
/// the shaft (and the seat node's share, which the gear body carries).
#[test]
fn pinned_shaft_mode_of_the_gearbox_is_timoshenkos() {
    let (l, d) = (0.3, 0.04);
    let axis = Vector3::new(1.0, 0.0, 0.0);
    let bearings = [bearing(0.0, 1e13, 1e13), bearing(l, 1e13, 0.0)];
    let sh = shaft(0.0, l, d, 0.37 * l);
    let light = body(axis, &bearings, 1e-6);
    let wheel = body(
        Vector3::new(0.0, 0.0, 1.0),
        &[bearing(-0.05, 1e13, 1e13), bearing(0.05, 1e13, 0.0)],
        1e-3,
    );
    let s = assemble(parts(&light, Some(&sh), &wheel), None, l / 40.0).unwrap();
    let modes = system_modes(&s, &SMatrix::zeros(), [true, true]).unwrap();
    let exact = pinned_timoshenko_omega2(d, l).sqrt() / (2.0 * std::f64::consts::PI);
    for m in &modes[..2] {
        let err = (m.frequency_hz - exact) / exact;
        assert!(
            err.abs() < 2e-4 && err > -1e-9,
            "{} Hz against {exact} Hz ({err:e})",
            m.frequency_hz
        );
        let total: f64 = m.energy_share.iter().sum();
        assert!((total - 1.0).abs() < 1e-9);
        let moving = m.energy_share[4] + m.energy_share[2];
        assert!(moving > 0.999, "{:?} of {ENERGY_PARTS:?}", m.energy_share);
    }
    // The order lines cross it where order × n / 60 is its frequency.
    let c = campbell_crossings(&modes[..1], &[20.0, 40.0], 1e5);
    assert_eq!(c.len(), 2);
    assert!((c[0].pinion_rpm - 60.0 * exact / 40.0).abs() < 1e-3 * c[0].pinion_rpm);
    assert!(campbell_crossings(&modes[..1], &[20.0], 0.5 * 60.0 * exact / 20.0).is_empty());
}

/// A housing as a spring k_h under each seat (in all three directions)
/// with a rigid shaft: the body's static stiffness is that of bearings in
/// series with the housing, k_b k_h / (k_b + k_h), radially and axially.
/// A housing much stiffer than the bearings gives the rigid housing's modes.
#[test]
fn housing_springs_act_in_series_with_the_bearings() {
    let axis = Vector3::new(0.0, 0.6, 0.8);
    let (kr, ka, kh) = (4e8, 2e8, 6e8);
    let bearings = [bearing(0.04, kr, ka), bearing(0.15, kr, 0.0)];
    let member = body(axis, &bearings, 3.0);
    let wheel = body(
        Vector3::new(1.0, 0.0, 0.0),
        &[bearing(-0.05, 5e8, 1e8), bearing(0.05, 5e8, 0.0)],
        4.0,
    );
    let spring_housing = |k: f64| Housing {
        stiffness: DMatrix::from_diagonal_element(12, 12, k),
        mass: DMatrix::from_diagonal_element(12, 12, 0.5),
        damping: DMatrix::zeros(12, 12),
        seats: vec![(0, 0), (0, 1)],
    };
    let soft = assemble(
        parts(&member, None, &wheel),
        Some(&spring_housing(kh)),
        0.01,
    )
    .unwrap();
    let on_body = condense(&soft.stiffness, &(2..7).collect::<Vec<_>>());
    let series = |k: f64| k * kh / (k + kh);
    let in_series = body(
        axis,
        &[
            bearing(0.04, series(kr), series(ka)),
            bearing(0.15, series(kr), 0.0),
        ],
        3.0,
    );
    let q = in_series.support.basis();
    let want = q.transpose() * in_series.support.stiffness() * q;
    let want = DMatrix::from_iterator(5, 5, want.iter().copied());
    assert!(close(&on_body, &want, 1e-9), "{on_body} against {want}");
    assert_eq!(soft.bearings.len(), 4);

    let rigid = assemble(parts(&member, None, &wheel), None, 0.01).unwrap();
    let stiff = assemble(
        parts(&member, None, &wheel),
        Some(&spring_housing(1e16)),
        0.01,
    )
    .unwrap();
    let a = system_modes(&rigid, &SMatrix::zeros(), [true, true]).unwrap();
    let b = system_modes(&stiff, &SMatrix::zeros(), [true, true]).unwrap();
    let c = system_modes(&soft, &SMatrix::zeros(), [true, true]).unwrap();
    for i in 0..a.len() {
        let err = (b[i].frequency_hz - a[i].frequency_hz) / a[i].frequency_hz;
        assert!(
            err.abs() < 1e-6,
            "mode {i}: {} against {}",
            b[i].frequency_hz,
            a[i].frequency_hz
        );
        assert!(
            c[i].frequency_hz < a[i].frequency_hz,
            "a soft housing lowers mode {i}"
        );
    }
    // Unheld turns of a pair with no mesh: two rigid modes at 0 Hz.
    let free = system_modes(&rigid, &SMatrix::zeros(), [false, false]).unwrap();
    assert!(free[0].frequency_hz < 1e-6 && free[1].frequency_hz < 1e-6);
    assert!(free[2].frequency_hz > 1.0);
}

/// A member's rigid motion (every node of its shaft and its gear body
/// moved as one body about the apex) strains no beam element: the
/// structure's forces are its bearings' alone, K r = Σ Gᵀ K_b G r.
#[test]
fn rigid_motion_of_a_member_strains_only_its_bearings() {
    let axis = Vector3::new(-0.2, 0.9, 0.4).normalize();
    let bearings = [bearing(0.03, 4e8, 2e8), bearing(0.14, 3e8, 0.0)];
    let sh = shaft(0.0, 0.17, 0.04, 0.08);
    let pinion = body(axis, &bearings, 2.0);
    let wheel = body(
        Vector3::new(1.0, 0.0, 0.0),
        &[bearing(-0.05, 5e8, 1e8), bearing(0.05, 5e8, 0.0)],
        4.0,
    );
    let s = assemble(parts(&pinion, Some(&sh), &wheel), None, 0.02).unwrap();
    let q = pinion.support.basis();
    let n = s.parts.len();
    // Shaft node axial positions in coordinate order: the nodes but the seat.
    let mut nodes: Vec<f64> = Vec::new();
    let named: [f64; 5] = [0.0, 0.03, 0.08, 0.14, 0.17];
    for w in named.windows(2) {
        let parts = ((w[1] - w[0]) / 0.02).ceil() as usize;
        for p in 1..=parts {
            nodes.push(w[0] + (w[1] - w[0]) * p as f64 / parts as f64);
        }
    }
    nodes.insert(0, 0.0);
    nodes.retain(|p| (p - 0.08).abs() > 1e-9);
    assert_eq!(
        5 * nodes.len(),
        s.parts.iter().filter(|p| **p == Part::Shaft(0)).count()
    );
    for (u, th) in [
        (Vector3::new(1.0, -2.0, 0.5), Vector3::zeros()),
        (Vector3::zeros(), axis.cross(&Vector3::new(0.0, 0.0, 1.0))),
    ] {
        let at = |p: f64| -> nalgebra::Vector5<f64> {
            let disp = u + th.cross(&(axis * p));
            let g = nalgebra::Vector6::new(disp.x, disp.y, disp.z, th.x, th.y, th.z);
            q.transpose() * g
        };
        let mut r = DMatrix::zeros(n, 1);
        r.view_mut((2, 0), (5, 1)).copy_from(&at(0.0));
        for (j, &p) in nodes.iter().enumerate() {
            r.view_mut((12 + 5 * j, 0), (5, 1)).copy_from(&at(p));
        }
        let f = &s.stiffness * &r;
        let mut bearings_only = DMatrix::zeros(n, 1);
        for b in s.bearings.iter().filter(|b| b.member == 0) {
            let kb = DMatrix::from_iterator(3, 3, b.stiffness.iter().copied());
            bearings_only += b.relative.transpose() * kb * (&b.relative * &r);
        }
        assert!(
            (&f - &bearings_only).amax() < 1e-9 * f.amax(),
            "{}",
            (&f - &bearings_only).amax() / f.amax()
        );
        assert!(f.amax() > 1e6);
    }
}

/// Modal damping of a reduced housing: c = 2 ζ √(k m) on each modal
/// coordinate (a mode of ω² = k/m damped at ratio ζ), none on the seats'.
#[test]
fn housing_modal_damping_gives_each_mode_its_ratio() {
    let k = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(
        vec![1e9; 6].into_iter().chain([4e8, 9e8]).collect(),
    ));
    let m = DMatrix::from_diagonal(&nalgebra::DVector::from_vec(
        vec![2.0; 6].into_iter().chain([1.0, 4.0]).collect(),
    ));
    let c = solver::gearbox::structure::modal_damping(&k, &m, 6, 0.02);
    for i in 0..6 {
        assert_eq!(c[(i, i)], 0.0);
    }
    for i in 6..8 {
        let zeta = c[(i, i)] / (2.0 * (k[(i, i)] * m[(i, i)]).sqrt());
        assert!((zeta - 0.02).abs() < 1e-15, "{zeta}");
    }
    assert_eq!(c[(6, 7)], 0.0);
}
