//! Published reference values (`reference/published/`), read where the
//! design is the white-paper pair.

use crate::report::Published;
use serde::Deserialize;
use std::path::Path;

#[derive(Deserialize)]
struct TeRow {
    load_nm: f64,
    ptp_te_nlfea_urad: f64,
}

#[derive(Deserialize)]
struct TeTables {
    source: String,
    standard_blank: Vec<TeRow>,
}

/// The NLFEA peak-to-peak TE at 1 N·m, standard blank (Table 3), when
/// `design` is the white-paper pair and the published table is present.
pub fn te_ptp_1nm(design: &Path) -> Option<Published> {
    if design.file_stem()? != "white_paper_20x43" {
        return None;
    }
    let file = design
        .parent()?
        .join("published/white_paper_tables3_4_te.toml");
    let t: TeTables = toml::from_str(&std::fs::read_to_string(file).ok()?).ok()?;
    let row = t.standard_blank.iter().find(|r| r.load_nm == 1.0)?;
    Some(Published {
        value: row.ptp_te_nlfea_urad,
        source: format!(
            "white paper Table 3, NLFEA, standard blank ({})",
            t.source.split(',').next().unwrap_or("")
        ),
    })
}
