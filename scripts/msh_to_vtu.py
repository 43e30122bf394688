"""Convert a gmsh .msh (4.1) into a .vtu for ParaView with meshio.

Usage: msh_to_vtu.py IN.msh OUT.vtu

The physical and geometrical entity numbers stay as cell data
(gmsh:physical, gmsh:geometrical). meshio's own cell_sets -> cell_data
conversion fails on gmsh files whose physical groups hold surfaces and
volumes (IndexError in cell_sets_to_data, meshio issue 1306), so the cell
sets are dropped before writing.
"""
import sys

import meshio

def main() -> int:
    src, dst = sys.argv[1], sys.argv[2]
    mesh = meshio.read(src)
    mesh.cell_sets = {}
    meshio.write(dst, mesh, file_format="vtu")
    return 0

if __name__ == "__main__":
    sys.exit(main())
