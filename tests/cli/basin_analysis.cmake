# A short basin run with an [analysis] table writes every analysis file and draws every figure
# of the fish-basin paper (Figs. 4-10) with the report.
file(REMOVE_RECURSE ${WORK}/analysis)
execute_process(COMMAND ${YUXI} run ${SOURCE}/cli/basin_analysis.toml -o ${WORK}/analysis
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "yuxi run failed (${rc}): ${err}")
endif()
foreach(f surface_t2.50.csv surface_t2.55.csv surface_t2.60.csv velocity_t2.55.csv
          elastic_map_t2.5050.csv elastic_map_t2.5100.csv period_sections.csv pdf_kinetic.csv
          pdf_elastic.csv pdf_total.csv fits.csv peaks.csv surface_profile.csv
          elastic_profile.csv)
  if(NOT EXISTS ${WORK}/analysis/analysis/${f})
    message(FATAL_ERROR "missing analysis file ${f}")
  endif()
endforeach()
# Per-grain samples (grain_sample_interval): one .npy file per sample time.
file(GLOB grain_samples ${WORK}/analysis/analysis/grains/grains_t*.npy)
list(LENGTH grain_samples n_samples)
if(n_samples LESS 1)
  message(FATAL_ERROR "no analysis/grains/grains_t*.npy")
endif()
foreach(f fig4_energies.png fig5_surface.png fig6_contours.png fig6b_peaks.png
          fig7_velocity.png fig8_elastic_maps.png fig8b_waves.png fig9_sections.png
          fig10_pdf.png report.md)
  if(NOT EXISTS ${WORK}/analysis/${f})
    message(FATAL_ERROR "missing figure ${f}: ${err}")
  endif()
endforeach()
# The report's parameter table numbers [[contact.pair]] tables from 1, as the scene reader's
# messages do (where Python can parse the scene into a table; else it prints the TOML as is).
file(READ ${WORK}/analysis/report.md report)
if(report MATCHES "\\| parameter \\| value \\|")
  if(NOT report MATCHES "`contact\\.pair\\[1\\]\\.k_n`" OR
     NOT report MATCHES "`contact\\.pair\\[2\\]\\.k_n`" OR
     report MATCHES "contact\\.pair\\[0\\]")
    message(FATAL_ERROR "report.md does not number the [[contact.pair]] tables from 1")
  endif()
endif()
file(STRINGS ${WORK}/analysis/analysis/fits.csv fits)
list(LENGTH fits n)
if(NOT n EQUAL 7) # header + kinetic, elastic, total in ranges A and B
  message(FATAL_ERROR "fits.csv has ${n} lines")
endif()
message(STATUS "ok")
