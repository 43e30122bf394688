//! Writes the mesh file: gmsh writes MSH 4.1 (ASCII) itself, through
//! [`formats::output::write_via`] (a temporary name beside the target, then
//! renamed over it), so that no partial file remains.

use super::request::{gmsh_err, other_err, MeshError, MeshRequest};
use formats::output::{write_via, WriteError};
use gmsh::Session;
use std::path::Path;

/// Writes the current mesh to `out`, creating the directory.
pub(super) fn write_msh(s: &Session, req: &MeshRequest, out: &Path) -> Result<(), MeshError> {
    let g = |e| gmsh_err(req, e);
    let dir = out.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)
        .map_err(|e| other_err(req, format!("cannot create {}: {e}", dir.display())))?;
    s.option_set_number("Mesh.MshFileVersion", 4.1).map_err(g)?;
    s.option_set_number("Mesh.Binary", 0.0).map_err(g)?;
    write_via(out, |tmp| {
        s.write(tmp).map_err(|e| WriteError {
            path: out.to_path_buf(),
            message: format!("gmsh: {e}"),
        })
    })
    .map_err(|e| other_err(req, e.to_string()))
}
