//! Seed 003's roughness grades as the pair's topography
//! (`solver::lumped::roughness::roughened`) on seed 003's 16/27 design (no
//! meshes needed): the grid of 41 profile nodes carries exactly the W–M
//! terms whose wavelength is at least two node spacings (counted here from
//! the W–M frequencies λ_c γ⁻ⁿ, γ = 1.5, λ_c = 0.8 mm), Rq of the carried
//! terms is √(Σ aₙ²/2) over them and below the whole profile's, the
//! composite Ra is √2 Ra, the topography at the nodes stays within
//! Σ|aₙ| of the carried terms and its RMS within 25 % of their Rq (41 nodes
//! over about 10–14 periods of the carried waves), and the rough pair
//! builds.

use geometry::pair::PairGeometry;
use geometry::roughness::WmProfile;
use geometry::scene::Scene;
use solver::lumped::roughness::roughened;
use std::path::Path;

#[test]
fn lumped_roughness_topography_carries_only_the_terms_its_grid_resolves() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../reference/scenes/seed003_lumped.toml");
    let scene = Scene::load(&path).unwrap();
    let g = PairGeometry::build(&scene.pair, Some(&scene.design_path)).unwrap();
    let fp = g.side(scene.scene.loaded_flank);
    for ra in [0.8, 0.4, 0.2] {
        let (pair, r) = roughened(&scene.pair, fp, ra, 3, [41, 5], 6).unwrap();
        let spacing = r.profile_length_m / 40.0;
        assert!((r.node_spacing_m - spacing).abs() < 1e-15);
        assert!((r.composite_ra_um - ra * std::f64::consts::SQRT_2).abs() < 1e-12);
        let wm = WmProfile::with_ra(
            *WmProfile::seed003(ra, 3).unwrap().spec(),
            r.composite_ra_um * 1e-6,
            3,
        )
        .unwrap();
        let carried: Vec<f64> = (0..)
            .map(|n| 0.8e-3 / 1.5f64.powi(n))
            .take_while(|l| *l >= 2.0 * spacing)
            .collect();
        assert_eq!(r.terms_resolved, carried.len(), "Ra {ra}");
        let amps = &wm.amplitudes_m()[..carried.len()];
        let rq = (amps.iter().map(|a| a * a).sum::<f64>() / 2.0).sqrt();
        assert!((r.rq_resolved_m - rq).abs() < 1e-15 && rq < r.rq_m);
        let topo = pair.ease_off.topography.as_ref().unwrap();
        let z: Vec<f64> = topo.deviation_um.iter().map(|row| row[0] * 1e-6).collect();
        let bound: f64 = amps.iter().sum();
        assert!(z.iter().all(|v| v.abs() <= bound * (1.0 + 1e-12)));
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        let rms = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64).sqrt();
        eprintln!(
            "Ra {ra}: {} of {} terms, Rq {:.3} of {:.3} µm, node RMS {:.3} µm, spacing {:.3} mm",
            r.terms_resolved,
            r.terms,
            1e6 * r.rq_resolved_m,
            1e6 * r.rq_m,
            1e6 * rms,
            1e3 * spacing
        );
        assert!(
            (rms / rq - 1.0).abs() < 0.25,
            "Ra {ra}: RMS {rms:e} against Rq {rq:e}"
        );
        PairGeometry::build(&pair, Some(&scene.design_path)).unwrap();
    }
}
