# Every scene shipped in scenes/ reads, builds and passes its checks (`yuxi check`): a scene
# generator or a key that changes cannot leave a broken scene behind.
file(GLOB_RECURSE scenes ${SCENES}/*.toml)
list(LENGTH scenes n)
if(n LESS 20)
  message(FATAL_ERROR "only ${n} scenes found in ${SCENES}")
endif()
set(failed "")
foreach(scene ${scenes})
  execute_process(COMMAND ${YUXI} check ${scene} RESULT_VARIABLE rc ERROR_VARIABLE err
                  OUTPUT_VARIABLE out)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "the scene is valid")
    string(APPEND failed "\n${scene} (${rc}): ${err}")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "scenes that do not check:${failed}")
endif()
message(STATUS "${n} scenes check")
