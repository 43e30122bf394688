//! Stiffness files: one HDF5 file per member × blank × mesh level holding the
//! contact grid and the compliance blocks of the reduced model.
//!
//! Layout (schema [`STIFFNESS_SCHEMA`]); every dataset carries a `units`
//! attribute and the root carries `schema_version`, `input_hash` (SHA-256 of
//! everything that determines the content) and `config` (JSON):
//!
//! | dataset | shape | content |
//! |---|---|---|
//! | `grid/xi`, `grid/eta` | face, profile | normalised flank parameters of the grid |
//! | `grid/position` | points × 3 | tooth 0, member frame (m) |
//! | `grid/normal` | points × 3 | outward unit normal |
//! | `grid/lever` | points | moment arm about the member axis of a unit force along −n (m) |
//! | `teeth/solved`, `teeth/offsets` | s, o | loaded teeth; responding teeth relative to them |
//! | `grid/depth_h` | s × points | mid-surface depth h of each point (m) |
//! | `compliance/total`, `compliance/global` | s × o × points × points | normal approach at point j of tooth solved+offset under a unit load at point i (m/N) |
//! | `compliance/local` | s × points × points | the near-load part on the loaded tooth (m/N) |
//! | `root_stress/offsets` | r | responding teeth of the root stress, relative to the loaded one |
//! | `root_stress/xi`, `root_stress/height` | fillet points | face-width position (0 toe, 1 heel) and fillet height (0 root, 1 flank junction) of each fillet point: the loaded flank's fillet's points, then the other flank's |
//! | `root_stress/stress` | s × r × points × fillet points × 6 | stress (Voigt xx, yy, zz, yz, xz, xy) at each fillet point of tooth solved+offset under a unit load at grid point i, in that tooth's own frame turned back onto tooth 0 (Pa/N), single precision (schema 3; double before) |
//!
//! Point index = i_face · profile + i_profile. Fillet points: side-major,
//! then face-major over [`ROOT_STRESS_GRID`] (ξ, height) cell centres.

use std::path::{Path, PathBuf};

/// Bumped whenever the file layout or its meaning changes (also when
/// [`ROOT_STRESS_GRID`] or [`ROOT_STRESS_OFFSETS`] change).
pub const STIFFNESS_SCHEMA: u32 = 3;

/// Fillet points per fillet side where the root stress is stored: across
/// the face width × up the fillet (cell centres of the unit square).
pub const ROOT_STRESS_GRID: [usize; 2] = [21, 9];

/// Responding teeth of the root stress, relative to the loaded tooth (those
/// of them the file's offsets hold).
pub const ROOT_STRESS_OFFSETS: [i32; 3] = [-1, 0, 1];

/// The stiffness file's root-stress influence coefficients.
#[derive(Debug, Clone, PartialEq)]
pub struct RootStressBlock {
    /// Responding teeth relative to the loaded one.
    pub offsets: Vec<i32>,
    /// Per fillet point: face-width position and fillet height; the loaded
    /// flank's fillet's points first, then the other flank's.
    pub xi: Vec<f64>,
    pub height: Vec<f64>,
    /// stress[s][r][i][point][6], Pa/N (see the module's table).
    pub stress: Vec<f64>,
}

impl RootStressBlock {
    /// Fillet points (both sides).
    pub fn points(&self) -> usize {
        self.xi.len()
    }

    /// The (xi, height) of the cell centres of one fillet side, face-major.
    pub fn side_points() -> (Vec<f64>, Vec<f64>) {
        let [nf, nh] = ROOT_STRESS_GRID;
        let mut xi = Vec::with_capacity(nf * nh);
        let mut h = Vec::with_capacity(nf * nh);
        for a in 0..nf {
            for b in 0..nh {
                xi.push((a as f64 + 0.5) / nf as f64);
                h.push((b as f64 + 0.5) / nh as f64);
            }
        }
        (xi, h)
    }
}

/// Everything besides the mesh that determines a stiffness file.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StiffnessConfig {
    pub schema: u32,
    pub member: String,
    pub blank: String,
    pub level: String,
    pub loaded_flank: String,
    pub grid: geometry::contact_grid::GridSize,
    pub load_radius_m: f64,
    pub offsets: Vec<i32>,
    pub solved_teeth: Vec<usize>,
    pub axisymmetric: bool,
    pub youngs_modulus_pa: f64,
    pub poisson_ratio: f64,
    pub clamped_groups: Vec<String>,
    /// How the local (near-load) field is computed (the stiffness stage's `influence::local_model`).
    pub local_model: String,
    /// Whether the file holds root-stress coefficients (the scene's
    /// `[stiffness] root_stress`).
    pub root_stress: bool,
    /// Hash of the mesh inputs (from `<stem>.inputs.json`) and of the mesh file.
    pub mesh_inputs_hash: String,
    pub mesh_file_sha256: String,
}

impl StiffnessConfig {
    /// The config as the file stores it (JSON) and its SHA-256, the file's
    /// `input_hash`.
    pub fn json_and_hash(&self) -> (String, String) {
        let json = serde_json::to_string(self).expect("a config serializes");
        let hash = crate::manifest::sha256_text(&json);
        (json, hash)
    }
}

/// Errors reading or writing a stiffness file (or a housing file, [`crate::housing_file`]).
#[derive(Debug, thiserror::Error)]
pub enum StiffnessFileError {
    #[error("{path}: {message}")]
    Hdf5 { path: PathBuf, message: String },
    #[error("{path}: schema version {found}, this program reads {expected}")]
    Schema {
        path: PathBuf,
        found: u32,
        expected: u32,
    },
    #[error("{path}: input hash {found} does not match the current inputs ({expected}); it was made for other inputs")]
    Hash {
        path: PathBuf,
        found: String,
        expected: String,
    },
    #[error("{path}: dataset {dataset} has {found} values, expected {expected}")]
    Shape {
        path: PathBuf,
        dataset: String,
        found: usize,
        expected: usize,
    },
    #[error(transparent)]
    Write(#[from] crate::output::WriteError),
}

/// The content of a stiffness file.
#[derive(Debug, Clone, PartialEq)]
pub struct StiffnessData {
    pub input_hash: String,
    /// The producing configuration as JSON.
    pub config: String,
    pub member: String,
    pub blank: String,
    pub level: String,
    pub teeth: usize,
    /// True when one tooth's fields stand for all (axisymmetric blank).
    pub axisymmetric: bool,
    pub grid_profile: usize,
    pub grid_face: usize,
    pub xi: Vec<f64>,
    pub eta: Vec<f64>,
    pub position: Vec<f64>,
    pub normal: Vec<f64>,
    pub lever: Vec<f64>,
    pub solved_teeth: Vec<u32>,
    pub offsets: Vec<i32>,
    pub depth_h: Vec<f64>,
    pub total: Vec<f64>,
    pub local: Vec<f64>,
    pub global: Vec<f64>,
    /// Root-stress influence coefficients (None: not computed).
    pub root_stress: Option<RootStressBlock>,
}

impl StiffnessData {
    pub fn points(&self) -> usize {
        self.grid_profile * self.grid_face
    }

    /// Global compliance (m/N): load at point i of solved tooth s, response at
    /// point j of tooth solved[s] + offsets[o].
    pub fn global_at(&self, s: usize, o: usize, i: usize, j: usize) -> f64 {
        let np = self.points();
        self.global[((s * self.offsets.len() + o) * np + i) * np + j]
    }
}

fn h5err(path: &Path) -> impl Fn(hdf5::Error) -> StiffnessFileError + '_ {
    move |e| StiffnessFileError::Hdf5 {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Opens HDF5 files without HDF5's `flock` file locking. The lock belongs to
/// the open file description, so a subprocess forked by another thread while
/// a file is open (gmsh, meshio, python) inherits it and keeps the file locked
/// after we have closed it. Writes are atomic by rename, so the lock protects
/// nothing here.
pub fn h5() -> hdf5::FileBuilder {
    let mut b = hdf5::File::with_options();
    b.fapl().file_locking(false);
    b
}

/// Writes a float dataset of `shape` with a `units` attribute.
pub fn write_dataset<T: hdf5::H5Type>(
    f: &hdf5::File,
    name: &str,
    shape: &[usize],
    v: &[T],
    units: &str,
) -> hdf5::Result<()> {
    let ds = f.new_dataset::<T>().shape(shape.to_vec()).create(name)?;
    ds.write_raw(v)?;
    ds.new_attr::<hdf5::types::VarLenUnicode>()
        .create("units")?
        .write_scalar(&vlu(units))
}

fn vlu(s: &str) -> hdf5::types::VarLenUnicode {
    s.parse().expect("no NUL in attribute text")
}

/// Writes `data` to `path` atomically (temporary file in the same directory, then rename).
pub fn write(path: &Path, data: &StiffnessData) -> Result<(), StiffnessFileError> {
    crate::output::write_via(path, |tmp| write_to(tmp, data))
}

fn write_to(path: &Path, d: &StiffnessData) -> Result<(), StiffnessFileError> {
    let e = h5err(path);
    let f = h5().create(path).map_err(&e)?;
    let sattr = |loc: &hdf5::Location, name: &str, v: &str| -> hdf5::Result<()> {
        loc.new_attr::<hdf5::types::VarLenUnicode>()
            .create(name)?
            .write_scalar(&vlu(v))
    };
    f.new_attr::<u32>()
        .create("schema_version")
        .and_then(|a| a.write_scalar(&STIFFNESS_SCHEMA))
        .map_err(&e)?;
    for (k, v) in [
        ("input_hash", d.input_hash.as_str()),
        ("config", d.config.as_str()),
        ("member", d.member.as_str()),
        ("blank", d.blank.as_str()),
        ("level", d.level.as_str()),
        (
            "producer",
            concat!("preprocess ", env!("CARGO_PKG_VERSION")),
        ),
    ] {
        sattr(&f, k, v).map_err(&e)?;
    }
    for (k, v) in [
        ("teeth", d.teeth as u32),
        ("axisymmetric", d.axisymmetric as u32),
        ("grid_profile", d.grid_profile as u32),
        ("grid_face", d.grid_face as u32),
    ] {
        f.new_attr::<u32>()
            .create(k)
            .and_then(|a| a.write_scalar(&v))
            .map_err(&e)?;
    }
    let np = d.points();
    let ns = d.solved_teeth.len();
    let no = d.offsets.len();
    let put = |name: &str, shape: &[usize], v: &[f64], units: &str| {
        write_dataset(&f, name, shape, v, units)
    };
    f.create_group("grid").map_err(&e)?;
    f.create_group("teeth").map_err(&e)?;
    f.create_group("compliance").map_err(&e)?;
    put("grid/xi", &[d.grid_face], &d.xi, "1").map_err(&e)?;
    put("grid/eta", &[d.grid_profile], &d.eta, "1").map_err(&e)?;
    put("grid/position", &[np, 3], &d.position, "m").map_err(&e)?;
    put("grid/normal", &[np, 3], &d.normal, "1").map_err(&e)?;
    put("grid/lever", &[np], &d.lever, "m").map_err(&e)?;
    put("grid/depth_h", &[ns, np], &d.depth_h, "m").map_err(&e)?;
    put("compliance/total", &[ns, no, np, np], &d.total, "m/N").map_err(&e)?;
    put("compliance/local", &[ns, np, np], &d.local, "m/N").map_err(&e)?;
    put("compliance/global", &[ns, no, np, np], &d.global, "m/N").map_err(&e)?;
    f.new_dataset::<u32>()
        .shape([ns])
        .create("teeth/solved")
        .and_then(|ds| ds.write_raw(&d.solved_teeth[..]))
        .map_err(&e)?;
    f.new_dataset::<i32>()
        .shape([no])
        .create("teeth/offsets")
        .and_then(|ds| ds.write_raw(&d.offsets[..]))
        .map_err(&e)?;
    if let Some(r) = &d.root_stress {
        let nr = r.offsets.len();
        let nf = r.points();
        f.create_group("root_stress").map_err(&e)?;
        f.new_dataset::<i32>()
            .shape([nr])
            .create("root_stress/offsets")
            .and_then(|ds| ds.write_raw(&r.offsets[..]))
            .map_err(&e)?;
        put("root_stress/xi", &[nf], &r.xi, "1").map_err(&e)?;
        put("root_stress/height", &[nf], &r.height, "1").map_err(&e)?;
        // Single precision: the coefficients are summed over a few
        // hundred loads into stresses compared to a few per cent, and the
        // solver holds them as f32 anyway; half the file's largest block.
        let single: Vec<f32> = r.stress.iter().map(|&v| v as f32).collect();
        write_dataset(
            &f,
            "root_stress/stress",
            &[ns, nr, np, nf, 6],
            &single,
            "Pa/N",
        )
        .map_err(&e)?;
    }
    f.flush().map_err(&e)?;
    // Close now (not when the last handle drops) so the file can be renamed
    // and reopened at once.
    f.close().map_err(&e)?;
    Ok(())
}

/// Reads the schema version and input hash only.
fn read_header(path: &Path) -> Result<(u32, String), StiffnessFileError> {
    let e = h5err(path);
    let f = h5().open(path).map_err(&e)?;
    let schema: u32 = f
        .attr("schema_version")
        .and_then(|a| a.read_scalar())
        .map_err(&e)?;
    let hash: hdf5::types::VarLenUnicode = f
        .attr("input_hash")
        .and_then(|a| a.read_scalar())
        .map_err(&e)?;
    Ok((schema, utf8(path, "input_hash", &hash)?))
}

/// The text of a string attribute, refused unless it is UTF-8 (the HDF5
/// type does not check what a damaged file holds).
fn utf8(
    path: &Path,
    name: &str,
    v: &hdf5::types::VarLenUnicode,
) -> Result<String, StiffnessFileError> {
    std::str::from_utf8(v.as_bytes())
        .map(str::to_string)
        .map_err(|err| StiffnessFileError::Hdf5 {
            path: path.to_path_buf(),
            message: format!("attribute {name} is not UTF-8 text: {err}"),
        })
}

/// Largest number of values of one dataset the reader accepts before
/// reading it: a damaged header can claim any size.
const MAX_DATASET_VALUES: usize = 1 << 31;

/// Reads a stiffness file, checking its schema and, if given, its input hash.
pub fn read(path: &Path, expected_hash: Option<&str>) -> Result<StiffnessData, StiffnessFileError> {
    let (schema, hash) = read_header(path)?;
    if schema != STIFFNESS_SCHEMA {
        return Err(StiffnessFileError::Schema {
            path: path.to_path_buf(),
            found: schema,
            expected: STIFFNESS_SCHEMA,
        });
    }
    if let Some(x) = expected_hash {
        if x != hash {
            return Err(StiffnessFileError::Hash {
                path: path.to_path_buf(),
                found: hash,
                expected: x.to_string(),
            });
        }
    }
    let e = h5err(path);
    let f = h5().open(path).map_err(&e)?;
    let s = |k: &str| -> Result<String, StiffnessFileError> {
        let v: hdf5::types::VarLenUnicode = f.attr(k).and_then(|a| a.read_scalar()).map_err(&e)?;
        utf8(path, k, &v)
    };
    let u = |k: &str| -> Result<usize, StiffnessFileError> {
        Ok(f.attr(k).and_then(|a| a.read_scalar::<u32>()).map_err(&e)? as usize)
    };
    let shape_err = |dataset: &str, found: usize, expected: usize| StiffnessFileError::Shape {
        path: path.to_path_buf(),
        dataset: dataset.into(),
        found,
        expected,
    };
    // Every dataset's size is compared with the header before it is read,
    // so a damaged size is refused instead of allocated.
    let dataset = |name: &str,
                   expected: Option<usize>|
     -> Result<hdf5::Dataset, StiffnessFileError> {
        let ds = f.dataset(name).map_err(&e)?;
        let found = ds.size();
        match expected {
            Some(n) if found != n => Err(shape_err(name, found, n)),
            None if found > MAX_DATASET_VALUES => Err(shape_err(name, found, MAX_DATASET_VALUES)),
            _ => Ok(ds),
        }
    };
    let grid_profile = u("grid_profile")?;
    let grid_face = u("grid_face")?;
    let solved_teeth: Vec<u32> = dataset("teeth/solved", None)?.read_raw().map_err(&e)?;
    let offsets: Vec<i32> = dataset("teeth/offsets", None)?.read_raw().map_err(&e)?;
    let (ns, no) = (solved_teeth.len(), offsets.len());
    // Sizes from the header, refused when they overflow or exceed what a
    // reader accepts.
    let size = |name: &str, factors: &[usize]| -> Result<usize, StiffnessFileError> {
        factors
            .iter()
            .try_fold(1usize, |a, &b| a.checked_mul(b))
            .filter(|&n| n <= MAX_DATASET_VALUES)
            .ok_or_else(|| StiffnessFileError::Hdf5 {
                path: path.to_path_buf(),
                message: format!(
                    "dataset {name}: the header's sizes {factors:?} (grid_profile = {grid_profile}, grid_face = {grid_face}, {ns} solved teeth, {no} offsets) give more than {MAX_DATASET_VALUES} values"
                ),
            })
    };
    let np = size("grid", &[grid_profile, grid_face])?;
    let get = |name: &str, expected: usize| -> Result<Vec<f64>, StiffnessFileError> {
        let v: Vec<f64> = dataset(name, Some(expected))?.read_raw().map_err(&e)?;
        if v.len() != expected {
            return Err(shape_err(name, v.len(), expected));
        }
        Ok(v)
    };
    let n_total = size("compliance/total", &[ns, no, np, np])?;
    let n_local = size("compliance/local", &[ns, np, np])?;
    let root_stress = match f.group("root_stress") {
        Err(_) => None,
        Ok(_) => {
            let offsets: Vec<i32> = dataset("root_stress/offsets", None)?
                .read_raw()
                .map_err(&e)?;
            let nf = dataset("root_stress/xi", None)?.size();
            let n = size("root_stress/stress", &[ns, offsets.len(), np, nf, 6])?;
            let single: Vec<f32> = dataset("root_stress/stress", Some(n))?
                .read_raw()
                .map_err(&e)?;
            if single.len() != n {
                return Err(shape_err("root_stress/stress", single.len(), n));
            }
            Some(RootStressBlock {
                xi: get("root_stress/xi", nf)?,
                height: get("root_stress/height", nf)?,
                stress: single.into_iter().map(f64::from).collect(),
                offsets,
            })
        }
    };
    Ok(StiffnessData {
        root_stress,
        input_hash: hash,
        config: s("config")?,
        member: s("member")?,
        blank: s("blank")?,
        level: s("level")?,
        teeth: u("teeth")?,
        axisymmetric: u("axisymmetric")? != 0,
        grid_profile,
        grid_face,
        xi: get("grid/xi", grid_face)?,
        eta: get("grid/eta", grid_profile)?,
        position: get("grid/position", size("grid/position", &[3, np])?)?,
        normal: get("grid/normal", size("grid/normal", &[3, np])?)?,
        lever: get("grid/lever", np)?,
        depth_h: get("grid/depth_h", size("grid/depth_h", &[ns, np])?)?,
        total: get("compliance/total", n_total)?,
        local: get("compliance/local", n_local)?,
        global: get("compliance/global", n_total)?,
        solved_teeth,
        offsets,
    })
}
