# Runs one example: cmake -DPROGRAM=... -DSCENARIO=... -DEXPECT="regex;regex" -P check_example.cmake
# Fails unless the program exits with status 0 and its output matches every regular expression
# (each matched against the whole output; ^ and $ anchor at line starts and ends).
execute_process(COMMAND ${PROGRAM} ${SCENARIO} OUTPUT_VARIABLE out ERROR_VARIABLE err
  RESULT_VARIABLE status)
message("${out}${err}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} exited with ${status}")
endif()
string(REPLACE "\n" ";" lines "${out}")
foreach(regex IN LISTS EXPECT)
  set(found FALSE)
  foreach(line IN LISTS lines)
    if(line MATCHES "${regex}")
      set(found TRUE)
      break()
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "no line of the output matches '${regex}'")
  endif()
endforeach()
