# A grain on a flat mesh sees what it sees on the plane the mesh lies in (docs/walls.md
# section 2): each scene of flat_mesh/ runs on its mesh and on its [[plane]], and the last frame
# of the two dumps (position, velocity, force and spin, to 8 significant digits) must agree.
foreach(case rest_on_fan impact_on_grid)
  foreach(wall mesh plane)
    set(out ${WORK}/flat_mesh/${case}_${wall})
    file(REMOVE_RECURSE ${out})
    execute_process(COMMAND ${YUXI} run ${SOURCE}/cli/flat_mesh/${case}_${wall}.toml -o ${out}
                            --no-progress --no-plots
      RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE log)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${case}_${wall} failed (${rc}): ${err}")
    endif()
    file(STRINGS ${out}/particles.lammpstrj lines)
    list(GET lines -1 last_${wall})
  endforeach()
  if(NOT last_mesh STREQUAL last_plane)
    message(FATAL_ERROR "${case}: on the mesh\n  ${last_mesh}\non the plane\n  ${last_plane}")
  endif()
  message(STATUS "${case}: ${last_mesh}")
endforeach()
