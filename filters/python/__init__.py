"""ShadeLab's VTK filters, for VTK 9.1's Python (Debian 12: /usr/bin/python3).

    import shadelab
    shading = shadelab.vtkLocalReflectanceFilter()
    shading.SetSceneFileName("studio.json")

The filters are VTK algorithms like any other (docs/guide/cpp-and-python.md). Importing this package
also imports the vtkmodules the filters are built on.
"""
from .ShadeLabFilters import vtkLocalReflectanceFilter, vtkMeshVisibilityFilter, vtkShadingNormalsFilter

__all__ = ["vtkLocalReflectanceFilter", "vtkMeshVisibilityFilter", "vtkShadingNormalsFilter"]
