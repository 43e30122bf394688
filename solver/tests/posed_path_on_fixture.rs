//! The misaligned ("posed") contact path against the aligned one on the
//! checked-in example-02 stiffness fixture (no gmsh). The posed path is the
//! aligned surface-of-roll-angles model plus the pose's exact change
//! (`geometry::mate::pose_correction`), so with the identity pose it must
//! give the aligned slices, and a tiny misalignment must give the aligned
//! TE and pressures up to the misalignment's own (first-order) effect.
//! Before the correction form, the identity pose gave 20 slices where the
//! aligned path has 33, dropped whole tooth pairs, and moved the largest
//! pressure at 700 N·m by 5 %.

#[path = "support/fixture.rs"]
mod fixture;

use fixture::Fixture;
use geometry::misalignment::{Component, Misalignment, Pose};
use geometry::pair::PairGeometry;
use geometry::utca::roll_surface;
use solver::ltca::{geometry as slice_geometry, mean_ptp, run, PositionResult};

/// Torques of the checks, N·m: the fixture's two and the default scene's
/// largest, where the contact reaches the wheel's tip edge.
const TORQUES: [f64; 3] = [100.0, 300.0, 700.0];

/// The fixture's LTCA with the pair placed by `m` (the aligned path when
/// all four are zero).
fn ltca(f: &Fixture, m: &Misalignment) -> Vec<PositionResult> {
    let mut g: PairGeometry = f.g.clone();
    g.misalign(m);
    let fp = g.side(f.scene.scene.loaded_flank);
    let rs = roll_surface(fp, &f.scene.scene.utca).unwrap();
    run(fp, &rs, &f.pc, &f.sweep, &TORQUES).unwrap()
}

/// TE peak-to-peak (µrad), mean TE (µrad) and largest pressure (MPa) at torque index `i`.
fn statistics(res: &[PositionResult], i: usize) -> [f64; 3] {
    let te: Vec<f64> = res.iter().map(|p| p.loads[i].te).collect();
    let (mean, ptp) = mean_ptp(&te);
    let pmax = res
        .iter()
        .map(|p| p.loads[i].max_pressure_pa)
        .fold(0.0, f64::max);
    [ptp * 1e6, mean * 1e6, pmax * 1e-6]
}

/// Every slice of every position (pair, band, ξ, η, lag, curvature radius,
/// both levers, friction levers, the wheel point) of the posed path with
/// the identity pose equals the aligned path's. The correction is exactly
/// zero there, so the two agree bit for bit (measured); the tolerances
/// below (1e-12 relative, i.e. 1e-6 µrad on a 1 mrad lag) leave room for a
/// reordering of floating-point sums only.
#[test]
fn posed_path_with_identity_pose_reproduces_the_aligned_slices() {
    let f = Fixture::example_02();
    let fp = f.fp();
    let mut posed = fp.clone();
    posed.pose = Some(Pose::identity());
    let rs = roll_surface(&posed, &f.scene.scene.utca).unwrap();
    let tau = f.g.data.mesh_cycle();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-3);
    let mut compared = 0;
    for k in 0..f.sweep.positions {
        let phi = f.sweep.start + f.sweep.direction * f.sweep.step * k as f64;
        let a = slice_geometry(fp, &f.rs, phi, tau, f.sweep.slices);
        let b = slice_geometry(&posed, &rs, phi, tau, f.sweep.slices);
        assert!(
            close(a.utca_te, b.utca_te),
            "position {k}: UTCA {} vs {} urad",
            a.utca_te * 1e6,
            b.utca_te * 1e6
        );
        assert_eq!(
            a.slices.len(),
            b.slices.len(),
            "position {k}: slice count (aligned {:?}, posed {:?})",
            a.slices.iter().map(|s| (s.pair, s.xi)).collect::<Vec<_>>(),
            b.slices.iter().map(|s| (s.pair, s.xi)).collect::<Vec<_>>()
        );
        for (x, y) in a.slices.iter().zip(&b.slices) {
            let what = format!("position {k}, pair {}, xi {:.4}", x.pair, x.xi);
            assert_eq!(x.pair, y.pair, "{what}");
            let pairs = [
                ("band start", x.band[0], y.band[0]),
                ("band end", x.band[1], y.band[1]),
                ("xi", x.xi, y.xi),
                ("eta", x.eta, y.eta),
                ("lag", x.lag, y.lag),
                ("rho", x.rho, y.rho),
                ("wheel lever", x.lever_wheel, y.lever_wheel),
                ("pinion lever", x.lever_pinion, y.lever_pinion),
                ("friction lever 1", x.friction_lever[0], y.friction_lever[0]),
                ("friction lever 2", x.friction_lever[1], y.friction_lever[1]),
                ("wheel xi", x.wheel_xi_eta[0], y.wheel_xi_eta[0]),
                ("wheel eta", x.wheel_xi_eta[1], y.wheel_xi_eta[1]),
                ("length", x.length, y.length),
            ];
            for (name, u, v) in pairs {
                assert!(close(u, v), "{what}: {name} {u:e} vs {v:e}");
            }
            compared += 1;
        }
    }
    // The sweep's 18 positions hold about 30 slices each.
    assert!(compared > 400, "{compared} slices compared");
}

/// A misalignment of ±1e-4 mm (E, P, G) or ±1e-4° (ΔΣ) on the posed path
/// against the aligned path at zero: the loaded TE's peak-to-peak and the
/// largest pressure change by the misalignment's own small effect only, not
/// by a step between the two paths. The mean TE moves by the backlash
/// change, first order in the misalignment: opposite values move it by
/// opposite amounts (the symmetric part below 5 % of the antisymmetric one
/// measured ~1e-3; a step at zero would dominate it).
#[test]
fn te_and_pressure_are_continuous_through_zero_misalignment() {
    let f = Fixture::example_02();
    let aligned = ltca(&f, &Misalignment::default());
    for c in Component::ALL {
        let side = |s: f64| ltca(&f, &Misalignment::default().with(c, s * 1e-4));
        let (plus, minus) = (side(1.0), side(-1.0));
        for (i, t) in TORQUES.iter().enumerate() {
            let a = statistics(&aligned, i);
            let (p, m) = (statistics(&plus, i), statistics(&minus, i));
            println!(
                "{c:?} {t} N·m: ptp {:.4} / {:.4} / {:.4} urad, mean shift {:+.4} / {:+.4} urad, \
                 pmax {:.3} / {:.3} / {:.3} MPa (−, 0, +)",
                m[0],
                a[0],
                p[0],
                m[1] - a[1],
                p[1] - a[1],
                m[2],
                a[2],
                p[2]
            );
            for s in [&p, &m] {
                assert!(
                    (s[0] - a[0]).abs() < 0.1,
                    "{c:?} {t} N·m: TE ptp {:.4} vs {:.4} urad aligned",
                    s[0],
                    a[0]
                );
                assert!(
                    (s[2] / a[2] - 1.0).abs() < 5e-3,
                    "{c:?} {t} N·m: largest pressure {:.3} vs {:.3} MPa aligned",
                    s[2],
                    a[2]
                );
            }
            let (up, down) = (p[1] - a[1], m[1] - a[1]);
            assert!(
                (up + down).abs() < 0.05 * (up - down).abs(),
                "{c:?} {t} N·m: mean TE moves by {up:+.5} / {down:+.5} urad"
            );
        }
    }
}

/// Tooth pairs come from the aligned active roll range, for a misaligned
/// pair too. A pair just outside it (its tooth before entering or after
/// leaving that range) must not touch below the loaded TE, or the LTCA
/// would leave out a loaded pair: at 300 N·m its smallest slice lag stays
/// more than 100 µrad above the loaded TE, aligned and at the sensitivity
/// study's extremes of P and ΔΣ (measured about 170 µrad aligned). At
/// 700 N·m it does not (printed: 150–180 µrad below, corner contact),
/// a known limit (docs/misalignment.md).
#[test]
fn tooth_pairs_outside_the_aligned_roll_range_stay_clear_at_300_nm() {
    let f = Fixture::example_02();
    let tau = f.g.data.mesh_cycle();
    let cases = [
        Misalignment::default(),
        Misalignment::default().with(Component::PinionAxial, 0.05),
        Misalignment::default().with(Component::PinionAxial, -0.05),
        Misalignment::default().with(Component::ShaftAngle, 0.02),
        Misalignment::default().with(Component::ShaftAngle, -0.02),
    ];
    for m in cases {
        let mut g: PairGeometry = f.g.clone();
        g.misalign(&m);
        let fp = g.side(f.scene.scene.loaded_flank);
        let rs = roll_surface(fp, &f.scene.scene.utca).unwrap();
        let res = run(fp, &rs, &f.pc, &f.sweep, &TORQUES).unwrap();
        let mut clear = [f64::INFINITY; 3];
        for (k, p) in res.iter().enumerate() {
            let phi = f.sweep.start + f.sweep.direction * f.sweep.step * k as f64;
            let inside = geometry::pair::pairs_in_contact(phi, fp.roll_range, tau);
            for j in [inside[0] - 1, inside[inside.len() - 1] + 1] {
                let Some(ps) =
                    solver::element::slices::pair_slices(fp, &rs, phi, tau, j, f.sweep.slices)
                else {
                    continue;
                };
                let lag = ps
                    .slices
                    .iter()
                    .map(|s| s.lag)
                    .fold(f64::INFINITY, f64::min);
                for (c, l) in clear.iter_mut().zip(&p.loads) {
                    *c = c.min(lag - l.te);
                }
            }
        }
        println!(
            "{m:?}: the pairs outside the roll range touch {:.1} / {:.1} / {:.1} urad \
             above the loaded TE at {TORQUES:?} N·m",
            clear[0] * 1e6,
            clear[1] * 1e6,
            clear[2] * 1e6
        );
        assert!(
            clear[1] > 100e-6,
            "{m:?}: a pair outside the roll range touches {:.1} urad above the TE at 300 N·m",
            clear[1] * 1e6
        );
    }
}
