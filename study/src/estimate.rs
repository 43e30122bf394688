//! The cost of a study's reference sweeps on paper, from a measured sweep
//! of its base scene (`validate reference` of the scene itself, whose
//! `summary.json` gives each blank pair's positions, the wall time of
//! its sweep and the bodies' factoring times): the cases × positions at
//! the study's stride, the wall time of one shard job (the bodies factored
//! once, then its share of every case's positions) and of the whole
//! study on N nodes of the measuring machine's kind, one shard per node.
//! An estimate: it assumes every case costs what the measured sweep cost
//! per position (misalignment changes the contact, not the bodies).

use serde::Serialize;
use serde_json::Value;
use std::path::Path;

/// The measured sweep of one blank pair.
#[derive(Debug, Clone, Serialize)]
pub struct Measured {
    pub blanks: String,
    pub positions: usize,
    /// Wall seconds per solved position, and the bodies' factoring, s.
    pub wall_s_per_position: f64,
    pub factor_s: f64,
}

/// The estimate for one shard count.
#[derive(Debug, Clone, Serialize)]
pub struct Sizing {
    pub shards: usize,
    pub shard_job_h: f64,
    /// The study's wall time with one node per shard.
    pub study_wall_h: f64,
    /// Node-hours in all (factoring repeated on every node).
    pub node_hours: f64,
}

/// Reads the measured sweep of `scene` at `level` under `out`.
pub fn measured(out: &Path, scene: &str, level: &str) -> anyhow::Result<Vec<Measured>> {
    let path = formats::paths::reference_dir(out, scene, level).join("summary.json");
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&path).map_err(|e| {
        anyhow::anyhow!(
            "{}: no measured sweep to estimate from ({e}); run `validate reference` of the scene at level {level} first",
            path.display()
        )
    })?)?;
    let mut m = Vec::new();
    let mut pinion_factored = false;
    for b in v.as_array().into_iter().flatten() {
        let g = |k: &str| b.get(k).and_then(Value::as_f64).unwrap_or(f64::NAN);
        let positions = g("positions") as usize;
        let solved = positions.saturating_sub(g("positions_reused") as usize);
        if solved == 0 {
            anyhow::bail!(
                "{}: every position of {} came from the cache, so its wall time measures nothing; solve the sweep anew",
                path.display(),
                b["wheel_blank"]
            );
        }
        let f = b.get("factor_s").and_then(Value::as_array);
        let fs = |k: usize| {
            f.and_then(|f| f.get(k))
                .and_then(Value::as_f64)
                .unwrap_or(0.0)
        };
        // The pinion is factored once for every wheel blank.
        let factor_s = fs(1) + if pinion_factored { 0.0 } else { fs(0) };
        pinion_factored = true;
        m.push(Measured {
            blanks: format!(
                "{}_{}",
                b["pinion_blank"].as_str().unwrap_or("?"),
                b["wheel_blank"].as_str().unwrap_or("?")
            ),
            positions,
            wall_s_per_position: g("sweep_s") / solved as f64,
            factor_s,
        });
    }
    Ok(m)
}

/// The sizing of `cases` cases at `stride` over `nodes` shard counts.
pub fn sizing(m: &[Measured], cases: usize, stride: usize, nodes: &[usize]) -> Vec<Sizing> {
    let solve_s: f64 = m
        .iter()
        .map(|b| b.positions.div_ceil(stride) as f64 * b.wall_s_per_position)
        .sum::<f64>()
        * cases as f64;
    let factor_s: f64 = m.iter().map(|b| b.factor_s).sum();
    nodes
        .iter()
        .map(|&n| {
            let shard = factor_s + solve_s / n as f64;
            Sizing {
                shards: n,
                shard_job_h: shard / 3600.0,
                study_wall_h: shard / 3600.0,
                node_hours: n as f64 * shard / 3600.0,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One blank of 100 positions at 10 s and 300 s of factoring: 81
    /// cases are 81,000 s of solves; 8 shards take 300 + 10,125 s each.
    #[test]
    fn sizing_splits_the_solves_and_repeats_the_factoring() {
        let m = [Measured {
            blanks: "standard_standard".into(),
            positions: 100,
            wall_s_per_position: 10.0,
            factor_s: 300.0,
        }];
        let s = sizing(&m, 81, 1, &[1, 8]);
        assert!((s[0].shard_job_h - (300.0 + 81_000.0) / 3600.0).abs() < 1e-12);
        assert!((s[1].shard_job_h - (300.0 + 10_125.0) / 3600.0).abs() < 1e-12);
        assert!((s[1].node_hours - 8.0 * (300.0 + 10_125.0) / 3600.0).abs() < 1e-12);
        // A stride of 2 halves the positions (rounded up).
        let s2 = sizing(&m, 1, 3, &[1]);
        assert!((s2[0].shard_job_h - (300.0 + 34.0 * 10.0) / 3600.0).abs() < 1e-12);
    }
}
