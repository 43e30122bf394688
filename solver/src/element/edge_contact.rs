//! Edge contact: whether a loaded slice's contact reaches an edge of the
//! active flank, so that a load beyond it is reported rather than
//! extrapolated from a model that assumes the contact lies inside the flank.
//!
//! A loaded slice's contact patch is taken as its band of the pinion's face
//! width [ξ_a, ξ_b] and, along the profile, its Hertz half-width b on either
//! side of the contact point. The band reaches the toe (heel) when it is
//! cut at ξ = 0 (ξ = 1), the face's end. Along the profile, the distance
//! from the contact point to the tip is taken as (1 − η) |∂r/∂η| and to
//! the root-fillet limit as η |∂r/∂η| (|∂r/∂η| the flank's profile length
//! per unit normalised profile parameter at the contact point, by central
//! differences); the contact reaches the edge when b exceeds that distance,
//! on the pinion's flank (its η) or on the wheel's (the mate's η).
//!
//! A slice whose contact point lies on the profile's end is the end of the
//! contact line, cut there by the active region (see [`crate::element::slices`]):
//! loaded, its patch reaches that edge by its whole half-width. That is
//! edge contact as much as a patch growing past the edge from inside: the
//! loaded contact line is truncated by the flank's boundary.

use crate::element::slices::Slice;
use formats::summaries::Edge;
use geometry::flank::Flank;
use geometry::pair::FlankPair;
use serde::Serialize;

/// Step in η of the profile-length difference.
const PROFILE_STEP: f64 = 1e-3;

/// A band end within this of the face's end (in ξ) is cut there.
const FACE_END: f64 = 1e-12;

/// One slice's contact reaching an edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EdgeHit {
    pub edge: Edge,
    pub pair: i32,
    /// How far the patch reaches past the edge, m (≥ 0).
    pub overshoot_m: f64,
}

/// Profile length per unit η of `flank` at (ξ, η), m; None where the flank
/// cannot be evaluated on both sides.
pub fn profile_length_per_eta(flank: &Flank, xi: f64, eta: f64) -> Option<f64> {
    let lo = (eta - PROFILE_STEP).max(0.0);
    let hi = (eta + PROFILE_STEP).min(1.0);
    let a = flank.at_unit(xi, lo).ok()?.pos;
    let b = flank.at_unit(xi, hi).ok()?.pos;
    let d = (0..3).map(|i| (b[i] - a[i]).powi(2)).sum::<f64>().sqrt();
    Some(d / (hi - lo))
}

/// Overshoot (m) of a half-width `half_width` at profile parameter `eta`
/// past the tip and past the root-fillet limit, with `per_eta` the profile
/// length per unit η: (b − (1 − η) g, b − η g). Positive: past the edge.
pub fn profile_overshoot(eta: f64, half_width: f64, per_eta: f64) -> [f64; 2] {
    [
        half_width - (1.0 - eta) * per_eta,
        half_width - eta * per_eta,
    ]
}

/// The edges that one member's contact point at (ξ, η) with half-width
/// `half_width` reaches: (edge, overshoot m).
fn member_edges(
    flank: &Flank,
    xi: f64,
    eta: f64,
    half_width: f64,
    [tip, root]: [Edge; 2],
) -> Vec<(Edge, f64)> {
    // Far from both ends (the profile is tens of half-widths high): no
    // evaluation needed. The bound uses a profile length per η of at
    // least 1 mm, far below any gear this toolkit designs.
    if half_width < eta.min(1.0 - eta) * 1e-3 {
        return Vec::new();
    }
    let Some(g) = profile_length_per_eta(flank, xi.clamp(0.0, 1.0), eta.clamp(0.0, 1.0)) else {
        return Vec::new();
    };
    let [t, r] = profile_overshoot(eta, half_width, g);
    let mut v = Vec::new();
    if t >= 0.0 {
        v.push((tip, t));
    }
    if r >= 0.0 {
        v.push((root, r));
    }
    v
}

/// The edges that the loaded `slice` (normal force > 0, Hertz half-width
/// `half_width` m) reaches, with their overshoots.
pub fn slice_edges(fp: &FlankPair, slice: &Slice, half_width: f64) -> Vec<EdgeHit> {
    let mut hits = Vec::new();
    let mut push = |edge, overshoot_m| {
        hits.push(EdgeHit {
            edge,
            pair: slice.pair,
            overshoot_m,
        })
    };
    if slice.band[0] <= FACE_END {
        push(Edge::Toe, 0.0);
    }
    if slice.band[1] >= 1.0 - FACE_END {
        push(Edge::Heel, 0.0);
    }
    for (e, o) in member_edges(
        &fp.pinion,
        slice.xi,
        slice.eta,
        half_width,
        [Edge::PinionTip, Edge::PinionRootFillet],
    ) {
        push(e, o);
    }
    let [xw, ew] = slice.wheel_xi_eta;
    for (e, o) in member_edges(
        &fp.wheel,
        xw,
        ew,
        half_width,
        [Edge::WheelTip, Edge::WheelRootFillet],
    ) {
        push(e, o);
    }
    hits
}

/// The edge hit with the largest overshoot over a position's loaded slices
/// (`force` N and `half_width` m per slice, in `slices`' order); None
/// where every loaded slice's contact stays inside the flanks.
pub fn position_edge(
    fp: &FlankPair,
    slices: &[Slice],
    force: &[f64],
    half_width: &[f64],
) -> Option<EdgeHit> {
    slices
        .iter()
        .zip(force)
        .zip(half_width)
        .filter(|((_, &f), _)| f > 0.0)
        .flat_map(|((s, _), &b)| slice_edges(fp, s, b))
        .max_by(|a, b| a.overshoot_m.total_cmp(&b.overshoot_m))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn profile_overshoot_is_the_half_width_past_each_end() {
        // η = 0.9 on a profile of 10 mm per unit η: 1 mm to the tip, 9 mm
        // to the fillet limit.
        let [tip, root] = profile_overshoot(0.9, 1.2e-3, 10e-3);
        assert!((tip - 0.2e-3).abs() < 1e-15, "{tip}");
        assert!((root - (1.2e-3 - 9e-3)).abs() < 1e-15, "{root}");
        let [tip, _] = profile_overshoot(0.9, 0.8e-3, 10e-3);
        assert!(tip < 0.0);
    }
}
