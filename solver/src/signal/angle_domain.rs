//! Two runs compared in the pinion's angle domain: both sampled at the
//! same pinion rotations (the white paper's synchronization of its 10 and
//! 1,000 rpm run-ups), and how far the dynamic TE departs from the
//! quasi-static one.

use crate::ltca::mean_ptp;
use crate::multibody::model::interpolate;

/// `n + 1` pinion rotations evenly spaced over [0, `end`], rad.
pub fn grid(end: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|k| end * k as f64 / n as f64).collect()
}

/// A run's signal `y` over its pinion rotation `q1` (increasing), linearly
/// interpolated at the rotations `at`.
pub fn sample(q1: &[f64], y: &[f64], at: &[f64]) -> Vec<f64> {
    at.iter().map(|&a| interpolate(q1, y, a)).collect()
}

/// How a dynamic TE departs from the quasi-static one at the same
/// rotations, d(φ) = DTE(φ) − STE(φ) (units of the inputs; rotations in
/// rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Departure {
    /// Mean of d while the pinion accelerates, φ ≤ φₐ.
    pub mean_during_acceleration: f64,
    /// The largest |d| after the acceleration ends (signed) and where, φ > φₐ.
    pub largest_after_acceleration: f64,
    pub largest_after_acceleration_at: f64,
    /// Peak-to-peak of d over the last whole mesh cycle of the grid: what
    /// is left of the transient at the end of the comparison.
    pub last_cycle_ptp: f64,
}

/// The departure of `dte` from `ste` on `grid` (rotations, increasing,
/// from 0), the acceleration ending at `acceleration_end` and the mesh
/// cycle `mesh_cycle` (rad). None when the grid holds no point after the
/// acceleration or is shorter than a mesh cycle past it.
pub fn departure(
    grid: &[f64],
    ste: &[f64],
    dte: &[f64],
    acceleration_end: f64,
    mesh_cycle: f64,
) -> Option<Departure> {
    let end = *grid.last()?;
    if end - mesh_cycle < acceleration_end {
        return None;
    }
    let d: Vec<f64> = dte.iter().zip(ste).map(|(a, b)| a - b).collect();
    let during: Vec<f64> = grid
        .iter()
        .zip(&d)
        .filter(|(p, _)| **p <= acceleration_end)
        .map(|(_, v)| *v)
        .collect();
    let (k, largest) = grid
        .iter()
        .zip(&d)
        .enumerate()
        .filter(|(_, (p, _))| **p > acceleration_end)
        .map(|(k, (_, v))| (k, *v))
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
    let last: Vec<f64> = grid
        .iter()
        .zip(&d)
        .filter(|(p, _)| **p >= end - mesh_cycle)
        .map(|(_, v)| *v)
        .collect();
    Some(Departure {
        mean_during_acceleration: mean_ptp(&during).0,
        largest_after_acceleration: largest,
        largest_after_acceleration_at: grid[k],
        last_cycle_ptp: mean_ptp(&last).1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sampling_two_time_scaled_runs_at_the_same_rotations_gives_the_same_signal() {
        // A signal of the rotation alone, recorded by a run 100 times
        // slower on a different (uneven) time grid, is the same function
        // of the rotation: the angle domain removes the time scale.
        let f = |q: f64| (20.0 * q).sin() + 0.3 * q;
        let fast: Vec<f64> = (0..=4000)
            .map(|k| 0.5 * (k as f64 * 1e-3).powi(2))
            .collect();
        let slow: Vec<f64> = (0..=3000)
            .map(|k| 8.0 * (k as f64 / 3000.0).powf(1.3))
            .collect();
        let at = grid(2.0 * PI, 720);
        let a = sample(&fast, &fast.iter().map(|&q| f(q)).collect::<Vec<_>>(), &at);
        let b = sample(&slow, &slow.iter().map(|&q| f(q)).collect::<Vec<_>>(), &at);
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 2e-3, "{x} {y}");
        }
    }

    #[test]
    fn a_decaying_oscillation_after_the_acceleration_is_located_where_it_starts() {
        // d = offset during the acceleration, then e^{-(φ-φa)/w} sin(...)
        // peaking just after φa: the largest departure lies within a
        // quarter period past φa and the last cycle holds only its tail.
        let (pa, tau) = (30f64.to_radians(), 2.0 * PI / 20.0);
        let at = grid(2.0 * PI, 7200);
        let ste: Vec<f64> = at.iter().map(|p| (20.0 * p).cos()).collect();
        let period = 0.05;
        let dte: Vec<f64> = at
            .iter()
            .zip(&ste)
            .map(|(&p, s)| {
                s + if p <= pa {
                    5.0
                } else {
                    5.0 * (-(p - pa) / 0.1).exp() * (2.0 * PI * (p - pa) / period + PI / 2.0).sin()
                }
            })
            .collect();
        let d = departure(&at, &ste, &dte, pa, tau).unwrap();
        assert!((d.mean_during_acceleration - 5.0).abs() < 1e-12);
        assert!(d.largest_after_acceleration_at > pa);
        assert!(d.largest_after_acceleration_at - pa < period / 4.0);
        // The first sample after φa lies up to a grid step (0.87 mrad)
        // past it: 1.5 % of the period and of the decay length there.
        assert!((d.largest_after_acceleration - 5.0).abs() < 0.1, "{d:?}");
        assert!(d.last_cycle_ptp < 1e-10, "{d:?}");
    }

    #[test]
    fn equal_signals_do_not_depart() {
        let at = grid(2.0 * PI, 360);
        let y: Vec<f64> = at.iter().map(|p| p.sin()).collect();
        let d = departure(&at, &y, &y, 0.5, 0.3).unwrap();
        assert_eq!(d.largest_after_acceleration, 0.0);
        assert_eq!(d.last_cycle_ptp, 0.0);
    }

    #[test]
    fn a_grid_ending_within_a_mesh_cycle_of_the_acceleration_has_no_departure() {
        let at = grid(1.0, 100);
        let y = vec![0.0; 101];
        assert!(departure(&at, &y, &y, 0.8, 0.3).is_none());
    }
}
