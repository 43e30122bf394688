//! Checks on the results of the scene
//! `reference/scenes/white_paper_lightweight_runup.toml` (every wheel tooth
//! of the lightweight wheel solved), run by `make lightweight` after the
//! scene's stages (its cold cost keeps it out of `make test`; ignored
//! there). They read `$LIGHTWEIGHT_OUT` (default `out/` of the workspace)
//! and fail when a file is missing.
//!
//! - The FE data repeat with the blank's 3-fold symmetry: the mean mesh
//!   stiffness of each mesh cycle over the solved revolution against the
//!   one 43/3 teeth on (an independent check of the 43 teeth's meshes and
//!   solves: nothing in them is copied from tooth to tooth).
//! - The 8-DOF model's lobe fitted to 5 mesh cycles (an 8-tooth stiffness
//!   file) against the lobe of the whole revolution: its phase agrees, its
//!   size does not (the finding is asserted, see the test).
//! - The multibody run-up shows the lightweight wheel's hole order
//!   3·20/43 above the standard wheel's (its side bands 20 ± 1.40 are
//!   not resolved above the windows' floor in this run-up: reported).

use formats::lumped_summary::OrderMapSummary;
use formats::summaries::RunupOrders;
use std::path::PathBuf;
use validate::report::sections::lightweight_revolution::RUNUP_SCENE;

fn out() -> PathBuf {
    std::env::var_os("LIGHTWEIGHT_OUT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../out"))
}

fn read<T: serde::de::DeserializeOwned>(rel: &str) -> T {
    let p = out().join(RUNUP_SCENE).join(rel);
    let t = std::fs::read_to_string(&p)
        .unwrap_or_else(|e| panic!("{}: {e} (run `make lightweight`)", p.display()));
    serde_json::from_str(&t).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn lightweight_map() -> OrderMapSummary {
    let maps: Vec<OrderMapSummary> = read("lumped/order_map.json");
    maps.into_iter()
        .find(|m| m.lobes > 0)
        .expect("order_map.json has no lightweight wheel")
}

/// Signed lobe-phase difference of two least-k teeth, teeth in (−L/2, L/2].
fn phase_teeth(a: f64, b: f64, lobe: f64) -> f64 {
    let d = (a - b).rem_euclid(lobe);
    if d > 0.5 * lobe {
        d - lobe
    } else {
        d
    }
}

#[test]
#[ignore = "needs the white_paper_lightweight_runup scene's results (make lightweight)"]
fn solved_revolution_mean_stiffness_repeats_every_third_of_the_wheel() {
    let m = lightweight_map();
    assert_eq!(
        m.wheel_solved_teeth.len(),
        m.wheel_teeth,
        "not every tooth solved"
    );
    assert_eq!(m.excitation, "solved revolution");
    let [max, rms] = m.lobe_repeat_mismatch_of_mean.expect("no repeat check");
    let ptp = m.stiffness_lobe_ptp_relative;
    // The 3-fold repeat holds to a fraction of the lobe itself: what is
    // left is mesh noise from tooth to tooth (every tooth meshed on its
    // own) and the linear interpolation over 1/3 tooth.
    assert!(
        rms < 0.25 * ptp && max < 0.5 * ptp,
        "repeat mismatch max {max:.4}, rms {rms:.4} of mean k; lobe ptp {ptp:.4}"
    );
}

#[test]
#[ignore = "needs the white_paper_lightweight_runup scene's results (make lightweight)"]
fn lobe_fitted_to_five_mesh_cycles_has_the_solved_revolutions_phase_but_not_its_size() {
    let m = lightweight_map();
    let lobe = m.wheel_teeth as f64 / m.lobes as f64;
    let short = m.short_span_lobe.as_ref().expect("no short-span lobe");
    let (a, b) = (
        m.stiffness_lobe_minimum_wheel_tooth.unwrap(),
        short.stiffness_lobe_minimum_wheel_tooth.unwrap(),
    );
    let dphase = phase_teeth(b, a, lobe);
    let ratio = short.stiffness_lobe_ptp_relative / m.stiffness_lobe_ptp_relative;
    eprintln!(
        "lobe ptp: revolution {:.4}, 5 cycles {:.4} (ratio {ratio:.3}); least k at tooth {a:.2} and {b:.2} (phase {dphase:+.2} teeth of {lobe:.2}); holes at {:?}",
        m.stiffness_lobe_ptp_relative, short.stiffness_lobe_ptp_relative, m.hole_wheel_teeth
    );
    // Phase within 1.5 teeth (38° of lobe phase).
    assert!(dphase.abs() < 1.5, "phase {dphase:+.2} teeth");
    // Size: the bound set before the whole revolution was solved (within
    // 35 %) failed, measured 2026-11-24: the 5 cycles lie on the steep
    // side of the per-tooth stiffness (a sharp dip past each hole and a
    // slow rise: not one harmonic), and their fit is 1.6 times the
    // revolution's first harmonic. What this asserts is that finding: the
    // short span's lobe is too large by more than a quarter, so the
    // extrapolated order map overstates the hole family; the solved
    // revolution replaces it where every tooth is solved.
    assert!(
        ratio > 1.25,
        "size ratio {ratio:.3}: the short span's lobe is no longer too large"
    );
}

#[test]
#[ignore = "needs the white_paper_lightweight_runup scene's results (make lightweight)"]
fn runup_hole_order_of_the_lightweight_wheel_stands_above_the_standard_wheels() {
    let light: RunupOrders = read("multibody/standard_lightweight/runup_orders.json");
    let std: RunupOrders = read("multibody/standard_standard/runup_orders.json");
    assert_eq!(light.windows.len(), std.windows.len());
    let line = |w: &formats::summaries::RunupOrderWindow, label: &str| {
        w.marked
            .iter()
            .find(|x| x.label == label)
            .map(|x| x.wheel_bearing_force_n)
            .expect("marked order missing")
    };
    for (l, s) in light.windows.iter().zip(&std.windows) {
        let (hl, hs) = (line(l, "3·20/43"), line(s, "3·20/43"));
        let band = |w| line(w, "20-1.40") + line(w, "20+1.40");
        eprintln!(
            "{:.0} rpm: hole order lightweight {hl:.3e} N, standard {hs:.3e} N; side bands 20 ± 1.40 lightweight {:.3e} N, standard {:.3e} N",
            l.mean_pinion_rpm,
            band(l),
            band(s)
        );
        // Chosen after the first run (measured 2026-11-24: 3.7 to 46 times
        // over the windows): the hole order 3·20/43 at least 3 times the
        // standard wheel's in every window. The side bands 20 ± 1.40 are
        // not asserted: in this run-up they stand only 0.9 to 1.9 times
        // above the standard wheel's lines there, the floor of the
        // windows (content not locked to the orders, such as the
        // torsional mode's response while the ramp sweeps towards it).
        assert!(
            hl > 3.0 * hs,
            "{:.0} rpm: hole order lightweight {hl:.3e} N, standard {hs:.3e} N",
            l.mean_pinion_rpm
        );
    }
}
