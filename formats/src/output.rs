//! Atomic output files: write to a temporary file in the target directory,
//! then rename, so that a reader never sees a partial file.

use serde::Serialize;
use std::io::Write;
use std::path::Path;

/// A file that could not be written: names the file and the cause.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}: {message}", .path.display())]
pub struct WriteError {
    pub path: std::path::PathBuf,
    pub message: String,
}

fn write_err(path: &Path, e: impl std::fmt::Display) -> WriteError {
    WriteError {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Writes `bytes` to `path` atomically (temp file in the same directory + rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)
        .map_err(|e| write_err(path, format!("cannot create {}: {e}", dir.display())))?;
    let mut tmp = tempfile::NamedTempFile::new_in(dir).map_err(|e| write_err(path, e))?;
    // Removed by the termination handler if the run is stopped (a signal
    // ends the process without running the temporary file's destructor).
    let _on_interrupt = crate::interrupt::pending_file(tmp.path());
    tmp.write_all(bytes).map_err(|e| write_err(path, e))?;
    tmp.as_file().sync_all().map_err(|e| write_err(path, e))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let perm = std::fs::Permissions::from_mode(0o644);
        std::fs::set_permissions(tmp.path(), perm).map_err(|e| write_err(path, e))?;
    }
    crate::stop_point::at("writing");
    tmp.persist(path).map_err(|e| write_err(path, e.error))?;
    Ok(())
}

/// Has `write` make the file `path` through a temporary path beside it (for
/// writers that open the file themselves: HDF5, gmsh, meshio), then renames
/// it onto `path`; on failure the temporary file is removed and `path` is
/// left as it was. `write`'s error is returned as it is; a failed rename
/// becomes `E` through [`WriteError`].
pub fn write_via<E: From<WriteError>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), E> {
    // Hidden, per process, and ending in the file's own name (writers such
    // as meshio choose the format by the extension).
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(
        ".tmp.{}.{}",
        std::process::id(),
        name.as_deref().unwrap_or("out")
    ));
    let on_interrupt = crate::interrupt::pending_file(&tmp);
    let r = write(&tmp).and_then(|()| {
        crate::stop_point::at("writing");
        std::fs::rename(&tmp, path).map_err(|e| {
            E::from(write_err(
                path,
                format!("cannot rename {}: {e}", tmp.display()),
            ))
        })
    });
    if r.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    drop(on_interrupt);
    r
}

/// Writes a value as pretty JSON, atomically.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), WriteError> {
    let text = serde_json::to_string_pretty(value).map_err(|e| write_err(path, e))?;
    write_atomic(path, text.as_bytes())
}

/// Peak resident memory of this process (VmHWM from /proc), GiB; NaN where
/// /proc is not there. For benchmarks.
pub fn peak_memory_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|v| v.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb / 1024.0 / 1024.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn write_via_renames_on_success_and_leaves_nothing_on_failure() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.vtu");
        write_via(&path, |tmp| -> Result<(), WriteError> {
            assert!(tmp.to_string_lossy().ends_with(".vtu"), "{}", tmp.display());
            std::fs::write(tmp, "new").map_err(|e| write_err(tmp, e))
        })
        .unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        let r = write_via(&path, |tmp| -> Result<(), WriteError> {
            std::fs::write(tmp, "half").unwrap();
            Err(write_err(tmp, "the writer failed"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
