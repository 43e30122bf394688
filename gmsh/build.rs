//! Embeds the gmsh library directory as an rpath in this crate's own tests,
//! examples and binaries (so they run without LD_LIBRARY_PATH), and re-exports
//! it to direct dependents as `DEP_GMSH_SAFE_LIBDIR` (`links = "gmsh-safe"`).

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=DEP_GMSH_LIBDIR");
    let dir = std::env::var("DEP_GMSH_LIBDIR")
        .expect("DEP_GMSH_LIBDIR not set by gmsh-sys (its build script prints cargo:libdir)");
    println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    println!("cargo:libdir={dir}");
}
