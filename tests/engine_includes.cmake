# The engine's sources name no file layer (issue 15): no file in core/ or dem/ includes io/,
# lab/, mesogen/, doe/, campaign/, calibrate/, apps/, toml++, HDF5 or cairo.
# Run as `cmake -DSOURCE_DIR=<source tree> -P engine_includes.cmake`.
file(GLOB_RECURSE sources ${SOURCE_DIR}/core/*.hpp ${SOURCE_DIR}/core/*.cpp ${SOURCE_DIR}/core/*.in
     ${SOURCE_DIR}/dem/*.hpp ${SOURCE_DIR}/dem/*.cpp)
set(bad "")
foreach(source ${sources})
  file(STRINGS ${source} lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${lines})
    if(line MATCHES "[\"<](io|lab|mesogen|doe|campaign|calibrate|calib|apps|python)/|toml|H5|hdf5|cairo")
      list(APPEND bad "${source}: ${line}")
    endif()
  endforeach()
endforeach()
list(LENGTH sources count)
if(count LESS 20)
  message(FATAL_ERROR "found only ${count} engine sources under ${SOURCE_DIR}")
endif()
if(bad)
  list(JOIN bad "\n  " text)
  message(FATAL_ERROR "the engine (core/, dem/) includes file layers:\n  ${text}")
endif()
message(STATUS "${count} engine sources, none includes a file layer")
