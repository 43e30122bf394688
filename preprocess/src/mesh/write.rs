//! Writes the mesh file: gmsh writes MSH 4.1 (ASCII) itself, to a temporary
//! name next to the target that is then renamed over it, so that no partial
//! file remains.

use super::request::{gmsh_err, other_err, MeshError, MeshRequest};
use gmsh::Session;
use std::path::{Path, PathBuf};

/// Writes the current mesh to `out` (`.<stem>.tmp.msh` in the same
/// directory, renamed to `out`), creating the directory.
pub(super) fn write_msh(s: &Session, req: &MeshRequest, out: &Path) -> Result<(), MeshError> {
    let g = |e| gmsh_err(req, e);
    let dir = out.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)
        .map_err(|e| other_err(req, format!("cannot create {}: {e}", dir.display())))?;
    let tmp: PathBuf = dir.join(format!(
        ".{}.tmp.msh",
        out.file_stem().and_then(|x| x.to_str()).unwrap_or("mesh")
    ));
    s.option_set_number("Mesh.MshFileVersion", 4.1).map_err(g)?;
    s.option_set_number("Mesh.Binary", 0.0).map_err(g)?;
    s.write(&tmp).map_err(g)?;
    std::fs::rename(&tmp, out)
        .map_err(|e| other_err(req, format!("cannot rename {}: {e}", tmp.display())))?;
    Ok(())
}
