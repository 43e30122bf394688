//! The white paper's Table 5 (CPU) as printed, which the comparison reads
//! beside Tables 3–4 ([`crate::report::published::PublishedTeTables`]).

use serde::Deserialize;

#[derive(Deserialize)]
pub(super) struct PubCpu {
    pub(super) pinion_load_nm: f64,
    pub(super) blank: String,
    pub(super) cpu_step_s: f64,
    /// The multibody rows print minutes, the NLFEA rows days.
    pub(super) cpu_total_min: Option<f64>,
    pub(super) cpu_total_days: Option<f64>,
}

impl PubCpu {
    /// The printed total CPU in seconds.
    pub(super) fn total_s(&self) -> Option<f64> {
        self.cpu_total_min
            .map(|m| m * 60.0)
            .or(self.cpu_total_days.map(|d| d * 86_400.0))
    }
}

#[derive(Deserialize)]
pub(super) struct PubCpuTable {
    pub(super) multibody: Vec<PubCpu>,
    pub(super) nlfea_ltca: Vec<PubCpu>,
}

/// The white paper's Table 5 row of wheel blank `blank` at pinion load
/// `torque_nm`, in the multibody or the NLFEA rows `v`.
pub(super) fn published_cpu_row<'a>(
    v: Option<&'a Vec<PubCpu>>,
    blank: &str,
    torque_nm: f64,
) -> Option<&'a PubCpu> {
    v?.iter()
        .find(|c| c.blank == blank && (c.pinion_load_nm - torque_nm).abs() < 1e-9)
}

#[cfg(test)]
mod tests {
    use super::PubCpu;
    /// Table 5 prints the multibody totals in minutes and the NLFEA totals
    /// in days: both come out in seconds (4.0 min, 0.9 days as printed).
    #[test]
    fn published_cpu_totals_are_in_seconds() {
        let row = |min, days| PubCpu {
            pinion_load_nm: 300.0,
            blank: "standard".into(),
            cpu_step_s: 0.8,
            cpu_total_min: min,
            cpu_total_days: days,
        };
        assert_eq!(row(Some(4.0), None).total_s(), Some(240.0));
        assert_eq!(row(None, Some(0.9)).total_s(), Some(77_760.0));
        assert_eq!(row(None, None).total_s(), None);
    }
}
