#!/usr/bin/env bash
# Time and peak memory per MPI rank of shading a mesh split over 1, 2 and 4 ranks
# (docs/guide/mpi.md; the figures in docs/dev/benchmarks.md): studio.json's default arrays in
# float32 (or, with ARRAYS "all", every array in float64). The mesh: COPIES bunnies side by
# side, each Loop-subdivided LEVELS times (defaults 4 and 1: 8.9M vertices; 3 copies: 26.7M).
# RUNNER pvbatch (the default): Local Reflectance under pvbatch, read from the mesh cut into 4
# pieces with global ids and written as a .pvtp (needs .ci/paraview to have run: ParaView
# unpacked, the plugin built). RUNNER shadelab: `mpiexec shadelab shade` on the mesh's .ply,
# split on read, written as a .pvtp. RUNNER shadelab-pieces: `mpiexec shadelab shade` on the
# same 4 pieces as pvbatch's (cut by VTK's own Python, no ParaView needed), each rank reading
# only its own; then the first piece shaded alone, a rank's share to compare with.
# With a shadelab runner, any further arguments go to `shadelab shade` (--shadows, say).
#   bash bench/split_run.sh [LEVELS] [COPIES] [WORK] [ARRAYS] [RUNNER] [SHADE OPTIONS...]
set -euo pipefail
cd "$(dirname "$0")/.."
levels=${1:-4}
copies=${2:-1}
work=${3:-/tmp/shadelab-split-run}
arrays=$([ "${4:-default}" = all ] || echo default) # the check script's "default", or nothing for all
runner=${5:-pvbatch}
case "$runner" in
  pvbatch | shadelab | shadelab-pieces) ;;
  *) echo "split_run: RUNNER is pvbatch, shadelab or shadelab-pieces, not '$runner'"; exit 1 ;;
esac
paraview=$PWD/build/paraview-5.11
plugin=build/paraview-plugin/lib/paraview-5.11/plugins/ShadeLab/ShadeLab.so
if [ "$runner" = pvbatch ] && ! { [ -x "$paraview/usr/bin/pvbatch" ] && [ -f "$plugin" ]; }; then
  echo "split_run: run bash .ci/paraview first"
  exit 1
fi
mkdir -p "$work"
mesh="$work/bunnies_${copies}_loop$levels.ply"
if [ ! -f "$mesh" ]; then
  /usr/bin/python3 - "$levels" "$copies" "$mesh" <<'PYTHON'
import sys
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkCleanPolyData
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkFiltersModeling import vtkLoopSubdivisionFilter
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkIOPLY import vtkPLYReader, vtkPLYWriter
levels, copies, output = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
reader = vtkPLYReader()
reader.SetFileName("data/meshes/bunny_zipper.ply")
clean = vtkCleanPolyData()  # the file's unused points stop Loop subdivision
clean.SetInputConnection(reader.GetOutputPort())
loop = vtkLoopSubdivisionFilter()
loop.SetNumberOfSubdivisions(levels)
loop.SetInputConnection(clean.GetOutputPort())
loop.Update()
if loop.GetOutput().GetNumberOfPoints() == 0:
    sys.exit("split_run: the subdivision failed")
append = vtkAppendPolyData()
for copy in range(copies):
    shift = vtkTransform()
    shift.Translate(0.2 * copy, 0, 0)  # side by side: the bunny is 0.16 wide
    moved = vtkTransformPolyDataFilter()
    moved.SetTransform(shift)
    moved.SetInputConnection(loop.GetOutputPort())
    append.AddInputConnection(moved.GetOutputPort())
append.Update()
writer = vtkPLYWriter()
writer.SetFileName(output)
writer.SetFileTypeToBinary()
writer.SetInputConnection(append.GetOutputPort())
if writer.Write() != 1:
    sys.exit("split_run: could not write " + output)
print(f"{output}: {append.GetOutput().GetNumberOfPoints()} points, {append.GetOutput().GetNumberOfPolys()} triangles")
PYTHON
fi
environment=() # what mpiexec passes on to the ranks
# The 4 pieces with global ids, for every runner but shadelab's split on read.
pieces="$work/pieces_${copies}_loop$levels.pvtp" # named after the mesh: a folder may hold several
[ "$runner" = shadelab ] || [ -f "$pieces" ] ||
  /usr/bin/python3 tests/paraview_split_check.py pieces "$mesh" "$pieces" 4
if [ "$runner" != pvbatch ]; then
  input=$([ "$runner" = shadelab ] && echo "$mesh" || echo "$pieces")
  shade=(build/bin/shadelab shade "$input" --scene data/scenes/studio.json -o "$work/shaded.pvtp" "${@:6}")
  [ "${4:-default}" = all ] && shade+=(--arrays all --precision float64)
else
  export LD_LIBRARY_PATH="$paraview/usr/lib/x86_64-linux-gnu"
  environment=(-x LD_LIBRARY_PATH)
  (($# <= 5)) || { echo "split_run: shade options are for the shadelab runners"; exit 1; }
  shade=("$paraview/usr/bin/pvbatch" tests/paraview_split_check.py shade "$plugin" "$pieces"
    data/scenes/studio.json "$work/shaded.pvtp" $arrays)
fi
echo "| processes | wall time per rank | peak memory per rank |"
echo "|---|---|---|"
for processes in 1 2 4; do
  rm -f "$work"/rank_*.time # an earlier failed run's
  # Each rank timed by its own /usr/bin/time, into a file named after its rank.
  # (Its peak is that of the rank's process or of a child it waited for, as its reader.)
  mpiexec --allow-run-as-root --oversubscribe -np "$processes" "${environment[@]}" \
    sh -c 'exec /usr/bin/time -o "$0/rank_$OMPI_COMM_WORLD_RANK.time" -f "%e %M" "$@"' "$work" \
    "${shade[@]}" > "$work/np$processes.log" 2>&1 ||
    { echo "split_run: $processes ranks failed:"; tail -20 "$work/np$processes.log"; exit 1; }
  rm -rf "$work"/shaded*
  echo "| $processes | $(cat "$work"/rank_*.time | awk '{printf "%s%.1f s", (NR > 1 ? ", " : ""), $1}') | $(cat "$work"/rank_*.time | awk '{printf "%s%.2f GB", (NR > 1 ? ", " : ""), $2 / 1048576}') |"
  rm -f "$work"/rank_*.time
done
if [ "$runner" = shadelab-pieces ]; then
  alone=("${shade[@]}")
  alone[2]="${pieces%.pvtp}_0.vtp"
  alone[6]="$work/alone.vtp"
  /usr/bin/time -o "$work/alone.time" -f "%e %M" "${alone[@]}" > "$work/alone.log" 2>&1 ||
    { echo "split_run: the first piece alone failed:"; tail -20 "$work/alone.log"; exit 1; }
  echo
  echo "The first piece shaded alone in one process: $(awk '{printf "%.1f s, %.2f GB", $1, $2 / 1048576}' "$work/alone.time")"
  rm -f "$work/alone.vtp" "$work/alone.time"
fi
