# Regenerates the reference images of the render tests with the `power` strategy (independent
# of Triangle Rejection Sampling), TRS_REFERENCE_SPP samples per pixel; every scene's, or those
# SCENES names by their path under scenes/ (a semicolon-separated list):
#   cmake -D RENDER=build/bin/trs-render [-D SCENES=night-street;real/lantern] -P tests/render/make_references.cmake
include(${CMAKE_CURRENT_LIST_DIR}/reference_settings.cmake)
get_filename_component(root ${CMAKE_CURRENT_LIST_DIR}/../.. ABSOLUTE)
if(NOT SCENES)
  set(SCENES ${TRS_REFERENCE_SCENES} ${TRS_REFERENCE_REAL_SCENES} ${TRS_REFERENCE_MATERIAL_SCENES})
endif()
foreach(scene IN LISTS SCENES)
  get_filename_component(name ${scene} NAME)
  set(prefix ${CMAKE_CURRENT_LIST_DIR}/references/${scene})
  get_filename_component(folder ${prefix} DIRECTORY)
  file(MAKE_DIRECTORY ${folder})
  message(STATUS "${scene}: ${TRS_REFERENCE_SPP} spp")
  execute_process(
    COMMAND ${RENDER} ${root}/scenes/${scene}/${name}.gltf --out ${prefix}.exr
            --variance ${prefix}.variance.exr --strategy power --spp ${TRS_REFERENCE_SPP}
            --seed 1 ${TRS_REFERENCE_SETTINGS} --quiet
    RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "trs-render failed on ${scene} (${status})")
  endif()
endforeach()
