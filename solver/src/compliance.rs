//! The reduced model's body compliance at the slices: C = C_pinion + C_wheel,
//! interpolated from the stiffness files' global influence fields.
//!
//! A stiffness file holds G[s][o][a][b], the normal approach at grid point b
//! of tooth (solved[s] + o) under a unit normal load at grid point a of tooth
//! solved[s]. For slices k, l with interpolation weights W_k, W_l on the grid
//! (bicubic in the flank parameters, see [`crate::interp`]) the member's part
//! is C(k, l) = W_kᵀ G[s(k)][o(k, l)] W_l: smooth in the loaded and in the
//! responding point. Pinion tooth j meshes with wheel tooth −j, so the pinion
//! offset is j_l − j_k and the wheel offset j_k − j_l.

use crate::interp::{grid_weights, Weights};
use crate::SolverError;
use fem::Material;
use preprocess::stiffness_file::StiffnessData;

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
    pub material: Material,
}

impl MemberCompliance {
    pub fn new(d: StiffnessData, material: Material) -> Self {
        MemberCompliance {
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
            material,
        }
    }

    /// Index of the solved tooth whose data serve tooth `tooth` (pair numbering, any sign).
    pub fn solved_index(&self, tooth: i64) -> Result<usize, SolverError> {
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
        crate::interp::apply(w, &self.depth[s * self.np..(s + 1) * self.np])
    }

    /// The np × np block of solved tooth `s` responding at offset `o` (None beyond the stored teeth).
    fn block(&self, s: usize, o: i64) -> Option<&[f64]> {
        let oi = self.offsets.iter().position(|&x| x as i64 == o)?;
        let no = self.offsets.len();
        let n2 = self.np * self.np;
        let start = (s * no + oi) * n2;
        Some(&self.global[start..start + n2])
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
