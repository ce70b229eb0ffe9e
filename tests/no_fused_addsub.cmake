# fast/ must round every operation where its source writes it: no fused multiply-add that the
# source did not ask for with std::fma. Compilers' vectorizers have fused mixed add/subtract
# lanes into vfmaddsub / vfmsubadd despite -ffp-contract=off; the source never asks for those.
execute_process(COMMAND ${OBJDUMP} -d ${LIBRARY} OUTPUT_VARIABLE code RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "objdump failed on ${LIBRARY}")
endif()
string(REGEX MATCHALL "vfm(addsub|subadd)[0-9a-z]*" fused "${code}")
list(LENGTH fused n)
if(n GREATER 0)
  message(FATAL_ERROR "${LIBRARY} holds ${n} fused add/subtract instructions: ${fused}")
endif()
message(STATUS "no fused add/subtract in ${LIBRARY}")
