//! Quasi-static loaded tooth contact analysis: at each pinion position the
//! slices of every tooth pair that can touch, their compliance, and the
//! contact problem for each pinion torque.
//!
//! The TE convention is the UTCA's: wheel lag behind the conjugate position,
//! rad, positive = the wheel lags. Geometry and compliance of a position do
//! not depend on the load, so they are computed once for all torques.

use crate::cpu_clock::timed;
use crate::element::compliance::PairCompliance;
use crate::element::contact_problem::{ContactProblem, ContactSolution};
use crate::element::edge_contact::{position_edge, EdgeHit};
use crate::element::slices::{pair_slices, Slice};
use crate::element::weber_banaschek::{contact_modulus, half_width, LineContact};
use crate::SolverError;
use geometry::pair::{pairs_in_contact, FlankPair};
use geometry::utca::RollSurface;
use rayon::prelude::*;
use serde::Serialize;

/// The contact geometry of one position.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// Pinion angle, rad.
    pub phi: f64,
    /// Unloaded TE (UTCA) at this position, rad.
    pub utca_te: f64,
    pub slices: Vec<Slice>,
}

/// Slices of every tooth pair whose roll lies in the active range at `phi`.
pub fn geometry(fp: &FlankPair, rs: &RollSurface, phi: f64, tau: f64, n_slices: usize) -> Geometry {
    let mut utca_te = f64::INFINITY;
    let mut slices = Vec::new();
    for j in pairs_in_contact(phi, fp.roll_range, tau) {
        if let Some(ps) = pair_slices(fp, rs, phi, tau, j, n_slices) {
            utca_te = utca_te.min(ps.utca_lag);
            slices.extend(ps.slices);
        }
    }
    Geometry {
        phi,
        utca_te,
        slices,
    }
}

/// The slices of the pairs `pairs` at `phi` added to `g` (pairs without an
/// active point add nothing).
pub fn add_pairs(
    g: &mut Geometry,
    fp: &FlankPair,
    rs: &RollSurface,
    tau: f64,
    n_slices: usize,
    pairs: &[i32],
) {
    for &j in pairs {
        if let Some(ps) = pair_slices(fp, rs, g.phi, tau, j, n_slices) {
            g.utca_te = g.utca_te.min(ps.utca_lag);
            g.slices.extend(ps.slices);
        }
    }
    g.slices.sort_by_key(|s| s.pair);
}

/// The loaded-pair rule's candidates: the tooth pairs beyond those of `g`
/// (outward from its first and last while they qualify, at most three on
/// either side) whose unloaded closest point
/// lies below the wheel lag `limit` (rad), so that they close before the
/// wheel lags that far.
pub fn loaded_neighbours(
    g: &Geometry,
    fp: &FlankPair,
    rs: &RollSurface,
    tau: f64,
    limit: f64,
) -> Vec<i32> {
    let ls = geometry::utca::LineSearch::new(fp, rs);
    let (Some(lo), Some(hi)) = (
        g.slices.iter().map(|s| s.pair).min(),
        g.slices.iter().map(|s| s.pair).max(),
    ) else {
        return Vec::new();
    };
    let mut extra = Vec::new();
    for (first, step) in [(lo - 1, -1), (hi + 1, 1)] {
        let mut j = first;
        while let Some((lag, _)) = ls.min_contact(g.phi + j as f64 * tau) {
            if lag >= limit || (j - first).abs() > 2 {
                break;
            }
            extra.push(j);
            j += step;
        }
    }
    extra
}

/// Compliance and line contacts of a position's slices.
#[derive(Debug, Clone)]
pub struct Assembled {
    /// C = C_pinion + C_wheel, row-major n × n, m/N.
    pub compliance: Vec<f64>,
    pub line: Vec<LineContact>,
    /// Per slice: touching lag (rad), wheel and pinion normal levers.
    pub lag: Vec<f64>,
    pub lever_wheel: Vec<f64>,
    /// Pinion lever of each slice's normal force, friction included:
    /// λ₁ + μ ℓ₁ (the torque balance Σ (λ₁ + μ ℓ₁) F = T₁).
    pub lever_pinion: Vec<f64>,
    /// The friction coefficient μ.
    pub friction: f64,
}

/// Interpolates both members' global influence fields and reference depths
/// to the slices; `friction` is the Coulomb coefficient μ.
pub fn assemble(
    g: &Geometry,
    pc: &PairCompliance,
    friction: f64,
) -> Result<Assembled, SolverError> {
    let n = g.slices.len();
    let mut c = vec![0.0; n * n];
    let wp: Vec<_> = g
        .slices
        .iter()
        .map(|s| pc.pinion.weights(s.xi, s.eta))
        .collect();
    let ww: Vec<_> = g
        .slices
        .iter()
        .map(|s| pc.wheel.weights(s.wheel_xi_eta[0], s.wheel_xi_eta[1]))
        .collect();
    let mut pairs: Vec<i32> = g.slices.iter().map(|s| s.pair).collect();
    pairs.dedup();
    let members: Vec<Vec<usize>> = pairs
        .iter()
        .map(|&j| (0..n).filter(|&k| g.slices[k].pair == j).collect())
        .collect();
    let mut line = Vec::with_capacity(n);
    let bodies = [pc.pinion.material, pc.wheel.material];
    // Pair blocks (a, b) left out because (b, a) holds their transpose.
    let mut mirrored = vec![false; pairs.len() * pairs.len()];
    for (a, &ja) in pairs.iter().enumerate() {
        let sp = pc.pinion.solved_index(ja as i64)?;
        let sw = pc.wheel.solved_index(-(ja as i64))?;
        for &k in &members[a] {
            let h = [pc.pinion.depth(sp, &wp[k]), pc.wheel.depth(sw, &ww[k])];
            line.push((k, g.slices[k].line_contact(h, bodies)));
        }
        let rows = &members[a];
        let wpr: Vec<_> = rows.iter().map(|&k| &wp[k]).collect();
        let wwr: Vec<_> = rows.iter().map(|&k| &ww[k]).collect();
        for (b, &jb) in pairs.iter().enumerate() {
            let o = (jb - ja) as i64;
            if b < a && pc.pinion.mirrored(sp, o) && pc.wheel.mirrored(sw, -o) {
                mirrored[a * pairs.len() + b] = true;
                continue;
            }
            let cols = &members[b];
            let wpc: Vec<_> = cols.iter().map(|&k| &wp[k]).collect();
            let wwc: Vec<_> = cols.iter().map(|&k| &ww[k]).collect();
            pc.pinion
                .add_block(sp, o, &wpr, &wpc, rows, cols, &mut c, n);
            pc.wheel
                .add_block(sw, -o, &wwr, &wwc, rows, cols, &mut c, n);
        }
    }
    // C(k, l) and C(l, k) come from different blocks (load on k's tooth, or
    // on l's): equal by reciprocity where both members' blocks were
    // symmetrized on loading (then one was assembled and is copied), else up
    // to the FE's round-off and the mesh's departure from rotational
    // symmetry (then both were, and their mean is taken).
    let mut pair_of = vec![0; n];
    for (a, rows) in members.iter().enumerate() {
        for &k in rows {
            pair_of[k] = a;
        }
    }
    for k in 0..n {
        for l in 0..k {
            let m = if mirrored[pair_of[k] * pairs.len() + pair_of[l]] {
                c[l * n + k]
            } else if mirrored[pair_of[l] * pairs.len() + pair_of[k]] {
                c[k * n + l]
            } else {
                0.5 * (c[k * n + l] + c[l * n + k])
            };
            c[k * n + l] = m;
            c[l * n + k] = m;
        }
    }
    line.sort_by_key(|e| e.0);
    Ok(Assembled {
        compliance: c,
        line: line.into_iter().map(|e| e.1).collect(),
        lag: g.slices.iter().map(|s| s.lag).collect(),
        lever_wheel: g.slices.iter().map(|s| s.lever_wheel).collect(),
        lever_pinion: g
            .slices
            .iter()
            .map(|s| s.lever_pinion + friction * s.friction_lever[0])
            .collect(),
        friction,
    })
}

/// Solves one position at pinion torque `torque` (N·m).
pub fn solve(
    a: &Assembled,
    torque: f64,
    warm: Option<&[bool]>,
) -> Result<ContactSolution, SolverError> {
    ContactProblem {
        compliance: &a.compliance,
        lag: &a.lag,
        lever_wheel: &a.lever_wheel,
        lever_pinion: &a.lever_pinion,
        line: &a.line,
        torque,
    }
    .solve(warm)
}

/// The rotation sweep.
#[derive(Debug, Clone, Copy)]
pub struct Sweep {
    /// First pinion angle, rad.
    pub start: f64,
    /// Step, rad (> 0), taken in `direction` (±1).
    pub step: f64,
    pub direction: f64,
    pub positions: usize,
    /// Slices across the face width per tooth pair.
    pub slices: usize,
    /// Coulomb friction coefficient μ (forward rotation).
    pub friction: f64,
}

/// One loaded slice.
#[derive(Debug, Clone, Serialize)]
pub struct SliceLoad {
    pub pair: i32,
    pub xi: f64,
    pub eta: f64,
    pub force_n: f64,
    pub line_load_n_per_m: f64,
    /// Hertz maximum pressure p₀ = √(q E* / (π ρ)), Pa.
    pub pressure_pa: f64,
    pub half_width_m: f64,
}

/// Result of one position at one torque.
#[derive(Debug, Clone, Serialize)]
pub struct PositionLoad {
    /// Loaded TE, rad.
    pub te: f64,
    /// Torque the contact drives the wheel with, N·m (normal forces and,
    /// with friction, the friction forces); the mesh efficiency is
    /// wheel torque / (pinion torque · z₂/z₁).
    pub wheel_torque_nm: f64,
    /// Force of each tooth pair in contact: (pair, N).
    pub pair_force: Vec<(i32, f64)>,
    /// Share of the pinion torque carried by each pair (same order).
    pub pair_share: Vec<f64>,
    /// Torsional mesh stiffness T / (TE − TE_unloaded), N·m/rad (pinion torque per wheel lag).
    pub mesh_stiffness: f64,
    pub max_pressure_pa: f64,
    /// Loaded slices only.
    pub slices: Vec<SliceLoad>,
    pub solve_s: f64,
    pub iterations: usize,
    /// Active-set changes over all fixed-point iterations.
    pub active_set_changes: usize,
    /// Σ (λ₁ + μ ℓ₁) F − T, N·m: the contact's torque on the pinion less the
    /// applied torque (zero to rounding).
    pub torque_residual_nm: f64,
    /// Smallest slice force, N (≥ 0: compressive only), over all slices.
    pub min_force_n: f64,
    /// Loaded TE and every slice force finite.
    pub finite: bool,
    /// The loaded contact's reach past an edge of the active flank (the
    /// largest overshoot over the slices), if any.
    pub edge: Option<EdgeHit>,
    /// Root stress of each loaded tooth's two fillets, pinion's then
    /// wheel's ([`crate::element::root_stress`]); None when a stiffness
    /// file has no root-stress coefficients.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub root_stress: Option<[Vec<formats::root_stress::FilletStress>; 2]>,
    /// Time spent on the root stress, s.
    pub root_stress_s: f64,
}

/// A position over all torques.
#[derive(Debug, Clone, Serialize)]
pub struct PositionResult {
    /// Pinion rotation from the sweep start, rad.
    pub rotation: f64,
    pub utca_te: f64,
    pub slices: usize,
    /// CPU seconds (of the thread that ran the position) for the slice
    /// geometry and the compliance assembly.
    pub geometry_s: f64,
    pub assembly_s: f64,
    /// One entry per torque.
    pub loads: Vec<PositionLoad>,
    /// The loaded-pair rule at this position ([`loaded_pair_rule`]).
    pub neighbours: Neighbours,
}

/// The tooth pairs beyond the active roll range's that the loaded-pair
/// rule examined at one position.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Neighbours {
    /// Pairs whose unloaded closest point lies below the largest loaded TE.
    pub pairs: Vec<i32>,
    /// Of those, the pairs whose teeth the stiffness files do not hold
    /// (not checked).
    pub unchecked: Vec<i32>,
    /// Whether one of them closes under a torque (then they are part of
    /// the position's contact problem and its results).
    pub closing: bool,
}

/// The loads of every torque on one position's assembled problem, with
/// the contact solutions.
fn solve_torques(
    fp: &FlankPair,
    g: &Geometry,
    a: &Assembled,
    torques: &[f64],
) -> Result<(Vec<PositionLoad>, Vec<ContactSolution>), SolverError> {
    let mut loads = Vec::with_capacity(torques.len());
    let mut sols: Vec<ContactSolution> = Vec::with_capacity(torques.len());
    for &torque in torques {
        let warm = sols.last().map(|s| s.active.as_slice());
        let (s, dt) = timed(|| solve(a, torque, warm));
        let s = s?;
        loads.push(position_load(fp, g, a, &s, torque, dt));
        sols.push(s);
    }
    Ok((loads, sols))
}

/// The loaded-pair rule: a tooth pair beyond the active roll range enters
/// a position's problem when it closes under the load. Candidates are the
/// pairs whose unloaded closest point lies below the largest loaded TE of
/// the position ([`loaded_neighbours`]: rigidly, they would penetrate);
/// with them added, the gap of each of their slices under the forces found
/// without them, λ₂(lag − θ) + Σ C F (the loaded teeth's deflection moves
/// their neighbours too: the lightweight web turns them all), decides.
/// Candidates whose teeth the stiffness files do not hold cannot be checked
/// and are listed as such. Returns what was found and, where a candidate
/// closes, the geometry and problem with the candidates (None: the forces
/// found stand).
#[allow(clippy::too_many_arguments)]
fn loaded_pair_rule(
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    tau: f64,
    g: &Geometry,
    sols: &[ContactSolution],
    variant: Variant,
) -> Result<(Neighbours, Option<(Geometry, Assembled)>), SolverError> {
    let tmax = sols
        .iter()
        .map(|s| s.theta)
        .fold(f64::NEG_INFINITY, f64::max);
    let candidates = loaded_neighbours(g, fp, rs, tau, tmax);
    // Only pairs whose teeth the stiffness files hold can be checked.
    let (extra, unchecked): (Vec<i32>, Vec<i32>) = candidates.iter().partition(|&&j| {
        pc.pinion.solved_index(j as i64).is_ok() && pc.wheel.solved_index(-(j as i64)).is_ok()
    });
    if extra.is_empty() {
        return Ok((
            Neighbours {
                pairs: candidates,
                unchecked,
                closing: false,
            },
            None,
        ));
    }
    let mut wide = g.clone();
    add_pairs(&mut wide, fp, rs, tau, sweep.slices, &extra);
    let mut a = assemble(&wide, pc, sweep.friction)?;
    variant.apply(&mut a);
    let n = wide.slices.len();
    // Slices of g keep their order in `wide` (a stable sort by pair).
    let old: Vec<usize> = (0..n)
        .filter(|&k| !extra.contains(&wide.slices[k].pair))
        .collect();
    let closing = sols.iter().any(|s| {
        (0..n)
            .filter(|k| extra.contains(&wide.slices[*k].pair))
            .any(|k| {
                let coupled: f64 = old
                    .iter()
                    .zip(&s.force)
                    .map(|(&l, f)| a.compliance[k * n + l] * f)
                    .sum();
                a.lever_wheel[k] * (a.lag[k] - s.theta) + coupled < 0.0
            })
    });
    let found = Neighbours {
        pairs: candidates,
        unchecked,
        closing,
    };
    Ok((found, closing.then_some((wide, a))))
}

fn position_load(
    fp: &FlankPair,
    g: &Geometry,
    a: &Assembled,
    s: &ContactSolution,
    torque: f64,
    dt: f64,
) -> PositionLoad {
    let mut pair_force: Vec<(i32, f64)> = Vec::new();
    let mut pair_torque: Vec<f64> = Vec::new();
    let mut slices = Vec::new();
    let mut pmax: f64 = 0.0;
    let mut half_widths = vec![0.0; g.slices.len()];
    for (k, sl) in g.slices.iter().enumerate() {
        match pair_force.iter().position(|p| p.0 == sl.pair) {
            Some(i) => {
                pair_force[i].1 += s.force[k];
                pair_torque[i] += s.force[k] * a.lever_pinion[k];
            }
            None => {
                pair_force.push((sl.pair, s.force[k]));
                pair_torque.push(s.force[k] * a.lever_pinion[k]);
            }
        }
        if s.force[k] > 0.0 {
            let lc = &a.line[k];
            let q = s.force[k] / lc.length;
            let es = contact_modulus(lc.bodies[0], lc.bodies[1]);
            let b = half_width(q, lc.rho, es);
            let p0 = 2.0 * q / (std::f64::consts::PI * b);
            pmax = pmax.max(p0);
            half_widths[k] = b;
            slices.push(SliceLoad {
                pair: sl.pair,
                xi: sl.xi,
                eta: sl.eta,
                force_n: s.force[k],
                line_load_n_per_m: q,
                pressure_pa: p0,
                half_width_m: b,
            });
        }
    }
    let share = pair_torque
        .iter()
        .map(|t| if torque > 0.0 { t / torque } else { 0.0 })
        .collect();
    let wheel_torque = g
        .slices
        .iter()
        .zip(&s.force)
        .map(|(sl, f)| f * (sl.lever_wheel + a.friction * sl.friction_lever[1]))
        .sum();
    PositionLoad {
        te: s.theta,
        wheel_torque_nm: wheel_torque,
        pair_force,
        pair_share: share,
        mesh_stiffness: if s.theta > g.utca_te {
            torque / (s.theta - g.utca_te)
        } else {
            f64::INFINITY
        },
        max_pressure_pa: pmax,
        slices,
        solve_s: dt,
        iterations: s.iterations,
        active_set_changes: s.active_set_changes,
        torque_residual_nm: s
            .force
            .iter()
            .zip(&a.lever_pinion)
            .map(|(f, l)| f * l)
            .sum::<f64>()
            - torque,
        min_force_n: s.force.iter().copied().fold(f64::INFINITY, f64::min),
        finite: s.theta.is_finite() && s.force.iter().all(|f| f.is_finite()),
        edge: position_edge(fp, &g.slices, &s.force, &half_widths),
        root_stress: None,
        root_stress_s: 0.0,
    }
}

/// The element with one of its modelling changes switched off, for the
/// ablation study that measures what each change does (the element itself
/// always runs [`Variant::Element`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variant {
    /// The element as it is.
    Element,
    /// Without the edge cut: every slice a Hertz strip, tip edges or not
    /// ([`crate::element::edge_cut`]).
    WithoutEdgeCut,
}

impl Variant {
    /// The variants the ablation study runs beside the element.
    pub const ABLATED: [Variant; 1] = [Variant::WithoutEdgeCut];

    /// Short name (file key).
    pub fn name(self) -> &'static str {
        match self {
            Variant::Element => "element",
            Variant::WithoutEdgeCut => "without_edge_cut",
        }
    }

    /// The modelling change this variant switches off, in words.
    pub fn change(self) -> &'static str {
        match self {
            Variant::Element => "none",
            Variant::WithoutEdgeCut => "edge cut (a tip edge cutting a slice's contact strip)",
        }
    }

    fn apply(self, a: &mut Assembled) {
        if self == Variant::WithoutEdgeCut {
            for l in &mut a.line {
                l.edge = None;
            }
        }
    }
}

/// Runs the sweep for every torque (positions in parallel).
pub fn run(
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
) -> Result<Vec<PositionResult>, SolverError> {
    run_variant(fp, rs, pc, sweep, torques, Variant::Element)
}

/// [`run`] with the element's `variant`.
pub fn run_variant(
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
    variant: Variant,
) -> Result<Vec<PositionResult>, SolverError> {
    sweep_positions(fp, rs, pc, sweep, torques, variant, false)
}

/// [`run`], and at every position and torque the loaded teeth's root
/// stress ([`crate::element::root_stress`]) where both stiffness files hold
/// root-stress coefficients: the LTCA stage's sweep. The studies that
/// need the TE only ([`run`]) do not pay for it.
pub fn run_with_root_stress(
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
) -> Result<Vec<PositionResult>, SolverError> {
    sweep_positions(fp, rs, pc, sweep, torques, Variant::Element, true)
}

fn sweep_positions(
    fp: &FlankPair,
    rs: &RollSurface,
    pc: &PairCompliance,
    sweep: &Sweep,
    torques: &[f64],
    variant: Variant,
    root_stress: bool,
) -> Result<Vec<PositionResult>, SolverError> {
    let tau = fp.pinion.gen.frame.pitch();
    (0..sweep.positions)
        .into_par_iter()
        .map(|k| {
            let rotation = sweep.step * k as f64;
            let phi = sweep.start + sweep.direction * rotation;
            let (g, geometry_s) = timed(|| geometry(fp, rs, phi, tau, sweep.slices));
            if g.slices.is_empty() {
                return Err(SolverError::NoContact);
            }
            let (a, assembly_s) = timed(|| assemble(&g, pc, sweep.friction));
            let mut a = a?;
            variant.apply(&mut a);
            let (mut loads, mut sols) = solve_torques(fp, &g, &a, torques)?;
            let (neighbours, wider) = loaded_pair_rule(fp, rs, pc, sweep, tau, &g, &sols, variant)?;
            let g = match wider {
                Some((g2, a2)) => {
                    (loads, sols) = solve_torques(fp, &g2, &a2, torques)?;
                    g2
                }
                None => g,
            };
            for (l, s) in loads.iter_mut().zip(&sols).filter(|_| root_stress) {
                let (r, dt) =
                    timed(|| crate::element::root_stress::root_stress(pc, &g.slices, &s.force));
                l.root_stress = r?;
                l.root_stress_s = dt;
            }
            Ok(PositionResult {
                rotation,
                utca_te: g.utca_te,
                slices: g.slices.len(),
                geometry_s,
                assembly_s,
                loads,
                neighbours,
            })
        })
        .collect()
}

/// Mean and peak-to-peak of a series.
pub fn mean_ptp(v: &[f64]) -> (f64, f64) {
    let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
    let (lo, hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    (mean, hi - lo)
}
