//! The options of each `validate` subcommand and their checks (field,
//! value and limit named before any work).

use std::path::PathBuf;

#[derive(clap::Args)]
pub struct ReportArgs {
    /// Scene or design file.
    pub scene: PathBuf,
    /// Output directory of `preprocess flanks` (for the plots).
    #[arg(long)]
    pub flanks: PathBuf,
    /// Report directory.
    #[arg(long, default_value = "reports")]
    pub reports: PathBuf,
    /// Positions per mesh cycle for the direct search, 1 to 3600.
    #[arg(long, default_value_t = 12, value_parser = positions_per_cycle)]
    pub positions: usize,
    /// Output root of the solver and `validate reference`: when given, the
    /// report also compares their loaded TE (Tables 3-5).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Mesh root (for the convergence study's mesh check).
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    /// README whose text between `<!-- results:begin -->` and
    /// `<!-- results:end -->` is replaced by the results table (left
    /// alone without both markers).
    #[arg(long, default_value = "README.md")]
    pub readme: PathBuf,
}

#[derive(clap::Args)]
pub struct UtcaArgs {
    /// Scene or design file.
    pub scene: PathBuf,
    /// Positions per mesh cycle for the direct search, 1 to 3600.
    #[arg(long, default_value_t = 12, value_parser = positions_per_cycle)]
    pub positions: usize,
    /// Writes the comparison as one result set in this folder
    /// (`utca_check.json` and its `run.json`).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(clap::Args)]
pub struct ReferenceArgs {
    /// Scene file; several scenes of one design (cases at other
    /// misalignments, sharing the meshes) are solved in one run, each body
    /// factored once for all of them, each scene's results its own set.
    #[arg(required = true, num_args = 1..)]
    pub scene: Vec<PathBuf>,
    /// Mesh directory (as written by `preprocess mesh`).
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    /// Output directory: one for every scene, or one per scene in the
    /// scenes' order (`--out a --out b`).
    #[arg(long, default_value = "out")]
    pub out: Vec<PathBuf>,
    /// Mesh level of both bodies: reduced, medium or reference.
    #[arg(long, default_value = "reduced", value_parser = ["reduced", "medium", "reference"])]
    pub level: String,
    /// Penalty ε = factor · E / (local face size).
    #[arg(long, default_value_t = 100.0)]
    pub penalty: f64,
    /// Second penalty factor, whose TE is compared.
    #[arg(long, default_value_t = 200.0)]
    pub penalty_check: f64,
    /// Constraints within this of the smallest initial gap start in the
    /// solve, um.
    #[arg(long, default_value_t = 2.0)]
    pub start_band_um: f64,
    /// Constraints are searched up to this initial gap and join the
    /// solve when they penetrate, um.
    #[arg(long, default_value_t = 60.0)]
    pub search_gap_um: f64,
    /// Solve every n-th position of the scene's sweep (n >= 1).
    #[arg(long, default_value_t = 1, value_parser = at_least_one)]
    pub stride: usize,
    /// Stride for the lightweight wheel blank (default: --stride).
    #[arg(long, value_parser = at_least_one)]
    pub stride_lightweight: Option<usize>,
    /// Right-hand sides per forward-solve block.
    #[arg(long, default_value_t = 96)]
    pub block: usize,
    /// Solve every cached position anew and compare it with the cache
    /// (relative tolerance 1e-6); writes compare_cache.json, exits
    /// non-zero on a difference.
    #[arg(long)]
    pub compare_cache: bool,
    /// Solve one shard of the sweep, I/N (positions i with i mod N = I),
    /// into the shared position cache.
    #[arg(long)]
    pub shard: Option<String>,
    /// Memory the bodies' factors may use, GB (default: what the system
    /// has available); the run refuses before factoring when the
    /// factors estimated from the meshes need more.
    #[arg(long)]
    pub memory_gb: Option<f64>,
    /// Contact passes: two-pass (pinion nodes against the wheel's faces
    /// and wheel nodes against the pinion's), or pinion-slave (the first
    /// only; results in `reference_<level>_pinion_slave/`, the contact
    /// formulation's share of the reference's uncertainty).
    #[arg(long, default_value = "two-pass", value_parser = ["two-pass", "pinion-slave"])]
    pub contact: String,
}

/// `--contact`: two-pass or pinion-slave.
pub fn contact_passes(
    s: &str,
) -> anyhow::Result<validate::reference::reference_ltca::ContactPasses> {
    use validate::reference::reference_ltca::ContactPasses;
    [ContactPasses::TwoPass, ContactPasses::PinionSlave]
        .into_iter()
        .find(|p| p.name() == s)
        .ok_or_else(|| anyhow::anyhow!("--contact {s}: must be two-pass or pinion-slave"))
}

#[derive(clap::Args)]
pub struct TradeoffArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Slice counts per tooth pair.
    #[arg(long, value_delimiter = ',', default_value = "8,12,20,30,45,60")]
    pub slices: Vec<usize>,
}

#[derive(clap::Args)]
pub struct StressArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Scenes of the same designs at other stiffness grids, their
    /// stiffness files in `meshes/` beside each or in `--meshes`.
    #[arg(long)]
    pub grid_scene: Vec<PathBuf>,
    /// Scenes of the same designs with coast-flank contact, whose
    /// coast stiffness files serve the coast cells.
    #[arg(long)]
    pub coast_scene: Vec<PathBuf>,
}

#[derive(clap::Args)]
pub struct StageTradeoffsArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Scenes of the same design at other contact grids (their
    /// stiffness files in `meshes/` beside each, or in `--meshes`).
    #[arg(long)]
    pub grid_scene: Vec<PathBuf>,
}

#[derive(clap::Args)]
pub struct GridConvergenceArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Scenes of the same design at finer contact grids (their stiffness
    /// files in `meshes/` beside each, or in `--meshes`); at least two.
    #[arg(long)]
    pub grid_scene: Vec<PathBuf>,
}

#[derive(clap::Args)]
pub struct ConvergenceArgs {
    #[command(flatten)]
    pub study: LevelStudyArgs,
    /// Position index in the scene's sweep (its rotation steps).
    #[arg(long, default_value_t = 0)]
    pub position: usize,
    /// Pinion torques, N·m (default: the scene's loads).
    #[arg(long, value_delimiter = ',')]
    pub torque_nm: Vec<f64>,
}

#[derive(clap::Args)]
pub struct MeshStiffnessArgs {
    #[command(flatten)]
    pub study: LevelStudyArgs,
    /// Position index in the scene's sweep (default: the middle of the
    /// longest run with the fewest tooth pairs in contact).
    #[arg(long)]
    pub position: Option<usize>,
    /// Memory the two FE factors may take together, GB (default: what
    /// the system has available); a level estimated above it is skipped.
    #[arg(long)]
    pub memory_gb: Option<f64>,
    /// The lumped scene whose reduced meshes and roughness grades the
    /// study relates to.
    #[arg(long)]
    pub lumped_scene: Option<PathBuf>,
}

#[derive(clap::Args)]
pub struct LineLoadArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Fine mesh levels.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "medium,reference",
        value_parser = ["reduced", "medium", "reference"]
    )]
    pub levels: Vec<String>,
    /// Hertz half-widths, mm.
    #[arg(long, value_delimiter = ',', default_value = "0.25,0.5,1.0")]
    pub half_width_mm: Vec<f64>,
    /// Line load, N/mm.
    #[arg(long, default_value_t = 100.0)]
    pub line_load_n_per_mm: f64,
    /// Profile row of the contact grid (default: the middle one).
    #[arg(long)]
    pub row: Option<usize>,
    /// Grid columns at the toe and at the heel left out of the statistics.
    #[arg(long, default_value_t = 2)]
    pub end_columns: usize,
    /// Load only grid columns A to B (A-B, inclusive): a line load over part
    /// of the face width, compared on those columns (default: the whole
    /// line, compared inside --end-columns).
    #[arg(long, value_parser = column_range)]
    pub columns: Option<(usize, usize)>,
    /// Compare the approach on this tooth relative to the loaded one (0: the
    /// loaded tooth; ±1: its neighbours, the coupling between teeth).
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub response_tooth: i32,
    /// The loaded member: pinion or wheel.
    #[arg(long, default_value = "pinion", value_parser = ["pinion", "wheel"])]
    pub member: String,
    /// Its blank: standard or lightweight.
    #[arg(long, default_value = "standard", value_parser = ["standard", "lightweight"])]
    pub blank: String,
}

/// What the studies on one position over mesh levels share.
#[derive(clap::Args)]
pub struct LevelStudyArgs {
    /// Scene file.
    pub scene: PathBuf,
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Mesh levels, coarse to fine.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "reduced,medium,reference",
        value_parser = ["reduced", "medium", "reference"]
    )]
    pub levels: Vec<String>,
    /// Penalty ε = factor · E / (local face size).
    #[arg(long, default_value_t = 100.0)]
    pub penalty: f64,
    /// Second penalty factor, whose result is compared.
    #[arg(long, default_value_t = 200.0)]
    pub penalty_check: f64,
    /// Right-hand sides per forward-solve block.
    #[arg(long, default_value_t = 96)]
    pub block: usize,
}

impl LevelStudyArgs {
    /// The penalty settings and `--block` checked (before the scene is
    /// read), and the scene loaded.
    pub fn checked(
        &self,
    ) -> anyhow::Result<(
        geometry::scene::LoadedScene,
        validate::reference::reference_ltca::ReferenceSettings,
        usize,
    )> {
        let settings = penalty_settings(self.penalty, self.penalty_check, 2.0, 60.0)?;
        let block = check_block(self.block)?;
        Ok((geometry::scene::Scene::load(&self.scene)?, settings, block))
    }
}

/// A count of at least one (`--stride`): clap refuses anything else
/// before any work, naming the option and the value.
pub fn at_least_one(s: &str) -> Result<usize, String> {
    count_in(s, 1, usize::MAX).map_err(|_| "must be a whole number >= 1".into())
}

/// Positions per mesh cycle of the direct UTCA search (`--positions`):
/// 1 to 3600 (a bound on the run time, each position a direct search).
pub fn positions_per_cycle(s: &str) -> Result<usize, String> {
    count_in(s, 1, 3600)
}

/// A whole number in [lo, hi], else the range in words.
fn count_in(s: &str, lo: usize, hi: usize) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(format!("must be a whole number in [{lo}, {hi}]")),
    }
}

/// `--block` within [1, 100000] right-hand sides.
pub fn check_block(block: usize) -> anyhow::Result<usize> {
    if !(1..=100_000).contains(&block) {
        anyhow::bail!("--block {block}: must lie in [1, 100000] right-hand sides");
    }
    Ok(block)
}

/// `--memory-gb` (positive) in bytes.
pub fn memory_bytes(memory_gb: Option<f64>) -> anyhow::Result<Option<usize>> {
    match memory_gb {
        Some(gb) if !(gb.is_finite() && gb > 0.0) => {
            anyhow::bail!("--memory-gb = {gb}: must be a positive number of GB")
        }
        gb => Ok(gb.map(|gb| (gb * 1e9) as usize)),
    }
}

/// Checks the penalty factors (positive, finite).
pub fn penalty_settings(
    penalty: f64,
    penalty_check: f64,
    start_band_um: f64,
    search_gap_um: f64,
) -> anyhow::Result<validate::reference::reference_ltca::ReferenceSettings> {
    for (field, v) in [
        ("--penalty", penalty),
        ("--penalty-check", penalty_check),
        ("--start-band-um", start_band_um),
        ("--search-gap-um", search_gap_um),
    ] {
        if !(v.is_finite() && v > 0.0) {
            anyhow::bail!("{field} {v}: must be a positive number");
        }
    }
    Ok(validate::reference::reference_ltca::ReferenceSettings {
        penalty_factor: penalty,
        penalty_factor_check: penalty_check,
        start_band_m: start_band_um * 1e-6,
        search_gap_m: search_gap_um * 1e-6,
        passes: Default::default(),
    })
}

/// `I/N` with N ≥ 1 and I < N.
pub fn parse_shard(s: &str) -> anyhow::Result<(usize, usize)> {
    let bad =
        || anyhow::anyhow!("--shard {s}: must be I/N with whole numbers N >= 1 and 0 <= I < N");
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

#[derive(clap::Args)]
pub struct CalibrateArgs {
    /// The base scene (the white-paper pair's default scene); its
    /// standard/standard stiffness files must exist.
    pub scene: PathBuf,
    /// Mesh directory; the web trials' meshes and stiffness files go here.
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    /// Output root: the web trials' scenes go to `<out>/calibration/`.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// The calibrated design file to write.
    #[arg(long, default_value = "reference/white_paper_20x43_calibrated.toml")]
    pub design_out: PathBuf,
    /// The calibrated scene file to write.
    #[arg(long, default_value = "reference/scenes/white_paper_calibrated.toml")]
    pub scene_out: PathBuf,
    /// The calibration record to write (read by the report).
    #[arg(long, default_value = "reference/white_paper_20x43_calibration.json")]
    pub record_out: PathBuf,
}

/// `A-B`: a range of grid columns.
fn column_range(s: &str) -> Result<(usize, usize), String> {
    let (a, b) = s
        .split_once('-')
        .ok_or_else(|| format!("{s}: expected A-B (grid columns, e.g. 34-39)"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<usize>()
            .map_err(|_| format!("{s}: {v} is not a column number"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if a > b {
        return Err(format!("{s}: the first column must not follow the last"));
    }
    Ok((a, b))
}

#[derive(clap::Args)]
pub struct ExportInpArgs {
    /// Scene file.
    pub scene: PathBuf,
    /// Mesh directory (as written by `preprocess mesh`).
    #[arg(long, default_value = "meshes")]
    pub meshes: PathBuf,
    /// Output directory: the deck goes to <out>/<scene>/calculix/.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Mesh level of both bodies: reduced, medium or reference.
    #[arg(long, default_value = "reduced", value_parser = ["reduced", "medium", "reference"])]
    pub level: String,
    /// Position of the reference sweep (0: its start).
    #[arg(long)]
    pub position: usize,
    /// Pinion blank (default: the scene's first).
    #[arg(long, value_parser = ["standard", "lightweight"])]
    pub pinion_blank: Option<String>,
    /// Wheel blank (default: the scene's first).
    #[arg(long, value_parser = ["standard", "lightweight"])]
    pub wheel_blank: Option<String>,
    /// Contact of the deck: node-to-surface (the pinion's nodes against the
    /// wheel's faces), surface-to-surface, or none (the rigid-rotation
    /// check: no contact, one prescribed rotation).
    #[arg(long, default_value = "node-to-surface", value_parser = ["node-to-surface", "surface-to-surface", "none"])]
    pub contact: String,
    /// Penalty ε = factor · E / (mean flank face size).
    #[arg(long, default_value_t = 100.0)]
    pub penalty: f64,
    /// Solve the deck with CalculiX (`ccx`) and write its loaded TE.
    #[arg(long)]
    pub run: bool,
    /// Solver threads of the CalculiX run.
    #[arg(long, default_value_t = 2, value_parser = at_least_one)]
    pub threads: usize,
}
