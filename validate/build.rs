//! Binaries and tests of this crate load libgmsh from the project's .venv: rpath.
fn main() {
    let dir =
        std::env::var("DEP_GMSH_SAFE_LIBDIR").expect("the gmsh crate exports its library dir");
    println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
    println!("cargo:rerun-if-changed=build.rs");
}
