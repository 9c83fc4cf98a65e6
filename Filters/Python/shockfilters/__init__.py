"""Shock filters of Prada and Kazhdan (2015) for VTK pipelines in Python.

    from shockfilters import (vtkImageShockAdvectionFilter,
                              vtkPolyDataShockAdvectionFilter,
                              vtkPolyDataShockSharpenFilter)

The classes are those of the VTK modules VTK::FiltersShock and VTK::IOShock
(vtkOFFReader, vtkOFFWriter), wrapped with VTK's
own vtk_module_wrap_python against ParaView's vtkmodules; use them with
ParaView's vtkmodules (pvpython, or the python3 ParaView was built with).
"""
# The base classes (vtkAlgorithm, ...) come from ParaView's vtkmodules.
from vtkmodules import vtkCommonExecutionModel as _vtkCommonExecutionModel  # noqa: F401
from .vtkFiltersShock import *  # noqa: F401,F403
from .vtkIOShock import *  # noqa: F401,F403
