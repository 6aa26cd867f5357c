# ctest gpu_report_quick: tools/gpu-report.sh --quick on whatever Vulkan device there is
# (lavapipe in CI), so that the report still runs whole when a GPU is at hand. Every part must
# finish and report.md must hold every section, its first line saying whether a GPU was found;
# --tables must then make the same report from the archive alone.
# -D ROOT=source dir -D BUILD=build dir -D OUT=output dir
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND bash ${ROOT}/tools/gpu-report.sh --quick --build ${BUILD} ${OUT}
                RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "gpu-report.sh --quick failed (${status})")
endif()
foreach(file report.md data.tar.gz)
  if(NOT EXISTS ${OUT}/${file})
    message(FATAL_ERROR "gpu-report.sh wrote no ${file}")
  endif()
endforeach()
file(READ ${OUT}/report.md report)

execute_process(COMMAND ${BUILD}/bin/trs-bench --list-devices OUTPUT_VARIABLE devices)
string(REGEX MATCH "^# GPU report: [^\n]*" first_line "${report}")
if(devices MATCHES "(discrete|integrated|virtual) GPU")
  set(gpu_expected TRUE)
else()
  set(gpu_expected FALSE)
endif()
if(first_line STREQUAL "" OR (first_line MATCHES "no GPU found") STREQUAL gpu_expected)
  message(FATAL_ERROR "report.md's first line does not say whether a GPU was found: '${first_line}'")
endif()

foreach(section "## 1. Vulkan tests" "## 2. trs-bench" "## 3. The paper's Figures" "## 4. trs-render"
                "## 5. The CPU backend" "### Sampling, counts kept" "### Counting paths" "### Ablation"
                "### Scans" "### Slivers" "### The subdivision")
  string(FIND "${report}" "${section}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "report.md has no section '${section}'")
  endif()
endforeach()
foreach(problem "| not run |" "| cut short |" "| finished, with failures |" "No case finished" "Not complete")
  string(FIND "${report}" "${problem}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "report.md says '${problem}':\n${report}")
  endif()
endforeach()
if(NOT report MATCHES "\n\\| vulkan_sampler_test \\| ok \\| 1 \\| 0 \\|")
  message(FATAL_ERROR "report.md does not show vulkan_sampler_test passing")
endif()
if(NOT report MATCHES "\n\\| neon-sign \\| vulkan \\|[^\n]*\\| pass \\([0-9.]+ sigmas\\) \\|\n")
  message(FATAL_ERROR "report.md does not show the Vulkan render of neon-sign agreeing with the CPU's")
endif()

file(REMOVE_RECURSE ${OUT}-tables)
file(MAKE_DIRECTORY ${OUT}-tables)
file(COPY ${OUT}/data.tar.gz DESTINATION ${OUT}-tables)
execute_process(COMMAND bash ${ROOT}/tools/gpu-report.sh --tables ${OUT}-tables RESULT_VARIABLE status)
file(READ ${OUT}-tables/report.md again)
if(NOT status EQUAL 0 OR NOT again STREQUAL report)
  message(FATAL_ERROR "gpu-report.sh --tables did not make the same report from data.tar.gz")
endif()
