# `yuxi run --device`: the device engine's host build runs the chute into an ordinary run folder
# and logs its device; a scene it does not run, and the GPU in a build without CUDA, are refused
# by name before any folder is made (never run on the CPU engine in silence).
set(chute ${SCENES}/chute-lammps.toml)
file(REMOVE_RECURSE ${WORK}/device_host ${WORK}/device_gpu ${WORK}/device_drum)
execute_process(COMMAND ${YUXI} run ${chute} -o ${WORK}/device_host --t-end 0.005 --device host
                        --no-plots --no-progress
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "yuxi run --device host failed (${rc}): ${err}")
endif()
if(NOT "${out}${err}" MATCHES "device engine on host \\(Thrust CPP\\): [0-9]+ bytes of device")
  message(FATAL_ERROR "the log does not name the device and its memory: ${out}${err}")
endif()
file(STRINGS ${WORK}/device_host/energies.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 3) # header, t = 0 and the end (energy_interval 0.01 > t_end)
  message(FATAL_ERROR "energies.csv has ${n} lines")
endif()
file(READ ${WORK}/device_host/scene.resolved.toml resolved)
if(NOT resolved MATCHES "device = 'host'")
  message(FATAL_ERROR "the resolved scene does not keep the device")
endif()

if(NOT CUDA)
  execute_process(COMMAND ${YUXI} run ${chute} -o ${WORK}/device_gpu --t-end 0.005 --device gpu
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "-DYUXI_CUDA=ON" OR NOT err MATCHES "--device cpu")
    message(FATAL_ERROR "--device gpu without CUDA: ${rc} ${err}")
  endif()
  if(EXISTS ${WORK}/device_gpu)
    message(FATAL_ERROR "a refused run made its folder")
  endif()
endif()

execute_process(COMMAND ${YUXI} run ${SCENES}/drum/drum-cylinder.toml -o ${WORK}/device_drum
                        --device host
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "\\[\\[cylinder\\]\\]")
  message(FATAL_ERROR "the drum's cylinder was not refused: ${rc} ${err}")
endif()
if(EXISTS ${WORK}/device_drum)
  message(FATAL_ERROR "a refused run made its folder")
endif()
message(STATUS "ok")
