# A simulation that blows up (time step forced far above t_c/10) stops with exit code 3, a
# diagnosis naming the grain, its position and velocity, a last snapshot, and the checkpoints
# written before the trouble.
file(REMOVE_RECURSE ${WORK}/blowup)
file(MAKE_DIRECTORY ${WORK}/blowup)
file(WRITE ${WORK}/blowup/scene.toml "materials = [\"grain\"]
[run]
dt = 2.0e-3
t_end = 1.0
[checkpoint]
every_steps = 5
every_minutes = 0
[domain]
lo = [-5.0, -5.0, -5.0]
hi = [5.0, 5.0, 5.0]
gravity = [0.0, 0.0, 0.0]
[contact]
model = \"linear\"
[[contact.pair]]
materials = [\"grain\", \"grain\"]
k_n = 1.0e6
[[particle]]
position = [0.0, 0.0, 1.5]
velocity = [0.0, 0.0, -20.0]
radius = 0.5
mass = 1.0
material = \"grain\"
[[particle]]
position = [0.0, 0.0, -1.5]
velocity = [0.0, 0.0, 20.0]
radius = 0.5
mass = 1.0
material = \"grain\"
")
execute_process(COMMAND ${YUXI} run ${WORK}/blowup/scene.toml -o ${WORK}/blowup/out
  RESULT_VARIABLE rc0 ERROR_VARIABLE err0)
if(NOT rc0 EQUAL 2 OR NOT err0 MATCHES "run.dt: 0.002 is")
  message(FATAL_ERROR "a time step far above t_c/10 was not refused (${rc0}): ${err0}")
endif()
execute_process(COMMAND ${YUXI} run ${WORK}/blowup/scene.toml -o ${WORK}/blowup/out --force
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 3)
  message(FATAL_ERROR "expected exit code 3, got ${rc}: ${err}")
endif()
file(READ ${WORK}/blowup/out/failure.txt diagnosis)
if(NOT diagnosis MATCHES "energy books gained .* the integration is unstable" OR
   NOT diagnosis MATCHES "Fastest grain [01] \\(radius 0.5\\) at \\(.*\\) with velocity")
  message(FATAL_ERROR "unclear diagnosis: ${diagnosis}")
endif()
foreach(f failure.vtu energies.csv)
  if(NOT EXISTS ${WORK}/blowup/out/${f})
    message(FATAL_ERROR "missing ${f} after the blow-up")
  endif()
endforeach()
# Checkpoints are written only after a rebuild whose energy check passed: the kept ones are good.
file(GLOB kept ${WORK}/blowup/out/checkpoints/*.yxc)
list(LENGTH kept n_kept)
if(NOT n_kept EQUAL 3)
  message(FATAL_ERROR "expected the 3 newest good checkpoints, found ${n_kept}")
endif()
message(STATUS "ok: ${diagnosis}")
