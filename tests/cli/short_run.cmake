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
message(STATUS "ok")
