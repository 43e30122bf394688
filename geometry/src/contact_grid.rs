//! The contact grid of a loaded flank: the points where the reduced model's
//! unit loads act and its compliance is tabulated (shared by the stiffness
//! files' writer and their readers).

use crate::error::GeometryError;
use crate::flank::Flank;

/// Grid density on the loaded flank.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GridSize {
    pub profile: usize,
    pub face: usize,
}

/// The contact grid of tooth 0's loaded flank (member frame). Point index =
/// i_face · profile + i_profile; grid points are the centres of a regular
/// profile × face partition of the flank (fillet junction to tip, toe to heel).
#[derive(Debug, Clone)]
pub struct FlankGrid {
    pub size: GridSize,
    /// Normalised face-width parameter ξ of each face column.
    pub xi: Vec<f64>,
    /// Normalised profile parameter η of each profile row.
    pub eta: Vec<f64>,
    pub position: Vec<[f64; 3]>,
    /// Outward unit normal.
    pub normal: Vec<[f64; 3]>,
    /// Moment arm about the member axis of a unit force along −n, m.
    pub lever: Vec<f64>,
}

/// Rotation about the member axis z.
pub fn rotate_z(p: [f64; 3], a: f64) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]]
}

impl FlankGrid {
    /// Grid of `size` on `flank`.
    pub fn new(flank: &Flank, size: GridSize) -> Result<FlankGrid, GeometryError> {
        let xi: Vec<f64> = (0..size.face)
            .map(|i| (i as f64 + 0.5) / size.face as f64)
            .collect();
        let eta: Vec<f64> = (0..size.profile)
            .map(|j| (j as f64 + 0.5) / size.profile as f64)
            .collect();
        let mut g = FlankGrid {
            size,
            xi: xi.clone(),
            eta: eta.clone(),
            position: Vec::new(),
            normal: Vec::new(),
            lever: Vec::new(),
        };
        for &x in &xi {
            for &e in &eta {
                let p = flank.at_unit(x, e)?;
                let f = p.normal.map(|c| -c);
                g.lever.push(p.pos[0] * f[1] - p.pos[1] * f[0]);
                g.position.push(p.pos);
                g.normal.push(p.normal);
            }
        }
        Ok(g)
    }

    pub fn len(&self) -> usize {
        self.position.len()
    }

    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Spacing of neighbouring points in space: (largest along face, largest along profile).
    pub fn spacing(&self) -> (f64, f64) {
        let np = self.size.profile;
        let mut sf: f64 = 0.0;
        let mut sp: f64 = 0.0;
        for i in 0..self.len() {
            if i + np < self.len() {
                sf = sf.max(dist(self.position[i], self.position[i + np]));
            }
            if (i + 1) % np != 0 {
                sp = sp.max(dist(self.position[i], self.position[i + 1]));
            }
        }
        (sf, sp)
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
