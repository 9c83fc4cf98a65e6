# cmake -DBUILD=<build> -DWORK=<scratch> -DPVPYTHON=<pvpython> -DPYTHON=<python3>
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

# An external C++ project.
run("consumer configure" "${CMAKE_COMMAND}" -S "${CMAKE_CURRENT_LIST_DIR}/Consumer" -B "${WORK}/consumer"
    "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("consumer build" "${CMAKE_COMMAND}" --build "${WORK}/consumer")
run("consumer run" "${WORK}/consumer/consumer")
message(STATUS "${run_output}")

# The program.
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
endif ()
