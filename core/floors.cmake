# The core's floors, bottom first: a folder may include its own floor's folders and the floors below, never
# one above (core/ARCHITECTURE.md draws them). Checked at every configure, with the edges of the whole tree
# (core includes neither ui/ nor app/; ui/ never app/; ui/model never ui/gl): a back edge fails the build.
# core/CMakeLists.txt makes each floor an object library and links it with the floors below alone, so a call
# up a floor fails to link even where no include shows it.
set(SONARSIM_CORE_FLOORS
    "base"                    # units, errors, files, small helpers
    "data"                    # plain data: the scene description, pose, trajectory, hits, polar image
    "meshfile"                # mesh files: the format table and its readers
    "grid"                    # the sonar's grid: beams, bins, beam tables, beam patterns
    "scene"                   # the parameter table, scene files, device and material presets
    "geometry"                # the scene's meshes in Embree
    "display"                 # display ranges, the fan image
    "shading"                 # the sonar equation over the hits
    "sensor"                  # what a device makes of the ideal image
    "sampling"                # where rays go: the tracers and the adaptive sampler
    "pipeline"                # the staged simulator
    "kinds"                   # side-scan and scanning sonars: their pings and images
    "io"                      # files: PNG, NumPy, ARIS, MCAP
    "dataset analysis")       # batches and exports; study, compare, references

# Fails with every back edge found under `root` (the repository).
function(sonarsim_check_floors root)
  set(level 0)
  foreach(floor IN LISTS SONARSIM_CORE_FLOORS)
    separate_arguments(folders UNIX_COMMAND "${floor}")
    foreach(folder IN LISTS folders)
      set(floor_${folder} ${level})
    endforeach()
    math(EXPR level "${level} + 1")
  endforeach()
  set(problems "")
  file(GLOB_RECURSE sources RELATIVE ${root} ${root}/core/*.hpp ${root}/core/*.cpp ${root}/ui/*.hpp ${root}/ui/*.cpp)
  foreach(source IN LISTS sources)
    file(STRINGS ${root}/${source} includes REGEX "^#include \"(core|ui|app)/")
    string(REGEX MATCH "^([a-z]+)/([a-z_]+)/" _ "${source}")
    set(top ${CMAKE_MATCH_1})
    set(room ${CMAKE_MATCH_2})
    foreach(line IN LISTS includes)
      string(REGEX MATCH "^#include \"([a-z]+)/([a-z_]+)/" _ "${line}")
      set(to_top ${CMAKE_MATCH_1})
      set(to_room ${CMAKE_MATCH_2})
      set(back "")
      if(top STREQUAL "core" AND NOT to_top STREQUAL "core")
        set(back "core includes ${to_top}/")
      elseif(top STREQUAL "ui" AND to_top STREQUAL "app")
        set(back "ui includes app/")
      elseif(top STREQUAL "ui" AND room STREQUAL "model" AND to_top STREQUAL "ui" AND to_room STREQUAL "gl")
        set(back "ui/model includes ui/gl")
      elseif(top STREQUAL "core" AND NOT room STREQUAL to_room)
        if(NOT DEFINED floor_${room} OR NOT DEFINED floor_${to_room})
          set(back "core/${room} or core/${to_room} is on no floor (core/floors.cmake)")
        elseif(floor_${to_room} GREATER floor_${room})
          set(back "core/${room} (floor ${floor_${room}}) includes core/${to_room} (floor ${floor_${to_room}}), a floor above")
        endif()
      endif()
      if(back)
        string(APPEND problems "\n  ${source}: ${line}: ${back}")
      endif()
    endforeach()
  endforeach()
  if(problems)
    message(FATAL_ERROR "Includes that reach up a floor (core/floors.cmake):${problems}")
  endif()
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/grid_owner.cmake)

# As a script (the build's sonarsim_floors target): cmake -DROOT=<repository> -P floors.cmake; the grid's
# ownership of the sonar's geometry is checked with the floors.
if(CMAKE_SCRIPT_MODE_FILE)
  sonarsim_check_floors(${ROOT})
  sonarsim_check_grid_owner(${ROOT})
endif()
