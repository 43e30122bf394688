//! Root (fillet) stress of the loaded teeth from the slice forces, through
//! the stiffness files' root-stress influence coefficients S (the stress at
//! each fillet point of a tooth under a unit load at each grid point of the
//! same or a neighbouring tooth):
//!
//!   σ_r = Σ_j Σ_a W_j[a] S[s(j)][r − j][a],  W_j = Σ_{k on tooth j} F_k w_k,
//!
//! with w_k slice k's interpolation weights on the grid (the compliance's,
//! [`crate::element::interp`]), F_k its normal force, j the loaded teeth and
//! r the responding ones (the loaded teeth, each seen from itself and its
//! neighbours). Linear in the forces: the tensors are summed, then each
//! fillet's largest first and smallest third principal stress taken
//! ([`formats::root_stress::fillet_extremes`]). Pinion tooth j meshes with
//! wheel tooth −j, so the wheel's offset is the pinion's negated.

use crate::element::compliance::{MemberCompliance, PairCompliance};
use crate::element::interp::Weights;
use crate::element::slices::Slice;
use crate::SolverError;
use formats::root_stress::{fillet_extremes, FilletStress, Stress};

/// One member's loaded teeth's fillets: `tooth_of(pair)` its body tooth
/// of a pair, `weights(slice)` a slice's grid weights, `sign` +1 (pinion)
/// or −1 (wheel) for the tooth numbering. None without root stress.
/// With `loaded_only`, the loaded flanks' fillets alone (half the work).
fn member(
    m: &MemberCompliance,
    slices: &[Slice],
    force: &[f64],
    sign: i64,
    loaded_only: bool,
    weights: impl Fn(&Slice) -> Weights,
) -> Result<Option<Vec<FilletStress>>, SolverError> {
    let Some((xi, height, loaded)) = m.root_points() else {
        return Ok(None);
    };
    // Combined weights W_j of every loaded pair.
    let mut pairs: Vec<(i64, Vec<f64>)> = Vec::new();
    let np = m.points();
    for (sl, &f) in slices.iter().zip(force) {
        if f <= 0.0 {
            continue;
        }
        let j = sign * sl.pair as i64;
        let at = match pairs.iter().position(|p| p.0 == j) {
            Some(i) => i,
            None => {
                pairs.push((j, vec![0.0; np]));
                pairs.len() - 1
            }
        };
        for (a, w) in weights(sl) {
            pairs[at].1[a] += f * w;
        }
    }
    let combined: Vec<(i64, usize, Weights)> = pairs
        .into_iter()
        .map(|(j, w)| {
            let sparse: Weights = w
                .into_iter()
                .enumerate()
                .filter(|&(_, v)| v != 0.0)
                .collect();
            Ok((j, m.solved_index(j)?, sparse))
        })
        .collect::<Result<_, SolverError>>()?;
    let mut out = Vec::with_capacity(2 * combined.len());
    for &(r, _, _) in &combined {
        let mut s: Vec<Stress> = vec![[0.0; 6]; if loaded_only { loaded } else { xi.len() }];
        for (j, sj, w) in &combined {
            m.add_root_stress(*sj, r - j, w, 1.0, &mut s);
        }
        let tooth = r.rem_euclid(m.teeth as i64) as usize;
        out.push(fillet_extremes(
            tooth,
            true,
            &xi[..loaded],
            &height[..loaded],
            &s[..loaded],
        ));
        if loaded_only {
            continue;
        }
        out.push(fillet_extremes(
            tooth,
            false,
            &xi[loaded..],
            &height[loaded..],
            &s[loaded..],
        ));
    }
    Ok(Some(out))
}

/// The root stress of both members' loaded teeth (pinion's, wheel's)
/// under the slice forces `force` (N, one per slice), or None when either
/// stiffness file has no root-stress coefficients.
pub fn root_stress(
    pc: &PairCompliance,
    slices: &[Slice],
    force: &[f64],
) -> Result<Option<[Vec<FilletStress>; 2]>, SolverError> {
    both_members(pc, slices, force, false)
}

fn both_members(
    pc: &PairCompliance,
    slices: &[Slice],
    force: &[f64],
    loaded_only: bool,
) -> Result<Option<[Vec<FilletStress>; 2]>, SolverError> {
    let p = member(&pc.pinion, slices, force, 1, loaded_only, |s| {
        pc.pinion.weights(s.xi, s.eta)
    })?;
    let w = member(&pc.wheel, slices, force, -1, loaded_only, |s| {
        pc.wheel.weights(s.wheel_xi_eta[0], s.wheel_xi_eta[1])
    })?;
    Ok(p.zip(w).map(|(p, w)| [p, w]))
}

/// The largest first principal stress over the loaded flanks' fillets of
/// the loaded teeth, [pinion, wheel], Pa (0 where none carries load), or
/// None without root-stress coefficients: [`root_stress`]'s tension at half
/// its work (the other flanks' fillets are not summed).
pub fn largest_loaded_tension(
    pc: &PairCompliance,
    slices: &[Slice],
    force: &[f64],
) -> Result<Option<[f64; 2]>, SolverError> {
    Ok(both_members(pc, slices, force, true)?.map(|m| {
        m.map(|fillets| {
            fillets
                .iter()
                .map(|f| f.max_principal_pa)
                .fold(0.0, f64::max)
        })
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use formats::stiffness_file::{RootStressBlock, StiffnessData};
    use geometry::Material;

    /// Five teeth, all solved, offsets −1..1, a 3 × 4 grid, two
    /// fillet points per side, pseudo-random root-stress coefficients.
    fn member(name: &str, seed: u64) -> MemberCompliance {
        MemberCompliance::new(data(name, seed), Material::STEEL)
    }

    fn data(name: &str, seed: u64) -> StiffnessData {
        let (gp, gf, no, ns, nf) = (3, 4, 3, 5, 4);
        let np = gp * gf;
        let mut state = seed;
        let mut rnd = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e5
        };
        StiffnessData {
            input_hash: String::new(),
            config: String::new(),
            member: name.into(),
            blank: "lightweight".into(),
            level: "reduced".into(),
            teeth: 5,
            axisymmetric: false,
            grid_profile: gp,
            grid_face: gf,
            xi: (0..gf).map(|i| i as f64 / (gf - 1) as f64).collect(),
            eta: (0..gp).map(|i| i as f64 / (gp - 1) as f64).collect(),
            position: vec![0.0; 3 * np],
            normal: vec![0.0; 3 * np],
            lever: vec![0.0; np],
            solved_teeth: vec![0, 1, 2, 3, 4],
            offsets: vec![-1, 0, 1],
            depth_h: vec![1e-3; ns * np],
            total: Vec::new(),
            local: Vec::new(),
            global: vec![1e-9; ns * no * np * np],
            root_stress: Some(RootStressBlock {
                offsets: vec![-1, 0, 1],
                xi: vec![0.25, 0.75, 0.25, 0.75],
                height: vec![0.5, 0.5, 0.5, 0.5],
                stress: (0..ns * 3 * np * nf * 6).map(|_| rnd()).collect(),
            }),
        }
    }

    fn slice(pair: i32, xi: f64, eta: f64, wheel: [f64; 2]) -> Slice {
        Slice {
            pair,
            band: [xi - 0.05, xi + 0.05],
            xi,
            eta,
            uv: [0.0; 2],
            wheel_xi_eta: wheel,
            lag: 0.0,
            lever_wheel: 0.0,
            lever_pinion: 0.0,
            wheel_radius: 0.0,
            pos: [0.0; 3],
            normal: [0.0; 3],
            length: 1e-3,
            rho: 1e-2,
            friction_lever: [0.0; 2],
            edge: None,
        }
    }

    /// Slice by slice, with the stored coefficients of the slice's own
    /// tooth read at the offset to each responding tooth (pinion r − j,
    /// wheel −r − (−j)), summed, then the extremes: the combined kernel
    /// gives the same for both members; an unloaded slice adds nothing.
    #[test]
    fn root_stress_of_slice_forces_is_their_sum_slice_by_slice() {
        let pc = PairCompliance {
            pinion: member("pinion", 1),
            wheel: member("wheel", 2),
        };
        let slices = [
            slice(0, 0.3, 0.4, [0.6, 0.5]),
            slice(0, 0.6, 0.5, [0.3, 0.6]),
            slice(1, 0.5, 0.7, [0.5, 0.2]),
            slice(1, 0.8, 0.2, [0.1, 0.9]),
        ];
        let force = [1200.0, 800.0, 0.0, 1500.0];
        let got = root_stress(&pc, &slices, &force).unwrap().unwrap();
        for (b, m) in [&pc.pinion, &pc.wheel].into_iter().enumerate() {
            let sign = if b == 0 { 1 } else { -1 };
            let (xi, h, half) = m.root_points().unwrap();
            let mut expected = Vec::new();
            for r in [0i64, 1].map(|p| sign * p) {
                let mut s: Vec<Stress> = vec![[0.0; 6]; xi.len()];
                for (sl, &f) in slices.iter().zip(&force) {
                    if f <= 0.0 {
                        continue;
                    }
                    let j = sign * sl.pair as i64;
                    let w = if b == 0 {
                        m.weights(sl.xi, sl.eta)
                    } else {
                        m.weights(sl.wheel_xi_eta[0], sl.wheel_xi_eta[1])
                    };
                    m.add_root_stress(m.solved_index(j).unwrap(), r - j, &w, f, &mut s);
                }
                let tooth = r.rem_euclid(5) as usize;
                expected.push(fillet_extremes(
                    tooth,
                    true,
                    &xi[..half],
                    &h[..half],
                    &s[..half],
                ));
                expected.push(fillet_extremes(
                    tooth,
                    false,
                    &xi[half..],
                    &h[half..],
                    &s[half..],
                ));
            }
            assert_eq!(got[b].len(), expected.len());
            for (g, e) in got[b].iter().zip(&expected) {
                assert_eq!((g.tooth, g.loaded_side), (e.tooth, e.loaded_side));
                let scale = e.max_principal_pa.abs().max(e.min_principal_pa.abs());
                assert!((g.max_principal_pa - e.max_principal_pa).abs() <= 1e-12 * scale);
                assert!((g.min_principal_pa - e.min_principal_pa).abs() <= 1e-12 * scale);
            }
        }
        // Without root stress in a file: none.
        let plain = PairCompliance {
            pinion: MemberCompliance::new(
                StiffnessData {
                    root_stress: None,
                    ..data("pinion", 1)
                },
                Material::STEEL,
            ),
            wheel: pc.wheel.clone(),
        };
        assert!(root_stress(&plain, &slices, &force).unwrap().is_none());
        assert!(largest_loaded_tension(&plain, &slices, &force)
            .unwrap()
            .is_none());
    }

    /// The loaded-fillets-only kernel gives the full kernel's largest
    /// loaded-side tension of each member, to round-off.
    #[test]
    fn largest_loaded_tension_equals_the_full_kernels_loaded_side() {
        let pc = PairCompliance {
            pinion: member("pinion", 3),
            wheel: member("wheel", 4),
        };
        let slices = [
            slice(0, 0.2, 0.5, [0.7, 0.4]),
            slice(0, 0.5, 0.6, [0.4, 0.5]),
            slice(-1, 0.7, 0.3, [0.2, 0.8]),
        ];
        let force = [900.0, 1100.0, 400.0];
        let full = root_stress(&pc, &slices, &force).unwrap().unwrap();
        let fast = largest_loaded_tension(&pc, &slices, &force)
            .unwrap()
            .unwrap();
        for b in 0..2 {
            let want = full[b]
                .iter()
                .filter(|f| f.loaded_side)
                .map(|f| f.max_principal_pa)
                .fold(0.0, f64::max);
            assert!(want > 0.0);
            assert!(
                (fast[b] - want).abs() <= 1e-12 * want,
                "{b}: {} {want}",
                fast[b]
            );
        }
    }
}
