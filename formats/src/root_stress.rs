//! Root (fillet) stress as every stage reports it: a fillet's largest
//! first principal stress (tension) and smallest third principal stress
//! (compression), each with where it sits, from the stress tensors at the
//! fillet's points ([`fillet_extremes`]). Shared by the reference FE (at
//! the fillet's mesh nodes) and the reduced model (at the stiffness file's
//! fillet points).

use serde::{Deserialize, Serialize};

/// Symmetric stress in Voigt order [σxx, σyy, σzz, σyz, σxz, σxy], Pa.
pub type Stress = [f64; 6];

/// Principal stresses σ₁ ≥ σ₂ ≥ σ₃ (eigenvalues of the stress tensor), in
/// closed form (the trigonometric solution of the characteristic cubic,
/// O. K. Smith 1961): with q = tr σ / 3, p = √(|σ − qI|²_F / 6) and
/// r = det((σ − qI)/p) / 2, φ = acos(r)/3, the eigenvalues are
/// q + 2p cos(φ + 2πk/3). A reduced-model sweep takes hundreds per
/// position, where an iterative eigen-solver costs more than the rest of
/// the root stress.
pub fn principal(s: Stress) -> [f64; 3] {
    let [a, b, c, yz, xz, xy] = s;
    let off = xy * xy + xz * xz + yz * yz;
    let q = (a + b + c) / 3.0;
    let (da, db, dc) = (a - q, b - q, c - q);
    let p2 = da * da + db * db + dc * dc + 2.0 * off;
    if p2 <= 1e-300 || off <= 1e-30 * p2 {
        let mut d = [a, b, c];
        d.sort_by(|x, y| y.total_cmp(x));
        return d;
    }
    let p = (p2 / 6.0).sqrt();
    let det = da * (db * dc - yz * yz) - xy * (xy * dc - yz * xz) + xz * (xy * yz - db * xz);
    let r = (det / (2.0 * p * p * p)).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    let e1 = q + 2.0 * p * phi.cos();
    let e3 = q + 2.0 * p * (phi + 2.0 * std::f64::consts::PI / 3.0).cos();
    [e1, 3.0 * q - e1 - e3, e3]
}

/// One fillet's extreme stresses.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilletStress {
    pub tooth: usize,
    /// Under the loaded flank (true) or the tooth's other flank.
    pub loaded_side: bool,
    /// Largest first principal stress over the fillet's points, Pa, and its
    /// point's face-width position and fillet height.
    pub max_principal_pa: f64,
    pub max_xi: f64,
    pub max_height: f64,
    /// Smallest third principal stress, Pa (negative: compression), and
    /// where.
    pub min_principal_pa: f64,
    pub min_xi: f64,
    pub min_height: f64,
}

/// The extremes over one fillet's points: stress `s[k]` at face-width
/// position `xi[k]` and fillet height `height[k]`.
pub fn fillet_extremes(
    tooth: usize,
    loaded_side: bool,
    xi: &[f64],
    height: &[f64],
    s: &[Stress],
) -> FilletStress {
    let mut out = FilletStress {
        tooth,
        loaded_side,
        max_principal_pa: f64::NEG_INFINITY,
        max_xi: f64::NAN,
        max_height: f64::NAN,
        min_principal_pa: f64::INFINITY,
        min_xi: f64::NAN,
        min_height: f64::NAN,
    };
    for (k, s) in s.iter().enumerate() {
        let p = principal(*s);
        if p[0] > out.max_principal_pa {
            out.max_principal_pa = p[0];
            out.max_xi = xi[k];
            out.max_height = height[k];
        }
        if p[2] < out.min_principal_pa {
            out.min_principal_pa = p[2];
            out.min_xi = xi[k];
            out.min_height = height[k];
        }
    }
    out
}

/// Where on which fillet, at which position, an extreme stress sits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FilletPlace {
    /// Pinion rotation from the sweep's start, deg.
    pub pinion_rotation_deg: f64,
    pub tooth: usize,
    /// Face-width position (0 toe, 1 heel) and fillet height (0 root, 1
    /// flank junction).
    pub xi: f64,
    pub height: f64,
}

/// One member's extreme root stresses over a sweep at one torque.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RootStressExtreme {
    /// Largest first principal stress in a loaded flank's fillet, MPa.
    pub tension_mpa: f64,
    pub tension_at: FilletPlace,
    /// Smallest third principal stress in an other flank's fillet, MPa
    /// (negative: compression).
    pub compression_mpa: f64,
    pub compression_at: FilletPlace,
}

/// Pinion's and wheel's extremes at one torque.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RootStressSummary {
    pub pinion: RootStressExtreme,
    pub wheel: RootStressExtreme,
}

/// One member's extremes over positions, each given as (pinion rotation,
/// its fillets); None when a position has none or no fillet of each side
/// appears.
fn extreme<'a>(
    positions: impl Iterator<Item = (f64, Option<&'a [FilletStress]>)>,
) -> Option<RootStressExtreme> {
    let nan = FilletPlace {
        pinion_rotation_deg: f64::NAN,
        tooth: 0,
        xi: f64::NAN,
        height: f64::NAN,
    };
    let mut e = RootStressExtreme {
        tension_mpa: f64::NEG_INFINITY,
        tension_at: nan,
        compression_mpa: f64::INFINITY,
        compression_at: nan,
    };
    for (deg, fillets) in positions {
        for f in fillets? {
            let place = |xi, height| FilletPlace {
                pinion_rotation_deg: deg,
                tooth: f.tooth,
                xi,
                height,
            };
            if f.loaded_side && f.max_principal_pa * 1e-6 > e.tension_mpa {
                e.tension_mpa = f.max_principal_pa * 1e-6;
                e.tension_at = place(f.max_xi, f.max_height);
            }
            if !f.loaded_side && f.min_principal_pa * 1e-6 < e.compression_mpa {
                e.compression_mpa = f.min_principal_pa * 1e-6;
                e.compression_at = place(f.min_xi, f.min_height);
            }
        }
    }
    (e.tension_mpa.is_finite() && e.compression_mpa.is_finite()).then_some(e)
}

/// Both members' extremes over the positions, each given as (pinion
/// rotation from the sweep's start in deg, its [pinion, wheel] fillets or
/// None); None when any position lacks them.
pub fn summarize<'a>(
    positions: impl Iterator<Item = (f64, Option<&'a [Vec<FilletStress>; 2]>)> + Clone,
) -> Option<RootStressSummary> {
    let member = |b: usize| {
        extreme(
            positions
                .clone()
                .map(move |(d, f)| (d, f.map(|f| f[b].as_slice()))),
        )
    };
    Some(RootStressSummary {
        pinion: member(0)?,
        wheel: member(1)?,
    })
}

/// The header of a `root_stress.csv` (the reference's and the LTCA's):
/// one row per position, torque, member and fillet.
pub const CSV_HEADER: &str = "pinion_rotation_deg,torque_nm,member,tooth,fillet,sigma1_max_mpa,sigma1_xi,sigma1_height,sigma3_min_mpa,sigma3_xi,sigma3_height";

/// A `root_stress.csv` of `positions`, each (pinion rotation deg, torque
/// N·m, [pinion's, wheel's] fillets); None when no position has a fillet.
pub fn fillets_csv<'a>(
    positions: impl Iterator<Item = (f64, f64, &'a [Vec<FilletStress>; 2])>,
) -> Option<String> {
    use std::fmt::Write as _;
    let mut s = format!("{CSV_HEADER}\n");
    let mut any = false;
    for (deg, t, fillets) in positions {
        for (member, list) in ["pinion", "wheel"].iter().zip(fillets) {
            for f in list {
                any = true;
                let _ = writeln!(
                    s,
                    "{deg},{t},{member},{},{},{},{},{},{},{},{}",
                    f.tooth,
                    if f.loaded_side { "loaded" } else { "opposite" },
                    f.max_principal_pa * 1e-6,
                    f.max_xi,
                    f.max_height,
                    f.min_principal_pa * 1e-6,
                    f.min_xi,
                    f.min_height
                );
            }
        }
    }
    any.then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fillet(tooth: usize, loaded_side: bool, max: f64, min: f64) -> FilletStress {
        FilletStress {
            tooth,
            loaded_side,
            max_principal_pa: max,
            max_xi: 0.5,
            max_height: 0.4,
            min_principal_pa: min,
            min_xi: 0.3,
            min_height: 0.6,
        }
    }

    /// Over two positions the tension comes from the loaded fillets only
    /// and the compression from the other ones, with their position and
    /// tooth; a position without fillets gives no summary.
    #[test]
    fn summary_takes_tension_from_loaded_fillets_and_compression_from_the_others() {
        let a = [
            vec![
                fillet(1, true, 100e6, -5e6),
                fillet(1, false, 150e6, -120e6),
            ],
            vec![fillet(42, true, 90e6, -1e6), fillet(42, false, 5e6, -95e6)],
        ];
        let b = [
            vec![
                fillet(2, true, 110e6, -300e6),
                fillet(2, false, 10e6, -80e6),
            ],
            vec![fillet(41, true, 80e6, -1e6), fillet(41, false, 5e6, -99e6)],
        ];
        let s = summarize([(0.0, Some(&a)), (0.5, Some(&b))].into_iter()).unwrap();
        assert_eq!(
            (s.pinion.tension_mpa, s.pinion.tension_at.tooth),
            (110.0, 2)
        );
        assert_eq!(s.pinion.tension_at.pinion_rotation_deg, 0.5);
        assert_eq!(
            (s.pinion.compression_mpa, s.pinion.compression_at.tooth),
            (-120.0, 1)
        );
        assert_eq!(
            (s.wheel.tension_mpa, s.wheel.compression_mpa),
            (90.0, -99.0)
        );
        assert!(summarize([(0.0, Some(&a)), (0.5, None)].into_iter()).is_none());
    }

    /// The closed form gives nalgebra's symmetric eigenvalues of random
    /// tensors to 1e-12 of their size, and of diagonal and (nearly)
    /// repeated-root ones to 1e-8: where two roots nearly coincide, acos
    /// near ±1 loses half the digits (√ε ≈ 1.5e-8), far below anything a
    /// stress is read to.
    #[test]
    fn closed_form_principal_stresses_equal_the_eigenvalues() {
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 400e6
        };
        let mut cases: Vec<Stress> = (0..200).map(|_| std::array::from_fn(|_| rnd())).collect();
        cases.push([3.0, 1.0, 2.0, 0.0, 0.0, 0.0]);
        cases.push([1.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
        cases.push([2.0, 2.0, 5.0, 0.0, 0.0, 1e-9]);
        for s in cases {
            let m = nalgebra::Matrix3::new(s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2]);
            let mut ev: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
            ev.sort_by(|a, b| b.total_cmp(a));
            let p = principal(s);
            let scale = s.iter().fold(1e-300f64, |a, v| a.max(v.abs()));
            let gap = (ev[0] - ev[1]).min(ev[1] - ev[2]);
            let tol = if gap > 1e-3 * scale { 1e-12 } else { 1e-8 };
            for k in 0..3 {
                assert!(
                    (p[k] - ev[k]).abs() <= tol * scale,
                    "{s:?}: {p:?} against {ev:?}"
                );
            }
        }
    }

    /// A uniaxial tension σ and a pure shear τ: principal values (σ, 0, 0)
    /// and (τ, 0, −τ); the extremes take the tension's point for σ₁ and
    /// the shear's for σ₃.
    #[test]
    fn extremes_of_a_uniaxial_tension_and_a_pure_shear() {
        let t = [5.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let q = [0.0, 0.0, 0.0, 0.0, 0.0, 2.0];
        let p = principal(q);
        assert!((p[0] - 2.0).abs() < 1e-12 && p[1].abs() < 1e-12 && (p[2] + 2.0).abs() < 1e-12);
        let e = fillet_extremes(3, true, &[0.1, 0.7], &[0.2, 0.9], &[t, q]);
        assert_eq!((e.tooth, e.loaded_side), (3, true));
        assert!((e.max_principal_pa - 5.0).abs() < 1e-12);
        assert_eq!((e.max_xi, e.max_height), (0.1, 0.2));
        assert!((e.min_principal_pa + 2.0).abs() < 1e-12);
        assert_eq!((e.min_xi, e.min_height), (0.7, 0.9));
    }
}
