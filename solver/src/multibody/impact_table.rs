//! The impact law ([`crate::multibody::impact_law`]) as the multibody's force element,
//! tabulated like the FE-analytical element ([`crate::multibody::mesh_table`]) so that
//! both laws see the same geometry and run through the same machinery.
//!
//! Geometry: at each table position the slices of every tooth pair in the
//! active range ([`crate::ltca::geometry`], from the surface of roll
//! angles). At wheel lag θ slice k of pair j overlaps its rigid mate by
//! λ₂ₖ (θ − lagₖ) along the contact normal (λ₂ the wheel's normal lever,
//! lagₖ the lag at which the slice touches). The pair's penetration is its
//! largest one, the rigid bodies' deepest point, as a general-purpose contact
//! detection reports it:
//!
//!   δⱼ(θ) = maxₖ λ₂ₖ (θ − lagₖ),   k*ⱼ the slice that attains it,
//!
//! and the pair carries F = K δⱼ^e along that slice's normal. Tabulated
//! per node (q₁, θ) like the element:
//! - pinion torque T₁ = Σⱼ λ₁ₖ* K δⱼ^e (the conservative part: the table's
//!   potential V, gradient and Hessian follow from it exactly as for the
//!   element);
//! - the contact force on the wheel Σⱼ K δⱼ^e nₖ* (output), the friction
//!   moments per unit μ, Φ = Σⱼ K δⱼ^e ℓₖ* (see [`crate::element::slices::friction_levers`]);
//! - the damping levers with wⱼ = STEP(δⱼ, 0, 0, d, 1): the damping
//!   C wⱼ δ̇ⱼ acts on the rigid bodies' normal approach speed at the deepest
//!   point, δ̇ⱼ = λ₁ q̇₁ − λ₂ q̇₂ = λ₂ θ̇ + (λ₁ − r λ₂) q̇₁ (the second term,
//!   zero for conjugate flanks, is the ease-off's approach as the pair
//!   rolls in), and pushes with the same levers, so that its power
//!   −C Σ wⱼ δ̇ⱼ² is never positive. Written with the small mismatch
//!   εⱼ = λ₁ − r λ₂ kept apart (interpolating λ₁² and λ₁ λ₂ separately would
//!   cancel to the interpolation error; on this project's generated flanks
//!   ε is zero to rounding, 1e-19 m² in E on the example-02 fixture, and is
//!   kept for flanks where it is not): A = (Σ w λ₁ λ₂, Σ w λ₂²) and
//!   E = (Σ w λ₁ ε, Σ w λ₂ ε), generalized damping forces
//!   −C (A₁ θ̇ + E₁ q̇₁) on q₁ and +C (A₂ θ̇ + E₂ q̇₁) on q₂;
//! - the force-weighted mean slip speed per unit pinion speed,
//!   ḡ = Σⱼ Fⱼ |gⱼ| / Σⱼ Fⱼ with |g| = ℓ₁ − r ℓ₂ (m/rad), at which the
//!   friction coefficient μ(ḡ |q̇₁|) is evaluated for the whole mesh.
//!
//! Simplifications, stated: the law's zero clamp acts on the mesh total
//! (the pinion torque of all pairs), not per pair; μ(v) is taken at the
//! force-weighted mean slip speed of the pairs, not per pair (per-pair
//! values would need the pairs tabulated separately).

use crate::ltca::{geometry, Geometry};
use crate::multibody::impact_law::{Friction, ImpactLaw};
use crate::multibody::mesh_table::{
    check_spec, columns_and_lags, Column, ImpactFields, MeshTable, TableSpec,
};
use crate::SolverError;
use geometry::generation::MemberFrame;
use geometry::pair::FlankPair;
use geometry::utca::RollSurface;
use rayon::prelude::*;

/// Per tooth pair at one lag: penetration, force and the attaining slice.
struct PairContact {
    delta: f64,
    force: f64,
    slice: usize,
}

/// The pairs' deepest slices at lag θ (pairs not touching are left out).
fn pairs_at(g: &Geometry, law: &ImpactLaw, theta: f64) -> Vec<PairContact> {
    let mut out: Vec<PairContact> = Vec::new();
    let mut current: Option<(i32, usize)> = None;
    for (k, s) in g.slices.iter().enumerate() {
        let d = s.lever_wheel * (theta - s.lag);
        match current {
            Some((pair, idx)) if pair == s.pair => {
                if d > out[idx].delta {
                    out[idx].delta = d;
                    out[idx].slice = k;
                }
            }
            _ => {
                current = Some((s.pair, out.len()));
                out.push(PairContact {
                    delta: d,
                    force: 0.0,
                    slice: k,
                });
            }
        }
    }
    out.retain(|p| p.delta > 0.0);
    for p in &mut out {
        p.force = law.elastic(p.delta).0;
    }
    out
}

/// Pinion torque of the law at lag θ at the position of `g`, N·m:
/// Σⱼ λ₁ₖ* K δⱼ^e (what the table holds at its nodes).
pub fn torque_at(g: &Geometry, law: &ImpactLaw, theta: f64) -> f64 {
    pairs_at(g, law, theta)
        .iter()
        .map(|p| g.slices[p.slice].lever_pinion * p.force)
        .sum()
}

/// Lag at which the law carries `torque` at the position of `g`
/// (bisection; the torque rises monotonically with θ), rad.
pub fn lag_for(g: &Geometry, law: &ImpactLaw, torque: f64) -> Result<f64, SolverError> {
    let lo0 = g.utca_te;
    let mut hi = lo0 + 1e-6;
    let mut n = 0;
    while torque_at(g, law, hi) < torque {
        hi = lo0 + 2.0 * (hi - lo0);
        n += 1;
        if n > 200 {
            return Err(SolverError::NotConverged {
                what: "impact-law lag bracket".into(),
                iterations: n,
            });
        }
    }
    let mut lo = lo0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if torque_at(g, law, mid) < torque {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-15 * hi.abs().max(1e-9) {
            break;
        }
    }
    Ok(hi)
}

/// Builds the impact law's table on the element's grid conventions (same
/// positions, lead-in, lag grid construction) with `law` and `friction`.
pub fn build(
    fp: &FlankPair,
    rs: &RollSurface,
    frame: &MemberFrame,
    ratio: f64,
    spec: TableSpec,
    law: ImpactLaw,
    friction: Option<Friction>,
) -> Result<MeshTable, SolverError> {
    check_spec(&spec)?;
    let tau = fp.pinion.gen.frame.pitch();
    let phi = |i: i64| spec.start + spec.direction * spec.step * i as f64;
    let pass1 = |range: std::ops::Range<i64>| -> Result<Vec<(Geometry, f64, f64)>, SolverError> {
        range
            .into_par_iter()
            .map(|i| {
                let t = std::time::Instant::now();
                let g = geometry(fp, rs, phi(i), tau, spec.slices);
                if g.slices.is_empty() {
                    return Err(SolverError::NoContact);
                }
                let hi = lag_for(&g, &law, spec.torque_max_nm)?;
                Ok((g, hi, t.elapsed().as_secs_f64()))
            })
            .collect()
    };
    let (columns, lead, lags) =
        columns_and_lags(&spec, ratio, pass1, |c: &(Geometry, f64, f64)| {
            (c.0.utca_te, c.1)
        })?;
    struct Col {
        base: Column,
        damping: Vec<[f64; 4]>,
        slip: Vec<f64>,
    }
    let cols: Vec<Col> = columns
        .into_par_iter()
        .map(|(g, _, cpu0)| {
            let t = std::time::Instant::now();
            let mut c = Col {
                base: Column {
                    te0: g.utca_te,
                    torque: Vec::with_capacity(lags.len()),
                    force: Vec::with_capacity(lags.len()),
                    wrench: Vec::with_capacity(lags.len()),
                    friction: Vec::with_capacity(lags.len()),
                    tangential: Vec::with_capacity(lags.len()),
                    // The impact law has no root stress.
                    root_tension: Vec::new(),
                    cpu: 0.0,
                },
                damping: Vec::with_capacity(lags.len()),
                slip: Vec::with_capacity(lags.len()),
            };
            for &lag in &lags {
                let (mut t1, mut f, mut phi_f, mut a) = (0.0, [0.0; 3], [0.0; 2], [0.0; 4]);
                let mut wr = [0.0; 6];
                let (mut sum_f, mut sum_fg, mut ft) = (0.0, 0.0, 0.0);
                for p in pairs_at(&g, &law, lag) {
                    let s = &g.slices[p.slice];
                    t1 += s.lever_pinion * p.force;
                    let n = frame.to_fixed(
                        &nalgebra::Vector3::from(s.normal),
                        g.phi + s.pair as f64 * tau,
                    );
                    for (fi, ni) in f.iter_mut().zip(n.iter()) {
                        *fi += p.force * ni;
                    }
                    let wk = crate::multibody::mesh_table::slice_wrench(
                        frame,
                        fp.pose.as_ref(),
                        s,
                        g.phi + s.pair as f64 * tau,
                        p.force,
                    );
                    for (x, y) in wr.iter_mut().zip(wk) {
                        *x += y;
                    }
                    for (pf, l) in phi_f.iter_mut().zip(s.friction_lever) {
                        *pf += p.force * l;
                    }
                    let w = law.damping_weight(p.delta).0;
                    let eps = s.lever_pinion - ratio * s.lever_wheel;
                    a[0] += w * s.lever_pinion * s.lever_wheel;
                    a[1] += w * s.lever_wheel * s.lever_wheel;
                    a[2] += w * s.lever_pinion * eps;
                    a[3] += w * s.lever_wheel * eps;
                    sum_f += p.force;
                    ft += s.wheel_tangential(p.force);
                    sum_fg += p.force * (s.friction_lever[0] - ratio * s.friction_lever[1]).abs();
                }
                c.base.torque.push(t1);
                c.base.force.push(f);
                c.base.wrench.push(wr);
                c.base.friction.push(phi_f);
                c.base.tangential.push(ft);
                c.damping.push(a);
                c.slip.push(if sum_f > 0.0 { sum_fg / sum_f } else { 0.0 });
            }
            c.base.cpu = cpu0 + t.elapsed().as_secs_f64();
            c
        })
        .collect();
    let base: Vec<&Column> = cols.iter().map(|c| &c.base).collect();
    let impact = ImpactFields {
        law,
        friction,
        damping: cols
            .iter()
            .flat_map(|c| c.damping.iter().copied())
            .collect(),
        slip: cols.iter().flat_map(|c| c.slip.iter().copied()).collect(),
    };
    Ok(MeshTable::from_columns(
        spec,
        lead,
        ratio,
        lags,
        &base,
        Some(impact),
    ))
}
