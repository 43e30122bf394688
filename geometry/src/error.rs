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
    /// A TOML parse error with its line and column.
    pub fn parse(path: &Path, text: &str, e: &toml::de::Error) -> Self {
        let at = e
            .span()
            .map(|s| {
                let before = &text[..s.start.min(text.len())];
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
}
