# Installs the build into a scratch prefix, then builds and runs projects against it as users
# would: a consumer of every component (tests/install_consumer), a consumer of the fast component
# alone configured with every other dependency made unfindable (tests/install_fast_consumer), and
# the same program built by hand from pkg-config's linequad-fast.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# Every component.
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
run(${WORK_DIR}/build/consumer_exact)

# The fast component alone, nothing else findable: no package but linequad, no pkg-config.
file(MAKE_DIRECTORY ${WORK_DIR}/empty)
set(ENV{PKG_CONFIG_LIBDIR} ${WORK_DIR}/empty)
set(ENV{PKG_CONFIG_PATH} "")
set(unfindable)
foreach(p CGAL Boost GMP MPFR gmp mpfr embree Eigen3 PkgConfig Threads TBB)
  list(APPEND unfindable -DCMAKE_DISABLE_FIND_PACKAGE_${p}=ON)
endforeach()
run(${CMAKE_COMMAND} -S ${FAST_CONSUMER_DIR} -B ${WORK_DIR}/build-fast
    -DCMAKE_PREFIX_PATH=${prefix} ${unfindable})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build-fast)
run(${WORK_DIR}/build-fast/fast_consumer)
# Nothing but the C++ runtime on its link line or in the program.
file(GLOB_RECURSE link_lines ${WORK_DIR}/build-fast/*/link.txt)
foreach(f ${link_lines})
  file(READ ${f} line)
  if(line MATCHES "(embree|CGAL|boost|gmp|mpfr|tbb)")
    message(FATAL_ERROR "the fast consumer's link line names ${CMAKE_MATCH_1}: ${line}")
  endif()
endforeach()
run(ldd ${WORK_DIR}/build-fast/fast_consumer)
if(run_output MATCHES "(embree|gmp|mpfr|boost|tbb)")
  message(FATAL_ERROR "the fast consumer loads ${CMAKE_MATCH_1}:\n${run_output}")
endif()

# pkg-config: the same program, compiled and linked by hand.
unset(ENV{PKG_CONFIG_LIBDIR})
file(GLOB pc_files ${prefix}/*/pkgconfig/linequad-fast.pc ${prefix}/*/*/pkgconfig/linequad-fast.pc)
list(LENGTH pc_files n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "linequad-fast.pc: expected one under ${prefix}, found '${pc_files}'")
endif()
get_filename_component(pc_dir ${pc_files} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
run(${PKG_CONFIG} --cflags --libs linequad-fast)
string(STRIP "${run_output}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run(${CXX} -std=c++17 -O2 ${CONSUMER_DIR}/main.cpp ${flags} -o ${WORK_DIR}/pkg_config_consumer)
run(${WORK_DIR}/pkg_config_consumer)
message(STATUS "consumers built against the installed package (every component, fast alone, "
               "pkg-config) and ran")
