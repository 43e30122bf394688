//! The two solve paths of a stiffness file compared on one body: the
//! influence fields of a member × blank computed by pruned forward solves
//! with Gram products and by full solves, on the same factorization input
//! (`make bench`, stiffness).

use crate::body_mesh;
use crate::influence::{compute, Influence, InfluenceStats, Solves};
use crate::stiffness_stage::{clamped_groups, planned_under, request};
use formats::paths::MeshLevel;
use geometry::design::Member;
use geometry::scene::{Blank, LoadedScene};
use serde::Serialize;
use std::path::Path;

/// Both paths' timings and how far their fields differ.
#[derive(Debug, Clone, Serialize)]
pub struct SolvePaths {
    pub member: String,
    pub blank: String,
    pub pruned: InfluenceStats,
    pub full: InfluenceStats,
    /// Largest |C_pruned − C_full| over each block of the total (resp.
    /// global) field, relative to that block's largest |C_full|.
    pub total_max_rel: f64,
    pub global_max_rel: f64,
}

/// Largest blockwise relative difference of two fields of `np × np` blocks.
fn max_rel(a: &[f64], b: &[f64], np: usize) -> f64 {
    a.chunks(np * np)
        .zip(b.chunks(np * np))
        .map(|(x, y)| {
            let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let d = x
                .iter()
                .zip(y)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
            if scale > 0.0 {
                d / scale
            } else {
                d
            }
        })
        .fold(0.0, f64::max)
}

/// [`SolvePaths`] of `member` × `blank` on the meshes of `level` under
/// `root/<scene>/`, for the stiffness file's own request.
pub fn compare(
    scene: &LoadedScene,
    root: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
) -> anyhow::Result<SolvePaths> {
    let sc = &scene.scene;
    let side = sc.loaded_flank;
    let (g, p) = planned_under(scene, root, member, blank, level)?;
    let body = body_mesh::read(&p.msh).map_err(anyhow::Error::msg)?;
    let groups = clamped_groups(&p.config);
    let run = |solves: Solves| -> anyhow::Result<Influence> {
        let req = request(
            &p.config,
            &p.grid,
            &body,
            &g,
            member,
            side,
            sc.stiffness.solve_block,
        );
        Ok(compute(
            &crate::influence::InfluenceRequest { solves, ..req },
            &groups,
        )?)
    };
    let pruned = run(Solves::Pruned)?;
    let full = run(Solves::Full)?;
    let np = p.grid.len();
    Ok(SolvePaths {
        member: member.name().into(),
        blank: blank.name().into(),
        total_max_rel: max_rel(&pruned.total, &full.total, np),
        global_max_rel: max_rel(&pruned.global, &full.global, np),
        pruned: pruned.stats,
        full: full.stats,
    })
}
