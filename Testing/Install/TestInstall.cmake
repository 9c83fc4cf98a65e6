# cmake -DBUILD=<build> -DWORK=<scratch> [-DSOURCE=<repository>] -DPVPYTHON=<pvpython> -DPYTHON=<python3>
#       [-DPLUGIN_SUBDIR=lib/paraview-5.11/plugins/ShockFilters]
#       [-DPYTHON_SUBDIR=lib/python3.11/site-packages] -P TestInstall.cmake
#
# Installs the build into a fresh prefix and uses the installed tree only, as
# a user would: an external project (Consumer/) with find_package(ShockFilters)
# and VTK::FiltersShock is configured, built and run; the installed program
# runs; pvpython loads the installed plugin through PV_PLUGIN_PATH and through
# LoadPlugin; Python imports the installed package shockfilters.
foreach (var IN ITEMS BUILD WORK)
  if (NOT DEFINED ${var})
    message(FATAL_ERROR "${var} is required")
  endif ()
endforeach ()
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")

function (run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif ()
  message(STATUS "${what}: ok")
  set(run_output "${out}${err}" PARENT_SCOPE)
endfunction ()

run("install" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${prefix}")

# The headers: in a versioned folder, as VTK's and ParaView's, none loose in include/.
file(GLOB loose_headers "${prefix}/include/*.h")
if (loose_headers)
  message(FATAL_ERROR "headers installed loose in include/: ${loose_headers}")
endif ()
file(GLOB versioned "${prefix}/include/ShockFilters-*/vtkImageShockAdvectionFilter.h")
if (NOT versioned)
  message(FATAL_ERROR "vtkImageShockAdvectionFilter.h is not in include/ShockFilters-<major>.<minor>/")
endif ()

# An external C++ project.
run("consumer configure" "${CMAKE_COMMAND}" -S "${CMAKE_CURRENT_LIST_DIR}/Consumer" -B "${WORK}/consumer"
    "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("consumer build" "${CMAKE_COMMAND}" --build "${WORK}/consumer")
run("consumer run" "${WORK}/consumer/consumer")
message(STATUS "${run_output}")

# README's C++ route, exactly as written there: its CMakeLists.txt and program,
# run on a PNG photo in the program's folder.
if (DEFINED SOURCE AND DEFINED PYTHON)
  file(READ "${SOURCE}/README.md" readme)
  string(FIND "${readme}" "### C++ (VTK pipeline)" at)
  if (at LESS 0)
    message(FATAL_ERROR "README.md has no section '### C++ (VTK pipeline)'")
  endif ()
  string(SUBSTRING "${readme}" ${at} -1 section)
  foreach (language IN ITEMS cpp cmake)
    string(FIND "${section}" "```${language}\n" begin)
    if (begin LESS 0)
      message(FATAL_ERROR "README.md's C++ section has no ${language} block")
    endif ()
    string(LENGTH "```${language}\n" fence)
    math(EXPR begin "${begin} + ${fence}")
    string(SUBSTRING "${section}" ${begin} -1 rest)
    string(FIND "${rest}" "\n```" end)
    string(SUBSTRING "${rest}" 0 ${end} code_${language})
  endforeach ()
  file(WRITE "${WORK}/readme/app.cxx" "${code_cpp}\n")
  file(WRITE "${WORK}/readme/CMakeLists.txt" "${code_cmake}\n")
  run("README's C++ project configure" "${CMAKE_COMMAND}" -S "${WORK}/readme" -B "${WORK}/readme/build"
      "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
  run("README's C++ project build" "${CMAKE_COMMAND}" --build "${WORK}/readme/build")
  file(WRITE "${WORK}/readme/photo.py" [[
from vtkmodules.vtkImagingCore import vtkImageShiftScale, vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
source = vtkRTAnalyticSource()
source.SetWholeExtent(0, 63, 0, 47, 0, 0)
to_bytes = vtkImageShiftScale()
to_bytes.SetInputConnection(source.GetOutputPort())
to_bytes.SetShift(-37.0)
to_bytes.SetScale(255.0 / 240.0)
to_bytes.SetOutputScalarTypeToUnsignedChar()
to_bytes.ClampOverflowOn()
writer = vtkPNGWriter()
writer.SetInputConnection(to_bytes.GetOutputPort())
writer.SetFileName("photo.png")
writer.Write()
]])
  execute_process(COMMAND "${PYTHON}" photo.py WORKING_DIRECTORY "${WORK}/readme" RESULT_VARIABLE rc)
  execute_process(COMMAND "${WORK}/readme/build/app" WORKING_DIRECTORY "${WORK}/readme" RESULT_VARIABLE rc
    OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0 OR NOT EXISTS "${WORK}/readme/photo_sharp.png")
    message(FATAL_ERROR "README's C++ program failed (${rc}) or wrote no photo_sharp.png:\n${out}\n${err}")
  endif ()
  message(STATUS "README's C++ program: ok")
endif ()

# The program.
run("installed shockfilter --version" "${prefix}/bin/shockfilter" --version)
if (NOT run_output MATCHES "^shockfilter [0-9]+\\.[0-9]+\\.[0-9]+ ")
  message(FATAL_ERROR "shockfilter --version printed: ${run_output}")
endif ()
run("installed shockfilter --help" "${prefix}/bin/shockfilter" --help)

# The plugin, both ways ParaView users load it.
if (DEFINED PVPYTHON AND DEFINED PLUGIN_SUBDIR)
  set(plugin_dir "${prefix}/${PLUGIN_SUBDIR}")
  file(WRITE "${WORK}/load.py" [[
import sys
from paraview.simple import *
if len(sys.argv) > 1:
    LoadPlugin(sys.argv[1], ns=globals())
shock = ImageShockAdvection(Input=Wavelet())
shock.UpdatePipeline()
assert list(shock.InputArray) == ["POINTS", "RTData"], shock.InputArray
assert shock.GetDataInformation().GetNumberOfPoints() == 9261
print("plugin from", sys.argv[1] if len(sys.argv) > 1 else "PV_PLUGIN_PATH")
]])
  run("pvpython with PV_PLUGIN_PATH" "${CMAKE_COMMAND}" -E env "PV_PLUGIN_PATH=${plugin_dir}"
      "${PVPYTHON}" --force-offscreen-rendering "${WORK}/load.py")
  run("pvpython LoadPlugin" "${PVPYTHON}" --force-offscreen-rendering "${WORK}/load.py"
      "${plugin_dir}/ShockFilters.so")
endif ()

# The Python package.
if (DEFINED PYTHON AND DEFINED PYTHON_SUBDIR)
  file(WRITE "${WORK}/import.py" [[
from shockfilters import vtkImageShockAdvectionFilter, vtkPolyDataShockAdvectionFilter, vtkPolyDataShockSharpenFilter
import shockfilters
assert vtkImageShockAdvectionFilter().GetFlowTime() == 64.0
print("shockfilters from", shockfilters.__file__)
]])
  foreach (interpreter IN ITEMS "${PYTHON}" "${PVPYTHON}")
    run("${interpreter} imports shockfilters" "${CMAKE_COMMAND}" -E env "PYTHONPATH=${prefix}/${PYTHON_SUBDIR}"
        "${interpreter}" "${WORK}/import.py")
    if (NOT run_output MATCHES "shockfilters from ${prefix}/")
      message(FATAL_ERROR "shockfilters was not imported from the installed tree:\n${run_output}")
    endif ()
  endforeach ()
  if (DEFINED SOURCE)
    run("Examples/vtk_pipeline.py on the installed package" "${CMAKE_COMMAND}" -E env
        "PYTHONPATH=${prefix}/${PYTHON_SUBDIR}" "${PYTHON}" "${SOURCE}/Examples/vtk_pipeline.py" "${WORK}/pipeline")
  endif ()
endif ()
