"""ShadeLab's VTK filters, for VTK 9.1's Python (Debian 12: /usr/bin/python3).

    import shadelab
    shading = shadelab.vtkLocalReflectanceFilter()
    shading.SetSceneFileName("studio.json")

The filters are VTK algorithms like any other (docs/guide/cpp-and-python.md), except that their
Update() and the other Update methods raise ShadeLabError when the run reports an error, rather
than leaving an empty output and printing the message. Importing this package also imports the
vtkmodules the filters are built on.
"""
import re

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkOutputWindow

from . import ShadeLabFilters

__all__ = ["vtkLocalReflectanceFilter", "vtkMeshVisibilityFilter", "vtkShadingNormalsFilter",
           "vtkTransferRelightFilter", "vtkInterreflectionFilter", "relight", "ShadeLabError"]


class ShadeLabError(RuntimeError):
    """A run's error, with the message the command line prints for it (without VTK's
    "ERROR: In FILE, line N" and "vtkClass (0x...): ")."""


def _message_text(text):
    text = re.sub(r"^(ERROR|Warning|Generic Warning): In [^\n]*\n", "", text)
    return re.sub(r"^[A-Za-z0-9_]+ \(0x[0-9a-fA-F]+\): ", "", text).rstrip()


# The pipeline's message after an algorithm has failed, which says no more than which one failed.
_FAILURE_FOLLOW_UP = re.compile(r"Algorithm ([A-Za-z0-9_]+)\(0x[0-9a-fA-F]+\) returned failure for request")


def _first_error(messages):
    """The first of messages that an algorithm gave itself; or, when it gave none, which failed."""
    for message in messages:
        if not _FAILURE_FOLLOW_UP.match(message):
            return message
    failed = _FAILURE_FOLLOW_UP.match(messages[0]).group(1)
    return failed + " failed without an error of its own (its warnings, if VTK printed any, say why)"


def _pipeline(algorithm):
    """algorithm and every algorithm upstream of it."""
    found, waiting = {}, [algorithm]
    while waiting:
        step = waiting.pop()
        if step.__this__ in found:
            continue
        found[step.__this__] = step
        waiting += [step.GetInputAlgorithm(port, connection) for port in range(step.GetNumberOfInputPorts())
                    for connection in range(step.GetNumberOfInputConnections(port))]
    return list(found.values())


class _RaisedErrors:
    """While in the with block, collects the errors of algorithm's run: those of every algorithm
    of its pipeline and of their executives, observed (so VTK does not print them), and any other
    that reaches VTK's output window (a filter's internal steps, which VTK prints too). On
    leaving, raises ShadeLabError with the first of them (_first_error)."""

    def __init__(self, algorithm):
        self.algorithm = algorithm
        self.messages = []
        self.observed = []

    def __enter__(self):
        @calldata_type(VTK_STRING)
        def keep(caller, event, text):
            self.messages.append(_message_text(text))

        window = vtkOutputWindow.GetInstance()
        for step in _pipeline(self.algorithm):
            for source in (step, step.GetExecutive()):
                self.observed.append((source, source.AddObserver("ErrorEvent", keep)))
        self.observed.append((window, window.AddObserver("ErrorEvent", keep)))
        return self

    def __exit__(self, kind, value, trace):
        for source, tag in self.observed:
            source.RemoveObserver(tag)
        if kind is None and self.messages:
            raise ShadeLabError(_first_error(self.messages))
        return False


def _raising(update):
    def raising(self, *arguments):
        with _RaisedErrors(self):
            return update(self, *arguments)
    raising.__name__ = update.__name__
    raising.__doc__ = update.__doc__
    return raising


def _filter_raising_errors(wrapped):
    """A Python subclass of the wrapped filter whose Update methods raise ShadeLabError."""
    updates = ("Update", "UpdateInformation", "UpdateDataObject", "UpdateWholeExtent", "UpdatePiece",
               "UpdateExtent", "UpdateTimeStep")
    methods = {name: _raising(getattr(wrapped, name)) for name in updates}
    methods["__doc__"] = wrapped.__doc__
    methods["__module__"] = __name__
    return type(wrapped.__name__, (wrapped,), methods)


vtkLocalReflectanceFilter = _filter_raising_errors(ShadeLabFilters.vtkLocalReflectanceFilter)
vtkMeshVisibilityFilter = _filter_raising_errors(ShadeLabFilters.vtkMeshVisibilityFilter)
vtkShadingNormalsFilter = _filter_raising_errors(ShadeLabFilters.vtkShadingNormalsFilter)
vtkTransferRelightFilter = _filter_raising_errors(ShadeLabFilters.vtkTransferRelightFilter)
vtkInterreflectionFilter = _filter_raising_errors(ShadeLabFilters.vtkInterreflectionFilter)


def relight(mesh, environment_map, rotation=0.0, intensity=1.0, color=(1.0, 1.0, 1.0), transfer_array="",
            output_array="relit_irradiance", direct_only=False):
    """The mesh (a vtkPolyData shaded with "estimator": "prt") with the irradiance under another map.

    Each vertex's transfer vector (transfer_array, by default the one array ending in
    "_sh_transfer") is dotted with environment_map's coefficients, the map turned by rotation
    degrees about +y and scaled by color x intensity, with no ray traced; the result is the RGB
    point array output_array. A mesh shaded with interreflection also has the transfer's
    indirect part (<transfer>_indirect): unless direct_only, output_array includes the light the
    mesh reflects onto itself, and output_array + "_indirect" holds that part alone. Raises
    ShadeLabError with the filter's message when it cannot.
    """
    relighting = vtkTransferRelightFilter()
    relighting.SetInputData(mesh)
    relighting.SetEnvironmentMapFileName(str(environment_map))
    relighting.SetRotation(rotation)
    relighting.SetIntensity(intensity)
    relighting.SetColor(*color)
    relighting.SetTransferArrayName(transfer_array)
    relighting.SetOutputArrayName(output_array)
    relighting.SetUseIndirectTransfer(not direct_only)
    relighting.Update()
    return relighting.GetOutput()
