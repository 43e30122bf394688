use super::*;
use geometry::design_file::load_pair;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::utca::LineGrid;

/// The white-paper pair as designed (`reference/white_paper_20x43.toml`).
fn white_paper() -> PairGeometry {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../reference/white_paper_20x43.toml"
    );
    PairGeometry::new(&load_pair(std::path::Path::new(path)).unwrap()).unwrap()
}

/// The column search is a local method started from the tabulated
/// surface of roll angles. Started instead from η = 0, 0.1, …, 1 on the
/// same column, it must never find a smaller lag than from its own start
/// (white-paper pair, drive flanks, one mesh cycle in 24 positions, five
/// tooth pairs, 31 columns; lags up to 2.5 mrad, which covers every
/// contact up to 700 N·m). Until the search went on past the node-based
/// interval's end to the active region's boundary, it missed minima just
/// inside the wheel's tip edge by up to 6 µrad.
#[test]
fn column_minimum_does_not_depend_on_the_newton_start() {
    let g = white_paper();
    let fp = g.side(Side::Drive);
    let grid = LineGrid {
        n_face: 41,
        n_profile: 41,
    };
    let rs = RollSurface::new(fp, grid).unwrap();
    let tau = g.data.mesh_cycle();
    let mut worst = (0.0f64, String::new());
    let mut columns = 0;
    for ip in 0..24 {
        let phi = fp.roll_range[0] + ip as f64 * tau / 24.0;
        for pair in -2..=2 {
            let target = phi + pair as f64 * tau;
            for ic in 0..=30 {
                let xi = ic as f64 / 30.0;
                let column = || Column::new(fp, &rs, target, xi);
                let Some(own) = tabulated_minimum(&rs, xi, target) else {
                    continue;
                };
                let own = column().minimum(own).expect("active column has a minimum");
                columns += 1;
                for k in 0..=10 {
                    let Some(other) = column().minimum(k as f64 / 10.0) else {
                        continue;
                    };
                    let gain = own.lag - other.lag;
                    if other.lag < 2.5e-3 && gain > worst.0 {
                        worst = (
                            gain,
                            format!(
                                "position {ip}, pair {pair}, ξ {xi:.3}: η {:.6} lag {:.4e} \
                                 from its own start, η {:.6} lag {:.4e} from {:.1}",
                                own.eta,
                                own.lag,
                                other.eta,
                                other.lag,
                                k as f64 / 10.0
                            ),
                        );
                    }
                }
            }
        }
    }
    assert!(columns > 1000, "{columns} active columns");
    assert!(
        worst.0 < 1e-6,
        "another start finds {:.3e} rad less: {}",
        worst.0,
        worst.1
    );
}

/// Tip edges of the white-paper pair's slices over one mesh cycle: a slice
/// whose contact point is the pinion's tip (η = 1, the end of its column)
/// is cut there (distance 0, gap slope ≥ 0); a slice near a tip is cut at
/// a distance no larger than its distance along the profile to the
/// pinion's tip, (1 − η) |∂r/∂η| (the component across the contact line is
/// smaller); a slice far from both tips has no cut.
#[test]
fn slices_on_or_near_a_tip_edge_carry_their_cut() {
    let g = white_paper();
    let fp = g.side(Side::Drive);
    let rs = RollSurface::new(
        fp,
        LineGrid {
            n_face: 41,
            n_profile: 41,
        },
    )
    .unwrap();
    let tau = g.data.mesh_cycle();
    let (mut on_tip, mut near, mut far, mut face_end) = (0, 0, 0, 0);
    for ip in 0..12 {
        let phi = fp.roll_range[0] + ip as f64 * tau / 12.0;
        for pair in -1..=1 {
            let Some(ps) = pair_slices(fp, &rs, phi, tau, pair, 30) else {
                continue;
            };
            for s in &ps.slices {
                let [_, ew] = s.wheel_xi_eta;
                match s.edge {
                    Some(c) if s.eta >= 1.0 - 1e-9 => {
                        assert_eq!(c.distance_m, 0.0, "{s:?}");
                        assert!(c.slope >= 0.0, "{s:?}");
                        on_tip += 1;
                    }
                    Some(c) if s.eta > TIP_ZONE && ew <= TIP_ZONE => {
                        let per_eta = crate::element::edge_contact::profile_length_per_eta(
                            &fp.pinion, s.xi, s.eta,
                        )
                        .unwrap();
                        assert!(
                            c.distance_m <= (1.0 - s.eta) * per_eta * (1.0 + 1e-3),
                            "{c:?} {s:?}"
                        );
                        assert!(c.distance_m > 0.0);
                        near += 1;
                    }
                    Some(_) => {}
                    // Contact on the wheel's toe or heel edge (the end of
                    // its column's active part there): no tip cut.
                    None if s.wheel_xi_eta[0].min(1.0 - s.wheel_xi_eta[0]) < 1e-6 => {
                        face_end += 1;
                    }
                    None => {
                        assert!(s.eta <= TIP_ZONE && ew <= TIP_ZONE, "{s:?}");
                        far += 1;
                    }
                }
            }
        }
    }
    assert!(
        on_tip > 0 && near > 0 && far > 0 && face_end > 0,
        "{on_tip} {near} {far} {face_end}"
    );
}

/// Brute force over the white-paper pair's slices (one mesh cycle in 24
/// positions, five tooth pairs, 30 bands): no point of a slice's column,
/// sampled every 0.0025 in η with the wheel's bounds checked exactly at
/// each, has a smaller lag than the slice's contact point. The columns
/// next to the heel lie between a node column of the surface of roll
/// angles and the last one, whose wheel mates lie a hair beyond the wheel's
/// heel on the upper half of the profile; until a row with one active node
/// counted, the search there stopped where the last node column's activity
/// ended, below the contact line, and those slices touched late or not at
/// all: the contact line ended one node spacing short of the heel.
#[test]
fn every_slice_touches_at_its_columns_least_lag() {
    let g = white_paper();
    let fp = g.side(Side::Drive);
    let rs = RollSurface::new(fp, LineGrid::default()).unwrap();
    let tau = g.data.mesh_cycle();
    let (mut checked, mut heel) = (0, 0);
    let mut worst = (0.0f64, String::new());
    for ip in 0..24 {
        let phi = fp.roll_range[0] + ip as f64 * tau / 24.0;
        for pair in -2..=2 {
            let Some(ps) = pair_slices(fp, &rs, phi, tau, pair, 30) else {
                continue;
            };
            let target = phi + pair as f64 * tau;
            for s in &ps.slices {
                // A fresh column checks the wheel's bounds at every point.
                let col = column::Column::new(fp, &rs, target, s.xi);
                let (lag, eta) = (0..=400)
                    .map(|j| (col.value(j as f64 / 400.0), j as f64 / 400.0))
                    .min_by(|a, b| a.0.total_cmp(&b.0))
                    .unwrap();
                checked += 1;
                heel += usize::from(s.xi > 0.975);
                if s.lag - lag > worst.0 {
                    worst = (
                        s.lag - lag,
                        format!(
                            "position {ip}, pair {pair}, ξ {:.4}: slice η {:.4} lag {:.4e}, \
                             sampled η {eta:.4} lag {lag:.4e}",
                            s.xi, s.eta, s.lag
                        ),
                    );
                }
            }
        }
    }
    assert!(
        checked > 1000 && heel > 10,
        "{checked} slices, {heel} by the heel"
    );
    assert!(worst.0 < 1e-9, "{:.3e} rad: {}", worst.0, worst.1);
}
