# The Python package as `cmake --install` leaves it: installed into a folder of its own, then
# imported by PYTHON with only that prefix's package folder on PYTHONPATH, from outside the build
# tree, and README.md's Python example run with it. Run by CTest with BUILD, PYTHON, DESTINATION
# (SHADELAB_PYTHON_DESTINATION), EXAMPLE, EXPECTED (a regular expression its output must match),
# SOURCE (the repository, the example's working folder) and WORK.
if(NOT EXPECTED)
  message(FATAL_ERROR "PythonInstalled.cmake needs EXPECTED, the example's output")
endif()
file(REMOVE_RECURSE "${WORK}")
include("${CMAKE_CURRENT_LIST_DIR}/ScriptStep.cmake")
step("installing ShadeLab" "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/prefix")
set(packages "${WORK}/prefix/${DESTINATION}")
file(MAKE_DIRECTORY "${WORK}/elsewhere")
step("importing shadelab" "${CMAKE_COMMAND}" -E chdir "${WORK}/elsewhere" env "PYTHONPATH=${packages}" "${PYTHON}" -c
  "import shadelab\nprint(shadelab.__file__)") # a newline: CMake would split the arguments at a ';'
string(FIND "${step_output}" "${packages}/shadelab/__init__.py" found)
if(NOT found EQUAL 0)
  message(FATAL_ERROR "shadelab was imported from ${step_output}, not from ${packages}")
endif()
step("running README.md's Python example" "${CMAKE_COMMAND}" -E chdir "${SOURCE}" env "PYTHONPATH=${packages}"
  "${PYTHON}" "${EXAMPLE}")
if(NOT step_output MATCHES "${EXPECTED}")
  message(FATAL_ERROR "README.md's Python example did not finish:\n${step_output}")
endif()
# A map is read through the image module the install put under its prefix (ImageFile.h), found
# from the package's own place, not the build tree's.
file(WRITE "${WORK}/map.json" "{ \"lights\": [ { \"name\": \"sky\", \"type\": \"environment\", \"file\": "
  "\"${SOURCE}/data/envmaps/venice_sunset_1k.hdr\", \"estimator\": \"sh\" } ] }")
step("shading under a map" "${CMAKE_COMMAND}" -E chdir "${WORK}/elsewhere" env "PYTHONPATH=${packages}" "${PYTHON}" -c
  "import shadelab\nfrom vtkmodules.vtkFiltersSources import vtkSphereSource\nsphere = vtkSphereSource()\nshade = shadelab.vtkLocalReflectanceFilter()\nshade.SetInputConnection(sphere.GetOutputPort())\nshade.SetSceneFileName('${WORK}/map.json')\nshade.Update()\nprint([line.split()[-1] for line in open('/proc/self/maps') if 'libshadelab_images' in line][0])")
string(FIND "${step_output}" "${WORK}/prefix/" found)
if(NOT found EQUAL 0)
  message(FATAL_ERROR "the image module was loaded from ${step_output}, not from under ${WORK}/prefix")
endif()
message(STATUS "the package was imported from the install prefix and ran README.md's Python example")
