# Runs `cinepath ARGS...` (ARGS is a ;-list) and expects exit code RC, a stderr matching REGEX, and no
# output folder OUT left behind (a failed run writes nothing). Used for bad-input cases whose
# messages contain machine-specific paths (so they cannot be byte-compared as golden files).
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${CINEPATH} ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL RC)
  message(FATAL_ERROR "exit code ${rc}, expected ${RC}\nstderr: ${err}")
endif()
if(NOT err MATCHES "${REGEX}")
  message(FATAL_ERROR "stderr does not match '${REGEX}':\n${err}")
endif()
if(EXISTS ${OUT})
  file(GLOB left ${OUT}/*)
  if(left)
    message(FATAL_ERROR "a failed run left output behind: ${left}")
  endif()
endif()
