# The mesh corpus that the tests and the benchmarks read. tests/corpus/ is in
# the repository (every mesh with its reference answers; sources and licences
# in tests/corpus/MANIFEST.md), so a plain clone needs nothing beside it.
# MESHTOPO_EXTRA_CORPUS (default: the environment's MESHTOPO_CORPUS when the
# build tree is first configured) names a directory laid out the same way
# whose meshes are added. Both are copied into BUILD/corpus, a file of
# tests/corpus winning over one of the same name there, and
# MESHTOPO_CORPUS_DIR names that directory for every test. Included once from
# the top-level CMakeLists.txt.

set(MESHTOPO_EXTRA_CORPUS "$ENV{MESHTOPO_CORPUS}" CACHE PATH
    "A directory of more corpus meshes (NAME.off[.gz] and NAME.expected.json) for the tests")
set(MESHTOPO_CORPUS_DIR ${PROJECT_BINARY_DIR}/corpus)

file(GLOB meshtopo_corpus_own CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/corpus/*)
set(meshtopo_corpus_extra "")
if(MESHTOPO_EXTRA_CORPUS)
  if(NOT IS_DIRECTORY "${MESHTOPO_EXTRA_CORPUS}")
    message(FATAL_ERROR "MESHTOPO_EXTRA_CORPUS (or MESHTOPO_CORPUS): no directory "
                        "${MESHTOPO_EXTRA_CORPUS}")
  endif()
  file(GLOB meshtopo_corpus_extra CONFIGURE_DEPENDS ${MESHTOPO_EXTRA_CORPUS}/*)
endif()

# Laid anew at each configure, so a mesh taken out of either source is gone.
file(REMOVE_RECURSE ${MESHTOPO_CORPUS_DIR})
file(MAKE_DIRECTORY ${MESHTOPO_CORPUS_DIR})
set(meshtopo_corpus_names "")
foreach(file ${meshtopo_corpus_own})
  get_filename_component(name ${file} NAME)
  list(APPEND meshtopo_corpus_names ${name})
  file(COPY ${file} DESTINATION ${MESHTOPO_CORPUS_DIR})
endforeach()
set(meshtopo_corpus_added 0)
foreach(file ${meshtopo_corpus_extra})
  get_filename_component(name ${file} NAME)
  if(IS_DIRECTORY ${file} OR name IN_LIST meshtopo_corpus_names)
    continue()
  endif()
  file(COPY ${file} DESTINATION ${MESHTOPO_CORPUS_DIR})
  math(EXPR meshtopo_corpus_added "${meshtopo_corpus_added} + 1")
endforeach()
if(MESHTOPO_EXTRA_CORPUS)
  message(STATUS "corpus: tests/corpus and ${meshtopo_corpus_added} files of "
                 "${MESHTOPO_EXTRA_CORPUS} in ${MESHTOPO_CORPUS_DIR}")
endif()
