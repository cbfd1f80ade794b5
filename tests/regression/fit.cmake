# fin-fit on the coarse hybrid-plate twin (4 x 4 plate, one GA run of 10 x 3 and the polish, both
# objectives): materials.h5 of the eq. (2) fit -- parameters, every generation's best, the polish,
# the uncertainty and verdicts. Same seed gives a byte-identical file for any thread count, so a
# change anywhere in the FEM, the objectives or the optimisers shows here. The validation summary
# (wall times) goes beside the compared directory.
if(TARGET fin-fit)
  finverse_add_regression(STAGE fit CASE hybrid_plate_coarse
                          COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/fit/missed_is_a_result.sh
                                  $<TARGET_FILE:fin-fit> --threads 2 hybrid_plate
                                  --case ${PROJECT_SOURCE_DIR}/data/cases/hybrid_plate_small_heave.json
                                  --nx 4 --nz 4 --runs 1 --population 10 --generations 3
                                  --out-dir @OUT@.validation --materials-out @OUT@/materials.h5)
endif()
