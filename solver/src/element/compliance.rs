//! The reduced model's body compliance at the slices: C = C_pinion + C_wheel,
//! interpolated from the stiffness files' global influence fields.
//!
//! A stiffness file holds G[s][o][a][b], the normal approach at grid point b
//! of tooth (solved[s] + o) under a unit normal load at grid point a of tooth
//! solved[s]. For slices k, l with interpolation weights W_k, W_l on the grid
//! (bicubic in the flank parameters, see [`crate::element::interp`]) the member's part
//! is C(k, l) = W_kᵀ G[s(k)][o(k, l)] W_l: smooth in the loaded and in the
//! responding point. Pinion tooth j meshes with wheel tooth −j, so the pinion
//! offset is j_l − j_k and the wheel offset j_k − j_l.

use crate::element::interp::{grid_weights, Weights};
use crate::SolverError;
use formats::root_stress::Stress;
use formats::stiffness_file::{RootStressBlock, StiffnessData};
use geometry::Material;

/// One member's influence data, ready for interpolation.
#[derive(Debug, Clone)]
pub struct MemberCompliance {
    pub member: String,
    pub teeth: usize,
    pub axisymmetric: bool,
    xi: Vec<f64>,
    eta: Vec<f64>,
    np: usize,
    solved: Vec<usize>,
    offsets: Vec<i32>,
    global: Vec<f64>,
    depth: Vec<f64>,
    /// Body tooth of pair-numbering tooth t: t + tooth_shift (the coast
    /// model's wheel, see `geometry::pair::OppositePlacement`).
    tooth_shift: i64,
    pub material: Material,
    /// The stiffness file's root-stress coefficients, when it has them.
    root: Option<RootCoefficients>,
}

/// A stiffness file's root-stress coefficients as the LTCA holds them: the
/// stress values in single precision. The sum over grid loads reads every
/// coefficient of the loaded teeth once per position and torque, so its
/// cost is the memory it streams; f32 halves it (measured in the LTCA
/// bench) at a relative rounding of 6e-8 per coefficient, far below the
/// FE's own discretization error of the stresses. The file keeps f64.
#[derive(Debug, Clone)]
struct RootCoefficients {
    offsets: Vec<i32>,
    xi: Vec<f64>,
    height: Vec<f64>,
    stress: Vec<f32>,
}

impl RootCoefficients {
    fn new(b: RootStressBlock) -> Self {
        RootCoefficients {
            offsets: b.offsets,
            xi: b.xi,
            height: b.height,
            stress: b.stress.iter().map(|&v| v as f32).collect(),
        }
    }

    /// Fillet points of one tooth (both fillets).
    fn points(&self) -> usize {
        self.xi.len()
    }
}

impl MemberCompliance {
    /// The member's data with every reciprocal pair of blocks replaced by
    /// its mean: G[s][o] and G[s′][−o]ᵀ, where s′ serves tooth solved[s] + o,
    /// become equal (Maxwell–Betti; the FE gives them equal up to round-off
    /// and, across teeth of an axisymmetric body, the mesh's departure from
    /// rotational symmetry). The assembly then takes such a pair's coupling
    /// from one of them, see [`MemberCompliance::mirrored`].
    pub fn new(d: StiffnessData, material: Material) -> Self {
        let mut m = MemberCompliance {
            member: d.member.clone(),
            teeth: d.teeth,
            axisymmetric: d.axisymmetric,
            np: d.points(),
            xi: d.xi,
            eta: d.eta,
            solved: d.solved_teeth.iter().map(|&t| t as usize).collect(),
            offsets: d.offsets,
            global: d.global,
            depth: d.depth_h,
            tooth_shift: 0,
            material,
            root: d.root_stress.map(RootCoefficients::new),
        };
        m.symmetrize();
        m
    }

    /// Start of block (s, offset index oi) in `global`.
    fn block_start(&self, s: usize, oi: usize) -> usize {
        (s * self.offsets.len() + oi) * self.np * self.np
    }

    /// The reciprocal partner (s′, index of −o) of block (s, offset index
    /// oi), where stored.
    fn partner(&self, s: usize, oi: usize) -> Option<(usize, usize)> {
        let o = self.offsets[oi];
        let tooth = self.solved[s] as i64 + o as i64;
        let sp = self.body_index(tooth).ok()?;
        let op = self.offsets.iter().position(|&x| x == -o)?;
        Some((sp, op))
    }

    fn symmetrize(&mut self) {
        let np = self.np;
        for s in 0..self.solved.len() {
            for oi in 0..self.offsets.len() {
                let Some((sp, op)) = self.partner(s, oi) else {
                    continue;
                };
                let (x, y) = (self.block_start(s, oi), self.block_start(sp, op));
                if y < x {
                    continue; // met from its partner
                }
                for a in 0..np {
                    // On a block that is its own partner, the lower triangle only.
                    let bs = if x == y { 0..a + 1 } else { 0..np };
                    for b in bs {
                        let (i, j) = (x + a * np + b, y + b * np + a);
                        let mean = 0.5 * (self.global[i] + self.global[j]);
                        self.global[i] = mean;
                        self.global[j] = mean;
                    }
                }
            }
        }
    }

    /// Whether the coupling from solved tooth `s`'s loads to offset `o` is
    /// the transpose of a stored block (so that it need not be assembled
    /// twice).
    pub fn mirrored(&self, s: usize, o: i64) -> bool {
        self.offsets
            .iter()
            .position(|&x| x as i64 == o)
            .is_some_and(|oi| self.partner(s, oi).is_some())
    }

    /// The same data for a model whose tooth t is the body's tooth
    /// t + `shift`.
    pub fn with_tooth_shift(self, shift: i64) -> Self {
        MemberCompliance {
            tooth_shift: shift,
            ..self
        }
    }

    /// The body teeth whose data the stiffness file holds.
    pub fn solved_teeth(&self) -> &[usize] {
        &self.solved
    }

    /// Index of the solved tooth whose data serve tooth `tooth` (pair numbering, any sign).
    pub fn solved_index(&self, tooth: i64) -> Result<usize, SolverError> {
        self.body_index(tooth + self.tooth_shift)
    }

    /// Index of the solved tooth whose data serve the body's tooth `tooth`.
    fn body_index(&self, tooth: i64) -> Result<usize, SolverError> {
        if self.axisymmetric {
            return Ok(0);
        }
        let t = tooth.rem_euclid(self.teeth as i64) as usize;
        self.solved
            .iter()
            .position(|&s| s == t)
            .ok_or_else(|| SolverError::ToothNotSolved {
                member: self.member.clone(),
                tooth: t,
                solved: self.solved.clone(),
            })
    }

    /// Interpolation weights of the flank point (ξ, η).
    pub fn weights(&self, xi: f64, eta: f64) -> Weights {
        grid_weights(&self.xi, &self.eta, xi, eta)
    }

    /// Reference depth h at the point with weights `w` on solved tooth `s`, m.
    pub fn depth(&self, s: usize, w: &Weights) -> f64 {
        crate::element::interp::apply(w, &self.depth[s * self.np..(s + 1) * self.np])
    }

    /// Grid points of the contact grid.
    pub fn points(&self) -> usize {
        self.np
    }

    /// The fillet points' (ξ, height) and how many of them lie on the
    /// loaded flank's fillet (the first ones), when the file has root
    /// stress.
    pub fn root_points(&self) -> Option<(&[f64], &[f64], usize)> {
        self.root
            .as_ref()
            .map(|r| (&r.xi[..], &r.height[..], r.points() / 2))
    }

    /// Adds to `out` (one tensor per fillet point of the responding tooth,
    /// in the order of [`MemberCompliance::root_points`]; a shorter `out`
    /// takes the first points only, e.g. the loaded fillet's) the root
    /// stress of a force `force` (N) at the grid weights `w` on solved
    /// tooth `s`, seen at the tooth `offset` from it:
    /// σ += F Σ_a w_a S[s][offset][a]. False (nothing added) when the file
    /// has no root stress or not that offset.
    pub fn add_root_stress(
        &self,
        s: usize,
        offset: i64,
        w: &Weights,
        force: f64,
        out: &mut [Stress],
    ) -> bool {
        let Some(r) = &self.root else {
            return false;
        };
        let Some(ri) = r.offsets.iter().position(|&o| o as i64 == offset) else {
            return false;
        };
        let nf = r.points();
        let n = out.len().min(nf);
        // One axpy over the flat tensors per grid point.
        let flat = out[..n].as_flattened_mut();
        for &(a, x) in w.iter() {
            let at = ((s * r.offsets.len() + ri) * self.np + a) * nf * 6;
            let fx = force * x;
            for (o, &v) in flat.iter_mut().zip(&r.stress[at..at + n * 6]) {
                *o += fx * f64::from(v);
            }
        }
        true
    }

    /// The np × np block of solved tooth `s` responding at offset `o` (None beyond the stored teeth).
    fn block(&self, s: usize, o: i64) -> Option<&[f64]> {
        let oi = self.offsets.iter().position(|&x| x as i64 == o)?;
        let start = self.block_start(s, oi);
        Some(&self.global[start..start + self.np * self.np])
    }

    /// Adds this member's compliance between slice groups to `c` (row-major
    /// n × n): loads on slices `rows` of tooth `loaded`, responses on slices
    /// `cols` of tooth `loaded + offset` (member numbering).
    #[allow(clippy::too_many_arguments)]
    pub fn add_block(
        &self,
        s: usize,
        offset: i64,
        w_rows: &[&Weights],
        w_cols: &[&Weights],
        rows: &[usize],
        cols: &[usize],
        c: &mut [f64],
        n: usize,
    ) {
        let Some(g) = self.block(s, offset) else {
            return;
        };
        let np = self.np;
        // The sub-block of G on the grid points the weights touch (a band
        // along the contact lines), gathered once; then per loaded slice k
        // s_k = Σ_a W_k[a] G[a][·] over it and C[k][l] += Σ_b s_k[b] W_l[b].
        let (ra, rmap) = touched(w_rows, np);
        let (cb, cmap) = touched(w_cols, np);
        let ncb = cb.len();
        let mut gs = vec![0.0; ra.len() * ncb];
        for (dst, &a) in gs.chunks_exact_mut(ncb).zip(&ra) {
            let row = &g[a * np..(a + 1) * np];
            for (d, &b) in dst.iter_mut().zip(&cb) {
                *d = row[b];
            }
        }
        let w_cols: Vec<Vec<(usize, f64)>> = w_cols
            .iter()
            .map(|w| w.iter().map(|&(b, v)| (cmap[b], v)).collect())
            .collect();
        let mut s = vec![0.0; ncb];
        for (kk, wk) in w_rows.iter().enumerate() {
            s.fill(0.0);
            for &(a, x) in wk.iter() {
                let r = rmap[a];
                for (o, &v) in s.iter_mut().zip(&gs[r * ncb..(r + 1) * ncb]) {
                    *o += x * v;
                }
            }
            let row = &mut c[rows[kk] * n..(rows[kk] + 1) * n];
            for (wl, &l) in w_cols.iter().zip(cols) {
                row[l] += wl.iter().map(|&(b, v)| v * s[b]).sum::<f64>();
            }
        }
    }
}

/// The grid points that some of `weights` touch, ascending, and each grid
/// point's place in that list.
fn touched(weights: &[&Weights], np: usize) -> (Vec<usize>, Vec<usize>) {
    let mut on = vec![false; np];
    for w in weights {
        for &(a, _) in w.iter() {
            on[a] = true;
        }
    }
    let list: Vec<usize> = (0..np).filter(|&a| on[a]).collect();
    let mut place = vec![usize::MAX; np];
    for (i, &a) in list.iter().enumerate() {
        place[a] = i;
    }
    (list, place)
}

/// The two members' data.
#[derive(Debug, Clone)]
pub struct PairCompliance {
    pub pinion: MemberCompliance,
    pub wheel: MemberCompliance,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Five teeth, teeth 0–2 solved, offsets −1..1, a 3 × 4 grid, and
    /// deterministic pseudo-random, unsymmetric blocks.
    fn member() -> (StiffnessData, MemberCompliance) {
        let (gp, gf, no, ns) = (3, 4, 3, 3);
        let np = gp * gf;
        let mut state = 12345u64;
        let global = (0..ns * no * np * np)
            .map(|_| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                1e-9 * (1.0 + (state >> 33) as f64 / (1u64 << 31) as f64)
            })
            .collect();
        let d = StiffnessData {
            input_hash: String::new(),
            config: String::new(),
            member: "wheel".into(),
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
            solved_teeth: vec![0, 1, 2],
            offsets: vec![-1, 0, 1],
            depth_h: vec![1e-3; ns * np],
            total: Vec::new(),
            local: Vec::new(),
            global,
            root_stress: None,
        };
        (d.clone(), MemberCompliance::new(d, Material::STEEL))
    }

    /// Maxwell–Betti: after loading, the coupling from tooth t to tooth
    /// t + o is the transpose of that from t + o to t, and both are the mean
    /// of what the file held; a block whose partner tooth was not solved
    /// (tooth 2 → 3, tooth 0 → 4) is left as it was.
    #[test]
    fn reciprocal_blocks_are_each_others_transpose_and_the_mean() {
        let (d, m) = member();
        let np = d.points();
        for s in 0..3usize {
            for (oi, &o) in d.offsets.iter().enumerate() {
                let t = s as i64 + o as i64;
                let partner = (0..3).contains(&t);
                assert_eq!(m.mirrored(s, o as i64), partner, "tooth {s} offset {o}");
                let block = m.block(s, o as i64).unwrap();
                for a in 0..np {
                    for b in 0..np {
                        let here = d.global_at(s, oi, a, b);
                        if !partner {
                            assert_eq!(block[a * np + b], here);
                            continue;
                        }
                        let ti = t as usize;
                        let back = d.offsets.iter().position(|&x| x == -o).unwrap();
                        let mean = 0.5 * (here + d.global_at(ti, back, b, a));
                        assert!((block[a * np + b] - mean).abs() <= 1e-15 * mean);
                        assert_eq!(
                            block[a * np + b],
                            m.block(ti, -o as i64).unwrap()[b * np + a]
                        );
                    }
                }
            }
        }
    }

    /// A model whose tooth t is the body's tooth t + 1 (the coast model's
    /// wheel of the white-paper pair) takes tooth t's data from the body's
    /// tooth t + 1, wrapping round the wheel, and says which body tooth it
    /// missed; the reciprocal pairing of the blocks stays the body's.
    #[test]
    fn shifted_model_tooth_t_takes_the_body_tooth_t_plus_shift() {
        let (_, m) = member();
        let shifted = m.clone().with_tooth_shift(1);
        for t in [-1i64, 0, 1] {
            assert_eq!(
                shifted.solved_index(t).unwrap(),
                m.solved_index(t + 1).unwrap()
            );
        }
        assert_eq!(shifted.solved_index(-6).unwrap(), 0);
        match shifted.solved_index(2) {
            Err(SolverError::ToothNotSolved { tooth, .. }) => assert_eq!(tooth, 3),
            other => panic!("{other:?}"),
        }
        for s in 0..3 {
            for o in -1..=1 {
                assert_eq!(shifted.mirrored(s, o), m.mirrored(s, o));
            }
        }
    }
}
