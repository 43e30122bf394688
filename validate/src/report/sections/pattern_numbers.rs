//! The contact pattern (the white paper's Figure 12) compared as numbers,
//! one definition for both models: the overlap of the two pressure
//! footprints (intersection over union on a common grid of the flank), the
//! largest pressure away from the flank's edges, and which edges each
//! model's contact reaches.
//!
//! Our choices (not from a seed): the grid is the reduced model's pattern
//! grid ([`PATTERN_CELLS_SLICES`]); a cell is in a footprint where the
//! model's envelope reaches [`FOOTPRINT_FRACTION`] of the larger of the two
//! interior peaks; "interior" is farther than [`EDGE_BAND`] from every edge
//! of the unit flank; a model's contact reaches an edge where a point with
//! at least [`FLAG_FRACTION`] of its own interior peak lies within
//! [`EDGE_FLAG_BAND`] of it. The interior peaks are judged against
//! [`PEAK_TARGET_PCT`].

use super::loaded_contact::{PatternPoint, PATTERN_CELLS_SLICES};
use serde::Serialize;
use std::fmt::Write as _;

/// Distance from the flank's edges (unit flank) beyond which a point is
/// interior.
pub const EDGE_BAND: f64 = 0.05;
/// Distance from an edge within which a loaded point flags that edge.
pub const EDGE_FLAG_BAND: f64 = 0.02;
/// Footprint threshold, fraction of the larger interior peak.
pub const FOOTPRINT_FRACTION: f64 = 0.05;
/// Edge-flag threshold, fraction of the model's own interior peak.
pub const FLAG_FRACTION: f64 = 0.10;
/// The interior peaks should agree within this, %.
pub const PEAK_TARGET_PCT: f64 = 10.0;

/// The pattern numbers of one blank pair and torque.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PatternNumbers {
    /// Intersection over union of the footprints.
    pub iou: f64,
    /// Interior peak pressure, MPa: [reduced, reference].
    pub interior_peak_mpa: [f64; 2],
    /// Reduced against reference, %.
    pub interior_peak_difference_pct: f64,
    /// Edges each model's contact reaches: [reduced, reference].
    pub edges: [Vec<&'static str>; 2],
    /// Largest pressure anywhere, edges included, MPa: [reduced, reference].
    pub overall_peak_mpa: [f64; 2],
}

/// Largest pressure farther than [`EDGE_BAND`] from every edge (0 when none).
pub fn interior_peak(pts: &[PatternPoint]) -> f64 {
    pts.iter()
        .filter(|&&(x, y, _)| x.min(1.0 - x) > EDGE_BAND && y.min(1.0 - y) > EDGE_BAND)
        .map(|p| p.2)
        .fold(0.0, f64::max)
}

/// Cells of a `cells` grid over the unit flank whose largest pressure
/// reaches `threshold`, row-major in (η, ξ).
pub fn footprint(pts: &[PatternPoint], threshold: f64, cells: [usize; 2]) -> Vec<bool> {
    let [nx, ny] = cells;
    let mut on = vec![false; nx * ny];
    for &(x, y, p) in pts {
        if p < threshold || !(0.0..=1.0).contains(&x) || !(0.0..=1.0).contains(&y) {
            continue;
        }
        let i = ((x * nx as f64) as usize).min(nx - 1);
        let j = ((y * ny as f64) as usize).min(ny - 1);
        on[j * nx + i] = true;
    }
    on
}

/// |A ∩ B| / |A ∪ B| of two footprints (0 when both are empty).
pub fn iou(a: &[bool], b: &[bool]) -> f64 {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let any = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    if any == 0 {
        0.0
    } else {
        both as f64 / any as f64
    }
}

/// The edges (toe ξ = 0, heel ξ = 1, root η = 0, tip η = 1) that a point
/// with at least [`FLAG_FRACTION`] of `peak` lies within [`EDGE_FLAG_BAND`] of.
pub fn edges_reached(pts: &[PatternPoint], peak: f64) -> Vec<&'static str> {
    let loaded: Vec<&PatternPoint> = pts.iter().filter(|p| p.2 >= FLAG_FRACTION * peak).collect();
    let near = |f: &dyn Fn(&PatternPoint) -> f64| loaded.iter().any(|p| f(p) <= EDGE_FLAG_BAND);
    let mut e = Vec::new();
    if near(&|p| p.0) {
        e.push("toe");
    }
    if near(&|p| 1.0 - p.0) {
        e.push("heel");
    }
    if near(&|p| p.1) {
        e.push("root");
    }
    if near(&|p| 1.0 - p.1) {
        e.push("tip");
    }
    e
}

/// The numbers of `reduced` against `reference` (None when either has no
/// interior contact).
pub fn numbers(reduced: &[PatternPoint], reference: &[PatternPoint]) -> Option<PatternNumbers> {
    let (pa, pb) = (interior_peak(reduced), interior_peak(reference));
    if pa <= 0.0 || pb <= 0.0 {
        return None;
    }
    let threshold = FOOTPRINT_FRACTION * pa.max(pb);
    Some(PatternNumbers {
        iou: iou(
            &footprint(reduced, threshold, PATTERN_CELLS_SLICES),
            &footprint(reference, threshold, PATTERN_CELLS_SLICES),
        ),
        interior_peak_mpa: [pa, pb],
        interior_peak_difference_pct: (pa / pb - 1.0) * 100.0,
        edges: [edges_reached(reduced, pa), edges_reached(reference, pb)],
        overall_peak_mpa: [reduced, reference].map(|v| v.iter().map(|p| p.2).fold(0.0, f64::max)),
    })
}

/// The contact pressure table: per blank pair and load, both models'
/// largest pressure away from the edges (judged against
/// [`PEAK_TARGET_PCT`]) and anywhere, and the edges each model's contact
/// reaches; then how many loads meet the target and agree on the edges.
/// `rows`: (blank pair, load N·m, numbers).
pub fn table(rows: &[(String, f64, PatternNumbers)]) -> String {
    if rows.is_empty() {
        return String::new();
    }
    let list = |e: &[&str]| {
        if e.is_empty() {
            "none".to_string()
        } else {
            e.join(", ")
        }
    };
    let mut s = format!(
        "Contact pressure per blank pair and load (the pattern's definitions above: interior farther than {EDGE_BAND} of the unit flank from every edge; an edge is reached where a point with at least {:.0} % of the model's interior peak lies within {EDGE_FLAG_BAND} of it):\n\n| blank pair | load, N·m | interior p_max reduced, MPa | reference, MPa | diff % | largest anywhere reduced, MPa | reference, MPa | edges reached, reduced | reference | IoU |\n|---|---|---|---|---|---|---|---|---|---|\n",
        FLAG_FRACTION * 100.0
    );
    let mut within = 0;
    let mut same_edges = 0;
    for (blanks, t, n) in rows {
        let _ = writeln!(
            s,
            "| {blanks} | {t} | {:.0} | {:.0} | {:+.1} | {:.0} | {:.0} | {} | {} | {:.2} |",
            n.interior_peak_mpa[0],
            n.interior_peak_mpa[1],
            n.interior_peak_difference_pct,
            n.overall_peak_mpa[0],
            n.overall_peak_mpa[1],
            list(&n.edges[0]),
            list(&n.edges[1]),
            n.iou
        );
        within += usize::from(n.interior_peak_difference_pct.abs() <= PEAK_TARGET_PCT);
        same_edges += usize::from(n.edges[0] == n.edges[1]);
    }
    let _ = writeln!(
        s,
        "\nThe interior peaks agree within the {PEAK_TARGET_PCT:.0} % target at {within} of {} loads; the two models reach the same edges at {same_edges} of {}.\n",
        rows.len(),
        rows.len()
    );
    s
}

/// The numbers as a sentence with their verdicts.
pub fn sentence(blanks: &str, torque_nm: f64, n: &PatternNumbers) -> String {
    let list = |e: &[&str]| {
        if e.is_empty() {
            "none".to_string()
        } else {
            e.join(", ")
        }
    };
    format!(
        "Contact pattern {blanks} at {torque_nm} N·m as numbers: footprints (from {:.0} % of the larger interior peak) overlap with an intersection over union of {:.2}; the largest pressure away from the edges is {:.0} MPa in the reduced model and {:.0} MPa in the reference ({:+.1} %, {} the {PEAK_TARGET_PCT:.0} % target); edges the contact reaches: reduced model {}, reference {} ({}).",
        FOOTPRINT_FRACTION * 100.0,
        n.iou,
        n.interior_peak_mpa[0],
        n.interior_peak_mpa[1],
        n.interior_peak_difference_pct,
        if n.interior_peak_difference_pct.abs() <= PEAK_TARGET_PCT {
            "within"
        } else {
            "outside"
        },
        list(&n.edges[0]),
        list(&n.edges[1]),
        if n.edges[0] == n.edges[1] {
            "the same"
        } else {
            "not the same"
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A filled rectangle of points on a fine grid with pressure `p`.
    fn patch(x: [f64; 2], y: [f64; 2], p: f64) -> Vec<PatternPoint> {
        let mut v = Vec::new();
        for i in 0..=40 {
            for j in 0..=40 {
                v.push((
                    x[0] + (x[1] - x[0]) * i as f64 / 40.0,
                    y[0] + (y[1] - y[0]) * j as f64 / 40.0,
                    p,
                ));
            }
        }
        v
    }

    #[test]
    fn iou_of_equal_disjoint_and_half_shifted_footprints() {
        let a = [true, true, false, false];
        assert_eq!(iou(&a, &a), 1.0);
        assert_eq!(iou(&a, &[false, false, true, true]), 0.0);
        // Two cells each, one shared: 1 / 3.
        assert!((iou(&a, &[false, true, true, false]) - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(iou(&[false; 4], &[false; 4]), 0.0);
    }

    #[test]
    fn same_patch_overlaps_fully_and_agrees_on_peak_and_edges() {
        let a = patch([0.2, 0.6], [0.3, 0.7], 900.0);
        let n = numbers(&a, &a).unwrap();
        assert_eq!(n.iou, 1.0);
        assert_eq!(n.interior_peak_difference_pct, 0.0);
        assert!(n.edges[0].is_empty() && n.edges[1].is_empty());
        let s = sentence("standard / standard", 700.0, &n);
        assert!(
            s.contains("within the 10 % target") && s.contains("(the same)"),
            "{s}"
        );
    }

    #[test]
    fn a_tip_corner_peak_is_an_edge_not_the_interior_peak() {
        // Reference: the same interior patch plus a 2,000 MPa line at the tip.
        let reduced = patch([0.2, 0.6], [0.3, 0.95], 900.0);
        let mut reference = patch([0.2, 0.6], [0.3, 0.95], 700.0);
        reference.extend(patch([0.2, 0.6], [0.995, 1.0], 2000.0));
        let n = numbers(&reduced, &reference).unwrap();
        assert_eq!(n.interior_peak_mpa, [900.0, 700.0]);
        assert_eq!(n.edges[0], Vec::<&str>::new());
        assert_eq!(n.edges[1], vec!["tip"]);
        let s = sentence("standard / lightweight", 700.0, &n);
        assert!(
            s.contains("outside the 10 % target") && s.contains("(not the same)"),
            "{s}"
        );
    }

    #[test]
    fn half_overlapping_patches_give_an_iou_of_one_third() {
        // Patches of 10 × 4 grid cells each, shifted by half along ξ.
        let a = patch([0.2, 0.6 - 1e-9], [1.0 / 3.0, 2.0 / 3.0 - 1e-9], 500.0);
        let b = patch([0.4, 0.8 - 1e-9], [1.0 / 3.0, 2.0 / 3.0 - 1e-9], 500.0);
        let n = numbers(&a, &b).unwrap();
        assert!((n.iou - 1.0 / 3.0).abs() < 1e-12, "{}", n.iou);
    }

    /// The table's rows and its counts: a matching interior patch, and a
    /// reference with a tip-edge peak 20 % above the reduced model's
    /// interior one (outside the target, edges not the same).
    #[test]
    fn contact_pressure_table_counts_loads_within_the_target_and_same_edges() {
        let a = patch([0.3, 0.7], [0.3, 0.7], 1000.0);
        let mut b = patch([0.3, 0.7], [0.3, 0.7], 1200.0);
        b.push((0.5, 1.0, 2500.0));
        let same = numbers(&a, &a).unwrap();
        let edge = numbers(&a, &b).unwrap();
        assert_eq!(edge.overall_peak_mpa, [1000.0, 2500.0]);
        let t = table(&[
            ("standard_standard".into(), 300.0, same),
            ("standard_standard".into(), 700.0, edge),
        ]);
        assert!(
            t.contains(
                "| standard_standard | 700 | 1000 | 1200 | -16.7 | 1000 | 2500 | none | tip |"
            ),
            "{t}"
        );
        assert!(t.contains("within the 10 % target at 1 of 2 loads; the two models reach the same edges at 1 of 2."), "{t}");
        assert_eq!(table(&[]), "");
    }
}
