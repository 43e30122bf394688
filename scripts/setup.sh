#!/usr/bin/env bash
# One-command, idempotent set-up of everything the project needs on a fresh
# Debian 12 (x86_64) machine:
#   - Debian packages: the HDF5 C library + headers for the Rust `hdf5-metno`
#     crate, pkg-config, python3-venv, CalculiX (`ccx`), Slurm and munge (the
#     study tests' one-node cluster), and the shared libraries that the
#     official gmsh wheel's libgmsh.so links against;
#   - .venv at the repo root with python/requirements.txt (hash-pinned);
#   - .venv/gmsh-paths.env with GMSH_LIB_DIR / GMSH_INCLUDE_DIR for build scripts.
# Second run with nothing missing does no network access and takes well under 2 s.
# Usage: bash scripts/setup.sh   (or `make setup`). Works with CI=true and no stdin.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
cd "$ROOT"

VENV="$ROOT/.venv"
REQ="python/requirements.txt"
STAMP="$VENV/.requirements.sha256"
PATHS_ENV="$VENV/gmsh-paths.env"
PY_SERIES="3.11"   # the wheels in $REQ (numpy, h5py) are cp311

log() { printf 'setup: %s\n' "$*" >&2; }
die() { printf 'setup: ERROR: %s\n' "$*" >&2; exit 1; }

# Serialise concurrent runs (e.g. two make targets started together).
if command -v flock >/dev/null 2>&1; then
    LOCK="${TMPDIR:-/tmp}/setup-$(printf '%s' "$ROOT" | sha256sum | cut -c1-16).lock"
    exec 9>"$LOCK"
    flock 9
fi

# ---------------------------------------------------------------------------
# 1. Debian packages
# ---------------------------------------------------------------------------
# Found with `readelf -d`/`ldd` on the gmsh 4.15.2 wheel's libgmsh.so.4.15 and
# `dpkg -S` on each NEEDED library (libc6's libm/libdl/libpthread/librt are
# always there and not listed).
APT_PACKAGES=(
    libhdf5-dev     # HDF5 C library, headers, hdf5.pc, h5cc (Rust hdf5-metno crate)
    pkg-config      # lets hdf5-metno-sys find HDF5
    python3-venv    # venv/ensurepip for Debian's python3 (fallback interpreter)
    calculix-ccx    # CalculiX (ccx): the independent FE code that checks the reference
    slurmctld       # Slurm: the one-node cluster of the study tests (scripts/slurm_cluster.sh)
    slurmd
    slurm-client    # sbatch, squeue, scontrol, scancel
    munge           # Slurm's authentication
    # shared libraries needed by libgmsh.so.4.15 (NEEDED entry -> package)
    libglu1-mesa    # libGLU.so.1
    libgl1          # libGL.so.1
    libxrender1     # libXrender.so.1
    libxcursor1     # libXcursor.so.1
    libxfixes3      # libXfixes.so.3
    libxext6        # libXext.so.6
    libxft2         # libXft.so.2
    libfontconfig1  # libfontconfig.so.1
    libxinerama1    # libXinerama.so.1
    libx11-6        # libX11.so.6
    libgomp1        # libgomp.so.1
    libstdc++6      # libstdc++.so.6
    libgcc-s1       # libgcc_s.so.1
    zlib1g          # libz.so.1
)

missing=()
for p in "${APT_PACKAGES[@]}"; do
    status="$(dpkg -s "$p" 2>/dev/null | sed -n 's/^Status: //p')" || true
    [[ "$status" == *" ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]})); then
    log "installing Debian packages: ${missing[*]}"
    SUDO=()
    if [[ $(id -u) -ne 0 ]]; then
        command -v sudo >/dev/null 2>&1 \
            || die "not root and no sudo: install these Debian packages by hand: ${missing[*]}"
        if [[ -t 0 ]]; then SUDO=(sudo); else SUDO=(sudo -n); fi
    fi
    export DEBIAN_FRONTEND=noninteractive
    # (`env` re-sets it because sudo drops the caller's environment)
    APT_OPTS=(-o DPkg::Lock::Timeout=300 -o Dpkg::Use-Pty=0 -q)
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "${APT_OPTS[@]}" update </dev/null >&2 \
        || die "apt-get update failed"
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "${APT_OPTS[@]}" install -y \
        --no-install-recommends "${missing[@]}" </dev/null >&2 \
        || die "apt-get install failed for: ${missing[*]}"
fi

# ---------------------------------------------------------------------------
# 2. Python virtual environment
# ---------------------------------------------------------------------------
venv_ok() {
    # usable interpreter of the right series, and not copied from another path
    # (pip/meshio scripts carry the absolute path of the venv in their shebang)
    [[ -x "$VENV/bin/python" && -f "$VENV/pyvenv.cfg" ]] || return 1
    grep -Eq "^version(_info)? = ${PY_SERIES//./\\.}\." "$VENV/pyvenv.cfg" || return 1
    [[ -f "$VENV/bin/pip" ]] || return 1
    local shebang
    IFS= read -r shebang <"$VENV/bin/pip" || return 1
    [[ "$shebang" == "#!$VENV/bin/python"* ]] || return 1
}

pick_python() {
    local c
    for c in ${PYTHON:+"$PYTHON"} python3 "python$PY_SERIES" /usr/bin/python3; do
        command -v "$c" >/dev/null 2>&1 || continue
        if "$c" -c "import sys, venv, ensurepip; sys.exit(0 if '%d.%d' % sys.version_info[:2] == '$PY_SERIES' else 1)" \
            >/dev/null 2>&1; then
            printf '%s\n' "$c"
            return 0
        fi
    done
    return 1
}

if ! venv_ok; then
    if [[ -e "$VENV" ]]; then
        log "existing .venv is unusable (missing interpreter, wrong Python or moved); recreating"
        rm -rf "$VENV"
    fi
    PY="$(pick_python)" || die "no Python $PY_SERIES interpreter able to create a venv (tried \$PYTHON, python3, python$PY_SERIES, /usr/bin/python3)"
    log "creating .venv with $(command -v "$PY") ($("$PY" -c 'import platform; print(platform.python_version())'))"
    if ! "$PY" -m venv "$VENV" >&2; then
        rm -rf "$VENV"
        die "'$PY -m venv .venv' failed"
    fi
fi

req_sum="$(sha256sum "$REQ" | cut -d' ' -f1)"
installed_sum=""
[[ -f "$STAMP" ]] && installed_sum="$(<"$STAMP")"

gmsh_lib_present() {
    compgen -G "$VENV/lib/libgmsh.so.*" >/dev/null || compgen -G "$VENV/lib/python*/site-packages/gmsh*/lib/libgmsh.so*" >/dev/null
}

if [[ "$installed_sum" != "$req_sum" ]] || ! gmsh_lib_present; then
    log "installing $REQ into .venv"
    rm -f "$STAMP" "$PATHS_ENV"
    PIP_NO_INPUT=1 "$VENV/bin/python" -m pip install --disable-pip-version-check --no-input \
        --require-hashes -r "$REQ" >&2 \
        || die "pip install --require-hashes -r $REQ failed"
    printf '%s\n' "$req_sum" >"$STAMP"
fi

# ---------------------------------------------------------------------------
# 3. Where the gmsh wheel put its C library and headers
# ---------------------------------------------------------------------------
paths_ok() {
    [[ -f "$PATHS_ENV" ]] || return 1
    local lib_dir="" inc_dir="" lib_file="" k v
    while IFS='=' read -r k v; do
        case "$k" in
            GMSH_LIB_DIR) lib_dir="$v" ;;
            GMSH_INCLUDE_DIR) inc_dir="$v" ;;
            GMSH_LIBRARY) lib_file="$v" ;;
        esac
    done <"$PATHS_ENV"
    [[ "$lib_dir" == "$VENV"/* && -f "$lib_file" && -f "$inc_dir/gmshc.h" && -e "$lib_dir/libgmsh.so" ]]
}

if ! paths_ok; then
    # The 4.15.x wheel installs its data files under the venv prefix
    # (lib/libgmsh.so.4.15, include/gmshc.h); older wheels used a
    # site-packages/gmsh-X.Y.Z-Linux64-sdk/ directory. Search both.
    lib_file="$(find "$VENV/lib" -maxdepth 4 -name 'libgmsh.so*' \( -type f -o -type l \) \
        ! -name 'libgmsh.so' -print 2>/dev/null | sort | head -n1)"
    [[ -n "$lib_file" ]] || lib_file="$(find "$VENV/lib" -maxdepth 4 -name 'libgmsh.so' -type f -print 2>/dev/null | head -n1)"
    [[ -n "$lib_file" ]] || die "gmsh is installed but no libgmsh.so* was found under .venv/lib"
    inc_file="$(find "$VENV/include" "$VENV/lib" -maxdepth 4 -name 'gmshc.h' -type f -print 2>/dev/null | head -n1)"
    [[ -n "$inc_file" ]] || die "gmsh is installed but no gmshc.h was found under .venv"
    lib_dir="$(dirname "$lib_file")"
    # The wheel ships only the versioned file; add the unversioned link so
    # that build scripts can link with `-L$GMSH_LIB_DIR -lgmsh`.
    [[ -e "$lib_dir/libgmsh.so" ]] || ln -s "$(basename "$lib_file")" "$lib_dir/libgmsh.so"
    {
        printf 'GMSH_LIB_DIR=%s\n' "$lib_dir"
        printf 'GMSH_INCLUDE_DIR=%s\n' "$(dirname "$inc_file")"
        printf 'GMSH_LIBRARY=%s\n' "$lib_file"
    } >"$PATHS_ENV"
fi

lib_file="$(sed -n 's/^GMSH_LIBRARY=//p' "$PATHS_ENV")"
gmsh_version="unknown"
for d in "$VENV"/lib/python*/site-packages/gmsh-*.dist-info; do
    [[ -d "$d" ]] || continue
    gmsh_version="${d##*/gmsh-}"
    gmsh_version="${gmsh_version%.dist-info}"
done

echo "setup: ok (gmsh $gmsh_version at ${lib_file#"$ROOT"/})"
