"""ParaView 5.11 with the ShadeLab plugin: every filter applied to the bunny as a ParaView user
applies it, its arrays against the command line's output bit for bit, a scene error's message
against the command line's, and a picture of the result drawn by ParaView.

    pvpython tests/paraview_plugin_check.py PLUGIN SHADELAB DATA WORK [PICTURE]

PLUGIN is ShadeLab.so, SHADELAB the command line, DATA the repository's data/, WORK a scratch
folder; PICTURE, if given, is where the picture goes (docs/paraview_total.png, in docs/guide/paraview.md).
Run by .ci/paraview under xvfb-run. Exits 1 unless every check passes.
"""
import os
import subprocess
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import (ColorBy, CreateView, Delete, LoadPlugin, OpenDataFile, PythonCalculator, Render,
                             SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

plugin, shadelab, data, work = sys.argv[1:5]
picture = sys.argv[5] if len(sys.argv) > 5 else None
bunny_file = os.path.join(data, "meshes", "bunny_zipper.ply")
studio = os.path.join(data, "scenes", "studio.json")
shadows = os.path.join(data, "scenes", "shadows_occlusion.json")
failures = []

LoadPlugin(plugin, remote=False, ns=globals())


def check(what, passed, detail=""):
    print(("passed: " if passed else "FAILED: ") + what + ("" if passed else " (" + detail + ")"))
    if not passed:
        failures.append(what)


def arrays_of(proxy):
    proxy.UpdatePipeline()
    point_data = servermanager.Fetch(proxy).GetPointData()
    return {point_data.GetArrayName(a): vtk_to_numpy(point_data.GetArray(a)).copy()
            for a in range(point_data.GetNumberOfArrays())}


def command_line(name, *arguments):
    """The point arrays that `shadelab shade` writes for the bunny, as ParaView reads them."""
    output = os.path.join(work, name + ".vtp")
    subprocess.run([shadelab, "shade", bunny_file, "-o", output, *arguments], check=True, capture_output=True)
    return arrays_of(OpenDataFile(output))


def same_arrays(what, expected, actual, names=None):
    names = sorted(expected) if names is None else names
    missing = [name for name in names if name not in actual]
    if missing or (names == sorted(expected) and sorted(actual) != names):
        check(what, False, f"arrays {sorted(actual)} against {names}")
        return
    different = [name for name in names if expected[name].dtype != actual[name].dtype
                 or not np.array_equal(expected[name], actual[name], equal_nan=True)]
    check(f"{what}: {len(names)} arrays bit for bit", not different, "different: " + ", ".join(different))


bunny = OpenDataFile(bunny_file)

as_it_comes = LocalReflectance(Input=bunny)  # every property as the panel first shows it
same_arrays("Local Reflectance as it comes: the default light kit and arrays", command_line("defaults"),
            arrays_of(as_it_comes))

def tick_every_array(proxy):
    proxy.UpdatePipelineInformation()  # the list of the scene's arrays
    proxy.ArraySelection = proxy.ArraySelection.Available


shade = LocalReflectance(Input=bunny)
shade.SceneFileName = studio
tick_every_array(shade)
shade.OutputPrecision = "float64"
shade.NumberOfThreads = 1
same_arrays("Local Reflectance, studio.json, all arrays, float64, one thread",
            command_line("studio", "-s", studio, "-a", "all", "--precision", "float64"), arrays_of(shade))

shadowed = LocalReflectance(Input=bunny)
shadowed.SceneFileName = shadows
shadowed.UpdatePipelineInformation()
# What the filter ticks for this scene's list (name, status pairs), as the panel shows it: the
# default arrays.
listed = list(shadowed.GetProperty("ArraySelectionInfo"))
ticked = [listed[i] for i in range(0, len(listed), 2) if listed[i + 1] == "1"]
check("at first the default arrays are ticked",
      ticked == ["ambient", "diffuse", "specular", "total", "shading_flags", "ambient_occlusion",
                 "ambient_occlusion_std_error", "key_visibility"], f"ticked: {ticked}")
shadowed.ArraySelection = ticked + ["bent_normal", "sky_view_factor"]
shadowed.ArrayPrefix = "pv_"
same_arrays("Local Reflectance, shadows_occlusion.json, two more boxes ticked, with a prefix",
            command_line("shadows", "-s", shadows, "-a", "default,bent_normal,sky_view_factor",
                         "--prefix", "pv_"), arrays_of(shadowed))

kit = LocalReflectance(Input=bunny)
kit.UpdatePipelineInformation()
kit.ArraySelection = ["ambient", "diffuse", "specular", "total"] + [
    name for name in kit.ArraySelection.Available if name.endswith("_cos_incidence")]
kit.Tolerance = 1e-3
same_arrays("Local Reflectance, the default light kit under a tolerance",
            command_line("kit", "-a", "totals,*_cos_incidence", "--tolerance", "1e-3"), arrays_of(kit))

normals = ShadingNormals(Input=bunny)
seen = MeshVisibility(Input=normals)
with open(shadows) as scene:
    seen.SceneJson = scene.read()
shadow_arrays = command_line("shadows_all", "-s", shadows, "-a", "all")
same_arrays("Shading Normals", shadow_arrays, arrays_of(normals), ["Normals"])
same_arrays("Mesh Visibility from Scene JSON", shadow_arrays, arrays_of(seen),
            ["ambient_occlusion", "ambient_occlusion_std_error", "bent_normal", "sky_view_factor"]
            + sorted(name for name in shadow_arrays if name.endswith("_visibility")))

# Relighting from stored transfer vectors, as docs/guide/relighting.md's pvpython example does it.
transfer = os.path.join(work, "transfer.vtp")
sunset = os.path.join(data, "envmaps", "venice_sunset_1k.hdr")
subprocess.run([shadelab, "shade", bunny_file, "-o", transfer, "--envmap", os.path.join(data, "envmaps",
                "studio_small_03_1k.hdr"), "--envmap-estimator", "prt", "--envmap-order", "3", "--shadows",
                "--envmap-samples", "16", "-a", "envmap_sh_transfer"], check=True, capture_output=True)
relit_file = os.path.join(work, "relit.vtp")
subprocess.run([shadelab, "relight", transfer, "--envmap", sunset, "--rotation", "45", "--intensity", "0.5",
                "-o", relit_file], check=True, capture_output=True)
relit = TransferRelight(Input=OpenDataFile(transfer))
relit.EnvironmentMapFileName = sunset
relit.Rotation = 45
relit.Intensity = 0.5
same_arrays("Transfer Relight", arrays_of(OpenDataFile(relit_file)), arrays_of(relit), ["relit_irradiance"])

# Interreflection: the scene's through Local Reflectance, and the filter alone gathering from a
# shaded mesh's diffuse term (one bounce: the albedo does not enter it), as the command line does.
bounces_scene = os.path.join(data, "scenes", "interreflection.json")
bounced = LocalReflectance(Input=bunny)
bounced.SceneFileName = bounces_scene
same_arrays("Local Reflectance with interreflection", command_line("bounces", "-s", bounces_scene),
            arrays_of(bounced), ["indirect_irradiance", "indirect", "diffuse", "total"])
direct = LocalReflectance(Input=bunny)
direct.SceneFileName = studio
gathered = Interreflection(Input=direct)
same_arrays("Interreflection", command_line("one_bounce", "-s", studio, "--bounces", "1", "-a", "indirect_irradiance"),
            arrays_of(gathered), ["indirect_irradiance"])

# The head scan coloured by its own RGB array, chosen in the panel, as the command line shades
# it with a scene that names the array.
head_file = os.path.join(data, "meshes", "head_scan.ply")
scan_scene = os.path.join(data, "scenes", "scan_colors.json")
head_cli = os.path.join(work, "head.vtp")
subprocess.run([shadelab, "shade", head_file, "-s", scan_scene, "-o", head_cli], check=True, capture_output=True)
with open(scan_scene) as scene:
    uniform_scene = scene.read().replace('"kd": { "array": "RGB" }', '"kd": 0.5')
colored = LocalReflectance(Input=OpenDataFile(head_file))
colored.SceneJson = uniform_scene
colored.ColorByArray = 1
colored.MaterialColorArray = "RGB"
same_arrays("Local Reflectance coloured by the scan's RGB array", arrays_of(OpenDataFile(head_cli)),
            arrays_of(colored))

# A scene error reaches ParaView's output with the command line's message.
bad_scene = os.path.join(work, "negative_intensity.json")
with open(bad_scene, "w") as scene:
    scene.write('{"lights": [{"type": "point", "position": [0, 1, 0], "intensity": -2}]}')
run = subprocess.run([shadelab, "shade", bunny_file, "-s", bad_scene, "-o", os.path.join(work, "unwritten.vtp")],
                     capture_output=True, text=True)
message = run.stderr.strip()[len("shadelab: "):]
broken = LocalReflectance(Input=bunny)
broken.SceneFileName = bad_scene
errors = []


@calldata_type(VTK_STRING)
def on_error(caller, event, text):
    errors.append(text)


broken.GetClientSideObject().AddObserver("ErrorEvent", on_error)
broken.UpdatePipeline()
check("a scene error gives the command line's message",
      run.returncode == 1 and message and len(errors) == 1 and message in errors[0],
      f"command line: {run.stderr!r}; ParaView: {errors!r}")

if picture:
    view = CreateView("RenderView")
    view.ViewSize = [900, 700]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0
    # The totals as colours, as `shadelab render` draws them: clamped to [0, 1] (an 8-bit colour
    # would wrap above 1), not mapped through a colour map, and not lit again by ParaView.
    clamped = PythonCalculator(Input=shade, Expression="numpy.clip(total, 0, 1)", ArrayName="total_clamped")
    display = Show(clamped, view)
    ColorBy(display, ("POINTS", "total_clamped"))
    display.MapScalars = 0
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0
    view.CameraPosition = [0.0, 0.12, 0.45]  # studio.json's viewer
    view.CameraFocalPoint = [-0.017, 0.11, 0.0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 30
    Render(view)
    SaveScreenshot(picture, view, ImageResolution=[900, 700])
    check("ParaView drew the result to " + picture, os.path.getsize(picture) > 10000, "the picture is nearly empty")
    Delete(view)  # while the X display is still there: at exit its OpenGL context would be gone

print(f"{'all checks passed' if not failures else str(len(failures)) + ' checks failed'}")
sys.exit(1 if failures else 0)
