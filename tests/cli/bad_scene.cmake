# A scene with a mistake: exit code 2, the message names file, line and key, and no output
# folder is left behind.
file(REMOVE_RECURSE ${WORK}/bad)
file(MAKE_DIRECTORY ${WORK}/bad)
file(WRITE ${WORK}/bad/scene.toml "materials = [\"grain\"]\n[run]\ndt = 1e-4\nt_end = -1.0\n")
execute_process(COMMAND ${YUXI} run ${WORK}/bad/scene.toml -o ${WORK}/bad/out
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "expected exit code 2, got ${rc}: ${err}")
endif()
if(NOT err MATCHES "scene.toml:4:9: run.t_end: must be > 0")
  message(FATAL_ERROR "unexpected message: ${err}")
endif()
if(EXISTS ${WORK}/bad/out)
  message(FATAL_ERROR "an output folder was created for a bad scene")
endif()
message(STATUS "ok: ${err}")
