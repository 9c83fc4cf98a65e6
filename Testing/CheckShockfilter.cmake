# Runs shockfilter once and checks what it did (the "cli" tests of Testing/CMakeLists.txt).
#
#   cmake -DPROGRAM=<shockfilter> -DARGS=<arguments, separated by |> -DEXPECT_EXIT=<code>
#         [-DEXPECT_STDERR=<regex>] [-DEXPECT_STDOUT=<regex>] [-DJSON_KEYS=<keys, separated by |>]
#         [-DJSON_EQUALS=<key=value|...>] [-DOUTPUT_FILE=<path>] [-DCHECK=<command, separated by |>]
#         -P CheckShockfilter.cmake
#
# Arguments are separated by | rather than ; because add_test() would split a
# list into separate arguments of cmake itself.
# - EXPECT_EXIT 2 also requires exactly one line "shockfilter: ..." on stderr
#   and nothing on stdout.
# - JSON_KEYS: stdout must be one line holding a JSON object with these members
#   (JSON_EQUALS: with these values).
# - OUTPUT_FILE: must exist, not empty (it is removed before the run).
# - CHECK: a command run afterwards that must exit with 0.
cmake_minimum_required(VERSION 3.19) # string(JSON)

string(REPLACE "|" ";" _args "${ARGS}")
if (OUTPUT_FILE)
  file(REMOVE "${OUTPUT_FILE}")
endif ()
execute_process(COMMAND "${PROGRAM}" ${_args}
  RESULT_VARIABLE _exit OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
message(STATUS "shockfilter ${ARGS}\n-- exit ${_exit}\n-- stdout: ${_out}\n-- stderr: ${_err}")

if (NOT _exit STREQUAL "${EXPECT_EXIT}")
  message(FATAL_ERROR "exit code ${_exit}, expected ${EXPECT_EXIT}")
endif ()
if (EXPECT_EXIT EQUAL 2)
  if (NOT _err MATCHES "^shockfilter: [^\n]+\n$")
    message(FATAL_ERROR "stderr is not one line \"shockfilter: ...\"")
  endif ()
  if (NOT _out STREQUAL "")
    message(FATAL_ERROR "stdout is not empty on failure")
  endif ()
endif ()
if (DEFINED EXPECT_STDERR AND NOT _err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr does not match '${EXPECT_STDERR}'")
endif ()
if (DEFINED EXPECT_STDOUT AND NOT _out MATCHES "${EXPECT_STDOUT}")
  message(FATAL_ERROR "stdout does not match '${EXPECT_STDOUT}'")
endif ()

if (JSON_KEYS OR JSON_EQUALS)
  if (NOT _out MATCHES "^{[^\n]*}\n$")
    message(FATAL_ERROR "stdout is not one line holding a JSON object")
  endif ()
  string(JSON _type ERROR_VARIABLE _error TYPE "${_out}")
  if (_error OR NOT _type STREQUAL "OBJECT")
    message(FATAL_ERROR "stdout is not a JSON object: ${_error}")
  endif ()
  string(REPLACE "|" ";" _keys "${JSON_KEYS}")
  foreach (_key IN LISTS _keys)
    string(JSON _type ERROR_VARIABLE _error TYPE "${_out}" "${_key}")
    if (_error)
      message(FATAL_ERROR "the JSON object has no member '${_key}'")
    endif ()
  endforeach ()
  string(REPLACE "|" ";" _pairs "${JSON_EQUALS}")
  foreach (_pair IN LISTS _pairs)
    string(REGEX REPLACE "=.*" "" _key "${_pair}")
    string(REGEX REPLACE "^[^=]*=" "" _expected "${_pair}")
    string(JSON _value ERROR_VARIABLE _error GET "${_out}" "${_key}")
    if (_error OR NOT _value STREQUAL _expected)
      message(FATAL_ERROR "JSON member '${_key}' is '${_value}', expected '${_expected}'")
    endif ()
  endforeach ()
endif ()

if (OUTPUT_FILE)
  if (NOT EXISTS "${OUTPUT_FILE}")
    message(FATAL_ERROR "no output file ${OUTPUT_FILE}")
  endif ()
  file(SIZE "${OUTPUT_FILE}" _size)
  if (_size EQUAL 0)
    message(FATAL_ERROR "empty output file ${OUTPUT_FILE}")
  endif ()
endif ()

if (CHECK)
  string(REPLACE "|" ";" _check "${CHECK}")
  execute_process(COMMAND ${_check} RESULT_VARIABLE _exit OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
  message(STATUS "check: ${_out}${_err}")
  if (NOT _exit EQUAL 0)
    message(FATAL_ERROR "check failed (exit ${_exit}): ${CHECK}")
  endif ()
endif ()
