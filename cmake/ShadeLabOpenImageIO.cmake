# OpenImageIO, found as ShadeLab's image module and the tests that write images need it.
# Debian 12's package lists /usr/include/opencv4 among its include directories, which only
# libopencv-dev (not one of its dependencies) creates, and CMake refuses a missing one: keep
# those that exist.
macro(shadelab_find_openimageio)
  find_package(OpenImageIO ${ARGN})
  if(TARGET OpenImageIO::OpenImageIO)
    get_target_property(_shadelab_oiio_dirs OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
    set(_shadelab_oiio_existing "")
    foreach(_shadelab_dir IN LISTS _shadelab_oiio_dirs)
      if(EXISTS "${_shadelab_dir}")
        list(APPEND _shadelab_oiio_existing "${_shadelab_dir}")
      endif()
    endforeach()
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_shadelab_oiio_existing}")
  endif()
endmacro()
