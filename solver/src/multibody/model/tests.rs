use super::*;

#[test]
fn speed_ramp_integrates_to_its_angle() {
    let r = Ramp {
        from: 1.0,
        to: 5.0,
        duration: 2.0,
    };
    // ∫₀² (1 + 2t) dt = 6, then 5 rad/s.
    assert!((r.at(2.0)[0] - 6.0).abs() < 1e-14);
    assert!((r.at(3.0)[0] - 11.0).abs() < 1e-14);
    assert_eq!(r.at(1.0)[2], 2.0);
    assert_eq!(r.at(2.5)[1], 5.0);
}

#[test]
fn fluctuating_speed_is_the_derivative_of_its_angle() {
    let f = Fluctuation {
        mean: 30.0,
        amplitude: 0.05,
        omega: 2.0 * std::f64::consts::PI * 25.0,
    };
    assert_eq!(f.at(0.0)[0], 0.0);
    // One period: the mean speed times the period.
    let period = 2.0 * std::f64::consts::PI / f.omega;
    assert!((f.at(period)[0] - 30.0 * period).abs() < 1e-12);
    for t in [0.003, 0.011, 0.027] {
        let h = 1e-6;
        let [a0, w, acc] = f.at(t);
        let (ap, am) = (f.at(t + h), f.at(t - h));
        assert!(((ap[0] - am[0]) / (2.0 * h) - w).abs() < 1e-6 * w);
        assert!(((ap[1] - am[1]) / (2.0 * h) - acc).abs() < 1e-6 * (w * 0.05 * f.omega));
        assert!(a0 > 0.0);
    }
}

#[test]
fn smoothstep_is_c1() {
    assert_eq!(smoothstep(-1.0), (0.0, 0.0));
    assert_eq!(smoothstep(2.0), (1.0, 0.0));
    assert!((smoothstep(0.5).0 - 0.5).abs() < 1e-15);
}

/// A contact whose drive and coast pairs are `u` = (drive, coast) into
/// contact, with combined pinion torque `t1`.
fn contact(u: [f64; 2], t1: f64) -> Contact {
    let state = |u: f64, t: f64| crate::multibody::mesh_table::MeshState {
        theta: 0.0,
        u,
        potential: 0.0,
        grad: [t, 0.0],
        hess: [[0.0; 2]; 2],
        force: [0.0; 3],
    };
    Contact {
        force: [0.0; 2],
        stiffness: [[0.0; 2]; 2],
        damping: [[0.0; 2]; 2],
        mesh: state(u[0], t1),
        coast: Some(state(u[1], 0.0)),
    }
}

#[test]
fn both_flank_pairs_into_contact_is_wedging_whatever_the_net_torque() {
    for t1 in [-50.0, 0.0, 50.0] {
        assert_eq!(contact([1e-7, 2e-7], t1).touching(), Touching::Both);
    }
    assert_eq!(contact([1e-7, -1e-6], 50.0).touching(), Touching::Drive);
    assert_eq!(contact([-1e-6, 1e-7], -50.0).touching(), Touching::Coast);
    assert_eq!(contact([-1e-6, -1e-6], 0.0).touching(), Touching::Neither);
}

#[test]
fn impacts_count_each_contact_begun_and_each_wedging_episode_once() {
    let mut i = Impacts::default();
    for t in [
        Touching::Drive,
        Touching::Drive,
        Touching::Neither,
        Touching::Coast,
        Touching::Both,
        Touching::Both,
        Touching::Coast,
        Touching::Drive,
    ] {
        i.record(t);
    }
    assert_eq!((i.drive, i.coast, i.wedged), (2, 2, 1));
}
