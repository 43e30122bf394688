//! Scenes of one design at other contact grids (`reference/scenes/grids/`,
//! the example-02 fixture): where their stiffness files are, and the
//! standard blanks' compliance and fields from them.
use solver::stage::context::LoadedPair;

use anyhow::Context;
use formats::paths::MeshLevel;
use formats::stiffness_file::StiffnessData;
use formats::stiffness_plan;
use geometry::design::Member;
use geometry::pair::PairGeometry;
use geometry::scene::{Blank, LoadedScene, Scene};
use solver::element::compliance::PairCompliance;
use std::path::{Path, PathBuf};

/// A scene at another contact grid, loaded.
pub struct GridScene {
    pub scene: LoadedScene,
    pub g: PairGeometry,
    /// Contact grid (profile × face).
    pub grid: [u32; 2],
    /// Its mesh folder: `meshes/<name>/` beside the scene file when that
    /// exists (the example-02 fixture), else `<meshes>/<name>/`.
    pub dir: PathBuf,
}

impl GridScene {
    pub fn load(path: &Path, meshes: &Path) -> anyhow::Result<GridScene> {
        let scene = Scene::load(path).with_context(|| format!("grid scene {}", path.display()))?;
        let g = PairGeometry::build(&scene.pair, Some(&scene.design_path))?;
        let name = &scene.scene.name;
        let beside = path
            .parent()
            .unwrap_or(Path::new("."))
            .join("meshes")
            .join(name);
        let dir = if beside.is_dir() {
            beside
        } else {
            meshes.join(name)
        };
        let o = scene.scene.mesh.reduced_order;
        Ok(GridScene {
            grid: [o.profile, o.face],
            scene,
            g,
            dir,
        })
    }

    /// Whether its design file is `other`'s.
    pub fn same_design(&self, other: &LoadedScene) -> bool {
        std::fs::canonicalize(&self.scene.design_path).ok()
            == std::fs::canonicalize(&other.design_path).ok()
    }

    pub fn label(&self) -> String {
        format!("{} × {}", self.grid[0], self.grid[1])
    }

    /// The standard blanks' compliance on the loaded flank.
    pub fn compliance(&self) -> anyhow::Result<PairCompliance> {
        Ok(LoadedPair::load(&self.scene, &self.g, &self.dir, [Blank::Standard; 2])?.pc)
    }
}

/// The checked stiffness data of `member`'s standard blank at `level`, and
/// the stiffness stage's recorded time for it (s; None where the stage's
/// report is not beside the file, as for checked-in fixtures).
pub fn member_fields(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    level: MeshLevel,
) -> anyhow::Result<(StiffnessData, Option<f64>)> {
    let side = scene.scene.loaded_flank;
    let p = stiffness_plan::plan(scene, g, dir, member, Blank::Standard, level, side)?;
    let data =
        stiffness_plan::check(scene, g, dir, &p, member, Blank::Standard, level).map_err(|e| {
            let mend = e
                .remedy()
                .advice(&scene.path, &scene.design_path, dir, level);
            anyhow::Error::new(e).context(format!(
                "stiffness file {} cannot be used{mend}",
                p.path.display()
            ))
        })?;
    let report = p.path.with_extension("json");
    let total_s = std::fs::read_to_string(&report)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
        .and_then(|v| v.get("total_s").and_then(|s| s.as_f64()));
    Ok((data, total_s))
}
