//! Published reference values: the files a design's `[published]` table
//! names (`reference/published/` for the white-paper pair).

use crate::report::Published;
use geometry::design::PublishedDesign;
use serde::Deserialize;
use std::path::{Path, PathBuf};

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

/// The NLFEA peak-to-peak TE at 1 N·m, standard blank (Table 3), when the
/// design names a published loaded-TE table with a 1 N·m row.
pub fn te_ptp_1nm(published: &PublishedDesign) -> Result<Option<Published>, PublishedError> {
    let Some(file) = &published.loaded_te else {
        return Ok(None);
    };
    let t: TeTables = read_toml(file)?;
    let Some(row) = t.standard_blank.iter().find(|r| r.load_nm == 1.0) else {
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
