# find_package(ShadeLab): the VTK module ShadeLab::Filters, the command ShadeLab::shadelab, and
# the CTest helper shadelab_add_regression_test (ShadeLabRegression.cmake).
include(CMakeFindDependencyMacro)
find_dependency(glm)
find_dependency(nlohmann_json 3)
find_dependency(embree 3)
find_dependency(VTK 9.1 COMPONENTS CommonCore CommonDataModel CommonExecutionModel CommonMath FiltersCore
  ParallelCore RenderingCore)
include("${CMAKE_CURRENT_LIST_DIR}/ShadeLab-targets.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/ShadeLab-vtk-module-properties.cmake")
if(NOT DEFINED SHADELAB_EXECUTABLE)
  set(SHADELAB_EXECUTABLE "$<TARGET_FILE:ShadeLab::shadelab>")
endif()
include("${CMAKE_CURRENT_LIST_DIR}/ShadeLabRegression.cmake")
