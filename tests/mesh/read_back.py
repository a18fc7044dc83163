#!/usr/bin/python3
"""Reads a mesh file with meshio (a reader this project did not write) and prints what it found as JSON:
points, cells by type, and for Gmsh files the number of cells in each named physical group.

usage: read_back.py FILE [MESHIO_FORMAT]
"""
import json
import sys

import meshio


def main():
    path = sys.argv[1]
    file_format = sys.argv[2] if len(sys.argv) > 2 else None
    mesh = meshio.read(path, file_format=file_format)
    cells = {}
    for block in mesh.cells:
        cells.setdefault(block.type, []).extend(block.data.tolist())
    groups = {}
    for name, per_block in mesh.cell_sets.items():
        if name.startswith("gmsh:"):
            continue
        groups[name] = int(sum(len(ids) for ids in per_block if ids is not None))
    # MSH 2.2 files: meshio keeps the names in field_data ({name: [tag, dim]}) and tags per cell.
    if not groups and "gmsh:physical" in mesh.cell_data:
        for name, (tag, dim) in mesh.field_data.items():
            count = 0
            for block, tags in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
                if block.dim == dim:
                    count += int((tags == tag).sum())
            groups[name] = count
    print(json.dumps({
        "points": mesh.points.tolist(),
        "cells": cells,
        "groups": groups,
        "point_data": sorted(mesh.point_data.keys()),
        "cell_data": sorted(mesh.cell_data.keys()),
    }))


if __name__ == "__main__":
    main()
