# Precompiled headers, one set per target of several translation units. Parsing the
# standard library's and the libraries' headers is about half of a translation unit's
# compile time here (radiosity/solver.cpp: 4.4 s of 7.7 s; <vector>, <algorithm>, ...
# with TBB's parallel_for: 2.5 s; <nlohmann/json.hpp>: 2.9 s; <gtest/gtest.h>: 2.2 s, each
# alone, -O3), paid again by each of the suite's 170 translation units in each of CI's
# builds. Precompiled once per target, the same headers load in about 1.2 s
# (bench/RESULTS.md, 2026-11-30). Only headers from outside the project: a change to the
# project's own headers then rebuilds what it rebuilt before.
option(RELIGHT_PCH "Precompile the standard library's and the libraries' headers per target" ON)

# The standard headers that most of the project's files include.
set(RELIGHT_PCH_STD <algorithm> <array> <cmath> <cstdint> <cstdio> <functional> <limits>
    <memory> <numbers> <optional> <span> <stdexcept> <string> <utility> <vector>)

# relight_precompile(target [header ...]): the standard set above and the given headers
# (<tbb/parallel_for.h>, <nlohmann/json.hpp>, <gtest/gtest.h>) precompiled for `target`.
function(relight_precompile target)
  if(RELIGHT_PCH)
    target_precompile_headers(${target} PRIVATE ${RELIGHT_PCH_STD} ${ARGN})
  endif()
endfunction()
