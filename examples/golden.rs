//! Golden-output checks shared by the numbered examples' tests
//! (`preprocess/tests/example_*.rs`, `solver/tests/example_*.rs`,
//! `validate/tests/example_*.rs`, each including this file with `#[path]`).
//!
//! A test computes named quantities and calls [`check`] with the example's
//! `golden.json`. With `BLESS=1` in the environment the file is rewritten
//! from the computed values; otherwise every quantity is compared with its
//! golden value, |value − golden| ≤ rel · |golden| + abs, and the test fails
//! with one line per quantity that is off or missing, naming the value, the
//! golden value and the tolerance. The tolerances are the test's (stated in
//! its source); `golden.json` repeats them for the reader.

#![allow(dead_code)]

use std::path::Path;

/// One checked quantity.
pub struct Quantity {
    pub name: String,
    pub value: f64,
    /// Relative tolerance.
    pub rel: f64,
    /// Absolute tolerance, in the quantity's unit.
    pub abs: f64,
    pub unit: &'static str,
}

impl Quantity {
    pub fn new(
        name: impl Into<String>,
        value: f64,
        unit: &'static str,
        rel: f64,
        abs: f64,
    ) -> Self {
        Quantity {
            name: name.into(),
            value,
            rel,
            abs,
            unit,
        }
    }
}

/// The example folder `examples/<name>` of the workspace, from a crate's
/// `CARGO_MANIFEST_DIR`.
pub fn example_dir(manifest_dir: &str, name: &str) -> std::path::PathBuf {
    let dir = Path::new(manifest_dir)
        .join("..")
        .join("examples")
        .join(name);
    dir.canonicalize().unwrap_or(dir)
}

/// Whether the run rewrites golden files (`BLESS=1`).
pub fn blessing() -> bool {
    std::env::var("BLESS").is_ok_and(|v| v == "1")
}

/// Compares `quantities` with `golden` (or rewrites it under `BLESS=1`);
/// `about` is a line saying what the example computes.
pub fn check(golden: &Path, about: &str, quantities: &[Quantity]) {
    for q in quantities {
        assert!(
            q.value.is_finite(),
            "{}: {} is not finite: {}",
            golden.display(),
            q.name,
            q.value
        );
    }
    if blessing() {
        let mut values = serde_json::Map::new();
        for q in quantities {
            values.insert(
                q.name.clone(),
                serde_json::json!({
                    "value": q.value,
                    "unit": q.unit,
                    "rel_tol": q.rel,
                    "abs_tol": q.abs,
                }),
            );
        }
        let doc = serde_json::json!({
            "about": about,
            "check": "|value - golden| <= rel_tol * |golden| + abs_tol; the tolerances are the test's; BLESS=1 rewrites this file",
            "values": values,
        });
        let text = serde_json::to_string_pretty(&doc).expect("golden JSON") + "\n";
        std::fs::write(golden, text)
            .unwrap_or_else(|e| panic!("BLESS=1: cannot write {}: {e}", golden.display()));
        eprintln!(
            "BLESS=1: wrote {} ({} values)",
            golden.display(),
            quantities.len()
        );
        return;
    }
    let text = std::fs::read_to_string(golden).unwrap_or_else(|e| {
        panic!(
            "{}: cannot read the golden file ({e}); run the test with BLESS=1 to write it",
            golden.display()
        )
    });
    let doc: serde_json::Value = serde_json::from_str(&text)
        .unwrap_or_else(|e| panic!("{}: not JSON ({e})", golden.display()));
    let mut failures = Vec::new();
    for q in quantities {
        let Some(g) = doc["values"][&q.name]["value"].as_f64() else {
            failures.push(format!(
                "{}: no golden value (computed {:.17e}{}); run with BLESS=1 to add it",
                q.name,
                q.value,
                unit(q.unit)
            ));
            continue;
        };
        let tol = q.rel * g.abs() + q.abs;
        let diff = (q.value - g).abs();
        if diff.is_nan() || diff > tol {
            failures.push(format!(
                "{}: value {:.17e}{u}, golden {:.17e}{u}, |difference| {:.3e}{u} > tolerance {:.3e}{u} (rel {:e}, abs {:e})",
                q.name,
                q.value,
                g,
                diff,
                tol,
                q.rel,
                q.abs,
                u = unit(q.unit)
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} differs from the golden output ({} of {} quantities); if the change is intended, rerun with BLESS=1:\n  {}",
        golden.display(),
        failures.len(),
        quantities.len(),
        failures.join("\n  ")
    );
}

fn unit(u: &str) -> String {
    if u.is_empty() {
        String::new()
    } else {
        format!(" {u}")
    }
}
