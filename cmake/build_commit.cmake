# Writes OUTPUT, a C++ source defining trs::build_commit(): the commit of SOURCE_DIR, with
# "-dirty" when the tree has changes, or "unknown" outside a git checkout. Run at every build;
# OUTPUT is rewritten only when the text changes, so an unchanged commit rebuilds nothing.
execute_process(COMMAND git -C ${SOURCE_DIR} describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE status)
if(NOT status EQUAL 0 OR commit STREQUAL "")
  set(commit unknown)
endif()
set(text "// Generated at build time by cmake/build_commit.cmake.\n#include \"common/build_commit.h\"\n\nconst char* trs::build_commit() { return \"${commit}\"; }\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} previous)
endif()
if(NOT previous STREQUAL text)
  file(WRITE ${OUTPUT} "${text}")
endif()
