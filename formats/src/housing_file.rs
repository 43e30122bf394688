//! The housing file: the gearbox housing reduced onto its bearing seats
//! (`preprocess housing`, read by `solver dynamic`), one HDF5 file
//! `<meshes>/<scene>/housing.h5`.
//!
//! Root attributes: `schema_version` ([`HOUSING_SCHEMA`]), `input_hash`
//! (SHA-256 of [`input_hash`]'s text: the schema, the housing's settings
//! and its layout), `config` (that text, JSON), `producer`.
//!
//! | dataset | shape | content |
//! |---|---|---|
//! | `reduced/stiffness`, `reduced/mass` | r × r | K_r (N/m, N, N·m per unit coordinate) and M_r: 6 coordinates per seat (u_x, u_y, u_z in m, θ_x, θ_y, θ_z in rad of the seat's reference point, assembly frame), then the fixed-interface modes' |
//! | `seats/member`, `seats/bearing` | s | the bearing each seat holds: member (0 pinion, 1 wheel) and its index in `[bearings]` |
//! | `seats/reference` | s × 3 | the seat's reference point (the bearing's centre), assembly frame (m) |
//! | `seats/nodes` | s | mesh nodes on each seat's bore |
//! | `modes/fixed_interface_hz` | k | the kept fixed-interface modes |
//! | `check/reduced_hz`, `check/reference_hz` | c | the housing's modes (feet clamped, seats rigid and free) up to the gearbox's `modes_up_to_hz`: the reduced model's, and the whole FE model's without truncation (the reduction's check) |
//!
//! Scalars (attributes): `mass_kg`, `nodes`, `elements`, `least_gap_m`.

use crate::stiffness_file::{h5, write_dataset, StiffnessFileError};
use std::path::{Path, PathBuf};

/// The housing file of scene `scene` under the meshes' root.
pub fn path(meshes: &Path, scene: &str) -> PathBuf {
    meshes.join(scene).join("housing.h5")
}

/// Bumped whenever the layout or meaning changes.
pub const HOUSING_SCHEMA: u32 = 1;

/// The housing file's content.
#[derive(Debug, Clone, PartialEq)]
pub struct HousingData {
    pub input_hash: String,
    /// The producing configuration as JSON.
    pub config: String,
    /// Row-major r × r.
    pub stiffness: Vec<f64>,
    pub mass: Vec<f64>,
    pub seat_member: Vec<u32>,
    pub seat_bearing: Vec<u32>,
    pub seat_reference: Vec<[f64; 3]>,
    pub seat_nodes: Vec<u32>,
    pub fixed_interface_hz: Vec<f64>,
    pub reference_hz: Vec<f64>,
    pub reduced_hz: Vec<f64>,
    pub mass_kg: f64,
    pub nodes: u32,
    pub elements: u32,
    pub least_gap_m: f64,
}

impl HousingData {
    /// Number of reduced coordinates r.
    pub fn coordinates(&self) -> usize {
        (self.stiffness.len() as f64).sqrt().round() as usize
    }

    /// Largest |reduced/whole − 1| of the housing's modes compared
    /// (`check/reduced_hz` against `check/reference_hz`).
    pub fn truncation_error(&self) -> f64 {
        self.reduced_hz
            .iter()
            .zip(&self.reference_hz)
            .map(|(x, y)| (x / y - 1.0).abs())
            .fold(0.0, f64::max)
    }
}

/// The input hash of a housing from its configuration text.
pub fn input_hash(config: &str) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    h.update(format!("housing schema {HOUSING_SCHEMA}\n"));
    h.update(config.as_bytes());
    format!("{:x}", h.finalize())
}

fn err(path: &Path) -> impl Fn(hdf5::Error) -> StiffnessFileError + '_ {
    move |e| StiffnessFileError::Hdf5 {
        path: path.to_path_buf(),
        message: format!("housing file: {e}"),
    }
}

/// Writes `d` to `path` atomically.
pub fn write(path: &Path, d: &HousingData) -> Result<(), StiffnessFileError> {
    crate::output::write_via(path, |tmp| write_to(tmp, d))
}

fn write_to(path: &Path, d: &HousingData) -> Result<(), StiffnessFileError> {
    let e = err(path);
    let r = d.coordinates();
    if r * r != d.stiffness.len() || d.mass.len() != d.stiffness.len() {
        return Err(StiffnessFileError::Shape {
            path: path.to_path_buf(),
            dataset: "reduced/mass".into(),
            found: d.mass.len(),
            expected: d.stiffness.len(),
        });
    }
    let f = h5().create(path).map_err(&e)?;
    f.new_attr::<u32>()
        .create("schema_version")
        .and_then(|a| a.write_scalar(&HOUSING_SCHEMA))
        .map_err(&e)?;
    for (k, v) in [
        ("input_hash", d.input_hash.as_str()),
        ("config", d.config.as_str()),
        (
            "producer",
            concat!("preprocess ", env!("CARGO_PKG_VERSION")),
        ),
    ] {
        let v: hdf5::types::VarLenUnicode = v.parse().expect("no NUL in attribute text");
        f.new_attr::<hdf5::types::VarLenUnicode>()
            .create(k)
            .and_then(|a| a.write_scalar(&v))
            .map_err(&e)?;
    }
    for (k, v) in [("mass_kg", d.mass_kg), ("least_gap_m", d.least_gap_m)] {
        f.new_attr::<f64>()
            .create(k)
            .and_then(|a| a.write_scalar(&v))
            .map_err(&e)?;
    }
    for (k, v) in [("nodes", d.nodes), ("elements", d.elements)] {
        f.new_attr::<u32>()
            .create(k)
            .and_then(|a| a.write_scalar(&v))
            .map_err(&e)?;
    }
    let s = d.seat_member.len();
    let refs: Vec<f64> = d.seat_reference.iter().flatten().copied().collect();
    write_dataset(&f, "reduced/stiffness", &[r, r], &d.stiffness, "SI").map_err(&e)?;
    write_dataset(&f, "reduced/mass", &[r, r], &d.mass, "SI").map_err(&e)?;
    write_dataset(&f, "seats/member", &[s], &d.seat_member, "1").map_err(&e)?;
    write_dataset(&f, "seats/bearing", &[s], &d.seat_bearing, "1").map_err(&e)?;
    write_dataset(&f, "seats/reference", &[s, 3], &refs, "m").map_err(&e)?;
    write_dataset(&f, "seats/nodes", &[s], &d.seat_nodes, "1").map_err(&e)?;
    for (k, v) in [
        ("modes/fixed_interface_hz", &d.fixed_interface_hz),
        ("check/reference_hz", &d.reference_hz),
        ("check/reduced_hz", &d.reduced_hz),
    ] {
        write_dataset(&f, k, &[v.len()], v, "Hz").map_err(&e)?;
    }
    f.flush().map_err(&e)?;
    f.close().map_err(&e)?;
    Ok(())
}

/// Reads a housing file, checking its schema and, if given, its input hash.
pub fn read(path: &Path, expected_hash: Option<&str>) -> Result<HousingData, StiffnessFileError> {
    let e = err(path);
    let f = h5().open(path).map_err(&e)?;
    let schema: u32 = f
        .attr("schema_version")
        .and_then(|a| a.read_scalar())
        .map_err(&e)?;
    if schema != HOUSING_SCHEMA {
        return Err(StiffnessFileError::Schema {
            path: path.to_path_buf(),
            found: schema,
            expected: HOUSING_SCHEMA,
        });
    }
    let text = |k: &str| -> Result<String, StiffnessFileError> {
        let v: hdf5::types::VarLenUnicode = f.attr(k).and_then(|a| a.read_scalar()).map_err(&e)?;
        std::str::from_utf8(v.as_bytes())
            .map(str::to_string)
            .map_err(|x| StiffnessFileError::Hdf5 {
                path: path.to_path_buf(),
                message: format!("housing file: attribute {k} is not UTF-8 text: {x}"),
            })
    };
    let input_hash = text("input_hash")?;
    if let Some(x) = expected_hash {
        if x != input_hash {
            return Err(StiffnessFileError::Hash {
                path: path.to_path_buf(),
                found: input_hash,
                expected: x.to_string(),
            });
        }
    }
    let scalar = |k: &str| -> Result<f64, StiffnessFileError> {
        f.attr(k).and_then(|a| a.read_scalar()).map_err(&e)
    };
    let count = |k: &str| -> Result<u32, StiffnessFileError> {
        f.attr(k).and_then(|a| a.read_scalar()).map_err(&e)
    };
    let shape_err = |dataset: &str, found: usize, expected: usize| StiffnessFileError::Shape {
        path: path.to_path_buf(),
        dataset: dataset.into(),
        found,
        expected,
    };
    let floats = |k: &str| -> Result<Vec<f64>, StiffnessFileError> {
        f.dataset(k).and_then(|d| d.read_raw()).map_err(&e)
    };
    let ints = |k: &str| -> Result<Vec<u32>, StiffnessFileError> {
        f.dataset(k).and_then(|d| d.read_raw()).map_err(&e)
    };
    let stiffness = floats("reduced/stiffness")?;
    let mass = floats("reduced/mass")?;
    let r = (stiffness.len() as f64).sqrt().round() as usize;
    if r * r != stiffness.len() {
        return Err(shape_err("reduced/stiffness", stiffness.len(), r * r));
    }
    if mass.len() != stiffness.len() {
        return Err(shape_err("reduced/mass", mass.len(), stiffness.len()));
    }
    let seat_member = ints("seats/member")?;
    let s = seat_member.len();
    let seat_bearing = ints("seats/bearing")?;
    let refs = floats("seats/reference")?;
    let seat_nodes = ints("seats/nodes")?;
    for (k, n, want) in [
        ("seats/bearing", seat_bearing.len(), s),
        ("seats/reference", refs.len(), 3 * s),
        ("seats/nodes", seat_nodes.len(), s),
    ] {
        if n != want {
            return Err(shape_err(k, n, want));
        }
    }
    if r < 6 * s {
        return Err(shape_err("reduced/stiffness", r, 6 * s));
    }
    Ok(HousingData {
        config: text("config")?,
        input_hash,
        stiffness,
        mass,
        seat_member,
        seat_bearing,
        seat_reference: refs.chunks(3).map(|c| [c[0], c[1], c[2]]).collect(),
        seat_nodes,
        fixed_interface_hz: floats("modes/fixed_interface_hz")?,
        reference_hz: floats("check/reference_hz")?,
        reduced_hz: floats("check/reduced_hz")?,
        mass_kg: scalar("mass_kg")?,
        nodes: count("nodes")?,
        elements: count("elements")?,
        least_gap_m: scalar("least_gap_m")?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> HousingData {
        let r = 8;
        HousingData {
            input_hash: input_hash("{}"),
            config: "{}".into(),
            stiffness: (0..r * r).map(|i| i as f64).collect(),
            mass: (0..r * r).map(|i| 0.5 * i as f64).collect(),
            seat_member: vec![1],
            seat_bearing: vec![0],
            seat_reference: vec![[0.0, 0.1, 0.2]],
            seat_nodes: vec![42],
            fixed_interface_hz: vec![100.0, 200.0],
            reference_hz: vec![50.0],
            reduced_hz: vec![50.1],
            mass_kg: 12.5,
            nodes: 1000,
            elements: 500,
            least_gap_m: 0.01,
        }
    }

    #[test]
    fn housing_file_round_trip_and_hash_mismatch() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("housing.h5");
        let d = sample();
        write(&p, &d).unwrap();
        assert_eq!(read(&p, Some(&d.input_hash)).unwrap(), d);
        let e = read(&p, Some(&input_hash("other"))).unwrap_err();
        assert!(matches!(e, StiffnessFileError::Hash { .. }), "{e}");
    }
}
