//! Typed errors of the geometry library.

use std::path::{Path, PathBuf};
use thiserror::Error;

/// Bad input: every variant names the file, and where it applies the field,
/// the value and the limit.
#[derive(Debug, Error)]
pub enum InputError {
    #[error("{path}: cannot read: {message}")]
    Io { path: PathBuf, message: String },
    #[error("{path}: {message}")]
    Parse { path: PathBuf, message: String },
    #[error("{path}: {field} = {value}: {limit}")]
    Invalid {
        path: PathBuf,
        field: String,
        value: String,
        limit: String,
    },
}

impl InputError {
    /// Reads a text file: an unreadable file is [`InputError::Io`], bytes
    /// that are not UTF-8 are [`InputError::Parse`] with the line and column
    /// of the first bad byte.
    pub fn read_text(path: &Path) -> Result<String, Self> {
        let bytes = std::fs::read(path).map_err(|e| InputError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        String::from_utf8(bytes).map_err(|e| {
            let bytes = e.as_bytes();
            let at = e.utf8_error().valid_up_to();
            let before = &bytes[..at];
            let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
            let col = at
                - before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |i| i + 1)
                + 1;
            InputError::Parse {
                path: path.to_path_buf(),
                message: format!(
                    "line {line}, column {col}: not UTF-8 text (byte 0x{:02x})",
                    bytes[at]
                ),
            }
        })
    }

    /// A TOML parse error with its line and column.
    pub fn parse(path: &Path, text: &str, e: &toml::de::Error) -> Self {
        let at = e
            .span()
            .map(|s| {
                let mut end = s.start.min(text.len());
                while !text.is_char_boundary(end) {
                    end -= 1;
                }
                let before = &text[..end];
                let line = before.matches('\n').count() + 1;
                let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
                format!("line {line}, column {col}: ")
            })
            .unwrap_or_default();
        InputError::Parse {
            path: path.to_path_buf(),
            message: format!("{at}{}", e.message()),
        }
    }
}

/// Failures of flank generation and contact analysis.
#[derive(Debug, Error)]
pub enum GeometryError {
    #[error(transparent)]
    Input(#[from] InputError),
    #[error("{member} {flank} flank: no flank point at cone distance {cone_distance_mm:.3} mm, height {height_mm:.3} mm (Newton did not converge)")]
    NoFlankPoint {
        member: &'static str,
        flank: &'static str,
        cone_distance_mm: f64,
        height_mm: f64,
    },
    #[error("{member} {flank} flank: no flank-fillet junction at cone distance {cone_distance_mm:.3} mm (the junction's cone distance did not converge)")]
    NoFilletJunction {
        member: &'static str,
        flank: &'static str,
        cone_distance_mm: f64,
    },
    #[error("machine_settings: the {member} {flank} flank the settings cut was not met along the conjugate flank's normal at flank coordinates (face {xi:.3}, profile {eta:.3}) (Newton did not converge: no cradle angle cuts there, or the cutter misses the flank)")]
    SettingsCut {
        member: &'static str,
        flank: &'static str,
        xi: f64,
        eta: f64,
    },
    #[error("machine_settings: the relative deviation the settings cut on the pinion {flank} flank is not smooth: its fitted surface misses a grid node by {residual_um:.4} µm, beyond {limit_um} µm")]
    SettingsFit {
        flank: &'static str,
        residual_um: f64,
        limit_um: f64,
    },
    #[error("local synthesis: no pinion settings found that cut the design's ease-off of the {flank} flank to second order at the mean point (Gauss-Newton did not converge)")]
    Synthesis { flank: &'static str },
    #[error("machine_settings: the flanks the settings cut lie {deviation_um:.1} µm from the design's conjugate flanks (relative, pinion {flank} flank at face {xi:.3}, profile {eta:.3}), beyond the limit of {limit_um} µm: the settings describe another gear (check their signs against docs/machine_settings.md)")]
    SettingsDeviation {
        flank: &'static str,
        deviation_um: f64,
        xi: f64,
        eta: f64,
        limit_um: f64,
    },
}
