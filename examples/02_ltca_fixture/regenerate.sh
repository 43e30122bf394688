#!/usr/bin/env bash
# Remakes the stiffness fixture of example 02 with the project's own stages:
# reduced-level gmsh meshes of the scene in a temporary folder, the FE
# stiffness files on them, then only manifest.json and the *.stiffness.h5
# files copied into meshes/ltca_fixture/ (the .msh/.vtu stay out: the solver
# never reads them). Needs `make setup` (gmsh, HDF5); about 2 minutes.
# Afterwards run the example's test with BLESS=1 if the numbers moved.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
cd "$root"
target="${CARGO_TARGET_DIR:-$root/target}"
cargo build --release -p preprocess --bin preprocess
scene="$here/scene.toml"
name=ltca_fixture
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$target/release/preprocess" mesh "$scene" --level reduced --out "$tmp"
"$target/release/preprocess" stiffness "$scene" --meshes "$tmp"
dest="$here/meshes/$name"
rm -rf "$dest"
mkdir -p "$dest"
cp "$tmp/$name/manifest.json" "$dest/"
cp "$tmp/$name"/*.stiffness.h5 "$dest/"
ls -l "$dest"
du -sh "$dest"
