# Installs the build tree into a fresh prefix, then configures, builds and runs a consumer
# project against it with find_package; where the Python modules were built (PYTHON set), imports
# them from where they were installed. With PLUGIN_DIR and SCENE, builds that strategy plugin
# (examples/light_strategy) against the prefix as a researcher would, renders SCENE with it by the
# installed trs-render, studies it beside auto with the installed trs-study, and renders with it
# from the installed Python module. Run by ctest (label "install").
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consumer.cmake needs -D${var}=...")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    list(JOIN ARGV " " command)
    message(FATAL_ERROR "failed (${rc}): ${command}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
run(${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("${WORK_DIR}/build/consumer")
if(PYTHON)
  set(ENV{PYTHONPATH} "${WORK_DIR}/prefix/${PYTHON_INSTALL_DIR}")
  run(${PYTHON} -c "import ${PYTHON_IMPORTS}, lightsampler; assert lightsampler.__file__.startswith('${WORK_DIR}')")
endif()
if(NOT PLUGIN_DIR)
  return()
endif()
set(plugin "${WORK_DIR}/plugin/cosine_power.so")
run(${CMAKE_COMMAND} -S "${PLUGIN_DIR}" -B "${WORK_DIR}/plugin" -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
run(${CMAKE_COMMAND} --build "${WORK_DIR}/plugin")
set(small --width 24 --height 16 --max-depth 2 --quiet)
run("${WORK_DIR}/prefix/bin/trs-render" "${SCENE}" --plugin "${plugin}" --strategy cosine-power
    --strategy-option floor=0.2 --spp 2 ${small} --out "${WORK_DIR}/plugin.exr")
run("${WORK_DIR}/prefix/bin/trs-study" "${SCENE}" --plugin "${plugin}" --strategies auto,cosine-power
    --spp 1 --seeds 1 --reference-spp 4 ${small} --out "${WORK_DIR}/study")
file(READ "${WORK_DIR}/study/results.csv" results)
if(NOT results MATCHES "\ncosine-power,")
  message(FATAL_ERROR "trs-study's ${WORK_DIR}/study/results.csv has no row of the plugin's strategy")
endif()
if(PYTHON_IMPORTS MATCHES "trs_render")
  run(${PYTHON} -c "import trs_render; image, stats = trs_render.render('${SCENE}', plugin='${plugin}', strategy='cosine-power', spp=1, width=24, height=16, max_depth=2, quiet=True); assert stats['settings']['strategy'] == 'cosine-power', stats['settings']")
endif()
