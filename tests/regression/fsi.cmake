# fin-fsi on a tiny FSI3 (D/10 box, a 1 m channel, a 6 x 1 Q9 flag, the inflow ramped over 0.1 s,
# 8 coupled steps with IQN-ILS): fsi.h5 -- node motion, nodal loads, forces, coupling iterations and
# residuals. A run is bitwise reproducible, so any change in the flow solver, the structure, the
# transfer or the accelerations shows here. The summary (wall times) goes beside the compared
# directory; the short run has no period to grade (exit 1, a result).
if(TARGET fin-fsi)
  finverse_add_regression(STAGE fsi CASE turek_hron_fsi3_tiny
                          COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/fsi/missed_is_a_result.sh
                                  $<TARGET_FILE:fin-fsi> --threads 1 turek_hron --case FSI3
                                  --reference ${PROJECT_SOURCE_DIR}/data/reference/turek_hron.json
                                  --cells-per-diameter 10 --channel-length 1.0 --circle-vertices 64
                                  --nx 6 --ny 1 --dt 0.002 --t-end 0.016 --ramp-time 0.1
                                  --acceleration iqn-ils --absolute-tolerance 1e-12 --summary @OUT@.summary.json --out @OUT@/fsi.h5)
endif()
