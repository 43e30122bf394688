//! Finds the directory of the gmsh shared library installed by `make setup`
//! (the official gmsh wheel in `<workspace>/.venv`) and links against it.
//!
//! Lookup order: the env var `GMSH_LIB_DIR`, then the line `GMSH_LIB_DIR=...`
//! of `<workspace root>/.venv/gmsh-paths.env`. The directory is re-exported as
//! `cargo:libdir=...`, i.e. `DEP_GMSH_LIBDIR` for build scripts of crates that
//! depend on gmsh-sys directly.

use std::env;
use std::fs;
use std::path::{Path, PathBuf};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=GMSH_LIB_DIR");

    let manifest_dir =
        PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("CARGO_MANIFEST_DIR"));
    let workspace_root = manifest_dir.parent().unwrap_or(&manifest_dir);
    let paths_env = workspace_root.join(".venv").join("gmsh-paths.env");
    println!("cargo:rerun-if-changed={}", paths_env.display());

    let lib_dir = match find_lib_dir(&paths_env) {
        Ok(dir) => dir,
        Err(msg) => {
            eprintln!("error: gmsh-sys: {msg}");
            std::process::exit(1);
        }
    };

    println!("cargo:rustc-link-search=native={}", lib_dir.display());
    println!("cargo:rustc-link-lib=dylib=gmsh");
    println!("cargo:libdir={}", lib_dir.display());
    // rpath for this crate's own unit-test binary (link args do not propagate
    // to dependents; see the `gmsh` crate for theirs).
    println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib_dir.display());
}

fn find_lib_dir(paths_env: &Path) -> Result<PathBuf, String> {
    if let Some(dir) = env::var_os("GMSH_LIB_DIR").filter(|d| !d.is_empty()) {
        let dir = PathBuf::from(dir);
        if !dir.is_dir() {
            return Err(format!(
                "GMSH_LIB_DIR={} is not a directory; unset it and run `make setup` first",
                dir.display()
            ));
        }
        return Ok(dir);
    }
    let text = fs::read_to_string(paths_env).map_err(|e| {
        format!(
            "gmsh library not found: GMSH_LIB_DIR is not set and {} cannot be read ({e}); \
             run `make setup` first",
            paths_env.display()
        )
    })?;
    let dir = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("GMSH_LIB_DIR="))
        .map(|v| PathBuf::from(v.trim()))
        .ok_or_else(|| {
            format!(
                "{} has no GMSH_LIB_DIR= line; run `make setup` first",
                paths_env.display()
            )
        })?;
    if !dir.is_dir() {
        return Err(format!(
            "GMSH_LIB_DIR={} (from {}) is not a directory; run `make setup` first",
            dir.display(),
            paths_env.display()
        ));
    }
    Ok(dir)
}
