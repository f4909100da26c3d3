"""ShadeLab's VTK filters, for VTK 9.1's Python (Debian 12: /usr/bin/python3).

    import shadelab
    shading = shadelab.vtkLocalReflectanceFilter()
    shading.SetSceneFileName("studio.json")

The filters are VTK algorithms like any other (docs/guide/cpp-and-python.md). Importing this package
also imports the vtkmodules the filters are built on.
"""
import re

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

from .ShadeLabFilters import (vtkLocalReflectanceFilter, vtkMeshVisibilityFilter, vtkShadingNormalsFilter,
                              vtkTransferRelightFilter)

__all__ = ["vtkLocalReflectanceFilter", "vtkMeshVisibilityFilter", "vtkShadingNormalsFilter",
           "vtkTransferRelightFilter", "relight"]


def relight(mesh, environment_map, rotation=0.0, intensity=1.0, color=(1.0, 1.0, 1.0), transfer_array="",
            output_array="relit_irradiance"):
    """The mesh (a vtkPolyData shaded with "estimator": "prt") with the irradiance under another map.

    Each vertex's transfer vector (transfer_array, by default the one array ending in
    "_sh_transfer") is dotted with environment_map's coefficients, the map turned by rotation
    degrees about +y and scaled by color x intensity, with no ray traced; the result is the RGB
    point array output_array. Raises RuntimeError with the filter's message when it cannot.
    """
    relighting = vtkTransferRelightFilter()
    relighting.SetInputData(mesh)
    relighting.SetEnvironmentMapFileName(str(environment_map))
    relighting.SetRotation(rotation)
    relighting.SetIntensity(intensity)
    relighting.SetColor(*color)
    relighting.SetTransferArrayName(transfer_array)
    relighting.SetOutputArrayName(output_array)
    messages = []

    @calldata_type(VTK_STRING)
    def keep(caller, event, text):
        # Without VTK's "ERROR: In FILE, line N" and "vtkClass (0x...): ", as the command line shows it.
        text = re.sub(r"^(ERROR|Warning|Generic Warning): In [^\n]*\n", "", text)
        messages.append(re.sub(r"^[A-Za-z0-9_]+ \(0x[0-9a-fA-F]+\): ", "", text).rstrip())

    relighting.AddObserver("ErrorEvent", keep)
    relighting.Update()
    if messages:
        raise RuntimeError(messages[0])
    return relighting.GetOutput()
