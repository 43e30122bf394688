#!/usr/bin/env bash
# Smoke test of the tools installed by scripts/setup.sh (run by `make test`).
#   gmsh    - import, OCC box, 3D second-order mesh, version 4.15.2, write .msh 4.1
#   meshio  - `meshio convert` of that .msh to a non-empty .vtu, read back
#   h5py    - write and read back a dataset with an attribute
#   hdf5-c  - HDF5 C library + headers for the Rust hdf5-metno crate
#             (dpkg, pkg-config, h5cc, and a tiny C program linked against it)
# Prints `check_env: <name> ok` per check and a closing `N passed, M failed`;
# exits non-zero naming every check that failed. CHECK_ENV_VERBOSE=1 also
# shows the details of the checks that passed.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
cd "$ROOT"

VENV="$ROOT/.venv"
PY="$VENV/bin/python"
EXPECTED_GMSH="4.15.2"

TMP="$(mktemp -d "${TMPDIR:-/tmp}/check_env.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT

passed=0
failed=0
failed_names=()

# run_check NAME FUNCTION: runs FUNCTION with its output in a log, shown on failure.
run_check() {
    local name="$1" fn="$2" log="$TMP/$1.log"
    local rc
    # not inside `if`: bash would ignore `set -e` in the subshell there
    set +e
    ( set -euo pipefail; "$fn" ) >"$log" 2>&1
    rc=$?
    set -e
    if ((rc == 0)); then
        echo "check_env: $name ok"
        if [[ "${CHECK_ENV_VERBOSE:-0}" == 1 ]]; then sed -e 's/^/    /' "$log"; fi
        passed=$((passed + 1))
    else
        echo "check_env: $name FAILED" >&2
        sed -e 's/^/    /' "$log" | tail -n 40 >&2
        failed=$((failed + 1))
        failed_names+=("$name")
    fi
}

need_venv() {
    if [[ ! -x "$PY" ]]; then
        echo "no Python venv at $VENV (run 'make setup' or 'bash scripts/setup.sh')"
        return 1
    fi
}

check_gmsh() {
    need_venv
    MSH="$TMP/box.msh" EXPECTED_GMSH="$EXPECTED_GMSH" "$PY" -c '
import os, sys
import gmsh

expected = os.environ["EXPECTED_GMSH"]
if gmsh.__version__ != expected:
    sys.exit(f"gmsh.__version__ is {gmsh.__version__!r}, expected {expected!r}")
gmsh.initialize(["check_env"], readConfigFiles=False)
try:
    gmsh.option.setNumber("General.Terminal", 1)
    gmsh.option.setNumber("General.Verbosity", 2)
    gmsh.model.add("box")
    box = gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    gmsh.model.occ.synchronize()
    # Physical groups, as real meshes have: without any, meshio 5.3.5 cannot
    # write the .msh 4.1 to .vtu (IndexError in cell_sets_to_data on the
    # "gmsh:bounding_entities" cell set, nschloe/meshio#1306).
    gmsh.model.addPhysicalGroup(3, [box], name="body")
    skin = [tag for _, tag in gmsh.model.getBoundary([(3, box)], oriented=False)]
    gmsh.model.addPhysicalGroup(2, skin, name="skin")
    gmsh.option.setNumber("Mesh.MeshSizeMax", 0.5)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    types, tags, _ = gmsh.model.mesh.getElements(dim=3)
    n = sum(len(t) for t in tags)
    if n <= 0:
        sys.exit("gmsh produced no 3D elements")
    names = [gmsh.model.mesh.getElementProperties(t)[0] for t in types]
    orders = {gmsh.model.mesh.getElementProperties(t)[2] for t in types}
    if orders != {2}:
        sys.exit(f"expected second-order 3D elements, got {names}")
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.write(os.environ["MSH"])
    print(f"gmsh {gmsh.__version__}: {n} 3D elements of type {names}")
finally:
    gmsh.finalize()
'
    [[ -s "$TMP/box.msh" ]] || { echo "gmsh did not write $TMP/box.msh"; return 1; }
    [[ "$(sed -n 2p "$TMP/box.msh")" == "4.1 0 8" ]] || { echo "box.msh is not an ASCII .msh 4.1 file"; return 1; }
}

check_meshio() {
    need_venv
    [[ -s "$TMP/box.msh" ]] || { echo "no box.msh to convert (the gmsh check failed)"; return 1; }
    [[ -x "$VENV/bin/meshio" ]] || { echo "no meshio command in $VENV/bin"; return 1; }
    "$VENV/bin/meshio" convert "$TMP/box.msh" "$TMP/box.vtu"
    [[ -s "$TMP/box.vtu" ]] || { echo "meshio convert did not write a non-empty $TMP/box.vtu"; return 1; }
    VTU="$TMP/box.vtu" "$PY" -c '
import os, sys
import meshio
m = meshio.read(os.environ["VTU"])
n = sum(len(c.data) for c in m.cells if c.type == "tetra10")
if n <= 0:
    sys.exit(f"no tetra10 cells in the .vtu: {[c.type for c in m.cells]}")
print(f"meshio {meshio.__version__}: {len(m.points)} points, {n} tetra10 cells")
'
}

check_h5py() {
    need_venv
    H5="$TMP/check.h5" "$PY" -c '
import os, sys
import numpy as np
import h5py
path = os.environ["H5"]
data = np.arange(12, dtype=np.float64).reshape(3, 4) * 0.5
with h5py.File(path, "w") as f:
    d = f.create_dataset("flank/points", data=data, compression="gzip")
    d.attrs["units"] = "mm"
    d.attrs["module"] = 3.25
with h5py.File(path, "r") as f:
    d = f["flank/points"]
    if not np.array_equal(d[...], data):
        sys.exit("dataset read back differs")
    if d.attrs["units"] != "mm" or d.attrs["module"] != 3.25:
        sys.exit(f"attributes read back differ: {dict(d.attrs)}")
print(f"h5py {h5py.__version__} (HDF5 {h5py.version.hdf5_version}) round trip ok")
'
}

check_hdf5_c() {
    local st
    st="$(dpkg -s libhdf5-dev 2>/dev/null | sed -n 's/^Status: //p')" || true
    [[ "$st" == *" ok installed" ]] || { echo "Debian package libhdf5-dev is not installed"; return 1; }
    command -v pkg-config >/dev/null || { echo "pkg-config is not installed"; return 1; }
    pkg-config --exists hdf5 || { echo "pkg-config does not know hdf5"; return 1; }
    echo "pkg-config hdf5 $(pkg-config --modversion hdf5): $(pkg-config --cflags --libs hdf5)"
    local inc found=""
    for inc in $(pkg-config --cflags-only-I hdf5 | sed 's/-I//g') /usr/include; do
        [[ -f "$inc/hdf5.h" ]] && { found="$inc/hdf5.h"; break; }
    done
    [[ -n "$found" ]] || { echo "hdf5.h not found"; return 1; }
    echo "header: $found"
    command -v h5cc >/dev/null || { echo "h5cc not found"; return 1; }
    h5cc -showconfig | grep -E 'HDF5 Version|Installation point' || { echo "h5cc -showconfig failed"; return 1; }
    local cc
    cc="$(command -v cc || command -v gcc || true)"
    if [[ -z "$cc" ]]; then
        echo "no C compiler: skipping the link test"
        return 0
    fi
    cat >"$TMP/h5ver.c" <<'EOF'
#include <stdio.h>
#include <hdf5.h>
int main(void) {
    unsigned maj, min, rel;
    if (H5get_libversion(&maj, &min, &rel) < 0) return 1;
    printf("linked HDF5 %u.%u.%u\n", maj, min, rel);
    return 0;
}
EOF
    # shellcheck disable=SC2046
    "$cc" -o "$TMP/h5ver" "$TMP/h5ver.c" $(pkg-config --cflags --libs hdf5)
    "$TMP/h5ver"
}

run_check gmsh check_gmsh
run_check meshio check_meshio
run_check h5py check_h5py
run_check hdf5-c check_hdf5_c

echo "$passed passed, $failed failed"
if ((failed)); then
    echo "check_env: FAILED: ${failed_names[*]}" >&2
    exit 1
fi
