//! Seed 004's meshing impact from our LTCA: the entering tooth pair's first
//! loaded position from the load-sharing curve, its approach velocity and
//! its own tangent stiffness there, and the peak force
//! F_s = v_s √(k_s mₑ′) (see [`super::excitation::seed004_impact_force`]).
//!
//! Approach velocity: before it touches, the entering pair j has the gap
//! g = r₂(lag_j − θ) (lag_j its touching wheel lag from the unloaded
//! geometry, θ the loaded TE), closing at
//! v_s = Ω₁ r₂ |d(lag_j − θ)/dφ₁|, taken as the forward difference over the
//! first two positions with pair j loaded. Entering pair's stiffness:
//! k_s = (F_j(T(1+ε)) − F_j(T(1−ε))) / (r₂ (θ(T(1+ε)) − θ(T(1−ε)))).

use super::from_ltca::MeshSamples;
use crate::ltca::PositionResult;

/// The impact quantities; `None` where no pair enters inside the sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Engagement {
    /// Index of the first loaded position of the entering pair.
    pub position: usize,
    pub pair: i32,
    /// Pinion rotation from the sweep start, rad.
    pub rotation: f64,
    pub velocity_m_s: f64,
    pub pair_stiffness_n_per_m: f64,
}

fn pair_force(p: &PositionResult, load: usize, pair: i32) -> f64 {
    p.loads[load]
        .pair_force
        .iter()
        .find(|f| f.0 == pair)
        .map_or(0.0, |f| f.1)
}

/// Finds the entering pair (loaded at position k, not at k − 1) and its
/// impact quantities; `lag(position, pair)` is the pair's touching lag
/// (rad) at that position. `res` at the three tangent torques.
pub fn engagement(
    res: &[PositionResult],
    samples: &MeshSamples,
    pinion_speed_rad_s: f64,
    lag: impl Fn(usize, i32) -> Option<f64>,
) -> Option<Engagement> {
    let r2 = samples.levers_m[1];
    for k in 1..res.len().saturating_sub(1) {
        for &(pair, f) in &res[k].loads[1].pair_force {
            if f <= 0.0 || pair_force(&res[k - 1], 1, pair) > 0.0 {
                continue;
            }
            let (Some(l0), Some(l1)) = (lag(k, pair), lag(k + 1, pair)) else {
                continue;
            };
            let dphi = res[k + 1].rotation - res[k].rotation;
            let dgap = (l1 - res[k + 1].loads[1].te) - (l0 - res[k].loads[1].te);
            let dtheta = res[k].loads[2].te - res[k].loads[0].te;
            let df = pair_force(&res[k], 2, pair) - pair_force(&res[k], 0, pair);
            if !(dphi > 0.0 && dtheta > 0.0) {
                continue;
            }
            return Some(Engagement {
                position: k,
                pair,
                rotation: res[k].rotation,
                velocity_m_s: pinion_speed_rad_s * r2 * (dgap / dphi).abs(),
                pair_stiffness_n_per_m: (df / (r2 * dtheta)).max(0.0),
            });
        }
    }
    None
}
