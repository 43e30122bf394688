//! Seed 004's TE slope as an ease-off variant (`solver::stage::lumped::varied`
//! on seed 004's 23/86 design, no meshes needed): m′₂₁ sets the parabolic
//! motion error A = ½|m′₂₁|(τ/2)² (wheel side, at ±half a mesh cycle
//! τ = 2π/23), and the unloaded TE of our UTCA grows with the difference
//! of the A's between m′₂₁ = −0.001 and −0.010: its peak-to-peak rises by
//! 0.8–1.05 ΔA. Why not exactly ΔA: the UTCA samples every 0.5° of a
//! 15.65° cycle, so the cusp at the tooth change can fall up to a quarter
//! step from a sample, losing up to 1 − (1 − 0.5/15.65)² = 6 % of A; and
//! the crowning's own TE moves the extremes away from mid-cycle and ±τ/2.
//! A wrong mapping (τ for τ/2, or without the ½) would give 4 or 2 times.
//! Measured: 0.886. Crownings given by a variant replace the design's;
//! those not given are kept.

use geometry::pair::PairGeometry;
use geometry::scene::Scene;
use geometry::scene_lumped::DesignVariant;
use geometry::utca::{roll_surface, sweep};
use solver::stage::lumped::varied;
use std::path::Path;

#[test]
fn te_slope_variant_sets_the_motion_error_and_the_unloaded_te_follows() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference/scenes/seed004_lumped.toml");
    let scene = Scene::load(&path).unwrap();
    let tau = 2.0 * std::f64::consts::PI / 23.0;
    let ptp = |m21: f64, crowning: Option<f64>| {
        let v = DesignVariant {
            name: "v".into(),
            te_slope_m21: Some(m21),
            profile_crowning_um: None,
            lengthwise_crowning_um: crowning,
        };
        let (pair, used) = varied(&scene.pair, &v);
        let a = 0.5 * m21.abs() * (0.5 * tau) * (0.5 * tau) * 1e6;
        assert!((used.motion_error_urad - a).abs() < 1e-9 * a, "{used:?}");
        assert_eq!(pair.ease_off.motion_error_urad, used.motion_error_urad);
        assert_eq!(
            used.profile_crowning_um,
            scene.pair.ease_off.profile_crowning_um
        );
        assert_eq!(
            used.lengthwise_crowning_um,
            crowning.unwrap_or(scene.pair.ease_off.lengthwise_crowning_um)
        );
        let g = PairGeometry::build(&pair, Some(&scene.design_path)).unwrap();
        let fp = g.side(scene.scene.loaded_flank);
        let rs = roll_surface(fp, &scene.scene.utca).unwrap();
        (
            sweep(fp, &g.data, &rs, &scene.scene.utca).te_ptp(),
            a * 1e-6,
        )
    };
    let (p1, a1) = ptp(-0.001, None);
    let (p10, a10) = ptp(-0.010, None);
    let rise = (p10 - p1) / (a10 - a1);
    eprintln!(
        "unloaded TE ptp {:.2} → {:.2} µrad for A {:.2} → {:.2} µrad: rise / ΔA = {rise:.3}",
        p1 * 1e6,
        p10 * 1e6,
        a1 * 1e6,
        a10 * 1e6
    );
    assert!((0.8..=1.05).contains(&rise), "{rise}");
    ptp(-0.00001, Some(10.0));
}
