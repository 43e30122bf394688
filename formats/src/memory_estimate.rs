//! How much memory a Cholesky factor of a body's stiffness matrix will take,
//! estimated from the body's degrees of freedom before any work, so that a
//! stage that would hold factors larger than the machine can give refuses
//! at its start with the estimate, instead of after minutes of factoring.
//!
//! nnz(L) ≈ c · n^β, n the degrees of freedom (3 per tet10 node), with
//! c = 11.0 and β = 1.296. This is a **calibration**: fitted by least
//! squares in log-log on the eight factors this project has measured
//! (METIS ordering, faer supernodal; five bodies of two designs at the
//! reduced and reference levels, 63 k to 1.35 M dofs), which it reproduces
//! with measured / estimated between 0.90 and 1.27 (test
//! `factor_estimate_brackets_the_measured_factors`).
//! Nested dissection of a 3D mesh gives nnz ∝ n^{4/3} in theory; the
//! smaller exponent here reflects that refinement is concentrated on the
//! flank surfaces. The fill is stored as f64 values, 8 bytes each.

/// Estimated factor size of a body with `dofs` degrees of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FactorEstimate {
    pub dofs: usize,
    /// Expected bytes of the factor's values.
    pub bytes: f64,
    /// The band the calibration data fall in: [0.8, 1.3] × `bytes`.
    pub low_bytes: f64,
    pub high_bytes: f64,
}

/// Fit constants (see the module documentation).
pub const FILL_COEFFICIENT: f64 = 11.0;
pub const FILL_EXPONENT: f64 = 1.296;

/// Estimated factor of a body with `dofs` degrees of freedom.
pub fn factor(dofs: usize) -> FactorEstimate {
    let bytes = 8.0 * FILL_COEFFICIENT * (dofs as f64).powf(FILL_EXPONENT);
    FactorEstimate {
        dofs,
        bytes,
        low_bytes: 0.8 * bytes,
        high_bytes: 1.3 * bytes,
    }
}

/// Factors that a stage would hold at once need more memory than there is.
#[derive(Debug, thiserror::Error)]
#[error("{what} would hold Cholesky factors of about {:.1} GB at once ({}), at least {:.1} GB by the estimate's lower band, but {:.1} GB are available; use a coarser mesh level or a machine with more memory", .expected_gb, .parts, .low_gb, .available_gb)]
pub struct TooLarge {
    pub what: String,
    pub parts: String,
    pub expected_gb: f64,
    pub low_gb: f64,
    pub available_gb: f64,
}

/// Refuses when the factors `parts` (name, dofs), held at once, need more
/// than `available` bytes even at the estimate's lower band; passes when
/// `available` is unknown (`fem::cholesky::available_memory_bytes`). Factors that may fit are left to the exact check
/// after the symbolic analysis.
pub fn check_fits(
    what: &str,
    parts: &[(&str, usize)],
    available: Option<usize>,
) -> Result<FactorEstimate, TooLarge> {
    let est: Vec<FactorEstimate> = parts.iter().map(|&(_, n)| factor(n)).collect();
    let total = FactorEstimate {
        dofs: parts.iter().map(|p| p.1).sum(),
        bytes: est.iter().map(|e| e.bytes).sum(),
        low_bytes: est.iter().map(|e| e.low_bytes).sum(),
        high_bytes: est.iter().map(|e| e.high_bytes).sum(),
    };
    match available {
        Some(a) if total.low_bytes > a as f64 => Err(TooLarge {
            what: what.to_string(),
            parts: parts
                .iter()
                .zip(&est)
                .map(|((name, n), e)| format!("{name}: {n} dofs, {:.1} GB", e.bytes / 1e9))
                .collect::<Vec<_>>()
                .join("; "),
            expected_gb: total.bytes / 1e9,
            low_gb: total.low_bytes / 1e9,
            available_gb: a as f64 / 1e9,
        }),
        _ => Ok(total),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Calibration check: the eight measured factors (dofs, nnz) lie within
    /// the estimate's band (the fit was made on them; this guards the
    /// constants, it does not validate the law on new bodies).
    #[test]
    fn factor_estimate_brackets_the_measured_factors() {
        let measured: [(usize, f64); 8] = [
            (341_481, 207_893_187.0),
            (346_533, 152_522_532.0),
            (292_953, 134_921_601.0),
            (62_604, 18_485_739.0),
            (90_147, 26_664_786.0),
            (1_350_429, 7.89e9 / 8.0),
            (875_583, 4.60e9 / 8.0),
            (1_254_276, 6.38e9 / 8.0),
        ];
        for (dofs, nnz) in measured {
            let e = factor(dofs);
            let bytes = 8.0 * nnz;
            assert!(
                e.low_bytes <= bytes && bytes <= e.high_bytes,
                "{dofs} dofs: measured {:.2} GB outside [{:.2}, {:.2}]",
                bytes / 1e9,
                e.low_bytes / 1e9,
                e.high_bytes / 1e9
            );
        }
    }

    #[test]
    fn factors_beyond_the_available_memory_are_refused_naming_each_part() {
        let parts = [("pinion", 8_700_000), ("wheel", 5_000_000)];
        let e = check_fits("validate reference --level x", &parts, Some(24_000_000_000))
            .unwrap_err()
            .to_string();
        for w in [
            "validate reference",
            "pinion: 8700000 dofs",
            "wheel",
            "24.0 GB are available",
        ] {
            assert!(e.contains(w), "{w} not in: {e}");
        }
        assert!(check_fits("x", &parts, None).is_ok());
        // The white paper's reference level fits in 24 GB.
        assert!(check_fits(
            "x",
            &[("p", 1_350_429), ("w", 1_254_276)],
            Some(24_000_000_000)
        )
        .is_ok());
    }
}
