# Compiling less: precompiled headers, and unity groups for the library, the tests and the program.
#
# CI builds the project three times (Release, AddressSanitizer, ThreadSanitizer) on two cores.
# Measured in CPU seconds of a Release build: the test files took 449 s compiled one by one and
# 224 s in unity groups (each file parsed GoogleTest, Eigen and the library's headers again and
# optimised the same inline functions and template instances again); a precompiled header saves
# 0.6 to 1.3 s on each of the library's 87 files. A precompiled header costs its own build (4 to
# 9 s) and, in GCC, making and optimising whatever its headers define for a file that would not
# have included them (apps/cli/progress.cpp: 0.4 s alone, 4.5 s with CLI11, JSON and toml++
# precompiled), so only the targets where most files include the headers have one: the library,
# the tests and the benchmarks; not the command-line program nor the Python module.
#
# Eigen's decompositions cost every file that instantiates one seconds of compilation (GCC -O3,
# the tests' precompiled header, over an empty file: 15 s for Quaterniond::FromTwoVectors, 10 s
# for a column-pivoting QR, 3 to 5 s for an LU or an LDLT), and a header's inline function
# instantiates them in every file that includes it. The tests and the benchmarks take theirs from
# tests/support/dense_solves.hpp, compiled once: the six unity groups and two benchmark files that
# used them took 312 s of CPU in a Release build, and 199 s with the helpers (their own 29 s
# included), 30 November 2026.

# Headers precompiled into every file of the library, the tests and the benchmarks: Eigen
# (included by 76 of the library's 87 files) and standard headers most files include.
# Not nlohmann/json.hpp (12 files): it includes <iomanip>, whose std::quoted then wins argument-
# dependent lookup over a file's own quoted(std::string_view) (src/blockdem/lab/law_spec.cpp).
# Not toml++ (11 files): src/blockdem/scenario/toml_implementation.cpp compiles its
# implementation by defining TOML_IMPLEMENTATION before including it, which a header included
# ahead of that file would defeat.
set(BLOCKDEM_PCH_LIBRARY
    <algorithm> <array> <cmath> <cstdint> <functional> <map> <memory> <optional> <string>
    <string_view> <utility> <vector> <Eigen/Core> <Eigen/Geometry>)
# Added for the tests, where most unity groups read scenarios or JSON (17 and 20 of the 87 test
# files; GoogleTest includes <iomanip> in every test file anyway).
set(BLOCKDEM_PCH_FILES <filesystem> <fstream> <sstream> <nlohmann/json.hpp> <toml++/toml.h>)

# blockdem_precompile_headers(TARGET HEADER...): precompiles HEADER... for TARGET's C++ files
# when BLOCKDEM_PRECOMPILED_HEADERS is on. With it off, every file must still include what it
# uses (precompiled headers are included ahead of each file and can hide a missing #include).
function(blockdem_precompile_headers target)
  if(BLOCKDEM_PRECOMPILED_HEADERS)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# blockdem_unity_groups(SOURCES SIZE): puts SOURCES (the library's, the tests', the program's) into
# unity groups of at most SIZE files, each folder's files (in sorted order) split evenly into
# groups of their own; SIZE 0 leaves every file alone. A group is one translation unit, so two
# files of one group may not define the same name in an anonymous namespace (give one file a
# namespace of its own, as some tests have). Groups follow folders, so a new file changes only
# its own folder's groups. The command-line program's 10 files took 70 s of CPU one by one and
# 30 s in two groups; the library's 124 files (Release, GCC, one job, the machine shared with
# as much other work in both runs, 29 November 2026) 725 s one by one and 423 s in 24 groups.
#
# blockdem_unity_groups(SOURCES SIZE DEPTH): the same, with a group's folder the first DEPTH
# folders of a file's path in the repository (DEPTH 2: every file under tests/unit/ in the groups
# of tests/unit). The tests use it: their 17 folders held 25 groups, most of one folder of 3 to 8
# files, and every group paid its own start (the tests' precompiled header of 190 MB read, 2 to
# 2.5 s of CPU for a file that only includes GoogleTest) and its own copies of the same
# GoogleTest, Eigen and JSON instances: the two groups of tests/unit/world, 7 files each, took
# 7.3 and 12.1 s of CPU, the same 14 files in one group 15.9 s.
function(blockdem_unity_groups sources size)
  if(NOT size GREATER 0)
    return()
  endif()
  set(depth 0)
  if(ARGC GREATER 2)
    set(depth ${ARGV2})
  endif()
  # Each file's group folder (its own, or its first `depth` folders below the repository), kept
  # beside it: a group takes the files whose folder is the same string.
  set(folders)
  set(keys)
  foreach(source ${sources})
    get_filename_component(folder ${source} DIRECTORY)
    if(depth GREATER 0)
      file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${folder})
      string(REPLACE "/" ";" parts "${relative}")
      list(LENGTH parts length)
      if(length GREATER depth)
        list(SUBLIST parts 0 ${depth} parts)
      endif()
      string(REPLACE ";" "/" relative "${parts}")
      set(folder ${PROJECT_SOURCE_DIR}/${relative})
    endif()
    list(APPEND keys ${folder})
  endforeach()
  set(folders ${keys})
  list(REMOVE_DUPLICATES folders)
  foreach(folder ${folders})
    set(files)
    foreach(source key IN ZIP_LISTS sources keys)
      if(key STREQUAL folder)
        list(APPEND files ${source})
      endif()
    endforeach()
    list(SORT files)
    list(LENGTH files count)
    # ceil(count / size) groups, the files dealt out in runs of nearly equal length.
    math(EXPR groups "(${count} + ${size} - 1) / ${size}")
    file(RELATIVE_PATH name ${PROJECT_SOURCE_DIR} ${folder})
    string(REPLACE "/" "_" name ${name})
    set(index 0)
    foreach(source ${files})
      math(EXPR group "${index} * ${groups} / ${count}")
      set_source_files_properties(${source} PROPERTIES UNITY_GROUP ${name}_${group})
      math(EXPR index "${index} + 1")
    endforeach()
  endforeach()
endfunction()

# GCC's garbage collector of its own memory runs less often: it starts collecting at 1 GiB of
# heap instead of a fraction of the machine's memory, and then only after the heap grew by 400 %
# instead of 30 %. A compiler process then holds up to 1 GB (0.8 GB before; two jobs on this
# 24 GiB machine), and the objects are the same bytes. `-pipe` hands the assembly to the
# assembler without a temporary file. Measured on the heaviest files, alternated, 4 December
# 2026: the test group tests/validation (0) 15.9 s of CPU against 14.5, the library's group
# src/blockdem/run (1) 16.7 and 17.2 s against 15.6 and 14.2; a fresh full build (Release, -j2,
# load 0.9-2.1) 400 s wall and 781 s of CPU before, 354 s and 703 s after.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  add_compile_options(--param=ggc-min-expand=400 --param=ggc-min-heapsize=1048576 -pipe)
endif()
