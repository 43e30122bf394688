//! Column names of the CSV files the stages write and the report reads
//! (one definition for writer and reader).
//!
//! - `solver ltca`: `ltca/<blanks>/te.csv` ([`PINION_ROTATION_DEG`],
//!   [`UTCA_TE_URAD`], [`te_at_urad`] per torque);
//! - `solver dynamic`: `multibody/<blanks>/quasi_static_<T>nm.csv` and
//!   `runup.csv` ([`TIME_S`], [`PINION_ROTATION_DEG`], [`TE_URAD`], ...);
//! - `validate reference`: `<blanks>/te.csv` (as the LTCA's, plus the
//!   unloaded columns) and `pattern_<T>nm.csv` ([`XI`], [`ETA`],
//!   [`PRESSURE_MPA`]).

pub const TIME_S: &str = "time_s";
pub const PINION_ROTATION_DEG: &str = "pinion_rotation_deg";
pub const PINION_RPM: &str = "pinion_rpm";
pub const TE_URAD: &str = "te_urad";
pub const UTCA_TE_URAD: &str = "utca_te_urad";
pub const TORQUE_NM: &str = "torque_nm";
pub const XI: &str = "xi";
pub const ETA: &str = "eta";
pub const PRESSURE_MPA: &str = "pressure_mpa";

/// Loaded TE at pinion torque `torque_nm`, µrad: `te_<T>nm_urad`.
pub fn te_at_urad(torque_nm: f64) -> String {
    format!("te_{torque_nm}nm_urad")
}

#[cfg(test)]
mod tests {
    #[test]
    fn torque_column_prints_the_torque_as_the_scene_gives_it() {
        assert_eq!(super::te_at_urad(700.0), "te_700nm_urad");
        assert_eq!(super::te_at_urad(1.5), "te_1.5nm_urad");
    }
}
