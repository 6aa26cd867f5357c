# One image-regression case: renders SCENE with STRATEGY at the test's settings, then compares it
# with the stored reference through trs-imgdiff's noise-aware tile test.
# -D RENDER=trs-render -D IMGDIFF=trs-imgdiff -D SCENE=file.gltf -D REFERENCE=prefix
# -D STRATEGY=name -D SPP=n -D REFERENCE_SPP=n -D WORK=dir [-D EXTRA="--max-depth;1"]
# Settings other than the strategy and the sample count come from reference_settings.cmake, so
# the references and the tests cannot drift apart.
include(${CMAKE_CURRENT_LIST_DIR}/reference_settings.cmake)
file(MAKE_DIRECTORY ${WORK})
execute_process(
  COMMAND ${RENDER} ${SCENE} --out ${WORK}/image.exr --variance ${WORK}/variance.exr
          --strategy ${STRATEGY} --spp ${SPP} --seed 7 ${TRS_REFERENCE_SETTINGS} ${EXTRA} --quiet
  RESULT_VARIABLE status ERROR_VARIABLE errors)
message("${errors}")
if(NOT status EQUAL 0)
  message(FATAL_ERROR "trs-render failed (${status})")
endif()
# With LIGHTSAMPLER_VULKAN_VALIDATION=1 the Vulkan light sampler must run silent.
if(errors MATCHES "lightsampler: Vulkan (error|warning)")
  message(FATAL_ERROR "the Vulkan validation layer reported problems")
endif()
execute_process(
  COMMAND ${IMGDIFF} ${WORK}/image.exr ${REFERENCE}.exr --variance ${WORK}/variance.exr
          --reference-variance ${REFERENCE}.variance.exr --spp ${SPP}
          --reference-spp ${REFERENCE_SPP}
  RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the render differs from ${REFERENCE}.exr beyond its noise")
endif()
