"""The Python package against the command line: the same arrays, bit for bit, and the same messages.

Run by CTest with /usr/bin/python3, PYTHONPATH on the package's folder, SHADELAB (the command
line's executable), SHADELAB_DATA (the repository's data/) and SHADELAB_WORK (a scratch folder).
"""
import os
import subprocess
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow, vtkSMPTools, vtkStringOutputWindow
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

import shadelab

SHADELAB = os.environ["SHADELAB"]
DATA = os.environ["SHADELAB_DATA"]
WORK = os.environ["SHADELAB_WORK"]
BUNNY = os.path.join(DATA, "meshes", "bunny_zipper.ply")
STUDIO = os.path.join(DATA, "scenes", "studio.json")
SHADOWS = os.path.join(DATA, "scenes", "shadows_occlusion.json")


def read_bunny():
    reader = vtkPLYReader()
    reader.SetFileName(BUNNY)
    reader.Update()
    return reader.GetOutput()


def command_line(name, *arguments):
    """The point arrays `shadelab shade` writes for the bunny with these arguments."""
    output = os.path.join(WORK, name + ".vtp")
    subprocess.run([SHADELAB, "shade", BUNNY, "-o", output, *arguments], check=True, capture_output=True)
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(output)
    reader.Update()
    return arrays_of(reader.GetOutput())


def arrays_of(mesh):
    point_data = mesh.GetPointData()
    return {point_data.GetArrayName(a): vtk_to_numpy(point_data.GetArray(a)).copy()
            for a in range(point_data.GetNumberOfArrays())}


def shaded(configure):
    """The point arrays of vtkLocalReflectanceFilter on the bunny, set up by configure(filter)."""
    shade = shadelab.vtkLocalReflectanceFilter()
    shade.SetInputData(read_bunny())
    configure(shade)
    shade.Update()
    return arrays_of(shade.GetOutput())


def select(shade, *entries):
    shade.ClearArraySelection()
    for entry in entries:
        shade.AddToArraySelection(entry)


class ErrorText:
    """What VTK reports while in a with block, instead of printing it."""

    def __enter__(self):
        self.window = vtkStringOutputWindow()
        self.previous = vtkOutputWindow.GetInstance()
        vtkOutputWindow.SetInstance(self.window)
        self.verbosity = vtkLogger.GetCurrentVerbosityCutoff()
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)  # VTK's logger would print it too
        return self

    def __exit__(self, *exception):
        vtkOutputWindow.SetInstance(self.previous)
        vtkLogger.SetStderrVerbosity(self.verbosity)

    def text(self):
        return self.window.GetOutput()


class SameAsTheCommandLine(unittest.TestCase):
    def assertSameArrays(self, expected, actual):
        self.assertEqual(sorted(expected), sorted(actual))
        for name in expected:
            self.assertEqual(expected[name].dtype, actual[name].dtype, name)
            self.assertTrue(np.array_equal(expected[name], actual[name], equal_nan=True), name)

    def test_a_scene_file_gives_every_array_bit_for_bit(self):
        expected = command_line("studio_all", "-s", STUDIO, "-a", "all", "--precision", "float64")
        def configure(shade):
            shade.SetSceneFileName(STUDIO)
            select(shade, "all")
            shade.SetOutputPrecision(vtkAlgorithm.DOUBLE_PRECISION)
        actual = shaded(configure)
        self.assertGreater(len(actual), 30)
        self.assertSameArrays(expected, actual)

    def test_json_text_gives_what_its_file_gives_and_wins_over_a_file_name(self):
        expected = command_line("studio_default", "-s", STUDIO)
        with open(STUDIO) as scene:
            text = scene.read()
        sun = os.path.join(DATA, "scenes", "sun.json")
        def configure(shade):
            shade.SetSceneFileName(sun)
            shade.SetSceneJson(text)
        with ErrorText() as warnings:
            actual = shaded(configure)
        self.assertSameArrays(expected, actual)
        self.assertIn("both SceneJson and SceneFileName are set: the JSON text is used, not " + sun, warnings.text())

    def test_a_new_scene_runs_the_filter_again(self):
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(read_bunny())
        shade.SetSceneFileName(STUDIO)
        shade.Update()
        self.assertSameArrays(command_line("studio_first", "-s", STUDIO), arrays_of(shade.GetOutput()))
        sun = os.path.join(DATA, "scenes", "sun.json")
        with open(sun) as scene:
            shade.SetSceneJson(scene.read())
        shade.Update()
        self.assertSameArrays(command_line("sun_then", "-s", sun), arrays_of(shade.GetOutput()))
        shade.SetSceneJson("  \n")  # white space alone is no text: the file again
        shade.Update()
        self.assertSameArrays(command_line("studio_again", "-s", STUDIO), arrays_of(shade.GetOutput()))

    def test_without_a_scene_the_default_light_kit(self):
        self.assertSameArrays(command_line("kit", "-a", "totals"), shaded(lambda shade: select(shade, "totals")))

    def test_shadows_and_occlusion_and_a_prefix(self):
        expected = command_line("shadows", "-s", SHADOWS, "-a", "all", "--prefix", "sl_")
        def configure(shade):
            shade.SetSceneFileName(SHADOWS)
            select(shade, "all")
            shade.SetArrayPrefix("sl_")
        actual = shaded(configure)
        self.assertIn("sl_ambient_occlusion", actual)
        self.assertSameArrays(expected, actual)

    def test_a_tolerance_chooses_as_the_command_line_does(self):
        expected = command_line("tolerance", "-s", STUDIO, "-a", "totals", "--tolerance", "1e-3")
        def configure(shade):
            shade.SetSceneFileName(STUDIO)
            select(shade, "totals")
            shade.SetTolerance(1e-3)
        self.assertSameArrays(expected, shaded(configure))


class Errors(unittest.TestCase):
    """A run that fails raises shadelab.ShadeLabError with the command line's message, and VTK
    prints nothing of it."""

    def raised_by(self, update):
        with ErrorText() as printed:
            with self.assertRaises(shadelab.ShadeLabError) as raised:
                update()
        self.assertEqual(printed.text(), "")
        self.assertIsInstance(raised.exception, RuntimeError)
        return str(raised.exception)

    def run_with_error(self, configure):
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(read_bunny())
        configure(shade)
        message = self.raised_by(shade.Update)
        self.assertEqual(shade.GetOutput().GetNumberOfPoints(), 0)
        return message

    def command_line_message(self, *arguments):
        """The command line's message for these arguments, without its 'shadelab: '."""
        run = subprocess.run([SHADELAB, "shade", BUNNY, "-o", os.path.join(WORK, "unwritten.vtp"), *arguments],
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 1, run.stderr)
        self.assertTrue(run.stderr.startswith("shadelab: "), run.stderr)
        return run.stderr[len("shadelab: "):].strip()

    def test_the_image_module_is_found_once_it_is_named(self):
        """A failure to load the module that reads maps is not kept: a long-lived process finds it
        once it is named. In a Python of its own, which has not loaded the module yet."""
        scene = os.path.join(WORK, "sunset_sky.json")
        with open(scene, "w") as out:
            out.write('{"lights": [{"name": "sky", "type": "environment", "estimator": "sh", "file": "%s"}]}'
                      % os.path.join(DATA, "envmaps", "venice_sunset_1k.hdr"))
        module = os.path.join(os.path.dirname(os.path.dirname(SHADELAB)), "lib", "shadelab", "libshadelab_images.so")
        nowhere = os.path.join(WORK, "nowhere", "libshadelab_images.so")
        code = "\n".join([
            "import os, shadelab",
            "from vtkmodules.vtkFiltersSources import vtkSphereSource",
            "sphere = vtkSphereSource()",
            "shade = shadelab.vtkLocalReflectanceFilter()",
            "shade.SetInputConnection(sphere.GetOutputPort())",
            "shade.SetSceneFileName(%r)" % scene,
            "os.environ['SHADELAB_IMAGE_MODULE'] = %r" % nowhere,
            "try:",
            "    shade.Update()",
            "except shadelab.ShadeLabError as error:",
            "    print(error)",
            "os.environ['SHADELAB_IMAGE_MODULE'] = %r" % module,
            "shade.Modified()",
            "shade.Update()",
            "print(shade.GetOutput().GetPointData().GetArray('total').GetNumberOfTuples())"])
        run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stdout.splitlines(), [
            scene + ": /lights/0/file: SHADELAB_IMAGE_MODULE names " + nowhere + ", which does not exist: give the path "
            "of ShadeLab's libshadelab_images.so, or unset it", "50"])

    def test_a_missing_scene_file(self):
        missing = os.path.join(WORK, "no_such_scene.json")
        message = self.command_line_message("-s", missing)
        self.assertEqual(message, missing + ": cannot open the scene file (does it exist, and is it readable?)")
        self.assertEqual(self.run_with_error(lambda shade: shade.SetSceneFileName(missing)), message)

    def test_a_negative_intensity_in_a_file_and_in_json_text(self):
        text = '{"lights": [{"type": "point", "position": [0, 1, 0], "intensity": -2}]}'
        scene_file = os.path.join(WORK, "negative_intensity.json")
        with open(scene_file, "w") as scene:
            scene.write(text)
        message = self.command_line_message("-s", scene_file)
        self.assertEqual(message, scene_file + ": /lights/0/intensity: must be a number >= 0")
        self.assertEqual(self.run_with_error(lambda shade: shade.SetSceneFileName(scene_file)), message)
        self.assertEqual(self.run_with_error(lambda shade: shade.SetSceneJson(text)),
                         "SceneJson: /lights/0/intensity: must be a number >= 0")

    def test_an_unknown_array(self):
        message = self.command_line_message("-a", "key_nonsense")
        self.assertTrue(message.startswith("--arrays: unknown array 'key_nonsense'; this scene has: default, "),
                        message)
        self.assertEqual(self.run_with_error(lambda shade: select(shade, "key_nonsense")), message[len("--arrays: "):])

    def test_the_first_error_upstream_is_raised_downstream(self):
        missing = os.path.join(WORK, "no_such_scene.json")
        normals = shadelab.vtkShadingNormalsFilter()
        normals.SetInputData(read_bunny())
        seen = shadelab.vtkMeshVisibilityFilter()
        seen.SetInputConnection(normals.GetOutputPort())
        seen.SetSceneFileName(missing)
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputConnection(seen.GetOutputPort())
        shade.SetSceneFileName(STUDIO)
        self.assertEqual(self.raised_by(shade.Update),
                         missing + ": cannot open the scene file (does it exist, and is it readable?)")
        # The observers are gone with the run: a good scene runs and raises nothing.
        seen.SetSceneFileName(SHADOWS)
        shade.Update()
        self.assertEqual(shade.GetOutput().GetNumberOfPoints(), 35947)

    def test_every_update_method_raises(self):
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(read_bunny())
        shade.SetSceneJson("{")
        for update in (shade.Update, lambda: shade.Update(0), shade.UpdateWholeExtent,
                       lambda: shade.UpdatePiece(0, 1, 0)):
            shade.Modified()
            self.assertTrue(self.raised_by(update).startswith("SceneJson: not valid JSON: "))

    def test_an_algorithm_upstream_that_fails_without_an_error(self):
        reader = vtkPLYReader()
        reader.SetFileName(os.path.join(WORK, "no_such_mesh.ply"))
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputConnection(reader.GetOutputPort())
        with ErrorText() as printed:
            with self.assertRaises(shadelab.ShadeLabError) as raised:
                shade.Update()
        self.assertEqual(str(raised.exception), "vtkPLYReader failed without an error of its own (its warnings, "
                         "if VTK printed any, say why)")
        self.assertIn("Could not open PLY file", printed.text())  # the reader's warning, printed as VTK prints it


class Properties(unittest.TestCase):
    def test_the_selection_one_entry_at_a_time(self):
        shade = shadelab.vtkLocalReflectanceFilter()
        self.assertEqual(shade.GetNumberOfArraySelectionEntries(), 1)
        self.assertEqual(shade.GetArraySelectionEntry(0), "default")
        select(shade, "totals", "*_cos_incidence")
        self.assertEqual([shade.GetArraySelectionEntry(i) for i in range(shade.GetNumberOfArraySelectionEntries())],
                         ["totals", "*_cos_incidence"])
        self.assertEqual(shade.GetArraySelectionEntry(2), "")

    def test_the_list_of_the_scenes_arrays(self):
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(read_bunny())
        shade.SetSceneFileName(STUDIO)
        shade.UpdateInformation()
        listed = shade.GetAvailableArrays()
        names = [listed.GetArrayName(i) for i in range(listed.GetNumberOfArrays())]
        self.assertEqual(len(names), 40)  # "all" but the computed normals
        ticked = [name for name in names if listed.ArrayIsEnabled(name)]
        self.assertEqual(ticked, ["ambient", "diffuse", "specular", "total", "shading_flags"])
        # Boxes ticked and unticked become the selection.
        listed.DisableArray("total")
        listed.EnableArray("key_diffuse")
        shade.Update()
        self.assertEqual(sorted(arrays_of(shade.GetOutput())),
                         sorted(["Normals", "ambient", "diffuse", "specular", "shading_flags", "key_diffuse"]))
        self.assertEqual([shade.GetArraySelectionEntry(i) for i in range(shade.GetNumberOfArraySelectionEntries())],
                         ["ambient", "diffuse", "specular", "shading_flags", "key_diffuse"])
        # Another scene: the names it lacks leave the selection, and its list is its own.
        shade.SetSceneFileName(os.path.join(DATA, "scenes", "sun.json"))
        shade.Update()
        self.assertEqual(sorted(arrays_of(shade.GetOutput())),
                         sorted(["Normals", "ambient", "diffuse", "specular", "shading_flags"]))
        self.assertFalse(any(listed.GetArrayName(i).startswith("key_") for i in range(listed.GetNumberOfArrays())))
        # The selection's own setters, used after the list, win over it.
        listed.DisableArray("ambient")
        select(shade, "totals")
        shade.Update()
        self.assertEqual(sorted(arrays_of(shade.GetOutput())), sorted(["Normals", "ambient", "diffuse", "specular", "total"]))
        self.assertTrue(listed.ArrayIsEnabled("ambient") and not listed.ArrayIsEnabled("shading_flags"))

    def test_one_thread_gives_the_same_bits_and_gives_the_count_back(self):
        before = vtkSMPTools.GetEstimatedNumberOfThreads()
        self.assertGreater(before, 1, "this test needs a machine with more than one core")
        during = []
        def seen_on(threads):
            normals = shadelab.vtkShadingNormalsFilter()
            normals.SetInputData(read_bunny())
            seen = shadelab.vtkMeshVisibilityFilter()
            seen.SetInputConnection(normals.GetOutputPort())
            seen.SetSceneFileName(SHADOWS)
            seen.SetNumberOfThreads(threads)
            # The rays report progress in tenths from within the run, where the count is the
            # filter's (VTK's pipeline reports 0 and 1 around it).
            seen.AddObserver("ProgressEvent", lambda caller, _: during.append(
                vtkSMPTools.GetEstimatedNumberOfThreads()) if 0 < caller.GetProgress() < 1 else None)
            seen.Update()
            return arrays_of(seen.GetOutput())
        one = seen_on(1)
        self.assertTrue(len(during) >= 5 and set(during) == {1}, during)
        self.assertEqual(vtkSMPTools.GetEstimatedNumberOfThreads(), before)
        during.clear()
        every = seen_on(0)
        self.assertTrue(len(during) >= 5 and set(during) == {before}, during)
        self.assertIn("ambient_occlusion", one)
        SameAsTheCommandLine.assertSameArrays(self, every, one)

    def test_the_visibility_filter_from_json_text(self):
        normals = shadelab.vtkShadingNormalsFilter()
        normals.SetInputData(read_bunny())
        seen = shadelab.vtkMeshVisibilityFilter()
        seen.SetInputConnection(normals.GetOutputPort())
        with open(SHADOWS) as scene:
            seen.SetSceneJson(scene.read())
        seen.Update()
        arrays = arrays_of(seen.GetOutput())
        expected = command_line("shadows_occlusion", "-s", SHADOWS, "-a", "all")
        for name in ("ambient_occlusion", "ambient_occlusion_std_error", "bent_normal", "sky_view_factor"):
            self.assertTrue(np.array_equal(arrays[name], expected[name]), name)
        self.assertIn("Cast up to", seen.GetReport())


class MaterialFromArrays(unittest.TestCase):
    """The head scan's own colours: the ColorByArray property and a scene naming the array give
    the command line's arrays bit for bit; a field's colour map ends at ParaView's preset."""

    def test_the_scans_colours_as_the_command_line_shades_them(self):
        head = os.path.join(DATA, "meshes", "head_scan.ply")
        scene = os.path.join(DATA, "scenes", "scan_colors.json")
        output = os.path.join(WORK, "head.vtp")
        subprocess.run([SHADELAB, "shade", head, "-s", scene, "-o", output], check=True, capture_output=True)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(output)
        reader.Update()
        expected = arrays_of(reader.GetOutput())
        ply = vtkPLYReader()
        ply.SetFileName(head)
        ply.Update()
        with open(scene) as text:
            uniform = text.read().replace('"kd": { "array": "RGB" }', '"kd": 0.5')
        self.assertNotIn('"array"', uniform)
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(ply.GetOutput())
        shade.SetSceneJson(uniform)
        shade.SetColorByArray(True)
        shade.SetMaterialColorArray("RGB")
        shade.Update()
        actual = arrays_of(shade.GetOutput())
        SameAsTheCommandLine.assertSameArrays(self, expected, actual)
        # Not the uniform grey: the colours vary as the scan's do.
        self.assertGreater(len(np.unique(actual["ambient"][:, 0])), 100)  # of 162 red levels in the scan

    def test_a_field_through_cool_to_warm(self):
        mesh = read_bunny()
        field = vtk_to_numpy(mesh.GetPoints().GetData())[:, 1].astype(np.float64)
        from vtkmodules.util.numpy_support import numpy_to_vtk
        array = numpy_to_vtk(field, deep=True)
        array.SetName("height")
        mesh.GetPointData().AddArray(array)
        shade = shadelab.vtkLocalReflectanceFilter()
        shade.SetInputData(mesh)
        shade.SetSceneFileName(STUDIO)
        shade.ColorByArrayOn()
        shade.SetMaterialColorArray("height")
        shade.SetOutputPrecision(vtkAlgorithm.DOUBLE_PRECISION)
        shade.Update()
        ambient = arrays_of(shade.GetOutput())["ambient"]
        def linear(byte):
            c = byte / 255.0
            return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
        # studio.json's room light is 0.08; the lowest and highest points take the map's ends.
        for vertex, color in ((np.argmin(field), (59, 76, 192)), (np.argmax(field), (180, 4, 38))):
            np.testing.assert_allclose(ambient[vertex], [0.08 * linear(b) for b in color], rtol=1e-12)


class Relighting(unittest.TestCase):
    def test_relight_is_the_command_lines_and_says_why_it_cannot(self):
        studio_map = os.path.join(DATA, "envmaps", "studio_small_03_1k.hdr")
        sunset = os.path.join(DATA, "envmaps", "venice_sunset_1k.hdr")
        transfer = os.path.join(WORK, "transfer.vtp")
        subprocess.run([SHADELAB, "shade", BUNNY, "-o", transfer, "--envmap", studio_map, "--envmap-estimator", "prt",
                        "--envmap-order", "4", "-a", "envmap_sh_transfer"], check=True, capture_output=True)
        relit_file = os.path.join(WORK, "relit.vtp")
        subprocess.run([SHADELAB, "relight", transfer, "--envmap", sunset, "--rotation", "30", "--intensity", "2",
                        "--name", "sunset", "-o", relit_file], check=True, capture_output=True)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(transfer)
        reader.Update()
        relit = shadelab.relight(reader.GetOutput(), sunset, rotation=30, intensity=2, output_array="sunset")
        reader.SetFileName(relit_file)
        reader.Update()
        expected = arrays_of(reader.GetOutput())
        actual = arrays_of(relit)
        self.assertEqual(actual["sunset"].shape, (35947, 3))
        self.assertTrue(np.array_equal(expected["sunset"], actual["sunset"]))
        # Twice the intensity, twice the irradiance (to float32's rounding).
        once = arrays_of(shadelab.relight(reader.GetOutput(), sunset, rotation=30, transfer_array="envmap_sh_transfer"))
        self.assertTrue(np.allclose(2 * once["relit_irradiance"], actual["sunset"], rtol=1e-6, atol=1e-6))
        with ErrorText() as printed:
            with self.assertRaises(shadelab.ShadeLabError) as refused:
                shadelab.relight(read_bunny(), sunset)
        self.assertEqual(printed.text(), "")
        self.assertEqual(str(refused.exception),
                         "the input has no point array whose name ends in '_sh_transfer': shade the mesh with "
                         "\"estimator\": \"prt\" (shadelab shade --envmap-estimator prt) first")


    def test_relight_adds_the_interreflection_the_transfer_carries_unless_direct_only(self):
        studio_map = os.path.join(DATA, "envmaps", "studio_small_03_1k.hdr")
        transfer = os.path.join(WORK, "transfer_bounces.vtp")
        subprocess.run([SHADELAB, "shade", BUNNY, "-o", transfer, "--envmap", studio_map, "--envmap-estimator", "prt",
                        "--bounces", "2", "-a", "envmap_sh_transfer,envmap_sh_transfer_indirect,indirect_irradiance"],
                       check=True, capture_output=True)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(transfer)
        reader.Update()
        self.assertEqual(reader.GetOutput().GetPointData().GetArray("envmap_sh_transfer_indirect")
                         .GetNumberOfComponents(), 27)
        # Relit under the map it was shaded with, the indirect part is the shading's gather, but
        # where the map's nine coefficients ring below 0 (shading reflects nothing there, the
        # transfer all its sign): 91% of the vertices agree to 1e-5, and none by more than 0.1%
        # of the largest (docs/guide/relighting.md).
        relit = arrays_of(shadelab.relight(reader.GetOutput(), studio_map))
        shaded = arrays_of(reader.GetOutput())["indirect_irradiance"]
        difference = np.abs(relit["relit_irradiance_indirect"] - shaded).max(axis=1)
        self.assertGreater(np.mean(difference < 1e-5), 0.85)
        self.assertLess(difference.max(), 1e-3 * shaded.max())
        direct = arrays_of(shadelab.relight(reader.GetOutput(), studio_map, direct_only=True))
        self.assertNotIn("relit_irradiance_indirect", direct)
        self.assertGreater(np.abs(relit["relit_irradiance"] - direct["relit_irradiance"]).max(), 0.1)


class Interreflection(unittest.TestCase):
    def test_bounces_are_the_command_lines_and_the_filter_alone_says_why_it_cannot(self):
        scene = os.path.join(DATA, "scenes", "interreflection.json")
        expected = command_line("interreflection", "-s", scene, "-a", "all")
        shading = shadelab.vtkLocalReflectanceFilter()
        shading.SetInputData(read_bunny())
        shading.SetSceneFileName(scene)
        shading.SetArraySelection(["all"])
        shading.Update()
        actual = arrays_of(shading.GetOutput())
        for name in ("indirect_irradiance", "indirect", "indirect_bounce_3", "diffuse", "total"):
            self.assertTrue(np.array_equal(expected[name], actual[name]), name)
        self.assertTrue(shading.GetInterreflectionReport().startswith("3 bounces from 'diffuse', 256 gather rays"))
        # The filter alone on the shaded bunny: the fewest bounces whose rest is within 1e-3.
        again = shadelab.vtkInterreflectionFilter()
        again.SetInputData(shading.GetOutput())
        again.SetAlbedo(0.8, 0.8, 0.8)
        again.SetBounces(64)
        again.SetBounceTolerance(1e-3)
        again.SetArrayPrefix("again_")
        again.Update()
        self.assertTrue(1 < again.GetBounceCount() < 64, again.GetBounceCount())
        self.assertLessEqual(again.GetRestBound(), 1e-3)
        self.assertIn(" bounces from 'diffuse', 64 gather rays per vertex", again.GetReport())
        gather = shadelab.vtkInterreflectionFilter()
        gather.SetInputData(read_bunny())
        with ErrorText() as printed:
            with self.assertRaises(shadelab.ShadeLabError) as refused:
                gather.Update()
        self.assertEqual(printed.text(), "")
        self.assertEqual(str(refused.exception), "the input has no point normals: the gather rays leave about them "
                         "(vtkShadingNormalsFilter makes them)")


if __name__ == "__main__":
    unittest.main(verbosity=2)
