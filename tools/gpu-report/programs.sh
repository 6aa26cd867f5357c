# shellcheck shell=bash
# The programs the GPU report runs, found in BUILD/bin: the bundle packs exactly these.
report_tests=(vulkan_context_test texel_pieces_shader_test vulkan_sampler_test vulkan_scan_test vulkan_process_test)
report_programs=("${report_tests[@]}" trs-bench trs-sample trs-render trs-imgdiff)
