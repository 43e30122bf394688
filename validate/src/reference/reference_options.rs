//! The settings of a `validate reference` run ([`StageOptions`]), the
//! version and tolerance of its position cache, and the UTCA it checks the
//! unloaded positions against: shared by the stage
//! ([`super::reference_stage`]) and each blank pair of it
//! ([`super::reference_blank_pair`]).

use crate::reference::reference_ltca::ReferenceSettings;
use geometry::scene::LoadedScene;
use serde::Serialize;

/// Version of the reference computation (constraints, solve, position
/// results); part of every cache key. A summary of another layout fails to
/// parse and is rebuilt from the cached positions.
pub const REFERENCE_SCHEMA: u32 = 7;

/// Options of the stage.
#[derive(Debug, Clone, Serialize)]
pub struct StageOptions {
    /// Mesh level ("reduced" or "reference").
    pub level: String,
    pub settings: ReferenceSettings,
    /// Solve every n-th position of the scene's sweep.
    pub stride: usize,
    /// Stride for the lightweight wheel blank (its sweep is 2.5 times
    /// longer), when given.
    pub stride_lightweight: Option<usize>,
    /// Right-hand sides per forward-solve block.
    pub block: usize,
    /// Solve every position anew and compare it with its cached result
    /// (old and new solution paths must agree within
    /// [`COMPARE_TOLERANCE`]); the cache is left as it is.
    pub compare_cache: bool,
    /// Solve only the positions i with i mod N = I (`Some((I, N))`): one
    /// shard of a sweep split among processes or machines. Shards write
    /// their positions to the shared cache; a run without a shard then
    /// finds them all there and writes the result.
    pub shard: Option<(usize, usize)>,
    /// Memory this run may use for the bodies' factors, bytes; `None`:
    /// what the system has available (`MemAvailable`). The factors a run
    /// would hold at once are estimated from the meshes before any
    /// factoring and refused above it ([`formats::memory_estimate`]).
    pub memory_bytes: Option<usize>,
}

/// Largest relative difference that `--compare-cache` accepts between a
/// position solved now and its cached result.
pub const COMPARE_TOLERANCE: f64 = 1e-6;

/// The UTCA of the scene's generated flanks (its own UTCA settings) at `n`
/// pinion angles from `start` in steps of `step`: the unloaded check's
/// reference.
pub fn utca_at(
    scene: &LoadedScene,
    fp: &geometry::pair::FlankPair,
    start: f64,
    step: f64,
    n: usize,
    direction: f64,
) -> anyhow::Result<geometry::utca::Utca> {
    let input = preprocess::flank_stage::load_input(&scene.path)?;
    let rs = geometry::utca::roll_surface(fp, &input.utca)?;
    Ok(geometry::utca::run(fp, &rs, start, step, n, direction))
}
