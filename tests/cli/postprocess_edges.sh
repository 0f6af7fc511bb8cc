# The straight-edge counter of scripts/postprocess/edges.py on known polygons,
# and the whole VTK path of particle_table.py (merge the per-cell points,
# warp by the displacement, cut each particle at mid-height, count) on a
# synthetic output directory holding a tetrahedral cube and hexagonal prism.
# Needs Debian's python3-numpy and python3-vtk9 (scripts/setup.sh installs them).
set -eu
python=${PYTHON:-/usr/bin/python3}
scripts="$SOURCE_DIR/scripts/postprocess"
cd "$WORK_DIR"
for module in numpy vtk; do
  if ! "$python" -c "import $module" 2>/dev/null; then
    echo "FAIL: $python cannot import $module: install python3-numpy and python3-vtk9 (bash scripts/setup.sh)" >&2
    exit 1
  fi
done

echo "== polygons"
"$python" - "$scripts" <<'EOF'
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
from edges import count_straight_edges

def polygon(corners, per_side=1, noise=0.0, seed=0):
    """Points along the sides of a closed polygon, optionally with Gaussian noise."""
    corners = np.asarray(corners, dtype=float)
    t = np.arange(per_side)[:, None] / per_side
    sides = [a + (b - a) * t for a, b in zip(corners, np.roll(corners, -1, axis=0))]
    points = np.vstack(sides)
    return points + noise * np.random.default_rng(seed).standard_normal(points.shape)

def regular(n, radius=1.0, phase=0.3):
    a = phase + 2 * np.pi * np.arange(n) / n
    return np.column_stack([radius * np.cos(a), radius * np.sin(a)])

def rounded_square(side=1.0, radius=0.15, per_corner=30):
    c = side / 2 - radius
    points = []
    for k, (cx, cy) in enumerate([(c, c), (-c, c), (-c, -c), (c, -c)]):
        for a in np.linspace(0, np.pi / 2, per_corner) + k * np.pi / 2:
            points.append((cx + radius * np.cos(a), cy + radius * np.sin(a)))
    return np.array(points)

cases = [
    ("square (cut of a cube)", [(0, 0), (1, 0), (1, 1), (0, 1)], 4),
    ("square, clockwise, closing point repeated", [(0, 0), (0, 1), (1, 1), (1, 0), (0, 0)], 4),
    ("regular hexagon", regular(6), 6),
    ("regular octagon", regular(8), 8),
    ("circle, 720 points", regular(720), 0),
    ("circle, 26 points (a P1 sphere section)", regular(26), 0),
    ("square with rounded corners (r = 0.15 a)", rounded_square(), 4),
    ("square with rounded corners (r = 0.3 a)", rounded_square(radius=0.3), 4),
    ("hexagon, 8 points per side", polygon(regular(6), 8), 6),
]
for seed in range(5):
    cases.append((f"hexagon, 100 points per side, noise 0.002 R, seed {seed}",
                  polygon(regular(6), 100, 0.002, seed), 6))
    cases.append((f"circle, 1000 points, noise 0.002 R, seed {seed}",
                  regular(1000) * (1 + 0.002 * np.random.default_rng(seed).standard_normal((1000, 1))), 0))
failed = 0
for name, points, expected in cases:
    got = count_straight_edges(points)
    status = "ok" if got == expected else "WRONG"
    failed += got != expected
    print(f"{status:5s} {name}: {got} edges (expected {expected})")
scaled = count_straight_edges(np.asarray(regular(6)) * 1e-3 + 5.0)
print(f"{'ok' if scaled == 6 else 'WRONG':5s} hexagon of radius 1e-3 far from the origin: {scaled}")
failed += scaled != 6
sys.exit(1 if failed else 0)
EOF

echo "== VTK path: tetrahedral cube and hexagonal prism, written like deal.II"
rm -rf synthetic && mkdir synthetic
"$python" - synthetic <<'EOF'
import math
import sys
import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy

def tetrahedralize(dataset):
    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(dataset)
    tets.TetrahedraOnlyOn()
    tets.Update()
    return tets.GetOutput()

def cube():
    """Unit cube, 4 x 4 x 4 hexahedra split into tetrahedra (the mid-plane runs through nodes)."""
    image = vtk.vtkImageData()
    image.SetDimensions(5, 5, 5)
    image.SetSpacing(0.25, 0.25, 0.25)
    return tetrahedralize(image)

def hexagonal_prism(centre=(3.0, 0.0), radius=1.0, height=1.0, layers=3):
    """Hexagonal prism: 6 triangles x 2 rings per layer as wedges, split into tetrahedra."""
    ring = [centre] + [(centre[0] + r * math.cos(k * math.pi / 3), centre[1] + r * math.sin(k * math.pi / 3))
                       for r in (radius / 2, radius) for k in range(6)]
    triangles = []
    for k in range(6):
        a, b = 1 + k, 1 + (k + 1) % 6
        triangles.append((0, a, b))
        triangles += [(a, 7 + k, 7 + (k + 1) % 6), (a, 7 + (k + 1) % 6, b)]
    points = vtk.vtkPoints()
    for layer in range(layers + 1):
        for x, y in ring:
            points.InsertNextPoint(x, y, height * layer / layers)
    grid = vtk.vtkUnstructuredGrid()
    grid.SetPoints(points)
    n = len(ring)
    for layer in range(layers):
        for t in triangles:
            ids = [layer * n + i for i in t] + [(layer + 1) * n + i for i in t]
            grid.InsertNextCell(vtk.VTK_WEDGE, 6, ids)
    return tetrahedralize(grid)

def explode(grid, particle):
    """Points (one copy per cell, as deal.II writes them), connectivity, particle ids."""
    pts = vtk_to_numpy(grid.GetPoints().GetData()).astype(np.float64)
    conn = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    return pts[conn.reshape(-1)], len(conn), np.full(conn.size, particle, dtype=np.float32)

blocks = [explode(cube(), 0), explode(hexagonal_prism(), 1)]
points = np.vstack([b[0] for b in blocks])
n_cells = sum(b[1] for b in blocks)
particle = np.concatenate([b[2] for b in blocks])
x, y, z = points.T
# affine deformation: stretch x by 10 %, shear x by z, squeeze z by 20 %,
# lift by 0.2: each section keeps its shape, the mid-plane moves from 0.5 to 0.6
displacement = np.column_stack([0.1 * x + 0.05 * z, 0.02 * y, -0.2 * z + 0.2])
plastic = np.where(particle == 0, z, 0.25)  # cube: z (mean 0.5, max 1); prism: 0.25

grid = vtk.vtkUnstructuredGrid()
vtk_points = vtk.vtkPoints()
vtk_points.SetData(numpy_to_vtk(points.astype(np.float32), deep=True))
grid.SetPoints(vtk_points)
for c in range(n_cells):
    grid.InsertNextCell(vtk.VTK_TETRA, 4, list(range(4 * c, 4 * c + 4)))
for name, values in [("displacement", displacement), ("von_mises", np.ones(len(points))),
                     ("plastic_strain", plastic), ("particle_id", particle)]:
    array = numpy_to_vtk(np.ascontiguousarray(values, dtype=np.float32), deep=True)
    array.SetName(name)
    grid.GetPointData().AddArray(array)
writer = vtk.vtkXMLPUnstructuredGridWriter()
writer.SetFileName(f"{sys.argv[1]}/solution_00003.pvtu")
writer.SetInputData(grid)
writer.SetNumberOfPieces(1)
writer.Write()
with open(f"{sys.argv[1]}/solution.pvd", "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
            '<DataSet timestep="0.6" group="" part="0" file="solution_00003.pvtu"/>\n'
            '</Collection>\n</VTKFile>\n')
hexagon_area = 1.5 * math.sqrt(3.0)
with open(f"{sys.argv[1]}/particles.csv", "w") as f:
    f.write("step,particle,material,volume,initial_volume,contact_partners,die_contact\n")
    f.write(f"3,0,Sn,{1.1 * 1.02 * 0.8:.6f},1,4,0\n")
    f.write(f"3,1,Sn,,{hexagon_area:.6f},6,1\n")  # no volume: the table measures the mesh
EOF
"$python" "$scripts/particle_table.py" synthetic
cat synthetic/particle_table_00003.csv
"$python" - synthetic/particle_table_00003.csv <<'EOF'
import csv
import math
import sys
rows = {int(r["particle"]): r for r in csv.DictReader(open(sys.argv[1]))}
hexagon_area = 1.5 * math.sqrt(3.0)
expected = {
    0: {"contact_partners": "4", "die_contact": "0", "cross_section_edges": 4, "section_z": 0.6,
        "volume": 0.8976, "mean_plastic_strain": 0.5, "max_plastic_strain": 1.0},
    1: {"contact_partners": "6", "die_contact": "1", "cross_section_edges": 6, "section_z": 0.6,
        "volume": 0.8976 * hexagon_area, "mean_plastic_strain": 0.25, "max_plastic_strain": 0.25},
}
failed = sorted(rows) != [0, 1]
for particle, want in expected.items():
    row = rows.get(particle, {})
    for key, value in want.items():
        got = row.get(key, "")
        if isinstance(value, str):
            good = got == value
        elif isinstance(value, int):
            good = got == str(value)
        else:
            good = got != "" and abs(float(got) - value) <= 1e-4 * max(1.0, abs(value))
        if not good:
            print(f"WRONG particle {particle} {key}: {got!r}, expected {value}")
            failed = True
print("table as expected" if not failed else "table differs")
sys.exit(1 if failed else 0)
EOF

echo "== errors"
if "$python" "$scripts/particle_table.py" does_not_exist 2> err.txt; then
  echo "FAIL: particle_table.py accepted a missing directory" >&2; exit 1
fi
cat err.txt
grep -q "does not exist" err.txt
echo "postprocess_edges: all checks passed"
