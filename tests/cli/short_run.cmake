# `yuxi run` with no scene runs the built-in basin; a short run writes every output.
file(REMOVE_RECURSE ${WORK}/short)
execute_process(COMMAND ${YUXI} run -o ${WORK}/short --t-end 0.02
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "yuxi run failed (${rc}): ${err}")
endif()
foreach(f scene.resolved.toml energies.csv particles.pvd particles_000000000.vtu particles.lammpstrj)
  if(NOT EXISTS ${WORK}/short/${f})
    message(FATAL_ERROR "missing output ${f}")
  endif()
endforeach()
file(STRINGS ${WORK}/short/energies.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 4) # header + t = 0, 0.01, 0.02
  message(FATAL_ERROR "energies.csv has ${n} lines")
endif()
# Running again into the same folder is refused without --overwrite.
execute_process(COMMAND ${YUXI} run -o ${WORK}/short --t-end 0.02 RESULT_VARIABLE rc2 ERROR_VARIABLE err2)
if(NOT rc2 EQUAL 2 OR NOT err2 MATCHES "already holds a run")
  message(FATAL_ERROR "an existing run was not protected: ${rc2} ${err2}")
endif()
# A resumed run logs its own list builds, not the count since t = 0 that the checkpoint keeps:
# the grains fall 1e-3 sigma in either segment, so neither builds a list (a checkpoint needs
# none).
execute_process(COMMAND ${YUXI} run --resume ${WORK}/short --t-end 0.04 --no-plots
  RESULT_VARIABLE rc3 ERROR_VARIABLE err3 OUTPUT_VARIABLE out3)
if(NOT rc3 EQUAL 0)
  message(FATAL_ERROR "resuming failed (${rc3}): ${err3}")
endif()
string(REGEX MATCH "\\(([0-9]+) list builds\\)" first "${out}${err}")
set(first_builds ${CMAKE_MATCH_1})
string(REGEX MATCH "\\(([0-9]+) list builds\\)" resumed "${out3}${err3}")
set(resumed_builds ${CMAKE_MATCH_1})
if(first_builds STREQUAL "" OR NOT resumed_builds STREQUAL first_builds)
  message(FATAL_ERROR "list builds: ${first_builds} in the first run, ${resumed_builds} resumed")
endif()
# An end before the checkpoint's time is refused, not run as nothing to do.
execute_process(COMMAND ${YUXI} run --resume ${WORK}/short --t-end 0.01 --no-plots
  RESULT_VARIABLE rc4 ERROR_VARIABLE err4)
if(NOT rc4 EQUAL 2 OR NOT err4 MATCHES "goes forwards only")
  message(FATAL_ERROR "resuming to an earlier end: ${rc4} ${err4}")
endif()
message(STATUS "ok")
