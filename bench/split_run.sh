#!/usr/bin/env bash
# Time and peak memory per MPI rank of Local Reflectance under pvbatch, on 1, 2 and 4 ranks
# (README, "A mesh split over MPI processes"): studio.json's default arrays, in float32, read
# from the pieces and written as a .pvtp. The mesh: the bunny and the dragon, each
# Loop-subdivided LEVELS times (default 4: 22M vertices), side by side in one mesh, cut into 4
# pieces with global ids. Needs .ci/paraview to have run (ParaView unpacked, the plugin built).
#   bash bench/split_run.sh [LEVELS] [WORK]
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-4}
work=${2:-/tmp/shadelab-split-run}
paraview=$PWD/build/paraview-5.11
plugin=build/paraview-plugin/lib/paraview-5.11/plugins/ShadeLab/ShadeLab.so
[ -x "$paraview/usr/bin/pvbatch" ] && [ -f "$plugin" ] || { echo "split_run: run bash .ci/paraview first"; exit 1; }
mkdir -p "$work"
mesh="$work/bunny_dragon_loop$levels.ply"
if [ ! -f "$mesh" ]; then
  /usr/bin/python3 - "$levels" "$mesh" <<'PYTHON'
import sys
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkCleanPolyData
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersModeling import vtkLoopSubdivisionFilter
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkIOPLY import vtkPLYReader, vtkPLYWriter
levels, output = int(sys.argv[1]), sys.argv[2]
append = vtkAppendPolyData()
for name, shift in (("bunny_zipper.ply", 0.0), ("xyzrgb_dragon_50k.ply", 0.25)):
    reader = vtkPLYReader()
    reader.SetFileName("data/meshes/" + name)
    clean = vtkCleanPolyData()  # Loop subdivision needs shared points
    clean.SetInputConnection(reader.GetOutputPort())
    loop = vtkLoopSubdivisionFilter()
    loop.SetNumberOfSubdivisions(levels)
    loop.SetInputConnection(clean.GetOutputPort())
    loop.Update()
    bounds = loop.GetOutput().GetBounds()
    place = vtkTransform()  # side by side, each scaled to the bunny's height
    scale = 0.15 / (bounds[3] - bounds[2])
    place.Translate(shift, 0, 0)
    place.Scale(scale, scale, scale)
    place.Translate(-0.5 * (bounds[0] + bounds[1]), -bounds[2], -0.5 * (bounds[4] + bounds[5]))
    moved = vtkTransformPolyDataFilter()
    moved.SetTransform(place)
    moved.SetInputConnection(loop.GetOutputPort())
    moved.Update()
    append.AddInputData(moved.GetOutput())
append.Update()
writer = vtkPLYWriter()
writer.SetFileName(output)
writer.SetFileTypeToBinary()
writer.SetInputConnection(append.GetOutputPort())
writer.Write()
print(f"{output}: {append.GetOutput().GetNumberOfPoints()} points, {append.GetOutput().GetNumberOfPolys()} triangles")
PYTHON
fi
export LD_LIBRARY_PATH="$paraview/usr/lib/x86_64-linux-gnu"
[ -f "$work/pieces.pvtp" ] || "$paraview/usr/bin/pvpython" tests/paraview_split_check.py pieces "$mesh" "$work/pieces.pvtp" 4
echo "| processes | wall time per rank | peak memory per rank |"
echo "|---|---|---|"
for processes in 1 2 4; do
  # Each rank timed by its own /usr/bin/time, into a file named after its rank.
  mpiexec --allow-run-as-root --oversubscribe -np "$processes" -x LD_LIBRARY_PATH \
    sh -c 'exec /usr/bin/time -o "$0/rank_$OMPI_COMM_WORLD_RANK.time" -f "%e %M" "$@"' "$work" \
    "$paraview/usr/bin/pvbatch" tests/paraview_split_check.py shade "$plugin" "$work/pieces.pvtp" \
    data/scenes/studio.json "$work/shaded.pvtp" default > "$work/np$processes.log" 2>&1 ||
    { echo "split_run: $processes ranks failed:"; tail -20 "$work/np$processes.log"; exit 1; }
  rm -rf "$work"/shaded*
  echo "| $processes | $(cat "$work"/rank_*.time | awk '{printf "%s%.1f s", (NR > 1 ? ", " : ""), $1}') | $(cat "$work"/rank_*.time | awk '{printf "%s%.2f GB", (NR > 1 ? ", " : ""), $2 / 1048576}') |"
  rm -f "$work"/rank_*.time
done
