//! What a scene asks of a stiffness file, from the scene alone: its name, its
//! contact grid and the fields of its `config` that the scene determines. The
//! stiffness stage completes the config with the mesh's hashes and the FE
//! local model and writes the file; readers check a file against the same
//! plan ([`check`]) using the mesh folder's [`Manifest`].

use crate::manifest::{field_differences, Manifest, ManifestError, MeshEntry, MeshInputs};
use crate::paths::{self, MeshLevel};
use crate::stiffness_file::{
    self, StiffnessConfig, StiffnessData, StiffnessFileError, STIFFNESS_SCHEMA,
};
use geometry::contact_grid::{FlankGrid, GridSize};
use geometry::design::Member;
use geometry::error::GeometryError;
use geometry::gear_body::Blank;
use geometry::generation::Side;
use geometry::pair::PairGeometry;
use geometry::scene::LoadedScene;
use geometry::teeth::{opposite_refined_teeth, periodic_teeth, refined_teeth_on, solved_tooth};
use std::path::{Path, PathBuf};

/// A stiffness file as the scene plans it.
#[derive(Debug, Clone)]
pub struct StiffnessPlan {
    /// The file's stem ([`paths::stiffness_stem`]).
    pub stem: String,
    /// The stem of the body mesh it is computed on.
    pub mesh_stem: String,
    pub path: PathBuf,
    pub grid: FlankGrid,
    /// `local_model`, `mesh_inputs_hash` and `mesh_file_sha256` are left
    /// empty: the mesh and the FE model supply them.
    pub config: StiffnessConfig,
}

/// The stiffness file of `member` × `blank` at `level` for loads on its
/// `side` flank, in the mesh folder `dir`.
pub fn plan(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
    side: Side,
) -> Result<StiffnessPlan, GeometryError> {
    let sc = &scene.scene;
    let stem = paths::stiffness_stem(member, blank, level, side, sc.loaded_flank);
    let md = g.data.member(member);
    let st = &sc.stiffness;
    let grid = GridSize {
        profile: if st.grid_profile == 0 {
            sc.mesh.reduced_order.profile as usize
        } else {
            st.grid_profile
        },
        face: if st.grid_face == 0 {
            sc.mesh.reduced_order.face as usize
        } else {
            st.grid_face
        },
    };
    let fg = FlankGrid::new(g.flank(member, side), grid)?;
    let (sf, sp) = fg.spacing();
    // The teeth of the mesh the file is computed on: the scene's, or those
    // of a mesh refined on more teeth that serves it.
    let serving = serving_mesh(scene, g, dir, member, blank, level);
    let [loaded, opposite] = match &serving {
        Some(e) => [
            e.inputs.refined_teeth.clone(),
            e.inputs.opposite_refined_teeth.clone(),
        ],
        None => [
            refined_teeth_on(g, sc, member, blank, sc.loaded_flank),
            opposite_refined_teeth(g, sc, member, blank),
        ],
    };
    let refined = match (serving.is_some(), side == sc.loaded_flank) {
        (_, true) => loaded.clone(),
        (true, false) => opposite.clone(),
        (false, false) => refined_teeth_on(g, sc, member, blank, side),
    };
    let axisymmetric = blank == Blank::Standard;
    // The mesh's periodic master (refined on both flanks with coast-side
    // contact), where this side is refined on it: the teeth around it are
    // its sector turned, so its loads hold for them by rotation.
    let periodic = periodic_teeth(blank, &loaded, &opposite);
    let solved_teeth = if axisymmetric {
        match periodic.first() {
            Some(&m) if refined.contains(&m) => vec![m],
            _ => solved_tooth(&refined).into_iter().collect(),
        }
    } else {
        refined.clone()
    };
    let r = st.response_teeth as i32;
    let config = StiffnessConfig {
        schema: STIFFNESS_SCHEMA,
        member: member.name().into(),
        blank: blank.name().into(),
        level: level.name().into(),
        loaded_flank: side.flank_name(member).into(),
        grid,
        load_radius_m: st.load_radius_factor * sf.max(sp),
        offsets: (-r..=r).collect(),
        solved_teeth,
        axisymmetric,
        youngs_modulus_pa: md.youngs_modulus,
        poisson_ratio: md.poisson_ratio,
        clamped_groups: vec!["bore".into()],
        local_model: String::new(),
        root_stress: st.root_stress,
        mesh_inputs_hash: String::new(),
        mesh_file_sha256: String::new(),
    };
    Ok(StiffnessPlan {
        path: paths::stiffness_h5(dir, &stem),
        mesh_stem: paths::mesh_stem(member, blank, level),
        stem,
        grid: fg,
        config,
    })
}

/// The manifest entry of the body mesh of `member` × `blank` at `level` in
/// `dir`, when there is one whose inputs serve the scene
/// ([`MeshInputs::serves`]): its refined teeth are those the stiffness
/// file is planned on. `None` when the folder, its manifest or the entry is
/// missing, or the mesh does not serve (the checks then name why).
fn serving_mesh(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    member: Member,
    blank: Blank,
    level: MeshLevel,
) -> Option<MeshEntry> {
    let manifest = Manifest::read(dir).ok()?;
    let entry = manifest
        .meshes
        .get(&paths::mesh_stem(member, blank, level))?
        .clone();
    let design_text = std::fs::read_to_string(&scene.design_path)
        .map(|t| geometry::design::geometry_text(&t))
        .ok()?;
    let elements = scene.scene.mesh.elements(level);
    let wanted = MeshInputs::of_scene(scene, g, &design_text, member, blank, elements);
    entry.inputs.serves(&wanted).is_empty().then_some(entry)
}

/// Which stage's output a [`CheckError`] is about, and so what a user runs
/// (or checks) to mend it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Remedy {
    /// The design file itself (unreadable or not a design).
    Design,
    /// The mesh folder: not readable as one (a file, no permission).
    Folder,
    /// The meshes (no manifest, an old schema, a mesh made from other
    /// inputs or changed since): `preprocess mesh`, then `preprocess
    /// stiffness`.
    Mesh,
    /// The stiffness file: `preprocess stiffness`.
    Stiffness,
}

/// Why a stiffness file cannot serve a scene.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    #[error(transparent)]
    Manifest(#[from] ManifestError),
    #[error("{}: cannot read the design file: {message}", .path.display())]
    Design { path: PathBuf, message: String },
    #[error("{stem}: the mesh was made from other scene inputs ({}); run `preprocess mesh` and `preprocess stiffness`", .fields.join("; "))]
    StaleMesh { stem: String, fields: Vec<String> },
    #[error("{stem}: no stiffness file in the manifest; run `preprocess stiffness`")]
    NoStiffness { stem: String },
    #[error("{stem}: the stiffness file was made for other inputs ({}); run `preprocess stiffness`", .fields.join("; "))]
    StaleStiffness { stem: String, fields: Vec<String> },
    #[error(transparent)]
    File(#[from] StiffnessFileError),
    #[error("{}: changed since the stiffness stage wrote it (SHA-256 {found}, the manifest lists {listed}); run `preprocess stiffness` again", .path.display())]
    Changed {
        path: PathBuf,
        found: String,
        listed: String,
    },
    #[error("{}: changed since the mesh stage wrote it (SHA-256 {found}, the manifest lists {listed}); run `preprocess mesh` again", .path.display())]
    MeshChanged {
        path: PathBuf,
        found: String,
        listed: String,
    },
    #[error("{}: {problem}; the file is damaged: delete it and run `preprocess stiffness` again", .path.display())]
    Nonsense { path: PathBuf, problem: String },
}

impl Remedy {
    /// What a user does about it, as the tail of an error message
    /// (`; run ...` or `; check ...`), for the scene file `scene`, its
    /// design file `design` and the mesh folder `dir` at `level`.
    ///
    /// The commands name the mesh root (`dir`'s parent) when it is not the
    /// default `meshes`, so that they write where this run reads; a root
    /// that does not exist is named as such first.
    pub fn advice(self, scene: &Path, design: &Path, dir: &Path, level: MeshLevel) -> String {
        let sc = scene.display();
        let [out, meshes, missing_root] = mesh_root_advice(dir);
        match self {
            Remedy::Design => format!("; check the design file {}", design.display()),
            Remedy::Folder => format!("; check the mesh folder {} (`--meshes`)", dir.display()),
            Remedy::Mesh => format!(
                "{missing_root}; run `preprocess mesh {sc} --level {}{out}`, then `preprocess stiffness {sc}{}{meshes}`",
                level.name(),
                level.option()
            ),
            Remedy::Stiffness => format!(
                "{missing_root}; run `preprocess stiffness {sc}{}{meshes}`",
                level.option()
            ),
        }
    }
}

/// For the commands a message gives about the mesh folder `dir`
/// (`<root>/<scene>`): the options ` --out <root>` (for `preprocess mesh`)
/// and ` --meshes <root>` (for `preprocess stiffness`), empty when the root
/// is the default `meshes`, so that the commands write where the run reads;
/// and `; no mesh folder <root> (`--meshes`)` when the root does not exist.
pub fn mesh_root_advice(dir: &Path) -> [String; 3] {
    let root = dir.parent().filter(|r| !r.as_os_str().is_empty());
    let [out, meshes] = match root.filter(|r| *r != Path::new("meshes")) {
        Some(r) => ["out", "meshes"].map(|o| format!(" --{o} {}", r.display())),
        None => [String::new(), String::new()],
    };
    let missing = match root {
        Some(r) if !r.exists() => format!("; no mesh folder {} (`--meshes`)", r.display()),
        _ => String::new(),
    };
    [out, meshes, missing]
}

impl CheckError {
    /// What mends this error: the stage to run again, or the design or
    /// the mesh folder to look at.
    pub fn remedy(&self) -> Remedy {
        match self {
            CheckError::Geometry(_) | CheckError::Design { .. } => Remedy::Design,
            CheckError::Manifest(ManifestError::Unreadable { .. } | ManifestError::Write(_)) => {
                Remedy::Folder
            }
            CheckError::Manifest(ManifestError::NoEntry { stage, .. }) if *stage != "mesh" => {
                Remedy::Stiffness
            }
            CheckError::Manifest(_)
            | CheckError::StaleMesh { .. }
            | CheckError::MeshChanged { .. } => Remedy::Mesh,
            CheckError::NoStiffness { .. }
            | CheckError::StaleStiffness { .. }
            | CheckError::File(_)
            | CheckError::Changed { .. }
            | CheckError::Nonsense { .. } => Remedy::Stiffness,
        }
    }
}

/// The manifest entry of the body mesh `stem` in `dir`, checked to be made
/// from the scene's current inputs (design geometry, blank, flank elements
/// of `level`; refined teeth: the scene's or more,
/// [`MeshInputs::serves`]); each field that differs is named. The
/// `.msh` bytes are not read here: a reader that opens the mesh compares
/// its SHA-256 with the entry's `msh_sha256` ([`CheckError::MeshChanged`]).
pub fn check_mesh(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    stem: &str,
    member: Member,
    blank: Blank,
    level: MeshLevel,
) -> Result<MeshEntry, CheckError> {
    let design_text = std::fs::read_to_string(&scene.design_path)
        .map(|t| geometry::design::geometry_text(&t))
        .map_err(|e| CheckError::Design {
            path: scene.design_path.clone(),
            message: e.to_string(),
        })?;
    let manifest = Manifest::read(dir)?;
    let mesh = manifest.mesh(dir, stem)?;
    let elements = scene.scene.mesh.elements(level);
    let wanted = MeshInputs::of_scene(scene, g, &design_text, member, blank, elements);
    let fields = mesh.inputs.serves(&wanted);
    if !fields.is_empty() {
        return Err(CheckError::StaleMesh {
            stem: stem.to_string(),
            fields,
        });
    }
    Ok(mesh.clone())
}

/// The files behind a stiffness file, as a result set records them
/// ([`crate::result_set::ResultSet::record_input`]): the design's geometry
/// text, the body mesh and the stiffness file, each with its SHA-256 as the
/// manifest of `dir` lists it (call after [`check`], which verified them).
pub fn inputs_of(dir: &Path, plan: &StiffnessPlan) -> Result<Vec<(String, String)>, CheckError> {
    let manifest = Manifest::read(dir)?;
    let mesh = manifest.mesh(dir, &plan.mesh_stem)?;
    let entry = mesh
        .stiffness
        .get(&plan.stem)
        .ok_or_else(|| CheckError::NoStiffness {
            stem: plan.stem.clone(),
        })?;
    Ok(vec![
        ("design".into(), mesh.inputs.design_sha256.clone()),
        (format!("mesh:{}", plan.mesh_stem), mesh.msh_sha256.clone()),
        (format!("stiffness:{}", plan.stem), entry.sha256.clone()),
    ])
}

/// Reads the stiffness file `plan` names and checks that it serves the scene:
/// the folder's manifest says its mesh was made from the scene's current
/// inputs and lists this file; the file's bytes are the ones listed
/// (SHA-256, checked before HDF5 opens it) and its hash is the manifest's;
/// its numbers make physical sense ([`crate::stiffness_sense`]); and its
/// config equals the plan's (completed with the mesh's hashes from the
/// manifest and the file's own local model). Every mismatch is named by
/// field.
pub fn check(
    scene: &LoadedScene,
    g: &PairGeometry,
    dir: &Path,
    plan: &StiffnessPlan,
    member: Member,
    blank: Blank,
    level: MeshLevel,
) -> Result<StiffnessData, CheckError> {
    let mesh = check_mesh(scene, g, dir, &plan.mesh_stem, member, blank, level)?;
    let entry = mesh
        .stiffness
        .get(&plan.stem)
        .ok_or_else(|| CheckError::NoStiffness {
            stem: plan.stem.clone(),
        })?;
    // The file is the one the stiffness stage listed (not replaced or
    // damaged since), and its numbers make physical sense.
    let sha = crate::manifest::sha256_file(&plan.path).map_err(|e| {
        CheckError::File(StiffnessFileError::Hdf5 {
            path: plan.path.clone(),
            message: e.to_string(),
        })
    })?;
    if sha != entry.sha256 {
        return Err(CheckError::Changed {
            path: plan.path.clone(),
            found: sha,
            listed: entry.sha256.clone(),
        });
    }
    let data = stiffness_file::read(&plan.path, Some(&entry.input_hash))?;
    if let Some(problem) = crate::stiffness_sense::first_problem(&data) {
        return Err(CheckError::Nonsense {
            path: plan.path.clone(),
            problem,
        });
    }
    let found: StiffnessConfig =
        serde_json::from_str(&data.config).map_err(|e| CheckError::StaleStiffness {
            stem: plan.stem.clone(),
            fields: vec![format!("config unreadable: {e}")],
        })?;
    let expected = StiffnessConfig {
        local_model: found.local_model.clone(),
        mesh_inputs_hash: mesh.inputs_hash.clone(),
        mesh_file_sha256: mesh.msh_sha256.clone(),
        ..plan.config.clone()
    };
    let fields = field_differences(&found, &expected, "in the file", "for the scene");
    if !fields.is_empty() {
        return Err(CheckError::StaleStiffness {
            stem: plan.stem.clone(),
            fields,
        });
    }
    Ok(data)
}
