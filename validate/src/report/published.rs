//! Published reference values: the files a design's `[published]` table
//! names (`reference/published/` for the white-paper pair).

use geometry::design::PublishedDesign;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A published value to compare with, and where it comes from.
#[derive(Debug, Clone, Serialize)]
pub struct Published {
    pub value: f64,
    pub source: String,
}

/// The NLFEA peak-to-peak TE at 1 N·m, standard blank (Table 3), when the
/// design names a published loaded-TE table with a 1 N·m row.
pub fn te_ptp_1nm(published: &PublishedDesign) -> Result<Option<Published>, PublishedError> {
    let Some(t) = PublishedTeTables::of(published)? else {
        return Ok(None);
    };
    let Some(row) = t.row(false, 1.0) else {
        return Ok(None);
    };
    Ok(Some(Published {
        value: row.ptp_te_nlfea_urad,
        source: format!(
            "white paper Table 3, NLFEA, standard blank ({})",
            t.source.split(',').next().unwrap_or("")
        ),
    }))
}

/// One load of the white paper's Tables 3–4: the multibody element's and
/// the NLFEA's mean and peak-to-peak TE, µrad.
#[derive(Debug, Clone, Deserialize)]
pub struct PublishedTeRow {
    pub load_nm: f64,
    pub mean_te_multibody_urad: f64,
    pub mean_te_nlfea_urad: f64,
    pub ptp_te_multibody_urad: f64,
    pub ptp_te_nlfea_urad: f64,
}

/// The white paper's Tables 3 (standard blank) and 4 (lightweight blank).
#[derive(Debug, Clone, Deserialize)]
pub struct PublishedTeTables {
    pub source: String,
    pub standard_blank: Vec<PublishedTeRow>,
    pub lightweight_blank: Vec<PublishedTeRow>,
}

impl PublishedTeTables {
    /// The tables the design's `[published] loaded_te` names.
    pub fn of(published: &PublishedDesign) -> Result<Option<Self>, PublishedError> {
        published.loaded_te.as_deref().map(read_toml).transpose()
    }

    /// The row of `blank` at `load_nm`, if printed.
    pub fn row(&self, lightweight: bool, load_nm: f64) -> Option<&PublishedTeRow> {
        let rows = if lightweight {
            &self.lightweight_blank
        } else {
            &self.standard_blank
        };
        rows.iter().find(|r| r.load_nm == load_nm)
    }
}

/// A published table that the design names but that cannot be read.
#[derive(Debug, thiserror::Error)]
#[error("{}: published table named in the design's [published]: {message}", .path.display())]
pub struct PublishedError {
    pub path: PathBuf,
    pub message: String,
}

/// Reads a published TOML table.
pub fn read_toml<T: for<'de> Deserialize<'de>>(path: &Path) -> Result<T, PublishedError> {
    let err = |message: String| PublishedError {
        path: path.to_path_buf(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| err(e.to_string()))?;
    toml::from_str(&text).map_err(|e| err(e.to_string()))
}

/// A value a seed prints, and where (table, figure or section).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Quoted {
    pub value: f64,
    pub source: String,
}

/// What seed 001 or 002 publishes about its load run and its impact law
/// (`reference/published/seed00{1,2}_contact_law.toml`); None where it
/// gives no number.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeedContactLaw {
    /// The seed document.
    pub source: String,
    pub notes: Vec<String>,
    /// Seed number as in the scene names (`seed001_impact`).
    pub id: String,
    /// Short description: pair, code.
    pub title: String,
    /// Mean wheel speed (°/s) and its relative difference to the kinematic
    /// speed (%, as the seed prints it: unsigned).
    pub wheel_speed_deg_s: Option<Quoted>,
    pub wheel_speed_error_percent: Option<Quoted>,
    /// Mean and largest tangential force (N), the seed's 2T/d (N) and the
    /// relative difference (%, on the base of the simulated mean).
    pub tangential_force_n: Option<Quoted>,
    pub tangential_force_max_n: Option<Quoted>,
    pub tangential_force_theory_n: Option<Quoted>,
    pub tangential_force_error_percent: Option<Quoted>,
    /// The seed's output interval, s (its simulation steps over its time).
    pub output_interval_s: Option<Quoted>,
    /// Mean and largest |ω₂ − kinematic|, °/s.
    pub speed_fluctuation_mean_deg_s: Option<Quoted>,
    pub speed_fluctuation_max_deg_s: Option<Quoted>,
    /// Mean and largest |F_t − mean|, N.
    pub force_fluctuation_mean_n: Option<Quoted>,
    pub force_fluctuation_max_n: Option<Quoted>,
    /// What the seed says about the meshing force, when it gives no number.
    pub mesh_force_statement: Option<String>,
    /// The impact law's parameters as printed: K, e, C (N·s/mm), d (mm),
    /// static and dynamic friction, and where they are printed.
    pub stiffness: Quoted,
    pub exponent: f64,
    pub damping_n_s_per_mm: f64,
    pub depth_mm: f64,
    pub static_friction: f64,
    pub dynamic_friction: f64,
    pub parameters_source: String,
}

/// Seed 003's test rig (`reference/published/seed003_test_rig.toml`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed003 {
    pub source: String,
    pub notes: Vec<String>,
    pub measured_source: String,
    /// (pinion, wheel).
    pub teeth: [f64; 2],
    /// μ₀ and μ_r of its friction coefficient.
    pub friction_mu0: f64,
    pub friction_mur: f64,
    pub measured: Vec<Seed003Measured>,
    /// Table 2: roughness, fractal dimension and characteristic scale
    /// coefficient per finishing process.
    pub table2: Vec<Seed003Table2Row>,
    /// Table 4: the 30 one-second values of the test-rig comparison, mm/s.
    pub table4: Vec<Seed003Table4Row>,
}

/// One row of seed 003's Table 2.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed003Table2Row {
    pub ra_um: f64,
    pub dimension: f64,
    pub scale_coefficient: f64,
}

/// One row of seed 003's Table 4 (vibration velocity, mm/s).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed003Table4Row {
    pub time_s: f64,
    pub simulated_77nm: f64,
    pub measured_77nm: f64,
    pub simulated_105nm: f64,
    pub measured_105nm: f64,
}

impl Seed003 {
    /// Means over Table 4's rows: (simulated, measured) at 77 N·m and at
    /// 105 N·m, mm/s.
    pub fn table4_means(&self) -> [[f64; 2]; 2] {
        let n = self.table4.len().max(1) as f64;
        let mean =
            |f: &dyn Fn(&Seed003Table4Row) -> f64| self.table4.iter().map(f).sum::<f64>() / n;
        [
            [mean(&|r| r.simulated_77nm), mean(&|r| r.measured_77nm)],
            [mean(&|r| r.simulated_105nm), mean(&|r| r.measured_105nm)],
        ]
    }
}

/// One loader torque of seed 003's test rig.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed003Measured {
    pub loader_torque_nm: f64,
    /// Measured mean vibration velocity, mm/s.
    pub measured_velocity_mm_s: f64,
    /// Seed 003's own simulated value, mm/s.
    pub simulated_velocity_mm_s: f64,
}

/// Seed 004's published numbers (`reference/published/seed004_lumped.toml`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004 {
    pub source: String,
    pub notes: Vec<String>,
    pub table3_source: String,
    pub table3: Vec<Seed004Direction>,
    pub mean_mesh_stiffness_n_per_m: f64,
    pub mean_mesh_stiffness_source: String,
    pub impact_force_n: f64,
    pub impact_force_source: String,
    pub stiffness_harmonics: usize,
    pub te_slope: Seed004TeSlope,
    pub table4: Seed004Table4,
}

/// A direction of seed 004's Table 3.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004Direction {
    pub direction: String,
    pub rms_acceleration_m_s2: f64,
    /// Share of the mesh normal's RMS, %.
    pub share_percent: f64,
}

/// Seed 004's TE-slope study.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004TeSlope {
    pub source: String,
    /// RMS rise along the mesh normal from the first to the last slope, %.
    pub rms_rise_percent: f64,
    pub rows: Vec<Seed004TeSlopeRow>,
}

/// One TE slope m′₂₁ and its largest impact force (N).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004TeSlopeRow {
    pub m21: f64,
    pub impact_force_n: f64,
}

/// Seed 004's Table 4 (design contact ratio).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004Table4 {
    pub source: String,
    pub te_slope_m21: f64,
    pub rows: Vec<Seed004Table4Row>,
}

/// One row of seed 004's Table 4.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Seed004Table4Row {
    pub contact_ratio: f64,
    pub mesh_stiffness_n_per_m: f64,
    pub impact_force_n: f64,
    pub rms_acceleration_m_s2: f64,
}

/// Parses a published table built into the binary; a table that does not
/// parse (a renamed or missing field, an unknown one) is a build defect
/// that the tests of this module catch.
fn embedded<T: for<'de> Deserialize<'de>>(file: &str, text: &str) -> T {
    toml::from_str(text).unwrap_or_else(|e| panic!("reference/published/{file}: {e}"))
}

static SEED_CONTACT_LAWS: std::sync::LazyLock<[SeedContactLaw; 2]> =
    std::sync::LazyLock::new(|| {
        [
            embedded(
                "seed001_contact_law.toml",
                include_str!("../../../reference/published/seed001_contact_law.toml"),
            ),
            embedded(
                "seed002_contact_law.toml",
                include_str!("../../../reference/published/seed002_contact_law.toml"),
            ),
        ]
    });

static SEED003: std::sync::LazyLock<Seed003> = std::sync::LazyLock::new(|| {
    embedded(
        "seed003_test_rig.toml",
        include_str!("../../../reference/published/seed003_test_rig.toml"),
    )
});

static SEED004: std::sync::LazyLock<Seed004> = std::sync::LazyLock::new(|| {
    embedded(
        "seed004_lumped.toml",
        include_str!("../../../reference/published/seed004_lumped.toml"),
    )
});

/// Seeds 001 and 002's published load runs and impact laws, in order.
pub fn seed_contact_laws() -> &'static [SeedContactLaw; 2] {
    &SEED_CONTACT_LAWS
}

/// Seed 003's test rig.
pub fn seed003() -> &'static Seed003 {
    &SEED003
}

/// Seed 004's published numbers.
pub fn seed004() -> &'static Seed004 {
    &SEED004
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every seed table parses and holds every row the report shows.
    #[test]
    fn every_published_seed_table_parses_with_all_its_rows() {
        let [s1, s2] = seed_contact_laws();
        assert_eq!((s1.id.as_str(), s2.id.as_str()), ("001", "002"));
        assert!(s1.wheel_speed_deg_s.is_some() && s1.mesh_force_statement.is_some());
        for (name, q) in [
            ("wheel_speed_deg_s", &s2.wheel_speed_deg_s),
            ("wheel_speed_error_percent", &s2.wheel_speed_error_percent),
            ("tangential_force_n", &s2.tangential_force_n),
            ("tangential_force_max_n", &s2.tangential_force_max_n),
            ("output_interval_s", &s2.output_interval_s),
            ("tangential_force_theory_n", &s2.tangential_force_theory_n),
            (
                "tangential_force_error_percent",
                &s2.tangential_force_error_percent,
            ),
            (
                "speed_fluctuation_mean_deg_s",
                &s2.speed_fluctuation_mean_deg_s,
            ),
            (
                "speed_fluctuation_max_deg_s",
                &s2.speed_fluctuation_max_deg_s,
            ),
            ("force_fluctuation_mean_n", &s2.force_fluctuation_mean_n),
            ("force_fluctuation_max_n", &s2.force_fluctuation_max_n),
        ] {
            assert!(q.is_some(), "seed 002 prints {name}");
        }
        assert_eq!(seed003().measured.len(), 2);
        assert_eq!(seed003().table2.len(), 3);
        assert_eq!(seed003().table4.len(), 30);
        // Table 4's means are not the text's 4.195 / 4.384 mm/s.
        let m = seed003().table4_means();
        assert!(
            (m[0][1] - 4.123).abs() < 1e-3 && (m[1][1] - 4.413).abs() < 1e-3,
            "{m:?}"
        );
        assert!(
            (m[0][0] - 4.055).abs() < 1e-3 && (m[1][0] - 4.135).abs() < 1e-3,
            "{m:?}"
        );
        let s4 = seed004();
        assert_eq!(s4.table3.len(), 7);
        assert_eq!(s4.te_slope.rows.len(), 3);
        assert_eq!(s4.table4.rows.len(), 3);
    }

    /// A field renamed in a table is refused, not read as absent.
    #[test]
    fn a_renamed_published_field_is_refused() {
        let text = include_str!("../../../reference/published/seed002_contact_law.toml")
            .replace("[tangential_force_n]", "[tangential_force]");
        assert!(toml::from_str::<SeedContactLaw>(&text).is_err());
        let text = include_str!("../../../reference/published/seed004_lumped.toml")
            .replace("rms_acceleration_m_s2 = 299.89", "rms_m_s2 = 299.89");
        assert!(toml::from_str::<Seed004>(&text).is_err());
    }
}
