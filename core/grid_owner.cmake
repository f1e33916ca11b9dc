# The sonar's geometry has one owner, SonarGrid (core/grid/sonar_grid.hpp): no other code derives a range
# from range_min_m or a bin from a range, half the fan or the elevation aperture from azimuth_fov_deg or
# elevation_fov_deg, or the window from the two range limits; it asks the grid (bin_centre_m, bin_position,
# port_edge_deg, elevation_half_deg, window_m, PolarLayout, ...). Checked at every configure and every build, with the floors (floors.cmake).
set(SONARSIM_GRID_DERIVATIONS
    "range_min_m \\+|azimuth_fov_deg / 2|elevation_fov_deg / 2|\\.range_max_m - [A-Za-z_.>-]*range_min_m|- [A-Za-z_]+(\\.|->)range_min_m\\) /")

# Fails naming every line under `root` (the repository) that derives the grid's geometry outside it.
function(sonarsim_check_grid_owner root)
  file(GLOB_RECURSE sources RELATIVE ${root} ${root}/core/*.hpp ${root}/core/*.cpp ${root}/ui/*.hpp ${root}/ui/*.cpp
       ${root}/app/*.hpp ${root}/app/*.cpp ${root}/python/*.cpp ${root}/bench/*.hpp ${root}/bench/*.cpp)
  set(problems "")
  foreach(source IN LISTS sources)
    if(source MATCHES "^core/grid/sonar_grid\\.(hpp|cpp)$")
      continue()
    endif()
    file(STRINGS ${root}/${source} lines REGEX "${SONARSIM_GRID_DERIVATIONS}")
    foreach(line IN LISTS lines)
      string(STRIP "${line}" line)
      string(APPEND problems "\n  ${source}: ${line}")
    endforeach()
  endforeach()
  if(problems)
    message(FATAL_ERROR "The sonar's geometry derived outside the grid (ask SonarGrid, core/grid_owner.cmake):${problems}")
  endif()
endfunction()
