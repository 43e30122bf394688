//! The line-load check of the reduced model's compliance split: a
//! Hertzian line load on one tooth of a member (the standard pinion by
//! default; the wheel and the lightweight blank as chosen), solved on a fine
//! FE mesh, against the reduced-order prediction global FE +
//! Weber–Banaschek.
//!
//! The load runs along the loaded flank of tooth 0 at a fixed profile
//! parameter η₀ (a profile row of the contact grid) over the whole active
//! face width. Across the line it is a Hertz pressure of half-width b and
//! line load q:
//!
//!   p(s) = 2q/(πb) · √(1 − s²/b²),   |s| < b,
//!
//! with s the distance from the line along the flank, pressed along the
//! flank's inward normal. The fine-mesh approach is the normal displacement
//! (into the tooth) of the line's surface points at the grid columns, the
//! bore clamped as in the stiffness files.
//!
//! The reduced model puts the same load on the grid: the force q · Lⱼ of
//! column j's stretch of line at grid point (j, η₀), and predicts the
//! approach at grid point j as
//!
//!   wⱼ = Σₖ G(k → j) q Lₖ + w_WB(q, b, hⱼ),
//!
//! G the stiffness file's global field (total − local) and w_WB the
//! half-plane approach to the stored depth hⱼ
//! ([`solver::element::weber_banaschek::body_approach`]).

mod load_line;
mod run;
#[cfg(test)]
mod tests;

pub use load_line::{hertz_pressure, strip_forces, surface_value, LoadLine};
pub use run::run;

use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// One half-width's comparison.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoadCase {
    pub half_width_mm: f64,
    /// Fine-mesh elements across the strip (2b over the mean flank element
    /// size along the profile).
    pub elements_across: f64,
    /// The applied force ∫ p dA over q · L (1 when the strip lies on the
    /// meshed flank and is integrated exactly).
    pub applied_load_ratio: f64,
    /// Per compared grid column: ξ, fine FE approach, global part, WB part,
    /// reduced prediction (µm), and the difference (%).
    pub xi: Vec<f64>,
    pub fe_um: Vec<f64>,
    pub global_um: Vec<f64>,
    pub weber_banaschek_um: Vec<f64>,
    pub reduced_um: Vec<f64>,
    pub difference_pct: Vec<f64>,
    pub mean_abs_difference_pct: f64,
    pub max_abs_difference_pct: f64,
}

/// The reduced model's approach at the grid columns of row `row`: the
/// global field `global(k, j)` (load at column k, response at column j)
/// under forces `forces[k]`, plus `wb[j]`.
pub fn reduced_prediction(
    global: impl Fn(usize, usize) -> f64,
    forces: &[f64],
    wb: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let g: Vec<f64> = (0..forces.len())
        .map(|j| {
            forces
                .iter()
                .enumerate()
                .map(|(k, f)| global(k, j) * f)
                .sum()
        })
        .collect();
    let total = g.iter().zip(wb).map(|(a, b)| a + b).collect();
    (g, total)
}

/// What `validate line-load` solves.
#[derive(Debug, Clone)]
pub struct LineLoadStudy {
    /// The loaded member and its blank (the stiffness file and the fine
    /// meshes of that body; its tooth 0 must be solved and refined).
    pub member: geometry::design::Member,
    pub blank: geometry::scene::Blank,
    /// Fine mesh levels (medium, reference).
    pub levels: Vec<String>,
    /// Hertz half-widths, m.
    pub half_widths: Vec<f64>,
    /// Line load, N/m (the comparison is linear in it).
    pub q: f64,
    /// Profile row of the contact grid the line runs along (default: the
    /// middle row).
    pub row: Option<usize>,
    /// Grid columns left out at each end (toe and heel) in the statistics.
    pub end_columns: usize,
    /// Load only the grid columns first..=last (a line load over part of
    /// the face width: a concentrated contact), compared on them; None:
    /// the whole line, compared inside the end columns.
    pub loaded_columns: Option<(usize, usize)>,
    /// Where the approach is compared: on the loaded tooth (0) or on a
    /// neighbour (±1, …: the coupling between teeth, without the local
    /// term).
    pub response_offset: i32,
}

/// One fine mesh level's comparison.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoadLevel {
    pub level: String,
    pub mesh: String,
    pub mesh_sha256: String,
    pub dofs: usize,
    pub factor_s: f64,
    /// Length of the load line that lies on the meshed flank, to the
    /// line's sampling (ten points per grid column), mm.
    pub line_on_mesh_mm: f64,
    /// Mean flank element size along the profile, mm.
    pub profile_element_mm: f64,
    pub cases: Vec<LineLoadCase>,
}

/// The study's result (`out/<scene>/reference/line_load.json` for the
/// standard pinion, `line_load_<member>_<blank>.json` for another body).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LineLoad {
    pub member: geometry::design::Member,
    /// (Results written before the blank was recorded are the standard
    /// pinion's.)
    #[serde(default = "standard_blank")]
    pub blank: geometry::scene::Blank,
    /// The tooth (relative to the loaded tooth 0) whose approach is
    /// compared.
    #[serde(default)]
    pub response_offset: i32,
    /// The grid columns loaded, where the line covered only part of the
    /// face width.
    #[serde(default)]
    pub loaded_columns: Option<(usize, usize)>,
    pub flank: String,
    pub stiffness_file: String,
    /// SHA-256 of the stiffness file's mesh (the reduced level's).
    pub stiffness_mesh_sha256: String,
    pub line_load_n_per_m: f64,
    pub profile_row: usize,
    pub eta: f64,
    pub line_length_mm: f64,
    /// Columns compared in the statistics (the others lie within
    /// `end_columns` of the toe or heel).
    pub compared_columns: Vec<usize>,
    pub levels: Vec<LineLoadLevel>,
}

fn standard_blank() -> geometry::scene::Blank {
    geometry::scene::Blank::Standard
}

/// The file a study of `member` with `blank` writes beside the reference
/// sweep: `line_load.json` for the standard pinion (the report's),
/// `line_load_<member>_<blank>.json` otherwise.
/// A comparison on a neighbouring tooth adds `_tooth<offset>`.
pub fn file_name(
    member: geometry::design::Member,
    blank: geometry::scene::Blank,
    response_offset: i32,
) -> String {
    let standard_pinion = (member, blank)
        == (
            geometry::design::Member::Pinion,
            geometry::scene::Blank::Standard,
        );
    match (standard_pinion, response_offset) {
        (true, 0) => "line_load.json".into(),
        (_, 0) => format!("line_load_{}_{}.json", member.name(), blank.name()),
        (_, o) => format!(
            "line_load_{}_{}_tooth{o:+}.json",
            member.name(),
            blank.name()
        ),
    }
}

impl LineLoad {
    /// Whether the meshes under `scene_meshes` are still the ones the study
    /// ran on.
    pub fn current(&self, scene_meshes: &std::path::Path) -> bool {
        let same = |level: &str, hash: &str| {
            let stem = formats::paths::stem_named(self.member, self.blank, level);
            preprocess::stiffness_stage::sha256_file(&formats::paths::msh(scene_meshes, &stem))
                .is_ok_and(|h| h == hash)
        };
        same("reduced", &self.stiffness_mesh_sha256)
            && self.levels.iter().all(|l| same(&l.level, &l.mesh_sha256))
    }

    /// The report's section.
    pub fn markdown(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "\n## Line load: global FE + Weber–Banaschek against fine-mesh FE\n"
        );
        let _ = writeln!(
            s,
            "A Hertzian line load (q = {:.0} N/mm, half-width b) along the {} flank of {} tooth 0 ({} blank) at profile row {} (η = {:.3}) {}, bore clamped (`validate line-load`). Fine-mesh FE: the normal approach {} at the grid columns. Reduced model: the stiffness file's global field (total − local, reduced level) under the column forces q·L{}. Compared on columns {}..={}{}. The project's bound is 3 %.\n",
            self.line_load_n_per_m * 1e-3,
            self.flank,
            self.member.name(),
            self.blank.name(),
            self.profile_row,
            self.eta,
            match self.loaded_columns {
                None => format!("over the whole face width ({:.1} mm)", self.line_length_mm),
                Some((a, b)) => format!("over grid columns {a}..={b} only ({:.1} mm)", self.line_length_mm),
            },
            match self.response_offset {
                0 => "of the line's surface points".to_string(),
                o => format!("of the flank of tooth {o:+}, the loaded tooth's neighbour,"),
            },
            match self.response_offset {
                0 => " plus the Weber–Banaschek approach to the stored depth h",
                _ => " (no local term on another tooth)",
            },
            self.compared_columns.first().unwrap_or(&0),
            self.compared_columns.last().unwrap_or(&0),
            match self.loaded_columns {
                None => " (the end columns, where the plane-strain WB term does not hold, left out)",
                Some(_) => "",
            },
        );
        let _ = writeln!(s, "| FE mesh | dofs | flank element, mm | b, mm | elements across 2b | FE approach, µm (mid column) | global + WB, µm | of which WB | mean \\|diff\\| % | max \\|diff\\| % |");
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
        for l in &self.levels {
            for c in &l.cases {
                let mid = c.fe_um.len() / 2;
                let _ = writeln!(
                    s,
                    "| {} | {} | {:.3} | {:.3} | {:.1} | {:.3} | {:.3} | {:.3} | {:.2} | {:.2} |",
                    l.level,
                    l.dofs,
                    l.profile_element_mm,
                    c.half_width_mm,
                    c.elements_across,
                    c.fe_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.reduced_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.weber_banaschek_um.get(mid).copied().unwrap_or(f64::NAN),
                    c.mean_abs_difference_pct,
                    c.max_abs_difference_pct
                );
            }
        }
    }
}
